"""EGM sensor built on PyPI `ABBRobotEGM`: see common.py for the protocol."""
import sys

from ABBRobotEGM import EGM

import common

MCI_RUNNING = 3


def main():
    args = common.parse_args("ABBRobotEGM")
    with EGM(port=args.port) as egm:
        common.say({"port": egm.socket.getsockname()[1]})

        def extra(checker, state):
            if len(state.joint_angles) != 6 or len(state.joint_angles_planned) != 6:
                checker.problem("ABBRobotEGM: joints not 6 values")
            if not (state.motors_on and state.rapid_running):
                checker.problem("ABBRobotEGM: motors off or RAPID not running")
            if state.mci_state != MCI_RUNNING:
                checker.problem(f"ABBRobotEGM: mci_state {state.mci_state}")
            if state.mci_convergence_met is None or state.utilization_rate is None:
                checker.problem("ABBRobotEGM: convergence or utilization missing")
            if state.clock is None or state.planned_clock is None:
                checker.problem("ABBRobotEGM: clock missing")
            if state.cartesian is None:
                checker.problem("ABBRobotEGM: cartesian missing")

        def reply(_state):
            v = args.values
            if args.mode == "joint":
                return egm.send_to_robot(joint_angles=v)
            return egm.send_to_robot_cart(v[:3], v[3:])

        return common.run("ABBRobotEGM", args, egm,
                          lambda: egm.receive_from_robot(timeout=0.5), reply, extra)


if __name__ == "__main__":
    sys.exit(main())
