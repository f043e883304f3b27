"""Replay the requests abb_librws and abb_egm_rws_managers (the C++ RWS layer of the ROS
drivers) make against a controller, in their order, and read every answer the way they do.

The list of requests and the fields read from each were written for rapidvc's tests from the
two libraries' behaviour: the RWS manager's start-up (system data, configuration, mechanical
units, tasks and modules), its runtime poll (state, positions, the StateMachine add-in's
data), and the RWS interface's other reads (speed ratio, robtargets). Answers are parsed as
XML with a DOM parser and searched the way librws searches them: elements by their `class`
attribute anywhere below a node, configuration attributes by their `title`, and a field's
text as the first non-empty text whose parent has the class.

The server at argv[1] is `rapidvc serve tests/serve_librws` (a motion task T_ROB1 with the
modules MainModule, TRobMain and TRobEGM). Every check prints "OK <name>"; a failed check
exits non-zero. The script ends with "ALL OK".
"""
import math
import re
import sys
import time
import xml.dom.minidom

import requests

base = sys.argv[1]
session = requests.Session()
auth = requests.auth.HTTPDigestAuth("Default User", "robotics")
requested = []


def ok(name, cond, detail=""):
    if not cond:
        raise SystemExit(f"FAILED {name}: {detail}")
    print("OK", name, flush=True)


def get(path, status=200):
    requested.append(path)
    res = session.get(base + path, auth=auth, timeout=10)
    assert res.status_code == status, (path, res.status_code, res.text)
    assert res.headers["Content-Type"].startswith("application/xhtml+xml"), res.headers
    return xml.dom.minidom.parseString(res.content)


def post(path, body, status=204):
    requested.append(path)
    res = session.post(base + path, data=body, auth=auth, timeout=10,
                       headers={"Content-Type": "application/x-www-form-urlencoded"})
    assert res.status_code == status, (path, res.status_code, res.text)


def elements(node):
    """Every element below `node` (itself included), in document order."""
    out = []
    stack = [node]
    while stack:
        n = stack.pop()
        if n.nodeType == n.ELEMENT_NODE:
            out.append(n)
        stack.extend(reversed(n.childNodes))
    return out


def find(node, cls):
    """The elements whose class is `cls` (librws' xmlFindNodes)."""
    return [e for e in elements(node) if e.getAttribute("class") == cls]


def content(node, cls):
    """The first non-empty text whose parent has class `cls` (librws' xmlFindTextContent)."""
    for e in elements(node):
        if e.getAttribute("class") == cls:
            for c in e.childNodes:
                if c.nodeType == c.TEXT_NODE and c.data:
                    return c.data
    return ""


def number(text):
    """A number as C++'s `stringstream >> double` reads it (a failed read fails the check)."""
    m = re.match(r"\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?", text)
    assert m, f"not a number: {text!r}"
    return float(m.group(0))


def cfg(domain, type_name):
    """The instances of a configuration type: a list of {title: value}, and the titles."""
    d = get(f"/rw/cfg/{domain}/{type_name}/instances")
    out = []
    for inst in find(d, "cfg-dt-instance-li"):
        attrs = {a.getAttribute("title"): content(a, "value") for a in find(inst, "cfg-ia-t-li")}
        attrs["(title)"] = inst.getAttribute("title")
        out.append(attrs)
    return out


# ---------------------------------------------------------------------------------------
# RWSManager::collectAndParseSystemData: general system info (getSystemInfo).
d = get("/rw/system")
systems = find(d, "sys-system-li")
system_name = content(systems[-1], "name") if systems else ""
version = content(systems[-1], "rwversionname") if systems else ""
options = [content(o, "option") for o in find(d, "sys-option-li")]
system_type = content(get("/ctrl"), "ctrl-type")
ok("system name", system_name != "", system_name)
ok("system type", system_type == "Virtual Controller", system_type)
ok("robotware version has three N. groups", len(re.findall(r"([0-9]+\.)", version)) == 3, version)
major, minor, patch = (int(x) for x in re.findall(r"([0-9]+)\.", version)[:3])
ok("robotware 6", major == 6, version)
ok("options", "689-1 Externally Guided Motion (EGM)" in options, options)
ok("statemachine option (TRobMain loaded)", "StateMachine Core" in options, options)
ok("no multimove", not any(o.startswith("604-") for o in options), options)

# Configurations, in the manager's order and with librws' spelling of each path.
mugs = cfg("sys", "mechanical_unit_group")
mus = cfg("moc", "mechanical_unit")
robots = cfg("moc", "robot")
singles = cfg("moc", "single")
joints = cfg("MOC", "JOINT")
arms = cfg("moc", "arm")
transmissions = cfg("MOC", "TRANSMISSION")

ok("mechanical unit groups", [(g.get("Name"), g.get("Robot")) for g in mugs] == [("rob1", "ROB_1")], mugs)
ok("mechanical units", [(m.get("name"), m.get("use_robot")) for m in mus] == [("ROB_1", "ROB_1")], mus)
ok("no singles", singles == [], singles)
ok("one robot", len(robots) == 1 and robots[0].get("name") == "ROB_1", robots)
robot = robots[0]
ok("robot type", robot.get("use_robot_type", "") != "", robot)
use_joints = [robot.get(f"use_joint_{i}", "") for i in range(6)]
ok("robot joints", use_joints == [f"rob1_{i}" for i in range(1, 7)], use_joints)
base_frame = [number(robot[k]) for k in ("base_frame_pos_x", "base_frame_pos_y", "base_frame_pos_z",
                                         "base_frame_orient_u0", "base_frame_orient_u1",
                                         "base_frame_orient_u2", "base_frame_orient_u3")]
ok("robot base frame at the world origin", base_frame == [0, 0, 0, 1, 0, 0, 0], base_frame)

ok("joints", len(joints) == 6, joints)
by_name = {j["name"]: j for j in joints}
arm_by_name = {a["name"]: a for a in arms}
trans_by_title = {t["(title)"]: t for t in transmissions}
# The IRB 2600-12/1.85's axis ranges (deg), which MOC.cfg holds in radians.
ranges = [(-180, 180), (-95, 155), (-180, 75), (-400, 400), (-120, 120), (-400, 400)]
for i, name in enumerate(use_joints):
    j = by_name.get(name)
    ok(f"joint {name}", j is not None and int(number(j["logical_axis"])) == i + 1
       and int(number(j["kinematic_axis_number"])) == -1, j)
    arm = arm_by_name.get(j["use_arm"])
    lo, hi = ranges[i]
    ok(f"arm {j['use_arm']}", arm is not None
       and math.isclose(number(arm["lower_joint_bound"]), math.radians(lo), abs_tol=1e-9)
       and math.isclose(number(arm["upper_joint_bound"]), math.radians(hi), abs_tol=1e-9), arm)
    t = trans_by_title.get(j["use_transmission"])
    ok(f"transmission {j['use_transmission']}", t is not None and t.get("rotating_move") == "true", t)

# Complementary info for each mechanical unit (getMechanicalUnitStaticInfo / DynamicInfo).
for m in mus:
    d = get(f"/rw/motionsystem/mechunits/{m['name']}?resource=static")
    static = {k: content(d, k) for k in ("task-name", "is-integrated-unit", "has-integrated-unit",
                                         "type", "axes", "axes-total")}
    ok("static info", static == {"task-name": "T_ROB1", "is-integrated-unit": "NoIntegratedUnit",
                                  "has-integrated-unit": "NoIntegratedUnit", "type": "TCPRobot",
                                  "axes": "6", "axes-total": "6"}, static)
    d = get(f"/rw/motionsystem/mechunits/{m['name']}?resource=dynamic")
    dynamic = {k: content(d, k) for k in ("tool-name", "wobj-name", "payload-name", "total-payload-name",
                                          "status", "jog-mode", "mode", "coord-system")}
    ok("dynamic info", all(dynamic.values()) and dynamic["mode"] == "Activated"
       and dynamic["coord-system"] in ("Base", "World", "Tool", "Wobj"), dynamic)

# RAPID tasks and their modules.
tasks = []
for li in find(get("/rw/rapid/tasks"), "rap-task-li"):
    tasks.append((content(li, "name"), content(li, "motiontask") == "TRUE", content(li, "active") == "On",
                  content(li, "excstate")))
ok("tasks", tasks == [("T_ROB1", True, True, "read")], tasks)
for name, *_ in tasks:
    mods = [(content(li, "name"), content(li, "type")) for li in find(get(f"/rw/rapid/modules?task={name}"),
                                                                       "rap-module-info-li")]
    ok(f"modules of {name}", {("MainModule", "ProgMod"), ("TRobMain", "ProgMod"), ("TRobEGM", "ProgMod")}
       <= set(mods), mods)


# ---------------------------------------------------------------------------------------
# RWSManager::collectAndUpdateRuntimeData.
def runtime(expect_running):
    d = get("/rw/system")
    ok("runtime system name", content(find(d, "sys-system-li")[-1], "name") == system_name)
    get("/ctrl")
    ok("motors on", content(get("/rw/panel/ctrlstate"), "ctrlstate") == "motoron")
    ok("auto", content(get("/rw/panel/opmode"), "opmode") == "AUTO")
    running = content(get("/rw/rapid/execution"), "ctrlexecstate") == "running"
    ok("execution state", running == expect_running, running)
    d = get("/rw/motionsystem/mechunits/ROB_1?resource=dynamic")
    ok("unit active", content(d, "mode") == "Activated")
    d = get("/rw/motionsystem/mechunits/ROB_1/jointtarget")
    axes = [number(content(d, f"rax_{i}")) for i in range(1, 7)]
    ext = [content(d, f"eax_{c}") for c in "abcdef"]
    ok("joint target", len(axes) == 6 and ext == ["9E+09"] * 6, (axes, ext))
    get("/rw/rapid/tasks")
    # The StateMachine add-in's data of each motion task (num, checked by its properties).
    for module, symbol, want in (("TRobMain", "current_state", "1"), ("TRobEGM", "current_action", "3")):
        d = get(f"/rw/rapid/symbol/properties/RAPID/T_ROB1/{module}/{symbol}")
        ok(f"{symbol} is a num", content(d, "dattyp") == "num", d.toxml())
        value = content(get(f"/rw/rapid/symbol/data/RAPID/T_ROB1/{module}/{symbol}"), "value")
        ok(f"{symbol} value", value == want, value)
    return axes


runtime(expect_running=False)
ok("speed ratio", int(number(content(get("/rw/panel/speedratio"), "speedratio"))) == 100)

# ---------------------------------------------------------------------------------------
# The program moves and writes CRobT for every tool and work object: librws' start
# (startRAPIDExecution's form), then the robtargets it serves.
post("/rw/rapid/execution?action=start",
     "regain=continue&execmode=continue&cycle=forever&condition=none&stopatbp=disabled&alltaskbytsp=false")
deadline = time.time() + 30
while content(get("/rw/rapid/symbol/data/RAPID/T_ROB1/MainModule/done"), "value") != "TRUE":
    ok("program done in time", time.time() < deadline)
    time.sleep(0.05)
axes = runtime(expect_running=True)
ok("joint target where the program moved", [round(a, 3) for a in axes] == [20, -10, 15, 30, 40, -25], axes)


def rapid_numbers(text):
    return [float(x) for x in re.split(r"[\[\],]", text) if x.strip()]


def served(tool, wobj, coordinate):
    """getMechanicalUnitRobTarget: the robtarget's 17 fields, in librws' order."""
    query = f"?coordinate={coordinate}" + (f"&tool={tool}" if tool else "") + (f"&wobj={wobj}" if wobj else "")
    d = get(f"/rw/motionsystem/mechunits/ROB_1/robtarget{query}")
    names = ["x", "y", "z", "q1", "q2", "q3", "q4", "cf1", "cf4", "cf6", "cfx"] + [f"eax_{c}" for c in "abcdef"]
    return [number(content(d, n)) for n in names]


def close(a, b, what):
    # RAPID's num is single precision: the served text and the PERS text both are.
    same = len(a) == len(b) and all(math.isclose(x, y, rel_tol=1e-5, abs_tol=2e-3) for x, y in zip(a, b))
    ok(what, same, (a, b))


def rapid(name):
    return rapid_numbers(content(get(f"/rw/rapid/symbol/data/RAPID/T_ROB1/MainModule/{name}"), "value"))


for tool, tk in (("tool0", "t0"), ("tGrip", "tg")):
    in_world = rapid(f"rt_{tk}_w0")
    in_table = rapid(f"rt_{tk}_wt")
    # librws spells World `Word`; rapidvc's robot stands at the world origin.
    for coordinate in ("Base", "Word", "World"):
        close(served(tool, "wobj0", coordinate), in_world, f"{tool} {coordinate} = CRobT(\\Tool:={tool})")
    close(served(tool, "wTable", "Wobj"), in_table, f"{tool} in wTable = CRobT(\\Tool:={tool} \\WObj:=wTable)")
    close(served(tool, "wobj0", "Wobj"), in_world, f"{tool} in wobj0 = CRobT(\\Tool:={tool})")
    t = served(tool, "wTable", "Tool")
    close(t[:7], [0, 0, 0, 1, 0, 0, 0], f"{tool} in its own frame")
    close(t[7:], in_world[7:], f"{tool} Tool keeps the configuration")

# Without tool and work object (librws' "active" request): the active ones, in Base.
active = served("", "", "Base")
close(active, rapid("rt_tg_w0"), "active tool tGrip in Base")
d = get("/rw/motionsystem/mechunits/ROB_1?resource=dynamic")
ok("active tool and wobj", (content(d, "tool-name"), content(d, "wobj-name")) == ("tGrip", "wTable"))

# Names the task does not have, or that are no tool: ABB's error body.
for query, status in (("?tool=tNone", 404), ("?wobj=wNone", 404), ("?tool=notATool", 400),
                      ("?coordinate=Galaxy", 400)):
    res = session.get(base + "/rw/motionsystem/mechunits/ROB_1/robtarget" + query, auth=auth, timeout=10)
    err = xml.dom.minidom.parseString(res.content)
    ok(f"robtarget{query} -> {status}", res.status_code == status
       and int(content(err, "code")) < 0 and content(err, "msg") != "", (res.status_code, res.text))

post("/rw/rapid/execution?action=stop", "stopmode=stop")
print("REQUESTED", len(requested), flush=True)
print("ALL OK", flush=True)
