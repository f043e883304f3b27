"""Records and arrays of records (the algorithm of records.mod)."""
import sys

N = int(sys.argv[1]) if len(sys.argv) > 1 else 25000


class Particle:
    __slots__ = ("x", "y", "vx", "vy", "hits")

    def __init__(self, x, y, vx, vy, hits):
        self.x = x
        self.y = y
        self.vx = vx
        self.vy = vy
        self.hits = hits


ps = [None] * 101


def moved(p):
    q = Particle(p.x, p.y, p.vx, p.vy, p.hits)
    q.x = q.x + q.vx
    if q.x < 0 or q.x > 1000:
        q.vx = -q.vx
        q.hits = q.hits + 1
    q.y = q.y + q.vy
    if q.y < 0 or q.y > 1000:
        q.vy = -q.vy
        q.hits = q.hits + 1
    return q


def busiest():
    best = 1
    for i in range(2, 101):
        if ps[i].hits > ps[best].hits:
            best = i
    return best


def main():
    check = 0
    hits = 0
    for i in range(1, 101):
        ps[i] = Particle(i * 7 % 1000, i * 13 % 1000, (i % 7) * 3 - 9, (i % 5) * 4 - 8, 0)
    for s in range(1, N + 1):
        for i in range(1, 101):
            ps[i] = moved(ps[i])
        if s % 10 == 0:
            check = (check + busiest() * s) % 1000000
    for i in range(1, 101):
        hits = hits + ps[i].hits
    print(f"result: {check} {hits}")


main()
