use std::path::PathBuf;
use std::process::ExitCode;

use rslam_suite::{
    available_bytes, format_bytes, plan, Shard, Suite, SuitePlan, SuiteStatus, DATASETS_DIR,
};

#[derive(clap::Args)]
pub struct StatusArgs {
    /// The suite folder (holding suite.toml).
    dir: PathBuf,
    /// Also the plan: frames and bytes per sequence and in all, free space, time to go.
    #[arg(long)]
    plan: bool,
    /// Print JSON instead of tables.
    #[arg(long)]
    json: bool,
}

pub fn run(args: StatusArgs) -> anyhow::Result<ExitCode> {
    let suite = Suite::open(&args.dir)?;
    let states = suite.shard_states(Shard::WHOLE);
    let status = SuiteStatus::read(&suite, &states)?;
    let planned = if args.plan {
        Some(plan(&suite.dir, &states)?)
    } else {
        None
    };
    let free = available_bytes(&suite.dir.join(DATASETS_DIR))?;
    if args.json {
        let json = serde_json::json!({ "status": status, "plan": planned, "bytes_free": free });
        println!("{}", serde_json::to_string_pretty(&json)?);
    } else {
        print!("{}", status.table());
        let counts: Vec<String> = ["complete", "partial", "missing", "conflict"]
            .iter()
            .map(|k| format!("{} {k}", status.counts.get(k).copied().unwrap_or(0)))
            .collect();
        println!(
            "{} sequences: {}; {} on disk, {} free",
            status.sequences.len(),
            counts.join(", "),
            format_bytes(status.bytes_used),
            format_bytes(free)
        );
        for s in &status.sequences {
            if let rslam_suite::SequenceState::Conflict(why) = &s.state {
                println!("conflict: {}: {why}", s.name);
            }
        }
        if let Some(planned) = &planned {
            print_plan(planned, free);
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
        if plan.bytes_to_write > free {
            " — NOT ENOUGH SPACE"
        } else {
            ""
        }
    );
    println!(
        "      {} frames still to draw: about {} at {:.1} frames/s ({})",
        plan.frames_to_render,
        duration(plan.seconds_to_go),
        plan.frames_per_second,
        plan.rate_source
    );
}

fn duration(seconds: f64) -> String {
    let minutes = (seconds / 60.0).round() as u64;
    match minutes {
        0 => format!("{seconds:.0} s"),
        m if m < 120 => format!("{m} min"),
        m => format!("{}.{} h", m / 60, (m % 60) / 6),
    }
}
