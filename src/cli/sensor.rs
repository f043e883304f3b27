//! `rapidvc sensor`: the built-in EGM sensor over UDP — replies to a controller, prints what it receives and latency statistics.

use std::net::{IpAddr, SocketAddr};
use std::process::ExitCode;
use std::time::{Duration, Instant};

use clap::Args;

use super::num;

/// Prints a line to stdout, ignoring a closed pipe (`rapidvc sensor | head` must not panic).
macro_rules! say {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stdout(), $($arg)*);
    }};
}
use tokio::net::UdpSocket;

use crate::egm::latency::LatencyHistogram;
use crate::egm::sensor::{
    BuiltinSensor, PathCorrProfile, RobotSnapshot, SensorConfig, SensorPattern, SineAxis,
    parse_axis, parse_profile,
};
use crate::egm::types::{EgmMode, MciState, MotorState, RapidExecState};

/// Arguments of `rapidvc sensor`.
#[derive(Debug, Args)]
pub struct SensorArgs {
    /// UDP port to listen on (the controller's Remote Port Number).
    #[arg(long, default_value_t = 6510)]
    pub port: u16,
    /// Address to bind.
    #[arg(long, default_value = "127.0.0.1")]
    pub bind: IpAddr,
    /// Constant joint target in degrees (joint mode).
    #[arg(long, value_name = "J1,J2,J3,J4,J5,J6", allow_hyphen_values = true,
          conflicts_with_all = ["pose", "pattern", "pathcorr"])]
    pub joint: Option<String>,
    /// Constant pose target: mm and ZYX Euler degrees (pose mode).
    #[arg(long, value_name = "X,Y,Z,RX,RY,RZ", allow_hyphen_values = true,
          conflicts_with_all = ["pattern", "pathcorr"])]
    pub pose: Option<String>,
    /// Pattern: hold, hold-pose, sine, circle, pathcorr, or a full text form such as
    /// `sine:axis=z,amplitude=20` (see the docs of `egm::sensor`).
    #[arg(long, value_name = "PATTERN", conflicts_with = "pathcorr")]
    pub pattern: Option<String>,
    /// Path correction with this profile: constant, ramp or sine.
    #[arg(long, value_name = "KIND")]
    pub pathcorr: Option<String>,
    /// Sine axis: 1..6 (joint mode) or x, y, z (pose mode).
    #[arg(long)]
    pub axis: Option<String>,
    /// Sine amplitude (degrees or mm, ±1e6 at most).
    #[arg(long, allow_hyphen_values = true, value_parser = num::sensor_offset)]
    pub amplitude: Option<f64>,
    /// Frequency of sine, circle and path-correction sine, Hz (0 to 1000).
    #[arg(long, value_parser = num::sensor_frequency)]
    pub frequency: Option<f64>,
    /// Circle radius, mm (0 to 1e6).
    #[arg(long, value_parser = num::sensor_radius)]
    pub radius: Option<f64>,
    /// Path correction y, mm (±1e6 at most).
    #[arg(long, allow_hyphen_values = true, value_parser = num::sensor_offset)]
    pub y: Option<f64>,
    /// Path correction z, mm (±1e6 at most).
    #[arg(long, allow_hyphen_values = true, value_parser = num::sensor_offset)]
    pub z: Option<f64>,
    /// Path-correction ramp time, s (more than 0, at most 1e6).
    #[arg(long, value_parser = num::sensor_ramp_time)]
    pub ramp_time: Option<f64>,
    /// Do not send the pattern's speed as `speedRef`.
    #[arg(long)]
    pub no_speed_ref: bool,
    /// Exit after this many received messages (at least 1).
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
    pub count: Option<u64>,
    /// Exit after this many seconds (more than 0, at most 1e9).
    #[arg(long, value_parser = num::sensor_duration)]
    pub duration: Option<f64>,
    /// Print one line per this many messages (0: only the summary).
    #[arg(long, default_value_t = 250)]
    pub print_every: u64,
    /// Allow replying to a controller that is not on this machine (moves a real robot!).
    #[arg(long)]
    pub confirm_motion: bool,
}

/// Runs the sensor until `--count`, `--duration` or Ctrl-C.
pub fn run(args: SensorArgs) -> ExitCode {
    let pattern = match build_pattern(&args) {
        Ok(p) => p,
        Err(msg) => {
            eprintln!("error: {msg}");
            return ExitCode::from(2);
        }
    };
    let mut config = SensorConfig::new(pattern);
    config.speed_feedforward = !args.no_speed_ref;
    let sensor = match BuiltinSensor::new(config) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let runtime = match tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
    {
        Ok(rt) => rt,
        Err(e) => {
            eprintln!("error: cannot start the async runtime: {e}");
            return ExitCode::FAILURE;
        }
    };
    runtime.block_on(serve(args, sensor))
}

fn build_pattern(args: &SensorArgs) -> Result<SensorPattern, String> {
    let mut pattern = if let Some(j) = &args.joint {
        format!("joint:{j}").parse::<SensorPattern>()
    } else if let Some(p) = &args.pose {
        format!("pose:{p}").parse::<SensorPattern>()
    } else if let Some(kind) = &args.pathcorr {
        format!("pathcorr:kind={kind}").parse::<SensorPattern>()
    } else {
        args.pattern
            .as_deref()
            .unwrap_or("hold")
            .parse::<SensorPattern>()
    }
    .map_err(|e| e.to_string())?;
    let unused = |flag: &str| Err(format!("{flag} does not apply to this pattern"));
    match &mut pattern {
        SensorPattern::Sine {
            axis,
            amplitude,
            frequency_hz,
        } => {
            if let Some(a) = &args.axis {
                *axis = parse_axis(a).map_err(|e| e.to_string())?;
            }
            if let Some(a) = args.amplitude {
                *amplitude = a;
            }
            if let Some(f) = args.frequency {
                *frequency_hz = f;
            }
            if args.radius.is_some() {
                return unused("--radius");
            }
        }
        SensorPattern::Circle {
            radius_mm,
            frequency_hz,
        } => {
            if let Some(r) = args.radius {
                *radius_mm = r;
            }
            if let Some(f) = args.frequency {
                *frequency_hz = f;
            }
            if args.axis.is_some() || args.amplitude.is_some() {
                return unused("--axis/--amplitude");
            }
        }
        SensorPattern::PathCorr {
            profile,
            y_mm,
            z_mm,
        } => {
            if let Some(y) = args.y {
                *y_mm = y;
            }
            if let Some(z) = args.z {
                *z_mm = z;
            }
            let kind = match profile {
                PathCorrProfile::Constant => "constant",
                PathCorrProfile::Ramp { .. } => "ramp",
                PathCorrProfile::Sine { .. } => "sine",
            };
            let time = match profile {
                PathCorrProfile::Ramp { time_s } => args.ramp_time.unwrap_or(*time_s),
                _ => args.ramp_time.unwrap_or(1.0),
            };
            let freq = match profile {
                PathCorrProfile::Sine { frequency_hz } => args.frequency.unwrap_or(*frequency_hz),
                _ => args.frequency.unwrap_or(0.5),
            };
            *profile = parse_profile(kind, time, freq).map_err(|e| e.to_string())?;
        }
        _ => {
            if args.axis.is_some()
                || args.amplitude.is_some()
                || args.frequency.is_some()
                || args.radius.is_some()
            {
                return unused("--axis/--amplitude/--frequency/--radius");
            }
        }
    }
    if !matches!(pattern, SensorPattern::PathCorr { .. })
        && (args.y.is_some() || args.z.is_some() || args.ramp_time.is_some())
    {
        return unused("--y/--z/--ramp-time");
    }
    pattern.validate().map_err(|e| e.to_string())?;
    Ok(pattern)
}

fn describe(pattern: &SensorPattern) -> String {
    match pattern {
        SensorPattern::Hold(EgmMode::Pose) => "hold the start pose".into(),
        SensorPattern::Hold(_) => "hold the start joints".into(),
        SensorPattern::Joint(j) => format!("joint target {}", fmt_list(j)),
        SensorPattern::Pose { pos, euler } => {
            format!(
                "pose target {} mm, ZYX {} deg",
                fmt_list(pos),
                fmt_list(euler)
            )
        }
        SensorPattern::Sine {
            axis,
            amplitude,
            frequency_hz,
        } => {
            let axis = match axis {
                SineAxis::Joint(i) => format!("J{}", i + 1),
                SineAxis::Cartesian(i) => ["x", "y", "z"].get(*i).unwrap_or(&"?").to_string(),
            };
            format!("sine on {axis}, amplitude {amplitude}, {frequency_hz} Hz")
        }
        SensorPattern::Circle {
            radius_mm,
            frequency_hz,
        } => format!("circle in x-y, radius {radius_mm} mm, {frequency_hz} Hz"),
        SensorPattern::PathCorr {
            profile,
            y_mm,
            z_mm,
        } => format!("path correction {profile:?}, y {y_mm} mm, z {z_mm} mm"),
    }
}

async fn serve(args: SensorArgs, mut sensor: BuiltinSensor) -> ExitCode {
    let addr = SocketAddr::new(args.bind, args.port);
    let socket = match UdpSocket::bind(addr).await {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: cannot bind {addr}: {e}");
            return ExitCode::FAILURE;
        }
    };
    let local = socket.local_addr().unwrap_or(addr);
    say!(
        "rapidvc sensor on {local}: {} ({} mode); waiting for EgmRobot",
        describe(&sensor.config().pattern),
        sensor.mode()
    );
    let origin = Instant::now();
    let deadline = args
        .duration
        .and_then(|d| Duration::try_from_secs_f64(d).ok())
        .map(|d| tokio::time::Instant::now() + d);
    let mut buf = vec![0u8; 65_536];
    let mut refused_remote = false;
    let mut warned_missing = false;
    let mut send_errors = 0u64;
    let mut failures = 0u64;
    let ctrl_c = tokio::signal::ctrl_c();
    tokio::pin!(ctrl_c);
    let reason = loop {
        if args.count.is_some_and(|n| sensor.stats().received >= n) {
            break "count reached";
        }
        let sleep = async {
            match deadline {
                Some(d) => tokio::time::sleep_until(d).await,
                None => std::future::pending().await,
            }
        };
        let (len, src) = tokio::select! {
            r = socket.recv_from(&mut buf) => match r {
                Ok(x) => x,
                Err(e) if matches!(e.kind(), std::io::ErrorKind::ConnectionRefused | std::io::ErrorKind::ConnectionReset) => continue,
                Err(e) => {
                    eprintln!("error: receiving: {e}");
                    return ExitCode::FAILURE;
                }
            },
            _ = sleep => break "duration elapsed",
            _ = &mut ctrl_c => break "interrupted",
        };
        let arrived = Instant::now();
        let now = arrived.duration_since(origin);
        let bytes = buf.get(..len).unwrap_or(&[]);
        let first = sensor.stats().received == 0;
        let reply = sensor.handle_datagram(now, bytes);
        if first {
            say!("first message from {src} ({len} bytes)");
        }
        if !sensor.last_missing().is_empty() && !warned_missing {
            warned_missing = true;
            say!(
                "warning: EgmRobot lacks what strict clients need: {}",
                sensor.last_missing().join(", ")
            );
        }
        match reply {
            Ok(out) => {
                if !src.ip().is_loopback() && !args.confirm_motion {
                    if !refused_remote {
                        refused_remote = true;
                        say!(
                            "not replying to {src}: it is not on this machine; pass --confirm-motion to move a real robot"
                        );
                    }
                } else if socket.send_to(&out, src).await.is_ok() {
                    sensor.record_turnaround(arrived.elapsed());
                } else {
                    send_errors += 1;
                }
            }
            Err(e) => {
                failures += 1;
                if failures <= 10 || failures.is_multiple_of(1000) {
                    say!("no reply to message #{failures} from {src}: {e}");
                }
            }
        }
        let received = sensor.stats().received;
        if args.print_every > 0
            && (received == 1 || received.is_multiple_of(args.print_every))
            && let Some(snap) = sensor.last_robot()
        {
            say!("{}", line(received, snap));
        }
    };
    say!("stopped: {reason}");
    summary(&sensor, send_errors);
    ExitCode::SUCCESS
}

fn line(n: u64, s: &RobotSnapshot) -> String {
    let joints = s.joints.map(|j| fmt_list(&j)).unwrap_or_else(|| "-".into());
    let tcp = s
        .pose
        .map(|p| fmt_list(&p.pos))
        .unwrap_or_else(|| "-".into());
    let motors = match s.motor_state {
        Some(MotorState::On) => "on",
        Some(MotorState::Off) => "off",
        None => "?",
    };
    let rapid = match s.exec_state {
        Some(RapidExecState::Running) => "running",
        Some(RapidExecState::Stopped) => "stopped",
        None => "?",
    };
    let mci = match s.mci_state {
        Some(MciState::Running) => "running",
        Some(MciState::Stopped) => "stopped",
        Some(MciState::Error) => "error",
        None => "?",
    };
    let conv = match s.convergence_met {
        Some(true) => "yes",
        Some(false) => "no",
        None => "?",
    };
    let util = s
        .utilization
        .map(|u| format!("{u:.1}%"))
        .unwrap_or_else(|| "?".into());
    format!(
        "#{n} seqno={} tm={} joints={joints} tcp={tcp} motors={motors} rapid={rapid} egm={mci} converged={conv} util={util}",
        s.seqno.map_or("-".into(), |v| v.to_string()),
        s.tm.map_or("-".into(), |v| v.to_string()),
    )
}

fn fmt_list(values: &[f64]) -> String {
    let parts: Vec<String> = values.iter().map(|v| format!("{v:.2}")).collect();
    format!("[{}]", parts.join(","))
}

fn summary(sensor: &BuiltinSensor, send_errors: u64) {
    let st = sensor.stats();
    say!(
        "messages: received {} replied {} undecodable {} incomplete {} sessions {} seqno-gaps {} send-errors {}",
        st.received,
        st.replied,
        st.decode_errors,
        st.incomplete,
        st.sessions,
        st.seqno_gaps,
        send_errors
    );
    print_hist("interval  ", &st.interval);
    print_hist("turnaround", &st.turnaround);
}

fn print_hist(name: &str, h: &LatencyHistogram) {
    say!("{name} {}", h.summary());
}
