"""Load generator for benches/rws_load.sh: starts the program of `rapidvc serve` (cycle
forever) with abb_robot_client's RWS class, then, with --clients N > 0, runs N threads that
each log in and read and write resources as fast as the server answers (execution state,
signals, a PERS variable, the joint target, the event log) for --seconds. Prints the request
count and rate.

argv: base URL; --clients N; --seconds S.
"""
import argparse
import threading
import time

from abb_robot_client import rws

p = argparse.ArgumentParser()
p.add_argument("base")
p.add_argument("--clients", type=int, default=0)
p.add_argument("--seconds", type=float, default=20.0)
a = p.parse_args()

main = rws.RWS(a.base)
main.start(cycle="forever", tasks=["T_ROB1"])
count = [0] * a.clients
stop = time.time() + a.seconds


def worker(k):
    c = rws.RWS(a.base)
    n = 0
    while time.time() < stop:
        c.get_execution_state()
        c.set_digital_io("DI1", n % 2)
        c.get_digital_io("DO_ECHO")
        c.set_rapid_variable_num("counter", n)
        c.get_rapid_variable_num("cycles")
        c.get_jointtarget()
        if n % 10 == 0:
            c.read_event_log()
        n += 7
    count[k] = n


threads = [threading.Thread(target=worker, args=(k,)) for k in range(a.clients)]
for t in threads:
    t.start()
for t in threads:
    t.join()
time.sleep(max(0.0, stop - time.time()))
total = sum(count)
print(f"{a.clients} clients: {total} requests in {a.seconds:.0f} s ({total / a.seconds:.0f}/s)",
      flush=True)
main.stop()
