#!/bin/sh
# The motion cycle's period error of `rapidvc serve` with and without a Robot Web Services
# load generator (benches/rws_load.py, abb_robot_client's RWS class in threads). Each run
# serves tests/serve/ for SECONDS with its program running forever, is stopped with SIGINT,
# and prints the summary line with the period error the motion thread measured.
#
#   PYTHON=/path/to/python-with-abb_robot_client benches/rws_load.sh [SECONDS] [CLIENTS]
#
# Build first (`cargo build --release`); RAPIDVC names the binary (default
# target/release/rapidvc).
set -eu
SECONDS_RUN=${1:-20}
CLIENTS=${2:-8}
RAPIDVC=${RAPIDVC:-target/release/rapidvc}
PYTHON=${PYTHON:-python3}
for clients in 0 "$CLIENTS"; do
    out=$(mktemp)
    err=$(mktemp)
    "$RAPIDVC" serve tests/serve --rws 127.0.0.1:0 >"$out" 2>"$err" &
    pid=$!
    url=""
    for _ in $(seq 1 100); do
        url=$(sed -n 's/.*\(http:\/\/[0-9.:]*\).*/\1/p' "$out" | head -n 1)
        [ -n "$url" ] && break
        sleep 0.1
    done
    [ -n "$url" ] || { echo "rapidvc serve did not start:"; cat "$err"; kill "$pid"; exit 1; }
    "$PYTHON" benches/rws_load.py "$url" --clients "$clients" --seconds "$SECONDS_RUN"
    kill -INT "$pid"
    wait "$pid" || true
    grep "period error" "$err" | sed "s/^/  $clients clients: /"
    rm -f "$out" "$err"
done
