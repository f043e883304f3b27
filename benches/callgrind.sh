#!/usr/bin/env bash
# Instructions per iteration of every function of the parse, interp, motion and egm benches,
# counted by callgrind: deterministic, so figures of two builds compare on a shared machine
# where wall times do not (docs/performance.md).
#
#   benches/callgrind.sh [CHECKOUT] > figures.tsv     # measure (builds the benches, release)
#   benches/callgrind.sh compare BEFORE.tsv AFTER.tsv…  # the markdown before/after table
#
# Each function runs in the benches' fixed-iteration mode (tests/support/src/fixed_iters.rs):
# its setup, one warm-up call, then exactly N calls between two calls of a boundary function,
# where callgrind dumps its counters (--dump-before); the second dump is the N calls, all
# threads. Output: bench, function, N, instructions of the N calls, instructions per call.
# ITERS_<bench>=N overrides a bench's N; BENCHES="parse motion" picks benches.
set -euo pipefail

if [[ ${1:-} == compare ]]; then   # the first file is "before"; each later one gets a ratio
    shift
    awk -F'\t' -v files=$# '
        FNR == 1 { f++ }
        { key = $1 FS $2; ir[f, key] = $5 }
        f == files && !(key in seen) { seen[key] = 1; order[++rows] = key }
        END {
            printf "| bench | function | before |"; for (i = 2; i <= files; i++) printf " after %d | ratio %d |", i - 1, i - 1
            printf "\n|---|---|---:|"; for (i = 2; i <= files; i++) printf "---:|---:|"; print ""
            for (r = 1; r <= rows; r++) {
                split(order[r], k, FS); b = ir[1, order[r]]
                printf "| %s | %s | %s |", k[1], k[2], (b == "" ? "new" : b)
                for (i = 2; i <= files; i++) {
                    a = ir[i, order[r]]
                    printf " %s | %s |", (a == "" ? "-" : a), (b == "" || a == "" ? "new" : sprintf("%.3f", a / b))
                }
                print ""
            }
        }' "$@"
    exit
fi

checkout=$(cd "${1:-$(dirname "$0")/..}" && pwd)
declare -A iters=([parse]=${ITERS_parse:-2} [interp]=${ITERS_interp:-2}
                  [motion]=${ITERS_motion:-1000} [egm]=${ITERS_egm:-2000})
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

for bench in ${BENCHES:-parse interp motion egm}; do
    exe=$(cd "$checkout" && cargo bench --no-run --bench "$bench" 2>&1 |
          sed -n 's/^ *Executable .*(\(.*\))$/\1/p')
    [[ $exe = /* ]] || exe=$checkout/$exe
    mapfile -t names < <(RAPIDVC_BENCH_ITERS=1 "$exe" | sed -n 's/^bench: //p')
    for name in "${names[@]}"; do
        rm -f "$out"/cg.*
        (cd "$checkout" &&
         RAPIDVC_BENCH_ITERS=${iters[$bench]} RAPIDVC_BENCH_ONLY=$name \
         valgrind --tool=callgrind --callgrind-out-file="$out/cg" \
             --dump-before='*fixed_iters::boundary*' "$exe" >"$out/log" 2>&1) ||
            { echo "$bench/$name failed:" >&2; tail "$out/log" >&2; exit 1; }
        grep -qF "fixed: $name: ${iters[$bench]} iterations, 2 boundaries" "$out/log" ||
            { echo "$bench/$name: not 2 boundaries" >&2; tail "$out/log" >&2; exit 1; }
        ir=$(sed -n 's/^summary: \([0-9]*\).*/\1/p' "$out/cg.2")
        printf '%s\t%s\t%s\t%s\t%s\n' "$bench" "$name" "${iters[$bench]}" "$ir" \
            $(( ir / ${iters[$bench]} ))
    done
done
