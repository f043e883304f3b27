//! The service thread: owns the [`ServiceEndpoint`], answers what needs no interpreter, hands
//! the rest to the program side, and publishes signal changes (whoever made them: RAPID, a
//! service, EGM) by comparing the signal table's generations every few milliseconds.

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::mpsc::Sender;
use std::thread::JoinHandle;
use std::time::Duration;

use super::{MAX_QUEUE_MESSAGES, MAX_QUEUES, SystemState, TaskError};
use crate::controller::service::{
    CfgInstance, Event, Request, ServiceEndpoint, ServiceError, SignalInfo, SystemInfo,
};
use crate::signals::{SignalId, SignalTable};
use crate::system::cfg_data::CfgData;

/// What the controller says about itself, fixed at boot.
#[derive(Debug)]
pub struct ServeInfo {
    /// System name, version, options.
    pub system: SystemInfo,
    /// The configuration database as loaded.
    pub cfg: CfgData,
    /// Mass storage roots (`HOME`, `TEMP`, `RAMDISK`) on the host.
    pub roots: Vec<(String, PathBuf)>,
    /// The signals' table.
    pub signals: Arc<SignalTable>,
}

/// How often signal changes are looked for.
const SIGNAL_POLL: Duration = Duration::from_millis(5);

/// Start the service thread. It ends when the controller shuts down (`state`) or the program
/// side has gone (`forward` disconnected).
pub fn spawn_service_thread(
    mut endpoint: ServiceEndpoint,
    state: Arc<SystemState>,
    info: ServeInfo,
    forward: Sender<Request>,
) -> std::io::Result<JoinHandle<()>> {
    std::thread::Builder::new()
        .name("rapidvc-services".into())
        .spawn(move || {
            let ids: Vec<SignalId> = info.signals.iter().map(|(id, _)| id).collect();
            let mut seen: Vec<u64> = ids
                .iter()
                .map(|id| info.signals.generation(*id).unwrap_or(0))
                .collect();
            let mut total = info.signals.total_generation();
            let mut last_poll = std::time::Instant::now();
            while !state.shutting_down() {
                let mut idle = true;
                while let Some(req) = endpoint.try_next() {
                    idle = false;
                    if let Some(rest) = answer(&state, &info, &endpoint, req)
                        && let Err(e) = forward.send(rest)
                    {
                        e.0.refuse(ServiceError::Gone);
                        return;
                    }
                }
                if last_poll.elapsed() >= SIGNAL_POLL {
                    last_poll = std::time::Instant::now();
                    let now_total = info.signals.total_generation();
                    if now_total != total {
                        total = now_total;
                        for (k, id) in ids.iter().enumerate() {
                            let g = info.signals.generation(*id).unwrap_or(0);
                            if let Some(s) = seen.get_mut(k)
                                && *s != g
                            {
                                *s = g;
                                if let (Some(d), Some(v)) =
                                    (info.signals.def(*id), info.signals.value(*id))
                                {
                                    endpoint.publish(Event::Signal {
                                        name: d.name.clone(),
                                        value: v,
                                    });
                                }
                            }
                        }
                    }
                }
                if idle {
                    std::thread::sleep(Duration::from_millis(1));
                }
            }
            while let Some(req) = endpoint.try_next() {
                req.refuse(ServiceError::Gone);
            }
        })
}

fn send<T>(reply: crate::controller::service::Reply<T>, v: Result<T, ServiceError>) {
    let _ = reply.send(v);
}

/// The network of a device: its `EIO_DEVICE -Network`, else `Local` for the controller's own
/// signals (no device: `Local/DRV_1`).
fn signal_info(info: &ServeInfo, id: SignalId) -> Option<SignalInfo> {
    let d = info.signals.def(id)?;
    let (network, device) = match &d.device {
        Some(dev) => {
            let net = info
                .cfg
                .instances("EIO", "EIO_DEVICE")
                .find(|i| i.name().is_some_and(|n| n.eq_ignore_ascii_case(dev)))
                .and_then(|i| {
                    i.attrs
                        .iter()
                        .find(|(k, _)| k.eq_ignore_ascii_case("Network"))
                        .map(|(_, v)| cfg_text(v))
                })
                .unwrap_or_else(|| "Local".to_string());
            (net, dev.clone())
        }
        None => ("Local".to_string(), "DRV_1".to_string()),
    };
    Some(SignalInfo {
        name: d.name.clone(),
        kind: d.kind,
        value: info.signals.value(id)?,
        network,
        device,
    })
}

fn cfg_text(v: &crate::config::cfg::CfgValue) -> String {
    use crate::config::cfg::CfgValue;
    match v {
        // RWS writes a switch attribute as `true` (abb_librws compares with that).
        CfgValue::Flag => "true".into(),
        CfgValue::Str(s) | CfgValue::Word(s) => s.clone(),
        CfgValue::Num(n) => {
            if n.fract() == 0.0 && n.abs() < 1e15 {
                format!("{}", *n as i64)
            } else {
                format!("{n}")
            }
        }
    }
}

/// Answer `req` here, or give it back for the program side.
fn answer(
    state: &SystemState,
    info: &ServeInfo,
    endpoint: &ServiceEndpoint,
    req: Request,
) -> Option<Request> {
    fn not_allowed<T>(m: String) -> Result<T, ServiceError> {
        Err(ServiceError::NotAllowed(m))
    }
    match req {
        Request::Execution(r) => send(r, Ok(state.execution())),
        Request::Start { cycle, reply } => send(reply, state.start(cycle).or_else(not_allowed)),
        Request::Stop(r) => {
            state.stop("Stopped over Robot Web Services.");
            send(r, Ok(()));
        }
        Request::ResetPp(r) => send(r, state.reset_pp().or_else(not_allowed)),
        Request::CtrlState(r) => send(r, Ok(state.ctrl_state())),
        Request::SetMotors { on, reply } => {
            state.set_motors(on);
            send(reply, Ok(()));
        }
        Request::OpMode(r) => send(r, Ok(state.opmode())),
        Request::SetOpMode { mode, reply } => {
            state.set_opmode(mode);
            send(reply, Ok(()));
        }
        Request::SpeedRatio(r) => send(r, Ok(state.speed_ratio())),
        Request::SetSpeedRatio { percent, reply } => send(
            reply,
            state
                .set_speed_ratio(percent)
                .map_err(ServiceError::BadValue),
        ),
        Request::Tasks(r) => send(r, Ok(state.tasks())),
        Request::SetTaskActive {
            task,
            active,
            reply,
        } => send(
            reply,
            state.set_task_active(&task, active).map_err(|e| match e {
                TaskError::Unknown => ServiceError::NotFound(format!("task {task}")),
                TaskError::Running => ServiceError::NotAllowed(format!(
                    "task {task} cannot be (de)activated while the program runs"
                )),
            }),
        ),
        Request::Signals(r) => send(
            r,
            Ok(info
                .signals
                .iter()
                .filter_map(|(id, _)| signal_info(info, id))
                .collect()),
        ),
        Request::Signal { name, reply } => send(
            reply,
            info.signals
                .lookup(&name)
                .and_then(|id| signal_info(info, id))
                .ok_or_else(|| ServiceError::NotFound(format!("signal {name}"))),
        ),
        Request::SetSignal { name, value, reply } => {
            let r = match info.signals.lookup(&name) {
                None => Err(ServiceError::NotFound(format!("signal {name}"))),
                Some(id) => info
                    .signals
                    .set(id, value)
                    .map(|_| ())
                    .map_err(|e| ServiceError::BadValue(e.to_string())),
            };
            send(reply, r);
        }
        Request::Elog { domain, reply } => send(
            reply,
            Ok(if domain == 0 {
                state.elog()
            } else {
                Vec::new()
            }),
        ),
        Request::ClearElog { domain, reply } => {
            if domain == 0 {
                state.lock().elog.clear();
            }
            send(reply, Ok(()));
        }
        Request::Robot(r) => send(r, Ok(state.robot())),
        Request::System(r) => send(r, Ok(info.system.clone())),
        Request::Cfg {
            domain,
            type_name,
            reply,
        } => {
            let known = ["MOC", "SYS", "EIO", "SIO"]
                .iter()
                .any(|d| d.eq_ignore_ascii_case(&domain));
            let r = if known {
                Ok(info
                    .cfg
                    .instances(&domain, &type_name)
                    .map(|i| CfgInstance {
                        name: i.name().unwrap_or("").to_string(),
                        attributes: i
                            .attrs
                            .iter()
                            .map(|(k, v)| (k.clone(), cfg_text(v)))
                            .collect(),
                    })
                    .collect())
            } else {
                Err(ServiceError::NotFound(format!(
                    "configuration domain {domain}"
                )))
            };
            send(reply, r);
        }
        Request::FileRoots(r) => send(r, Ok(info.roots.clone())),
        Request::DipcCreate { queue, reply, .. } => {
            let mut g = state.lock();
            let r = if g.queues.contains_key(&queue) {
                Ok(false)
            } else if g.queues.len() >= MAX_QUEUES {
                not_allowed(format!("at most {MAX_QUEUES} external queues"))
            } else {
                g.queues.insert(queue, Default::default());
                Ok(true)
            };
            drop(g);
            send(reply, r);
        }
        Request::DipcSend {
            target,
            message,
            reply,
        } => {
            let to_task = state.deliver_to_task(&target, &message);
            let r = if let Some(r) = to_task {
                r.or_else(not_allowed)
            } else {
                let mut g = state.lock();
                match g.queues.get_mut(&target) {
                    None => Err(ServiceError::NotFound(format!("queue {target}"))),
                    Some(q) if q.len() >= MAX_QUEUE_MESSAGES => {
                        not_allowed(format!("queue {target} is full"))
                    }
                    Some(q) => {
                        q.push_back(message.clone());
                        drop(g);
                        endpoint.publish(Event::Dipc {
                            queue: target,
                            message,
                        });
                        Ok(())
                    }
                }
            };
            send(reply, r);
        }
        Request::DipcRead { queue, reply } => {
            let r = match state.lock().queues.get_mut(&queue) {
                Some(q) => Ok(q.pop_front()),
                None => Err(ServiceError::NotFound(format!("queue {queue}"))),
            };
            send(reply, r);
        }
        other @ (Request::Modules { .. }
        | Request::Symbol { .. }
        | Request::SetSymbol { .. }
        | Request::Symbols { .. }
        | Request::RobTarget { .. }
        | Request::MechUnits(_)) => return Some(other),
    }
    None
}
