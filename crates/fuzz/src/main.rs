//! `rslam-fuzz`: fuzzes every parser (or the named ones) for a given time each and prints, per
//! target, the executions, the distinct errors and the crashes, whose inputs it saves. Exits 1
//! when anything crashed. See `scripts/fuzz.sh`.

use std::alloc::System;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

use cap::Cap;
use clap::{Parser, Subcommand};
use rslam_fuzz::supervisor::{fuzz_target, RunOptions, TargetReport};
use rslam_fuzz::worker::{run_worker, WorkerOptions};
use rslam_fuzz::{run_one, target, Outcome, Scratch, Target, TARGETS};

/// Every allocation goes through the cap; a worker sets it, so that an allocation sized from an
/// unchecked header fails (the process aborts, the supervisor reports the input).
#[global_allocator]
static ALLOCATOR: Cap<System> = Cap::new(System, usize::MAX);

#[derive(Parser)]
#[command(about = "Fuzzes rslam's parsers with mutations of the seed files in crates/fuzz/corpus")]
struct Cli {
    #[command(subcommand)]
    command: Commands,
}

#[derive(Subcommand)]
enum Commands {
    /// Fuzzes each target for SECONDS (all targets unless named).
    Run {
        #[arg(long, default_value_t = 10.0)]
        seconds: f64,
        /// Crash inputs go to OUT/crashes/.
        #[arg(long, default_value = "target/fuzz")]
        out: PathBuf,
        #[arg(long, default_value_t = 0)]
        seed: u64,
        /// Longest time one input may take, in milliseconds.
        #[arg(long, default_value_t = 5000)]
        input_limit_ms: u64,
        /// Bytes a worker may hold, in MiB.
        #[arg(long, default_value_t = 1024)]
        memory_mib: usize,
        /// Targets fuzzed at once, each in a worker process of its own (default: one per core).
        #[arg(long)]
        jobs: Option<usize>,
        targets: Vec<String>,
    },
    /// Lists the targets.
    List,
    /// Runs one saved input (a crash) through its target and says what it does now.
    Replay { target: String, input: PathBuf },
    /// One target in this process (started by `run`).
    #[command(hide = true)]
    Worker {
        target: String,
        #[arg(long)]
        out: PathBuf,
        #[arg(long)]
        seconds: f64,
        #[arg(long)]
        seed: u64,
        #[arg(long)]
        input_limit_ms: u64,
        #[arg(long, default_value_t = 1024)]
        memory_mib: usize,
    },
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(code) => code,
        Err(message) => {
            eprintln!("rslam-fuzz: {message}");
            ExitCode::from(2)
        }
    }
}

fn run(cli: Cli) -> Result<ExitCode, String> {
    match cli.command {
        Commands::List => {
            for t in TARGETS {
                println!("{}", t.name);
            }
            Ok(ExitCode::SUCCESS)
        }
        Commands::Replay {
            target: name,
            input,
        } => {
            let target = target(&name).ok_or(format!("unknown target '{name}'"))?;
            let bytes = std::fs::read(&input).map_err(|e| format!("{}: {e}", input.display()))?;
            let dir = tempfile::tempdir().map_err(|e| e.to_string())?;
            (target.prepare)(dir.path()).map_err(|e| e.to_string())?;
            let scratch = Scratch {
                dir: dir.path().to_path_buf(),
            };
            let outcome = run_one(target, &scratch, &bytes);
            println!("{outcome:?}");
            Ok(match outcome {
                Outcome::Found(_) => ExitCode::FAILURE,
                Outcome::Accepted | Outcome::Rejected(_) => ExitCode::SUCCESS,
            })
        }
        Commands::Worker {
            target: name,
            out,
            seconds,
            seed,
            input_limit_ms,
            memory_mib,
        } => {
            let target = target(&name).ok_or(format!("unknown target '{name}'"))?;
            ALLOCATOR
                .set_limit(ALLOCATOR.allocated() + memory_mib * 1024 * 1024)
                .map_err(|()| "cannot set the memory cap".to_string())?;
            run_worker(&WorkerOptions {
                target,
                out: &out,
                run_for: Duration::from_secs_f64(seconds),
                seed,
                input_limit: Duration::from_millis(input_limit_ms),
            })?;
            Ok(ExitCode::SUCCESS)
        }
        Commands::Run {
            seconds,
            out,
            seed,
            input_limit_ms,
            memory_mib,
            jobs,
            targets,
        } => {
            if !(seconds.is_finite() && seconds > 0.0) {
                return Err(format!("--seconds {seconds}: expected a positive number"));
            }
            let chosen: Vec<_> = if targets.is_empty() {
                TARGETS.iter().collect()
            } else {
                targets
                    .iter()
                    .map(|name| target(name).ok_or(format!("unknown target '{name}' (see `list`)")))
                    .collect::<Result<_, _>>()?
            };
            std::fs::create_dir_all(&out).map_err(|e| format!("{}: {e}", out.display()))?;
            let exe = std::env::current_exe().map_err(|e| e.to_string())?;
            let options = RunOptions {
                exe: &exe,
                out: &out,
                run_for: Duration::from_secs_f64(seconds),
                seed,
                input_limit: Duration::from_millis(input_limit_ms),
                memory_mib,
            };
            let jobs = jobs
                .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
                .max(1);
            let mut crashed = 0;
            for report in fuzz_targets(&chosen, &options, jobs) {
                let report = report?;
                report.print();
                crashed += report.crashes.len();
            }
            println!(
                "crashes: {crashed} (inputs in {})",
                out.join("crashes").display()
            );
            Ok(if crashed == 0 {
                ExitCode::SUCCESS
            } else {
                ExitCode::FAILURE
            })
        }
    }
}

/// Each of `targets` fuzzed with `options`, `jobs` at once; the reports in the targets' order.
fn fuzz_targets(
    targets: &[&Target],
    options: &RunOptions,
    jobs: usize,
) -> Vec<Result<TargetReport, String>> {
    let next = std::sync::atomic::AtomicUsize::new(0);
    let mut reports: Vec<(usize, Result<TargetReport, String>)> = std::thread::scope(|scope| {
        let workers: Vec<_> = (0..jobs.min(targets.len()))
            .map(|_| {
                scope.spawn(|| {
                    let mut done = Vec::new();
                    loop {
                        let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                        let Some(target) = targets.get(i) else {
                            return done;
                        };
                        done.push((i, fuzz_target(target, options)));
                    }
                })
            })
            .collect();
        workers
            .into_iter()
            .flat_map(|w| w.join().expect("a fuzzing thread panicked"))
            .collect()
    });
    reports.sort_by_key(|(i, _)| *i);
    reports.into_iter().map(|(_, report)| report).collect()
}
