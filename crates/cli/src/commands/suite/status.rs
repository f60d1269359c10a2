use std::path::PathBuf;
use std::process::ExitCode;

use rslam_suite::{
    available_bytes, format_bytes, plan, plan_ephemeral, EphemeralPlan, SequenceState, Shard,
    Suite, SuitePlan, SuiteStatus, DATASETS_DIR,
};

#[derive(clap::Args)]
pub struct StatusArgs {
    /// The suite folder (holding suite.toml).
    dir: PathBuf,
    /// Also the plan: frames and bytes per sequence and in all, free space, time to go.
    #[arg(long)]
    plan: bool,
    /// With --plan: sequences in flight in `suite bench --ephemeral`, for its disk need.
    #[arg(long, default_value_t = 1, requires = "plan")]
    jobs: usize,
    /// Print JSON instead of tables.
    #[arg(long)]
    json: bool,
}

pub fn run(args: StatusArgs) -> anyhow::Result<ExitCode> {
    let suite = Suite::open(&args.dir)?;
    let states = suite.shard_states(Shard::WHOLE);
    let status = SuiteStatus::read(&suite, &states)?;
    let planned = if args.plan {
        let planned = plan(&suite.dir, &states)?;
        let ephemeral = plan_ephemeral(&suite, &planned, args.jobs)?;
        Some((planned, ephemeral))
    } else {
        None
    };
    let free = available_bytes(&suite.dir.join(DATASETS_DIR))?;
    if args.json {
        let (plan, ephemeral) = planned.unzip();
        let json = serde_json::json!({
            "status": status, "plan": plan, "ephemeral": ephemeral, "bytes_free": free
        });
        println!("{}", serde_json::to_string_pretty(&json)?);
    } else {
        print!("{}", status.table());
        let count = |label: &str| status.counts.get(label).copied().unwrap_or(0);
        // Frames deleted only where an ephemeral bench deleted some.
        let counts: Vec<String> = SequenceState::LABELS
            .iter()
            .filter(|k| **k != SequenceState::FramesDeleted.label() || count(k) > 0)
            .map(|k| format!("{} {k}", count(k)))
            .collect();
        println!(
            "{} sequences: {}; {} on disk, {} free",
            status.sequences.len(),
            counts.join(", "),
            format_bytes(status.bytes_used),
            format_bytes(free)
        );
        for s in &status.sequences {
            if let SequenceState::Conflict(why) = &s.state {
                println!("conflict: {}: {why}", s.name);
            }
        }
        if let Some((planned, ephemeral)) = &planned {
            print_plan(planned, free);
            print_ephemeral(ephemeral, free);
        }
    }
    Ok(if status.is_complete() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

fn print_plan(plan: &SuitePlan, free: u64) {
    let frames: usize = plan.sequences.iter().map(|s| s.frames_written).sum();
    let measured = plan.sequences.iter().filter(|s| s.bytes_measured).count();
    println!(
        "plan: {frames} frames in all, {} per frame on average ({} of {} sequences measured on disk, the rest estimated)",
        format_bytes(plan.bytes_total / frames.max(1) as u64),
        measured,
        plan.sequences.len()
    );
    println!(
        "      {} for the whole suite; {} still to write, {} free{}",
        format_bytes(plan.bytes_total),
        format_bytes(plan.bytes_to_write),
        format_bytes(free),
        space_warning(plan.bytes_to_write, free)
    );
    println!(
        "      {} frames still to draw: about {} at {:.1} frames/s ({})",
        plan.frames_to_render,
        duration(plan.seconds_to_go),
        plan.frames_per_second,
        plan.rate_source
    );
}

fn print_ephemeral(plan: &EphemeralPlan, free: u64) {
    println!(
        "ephemeral (suite bench --ephemeral --jobs {}): {} at most — the frames of the {} largest sequence(s) {}, what every sequence keeps {}, what the runs keep {}{}",
        plan.jobs,
        format_bytes(plan.bytes_total),
        plan.jobs,
        format_bytes(plan.bytes_in_flight),
        format_bytes(plan.bytes_kept),
        format_bytes(plan.bytes_runs),
        space_warning(plan.bytes_total, free)
    );
    println!("      runs: {}", plan.runs_source);
    match plan.run_seconds_to_go {
        Some(runs) => println!(
            "      about {} to go: the frames above and {} of runs, {} at once",
            duration(plan.seconds_to_go),
            duration(runs),
            plan.jobs
        ),
        None => println!(
            "      about {} to go for the frames, and the methods' own time",
            duration(plan.seconds_to_go)
        ),
    }
}

/// What follows a disk figure that does not fit.
fn space_warning(needed: u64, free: u64) -> &'static str {
    match needed > free {
        true => " — NOT ENOUGH SPACE",
        false => "",
    }
}

fn duration(seconds: f64) -> String {
    let minutes = (seconds / 60.0).round() as u64;
    match minutes {
        0 => format!("{seconds:.0} s"),
        m if m < 120 => format!("{m} min"),
        m => format!("{}.{} h", m / 60, (m % 60) / 6),
    }
}
