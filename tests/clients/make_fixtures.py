"""Writes tests/fixtures/egm/*.bin: datagrams encoded by the real third-party clients.

Each client package registers its own `egm.proto` in protobuf's default pool, so the two
cannot be imported into one process: run this script once per client.

    python tests/clients/make_fixtures.py abb_robot_client tests/fixtures/egm
    python tests/clients/make_fixtures.py ABBRobotEGM tests/fixtures/egm

The sensor replies are captured from the clients' own send methods (pointed at a local
socket), so the bytes are exactly what each client puts on the wire.
"""
import os
import socket
import sys


def capture(egm, send):
    """Points the client at a local socket, calls `send()`, returns the datagram."""
    sink = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sink.bind(("127.0.0.1", 0))
    sink.settimeout(5)
    egm.egm_addr = sink.getsockname()
    if send() is False:
        raise SystemExit("client refused to send")
    data, _ = sink.recvfrom(65536)
    sink.close()
    return data


def main():
    client, out = sys.argv[1], sys.argv[2]
    joints = [10.0, -5.0, 20.0, 0.0, 40.0, 30.0]
    pos, orient = [400.0, 100.0, 500.0], [0.0, 0.0, 1.0, 0.0]
    corr = [0.0, 1.5, -2.5]
    if client == "abb_robot_client":
        from abb_robot_client.egm import EGM

        prefix = "abb_robot_client"
    elif client == "ABBRobotEGM":
        from ABBRobotEGM import EGM

        prefix = "abbrobotegm"
    else:
        raise SystemExit(f"unknown client {client}")
    egm = EGM(port=0)
    files = {
        f"{prefix}_joint.bin": capture(egm, lambda: egm.send_to_robot(joints)),
        f"{prefix}_pose.bin": capture(egm, lambda: egm.send_to_robot_cart(pos, orient)),
        f"{prefix}_pathcorr.bin": capture(egm, lambda: egm.send_to_robot_path_corr(corr, age=1)),
    }
    if client == "ABBRobotEGM":
        files.update(rw7_robot_messages())
    egm.close()
    os.makedirs(out, exist_ok=True)
    for name, data in files.items():
        with open(os.path.join(out, name), "wb") as f:
            f.write(data)
        print(f"{name}: {len(data)} bytes")


def rw7_robot_messages():
    """EgmRobot with every RW7.16 field, with and without the renumbered measuredForce."""
    from ABBRobotEGM._egm_protobuf import egm_pb2 as pb

    m = pb.EgmRobot()
    m.header.seqno, m.header.tm, m.header.mtype = 12, 3456, pb.EgmHeader.MSGTYPE_DATA
    for part in (m.feedBack, m.planned):
        part.joints.joints.extend([1.0, 2.0, 3.0, 4.0, 5.0, 6.0])
        part.cartesian.pos.x, part.cartesian.pos.y, part.cartesian.pos.z = 500.0, 0.0, 600.0
        q = part.cartesian.orient
        q.u0, q.u1, q.u2, q.u3 = 0.0, 0.0, 1.0, 0.0
        part.externalJoints.joints.extend([7.0])
        part.time.sec, part.time.usec = 1700000000, 123456
        part.timeStamp.sec, part.timeStamp.nsec = 1700000000, 123456789
    m.motorState.state = pb.EgmMotorState.MOTORS_ON
    m.mciState.state = pb.EgmMCIState.MCI_RUNNING
    m.rapidExecState.state = pb.EgmRapidCtrlExecState.RAPID_RUNNING
    m.mciConvergenceMet = False
    m.utilizationRate = 12.5
    m.moveIndex = 7
    m.CollisionInfo.collsionTriggered = False
    m.CollisionInfo.collDetQuota.extend([0.1] * 6)
    m.RAPIDfromRobot.digVal = True
    m.RAPIDfromRobot.dnum.extend([float(i) for i in range(40)])
    m.torqueRef.joints.extend([0.5] * 6)
    no_force = m.SerializeToString()
    m.measuredForce.fcActive = True
    m.measuredForce.force.extend([1.0] * 6)
    return {"rw7_robot_no_force.bin": no_force, "rw7_robot_full.bin": m.SerializeToString()}


if __name__ == "__main__":
    main()
