"""Pose math (the algorithm of pose.mod): quaternions and vectors as tuples."""
import math
import sys

N = int(sys.argv[1]) if len(sys.argv) > 1 else 200000


def qmul(a, b):
    return (a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
            a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
            a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
            a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def rotate(q, v):
    u = (q[1], q[2], q[3])
    t = cross(u, v)
    t = (2 * t[0], 2 * t[1], 2 * t[2])
    c = cross(u, t)
    return (v[0] + q[0] * t[0] + c[0], v[1] + q[0] * t[1] + c[1], v[2] + q[0] * t[2] + c[2])


def compose(a, b):
    p = rotate(a[1], b[0])
    return ((a[0][0] + p[0], a[0][1] + p[1], a[0][2] + p[2]), qmul(a[1], b[1]))


def about_z(deg):
    h = math.radians(deg / 2)
    return (math.cos(h), 0, 0, math.sin(h))


def main():
    check = 0
    for i in range(1, N + 1):
        a = ((i % 100, 0, 50), about_z(i % 360))
        b = ((10, 20, 30), about_z((i * 7) % 360))
        c = compose(a, b)
        v = rotate(c[1], (100, 0, 0))
        check = (check + math.trunc((v[0] + c[0][0] + 1000) / 10)) % 100000
    print(f"result: {check}")


main()
