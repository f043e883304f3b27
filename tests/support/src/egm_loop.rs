//! Shared EGM test harness: the built-in sensor on a thread, and a controller loop (session + transport + servo) at 4 ms.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

use std::net::{SocketAddr, UdpSocket};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use rapidvc::egm::sensor::{BuiltinSensor, SensorConfig, SensorStats};
use rapidvc::egm::servo::{EgmServo, ServoInput, ServoParams};
use rapidvc::egm::session::MAX_DATAGRAM_LEN;
use rapidvc::egm::{
    EgmConfig, EgmEvent, EgmMode, EgmSession, Joints, MciState, Pose, RobotFeedback, Target,
};
use rapidvc::time::RobotTime;
use rapidvc::wire::udp::{DEFAULT_DRAIN_LIMIT, UdpTransport};

pub const PERIOD: Duration = Duration::from_millis(4);
pub const START: Joints = [0.0, 0.0, 0.0, 0.0, 30.0, 0.0];

/// The built-in sensor on its own thread and socket, until `stop` is set or 30 s pass.
pub struct SensorThread {
    pub addr: SocketAddr,
    pub stop: Arc<AtomicBool>,
    pub mute_after: Arc<AtomicU64>,
    pub handle: JoinHandle<SensorStats>,
}

impl SensorThread {
    pub fn spawn(pattern: &str) -> Self {
        let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
        socket
            .set_read_timeout(Some(Duration::from_millis(20)))
            .unwrap();
        let addr = socket.local_addr().unwrap();
        let mut sensor = BuiltinSensor::new(SensorConfig::new(pattern.parse().unwrap())).unwrap();
        let stop = Arc::new(AtomicBool::new(false));
        let mute_after = Arc::new(AtomicU64::new(u64::MAX));
        let (stop2, mute2) = (stop.clone(), mute_after.clone());
        let handle = std::thread::spawn(move || {
            let origin = Instant::now();
            let mut buf = vec![0u8; 2048];
            while !stop2.load(Ordering::Relaxed) && origin.elapsed() < Duration::from_secs(30) {
                let Ok((len, src)) = socket.recv_from(&mut buf) else {
                    continue;
                };
                assert!(len <= MAX_DATAGRAM_LEN, "EgmRobot of {len} bytes");
                let arrived = Instant::now();
                let reply = sensor.handle_datagram(arrived - origin, &buf[..len]);
                assert!(
                    sensor.last_missing().is_empty(),
                    "{:?}",
                    sensor.last_missing()
                );
                if sensor.stats().received > mute2.load(Ordering::Relaxed) {
                    continue;
                }
                if let Ok(bytes) = reply {
                    socket.send_to(&bytes, src).unwrap();
                    sensor.record_turnaround(arrived.elapsed());
                }
            }
            sensor.stats().clone()
        });
        SensorThread {
            addr,
            stop,
            mute_after,
            handle,
        }
    }

    pub fn finish(self) -> SensorStats {
        self.stop.store(true, Ordering::Relaxed);
        self.handle.join().unwrap()
    }
}

/// Controller side: one session, one transport, a servo as the robot.
pub struct Controller {
    pub session: EgmSession,
    pub transport: UdpTransport,
    pub servo: EgmServo,
    pub origin: Instant,
    pub events: Vec<EgmEvent>,
    pub last: Joints,
    pub sent: Vec<u8>,
}

impl Controller {
    pub fn new(mode: EgmMode, remote: SocketAddr, comm_timeout: Duration) -> Self {
        let mut config = EgmConfig::new(mode, remote);
        config.comm_timeout = Some(comm_timeout);
        let params = ServoParams {
            max_speed_deviation: 500.0,
            ramp_in_time: Duration::from_millis(40),
            cond_time: Duration::from_secs(1000),
            ..ServoParams::default()
        };
        Controller {
            session: EgmSession::new(config).unwrap(),
            transport: UdpTransport::for_device(0, remote).unwrap(),
            servo: EgmServo::new(params, START).unwrap(),
            origin: Instant::now(),
            events: Vec::new(),
            last: START,
            sent: Vec::new(),
        }
    }

    pub fn now(&self) -> RobotTime {
        RobotTime::from_duration(self.origin.elapsed())
    }

    /// One EGM cycle: drain, take the reference, step the robot, send, sleep to the deadline.
    pub fn cycle(
        &mut self,
        deadline: Instant,
        reference: &mut ServoInput,
        to_joints: impl Fn(&Target) -> Joints,
    ) {
        let now = self.now();
        let session = &mut self.session;
        self.transport
            .drain(DEFAULT_DRAIN_LIMIT, |src, bytes| {
                session.handle_datagram(now, src, bytes);
            })
            .unwrap();
        if let Some(r) = self.session.poll_reference() {
            reference.position = to_joints(&r.target);
        }
        let out = self.servo.step(reference);
        self.last = out.feedback;
        let mut fb = RobotFeedback::standing(out.feedback, toy_pose(&out.feedback));
        fb.planned_joints = out.commanded;
        fb.planned_pose = toy_pose(&out.commanded);
        fb.time = now;
        fb.planned_time = now + Duration::from_millis(12);
        fb.convergence_met = out.convergence_met;
        fb.utilization = out.utilization;
        fb.mci_state = MciState::Running;
        self.session.handle_timeout(now);
        if self.session.poll_transmit_into(now, &fb, &mut self.sent) {
            assert!(self.sent.len() <= MAX_DATAGRAM_LEN);
            self.transport.send(&self.sent).unwrap();
        }
        while let Some(e) = self.session.poll_event() {
            self.events.push(e);
        }
        let left = deadline.saturating_duration_since(Instant::now());
        std::thread::sleep(left);
    }

    pub fn run(
        &mut self,
        cycles: u32,
        reference: &mut ServoInput,
        to_joints: impl Fn(&Target) -> Joints + Copy,
    ) {
        let t0 = Instant::now();
        for k in 1..=cycles {
            self.cycle(t0 + PERIOD * k, reference, to_joints);
        }
    }
}

/// A toy Cartesian "robot" for pose mode: joints 1-3 are x, y, z in mm.
pub fn toy_pose(j: &Joints) -> Pose {
    Pose {
        pos: [j[0], j[1], j[2]],
        orient: [1.0, 0.0, 0.0, 0.0],
    }
}

pub fn joints_of(t: &Target) -> Joints {
    match t {
        Target::Joint(j) => j.joints,
        Target::Pose(p) => [p.pose.pos[0], p.pose.pos[1], p.pose.pos[2], 0.0, 30.0, 0.0],
        Target::PathCorr(_) => START,
    }
}

pub fn close(a: &Joints, b: &Joints, tol: f64) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
}
