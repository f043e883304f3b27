"""TEST/CASE dispatch (the algorithm of testcase.mod): a stack machine and a word classifier."""
import sys

N = int(sys.argv[1]) if len(sys.argv) > 1 else 750

code = [None, 2, 2, 2, 1, 2, 1, 6, 4, 1, 10007, 7, 3, 2, 2, 1, 1, 1, 5, 9, 3, 1, 8, 1, 0]
stack = [0] * 17
reg = [0] * 5
VOCAB = [None, "red", "one", "square", "blue", "three", "tree", "green", "circle", "two", "sky"]


def run(n):
    pc = 1
    sp = 0
    going = True
    reg[1] = n
    reg[2] = 0
    while going:
        op = code[pc]
        pc = pc + 1
        if op == 1:
            sp = sp + 1
            stack[sp] = code[pc]
            pc = pc + 1
        elif op == 2:
            sp = sp + 1
            stack[sp] = reg[code[pc]]
            pc = pc + 1
        elif op == 3:
            reg[code[pc]] = stack[sp]
            sp = sp - 1
            pc = pc + 1
        elif op == 4:
            stack[sp - 1] = stack[sp - 1] + stack[sp]
            sp = sp - 1
        elif op == 5:
            stack[sp - 1] = stack[sp - 1] - stack[sp]
            sp = sp - 1
        elif op == 6:
            stack[sp - 1] = stack[sp - 1] * stack[sp]
            sp = sp - 1
        elif op == 7:
            stack[sp - 1] = stack[sp - 1] % stack[sp]
            sp = sp - 1
        elif op == 8:
            if stack[sp] != 0:
                pc = code[pc]
            else:
                pc = pc + 1
            sp = sp - 1
        elif op == 9:
            sp = sp + 1
            stack[sp] = stack[sp - 1]
        else:
            going = False
    return reg[2]


def classify(w):
    if w in ("red", "green", "blue"):
        return 1
    elif w in ("circle", "square"):
        return 2
    elif w in ("one", "two", "three"):
        return 3
    else:
        return 0


def main():
    check = 0
    words = 0
    for k in range(1, N + 1):
        check = (check + run(1000 + k % 7)) % 1000000
    for k in range(1, 500 * N + 1):
        words = words + classify(VOCAB[k % 10 + 1]) * (k % 3)
    print(f"result: {check} {words}")


main()
