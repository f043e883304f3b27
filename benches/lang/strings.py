"""String building (the algorithm of strings.mod)."""
import sys

N = int(sys.argv[1]) if len(sys.argv) > 1 else 150000


def main():
    total = 0
    sevens = 0
    for rnd in range(1, N + 1):
        s = ""
        for i in range(1, 11):
            s = s + str((rnd * i) % 997) + ","
        r = ""
        for k in range(len(s), 0, -1):
            c = s[k - 1]
            if c == "7":
                sevens = sevens + 1
            r = r + c
        found = r.find("9")
        found = len(r) + 1 if found < 0 else found + 1
        total = (total + len(r) + found) % 1000000
    print(f"result: {total} {sevens}")


main()
