//! The end-of-run summary of `rapidvc run` with its wall-clock part taken out, so runs can be
//! compared.

/// `stderr` with the summary line's wall-clock part replaced (`simulated 2.260 s in <wall>,
/// 565 cycles; …`), and the paths of the run's fresh mass storage directories too.
pub fn without_wall_time(stderr: &str) -> String {
    stderr
        .lines()
        .map(|l| match (l.find(" s in "), l.find(" real time)")) {
            (Some(a), Some(b)) if l.starts_with("simulated ") && a < b => {
                format!("{} s in <wall>{}", &l[..a], &l[b + " real time)".len()..])
            }
            // The fresh mass storage directories of a run differ from run to run.
            _ => match l.find("mass storage: ") {
                Some(i) => format!("{}mass storage: <fresh directories>", &l[..i]),
                None => l.to_string(),
            },
        })
        .map(|l| l + "\n")
        .collect()
}
