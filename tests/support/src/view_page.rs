//! Reading a view page's embedded data back (the inverse of `src/output/view/encode.rs`), for the
//! view tests.

use serde_json::Value;

/// The data of a replay page.
pub fn page_data(html: &str) -> Value {
    let start = html
        .find(r#"<script type="application/json" id="rapidvc-data">"#)
        .expect("data element");
    let body = &html[start..];
    let open = body.find('>').expect("tag end") + 1;
    let close = body.find("</script>").expect("script end");
    serde_json::from_str(&body[open..close]).expect("data is JSON")
}

/// The TP lines of a page's log (`[time, "tp", text]` entries), in order.
pub fn tp_lines(log: &Value) -> Vec<&str> {
    log.as_array()
        .map(|a| {
            a.iter()
                .filter(|e| e[1] == "tp")
                .filter_map(|e| e[2].as_str())
                .collect()
        })
        .unwrap_or_default()
}

/// A column of differences of quantised integers, as values.
pub fn decode(col: &Value, scale: f64) -> Vec<f64> {
    let mut acc = 0i64;
    col.as_array()
        .expect("column")
        .iter()
        .map(|d| {
            acc += d.as_i64().expect("integer");
            acc as f64 / scale
        })
        .collect()
}

/// A time column (`{unit, d}`) in µs.
pub fn decode_time(col: &Value) -> Vec<i64> {
    let unit = col["unit"].as_i64().expect("unit");
    let mut acc = 0i64;
    col["d"]
        .as_array()
        .expect("column")
        .iter()
        .map(|d| {
            acc += d.as_i64().expect("integer");
            acc * unit
        })
        .collect()
}

/// The kept motion rows: times (µs), joints, TCP.
pub struct Rows {
    pub t: Vec<i64>,
    pub j: [Vec<f64>; 6],
    pub p: [Vec<f64>; 3],
}

impl Rows {
    pub fn of(data: &Value) -> Rows {
        let r = &data["rows"];
        Rows {
            t: decode_time(&r["t"]),
            j: std::array::from_fn(|a| decode(&r["j"][a], 1e3)),
            p: std::array::from_fn(|a| decode(&r["p"][a], 1e2)),
        }
    }

    /// Joints and TCP interpolated at `t` (µs), as the page does.
    pub fn at(&self, t: i64) -> ([f64; 6], [f64; 3]) {
        let n = self.t.len();
        let k = self.t.partition_point(|&x| x <= t).saturating_sub(1);
        let k2 = (k + 1).min(n - 1);
        let span = (self.t[k2] - self.t[k]) as f64;
        let f = if span > 0.0 {
            ((t - self.t[k]) as f64 / span).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let lerp = |c: &Vec<f64>| c[k] + (c[k2] - c[k]) * f;
        (
            std::array::from_fn(|a| lerp(&self.j[a])),
            std::array::from_fn(|a| lerp(&self.p[a])),
        )
    }
}

/// One trace row: time (µs), joints, TCP, line.
pub struct TraceRow {
    pub t: i64,
    pub joints: [f64; 6],
    pub tcp: [f64; 3],
    pub line: Option<u32>,
}

/// The rows of a `--trace` file.
pub fn read_trace(path: &std::path::Path) -> Vec<TraceRow> {
    let text = std::fs::read_to_string(path).expect("trace");
    text.lines()
        .skip(1)
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            let num = |k: usize| f[k].parse::<f64>().expect("number");
            TraceRow {
                t: (num(0) * 1e6).round() as i64,
                joints: std::array::from_fn(|a| num(1 + a)),
                tcp: std::array::from_fn(|a| num(7 + a)),
                line: f.get(17).and_then(|s| s.parse().ok()),
            }
        })
        .collect()
}

/// A `rapidvc run PROGRAM --view-live` started in `dir`, with its printed page address.
pub struct LiveRun {
    pub child: std::process::Child,
    /// The rest of rapidvc's standard error, after the `live view: URL` line.
    pub stderr: std::io::BufReader<std::process::ChildStderr>,
    /// The page's address as printed (`http://127.0.0.1:PORT/`).
    pub url: String,
}

impl LiveRun {
    /// Starts the run (`rapidvc`: the command from [`crate::rapidvc!`]; standard output
    /// discarded) and reads the address from its first line of standard error.
    pub fn start(
        mut rapidvc: std::process::Command,
        dir: &std::path::Path,
        program: &str,
    ) -> LiveRun {
        use std::io::BufRead;
        use std::process::Stdio;
        let mut child = rapidvc
            .args(["run", program, "--view-live"])
            .current_dir(dir)
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .expect("start rapidvc");
        let mut stderr = std::io::BufReader::new(child.stderr.take().expect("piped stderr"));
        let mut first = String::new();
        stderr.read_line(&mut first).expect("stderr");
        let url = first
            .strip_prefix("live view: ")
            .and_then(|r| r.split_whitespace().next())
            .unwrap_or_else(|| panic!("no URL in {first:?}"))
            .to_string();
        LiveRun { child, stderr, url }
    }

    /// Waits for the run to end: its exit status and the rest of its standard error.
    pub fn finish(mut self) -> (std::process::ExitStatus, String) {
        use std::io::Read;
        let status = self.child.wait().expect("rapidvc ends");
        let mut rest = String::new();
        self.stderr.read_to_string(&mut rest).expect("stderr");
        (status, rest)
    }
}
