//! One target fuzzed in this process until a deadline: mutate a seed, run it, report on stdout.
//! What cannot be caught in-process (an abort, an allocation over the memory cap, an input that
//! runs too long) ends the process; the [`supervisor`](crate::supervisor) finds the input that
//! did it in the `current` file, written before each run.
//!
//! Lines on stdout, tab-separated: `progress N`, `error SIGNATURE` (a new distinct error),
//! `crash FILE MESSAGE`, `done N`.

use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use rslam_core::hash::{fnv1a64, splitmix64};

use crate::mutate::mutate;
use crate::{corpus, finding_key, run_one, signature, Outcome, Scratch, Target};

/// Exit status of a worker whose watchdog found an input running over the time limit.
pub const TIMEOUT_EXIT: i32 = 86;

/// Inputs kept beside the seeds because they gave a new error (mutated further later).
const MAX_LEARNED: usize = 512;

/// How often progress is reported.
const PROGRESS_EVERY: Duration = Duration::from_millis(500);

pub struct WorkerOptions<'a> {
    pub target: &'a Target,
    /// Crashes go to `out/crashes/`, the input being run to `out/<target>.current`.
    pub out: &'a Path,
    pub run_for: Duration,
    pub seed: u64,
    /// Longest time one input may take.
    pub input_limit: Duration,
}

/// The file holding the input being run.
pub fn current_file(out: &Path, target: &str) -> PathBuf {
    out.join(format!("{target}.current"))
}

/// Saves a crashing input as `out/crashes/<target>-<hash>.bin` with its message beside it.
pub fn save_crash(
    out: &Path,
    target: &str,
    input: &[u8],
    message: &str,
) -> std::io::Result<PathBuf> {
    let dir = out.join("crashes");
    std::fs::create_dir_all(&dir)?;
    let stem = format!("{target}-{:016x}", fnv1a64(input));
    std::fs::write(dir.join(format!("{stem}.txt")), format!("{message}\n"))?;
    let path = dir.join(format!("{stem}.bin"));
    std::fs::write(&path, input)?;
    Ok(path)
}

pub fn run_worker(options: &WorkerOptions) -> Result<(), String> {
    let target = options.target;
    let io = |e: std::io::Error| e.to_string();
    let seeds = corpus::seeds(target.name)?;
    let scratch_dir = tempfile::tempdir().map_err(io)?;
    let scratch = Scratch {
        dir: scratch_dir.path().to_path_buf(),
    };
    (target.prepare)(&scratch.dir).map_err(io)?;
    let current = current_file(options.out, target.name);
    let busy_since = Arc::new(AtomicU64::new(0));
    let start = Instant::now();
    start_watchdog(busy_since.clone(), start, options.input_limit);

    let mut pool = seeds.clone();
    let mut errors = HashSet::new();
    let mut crashes = HashSet::new();
    let mut state = options.seed;
    let mut executions = 0u64;
    let mut reported = Instant::now();
    while start.elapsed() < options.run_for {
        let entropy: Vec<u8> = (0..16)
            .flat_map(|_| {
                state = splitmix64(state);
                state.to_le_bytes()
            })
            .collect();
        let parent = &pool[(state % pool.len() as u64) as usize];
        let input = mutate(parent, &seeds, &entropy);
        std::fs::write(&current, &input).map_err(io)?;
        busy_since.store(start.elapsed().as_millis() as u64 + 1, Ordering::SeqCst);
        let outcome = run_one(target, &scratch, &input);
        busy_since.store(0, Ordering::SeqCst);
        executions += 1;
        match outcome {
            Outcome::Accepted => {}
            Outcome::Rejected(message) => {
                let signature = signature(&message, &input, &scratch);
                if errors.insert(signature.clone()) {
                    println!("error\t{signature}");
                    if pool.len() < seeds.len() + MAX_LEARNED {
                        pool.push(input);
                    }
                }
            }
            Outcome::Found(finding) => {
                let message =
                    format!("{}: {}", finding.kind, finding.message).replace(['\n', '\r'], " ⏎ ");
                // One saved input per kind and place of failure.
                if crashes.insert(finding_key(&finding, &scratch)) {
                    let file =
                        save_crash(options.out, target.name, &input, &message).map_err(io)?;
                    println!("crash\t{}\t{message}", file.display());
                }
            }
        }
        if reported.elapsed() >= PROGRESS_EVERY {
            println!("progress\t{executions}");
            reported = Instant::now();
        }
    }
    println!("done\t{executions}");
    Ok(())
}

/// Ends the process when one input runs over `limit` (an infinite loop cannot be caught
/// otherwise); `busy_since` holds the input's start in milliseconds after `start`, plus one, or
/// 0 between inputs.
fn start_watchdog(busy_since: Arc<AtomicU64>, start: Instant, limit: Duration) {
    std::thread::spawn(move || loop {
        std::thread::sleep(Duration::from_millis(50));
        let since = busy_since.load(Ordering::SeqCst);
        if since != 0 && start.elapsed().as_millis() as u64 + 1 - since > limit.as_millis() as u64 {
            eprintln!("timeout: one input ran over {limit:?}");
            std::process::exit(TIMEOUT_EXIT);
        }
    });
}
