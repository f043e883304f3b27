//! EGMActJoint, EGMActPose and EGMActMove: argument checks, defaults and `\\StreamStart`.

use super::*;

impl EgmRegistry {
    /// `EGMActJoint`; with `\StreamStart` the identity starts streaming and the plan of the
    /// stream is returned.
    pub fn act_joint(
        &mut self,
        id: EgmId,
        args: &ActJoint,
    ) -> Result<Option<StreamPlan>, EgmError> {
        let instruction = "EGMActJoint";
        let setup = self.setup_for_activation(id, instruction)?;
        if args.windows.get(6).copied().flatten().is_some() {
            return Err(EgmError::Unsupported {
                instruction,
                what: "\\J7 (rapidvc models 6-axis robots)",
            });
        }
        let mut windows = [defaults::JOINT_WINDOW; ROBOT_AXES];
        for (i, (slot, given)) in windows.iter_mut().zip(&args.windows).enumerate() {
            if let Some(w) = given {
                check_window(
                    instruction,
                    JOINT_WINDOW_ARGS.get(i).copied().unwrap_or("\\J"),
                    w,
                )?;
                *slot = *w;
            }
        }
        let activation = resolve_common(
            instruction,
            &args.common,
            &setup,
            ActivationKind::Joint { windows },
        )?;
        self.store_activation(id, activation, args.common.stream_start)
    }

    /// `EGMActPose`; with `\StreamStart` the identity starts streaming and the plan of the
    /// stream is returned.
    pub fn act_pose(&mut self, id: EgmId, args: &ActPose) -> Result<Option<StreamPlan>, EgmError> {
        let instruction = "EGMActPose";
        let setup = self.setup_for_activation(id, instruction)?;
        for (t, which) in [(args.corr_type, "correction"), (args.sens_type, "sensor")] {
            if t == EgmFrameType::Joint {
                return Err(EgmError::Guidance {
                    instruction,
                    source: GuidanceError::JointFrameInPoseMode { which },
                });
            }
        }
        for (p, argument) in [
            (&args.corr_frame, "CorrFrame"),
            (&args.sensor_frame, "SensorFrame"),
        ] {
            if !pose_is_finite(p) {
                return Err(EgmError::BadSetup {
                    instruction,
                    detail: format!("{argument} is not a finite pose"),
                });
            }
        }
        for (i, w) in args.windows.iter().enumerate() {
            if let Some(w) = w {
                check_window(
                    instruction,
                    POSE_WINDOW_ARGS.get(i).copied().unwrap_or("\\x"),
                    w,
                )?;
            }
        }
        let windows = Convergence::with_overrides(args.windows.map(|w| w.map(|m| (m.min, m.max))))
            .map_err(|source| EgmError::Guidance {
                instruction,
                source,
            })?;
        let tool = args.common.tool.unwrap_or_default();
        let wobj = args.common.wobj.clone().unwrap_or_default();
        let frames = PoseSetup {
            tool,
            wobj,
            corr_frame: args.corr_frame,
            corr_type: args.corr_type,
            sensor_frame: args.sensor_frame,
            sens_type: args.sens_type,
            offset: None,
            selection: [true; ROBOT_AXES],
        };
        let activation = resolve_common(
            instruction,
            &args.common,
            &setup,
            ActivationKind::Pose {
                frames: Box::new(frames),
                windows,
            },
        )?;
        self.store_activation(id, activation, args.common.stream_start)
    }

    /// `EGMActMove`.
    pub fn act_move(&mut self, id: EgmId, args: &ActMove) -> Result<(), EgmError> {
        let instruction = "EGMActMove";
        self.setup_for_activation(id, instruction)?;
        if !pose_is_finite(&args.sensor_frame) {
            return Err(bad(instruction, "SensorFrame is not a finite pose"));
        }
        let sample_period = sample_rate(
            instruction,
            args.sample_rate,
            defaults::MOVE_SAMPLE_RATE_MS,
            defaults::MOVE_SAMPLE_RATE_MULTIPLE_MS,
        )?;
        if let Some(i) = self.get_mut(id) {
            i.act_move = Some(MoveActivation {
                sensor_frame: args.sensor_frame,
                sample_period,
            });
        }
        Ok(())
    }

    /// The setup an activation refers to; the identity must be idle.
    fn setup_for_activation(
        &self,
        id: EgmId,
        instruction: &'static str,
    ) -> Result<Setup, EgmError> {
        let i = self.reserved(id, instruction)?;
        let setup = i.setup.clone().ok_or_else(|| EgmError::NotSetUp {
            name: i.name.clone(),
            instruction,
        })?;
        if i.activity != Activity::Idle {
            return Err(busy(i, instruction));
        }
        Ok(setup)
    }

    fn store_activation(
        &mut self,
        id: EgmId,
        activation: Activation,
        stream_start: bool,
    ) -> Result<Option<StreamPlan>, EgmError> {
        let plan = {
            let i = self.reserved(id, activation.instruction)?;
            match (&i.setup, stream_start) {
                (Some(setup), true) => {
                    check_streamable(activation.instruction, setup)?;
                    let mut plan = stream_plan(id, i, setup, activation.sample_period);
                    plan.tool = activation.tool;
                    plan.wobj = activation.wobj.clone();
                    Some(plan)
                }
                _ => None,
            }
        };
        if let Some(i) = self.get_mut(id) {
            i.activation = Some(activation);
            if plan.is_some() {
                i.activity = Activity::Stream;
            }
        }
        Ok(plan)
    }
}
