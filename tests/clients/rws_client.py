"""Drive rapidvc's Robot Web Services with abb_robot_client's RWS class (PyPI, unchanged).

Every call the class makes is exercised against the server at argv[1]; each check prints
"OK <name>", a failed check raises (non-zero exit). The server is a real `rapidvc serve` of
tests/serve/: signals DO1, AO_MODE on Local/DRV_1 and DN_DO on DeviceNet/d651 (EIO.cfg),
PERS counter, arr, jt, cycles in T_ROB1/MainModule, one motion task T_ROB1, the robot at its
calibration position. The XHTML resources abb_librws reads are parsed with a DOM parser, as
librws does, and searched by class.
"""
import sys
import threading
import time
import xml.dom.minidom

import numpy as np
import requests
from abb_robot_client import rws

base = sys.argv[1]
r = rws.RWS(base)


def ok(name, cond, detail=""):
    if not cond:
        raise SystemExit(f"FAILED {name}: {detail}")
    print("OK", name, flush=True)


# Controller and panel state.
ok("ctrlstate", r.get_controller_state() == "motoron")
ok("opmode", r.get_operation_mode() == "AUTO")
st = r.get_execution_state()
ok("execution", st.ctrlexecstate == "stopped", st)
tasks = r.get_tasks()
ok("tasks", tasks["T_ROB1"].motiontask and tasks["T_ROB1"].active and list(tasks) == ["T_ROB1"], tasks)
r.deactivate_task("T_ROB1")
ok("deactivate", not r.get_tasks()["T_ROB1"].active)
r.activate_task("T_ROB1")
ok("activate", r.get_tasks()["T_ROB1"].active)

# Subscription first, so the changes below arrive as events.
events = []
lock = threading.Lock()


def handler(ev):
    with lock:
        events.append(ev)


sub = r.subscribe([
    rws.SubscriptionResourceRequest(rws.SubscriptionResourceType.Signal, rws.SubscriptionResourcePriority.High, "DO1"),
    rws.SubscriptionResourceRequest(rws.SubscriptionResourceType.ExecutionState, rws.SubscriptionResourcePriority.Medium),
    rws.SubscriptionResourceRequest(rws.SubscriptionResourceType.ControllerState, rws.SubscriptionResourcePriority.Medium),
    rws.SubscriptionResourceRequest(rws.SubscriptionResourceType.PersVar, rws.SubscriptionResourcePriority.High, "counter"),
    rws.SubscriptionResourceRequest(rws.SubscriptionResourceType.Elog, rws.SubscriptionResourcePriority.Medium),
], handler)
time.sleep(0.5)

# Start forever, stop, start once, reset the program pointer.
r.start(cycle="forever", tasks=["T_ROB1"])
st = r.get_execution_state()
ok("start forever", st.ctrlexecstate == "running" and st.cycle == "forever", st)
r.stop()
ok("stop", r.get_execution_state().ctrlexecstate == "stopped")
r.start(cycle="once", tasks=["T_ROB1"])
ok("start once", r.get_execution_state().cycle == "once")
r.stop()
r.resetpp()
ok("resetpp", True)

# Signals on Local/DRV_1 and on a DeviceNet device.
r.set_digital_io("DO1", 1)
ok("digital io", r.get_digital_io("DO1") == 1)
r.set_analog_io("AO_MODE", 2.5)
ok("analog io", r.get_analog_io("AO_MODE") == 2.5)
r.set_digital_io("DN_DO", True, network="DeviceNet", unit="d651")
ok("devicenet io", r.get_digital_io("DN_DO", network="DeviceNet", unit="d651") == 1)

# PERS by task and by task/module, numbers, arrays, jointtargets; the symbol search.
ok("pers num", r.get_rapid_variable_num("counter") == 0)
r.set_rapid_variable_num("counter", 42)
ok("pers num set", r.get_rapid_variable_num("counter") == 42)
ok("pers by module", r.get_rapid_variable("counter", "T_ROB1/MainModule") == "42")
r.set_rapid_variable_num_array("arr", [4, 5, 6])
ok("pers array", list(r.get_rapid_variable_num_array("arr")) == [4, 5, 6])
jt = r.get_rapid_variable_jointtarget("jt")
ok("pers jointtarget", np.allclose(np.rad2deg(jt.robax), [0, 0, 0, 0, 30, 0]))
r.set_rapid_variable_jointtarget("jt", rws.JointTarget(np.deg2rad([1, 2, 3, 4, 5, 6]), np.deg2rad([0] * 6)))
ok("pers jointtarget set", np.allclose(np.rad2deg(r.get_rapid_variable_jointtarget("jt").robax), [1, 2, 3, 4, 5, 6]))
found = [s["name"] for s in r.get_rapid_variables("T_ROB1")]
ok("search symbols", {"counter", "arr", "jt", "cycles"} <= set(found), found)
try:
    r.set_rapid_variable("counter", "not a number")
    ok("bad pers value refused", False)
except rws.ABBException as e:
    ok("bad pers value refused", e.code < 0, e)

# Files on $RAMDISK.
ram = r.get_ramdisk_path()
ok("ramdisk path", ram == "$RAMDISK", ram)
r.upload_file(ram + "/motion.bin", b"\x00\x01binary")
ok("list files", "motion.bin" in r.list_files(ram))
ok("read file", r.read_file(ram + "/motion.bin") == b"\x00\x01binary")
r.delete_file(ram + "/motion.bin")
ok("delete file", "motion.bin" not in r.list_files(ram))

# The event log (with its time stamp format), joints and robtarget, speed ratio.
log = r.read_event_log()
ok("event log", len(log) >= 4 and any(e.code == 10150 for e in log), log[:2])
ok("event log time", all(e.tstamp.year >= 2024 for e in log))
j = r.get_jointtarget()
ok("jointtarget", np.allclose(j.robax, [0] * 6) and j.extax[0] == 9e9, j)
t = r.get_robtarget(tool="tool0", wobj="wobj0", coordinate="Base")
ok("robtarget", t.trans[0] > 500 and abs(t.trans[1]) < 1e-3 and abs(np.linalg.norm(t.rot) - 1) < 1e-3 and t.extax[0] == 9e9, t)
ok("speedratio", r.get_speedratio() == 100)
r.set_speedratio(50)
ok("speedratio set", r.get_speedratio() == 50)

# External queues (RAPID's RMQ is not served yet: a message to a task is refused).
ok("ipc create", r.try_create_ipc_queue("rmq_client") is True)
ok("ipc exists", r.try_create_ipc_queue("rmq_client") is False)
r.send_ipc_message("rmq_client", 'string;"hello"', "rmq_client")
msgs = r.read_ipc_message("rmq_client", timeout=2)
ok("ipc read", len(msgs) == 1 and "hello" in msgs[0].data, msgs)
try:
    r.send_ipc_message("T_ROB1", 'string;"hello"', "rmq_client")
    ok("ipc to a task refused", False)
except Exception as e:
    ok("ipc to a task refused", "RMQ" in str(e) or "403" in str(e) or "not supported" in str(e), e)

# Remote mastering: the calls request_rmmp makes (its poll_rmmp builds a doubled URL,
# base + base + path, which no controller serves, so request_rmmp itself is not called).
r._do_post("users/rmmp", {"privilege": "modify"})
poll = r._do_get("users/rmmp/poll")["_embedded"]["_state"][0]
ok("rmmp", poll["_type"] == "user-rmmp-poll" and poll["status"] == "GRANTED", poll)

# What abb_librws reads, parsed as XML by class.
s = requests.Session()
auth = requests.auth.HTTPDigestAuth("Default User", "robotics")


def dom(path):
    res = s.get(base + path, auth=auth)
    assert res.status_code == 200, (path, res.status_code, res.text)
    return xml.dom.minidom.parseString(res.content)


def by_class(doc, cls):
    return [e for tag in ("li", "span") for e in doc.getElementsByTagName(tag) if e.getAttribute("class") == cls]


def text(e):
    return "".join(n.data for n in e.childNodes if n.nodeType == n.TEXT_NODE)


d = dom("/rw/system")
ok("librws system", text(by_class(d, "rwversionname")[0]).count(".") == 3
   and "689-1 Externally Guided Motion (EGM)" in [text(e) for e in by_class(d, "option")])
ok("librws ctrl", text(by_class(dom("/ctrl"), "ctrl-type")[0]) != "")
d = dom("/rw/rapid/tasks")
li = [e for e in by_class(d, "rap-task-li") if e.getAttribute("title") == "T_ROB1"][0]
ok("librws tasks", text(by_class(li, "motiontask")[0]) == "TRUE" and text(by_class(li, "active")[0]) == "On")
mods = {e.getAttribute("title"): text(by_class(e, "type")[0]) for e in by_class(dom("/rw/rapid/modules?task=T_ROB1"), "rap-module-info-li")}
ok("librws modules", mods.get("T_ROB1/MainModule") == "ProgMod" and list(mods.values()).count("ProgMod") == 1, mods)
d = dom("/rw/cfg/moc/mechanical_unit/instances")
inst = by_class(d, "cfg-dt-instance-li")[0]
attrs = {a.getAttribute("title"): text(by_class(a, "value")[0]) for a in by_class(inst, "cfg-ia-t-li")}
ok("librws cfg", attrs == {"name": "ROB_1", "use_robot": "ROB_1"}, attrs)
d = dom("/rw/motionsystem/mechunits/ROB_1?resource=static")
ok("librws mechunit static", text(by_class(d, "type")[0]) == "TCPRobot" and text(by_class(d, "axes")[0]) == "6")
d = dom("/rw/motionsystem/mechunits/ROB_1?resource=dynamic")
ok("librws mechunit dynamic", text(by_class(d, "mode")[0]) == "Activated" and text(by_class(d, "payload-name")[0]) == "load0")
d = dom("/rw/rapid/symbol/properties/RAPID/T_ROB1/MainModule/counter")
ok("librws properties", text(by_class(d, "dattyp")[0]) == "num")
ok("librws jointtarget", text(by_class(dom("/rw/motionsystem/mechunits/ROB_1/jointtarget"), "eax_a")[0]) == "9E+09")
ok("librws signal", text(by_class(dom("/rw/iosystem/signals/DO1"), "lvalue")[0]) == "1")

# The subscription's events.
deadline = time.time() + 5
want = {"signal", "exec", "ctrl-free", "pers", "elog"}
while time.time() < deadline:
    with lock:
        sig = any(isinstance(e, rws.Signal) and e.name == "DO1" and e.lvalue == "1" for e in events)
        ex = any(isinstance(e, rws.RAPIDExecutionState) and e.ctrlexecstate == "running" for e in events)
        pers = any(isinstance(e, rws.VariableValue) and e.value == "42" for e in events)
        elog = any(isinstance(e, rws.EventLogEntryEvent) for e in events)
    if sig and ex and pers and elog:
        break
    time.sleep(0.1)
ok("subscription signal", sig, events)
ok("subscription execution", ex, events)
ok("subscription pers", pers, events)
ok("subscription elog", elog, events)
sub.close()

r.logout()
try:
    rws.RWS(base, password="wrong").get_controller_state()
    ok("wrong password refused", False)
except Exception as e:
    ok("wrong password refused", "401" in str(e) or "login failed" in str(e), e)
print("ALL OK", flush=True)
