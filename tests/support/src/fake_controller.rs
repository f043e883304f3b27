//! A STAND-IN for the controller, used only until `rapidvc serve` lands: it answers the
//! service contract's requests (`controller::service::Request`) from fixed state on a thread
//! of its own, and publishes the events a controller would for the changes it makes. It runs
//! no RAPID; its "RAPID side" is a few canned reactions (named below). The RWS tests that use
//! it (tests/rws.rs, tests/rws_clients.rs) move to a real `rapidvc serve` once the controller
//! serves the contract.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

use std::collections::{HashMap, VecDeque};
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::thread::JoinHandle;
use std::time::{Duration, SystemTime, UNIX_EPOCH};

use rapidvc::controller::service::{
    CfgInstance, CtrlState, CycleMode, DipcMessage, ElogEntry, ElogSeverity, Event, ExecState,
    MechUnitInfo, ModuleInfo, OpMode, Request, RobotState, ServiceEndpoint, ServiceError,
    ServiceHandle, SignalInfo, SymbolClass, SymbolInfo, SymbolPath, SystemInfo, TaskExecState,
    TaskInfo, TaskType, channel,
};
use rapidvc::signals::SignalKind;

/// Something a test makes happen on the controller side.
pub enum Inject {
    /// RAPID sets a signal.
    Signal(String, f64),
    /// Publish `n` signal events as fast as possible (load).
    Flood(usize),
}

struct FakeState {
    exec: ExecState,
    cycle: CycleMode,
    ctrl: CtrlState,
    opmode: OpMode,
    speed: u8,
    tasks: Vec<TaskInfo>,
    signals: Vec<SignalInfo>,
    symbols: Vec<SymbolInfo>,
    elog: Vec<ElogEntry>,
    queues: HashMap<String, VecDeque<DipcMessage>>,
    roots: Vec<(String, PathBuf)>,
}

/// The stand-in controller; stops when dropped.
pub struct FakeController {
    handle: ServiceHandle,
    stop: Arc<AtomicBool>,
    inject: mpsc::Sender<Inject>,
    thread: Option<JoinHandle<()>>,
    /// Its mass storage (HOME, TEMP, RAMDISK below it).
    pub dir: PathBuf,
}

fn sym(
    task: &str,
    module: &str,
    name: &str,
    class: SymbolClass,
    ty: &str,
    dims: Vec<u32>,
    v: &str,
) -> SymbolInfo {
    SymbolInfo {
        path: SymbolPath {
            task: task.into(),
            module: Some(module.into()),
            name: name.into(),
        },
        class,
        data_type: ty.into(),
        dims,
        value: v.into(),
    }
}

fn sig(name: &str, kind: SignalKind, network: &str, device: &str) -> SignalInfo {
    SignalInfo {
        name: name.into(),
        kind,
        value: 0.0,
        network: network.into(),
        device: device.into(),
    }
}

impl FakeController {
    /// Start it, with its mass storage in a fresh temporary directory named after `tag`.
    pub fn start(tag: &str) -> FakeController {
        let dir = std::env::temp_dir().join(format!("rapidvc-rws-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let roots: Vec<(String, PathBuf)> = ["HOME", "TEMP", "RAMDISK"]
            .iter()
            .map(|r| (r.to_string(), dir.join(r.to_lowercase())))
            .collect();
        for (_, d) in &roots {
            std::fs::create_dir_all(d).unwrap();
        }
        let state = FakeState {
            exec: ExecState::Stopped,
            cycle: CycleMode::AsIs,
            ctrl: CtrlState::MotorsOn,
            opmode: OpMode::Auto,
            speed: 100,
            tasks: vec![
                TaskInfo {
                    name: "T_ROB1".into(),
                    task_type: TaskType::Normal,
                    exec_state: TaskExecState::Ready,
                    active: true,
                    motion_task: true,
                },
                TaskInfo {
                    name: "T_LOG".into(),
                    task_type: TaskType::Static,
                    exec_state: TaskExecState::Started,
                    active: true,
                    motion_task: false,
                },
            ],
            signals: vec![
                sig("DO1", SignalKind::Do, "Local", "DRV_1"),
                sig("DI1", SignalKind::Di, "Local", "DRV_1"),
                sig("AO_MODE", SignalKind::Ao, "Local", "DRV_1"),
                sig("GO1", SignalKind::Go, "Local", "DRV_1"),
                sig("DN_DO", SignalKind::Do, "DeviceNet", "d651"),
            ],
            symbols: vec![
                sym(
                    "T_ROB1",
                    "MainModule",
                    "counter",
                    SymbolClass::Pers,
                    "num",
                    vec![],
                    "0",
                ),
                sym(
                    "T_ROB1",
                    "MainModule",
                    "arr",
                    SymbolClass::Pers,
                    "num",
                    vec![3],
                    "[1,2,3]",
                ),
                sym(
                    "T_ROB1",
                    "MainModule",
                    "jt",
                    SymbolClass::Pers,
                    "jointtarget",
                    vec![],
                    "[[0,0,0,0,30,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]]",
                ),
                sym(
                    "T_ROB1",
                    "MainModule",
                    "v",
                    SymbolClass::Var,
                    "num",
                    vec![],
                    "5",
                ),
                sym(
                    "T_ROB1",
                    "MainModule",
                    "c",
                    SymbolClass::Const,
                    "num",
                    vec![],
                    "3",
                ),
                sym(
                    "T_LOG",
                    "LogModule",
                    "lines",
                    SymbolClass::Pers,
                    "num",
                    vec![],
                    "0",
                ),
            ],
            elog: Vec::new(),
            queues: HashMap::new(),
            roots,
        };
        let (handle, endpoint) = channel();
        let stop = Arc::new(AtomicBool::new(false));
        let (inject, injected) = mpsc::channel();
        let s = stop.clone();
        let thread = std::thread::spawn(move || run(endpoint, state, s, injected));
        FakeController {
            handle,
            stop,
            inject,
            thread: Some(thread),
            dir,
        }
    }

    /// The services' side.
    pub fn handle(&self) -> ServiceHandle {
        self.handle.clone()
    }

    /// Make something happen on the controller side.
    pub fn inject(&self, what: Inject) {
        let _ = self.inject.send(what);
    }
}

impl Drop for FakeController {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::SeqCst);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

fn now() -> f64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map(|d| d.as_secs_f64())
        .unwrap_or(0.0)
}

fn log(st: &mut FakeState, ep: &ServiceEndpoint, code: u32, title: &str, desc: &str) {
    let e = ElogEntry {
        seq: st.elog.len() as u64 + 1,
        severity: ElogSeverity::Info,
        code,
        title: title.into(),
        description: desc.into(),
        timestamp: now(),
    };
    st.elog.push(e.clone());
    ep.publish(Event::Elog(0, e));
}

fn find_symbol<'a>(st: &'a mut FakeState, p: &SymbolPath) -> Option<&'a mut SymbolInfo> {
    st.symbols.iter_mut().find(|s| {
        s.path.task.eq_ignore_ascii_case(&p.task)
            && s.path.name.eq_ignore_ascii_case(&p.name)
            && p.module.as_ref().is_none_or(|m| {
                s.path
                    .module
                    .as_ref()
                    .is_some_and(|sm| sm.eq_ignore_ascii_case(m))
            })
    })
}

/// The stand-in's value check: num data must be a number, arrays the right count of them.
fn check_value(s: &SymbolInfo, v: &str) -> Result<(), ServiceError> {
    if s.data_type != "num" {
        return if v.starts_with('[') && v.ends_with(']') {
            Ok(())
        } else {
            Err(ServiceError::BadValue(format!(
                "`{v}` is not a {}",
                s.data_type
            )))
        };
    }
    let inner = v.trim().trim_start_matches('[').trim_end_matches(']');
    let n: Result<Vec<f64>, _> = inner.split(',').map(|t| t.trim().parse::<f64>()).collect();
    match n {
        Ok(n) if s.dims.is_empty() && n.len() == 1 && !v.contains('[') => Ok(()),
        Ok(n) if s.dims.first() == Some(&(n.len() as u32)) && v.contains('[') => Ok(()),
        _ => Err(ServiceError::BadValue(format!(
            "`{v}` does not fit {} {}",
            s.data_type, s.path.name
        ))),
    }
}

fn set_exec(st: &mut FakeState, ep: &ServiceEndpoint, exec: ExecState) {
    st.exec = exec;
    ep.publish(Event::Execution {
        state: exec,
        cycle: st.cycle,
    });
    if let Some(t) = st.tasks.first_mut() {
        t.exec_state = if exec == ExecState::Running {
            TaskExecState::Started
        } else {
            TaskExecState::Stopped
        };
        ep.publish(Event::Task(t.clone()));
    }
}

fn run(
    mut ep: ServiceEndpoint,
    mut st: FakeState,
    stop: Arc<AtomicBool>,
    injected: mpsc::Receiver<Inject>,
) {
    while !stop.load(Ordering::SeqCst) {
        while let Ok(i) = injected.try_recv() {
            match i {
                Inject::Signal(name, value) => {
                    if let Some(s) = st.signals.iter_mut().find(|s| s.name == name) {
                        s.value = value;
                    }
                    ep.publish(Event::Signal { name, value });
                }
                Inject::Flood(n) => {
                    for k in 0..n {
                        ep.publish(Event::Signal {
                            name: "DO1".into(),
                            value: (k % 2) as f64,
                        });
                    }
                }
            }
        }
        let Some(req) = ep.try_next() else {
            std::thread::sleep(Duration::from_millis(1));
            continue;
        };
        answer(&mut st, &ep, req);
    }
}

fn answer(st: &mut FakeState, ep: &ServiceEndpoint, req: Request) {
    match req {
        Request::Execution(r) => {
            let _ = r.send(Ok((st.exec, st.cycle)));
        }
        Request::Start { cycle, reply } => {
            if st.ctrl != CtrlState::MotorsOn {
                let _ = reply.send(Err(ServiceError::NotAllowed("motors are off".into())));
                return;
            }
            if cycle != CycleMode::AsIs {
                st.cycle = cycle;
            }
            set_exec(st, ep, ExecState::Running);
            log(
                st,
                ep,
                10150,
                "Program started",
                "Execution of task T_ROB1 has been started.",
            );
            let _ = reply.send(Ok(()));
        }
        Request::Stop(r) => {
            set_exec(st, ep, ExecState::Stopped);
            log(
                st,
                ep,
                10124,
                "Program stopped",
                "The task T_ROB1 has stopped.",
            );
            let _ = r.send(Ok(()));
        }
        Request::ResetPp(r) => {
            log(
                st,
                ep,
                10002,
                "Program pointer has been reset",
                "Task T_ROB1.",
            );
            let _ = r.send(Ok(()));
        }
        Request::CtrlState(r) => {
            let _ = r.send(Ok(st.ctrl));
        }
        Request::SetMotors { on, reply } => {
            st.ctrl = if on {
                CtrlState::MotorsOn
            } else {
                CtrlState::MotorsOff
            };
            ep.publish(Event::CtrlState(st.ctrl));
            let _ = reply.send(Ok(()));
        }
        Request::OpMode(r) => {
            let _ = r.send(Ok(st.opmode));
        }
        Request::SetOpMode { mode, reply } => {
            st.opmode = mode;
            ep.publish(Event::OpMode(mode));
            let _ = reply.send(Ok(()));
        }
        Request::SpeedRatio(r) => {
            let _ = r.send(Ok(st.speed));
        }
        Request::SetSpeedRatio { percent, reply } => {
            st.speed = percent;
            ep.publish(Event::SpeedRatio(percent));
            let _ = reply.send(Ok(()));
        }
        Request::Tasks(r) => {
            let _ = r.send(Ok(st.tasks.clone()));
        }
        Request::SetTaskActive {
            task,
            active,
            reply,
        } => {
            match st
                .tasks
                .iter_mut()
                .find(|t| t.name.eq_ignore_ascii_case(&task))
            {
                Some(t) => {
                    t.active = active;
                    let _ = reply.send(Ok(()));
                }
                None => {
                    let _ = reply.send(Err(ServiceError::NotFound(format!("task {task}"))));
                }
            }
        }
        Request::Modules { task, reply } => {
            let r = match task.to_ascii_uppercase().as_str() {
                "T_ROB1" => Ok(vec![
                    ModuleInfo {
                        name: "MainModule".into(),
                        system: false,
                    },
                    ModuleInfo {
                        name: "BASE".into(),
                        system: true,
                    },
                ]),
                "T_LOG" => Ok(vec![ModuleInfo {
                    name: "LogModule".into(),
                    system: false,
                }]),
                _ => Err(ServiceError::NotFound(format!("task {task}"))),
            };
            let _ = reply.send(r);
        }
        Request::Signals(r) => {
            let _ = r.send(Ok(st.signals.clone()));
        }
        Request::Signal { name, reply } => {
            let s = st
                .signals
                .iter()
                .find(|s| s.name.eq_ignore_ascii_case(&name))
                .cloned();
            let _ = reply.send(s.ok_or(ServiceError::NotFound(format!("signal {name}"))));
        }
        Request::SetSignal { name, value, reply } => {
            match st
                .signals
                .iter_mut()
                .find(|s| s.name.eq_ignore_ascii_case(&name))
            {
                Some(s) => {
                    s.value = value;
                    ep.publish(Event::Signal {
                        name: s.name.clone(),
                        value,
                    });
                    let _ = reply.send(Ok(()));
                }
                None => {
                    let _ = reply.send(Err(ServiceError::NotFound(format!("signal {name}"))));
                }
            }
        }
        Request::Symbol { path, reply } => {
            let s = find_symbol(st, &path).cloned();
            let _ = reply.send(s.ok_or(ServiceError::NotFound(format!("symbol {}", path.name))));
        }
        Request::SetSymbol { path, value, reply } => {
            let r = match find_symbol(st, &path) {
                None => Err(ServiceError::NotFound(format!("symbol {}", path.name))),
                Some(s) if s.class == SymbolClass::Const => Err(ServiceError::NotAllowed(format!(
                    "{} is a constant",
                    s.path.name
                ))),
                Some(s) => match check_value(s, &value) {
                    Ok(()) => {
                        s.value = value.clone();
                        if s.class == SymbolClass::Pers {
                            ep.publish(Event::Pers {
                                path: s.path.clone(),
                                value,
                            });
                        }
                        Ok(())
                    }
                    Err(e) => Err(e),
                },
            };
            let _ = reply.send(r);
        }
        Request::Symbols { task, class, reply } => {
            let list = st
                .symbols
                .iter()
                .filter(|s| s.path.task.eq_ignore_ascii_case(&task))
                .filter(|s| class.is_none_or(|c| c == s.class))
                .cloned()
                .collect();
            let _ = reply.send(Ok(list));
        }
        Request::Elog { domain, reply } => {
            let r = if domain == 0 {
                Ok(st.elog.clone())
            } else {
                Ok(Vec::new())
            };
            let _ = reply.send(r);
        }
        Request::ClearElog { reply, .. } => {
            st.elog.clear();
            let _ = reply.send(Ok(()));
        }
        Request::Robot(r) => {
            let _ = r.send(Ok(RobotState {
                time: 1.0,
                joints: [10.0, 20.0, 30.0, 40.0, 50.0, 60.0],
            }));
        }
        Request::RobTarget { reply, .. } => {
            let _ = reply.send(Ok(
                "[[500,0,600],[0.5,0.5,0.5,0.5],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]]"
                    .into(),
            ));
        }
        Request::System(r) => {
            let _ = r.send(Ok(SystemInfo {
                name: "rapidvc_test".into(),
                robotware_version: "6.08.01".into(),
                options: vec![
                    "689-1 Externally Guided Motion (EGM)".into(),
                    "616-1 PC Interface".into(),
                ],
                serial: "0-00000".into(),
            }));
        }
        Request::MechUnits(r) => {
            let _ = r.send(Ok(vec![MechUnitInfo {
                name: "ROB_1".into(),
                task: "T_ROB1".into(),
                axes: 6,
                tool: "tool0".into(),
                wobj: "wobj0".into(),
                payload: "load0".into(),
            }]));
        }
        Request::Cfg {
            domain,
            type_name,
            reply,
        } => {
            let r = match (
                domain.to_ascii_uppercase().as_str(),
                type_name.to_ascii_uppercase().as_str(),
            ) {
                ("MOC", "MECHANICAL_UNIT") => Ok(vec![CfgInstance {
                    name: "ROB_1".into(),
                    attributes: vec![("use_robot".into(), "ROB_1".into())],
                }]),
                ("SYS", "MECHANICAL_UNIT_GROUP") => Ok(vec![CfgInstance {
                    name: "rob1".into(),
                    attributes: vec![
                        ("Name".into(), "rob1".into()),
                        ("Robot".into(), "ROB_1".into()),
                    ],
                }]),
                ("MOC" | "SYS" | "EIO" | "SIO", _) => Ok(Vec::new()),
                _ => Err(ServiceError::NotFound(format!(
                    "configuration domain {domain}"
                ))),
            };
            let _ = reply.send(r);
        }
        Request::FileRoots(r) => {
            let _ = r.send(Ok(st.roots.clone()));
        }
        Request::DipcCreate { queue, reply, .. } => {
            let exists = st.queues.contains_key(&queue);
            st.queues.entry(queue).or_default();
            let _ = reply.send(Ok(!exists));
        }
        Request::DipcSend {
            target,
            message,
            reply,
        } => {
            if target.eq_ignore_ascii_case("T_ROB1") {
                // Canned "RAPID side": T_ROB1 answers every RMQ message with an acknowledgement
                // to the sender's queue.
                let ack = DipcMessage {
                    source: "T_ROB1".into(),
                    cmd: message.cmd,
                    userdef: message.userdef,
                    msgtype: 1,
                    data: format!("string;\"ack {}\"", message.data.replace('"', "")),
                };
                if let Some(q) = st.queues.get_mut(&message.source) {
                    q.push_back(ack.clone());
                    ep.publish(Event::Dipc {
                        queue: message.source.clone(),
                        message: ack,
                    });
                }
                let _ = reply.send(Ok(()));
            } else if let Some(q) = st.queues.get_mut(&target) {
                q.push_back(message.clone());
                ep.publish(Event::Dipc {
                    queue: target,
                    message,
                });
                let _ = reply.send(Ok(()));
            } else {
                let _ = reply.send(Err(ServiceError::NotFound(format!("queue {target}"))));
            }
        }
        Request::DipcRead { queue, reply } => {
            let r = match st.queues.get_mut(&queue) {
                Some(q) => Ok(q.pop_front()),
                None => Err(ServiceError::NotFound(format!("queue {queue}"))),
            };
            let _ = reply.send(r);
        }
    }
}
