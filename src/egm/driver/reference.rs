//! Step 2 of a tick: a sensor message or a signal sample becomes the servo's position and speed reference (IK and supervision in pose mode), and the convergence error.

use super::*;

impl EgmDriver {
    /// A reply that arrives while the run is ending: logged, not used.
    pub(super) fn log_reply(&mut self, r: &SensorReference) {
        let logged = match &r.target {
            Target::Joint(j) => Some(j.joints),
            Target::Pose(p) => Some(pose6(&p.pose)),
            Target::PathCorr(_) => None,
        };
        if let Some(row) = &mut self.pending {
            row.recv_time = Some(r.received_at);
            row.reference = logged;
        }
    }

    /// Step 2 for a sensor message.
    pub(super) fn apply_sensor(&mut self, r: &SensorReference, current: &Joints) {
        let logged = match &r.target {
            Target::Joint(j) => {
                self.input.position = j.joints;
                self.input.speed = j.speed;
                self.have_reference = true;
                Some(j.joints)
            }
            Target::Pose(p) => {
                self.apply_pose(&p.pose.to_robot(), Some(&p.speed), current);
                Some(pose6(&p.pose))
            }
            Target::PathCorr(_) => None,
        };
        if let (Some(di), Some(v)) = (self.di_from_sensor, r.rapid.and_then(|d| d.dig_val))
            && let Err(e) = self.signals.set(di, if v { 1.0 } else { 0.0 })
        {
            self.events.push(EgmEvent::new(
                EventKind::SignalSource,
                format!("\\DIFromSensor: {e}"),
            ));
        }
        if let Some(row) = &mut self.pending {
            row.recv_time = Some(r.received_at);
            row.reference = logged;
        }
    }

    /// Step 2 in pose mode: sensor pose → ordered TCP → joints (supervised) and the speed
    /// reference.
    pub(super) fn apply_pose(
        &mut self,
        sensor_pose: &Pose,
        speed: Option<&[f64; 6]>,
        current: &Joints,
    ) {
        let Some(g) = &self.guidance else {
            return;
        };
        let target = g
            .target_tcp_world(sensor_pose)
            .and_then(|tcp| g.joints_for_tcp(&tcp, current).map(|q| (tcp, q)));
        let (tcp, q) = match target {
            Ok(t) => t,
            Err(e) => {
                self.fail(EgmError::Supervision(e));
                return;
            }
        };
        let joint_speed = match speed {
            Some(s) if s.iter().any(|v| *v != 0.0) => match g.joint_speed_ref(current, s) {
                Ok(sr) => {
                    if let Some(limit) = sr.limit
                        && !self.speed_ref_reported
                    {
                        self.speed_ref_reported = true;
                        self.events.push(EgmEvent::new(
                            EventKind::SpeedRefLimited,
                            format!("the Cartesian speed reference was limited: {limit:?}"),
                        ));
                    }
                    sr.joints
                }
                Err(_) => [0.0; ROBOT_AXES],
            },
            _ => [0.0; ROBOT_AXES],
        };
        self.input.position = q;
        self.input.speed = joint_speed;
        self.ordered = Some(tcp);
        self.have_reference = true;
    }

    /// Step 2 for signals (applied only while `apply`); returns the logged reference.
    pub(super) fn read_signals(
        &mut self,
        src: &SignalSource,
        current: &Joints,
        apply: bool,
    ) -> Option<[f64; 6]> {
        match self.mode {
            EgmMode::Pose => {
                let start = *self.guidance.as_ref()?.start_sensor_pose();
                match src.sensor_pose(&self.signals, &start) {
                    Ok(s) => {
                        if apply {
                            self.apply_pose(&s, None, current);
                        }
                        Some(pose6(&WirePose::from(&s)))
                    }
                    Err(e) => {
                        self.fail(EgmError::Signal(e));
                        None
                    }
                }
            }
            _ => {
                match src.joint_reference(&self.signals, &self.start) {
                    Ok(q) if !apply => Some(q),
                    Ok(q) => {
                        match self.robot.check_limits(&q) {
                            Ok(()) => {
                                self.input.position = q;
                                self.input.speed = [0.0; ROBOT_AXES];
                                self.have_reference = true;
                                self.out_of_bounds = false;
                            }
                            Err(e) if !self.out_of_bounds => {
                                self.out_of_bounds = true;
                                self.events.push(EgmEvent::new(
                                EventKind::OutOfBounds,
                                format!("signal joint reference refused, the previous one stays: {e}"),
                            ));
                            }
                            Err(_) => {}
                        }
                        Some(q)
                    }
                    Err(e) => {
                        self.fail(EgmError::Signal(e));
                        None
                    }
                }
            }
        }
    }

    /// The convergence error to give the servo: unmet before the first reference; the
    /// Cartesian error in the correction frame in pose mode; the servo's own joint error
    /// otherwise.
    pub(super) fn convergence_error(&self) -> Option<[f64; ROBOT_AXES]> {
        if !self.have_reference {
            return Some([f64::NAN; ROBOT_AXES]);
        }
        match (&self.guidance, &self.ordered) {
            (Some(g), Some(ordered)) => Some(
                g.convergence_errors(ordered, &self.fb)
                    .unwrap_or([f64::NAN; ROBOT_AXES]),
            ),
            (Some(_), None) => Some([f64::NAN; ROBOT_AXES]),
            _ => None,
        }
    }
}
