"""Drive a served system of three tasks (tests/serve_tasks/) with abb_robot_client's RWS class
(PyPI, unchanged): the task list as it parses it, start of the motion task with its task
list, the STATIC task running across a stop, a shared PERS read per task, and an RMQ round
trip RWS -> T_ROB1 -> RWS over rw/dipc. Each check prints "OK <name>"; a failed check
raises (non-zero exit).
"""
import sys
import time

from abb_robot_client import rws

r = rws.RWS(sys.argv[1])


def ok(name, cond, detail=""):
    if not cond:
        raise SystemExit(f"FAILED {name}: {detail}")
    print("OK", name, flush=True)


def wait_for(what, cond, limit=10.0):
    end = time.time() + limit
    while time.time() < end:
        if cond():
            return True
        time.sleep(0.05)
    raise SystemExit(f"FAILED {what}: not within {limit} s")


tasks = r.get_tasks()
ok("tasks", list(tasks) == ["T_ROB1", "T_LOG", "T_CELL"], tasks)
ok("types", [t.type_ for t in tasks.values()] == ["norm", "stat", "semi"], tasks)
ok("motiontask", [t.motiontask for t in tasks.values()] == [True, False, False], tasks)
ok("static runs at boot", tasks["T_LOG"].excstate == "star", tasks)

ticks = lambda: float(r.get_rapid_variable("ticks", "T_LOG"))
t0 = ticks()
wait_for("T_LOG counts", lambda: ticks() >= t0 + 3)

ok("queue", r.try_create_ipc_queue("py_queue", 10, 444))
r.send_ipc_message("RMQ_T_ROB1", 'string;"py"', "py_queue", userdef=3)
r.start(cycle="once", tasks=["T_ROB1"])
msgs = []


def got():
    msgs.extend(r.read_ipc_message("py_queue", timeout=1))
    return bool(msgs)


wait_for("answer", got)
ok("rmq round trip", msgs[0].data == 'string;"got py"' and msgs[0].queue_name == "py_queue", msgs)
wait_for("stopped", lambda: r.get_execution_state().ctrlexecstate == "stopped")
ok("shared pers", float(r.get_rapid_variable("shared", "T_ROB1")) == 1.0
   and float(r.get_rapid_variable("shared", "T_CELL/Cell")) >= 1.0)

# Start again; stop while T_ROB1 waits for its message: the STATIC task keeps running.
r.start(cycle="once", tasks=["T_ROB1"])
wait_for("second cycle", lambda: float(r.get_rapid_variable("shared", "T_ROB1")) == 2.0)
r.stop()
wait_for("stopped again", lambda: r.get_execution_state().ctrlexecstate == "stopped")
tasks = r.get_tasks()
ok("only the normal task stopped", tasks["T_ROB1"].excstate == "stop" and tasks["T_LOG"].excstate == "star", tasks)
t1 = ticks()
wait_for("T_LOG counts across the stop", lambda: ticks() >= t1 + 3)
r.resetpp()
ok("resetpp", r.get_tasks()["T_ROB1"].excstate == "read")
print("ALL OK", flush=True)
