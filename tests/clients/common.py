"""Shared checks for the third-party EGM client scripts (no client import here).

Each script acts as an EGM sensor with one real client library: it receives EgmRobot from
rapidvc, checks that the message decoded and carries every item the strictest client
(libegm) needs, replies with a target, and prints one-line JSON: first {"port": N} once
bound, then a summary when it stops (after --count messages or --timeout seconds).
"""
import argparse
import json
import sys
import time

MSGTYPE_DATA = 2


def parse_args(client):
    p = argparse.ArgumentParser(description=f"EGM sensor using {client}")
    p.add_argument("--port", type=int, default=0)
    p.add_argument("--mode", choices=["joint", "pose"], default="joint")
    p.add_argument("--target", default="10,-5,20,0,40,30",
                   help="joint: J1..J6 degrees; pose: X,Y,Z mm,QW,QX,QY,QZ")
    p.add_argument("--count", type=int, default=300,
                   help="stop after this many messages (0: no limit)")
    p.add_argument("--timeout", type=float, default=20.0)
    p.add_argument("--until-quiet", type=float, default=0.0,
                   help="stop once messages stopped for this many seconds (after the first)")
    args = p.parse_args()
    args.values = [float(v) for v in args.target.split(",")]
    need = 6 if args.mode == "joint" else 7
    if len(args.values) != need:
        p.error(f"--target needs {need} values in {args.mode} mode")
    return args


def say(obj):
    print(json.dumps(obj), flush=True)


class Checker:
    """Accumulates problems found in successive EgmRobot messages."""

    def __init__(self):
        self.problems = []
        self.received = 0
        self.first_seqno = None
        self.last_seqno = None
        self.seqno_gaps = 0
        self.last_tm = None
        self.tm_backwards = 0
        self.max_size = 0
        self.last_joints = None
        self.last_pos = None

    def problem(self, text):
        if text not in self.problems and len(self.problems) < 20:
            self.problems.append(text)

    def check(self, m):
        """`m` is the client's decoded abb.egm.EgmRobot protobuf object."""
        self.received += 1
        self.max_size = max(self.max_size, m.ByteSize())
        if m.ByteSize() > 1024:
            self.problem(f"datagram of {m.ByteSize()} bytes")
        h = m.header
        if not (m.HasField("header") and h.HasField("seqno") and h.HasField("tm")):
            self.problem("header.seqno/tm missing")
        if h.mtype != MSGTYPE_DATA:
            self.problem(f"header.mtype {h.mtype}")
        if self.first_seqno is None:
            self.first_seqno = h.seqno
        elif h.seqno != (self.last_seqno + 1) % 2**32:
            self.seqno_gaps += 1
        if self.last_tm is not None and h.tm < self.last_tm:
            self.tm_backwards += 1
        self.last_seqno, self.last_tm = h.seqno, h.tm
        for name in ("feedBack", "planned"):
            part = getattr(m, name)
            if not m.HasField(name):
                self.problem(f"{name} missing")
                continue
            if len(part.joints.joints) != 6:
                self.problem(f"{name}.joints has {len(part.joints.joints)} values")
            c = part.cartesian
            if not (part.HasField("cartesian") and c.HasField("pos") and c.HasField("orient")):
                self.problem(f"{name}.cartesian pos/orient missing")
            if not part.HasField("time"):
                self.problem(f"{name}.time missing")
        for name in ("motorState", "mciState", "rapidExecState",
                     "mciConvergenceMet", "utilizationRate"):
            if not m.HasField(name):
                self.problem(f"{name} missing")
        if m.HasField("measuredForce"):
            self.problem("measuredForce present")
        values = [m.feedBack.joints.joints, [m.feedBack.cartesian.pos.x,
                  m.feedBack.cartesian.pos.y, m.feedBack.cartesian.pos.z]]
        if any(v != v for part in values for v in part):
            self.problem("NaN in feedback")
        self.last_joints = list(m.feedBack.joints.joints)
        p = m.feedBack.cartesian.pos
        self.last_pos = [p.x, p.y, p.z]

    def summary(self, client, mode, replied, reason):
        return {
            "client": client,
            "mode": mode,
            "reason": reason,
            "received": self.received,
            "replied": replied,
            "well_formed": not self.problems,
            "problems": self.problems,
            "first_seqno": self.first_seqno,
            "last_seqno": self.last_seqno,
            "seqno_gaps": self.seqno_gaps,
            "tm_backwards": self.tm_backwards,
            "max_size": self.max_size,
            "last_feedback_joints": self.last_joints,
            "last_feedback_pos": self.last_pos,
        }


def run(client, args, egm, receive, reply, extra_check):
    """Receive/reply loop shared by the scripts; `receive()` -> (ok, state)."""
    checker = Checker()
    replied = 0
    deadline = time.monotonic() + args.timeout
    last_rx = None
    reason = "timeout"
    while time.monotonic() < deadline:
        ok, state = receive()
        now = time.monotonic()
        if not ok:
            if args.until_quiet and last_rx is not None and now - last_rx >= args.until_quiet:
                reason = "quiet"
                break
            continue
        last_rx = now
        checker.check(state.robot_message)
        extra_check(checker, state)
        if reply(state):
            replied += 1
        if args.count and checker.received >= args.count:
            reason = "count"
            break
    say(checker.summary(client, args.mode, replied, reason))
    return 0 if reason in ("count", "quiet") and not checker.problems else 1


if __name__ == "__main__":
    sys.exit("run arc_sensor.py or abbrobotegm_sensor.py")
