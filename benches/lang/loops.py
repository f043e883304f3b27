"""WHILE loops (the algorithm of loops.mod): Collatz chain lengths and Euclid's gcd."""
import sys

N = int(sys.argv[1]) if len(sys.argv) > 1 else 48


def collatz(n):
    steps = 0
    x = n
    while x != 1:
        if x % 2 == 0:
            x = x // 2
        else:
            x = 3 * x + 1
        steps = steps + 1
    return steps


def gcd(a, b):
    x = a
    y = b
    while y != 0:
        t = x % y
        x = y
        y = t
    return x


def main():
    total = 0
    g = 0
    rnd = 1
    while rnd <= N:
        k = 1
        while k <= 3000:
            total = (total + collatz(k)) % 1000000
            k = k + 1
        i = 1
        while i <= 150:
            j = 1
            while j <= 150:
                g = (g + gcd(i * 7 + rnd, j * 3)) % 1000000
                j = j + 1
            i = i + 1
        rnd = rnd + 1
    print(f"result: {total} {g}")


main()
