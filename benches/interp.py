"""The interpreter benchmark in CPython: the same algorithm as benches/interp.mod.

Usage: python3 interp.py ITERATIONS -> prints "acc: <value>", "seconds: <loop wall time>"
and "cpu: <loop CPU time>".
"""
import sys
import time


def f(x):
    return x * 2 + 1


def main():
    n = int(sys.argv[1])
    data = [0] * 101
    acc = 0
    start = time.perf_counter()
    cpu = time.process_time()
    for i in range(1, n + 1):
        k = i % 100 + 1
        data[k] = (data[k] + f(k)) % 1000
        acc = (acc + data[k]) % 65536
    cpu = time.process_time() - cpu
    elapsed = time.perf_counter() - start
    print(f"acc: {acc}")
    print(f"seconds: {elapsed:.6f}")
    print(f"cpu: {cpu:.6f}")


main()
