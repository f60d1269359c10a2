//! One method process: its own process group (so a timeout or Ctrl-C ends everything it
//! started), stdout and stderr into a log, wall time, and the peak memory of the whole group
//! (summed resident memory of its processes, sampled every 50 ms from /proc).

use std::fs::File;
use std::os::unix::process::{CommandExt, ExitStatusExt};
use std::path::Path;
use std::process::{Command, ExitStatus, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use nix::sys::signal::{killpg, Signal};
use nix::unistd::Pid;

use crate::SuiteError;

const POLL: Duration = Duration::from_millis(50);

#[derive(Clone, Debug, PartialEq)]
pub enum Ending {
    Exited(i32),
    Signalled(i32),
    TimedOut,
    /// Stopped because the run was interrupted (Ctrl-C).
    Interrupted,
}

#[derive(Clone, Debug, PartialEq)]
pub struct ProcessReport {
    pub ending: Ending,
    pub seconds: f64,
    /// Peak summed resident memory of the process group, bytes; `None` where /proc is missing.
    pub peak_rss_bytes: Option<u64>,
}

/// Runs `command` (program and arguments) in `dir` with stdin closed and output into `log`.
pub fn run_process(
    command: &[String],
    dir: &Path,
    log: &Path,
    timeout: Duration,
    interrupted: &AtomicBool,
) -> Result<ProcessReport, SuiteError> {
    let log_file = File::create(log).map_err(|e| SuiteError::io(log, e))?;
    let err_file = log_file.try_clone().map_err(|e| SuiteError::io(log, e))?;
    let started = Instant::now();
    let spawned = Command::new(&command[0])
        .args(&command[1..])
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(log_file)
        .stderr(err_file)
        .process_group(0)
        .spawn();
    let mut child = match spawned {
        Ok(child) => child,
        Err(e) => {
            return Err(SuiteError::option(
                "command",
                format!("cannot start '{}': {e}", command[0]),
            ))
        }
    };
    let group = Pid::from_raw(child.id() as i32);
    let mut peak = group_rss_bytes(child.id());
    let ending = loop {
        if let Some(status) = child.try_wait().map_err(|e| SuiteError::io(log, e))? {
            break ending_of(status);
        }
        if started.elapsed() >= timeout {
            break Ending::TimedOut;
        }
        if interrupted.load(Ordering::SeqCst) {
            break Ending::Interrupted;
        }
        peak = peak.max(group_rss_bytes(child.id()));
        std::thread::sleep(POLL);
    };
    // Whatever the leader left running (or all of it, on a timeout) goes with it.
    let _ = killpg(group, Signal::SIGKILL);
    let _ = child.wait();
    Ok(ProcessReport {
        ending,
        seconds: started.elapsed().as_secs_f64(),
        peak_rss_bytes: peak,
    })
}

fn ending_of(status: ExitStatus) -> Ending {
    match (status.code(), status.signal()) {
        (Some(code), _) => Ending::Exited(code),
        (None, Some(signal)) => Ending::Signalled(signal),
        (None, None) => Ending::Exited(-1),
    }
}

/// Summed VmRSS of the processes in the group led by `leader`.
fn group_rss_bytes(leader: u32) -> Option<u64> {
    let entries = std::fs::read_dir("/proc").ok()?;
    let mut total = 0;
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(pid) = name.to_str().and_then(|n| n.parse::<u32>().ok()) else {
            continue;
        };
        if process_group(pid) == Some(leader) {
            total += resident_bytes(pid).unwrap_or(0);
        }
    }
    Some(total)
}

/// Field 5 of /proc/PID/stat (after the parenthesised command name, which may hold spaces).
fn process_group(pid: u32) -> Option<u32> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    let after_name = &stat[stat.rfind(')')? + 1..];
    after_name.split_whitespace().nth(2)?.parse().ok()
}

fn resident_bytes(pid: u32) -> Option<u64> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let line = status.lines().find(|l| l.starts_with("VmRSS:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(script: &str, timeout_s: f64) -> (ProcessReport, String) {
        let dir = tempfile::tempdir().unwrap();
        let log = dir.path().join("run.log");
        let command = ["sh", "-c", script].map(String::from);
        let report = run_process(
            &command,
            dir.path(),
            &log,
            Duration::from_secs_f64(timeout_s),
            &AtomicBool::new(false),
        )
        .unwrap();
        (report, std::fs::read_to_string(log).unwrap())
    }

    #[test]
    fn exit_codes_signals_and_output_are_kept() {
        let (report, log) = run("echo out; echo err >&2; exit 3", 10.0);
        assert_eq!(report.ending, Ending::Exited(3));
        assert!(log.contains("out") && log.contains("err"), "{log}");
        let (report, _) = run("kill -SEGV $$", 10.0);
        assert_eq!(report.ending, Ending::Signalled(11));
    }

    #[test]
    fn a_timeout_ends_the_whole_group() {
        let dir = tempfile::tempdir().unwrap();
        let marker = dir.path().join("late");
        let script = format!("(sleep 1.5; touch {}) & sleep 30", marker.display());
        let (report, _) = run(&script, 0.5);
        assert_eq!(report.ending, Ending::TimedOut);
        assert!(report.seconds < 5.0);
        std::thread::sleep(Duration::from_secs(2));
        assert!(
            !marker.exists(),
            "the background child was killed with its group"
        );
    }

    #[test]
    fn peak_memory_sees_a_child_that_holds_memory() {
        let (report, _) = run("python3 -c 'import time; b = bytearray(200_000_000); b[::4096] = b\"x\" * len(b[::4096]); time.sleep(0.5)'", 20.0);
        assert_eq!(report.ending, Ending::Exited(0));
        let peak = report.peak_rss_bytes.unwrap();
        assert!(peak > 150_000_000, "{peak}");
    }
}
