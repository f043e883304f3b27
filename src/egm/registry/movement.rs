//! EGMRunJoint/EGMRunPose, EGMStop, EGMStreamStart/Stop and EGMMoveL/C: the checks of each request, its plan, and the state changes when it ends.

use super::*;

impl EgmRegistry {
    /// `EGMRunJoint`: checks the request and marks the identity RUNNING; `axes` are the
    /// switches `\J1` … `\J7`. Call [`EgmRegistry::run_finished`] when the run ends or its
    /// driver cannot start.
    pub fn run_joint(
        &mut self,
        id: EgmId,
        args: &RunArgs,
        axes: [bool; 7],
    ) -> Result<RunPlan, EgmError> {
        let instruction = "EGMRunJoint";
        if axes.get(6).copied().unwrap_or(false) {
            return Err(EgmError::Unsupported {
                instruction,
                what: "\\J7 (rapidvc models 6-axis robots)",
            });
        }
        let mut selection = [false; ROBOT_AXES];
        for (s, a) in selection.iter_mut().zip(&axes) {
            *s = *a;
        }
        self.plan_run(id, instruction, args, selection, None)
    }

    /// `EGMRunPose`: checks the request and marks the identity RUNNING; `directions` are the
    /// switches `\x \y \z \rx \ry \rz`. Call [`EgmRegistry::run_finished`] when the run ends
    /// or its driver cannot start.
    pub fn run_pose(
        &mut self,
        id: EgmId,
        args: &RunArgs,
        directions: [bool; 6],
        offset: Option<Pose>,
    ) -> Result<RunPlan, EgmError> {
        let instruction = "EGMRunPose";
        if let Some(o) = &offset
            && !pose_is_finite(o)
        {
            return Err(bad(instruction, "\\Offset is not a finite pose"));
        }
        self.plan_run(id, instruction, args, directions, offset)
    }

    /// The run of `id` ended: CONNECTED, with correction state STOPPED (`ok`) or ERROR. A
    /// stream the run replaced ends too. Nothing happens when no run is active.
    pub fn run_finished(&mut self, id: EgmId, ok: bool) {
        if let Some(i) = self.get_mut(id)
            && matches!(i.activity, Activity::Run(_))
        {
            i.activity = Activity::Idle;
            i.corr = if ok {
                CorrState::Stopped
            } else {
                CorrState::Error
            };
        }
    }

    /// `EGMStop`: what is active and must be ended. A stream or a corrected movement is
    /// marked ended at once; a run stays RUNNING until [`EgmRegistry::run_finished`].
    pub fn stop(&mut self, id: EgmId) -> Result<StopTarget, EgmError> {
        let i = self.get_mut(id).ok_or(EgmError::NotReserved {
            instruction: "EGMStop",
        })?;
        let target = stop_target(i.activity);
        if matches!(i.activity, Activity::Stream | Activity::Move) {
            i.activity = Activity::Idle;
            i.corr = CorrState::Stopped;
        }
        Ok(target)
    }

    /// `EGMStreamStart \SampleRate`: checks and marks the identity RUNNING (correction state
    /// STOPPED).
    pub fn stream_start(
        &mut self,
        id: EgmId,
        sample_rate_ms: Option<f64>,
    ) -> Result<StreamPlan, EgmError> {
        let instruction = "EGMStreamStart";
        let i = self.reserved(id, instruction)?;
        let setup = i.setup.as_ref().ok_or_else(|| EgmError::NotSetUp {
            name: i.name.clone(),
            instruction,
        })?;
        check_streamable(instruction, setup)?;
        if i.activity != Activity::Idle {
            return Err(busy(i, instruction));
        }
        let period = sample_rate(
            instruction,
            sample_rate_ms,
            defaults::SAMPLE_RATE_MS,
            defaults::SAMPLE_RATE_MULTIPLE_MS,
        )?;
        let plan = stream_plan(id, i, setup, period);
        if let Some(i) = self.get_mut(id) {
            i.activity = Activity::Stream;
        }
        Ok(plan)
    }

    /// `EGMStreamStop` (also after a stream failed to start): CONNECTED again; returns whether
    /// a stream was active.
    pub fn stream_stop(&mut self, id: EgmId) -> Result<bool, EgmError> {
        let i = self.get_mut(id).ok_or(EgmError::NotReserved {
            instruction: "EGMStreamStop",
        })?;
        if i.activity == Activity::Stream {
            i.activity = Activity::Idle;
            i.corr = CorrState::Stopped;
            Ok(true)
        } else {
            Ok(false)
        }
    }

    /// `EGMMoveL` / `EGMMoveC` (`instruction`): checks the path-correction request (setup
    /// with `\PathCorr` or EGMSetupLTAPP, EGMActMove, a Level 2 profile) and marks the
    /// identity RUNNING. Further moves of the same sequence get the same plan.
    pub fn move_start(
        &mut self,
        id: EgmId,
        instruction: &'static str,
    ) -> Result<MovePlan, EgmError> {
        let i = self.reserved(id, instruction)?;
        let setup = i.setup.as_ref().ok_or_else(|| EgmError::NotSetUp {
            name: i.name.clone(),
            instruction,
        })?;
        if setup.mode != EgmMode::PathCorr {
            return Err(EgmError::ModeMismatch {
                name: i.name.clone(),
                instruction,
                detail: format!(
                    "the identity is set up for {} guidance by {}; {instruction} needs a path-correction setup (EGMSetupUC … \\PathCorr, or EGMSetupLTAPP)",
                    setup.mode, setup.instruction
                ),
            });
        }
        let act = i.act_move.ok_or_else(|| EgmError::NotActivated {
            name: i.name.clone(),
            instruction,
            needs: "EGMActMove",
        })?;
        if setup.profile.level != MotionLevel::Path {
            return Err(EgmError::PathCorrLevel {
                name: i.name.clone(),
                instruction,
                profile: setup.profile.name.clone(),
                level: setup.profile.level.number(),
            });
        }
        if !matches!(i.activity, Activity::Idle | Activity::Move) {
            return Err(busy(i, instruction));
        }
        let plan = MovePlan {
            id,
            name: i.name.clone(),
            tracker: setup.tracker.unwrap_or(TrackerKind::Aptr),
            sensor_frame: act.sensor_frame,
            sample_period: act.sample_period,
            source: setup.source.clone(),
            comm_timeout: setup.comm_timeout,
            profile: setup.profile.clone(),
        };
        if let Some(i) = self.get_mut(id) {
            i.activity = Activity::Move;
            i.corr = CorrState::Running;
        }
        Ok(plan)
    }

    /// The fine point ending a corrected sequence was reached (`ok`), or it ended with an
    /// error: CONNECTED.
    pub fn move_finished(&mut self, id: EgmId, ok: bool) {
        if let Some(i) = self.get_mut(id)
            && i.activity == Activity::Move
        {
            i.activity = Activity::Idle;
            i.corr = if ok {
                CorrState::Stopped
            } else {
                CorrState::Error
            };
        }
    }

    fn plan_run(
        &mut self,
        id: EgmId,
        instruction: &'static str,
        args: &RunArgs,
        selection: [bool; ROBOT_AXES],
        offset: Option<Pose>,
    ) -> Result<RunPlan, EgmError> {
        let pose_run = instruction == "EGMRunPose";
        let i = self.reserved(id, instruction)?;
        let setup = i.setup.as_ref().ok_or_else(|| EgmError::NotSetUp {
            name: i.name.clone(),
            instruction,
        })?;
        let wanted = if pose_run {
            EgmMode::Pose
        } else {
            EgmMode::Joint
        };
        if setup.mode != wanted {
            return Err(EgmError::ModeMismatch {
                name: i.name.clone(),
                instruction,
                detail: format!(
                    "EGM mode mismatch: the identity is set up for {} by {}; {instruction} needs {}",
                    describe_mode(setup.mode),
                    setup.instruction,
                    describe_mode(wanted)
                ),
            });
        }
        let needs = if pose_run {
            "EGMActPose"
        } else {
            "EGMActJoint"
        };
        let act = i
            .activation
            .as_ref()
            .ok_or_else(|| EgmError::NotActivated {
                name: i.name.clone(),
                instruction,
                needs,
            })?;
        let stops_stream = match i.activity {
            Activity::Idle => false,
            Activity::Stream => true,
            Activity::Run(_) | Activity::Move => return Err(busy(i, instruction)),
        };
        let (windows, pose) = match (&act.kind, pose_run) {
            (ActivationKind::Joint { windows }, false) => (*windows, None),
            (ActivationKind::Pose { frames, windows }, true) => {
                let mut w = [MinMax::JOINT_DEFAULT; ROBOT_AXES];
                for (slot, (min, max)) in w.iter_mut().zip(windows.windows()) {
                    *slot = MinMax {
                        min: *min,
                        max: *max,
                    };
                }
                let pose = PoseSetup {
                    offset,
                    selection,
                    ..(**frames).clone()
                };
                (w, Some(pose))
            }
            _ => {
                return Err(EgmError::ModeMismatch {
                    name: i.name.clone(),
                    instruction,
                    detail: format!(
                        "EGM mode mismatch: the identity is activated by {}; {instruction} needs {needs}",
                        act.instruction
                    ),
                });
            }
        };
        let ramp_default = profile_ramp(&setup.profile);
        let cond_time = opt_seconds(
            instruction,
            "\\CondTime",
            args.cond_time,
            defaults::COND_TIME,
        )?;
        let ramp_in_time =
            opt_seconds(instruction, "\\RampInTime", args.ramp_in_time, ramp_default)?;
        let ramp_out_time = opt_seconds(
            instruction,
            "\\RampOutTime",
            args.ramp_out_time,
            ramp_default,
        )?;
        let pos_corr_gain = args.pos_corr_gain.unwrap_or(defaults::POS_CORR_GAIN);
        if !(pos_corr_gain.is_finite() && pos_corr_gain >= 0.0) {
            return Err(EgmError::Argument {
                instruction,
                argument: "\\PosCorrGain",
                value: pos_corr_gain,
                range: "a number ≥ 0 (0 to 1 in ABB's manual)",
            });
        }
        let plan = RunPlan {
            id,
            name: i.name.clone(),
            instruction,
            mode: wanted,
            source: setup.source.clone(),
            profile: setup.profile.clone(),
            comm_timeout: setup.comm_timeout,
            sample_period: act.sample_period,
            tool: act.tool,
            wobj: act.wobj.clone(),
            tload: act.tload,
            pose,
            windows,
            selection,
            stop_mode: args.stop_mode,
            no_wait_cond: args.no_wait_cond,
            cond_time,
            ramp_in_time,
            ramp_out_time,
            pos_corr_gain,
            lp_filter_hz: act.lp_filter_hz.unwrap_or(setup.profile.filter_bandwidth),
            max_speed_deviation: act.max_speed_deviation,
            max_pos_deviation: act.max_pos_deviation,
            do_to_sensor: act.do_to_sensor,
            di_from_sensor: act.di_from_sensor,
            stops_stream,
        };
        if let Some(i) = self.get_mut(id) {
            i.activity = Activity::Run(instruction);
            i.corr = CorrState::Running;
        }
        Ok(plan)
    }
}
