"""abb_robot_client's RWS and EGM classes together (PyPI, unchanged) against `rapidvc serve`
of tests/serve_egm/, mode 4 (a slow EGMRunJoint): the client starts the run over RWS, stops
the program in the middle of it, sees the robot stand with RAPID stopped while the EGM session
goes on, starts it again, and the same run converges on its target. Then the speed ratio over
RWS: 50 % slows the run (the program's own ClkRead).

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
target = [10, -5, 20, 0, 40, 30]


def ok(name, cond, detail=""):
    if not cond:
        raise SystemExit(f"FAILED {name}: {detail}")
    print("OK", name, flush=True)


def pump(seconds, until=None):
    """Answer every EGM message for `seconds` (or until `until(state)`); the states seen."""
    states, t0 = [], time.time()
    while time.time() - t0 < seconds:
        got, state = egm.receive_from_robot(timeout=0.05)
        if got:
            states.append(state)
            egm.send_to_robot(target)
            if until is not None and until(state):
                break
    return states


def run_to_end(limit=60):
    last_look, t0 = 0.0, time.time()
    while time.time() - t0 < limit:
        pump(0.1)
        if time.time() - last_look > 0.25:
            last_look = time.time()
            if r.get_execution_state().ctrlexecstate == "stopped":
                return
    raise SystemExit("FAILED the run did not end")


r.set_analog_io("egm_mode", 4)
r.set_rapid_variable("egm_time", "0")
r.start(cycle="once", tasks=["T_ROB1"])
pump(20, until=lambda s: s.joint_angles[2] > 5)
r.stop()
ok("stopped", r.get_execution_state().ctrlexecstate == "stopped")
states = pump(1.5)
ok("session goes on while stopped", len(states) > 100, len(states))
late = states[len(states) // 2:]
ok("RAPID stopped reported", all(not s.rapid_running for s in late))
held = [s.joint_angles[2] for s in late]
ok("the robot stands", max(held) - min(held) < 1e-6, (min(held), max(held)))
ok("short of the target", 5 < held[-1] < 19, held[-1])
r.start(cycle="asis", tasks=["T_ROB1"])
run_to_end()
j = r.get_jointtarget()
ok("target reached after the start", np.allclose(j.robax, target, atol=0.3), j)
full = r.get_rapid_variable_num("egm_time")
ok("timed", full > 0, full)
errors = [e for e in r.read_event_log() if e.code in (41822, 90201)]
ok("no errors", not errors, errors)

# The speed ratio: an uninterrupted run at 100 %, then one at 50 %.
r.set_rapid_variable("egm_time", "0")
r.start(cycle="once", tasks=["T_ROB1"])
run_to_end()
full = r.get_rapid_variable_num("egm_time")
r.set_speedratio(50)
ok("speed ratio set", r.get_speedratio() == 50, r.get_speedratio())
r.set_rapid_variable("egm_time", "0")
r.start(cycle="once", tasks=["T_ROB1"])
run_to_end()
half = r.get_rapid_variable_num("egm_time")
ok("50 % slows EGM", 1.4 < half / full < 2.4, (half, full))
r.set_speedratio(100)
egm.close()
print("ALL OK", flush=True)
