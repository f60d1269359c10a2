//! Runs each target in a worker process for its share of time, restarts a worker that died
//! (saving the input that killed it), and sums up per target: executions, distinct errors,
//! crashes.

use std::collections::BTreeSet;
use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::worker::{current_file, save_crash, TIMEOUT_EXIT};
use crate::Target;

/// Workers that die this many times give their target up (a crash on nearly every input).
const MAX_RESTARTS: usize = 50;

/// What one target's fuzzing found.
#[derive(Debug, Default)]
pub struct TargetReport {
    pub name: String,
    pub executions: u64,
    pub errors: BTreeSet<String>,
    /// `kind: message (saved input)` per crash.
    pub crashes: Vec<String>,
}

pub struct RunOptions<'a> {
    /// The `rslam-fuzz` executable to start workers from.
    pub exe: &'a Path,
    pub out: &'a Path,
    pub run_for: Duration,
    pub seed: u64,
    pub input_limit: Duration,
    pub memory_mib: usize,
}

pub fn fuzz_target(target: &Target, options: &RunOptions) -> Result<TargetReport, String> {
    let mut report = TargetReport {
        name: target.name.to_string(),
        ..TargetReport::default()
    };
    let start = Instant::now();
    for restart in 0..=MAX_RESTARTS {
        let left = options.run_for.saturating_sub(start.elapsed());
        if left.is_zero() {
            break;
        }
        let mut child = Command::new(options.exe)
            .arg("worker")
            .arg(target.name)
            .arg("--out")
            .arg(options.out)
            .arg("--seconds")
            .arg(left.as_secs_f64().to_string())
            .arg("--seed")
            .arg((options.seed ^ (restart as u64).wrapping_mul(0x9e37_79b9)).to_string())
            .arg("--input-limit-ms")
            .arg(options.input_limit.as_millis().to_string())
            .arg("--memory-mib")
            .arg(options.memory_mib.to_string())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|e| format!("{}: {e}", options.exe.display()))?;
        let stdout = child.stdout.take().ok_or("worker without stdout")?;
        let mut executions = 0;
        for line in BufReader::new(stdout).lines() {
            let line = line.map_err(|e| e.to_string())?;
            let (tag, rest) = line.split_once('\t').unwrap_or((&line, ""));
            match (tag, rest.split_once('\t')) {
                ("progress" | "done", _) => executions = rest.parse().unwrap_or(executions),
                ("error", _) => {
                    report.errors.insert(rest.to_string());
                }
                ("crash", Some((file, message))) => {
                    report.crashes.push(format!("{message} (input: {file})"));
                }
                _ => eprintln!("{}: {line}", target.name),
            }
        }
        let mut stderr = String::new();
        if let Some(mut pipe) = child.stderr.take() {
            // A dead worker's last words; unreadable ones are not worth failing over.
            let _ = pipe.read_to_string(&mut stderr);
        }
        let status = child.wait().map_err(|e| e.to_string())?;
        report.executions += executions;
        if status.success() {
            break;
        }
        report.executions += 1; // the input that killed it
        let kind = if status.code() == Some(TIMEOUT_EXIT) {
            "input over the time limit"
        } else if stderr.contains("memory allocation of") {
            "allocation over the memory cap"
        } else {
            "worker died"
        };
        // The line that says why: the allocation that failed, the watchdog's, else the last.
        let last = stderr
            .lines()
            .find(|l| l.contains("memory allocation of") || l.starts_with("timeout:"))
            .or_else(|| stderr.lines().last())
            .unwrap_or("")
            .trim()
            .to_string();
        let message = format!("{kind} ({status}): {last}");
        let input = std::fs::read(current_file(options.out, target.name))
            .map_err(|e| format!("the input that killed the {} worker: {e}", target.name))?;
        let file: PathBuf =
            save_crash(options.out, target.name, &input, &message).map_err(|e| e.to_string())?;
        report
            .crashes
            .push(format!("{message} (input: {})", file.display()));
    }
    Ok(report)
}

impl TargetReport {
    /// One summary line, then one line per crash.
    pub fn print(&self) {
        println!(
            "{:<13} {:>10} executions {:>5} distinct errors {:>3} crashes",
            self.name,
            self.executions,
            self.errors.len(),
            self.crashes.len()
        );
        for crash in &self.crashes {
            println!("    crash: {crash}");
        }
    }
}
