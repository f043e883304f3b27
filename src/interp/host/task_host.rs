//! The capability of a host that runs among several RAPID tasks ([`super::Host::tasks`]):
//! what the inter-task instructions need (`GetTaskName`, `WaitSyncTask`, `TaskRunMec`,
//! `TaskRunRob`, the RAPID message queue). The controller's task scheduler implements it
//! (`controller::tasks`); a host of a single-task run has none, and the natives then answer
//! as for one motion task (`GetTaskName` is `T_ROB1`, number 1) or report what they need.

use super::HostError;

/// One RAPID message: what `RMQSendMessage` sends and `RMQGetMessage` takes.
#[derive(Clone, Debug, PartialEq)]
pub struct RmqMessage {
    /// The data's type name (`num`, `robtarget`, a record's name).
    pub datatype: String,
    /// Array sizes (empty for a scalar; at most three).
    pub dims: Vec<u32>,
    /// The data as RAPID literal text (how the message travels and is measured).
    pub data: String,
    /// The sending task's number.
    pub sender: i32,
    /// `\UserDef` (-1 when not given).
    pub userdef: i32,
    /// The queue's running number of the message (set by the receiving queue; tells
    /// `IRMQMessage` a new message from one already interrupted for).
    pub seq: u64,
}

/// What the inter-task instructions ask of the controller.
pub trait TaskHost {
    /// The running task's name.
    fn task_name(&self) -> String;

    /// The running task's number (1-based, SYS.cfg order).
    fn task_number(&self) -> i32;

    /// The number of the motion task whose robot this task moves (`GetTaskName(\MecTaskNo)`):
    /// its own number for the motion task, else the motion task's.
    fn mec_task_number(&self) -> i32;

    /// This task moves the robot (it is the motion task).
    fn is_motion_task(&self) -> bool;

    /// Arrive at the synchronisation point `ident` of the tasks `tasks` (names as written);
    /// returns a ticket for [`TaskHost::sync_passed`]. An error when a name is not a task,
    /// or this task is not in the list.
    fn sync_arrive(&mut self, ident: &str, tasks: &[String]) -> Result<u64, HostError>;

    /// True once every task of the synchronisation point has arrived (since the arrival that
    /// gave `ticket`).
    fn sync_passed(&mut self, ident: &str, ticket: u64) -> bool;

    /// Leave a synchronisation point without passing it (a time-out).
    fn sync_leave(&mut self, ident: &str, ticket: u64);

    /// The slot number of the task (or RMQ client) called `name` (`RMQFindSlot`).
    fn rmq_find_slot(&self, name: &str) -> Option<i32>;

    /// The name behind a slot number (`RMQGetSlotName`).
    fn rmq_slot_name(&self, slot: i32) -> Option<String>;

    /// Put `msg` in the queue of `slot`. Errors carry `ERR_RMQ_*` numbers (no such slot,
    /// queue full, message too large for the receiver).
    fn rmq_send(&mut self, slot: i32, msg: RmqMessage) -> Result<(), HostError>;

    /// Take the oldest message from this task's queue.
    fn rmq_take(&mut self) -> Option<RmqMessage>;

    /// The oldest message in this task's queue, left there.
    fn rmq_peek(&self) -> Option<RmqMessage>;

    /// Empty this task's queue (`RMQEmptyQueue`).
    fn rmq_empty(&mut self);
}
