//! The pair harness: a controller-side EGM machine (a run's `EgmDriver`, an `EgmStream`, a
//! path-correction `CorrectionLink`) and a sensor connected in memory, in virtual time, with
//! no socket — in the manner of quinn-proto's pair tests. Each cycle the test calls
//! [`Pair::deliver`] before the machine's tick and [`Pair::carry`] after it, exactly where the
//! controller's loop drains and sends the device's socket.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::collections::VecDeque;
use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::time::Duration;

use prost::Message;
use rapidvc::egm::DatagramMachine;
use rapidvc::egm::proto::EgmRobot;
use rapidvc::egm::sensor::{BuiltinSensor, SensorConfig};
use rapidvc::time::RobotTime;

/// The sensor's address in every pair (the UdpUc device's remote address: pass
/// `--device`-style override `NAME=127.0.0.1:6510` to the registry).
pub const SENSOR: SocketAddr = SocketAddr::new(IpAddr::V4(Ipv4Addr::LOCALHOST), 6510);

/// The sensor end of a pair.
pub trait SensorEnd {
    /// The controller's `EgmRobot` (`bytes`, decoded as `robot`) arrived at `now`; the reply,
    /// if the sensor answers.
    fn on_robot(&mut self, now: RobotTime, robot: &EgmRobot, bytes: &[u8]) -> Option<Vec<u8>>;
}

/// rapidvc's built-in sensor as the other end.
impl SensorEnd for BuiltinSensor {
    fn on_robot(&mut self, now: RobotTime, _robot: &EgmRobot, bytes: &[u8]) -> Option<Vec<u8>> {
        Some(self.handle_datagram(now.since_start(), bytes).unwrap())
    }
}

/// A sensor written by the test: called with the index of each message it receives (from
/// 0) and the message; returns the reply's bytes, or `None` to stay silent.
pub struct Scripted<F>(pub F);

impl<F: FnMut(u32, &EgmRobot) -> Option<Vec<u8>>> SensorEnd for Scripted<F> {
    fn on_robot(&mut self, _now: RobotTime, robot: &EgmRobot, _bytes: &[u8]) -> Option<Vec<u8>> {
        let k = robot.header.and_then(|h| h.seqno).unwrap_or(0);
        (self.0)(k, robot)
    }
}

/// A controller-side machine and a sensor, joined by an in-memory link with a one-way
/// `latency` (virtual time).
pub struct Pair<S> {
    /// The sensor end.
    pub sensor: S,
    /// One-way delay of every datagram.
    pub latency: Duration,
    /// Every `EgmRobot` the sensor received, in order.
    pub received: Vec<EgmRobot>,
    /// Replies in flight: when they arrive, and their bytes.
    in_flight: VecDeque<(RobotTime, Vec<u8>)>,
}

impl<S: SensorEnd> Pair<S> {
    /// A pair with no delay: a reply is handed in before the next tick, as the built-in sensor
    /// in process does.
    pub fn new(sensor: S) -> Pair<S> {
        Pair::with_latency(sensor, Duration::ZERO)
    }

    /// A pair whose datagrams take `latency` each way.
    pub fn with_latency(sensor: S, latency: Duration) -> Pair<S> {
        Pair {
            sensor,
            latency,
            received: Vec::new(),
            in_flight: VecDeque::new(),
        }
    }

    /// Before the machine's tick at `now`: every reply that has arrived by then, from
    /// [`SENSOR`].
    pub fn deliver(&mut self, now: RobotTime, machine: &mut impl DatagramMachine) {
        while self.in_flight.front().is_some_and(|(at, _)| *at <= now) {
            let (_, bytes) = self.in_flight.pop_front().unwrap();
            machine.handle_datagram(now, SENSOR, &bytes);
        }
    }

    /// After the machine's tick at `now`: the datagram it produced goes to the sensor (which
    /// must be its address), and the sensor's reply on its way back.
    pub fn carry(&mut self, now: RobotTime, machine: &mut impl DatagramMachine) {
        let Some((to, bytes)) = machine.poll_transmit(now) else {
            return;
        };
        assert_eq!(
            to, SENSOR,
            "the machine sends to its device's remote address"
        );
        let robot = EgmRobot::decode(bytes).expect("the controller sends a valid EgmRobot");
        let at_sensor = now + self.latency;
        if let Some(reply) = self.sensor.on_robot(at_sensor, &robot, bytes) {
            self.in_flight.push_back((at_sensor + self.latency, reply));
        }
        self.received.push(robot);
    }
}

/// The built-in sensor with `pattern` (as `--device NAME=builtin:PATTERN` writes it).
pub fn builtin(pattern: &str) -> BuiltinSensor {
    BuiltinSensor::new(SensorConfig::new(pattern.parse().unwrap())).unwrap()
}

/// A registry with the UdpUc devices `overrides` (`NAME=ADDR` or `NAME=builtin:PATTERN`, as
/// `--device` writes them) and, with `path_corr`, the manual's Level 2 MOC profile
/// `pathCorr` that path correction needs.
pub fn registry(overrides: &[String], path_corr: bool) -> rapidvc::egm::EgmRegistry {
    use rapidvc::config::devices::{DeviceOverride, DeviceTable};
    let moc = if path_corr {
        let text = "MOC:CFG_1.0:6:0::\n#\nEXT_MOTION_DATA:\n\n      -name \"pathCorr\" -ext_motion_level 2\n";
        let mut sources = rapidvc::source::SourceMap::new();
        let mut diags = rapidvc::diag::Diagnostics::new();
        let id = sources.add("MOC.cfg".to_string(), text);
        let file = rapidvc::config::cfg::parse(id, text, &mut diags).unwrap();
        rapidvc::config::moc::read(&file, &mut diags)
    } else {
        rapidvc::config::moc::MocConfig::default()
    };
    let overrides: Vec<DeviceOverride> = overrides.iter().map(|o| o.parse().unwrap()).collect();
    let devices = DeviceTable::new(None, &overrides).unwrap();
    rapidvc::egm::EgmRegistry::new(rapidvc::controller::egm_controller::registry_config(
        &moc, &devices,
    ))
}

/// `EGMActMove` of the manual's path-correction example on `id`: the sensor frame of
/// `t_fronius_cmt`, a correction every 48 ms.
pub fn act_move_48ms(reg: &mut rapidvc::egm::EgmRegistry, id: rapidvc::egm::EgmId) {
    reg.act_move(
        id,
        &rapidvc::egm::registry::ActMove {
            sensor_frame: crate::robot::t_fronius_cmt().tframe,
            sample_rate: Some(48.0),
        },
    )
    .unwrap();
}

/// What a path-correction `link` delivered over `ticks` cycles of 4 ms from time zero, with
/// the robot standing at `start` holding `tool` in `wobj0`, the TCP advancing 0.04 mm along
/// the path each cycle and no look-ahead: each correction's arrival and position, and the
/// offset an APTR corrector fed with them applies at the end. `pair`, when given, carries
/// the link's datagrams around each tick.
pub fn corrections<S: SensorEnd>(
    link: &mut rapidvc::egm::CorrectionLink,
    mut pair: Option<&mut Pair<S>>,
    (start, tool): (rapidvc::egm::Joints, &rapidvc::robot::ToolData),
    ticks: u32,
) -> (
    Vec<(RobotTime, [f64; 3])>,
    rapidvc::egm::path_correction::PathOffset,
) {
    use rapidvc::egm::driver::CorrectionInput;
    use rapidvc::egm::path_correction::{PathCorrConfig, PathCorrector};
    let mut corrector = PathCorrector::new(PathCorrConfig::aptr()).unwrap();
    corrector.start(0.0, 0.0);
    let wobj = rapidvc::robot::WobjData::wobj0();
    let mut got = Vec::new();
    let mut offset = Default::default();
    for k in 0..ticks {
        let now = RobotTime::from_millis(4 * u64::from(k));
        let input = CorrectionInput {
            commanded: start,
            tool,
            wobj: &wobj,
            tcp_s: f64::from(k) * 0.04,
            look_ahead: 0.0,
        };
        if let Some(p) = pair.as_deref_mut() {
            p.deliver(now, link);
        }
        let t = link.tick(now, &input);
        if let Some(p) = pair.as_deref_mut() {
            p.carry(now, link);
        }
        assert!(t.failed.is_none());
        let s = now.as_secs_f64();
        if let Some(c) = t.correction {
            got.push((now, c.pos));
            corrector.measurement(s, c.pos, c.age_s()).unwrap();
        }
        offset = corrector.step(s, input.tcp_s);
    }
    (got, offset)
}
