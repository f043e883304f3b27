"""EGM path-correction sensor built on a real client library: PyPI `abb_robot_client` (arc)
or `ABBRobotEGM`, chosen with --client.

It receives EgmRobot from rapidvc during EGMMoveL/EGMMoveC, checks every message with the
shared checks of common.py (decoded, complete for strict clients), and answers each one with
the client's own path-correction call, `send_to_robot_path_corr([0, y, z], age)`: a constant
seam offset in the path frame. Prints {"port": N} once bound, then a one-line JSON summary
when the session goes quiet (or after --count messages, or --timeout seconds).
"""
import argparse
import sys

import common


def parse_args():
    p = argparse.ArgumentParser(description="EGM path-correction sensor")
    p.add_argument("--client", choices=["abb_robot_client", "ABBRobotEGM"], required=True)
    p.add_argument("--port", type=int, default=0)
    p.add_argument("--y", type=float, default=3.0, help="seam offset along path y, mm")
    p.add_argument("--z", type=float, default=-2.0, help="seam offset along path z, mm")
    p.add_argument("--age", type=int, default=1, help="pathCorr.age, ms (positive)")
    p.add_argument("--count", type=int, default=0, help="stop after this many (0: no limit)")
    p.add_argument("--timeout", type=float, default=60.0)
    p.add_argument("--until-quiet", type=float, default=1.0,
                   help="stop once messages stopped for this many seconds (after the first)")
    args = p.parse_args()
    args.mode = "pathcorr"
    return args


def main():
    args = parse_args()
    if args.client == "abb_robot_client":
        from abb_robot_client.egm import EGM
    else:
        from ABBRobotEGM import EGM
    egm = EGM(port=args.port)
    common.say({"port": egm.socket.getsockname()[1]})

    def extra(checker, state):
        if not (state.motors_on and state.rapid_running):
            checker.problem(f"{args.client}: motors off or RAPID not running")
        if state.joint_angles is None or len(state.joint_angles) != 6:
            checker.problem(f"{args.client}: joint_angles not 6 values")
        if state.cartesian is None:
            checker.problem(f"{args.client}: cartesian missing")

    def reply(_state):
        return egm.send_to_robot_path_corr([0.0, args.y, args.z], age=args.age)

    code = common.run(args.client, args, egm,
                      lambda: egm.receive_from_robot(timeout=0.5), reply, extra)
    egm.close()
    return code


if __name__ == "__main__":
    sys.exit(main())
