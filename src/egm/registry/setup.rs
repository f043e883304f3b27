//! EGMSetupUC, EGMSetupAI/AO/GI and EGMSetupLTAPP: profiles, devices, trackers and signal sources resolved into an identity's [`Setup`].

use super::*;

impl EgmRegistry {
    /// `EGMSetupUC`.
    pub fn setup_uc(&mut self, id: EgmId, args: &SetupUc) -> Result<(), EgmError> {
        let instruction = "EGMSetupUC";
        self.check_idle(id, instruction)?;
        self.check_mecunit(instruction, &args.mecunit)?;
        let profile = self.profile(instruction, &args.profile)?;
        check_tracker_uc(instruction, args.mode, args.tracker)?;
        let comm_timeout = match args.comm_timeout {
            None => defaults::COMM_TIMEOUT,
            Some(s) => seconds(instruction, "\\CommTimeout", s, false)?,
        };
        let source = self.resolve_uc(instruction, &args.device, args.mode)?;
        self.store_setup(
            id,
            Setup {
                instruction,
                mecunit: args.mecunit.clone(),
                profile,
                mode: args.mode,
                tracker: args.tracker,
                comm_timeout,
                source,
            },
        );
        Ok(())
    }

    /// `EGMSetupAI`, `EGMSetupAO`, `EGMSetupGI` (by `args.kind`); the signals are checked
    /// against `table` (they must exist and be of the instruction's kind; at least one).
    pub fn setup_signals(
        &mut self,
        id: EgmId,
        args: &SetupSignals,
        table: &SignalTable,
    ) -> Result<(), EgmError> {
        let instruction = args.instruction();
        self.check_idle(id, instruction)?;
        self.check_mecunit(instruction, &args.mecunit)?;
        let profile = self.profile(instruction, &args.profile)?;
        match (args.mode, args.tracker) {
            (EgmMode::PathCorr, Some(TrackerKind::Aptr))
            | (EgmMode::Joint | EgmMode::Pose, None) => {}
            (EgmMode::PathCorr, Some(TrackerKind::Latr)) => {
                return Err(bad(
                    instruction,
                    "\\LATR does not exist for signal sources (removed in RobotWare 7.1); use \\APTR",
                ));
            }
            (EgmMode::PathCorr, None) => {
                return Err(bad(instruction, "\\PathCorr needs \\APTR"));
            }
            (_, Some(_)) => {
                return Err(bad(instruction, "\\APTR is only allowed with \\PathCorr"));
            }
        }
        let source =
            SignalSource::new(table, args.kind, args.mapping, args.ext).map_err(|source| {
                EgmError::Guidance {
                    instruction,
                    source,
                }
            })?;
        self.store_setup(
            id,
            Setup {
                instruction,
                mecunit: args.mecunit.clone(),
                profile,
                mode: args.mode,
                tracker: args.tracker,
                comm_timeout: defaults::COMM_TIMEOUT,
                source: SourceSpec::Signals {
                    kind: args.kind,
                    source,
                },
            },
        );
        Ok(())
    }

    /// `EGMSetupLTAPP`: only the simulated LTAPP devices (or a `builtin` device with a seam
    /// pattern) work; the LTAPP protocol is not public.
    pub fn setup_ltapp(&mut self, id: EgmId, args: &SetupLtapp) -> Result<(), EgmError> {
        let instruction = "EGMSetupLTAPP";
        self.check_idle(id, instruction)?;
        self.check_mecunit(instruction, &args.mecunit)?;
        let profile = self.profile(instruction, &args.profile)?;
        if !args.joint_type.is_finite() {
            return Err(EgmError::Argument {
                instruction,
                argument: "JointType",
                value: args.joint_type,
                range: "a number",
            });
        }
        let device = device_key(&args.device).to_string();
        let seam_text = match self.config.devices.resolve_device(&args.device) {
            Ok(DeviceTarget::Ltapp { seam, .. }) => seam,
            Ok(DeviceTarget::Builtin { pattern }) => {
                pattern.unwrap_or_else(|| "const:y=0,z=0".to_string())
            }
            Ok(DeviceTarget::Udp { .. }) => {
                return Err(EgmError::Unsupported {
                    instruction,
                    what: "an LTAPP sensor on a UdpUc device (the LTAPP protocol is not public; rapidvc simulates the LTAPP devices OptSim and wg1sim, and `--device NAME=builtin:SEAM` makes any name a simulated seam sensor)",
                });
            }
            Err(source) => {
                return Err(EgmError::Device {
                    instruction,
                    source,
                });
            }
        };
        let seam = SeamProfile::parse(&seam_text).map_err(|e| EgmError::BadDevice {
            instruction,
            device: device.clone(),
            detail: e.to_string(),
        })?;
        self.store_setup(
            id,
            Setup {
                instruction,
                mecunit: args.mecunit.clone(),
                profile,
                mode: EgmMode::PathCorr,
                tracker: Some(args.tracker),
                comm_timeout: defaults::COMM_TIMEOUT,
                source: SourceSpec::Ltapp {
                    device,
                    joint_type: args.joint_type,
                    seam,
                },
            },
        );
        Ok(())
    }

    fn check_mecunit(&self, instruction: &'static str, unit: &str) -> Result<(), EgmError> {
        if self
            .config
            .mecunits
            .iter()
            .any(|u| u.eq_ignore_ascii_case(unit))
        {
            Ok(())
        } else {
            Err(EgmError::BadSetup {
                instruction,
                detail: format!(
                    "MecUnit {unit} is not a TCP robot of this task (this task moves {})",
                    self.config.mecunits.join(", ")
                ),
            })
        }
    }

    fn profile(&self, instruction: &'static str, name: &str) -> Result<MotionProfile, EgmError> {
        self.config
            .profiles
            .profile(name)
            .cloned()
            .map_err(|source| EgmError::UnknownProfile {
                instruction,
                source,
            })
    }

    fn resolve_uc(
        &self,
        instruction: &'static str,
        device: &str,
        mode: EgmMode,
    ) -> Result<SourceSpec, EgmError> {
        let name = device_key(device).to_string();
        match self.config.devices.resolve_device(device) {
            Ok(DeviceTarget::Udp { remote, local_port }) => Ok(udp_spec(name, remote, local_port)),
            Ok(DeviceTarget::Builtin { pattern }) => {
                let pattern = builtin_pattern(instruction, &name, pattern.as_deref(), mode)?;
                Ok(SourceSpec::Builtin {
                    device: name,
                    pattern,
                })
            }
            Ok(DeviceTarget::Ltapp { .. }) => Err(EgmError::BadDevice {
                instruction,
                device: name,
                detail: "is a simulated LTAPP seam sensor; set it up with EGMSetupLTAPP"
                    .to_string(),
            }),
            Err(source) => Err(EgmError::Device {
                instruction,
                source,
            }),
        }
    }

    fn store_setup(&mut self, id: EgmId, setup: Setup) {
        if let Some(i) = self.get_mut(id) {
            i.setup = Some(setup);
            i.activation = None;
            i.act_move = None;
            i.corr = CorrState::Stopped;
        }
    }
}
