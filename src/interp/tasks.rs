//! The interpreter's side of running among several RAPID tasks: task-global persistents
//! shared by name, and the points where a task hands the processor to the others.
//!
//! Every task has its own interpreter (its own program, data, program pointer, error
//! handlers and interrupts). Only one task runs at a time (the controller's scheduler passes
//! one baton), so sharing a `PERS` needs no locking of the interpreter's data: each task
//! keeps its copy in its own globals, writes its shared persistents to the common
//! [`SharedPers`] store when it hands the baton over, and reads them back when it gets the
//! baton again. Every task therefore sees every other task's writes made before the switch,
//! in the order the tasks ran, exactly as if there were one copy.
//!
//! A task hands the baton over when it waits ([`Host::wait_until`](super::Host::wait_until)
//! from any waiting instruction) and, to share the processor, every
//! [`TaskLink::slice`] statements ([`Host::yield_now`](super::Host::yield_now)).
//! `TASK PERS` data and everything else stay the task's own.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use super::value::Value;
use super::{HostError, Interp};
use crate::ir::{GlobalOrigin, Storage};

/// The task-global persistents of a system, by upper-case name.
#[derive(Debug, Default)]
pub struct SharedPers {
    values: Mutex<HashMap<String, Value>>,
}

impl SharedPers {
    /// An empty store.
    pub fn new() -> Arc<SharedPers> {
        Arc::new(SharedPers::default())
    }

    /// The current value of `name` (any case).
    pub fn get(&self, name: &str) -> Option<Value> {
        let map = self.values.lock().ok()?;
        map.get(&name.to_ascii_uppercase()).cloned()
    }

    /// Every shared persistent, sorted by name.
    pub fn snapshot(&self) -> Vec<(String, Value)> {
        let mut v: Vec<(String, Value)> = match self.values.lock() {
            Ok(m) => m.iter().map(|(k, v)| (k.clone(), v.clone())).collect(),
            Err(_) => Vec::new(),
        };
        v.sort_by(|a, b| a.0.cmp(&b.0));
        v
    }
}

/// A task's link to the other tasks (see the module docs).
#[derive(Debug)]
pub(crate) struct TaskLink {
    store: Arc<SharedPers>,
    /// (global index, upper-case name) of the task's shared persistents.
    slots: Vec<(usize, String)>,
    /// Statements between two hand-overs.
    pub slice: u64,
    /// The step count at which the next hand-over is due.
    pub next_switch: u64,
}

impl Interp {
    /// Run as one task of several: share the program's task-global persistents through
    /// `store` and hand the processor over every `slice` statements (at least 1). Call it
    /// after [`Interp::init`]: a persistent the store already holds (another task declared
    /// it first) takes the store's value; one it does not hold yet is added with this
    /// task's initial value.
    pub fn set_task_link(&mut self, store: Arc<SharedPers>, slice: u64) {
        let slots = self.shared_slots();
        self.join_store(&store, &slots);
        let slice = slice.max(1);
        self.task = Some(Box::new(TaskLink {
            store,
            slots,
            slice,
            next_switch: self.steps + slice,
        }));
        self.update_poll();
    }

    /// (global index, upper-case name) of the program's task-global persistents.
    fn shared_slots(&self) -> Vec<(usize, String)> {
        let prog = &self.prog;
        prog.globals
            .iter()
            .enumerate()
            .filter(|(_, g)| g.storage == Storage::Pers && !g.task)
            .filter(|(_, g)| match g.origin {
                GlobalOrigin::Module(m) => {
                    prog.modules.get(m.0 as usize).is_some_and(|m| !m.stdlib)
                }
                _ => false,
            })
            .map(|(i, g)| (i, g.name.to_ascii_uppercase()))
            .collect()
    }

    /// Share `slots` through `store`: one the store holds takes the store's value, one it
    /// does not hold yet is added with this task's value.
    fn join_store(&mut self, store: &SharedPers, slots: &[(usize, String)]) {
        if let Ok(mut map) = store.values.lock() {
            for (i, key) in slots {
                match map.get(key) {
                    Some(v) => {
                        if let Some(slot) = self.globals.get_mut(*i) {
                            *slot = v.clone();
                        }
                    }
                    None => {
                        if let Some(v) = self.globals.get(*i) {
                            map.insert(key.clone(), v.clone());
                        }
                    }
                }
            }
        }
    }

    /// After `Load` changed the program: the task-global persistents of the loaded modules
    /// are shared by name as those of the boot (one another task has keeps that task's
    /// value). A name another task holds with another shape of data is refused, as loading
    /// a system with it is (`Err`: the message).
    pub(crate) fn relink_shared(&mut self) -> Result<(), String> {
        let Some(link) = self.task.as_ref() else {
            return Ok(());
        };
        let store = Arc::clone(&link.store);
        let known: Vec<String> = link.slots.iter().map(|s| s.1.clone()).collect();
        let slots = self.shared_slots();
        let added: Vec<(usize, String)> = slots
            .iter()
            .filter(|s| !known.contains(&s.1))
            .cloned()
            .collect();
        for (i, key) in &added {
            if let (Some(shared), Some(own)) = (store.get(key), self.globals.get(*i))
                && !same_shape(&shared, own)
            {
                let name = self.prog.globals.get(*i).map_or(key.as_str(), |g| &g.name);
                return Err(format!(
                    "the persistent `{name}` of the loaded module is a task-global PERS of \
                     another type or size in another task (declare it alike, or TASK PERS)"
                ));
            }
        }
        self.join_store(&store, &added);
        if let Some(link) = self.task.as_mut() {
            link.slots = slots;
        }
        Ok(())
    }

    /// Write this task's shared persistents to the store (before handing the baton over).
    pub(crate) fn publish_shared(&mut self) {
        let Some(link) = &self.task else { return };
        let Ok(mut map) = link.store.values.lock() else {
            return;
        };
        for (i, key) in &link.slots {
            if let Some(v) = self.globals.get(*i) {
                map.insert(key.clone(), v.clone());
            }
        }
    }

    /// Read the shared persistents back from the store (after getting the baton back).
    pub(crate) fn fetch_shared(&mut self) {
        let Some(link) = &self.task else { return };
        let Ok(map) = link.store.values.lock() else {
            return;
        };
        for (i, key) in &link.slots {
            if let (Some(v), Some(slot)) = (map.get(key), self.globals.get_mut(*i)) {
                *slot = v.clone();
            }
        }
    }

    /// Wait in the host with the shared persistents handed over around it.
    pub(crate) fn host_wait_until(
        &mut self,
        deadline: crate::time::RobotTime,
    ) -> Result<crate::time::RobotTime, HostError> {
        if self.task.is_none() {
            return self.host.wait_until(deadline);
        }
        self.publish_shared();
        let r = self.host.wait_until(deadline);
        self.fetch_shared();
        if let Some(link) = self.task.as_mut() {
            link.next_switch = self.steps + link.slice;
        }
        r
    }

    /// The time slice is over: let the other tasks run (called from the per-statement slow
    /// path).
    pub(crate) fn task_slice_due(&mut self) -> Result<(), HostError> {
        let due = self
            .task
            .as_ref()
            .is_some_and(|l| self.steps >= l.next_switch);
        if !due {
            return Ok(());
        }
        self.publish_shared();
        let r = self.host.yield_now();
        self.fetch_shared();
        if let Some(link) = self.task.as_mut() {
            link.next_switch = self.steps + link.slice;
        }
        r
    }

    /// The step count at which the next hand-over is due (`u64::MAX` for a single task).
    pub(crate) fn next_task_switch(&self) -> u64 {
        self.task.as_ref().map_or(u64::MAX, |l| l.next_switch)
    }
}

/// True when `a` and `b` are values of the same shape (kind, record length, array sizes).
fn same_shape(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Record(x), Value::Record(y)) => {
            x.len() == y.len() && x.iter().zip(y.iter()).all(|(p, q)| same_shape(p, q))
        }
        (Value::Array(x), Value::Array(y)) => {
            x.dims == y.dims
                && x.rank == y.rank
                && x.data
                    .first()
                    .zip(y.data.first())
                    .is_none_or(|(p, q)| same_shape(p, q))
        }
        _ => std::mem::discriminant(a) == std::mem::discriminant(b),
    }
}
