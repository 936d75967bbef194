//! The text of an RL update (`trace --rl`), and the update log (`rl --set update-log-path`)
//! that keeps the same lines in a file while the trace is on (Soar manual, ch. 9, `rl`).

use std::io::Write;

/// `RL update RULE ecr efr value -> ecr efr value`, numbers as 9.6 prints them (six
/// significant digits).
pub(crate) fn update_line(rule: &str, before: [f64; 3], after: [f64; 3]) -> String {
    let g = |x: f64| crate::printer::constants::c_general(x, 6);
    format!(
        "RL update {rule} {} {} {} -> {} {} {}",
        g(before[0]),
        g(before[1]),
        g(before[2]),
        g(after[0]),
        g(after[1]),
        g(after[2])
    )
}

/// Appends one line to the update log, making the file if it is not there.
pub(crate) fn append(path: &str, line: &str) -> std::io::Result<()> {
    let mut file = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(path)?;
    writeln!(file, "{line}")
}

/// The rule's documentation under `rl --set meta on`: its update count and its
/// delta-bar-delta trace.
pub(crate) fn meta_text(updates: f64, dbd_h: f64) -> String {
    let g = |x: f64| crate::printer::constants::c_general(x, 6);
    format!("rl-updates={};delta-bar-delta-h={};", g(updates), g(dbd_h))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_print_six_significant_digits() {
        let line = update_line("r", [0.0, -0.00277934, -0.00277934], [4.0, 0.5, 4.5]);
        assert_eq!(line, "RL update r 0 -0.00277934 -0.00277934 -> 4 0.5 4.5");
        assert_eq!(meta_text(6.0, 0.0), "rl-updates=6;delta-bar-delta-h=0;");
    }

    #[test]
    fn the_log_grows_line_by_line_and_a_bad_path_is_an_error() {
        let dir = std::env::temp_dir().join(format!("rusoar-rl-log-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("updates.log");
        let p = path.to_str().unwrap();
        append(p, "one").unwrap();
        append(p, "two").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "one\ntwo\n");
        assert!(append(dir.to_str().unwrap(), "a folder").is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
