"""abb_robot_client's RWS and EGM classes together (PyPI, unchanged) against `rapidvc serve`
of tests/serve_egm/: for each session kind the client sets the analog output egm_mode over
RWS (1 joint, 2 pose, 3 path correction), starts the program once, answers every EGM message
until the program has stopped, and checks where the robot is over RWS.

argv: the RWS base URL, the UDP port the EGM class listens on. Prints "OK <name>" per check
and "ALL OK" at the end; a failed check exits non-zero.
"""
import sys
import time

import numpy as np
from abb_robot_client import rws
from abb_robot_client.egm import EGM

base, port = sys.argv[1], int(sys.argv[2])
r = rws.RWS(base)
egm = EGM(port=port)


def ok(name, cond, detail=""):
    if not cond:
        raise SystemExit(f"FAILED {name}: {detail}")
    print("OK", name, flush=True)


def session(mode, reply):
    r.set_analog_io("egm_mode", mode)
    ok(f"mode {mode} set", r.get_analog_io("egm_mode") == mode)
    r.start(cycle="once", tasks=["T_ROB1"])
    received, last_look, t0 = 0, 0.0, time.time()
    while time.time() - t0 < 60:
        got, state = egm.receive_from_robot(timeout=0.05)
        if got:
            received += 1
            reply(state)
        if time.time() - last_look > 0.25:
            last_look = time.time()
            if r.get_execution_state().ctrlexecstate == "stopped":
                break
    ok(f"mode {mode} ended", r.get_execution_state().ctrlexecstate == "stopped")
    ok(f"mode {mode} messages", received > 50, received)
    ok(f"mode {mode} ran", r.get_rapid_variable_num("last_mode") == mode)
    errors = [e for e in r.read_event_log() if e.code in (41822, 90201)]
    ok(f"mode {mode} no errors", not errors, errors)
    return received


target = [10, -5, 20, 0, 40, 30]
session(1, lambda s: egm.send_to_robot(target))
j = r.get_jointtarget()
ok("joint target reached", np.allclose(j.robax, target, atol=0.25), j)

pos, orient = [1068.61, -30, 1457.5], [0.5, 0, 0.866025, 0]
session(2, lambda s: egm.send_to_robot_cart(pos, orient))
t = r.get_robtarget(tool="tool0", wobj="wobj0", coordinate="Base")
ok("pose reached", np.allclose(t.trans, pos, atol=0.6), t)

session(3, lambda s: egm.send_to_robot_path_corr([0.0, 3.0, -2.0], age=1))
t = r.get_robtarget(tool="tool0", wobj="wobj0", coordinate="Base")
ok("path corrected", abs(t.trans[0] - 1400) < 1 and abs(abs(t.trans[1] - 20) - 3) < 0.5
   and abs(abs(t.trans[2] - 700) - 2) < 0.5, t)
egm.close()
print("ALL OK", flush=True)
