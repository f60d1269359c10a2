use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use rslam_core::dataset::read_views;
use rslam_eval::recon::{
    evaluate_reconstruction, recon_text_report, Culling, ReconOptions, DEFAULT_RECON_SAMPLES,
    DEFAULT_THRESHOLD_CM,
};

const DETAILS: &str = "\
Mapping metrics as the CO-SLAM protocol defines them, with points P sampled on the reconstruction
and Q on the ground-truth mesh (both in metres):
  accuracy (cm)          = mean over p in P of the distance from p to the ground truth
  completion (cm)        = mean over q in Q of the distance from q to the reconstruction
  completion ratio (%)   = share of q in Q closer than --threshold-cm to the reconstruction

Sampling: --samples points uniformly by area on each mesh's triangles, drawn from --seed alone
(the same numbers on any machine and thread count). A reconstruction without faces is a point
cloud: its points are the samples, subsampled to --samples with the seed when it has more.

Distances are to the other side's surface: to the nearest point of the nearest triangle of the
mesh (through a BVH), or to the nearest point of a point cloud (all of its points). CO-SLAM's
code measures to the other side's sampled points (KD-tree) instead, which adds the other side's
sampling spacing to every distance; against the surface, a mesh against itself gives 0 cm and
100 %.

Culling (--cull), before the means are taken, of the sampled points of both sides, to what the
ground-truth cameras of --dataset DIR saw (its ground-truth poses, every camera of a rig, every
agent of a folder of agents; intrinsics from its manifest or camera file):
  none      every point (the whole ground-truth mesh: on a sequence that saw part of the scene,
            completion measures how much it did not see)
  frustum   points in front of some camera, inside its image and its depth files' range
            (NICE-SLAM, Co-SLAM)
  visible   of those, points the camera saw past the ground-truth mesh: nothing of it nearer
            than 2 cm of z-depth in front of them (Co-SLAM's occlusion culling, applied to the
            ground truth too so that completion measures the observed surface). The default.
The reconstruction must be in the scene's world frame (no alignment is applied).

Input: PLY, ASCII or binary, with or without faces (polygons are split into triangles);
coordinates in metres. The ground truth must be a mesh: `rslam scene export SCENE|MESH --out
gt.ply` writes it for a built-in scene or converts an OBJ/glTF mesh.";

#[derive(clap::Args)]
#[command(after_long_help = DETAILS)]
pub struct ReconArgs {
    /// Reconstructed mesh or point cloud (.ply, metres).
    reconstruction: PathBuf,
    /// Ground-truth mesh (.ply, metres), e.g. from `rslam scene export`.
    #[arg(long, value_name = "FILE")]
    gt: PathBuf,
    /// Points sampled on each surface.
    #[arg(long, default_value_t = DEFAULT_RECON_SAMPLES)]
    samples: usize,
    /// Seed of the sampling.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// The dataset whose ground-truth cameras the culling uses (Replica, TUM, EuRoC, or a folder
    /// of agents).
    #[arg(long, value_name = "DIR")]
    dataset: Option<PathBuf>,
    /// What of each surface is measured: none, frustum or visible (see below).
    #[arg(long, default_value_t = Culling::default())]
    cull: Culling,
    /// Completion ratio threshold, cm.
    #[arg(long, default_value_t = DEFAULT_THRESHOLD_CM)]
    threshold_cm: f64,
    /// Print one JSON object instead of the report.
    #[arg(long)]
    json: bool,
}

pub fn run(args: ReconArgs) -> anyhow::Result<ExitCode> {
    let options = ReconOptions {
        samples: args.samples,
        seed: args.seed,
        threshold_cm: args.threshold_cm,
        culling: args.cull,
    };
    let views = match &args.dataset {
        Some(dir) => Some(read_views(dir).context("reading the ground-truth cameras")?),
        None => None,
    };
    let metrics = evaluate_reconstruction(&args.reconstruction, &args.gt, &options, views.as_ref())
        .with_context(|| {
            format!(
                "evaluating {} against {}",
                args.reconstruction.display(),
                args.gt.display()
            )
        })?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&metrics)?);
    } else {
        print!("{}", recon_text_report(&metrics));
    }
    Ok(ExitCode::SUCCESS)
}
