"""EGM sensor built on PyPI `abb_robot_client` (arc): see common.py for the protocol."""
import sys

from abb_robot_client.egm import EGM

import common


def main():
    args = common.parse_args("abb_robot_client")
    egm = EGM(port=args.port)
    common.say({"port": egm.socket.getsockname()[1]})

    def extra(checker, state):
        if state.joint_angles is None or len(state.joint_angles) != 6:
            checker.problem("arc: joint_angles not 6 values")
        if not state.rapid_running:
            checker.problem("arc: rapid_running false")
        if not state.motors_on:
            checker.problem("arc: motors_on false")
        if state.cartesian is None or state.joint_angles_planned is None:
            checker.problem("arc: cartesian or planned joints missing")

    def reply(_state):
        v = args.values
        if args.mode == "joint":
            return egm.send_to_robot(v)
        return egm.send_to_robot_cart(v[:3], v[3:])

    code = common.run("abb_robot_client", args, egm,
                      lambda: egm.receive_from_robot(timeout=0.5), reply, extra)
    egm.close()
    return code


if __name__ == "__main__":
    sys.exit(main())
