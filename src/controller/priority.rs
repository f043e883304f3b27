//! Opt-in real-time scheduling for the motion thread (SCHED_FIFO through the
//! `thread-priority` crate, so this crate needs no `unsafe`).

use thread_priority::{
    RealtimeThreadSchedulePolicy, ThreadPriority, ThreadPriorityValue, ThreadSchedulePolicy,
    set_thread_priority_and_policy, thread_native_id,
};

/// Whether the real-time thread must run with real-time priority.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RealtimeConfig {
    /// Switch the motion thread to SCHED_FIFO; fail to start if that is not permitted.
    Enforce,
    /// Leave the thread's scheduling alone (no special permissions needed).
    #[default]
    Ignore,
}

/// The SCHED_FIFO priority of the motion thread (1…99 on Linux). High, but below the kernel's
/// own threaded interrupt handlers (50 is their default, so 80 preempts them; timers need
/// them only for wakeups, which the hrtimer delivers in interrupt context).
pub const MOTION_THREAD_PRIORITY: u8 = 80;

/// Switch the calling thread to SCHED_FIFO at [`MOTION_THREAD_PRIORITY`].
pub fn make_current_thread_realtime() -> Result<(), String> {
    let value = ThreadPriorityValue::try_from(MOTION_THREAD_PRIORITY)
        .map_err(|e| format!("priority {MOTION_THREAD_PRIORITY}: {e}"))?;
    set_thread_priority_and_policy(
        thread_native_id(),
        ThreadPriority::Crossplatform(value),
        ThreadSchedulePolicy::Realtime(RealtimeThreadSchedulePolicy::Fifo),
    )
    .map_err(|e| {
        format!(
            "cannot switch the motion thread to SCHED_FIFO priority {MOTION_THREAD_PRIORITY} ({e:?}); run as root or grant CAP_SYS_NICE, or run without real-time priority"
        )
    })
}
