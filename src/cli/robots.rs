//! `rapidvc robots [--robot NAME]`: the robot models with reach, axis ranges and speeds; and
//! the `--robot NAME` argument type other subcommands use.

use std::fmt::Write as _;
use std::process::ExitCode;
use std::str::FromStr;

use crate::output::number_format::fixed;
use crate::robot::{RobotModel, default_model, model_by_name, models};

/// A robot model chosen on the command line (`--robot "IRB 2600-12/1.85"`, `irb120`, …).
#[derive(Clone, Copy, Debug)]
pub struct RobotArg(pub &'static RobotModel);

impl Default for RobotArg {
    fn default() -> Self {
        RobotArg(default_model())
    }
}

impl FromStr for RobotArg {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        model_by_name(s).map(RobotArg).ok_or_else(|| {
            let names: Vec<&str> = models().iter().map(|m| m.name).collect();
            format!(
                "unknown or ambiguous robot model '{s}'; known models: {} (see `rapidvc robots`)",
                names.join(", ")
            )
        })
    }
}

/// Arguments of `rapidvc robots`.
#[derive(Debug, clap::Args)]
pub struct RobotsArgs {
    /// Show only this model.
    #[arg(long, value_name = "NAME")]
    pub robot: Option<RobotArg>,
}

/// List the models.
pub fn run(args: RobotsArgs) -> ExitCode {
    let list: Vec<&RobotModel> = match args.robot {
        Some(RobotArg(m)) => vec![m],
        None => models().iter().collect(),
    };
    let mut out = String::new();
    for (i, m) in list.iter().enumerate() {
        if i > 0 {
            out.push('\n');
        }
        out.push_str(&describe(m));
    }
    print!("{out}");
    ExitCode::SUCCESS
}

/// A block of text describing one model.
pub fn describe(m: &RobotModel) -> String {
    let mut s = String::new();
    let default = if std::ptr::eq(m, default_model()) {
        "  (default)"
    } else {
        ""
    };
    let _ = writeln!(
        s,
        "{}{default}\n  reach {} mm, max TCP speed {} mm/s",
        m.name,
        fixed(m.reach_mm(), 0),
        fixed(m.vmax_tcp, 0)
    );
    let _ = writeln!(
        s,
        "  {:<14}{:>9}{:>9}{:>9}{:>9}{:>9}{:>9}",
        "axis", 1, 2, 3, 4, 5, 6
    );
    let row = |label: &str, values: [f64; 6], decimals: usize| {
        let mut r = format!("  {label:<14}");
        for v in values {
            let _ = write!(r, "{:>9}", fixed(v, decimals));
        }
        r
    };
    let _ = writeln!(s, "{}", row("min (°)", m.joint_limits.map(|l| l.min), 0));
    let _ = writeln!(s, "{}", row("max (°)", m.joint_limits.map(|l| l.max), 0));
    let _ = writeln!(s, "{}", row("speed (°/s)", m.max_speed, 0));
    let _ = writeln!(s, "{}", row("accel (°/s²)", m.max_accel, 0));
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn robot_argument() {
        let a: RobotArg = "irb2600_12_185".parse().unwrap_or_default();
        assert!(std::ptr::eq(a.0, default_model()));
        let e = "irb9999".parse::<RobotArg>().err().unwrap_or_default();
        assert!(e.contains("IRB 2600-12/1.85"), "{e}");
        let text = describe(default_model());
        assert!(
            text.contains("(default)") && text.contains("reach 1853 mm"),
            "{text}"
        );
        assert!(
            text.contains("speed (°/s)") && text.contains("500"),
            "{text}"
        );
    }
}
