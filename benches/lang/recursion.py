"""Recursion (the algorithm of recursion.mod): naive Fibonacci and a recursive quicksort."""
import sys

N = int(sys.argv[1]) if len(sys.argv) > 1 else 240

data = [0] * 2001


def fib(n):
    if n < 2:
        return n
    return fib(n - 1) + fib(n - 2)


def qsort(lo, hi):
    if lo >= hi:
        return
    pivot = data[(lo + hi) // 2]
    i = lo
    j = hi
    while i <= j:
        while data[i] < pivot:
            i = i + 1
        while data[j] > pivot:
            j = j - 1
        if i <= j:
            t = data[i]
            data[i] = data[j]
            data[j] = t
            i = i + 1
            j = j - 1
    qsort(lo, j)
    qsort(i, hi)


def main():
    f = 0
    seed = 1
    check = 0
    for r in range(1, N + 1):
        f = f + fib(20 + r % 3)
        for i in range(1, 2001):
            seed = (seed * 251 + 7 + r) % 65521
            data[i] = seed
        qsort(1, 2000)
        for i in range(1, 2001, 50):
            check = (check + data[i] * (i % 7)) % 1000000
    print(f"result: {f} {check}")


main()
