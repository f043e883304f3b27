//! Interrupts: CONNECT, timer and signal orders, the pending queue, and running TRAPs
//! between statements and during waits.

use std::collections::{HashMap, HashSet, VecDeque};
use std::time::Duration;

use super::Interp;
use super::errnum;
use super::error::{Exec, Unwind};
use super::value::Value;
use crate::ir::{Place, Program, RoutineId};
use crate::source::Span;
use crate::time::{RobotTime, secs};

/// A condition a wait polls.
pub(crate) type WaitCond<'a> = dyn FnMut(&mut Interp, &Program) -> Exec<bool> + 'a;

/// Most interrupt numbers in use at once.
pub(crate) const MAX_INTERRUPTS: usize = 100;
/// Most interrupts waiting to run.
const MAX_PENDING: usize = 30;

/// A timer order (`ITimer`).
#[derive(Debug, Clone)]
pub(crate) struct Timer {
    pub intno: i32,
    pub period: Duration,
    pub next: RobotTime,
    pub single: bool,
}

/// What a signal order waits for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Trigger {
    /// Digital: 1 = rising edge, 0 = falling edge, 2 = both.
    Edge(u8),
    /// Analog: `aiotrigg` condition with high/low limits, the least change from the
    /// stored reference value (`DeltaValue`) and its direction (1 `\DPos`, -1 `\DNeg`, 0
    /// either).
    Analog {
        cond: u8,
        high: f64,
        low: f64,
        delta: f64,
        dir: i8,
    },
    /// Group: any change of the value.
    Change,
}

/// A signal order (`ISignalDI`, `ISignalDO`, `ISignalAO`).
#[derive(Debug, Clone)]
pub(crate) struct Watch {
    pub intno: i32,
    pub signal: String,
    pub trigger: Trigger,
    pub last: f64,
    /// Analog: the reference value (at the order, then at each change beyond the delta
    /// within the condition).
    pub reference: f64,
    pub single: bool,
}

/// An `IPers` order: the persistent and its value at the last check.
#[derive(Debug, Clone)]
pub(crate) struct PersWatch {
    pub intno: i32,
    pub place: super::place::AbsPlace,
    pub last: Value,
}

/// An event-log entry as `IError` traps see it (`GetTrapData`, `ReadErrData`).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct LogEvent {
    /// `errdomain` (event number / 10000).
    pub domain: i32,
    /// The number within the domain.
    pub number: i32,
    /// `errtype`: 1 state, 2 warning, 3 error.
    pub etype: i32,
    pub title: String,
    pub strs: Vec<String>,
}

/// An `IError` order.
#[derive(Debug, Clone)]
pub(crate) struct ErrorOrder {
    pub intno: i32,
    /// 0 (`COMMON_ERR`) = every domain.
    pub domain: i32,
    pub number: Option<i32>,
    /// 0 (`TYPE_ALL`) = every type.
    pub etype: i32,
}

/// Interrupt state of a task.
#[derive(Debug, Default)]
pub(crate) struct Interrupts {
    next_no: i32,
    connected: HashMap<i32, RoutineId>,
    pub timers: Vec<Timer>,
    pub watches: Vec<Watch>,
    pub pers_watches: Vec<PersWatch>,
    pub error_orders: Vec<ErrorOrder>,
    /// `IRMQMessage` orders: (interrupt number, data type name).
    pub rmq_orders: Vec<(i32, String)>,
    /// The queue number of the last RAPID message an `IRMQMessage` interrupted for.
    rmq_seen: u64,
    /// Events behind queued `IError` interrupts, in arrival order.
    events: VecDeque<(i32, LogEvent)>,
    /// The event of the running `IError` trap (`GetTrapData`).
    pub trap_event: Option<LogEvent>,
    pending: VecDeque<i32>,
    /// IDisable in effect.
    pub disabled: bool,
    /// ISleep'd interrupt numbers.
    pub asleep: HashSet<i32>,
    in_trap: bool,
    /// Signal writes due later (`\SDelay`, the end of a `PulseDO`): (time, signal, value).
    delayed: Vec<(RobotTime, String, f64)>,
    /// Moves with position events for the program (`TriggInt`, `MoveLSync`) are queued:
    /// ask the host for fired ones at every check.
    pub position: bool,
    /// `MoveLSync` procedures whose position event fired, to run at the next check.
    sync_calls: VecDeque<String>,
}

impl Interrupts {
    /// A connected TRAP for which `keep` is false (the program is about to lose it).
    pub fn traps_not_in(&self, keep: impl Fn(RoutineId) -> bool) -> Option<RoutineId> {
        self.connected.values().copied().find(|&r| !keep(r))
    }

    /// Renumber the connected TRAPs (the program was relinked).
    pub fn remap_traps(&mut self, f: impl Fn(RoutineId) -> RoutineId) {
        self.connected.values_mut().for_each(|r| *r = f(*r));
    }

    /// Is a TRAP routine running (`ExecLevel`)?
    pub fn in_trap(&self) -> bool {
        self.in_trap
    }

    /// Anything that needs checking between statements?
    pub fn armed(&self) -> bool {
        !self.timers.is_empty()
            || !self.watches.is_empty()
            || !self.pers_watches.is_empty()
            || !self.rmq_orders.is_empty()
            || !self.pending.is_empty()
            || !self.delayed.is_empty()
            || self.position
            || !self.sync_calls.is_empty()
    }

    /// Is this interrupt number connected?
    pub fn is_connected(&self, no: i32) -> bool {
        self.connected.contains_key(&no)
    }

    /// Earliest timer deadline.
    pub fn next_timer(&self) -> Option<RobotTime> {
        self.timers
            .iter()
            .map(|t| t.next)
            .chain(self.delayed.iter().map(|d| d.0))
            .min()
    }

    /// Remove an interrupt number and all its orders.
    pub fn delete(&mut self, no: i32) -> bool {
        self.timers.retain(|t| t.intno != no);
        self.watches.retain(|w| w.intno != no);
        self.pers_watches.retain(|w| w.intno != no);
        self.error_orders.retain(|w| w.intno != no);
        self.rmq_orders.retain(|w| w.0 != no);
        self.events.retain(|e| e.0 != no);
        self.pending.retain(|&n| n != no);
        self.asleep.remove(&no);
        self.connected.remove(&no).is_some()
    }

    fn queue(&mut self, no: i32) -> bool {
        if self.asleep.contains(&no) {
            return true;
        }
        if self.pending.len() >= MAX_PENDING {
            return false;
        }
        self.pending.push_back(no);
        true
    }
}

/// Does an analog value satisfy an `aiotrigg` condition?
fn analog_hit(cond: u8, high: f64, low: f64, v: f64) -> bool {
    match cond {
        1 => v > high,              // AIO_ABOVE_HIGH
        2 => v < high,              // AIO_BELOW_HIGH
        3 => v > low,               // AIO_ABOVE_LOW
        4 => v < low,               // AIO_BELOW_LOW
        5 => v >= low && v <= high, // AIO_BETWEEN
        6 => v < low || v > high,   // AIO_OUTSIDE
        _ => true,                  // AIO_ALWAYS
    }
}

impl Interp {
    /// `CONNECT place WITH trap`.
    pub(crate) fn connect(
        &mut self,
        p: &Program,
        place: &Place,
        trap: RoutineId,
        span: Span,
    ) -> Exec<()> {
        let cur = self.load(p, place)?.as_num().unwrap_or(0.0) as i32;
        if cur != 0 && self.ints.is_connected(cur) {
            return Err(self.error(
                errnum::ERR_ALRDYCNT,
                span,
                format!("the interrupt variable is already connected (interrupt {cur})"),
            ));
        }
        if self.ints.connected.len() >= MAX_INTERRUPTS {
            return Err(self.error(
                errnum::ERR_INOMAX,
                span,
                format!("more than {MAX_INTERRUPTS} interrupts connected"),
            ));
        }
        self.ints.next_no += 1;
        let no = self.ints.next_no;
        self.ints.connected.insert(no, trap);
        self.store(p, place, Value::Num(no as f32))
    }

    /// Check an interrupt number given to an I-instruction.
    pub(crate) fn check_intno(&self, no: i32, span: Span) -> Exec<()> {
        if self.ints.is_connected(no) {
            Ok(())
        } else {
            Err(self.error(
                errnum::ERR_UNKINO,
                span,
                format!("interrupt {no} is not connected (use CONNECT first)"),
            ))
        }
    }

    /// Order a timer interrupt.
    pub(crate) fn order_timer(
        &mut self,
        no: i32,
        period: f64,
        single: bool,
        span: Span,
    ) -> Exec<()> {
        self.check_intno(no, span)?;
        let now = self.host.now();
        let period = secs(period);
        self.ints.timers.retain(|t| t.intno != no);
        self.ints.timers.push(Timer {
            intno: no,
            period,
            next: now.saturating_add(period),
            single,
        });
        self.update_poll();
        Ok(())
    }

    /// Order a signal interrupt.
    pub(crate) fn order_watch(
        &mut self,
        no: i32,
        signal: &str,
        trigger: Trigger,
        single: bool,
        span: Span,
    ) -> Exec<()> {
        self.check_intno(no, span)?;
        let last = self
            .host
            .read_signal(signal)
            .map_err(|e| self.host_error(e, span))?;
        self.ints.watches.retain(|w| w.intno != no);
        self.ints.watches.push(Watch {
            intno: no,
            signal: signal.to_string(),
            trigger,
            last,
            reference: last,
            single,
        });
        self.update_poll();
        Ok(())
    }

    /// Order an interrupt on every change of a persistent (`IPers`).
    pub(crate) fn order_pers(
        &mut self,
        no: i32,
        place: super::place::AbsPlace,
        span: Span,
    ) -> Exec<()> {
        self.check_intno(no, span)?;
        let last = self
            .abs_get(&place)
            .map_err(|e| self.walk_err(e, span))?
            .clone();
        self.ints.watches.retain(|w| w.intno != no);
        self.ints.pers_watches.retain(|w| w.intno != no);
        self.ints.pers_watches.push(PersWatch {
            intno: no,
            place,
            last,
        });
        self.update_poll();
        Ok(())
    }

    /// Order an interrupt on event-log entries (`IError`).
    /// `IRMQMessage`: interrupt `no` when a RAPID message of `datatype` arrives.
    pub(crate) fn order_rmq(&mut self, no: i32, datatype: String, span: Span) -> Exec<()> {
        self.check_intno(no, span)?;
        self.ints.rmq_orders.retain(|o| o.0 != no);
        self.ints.rmq_orders.push((no, datatype));
        self.update_poll();
        Ok(())
    }

    pub(crate) fn order_error(&mut self, order: ErrorOrder, span: Span) -> Exec<()> {
        self.check_intno(order.intno, span)?;
        self.ints.error_orders.retain(|o| o.intno != order.intno);
        self.ints.error_orders.push(order);
        Ok(())
    }

    /// An entry of the event log: queues the `IError` interrupts it matches (they run at
    /// the next check, between statements or during a wait).
    pub(crate) fn log_event(&mut self, ev: LogEvent) {
        let hits: Vec<i32> = self
            .ints
            .error_orders
            .iter()
            .filter(|o| {
                (o.domain == 0 || o.domain == ev.domain)
                    && (o.etype == 0 || o.etype == ev.etype)
                    && o.number.is_none_or(|n| n == ev.number)
            })
            .map(|o| o.intno)
            .collect();
        for no in hits {
            if self.ints.asleep.contains(&no) {
                continue;
            }
            if self.ints.queue(no) {
                self.ints.events.push_back((no, ev.clone()));
            } else {
                self.host.output(super::Output::Event(format!(
                    "interrupt queue full: interrupt {no} was lost"
                )));
            }
        }
        self.update_poll();
    }

    /// Delete an interrupt (`IDelete`).
    pub(crate) fn delete_interrupt(&mut self, no: i32) {
        self.ints.delete(no);
        self.update_poll();
    }

    /// Write a signal at a later (host) time.
    pub(crate) fn schedule_write(&mut self, at: RobotTime, signal: String, value: f64) {
        self.ints.delayed.push((at, signal, value));
        self.update_poll();
    }

    /// Move due timers and signal changes into the queue, then run queued traps (unless
    /// disabled or already in a trap).
    pub(crate) fn service_interrupts(&mut self, p: &Program, span: Span) -> Exec<()> {
        let now = self.host.now();
        if !self.ints.delayed.is_empty() {
            let mut due: Vec<(RobotTime, String, f64)> = Vec::new();
            self.ints.delayed.retain(|d| {
                if d.0 <= now {
                    due.push(d.clone());
                    false
                } else {
                    true
                }
            });
            due.sort_by_key(|d| d.0);
            for (_, sig, v) in due {
                self.host
                    .write_signal(&sig, v)
                    .map_err(|e| self.host_error(e, span))?;
            }
        }
        let mut fired: Vec<i32> = Vec::new();
        if self.ints.position {
            let taken = self
                .host
                .position_events()
                .map(|h| (h.take_program_events(), h.program_events_pending()));
            let (actions, pending) = taken.unwrap_or_default();
            self.ints.position = pending;
            for a in actions {
                match a {
                    super::host::ProgramAction::Interrupt(no) => fired.push(no),
                    super::host::ProgramAction::Call(name) => self.ints.sync_calls.push_back(name),
                }
            }
        }
        self.ints.timers.retain_mut(|t| {
            if t.next <= now {
                fired.push(t.intno);
                if t.single {
                    return false;
                }
                t.next = t.next.saturating_add(t.period);
                if t.next <= now {
                    t.next = now.saturating_add(t.period);
                }
            }
            true
        });
        if !self.ints.watches.is_empty() {
            let mut watches = std::mem::take(&mut self.ints.watches);
            let mut err = None;
            watches.retain_mut(|w| {
                let v = match self.host.read_signal(&w.signal) {
                    Ok(v) => v,
                    Err(e) => {
                        err = Some(e);
                        return true;
                    }
                };
                let hit = match w.trigger {
                    Trigger::Edge(t) => {
                        let rising = w.last < 0.5 && v >= 0.5;
                        let falling = w.last >= 0.5 && v < 0.5;
                        match t {
                            1 => rising,
                            0 => falling,
                            _ => rising || falling,
                        }
                    }
                    Trigger::Analog {
                        cond,
                        high,
                        low,
                        delta,
                        dir,
                    } => {
                        // A new reference value is stored whenever the signal is within the
                        // condition and differs from the reference by more than the delta;
                        // it interrupts when that difference has the ordered direction.
                        let d = v - w.reference;
                        if analog_hit(cond, high, low, v) && d.abs() > delta {
                            w.reference = v;
                            match dir {
                                1 => d > 0.0,
                                -1 => d < 0.0,
                                _ => true,
                            }
                        } else {
                            false
                        }
                    }
                    Trigger::Change => v != w.last,
                };
                w.last = v;
                if hit {
                    fired.push(w.intno);
                    return !w.single;
                }
                true
            });
            self.ints.watches = watches;
            if let Some(e) = err {
                return Err(self.host_error(e, span));
            }
        }
        if !self.ints.pers_watches.is_empty() {
            let mut watches = std::mem::take(&mut self.ints.pers_watches);
            for w in watches.iter_mut() {
                if let Ok(v) = self.abs_get(&w.place)
                    && !super::value::values_equal(v, &w.last)
                {
                    w.last = v.clone();
                    fired.push(w.intno);
                }
            }
            self.ints.pers_watches = watches;
        }
        if !self.ints.rmq_orders.is_empty()
            && let Some(m) = self.host.tasks().and_then(|t| t.rmq_peek())
            && m.seq > self.ints.rmq_seen
        {
            self.ints.rmq_seen = m.seq;
            if let Some((no, _)) = self
                .ints
                .rmq_orders
                .iter()
                .find(|(_, ty)| ty.eq_ignore_ascii_case(&m.datatype))
            {
                fired.push(*no);
            }
        }
        for no in fired {
            if !self.ints.queue(no) {
                self.host.output(super::Output::Event(format!(
                    "interrupt queue full: interrupt {no} was lost"
                )));
            }
        }
        if !self.ints.in_trap {
            while let Some(name) = self.ints.sync_calls.pop_front() {
                self.run_sync_call(p, &name, span)?;
            }
        }
        if !self.ints.in_trap && !self.ints.disabled {
            while let Some(no) = self.ints.pending.pop_front() {
                if let Some(&trap) = self.ints.connected.get(&no) {
                    self.run_trap(p, trap, no, span)?;
                }
            }
        }
        self.update_poll();
        Ok(())
    }

    /// Run the procedure of a `MoveLSync` whose position event fired, as a trap routine runs
    /// (the program's execution level is kept).
    fn run_sync_call(&mut self, p: &Program, name: &str, span: Span) -> Exec<()> {
        let Some(rid) = p.find_proc(name).filter(|&r| {
            let r = p.routine(r);
            r.kind == crate::ir::RoutineKind::Proc && r.params.is_empty()
        }) else {
            return Err(self.error(
                errnum::ERR_REFUNKPRC,
                span,
                format!("there is no procedure `{name}` without parameters to call at the position event"),
            ));
        };
        self.ints.in_trap = true;
        let res = self.call_routine(p, rid, &[], span);
        self.ints.in_trap = false;
        match res {
            Ok(_) => Ok(()),
            Err(Unwind::Error(e) | Unwind::Propagate(e)) => Err(Unwind::Fatal(e)),
            Err(other) => Err(other),
        }
    }

    fn run_trap(&mut self, p: &Program, trap: RoutineId, no: i32, span: Span) -> Exec<()> {
        self.ints.in_trap = true;
        let saved = self.intno;
        self.intno = no;
        self.ints.trap_event = self
            .ints
            .events
            .iter()
            .position(|e| e.0 == no)
            .and_then(|i| self.ints.events.remove(i))
            .map(|e| e.1);
        let res = self.call_routine(p, trap, &[], span);
        self.intno = saved;
        self.ints.trap_event = None;
        self.ints.in_trap = false;
        match res {
            Ok(_) => Ok(()),
            // An error that leaves a TRAP stops execution.
            Err(Unwind::Error(e) | Unwind::Propagate(e)) => Err(Unwind::Fatal(e)),
            Err(other) => Err(other),
        }
    }

    /// Wait until `deadline` or until `cond` holds (polled every `poll` seconds), running
    /// traps as interrupts arrive. Returns true when `cond` held.
    pub(crate) fn wait(
        &mut self,
        p: &Program,
        span: Span,
        deadline: Option<RobotTime>,
        mut cond: Option<&mut WaitCond<'_>>,
        poll: f64,
    ) -> Exec<bool> {
        if let Some(f) = self.frames.last_mut() {
            f.at = span;
        }
        loop {
            if self.stop_requested() {
                return Err(Unwind::Stop);
            }
            if let Some(c) = cond.as_mut()
                && c(self, p)?
            {
                return Ok(true);
            }
            let now = self.host.now();
            if let Some(d) = deadline
                && now >= d
            {
                self.service_interrupts(p, span)?;
                return Ok(false);
            }
            let mut wake = deadline;
            if cond.is_some() {
                wake = Some(wake.map_or(now.after_secs(poll), |w| w.min(now.after_secs(poll))));
            }
            if let Some(t) = self.ints.next_timer() {
                let t = t.max(now);
                wake = Some(wake.map_or(t, |w| w.min(t)));
            }
            let Some(wake) = wake else {
                return Err(self.fatal(super::ErrorKind::Host, span, "this wait can never end"));
            };
            self.host_wait_until(wake)
                .map_err(|e| self.host_error(e, span))?;
            self.service_interrupts(p, span)?;
        }
    }
}
