"""Late binding (the algorithm of latebind.mod): functions called by a name built at run time."""
import sys

N = int(sys.argv[1]) if len(sys.argv) > 1 else 1000000
NAMES = [None, "op_1", "op_2", "op_3", "op_4"]
acc = 0


def op_1(x):
    global acc
    acc = (acc + x + 1) % 99991


def op_2(x):
    global acc
    acc = (acc + 2 * x + 3) % 99991


def op_3(x):
    global acc
    acc = (acc * 3 + x + 5) % 99991


def op_4(x):
    global acc
    acc = (acc + x * x + 7) % 99991


def main():
    for i in range(1, N + 1):
        globals()["op_" + str(i % 4 + 1)](i % 100)
    check = acc
    for i in range(1, N + 1):
        globals()[NAMES[(i * 3) % 4 + 1]](i % 50)
    print(f"result: {check} {acc}")


main()
