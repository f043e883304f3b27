//! Steps 3–4 of a tick: servo events, the `EgmRobot` feedback (measured, planned, Cartesian per mode, states) and its transmission and log row.

use super::*;

impl EgmDriver {
    pub(super) fn report_servo(&mut self, out: &ServoOutput) {
        let params = self.servo.params();
        if out.speed_limit_began {
            self.events.push(speed_limit_event(params, out));
        }
        if out.clamp_began {
            self.events.push(pos_clamp_event(params, out));
        }
        if out.limit_began {
            self.events.push(axis_limit_event(params, out));
        }
    }

    /// Step 4: the `EgmRobot` when due. Returns whether one went out.
    pub(super) fn transmit(&mut self, now: RobotTime, out: &ServoOutput) -> bool {
        let feedback = self.robot_feedback(now, out);
        let row = self.row(now, 0, out);
        let Link::Session {
            session, peer, buf, ..
        } = &mut self.link
        else {
            return false;
        };
        if !session.poll_transmit_into(now, &feedback, buf) {
            forward_events(session, &mut self.events);
            return false;
        }
        let seqno = session.next_seqno().wrapping_sub(1);
        if let Some(e) = peer.send(now, buf, session) {
            self.events.push(e);
        }
        forward_events(session, &mut self.events);
        self.awaiting = peer.is_external();
        if let Some(done) = self.pending.take() {
            self.log.push(done);
        }
        self.pending = Some(LogRow { seqno, ..row });
        true
    }

    /// The feedback of this tick.
    pub(super) fn robot_feedback(&self, now: RobotTime, out: &ServoOutput) -> RobotFeedback {
        let rapid_to_sensor = self.do_to_sensor.and_then(|id| {
            self.signals
                .value(id)
                .map(|v| RapidData::new(Some(v != 0.0), &[]))
        });
        RobotFeedback {
            joints: out.feedback,
            external: ExternalAxes::NONE,
            pose: self.fb_pose,
            time: now,
            planned_joints: out.commanded,
            planned_external: ExternalAxes::NONE,
            planned_pose: self.planned_pose,
            planned_time: now.saturating_add(self.servo_delay),
            motor_state: self.motors,
            exec_state: self.exec,
            mci_state: self.mci,
            convergence_met: out.convergence_met,
            utilization: out.utilization,
            move_index: None,
            rapid_to_sensor,
        }
    }

    /// A log row for this tick without reply data.
    pub(super) fn row(&self, now: RobotTime, seqno: u32, out: &ServoOutput) -> LogRow {
        let (kind, feedback) = match self.mode {
            EgmMode::Pose => (LogKind::Pose, pose6(&self.fb_pose)),
            _ => (LogKind::Joint, out.feedback),
        };
        LogRow {
            kind,
            send_time: now,
            recv_time: None,
            seqno,
            reference: None,
            feedback,
            state: phase_name(out.phase),
            utilization: out.utilization,
        }
    }

    /// `feedBack.cartesian` / `planned.cartesian` at `q`.
    pub(super) fn cartesian(&self, q: &Joints) -> Option<WirePose> {
        let r = match &self.guidance {
            Some(g) => g.feedback_cartesian(q, FeedbackMode::Pose),
            None => feedback_in_wobj(&self.robot, q, &self.tool, &self.wobj),
        };
        r.ok().map(|(pos, orient)| WirePose { pos, orient })
    }
}

/// The feedback of a position stream or a path-correction link at `now`: the measured
/// (servo-delayed) and the commanded joints, with the TCP of the tool relative to the work
/// object for each (identity where it cannot be computed); no convergence, no utilization.
pub(super) fn tcp_feedback(
    (robot, tool, wobj): (&Robot, &ToolData, &WobjData),
    now: RobotTime,
    (measured, commanded): (&Joints, &Joints),
    servo_delay: Duration,
    (motor_state, exec_state, mci_state): (MotorState, RapidExecState, MciState),
) -> RobotFeedback {
    let pose = |q: &Joints| {
        feedback_in_wobj(robot, q, tool, wobj)
            .ok()
            .map(|(pos, orient)| WirePose { pos, orient })
            .unwrap_or(WirePose::IDENTITY)
    };
    RobotFeedback {
        joints: *measured,
        external: ExternalAxes::NONE,
        pose: pose(measured),
        time: now,
        planned_joints: *commanded,
        planned_external: ExternalAxes::NONE,
        planned_pose: pose(commanded),
        planned_time: now.saturating_add(servo_delay),
        motor_state,
        exec_state,
        mci_state,
        convergence_met: false,
        utilization: 0.0,
        move_index: None,
        rapid_to_sensor: None,
    }
}
