use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context;
use rslam_core::trajectory_io::{read_trajectory_with, ReadOptions, TrajectoryFormat};
use rslam_eval::multi_agent::{
    agents_from_pairs, agents_in_folder, multi_agent_report, read_and_evaluate_agents, AgentFiles,
};
use rslam_eval::runs::{evaluate_runs_into, summary_text, RunsOptions, DEFAULT_FAILURE_ATE};
use rslam_eval::{
    dataset_of, dynamic_ate, evaluate_files, plot_evaluation, read_dynamic_fractions, text_report,
    AlignMode, DeltaUnit, EvalError, EvalOptions, Matching, RpeOptions, DEFAULT_MAX_DIFF,
};

const DETAILS: &str = "\
Numbers as evo 1.38.1 computes them (evo_ape / evo_rpe). Note the order: `rslam eval EST GT`; evo
takes the ground truth first.

Files: TUM (t tx ty tz qx qy qz qw), Replica traj.txt (16 numbers, row-major 4x4 camera-to-world;
frame i at i / --rate), KITTI (12 numbers, row-major 3x4; matched by index unless --kitti-times),
EuRoC ground truth (t[ns],px,py,pz,qw,qx,qy,qz,...) or COLMAP images.txt (world-to-camera per
image, in name order, image i at i / --rate), detected from the content; or a ROS 2 bag
folder: the header-stamped poses of a PoseStamped, PoseWithCovarianceStamped or Odometry topic, or
of the transforms to one frame on a TF topic (--est-topic / --gt-topic TOPIC or TOPIC:CHILD).

Association (as evo): every pose of the trajectory with fewer poses (the estimate on a tie) takes the
pose of the other with the nearest timestamp; kept if |dt| <= --max-diff (not one-to-one).
ATE: Umeyama alignment on positions (--align), then |p_est - p_gt| per pose.
RPE: pose pairs (i, j) chosen on the estimate (consecutive unless --all-pairs),
E = (Q_i^-1 Q_j)^-1 (P_i^-1 P_j); translation |t_E| in m, rotation angle of R_E in degrees.

SR (success rate of tracking) = covered ground-truth path / ground-truth path: the summed length of
the segments between consecutive ground-truth poses that both have an associated estimate pose (the
pairs above, same --max-diff), over the path length of the whole ground truth (every pose of its
file). In [0, 1], scale-free, and jitter does not change it; an estimate that starts late, stops
early or has gaps gets less. A lost tracker that keeps reporting a pose still covers: ATE shows it.
It needs an estimate pose per ground-truth pose: against a ground truth sampled faster than the
estimate (TUM's 100 Hz motion capture) or with a keyframe-only estimate, few segments are covered.
SR path ratio (sr_path_ratio) = L_est / L_gt, the paper's literal SR formula: the path length of the
whole estimate (multiplied by the Sim(3) scale with --align sim3) over that of the whole ground
truth. Jitter adds path length, so it grows when tracking gets worse and can exceed 1; it is kept
only for comparing with the paper.
Tracked fraction = ground-truth poses with an associated estimate pose / all ground-truth poses.
No reference tool computes these; they are rslam's definitions (the book's Evaluation chapter, docs/src/metrics.md, section SR).

--runs DIR --datasets DIR: evaluates DIR/<method>/<sequence>.txt (or DIR/<method>/<sequence>/<repeat>.txt)
against the ground truth in DATASETS/<sequence>/traj.txt, groundtruth.txt, (EuRoC)
mav0/state_groundtruth_estimate0/data.csv, (TUM-VI) mav0/mocap0/data.csv or, in a ROS 2 bag
(metadata.yaml), its one pose topic. A sequence named
<scene>__<setting> belongs to that setting (room0__fog-3), a bare <scene> is clean. A run is a
failure when a runner left <repeat>.failed (or <sequence>.failed) for it, a text file whose first
line is the reason (an empty one: 'failed (no reason given)'); a .failed beside a .txt of the same
name wins, the .txt is not evaluated. Other files (.json, .log) are ignored. Missing, empty,
unreadable or unassociable estimates are failures too. A failure counts as ATE = --failure-ate;
SR, SR path ratio and tracked fraction 0; marked F. Writes report.html (everything below in one
file that opens offline, figures inline), report.md, report.json, ate.csv, sr.csv,
sr_path_ratio.csv, tracked_fraction.csv, csr.csv, csr_curve.csv, welch.csv, runs.csv, csr.png,
csr.svg and bars/<category>.png/.svg into --out: ATE, SR, SR path ratio and tracked fraction per
method x setting with mean/max (mean/min for the last three), the survival upper bound (best
method per setting, and its mean per category), CSR at 0.02/0.1/1.0 m and as curves (failures
stay in the denominator and never count as successes), mean ATE and SR per setting as bars, one
figure per category (fog, depth_missing, rot, ...), and Welch's t-test of ln ATE of each setting
against clean per method, over scenes and repeats.

--agent EST GT (repeated, one per agent) or --agents DIR (DIR/<agent>/estimate.txt with
DIR/<agent>/traj.txt, groundtruth.txt, mav0/state_groundtruth_estimate0/data.csv or
mav0/mocap0/data.csv): several
agents of one multi-agent system, all in one world frame. Each agent is associated as above,
then aligned twice: on its own (--align), and by ONE
joint alignment of the same mode fitted over every agent's pairs together and applied to every
agent, as a multi-agent system is judged. Prints per agent the ATE (RMSE, m) and SSE under its own
alignment and under the joint one, and the joint ATE and SSE over all pairs. SSE = the sum of
squared position errors |p_est - p_gt|^2 (m^2) over the associated pairs after alignment (= n *
RMSE^2). RPE and SR are not computed for agents.";

#[derive(clap::Args)]
#[command(
    after_long_help = DETAILS,
    args_conflicts_with_subcommands = true,
    subcommand_negates_reqs = true
)]
pub struct EvalArgs {
    #[command(subcommand)]
    command: Option<EvalCommand>,
    /// Estimated trajectory.
    #[arg(
        required_unless_present_any = ["runs", "agent", "agents"],
        conflicts_with_all = ["runs", "agent", "agents"]
    )]
    est: Option<PathBuf>,
    /// Ground-truth trajectory.
    #[arg(
        required_unless_present_any = ["runs", "agent", "agents"],
        conflicts_with_all = ["runs", "agent", "agents"]
    )]
    gt: Option<PathBuf>,
    /// One agent of a multi-agent system (its estimate and ground truth, all agents in one world
    /// frame); repeat for each agent. Per-agent and joint ATE and SSE.
    #[arg(
        long,
        num_args = 2,
        value_names = ["EST", "GT"],
        action = clap::ArgAction::Append,
        conflicts_with_all = ["runs", "agents", "plot"]
    )]
    agent: Vec<PathBuf>,
    /// A folder of agents: DIR/<agent>/estimate.txt with DIR/<agent>/traj.txt, groundtruth.txt,
    /// mav0/state_groundtruth_estimate0/data.csv or mav0/mocap0/data.csv.
    #[arg(long, value_name = "DIR", conflicts_with_all = ["runs", "plot"])]
    agents: Option<PathBuf>,
    /// Force the file format instead of detecting it: tum, replica, kitti, euroc, colmap (a
    /// COLMAP images.txt) or nerfstudio (a camera_path.json or transforms.json); a ROS 2 bag
    /// folder is read as ros2.
    #[arg(long)]
    format: Option<TrajectoryFormat>,
    /// When EST is a ROS 2 bag: its topic of PoseStamped, PoseWithCovarianceStamped or Odometry
    /// messages, or TOPIC:CHILD for the transforms to frame CHILD on a TF topic (default: the
    /// bag's one pose topic).
    #[arg(long, value_name = "TOPIC")]
    est_topic: Option<String>,
    /// When GT is a ROS 2 bag: its pose topic, as --est-topic (rslam's bags hold
    /// /ground_truth/pose).
    #[arg(long, value_name = "TOPIC")]
    gt_topic: Option<String>,
    /// Frame rate of Replica traj.txt and COLMAP images.txt files (frame i gets timestamp
    /// i / rate), Hz.
    #[arg(long, default_value_t = ReadOptions::DEFAULT_REPLICA_RATE_HZ)]
    rate: f64,
    /// KITTI times file (one timestamp in seconds per line) for KITTI pose files.
    #[arg(long, value_name = "FILE")]
    kitti_times: Option<PathBuf>,
    /// Largest timestamp difference of an associated pair, seconds (inclusive).
    #[arg(long, default_value_t = DEFAULT_MAX_DIFF)]
    max_diff: f64,
    /// Added to the estimate's timestamps before association, seconds.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    t_offset: f64,
    /// Alignment of the estimate onto the ground truth: se3 (RGB-D), sim3 (monocular) or none.
    #[arg(long, default_value_t = AlignMode::Se3)]
    align: AlignMode,
    /// RPE step, in --delta-unit.
    #[arg(long, default_value_t = 1.0)]
    delta: f64,
    /// Unit of --delta: f (frames), m (metres travelled) or deg (degrees turned).
    #[arg(long, default_value_t = DeltaUnit::Frames)]
    delta_unit: DeltaUnit,
    /// RPE over overlapping pairs from every pose instead of consecutive pairs.
    #[arg(long)]
    all_pairs: bool,
    /// Also the ATE over the frames whose dynamic fraction (the share of pixels people cover,
    /// from the instance masks of GT's dataset: `extra.masks` in the rslam.json beside it)
    /// exceeds this fraction; aligned over all frames as the ATE is.
    #[arg(long, value_name = "FRACTION", conflicts_with_all = ["runs", "agent", "agents"])]
    dynamic_above: Option<f64>,
    /// Print one JSON object instead of the report.
    #[arg(long)]
    json: bool,
    /// Draw the top view of both trajectories and the per-pose error (.png or .svg).
    #[arg(long, value_name = "FILE", conflicts_with = "runs")]
    plot: Option<PathBuf>,
    /// Aggregate many runs: DIR/<method>/<sequence>.txt, or <sequence>/<repeat>.txt and .failed.
    #[arg(long, value_name = "DIR", requires = "datasets")]
    runs: Option<PathBuf>,
    /// Folder holding the datasets by sequence name (with --runs).
    #[arg(long, value_name = "DIR", requires = "runs")]
    datasets: Option<PathBuf>,
    /// Where --runs writes its tables and curves.
    #[arg(
        long,
        value_name = "DIR",
        requires = "runs",
        default_value = "rslam-eval-report"
    )]
    out: PathBuf,
    /// ATE counted for a failed run (with --runs), metres.
    #[arg(long, default_value_t = DEFAULT_FAILURE_ATE, requires = "runs")]
    failure_ate: f64,
}

/// Beside `rslam eval EST GT`: a first argument `recon` is this subcommand, not a file name.
#[derive(clap::Subcommand)]
enum EvalCommand {
    /// Mapping metrics of a reconstructed mesh or point cloud against the ground-truth mesh:
    /// accuracy, completion (cm) and completion ratio (%).
    Recon(super::eval_recon::ReconArgs),
}

pub fn run(args: EvalArgs) -> anyhow::Result<ExitCode> {
    if let Some(EvalCommand::Recon(recon)) = args.command {
        return super::eval_recon::run(recon);
    }
    let read = ReadOptions {
        format: args.format,
        replica_rate_hz: args.rate,
        kitti_times: args.kitti_times.clone(),
        topic: None,
        dataparser_transforms: None,
    };
    let options = EvalOptions {
        matching: Matching::Time {
            max_diff: args.max_diff,
            t_offset: args.t_offset,
        },
        align: args.align,
        rpe: RpeOptions {
            delta: args.delta,
            delta_unit: args.delta_unit,
            all_pairs: args.all_pairs,
        },
    };
    if let Some(dir) = &args.agents {
        let files = agents_in_folder(dir)?;
        return run_agents(&args, &files, &read, options.matching);
    }
    if !args.agent.is_empty() {
        let files = agents_from_pairs(&args.agent)?;
        return run_agents(&args, &files, &read, options.matching);
    }
    match (&args.runs, &args.datasets, &args.est, &args.gt) {
        (Some(runs), Some(datasets), _, _) => run_many(&args, runs, datasets, read, options),
        (_, _, Some(est), Some(gt)) => run_one(&args, est, gt, &read, &options),
        _ => anyhow::bail!("give EST and GT, or --runs DIR --datasets DIR"),
    }
}

fn run_one(
    args: &EvalArgs,
    est: &Path,
    gt: &Path,
    read: &ReadOptions,
    options: &EvalOptions,
) -> anyhow::Result<ExitCode> {
    let with_topic = |topic: &Option<String>| ReadOptions {
        topic: topic.clone(),
        ..read.clone()
    };
    let evaluation = read_trajectory_with(est, &with_topic(&args.est_topic))
        .and_then(|est| Ok((est, read_trajectory_with(gt, &with_topic(&args.gt_topic))?)))
        .map_err(EvalError::from)
        .and_then(|(est, gt)| evaluate_files(&est, &gt, options))
        .with_context(|| format!("evaluating {} against {}", est.display(), gt.display()))?;
    let dynamic = match args.dynamic_above {
        Some(threshold) => Some(
            read_dynamic_fractions(dataset_of(gt))
                .and_then(|fractions| dynamic_ate(&evaluation, &fractions, threshold))
                .with_context(|| format!("--dynamic-above: {}", gt.display()))?,
        ),
        None => None,
    };
    if args.json {
        let mut json = serde_json::to_value(&evaluation)?;
        if let Some(dynamic) = &dynamic {
            json["dynamic_ate"] = serde_json::to_value(dynamic)?;
        }
        println!("{}", serde_json::to_string_pretty(&json)?);
    } else {
        print!("{}", text_report(&evaluation));
        if let Some(d) = &dynamic {
            let frames = format!(
                "{} of {} frames with more than {} of the view moving",
                d.dynamic_frames, d.frames, d.threshold
            );
            match &d.ate {
                Some(ate) => println!(
                    "ATE on dynamic frames (m): rmse {:.6}  mean {:.6}  max {:.6}  ({} pairs; {frames})",
                    ate.rmse, ate.mean, ate.max, ate.n
                ),
                None => println!("ATE on dynamic frames: no estimate pose on them ({frames})"),
            }
        }
    }
    if let Some(plot) = &args.plot {
        plot_evaluation(plot, &evaluation)?;
        eprintln!("plot written to {}", plot.display());
    }
    Ok(ExitCode::SUCCESS)
}

fn run_agents(
    args: &EvalArgs,
    files: &[AgentFiles],
    read: &ReadOptions,
    matching: Matching,
) -> anyhow::Result<ExitCode> {
    let evaluation = read_and_evaluate_agents(files, read, matching, args.align)?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&evaluation)?);
    } else {
        print!("{}", multi_agent_report(&evaluation));
    }
    Ok(ExitCode::SUCCESS)
}

fn run_many(
    args: &EvalArgs,
    runs: &Path,
    datasets: &Path,
    read: ReadOptions,
    eval: EvalOptions,
) -> anyhow::Result<ExitCode> {
    let options = RunsOptions {
        runs_dir: runs.to_path_buf(),
        datasets_dir: datasets.to_path_buf(),
        read,
        eval,
        failure_ate: args.failure_ate,
        skip_dir: Some(args.out.clone()),
    };
    let (report, written) = evaluate_runs_into(&options, &args.out)
        .with_context(|| format!("evaluating the runs in {}", runs.display()))?;
    for path in &report.unmatched {
        eprintln!(
            "warning: ignored {} (no dataset of that name)",
            path.display()
        );
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print!("{}", summary_text(&report));
        println!("\nwritten:");
        for path in written {
            println!("  {}", path.display());
        }
    }
    Ok(ExitCode::SUCCESS)
}
