use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use clap::{Args, Subcommand};
use rslam_core::splat_io::write_splat_ply;
use rslam_render::load_scene;
use rslam_render::scene::{export, BUILTIN_SCENES};
use rslam_render::splat::capture_of_mesh;

#[derive(Args)]
pub struct SceneArgs {
    #[command(subcommand)]
    command: SceneCommand,
}

#[derive(Subcommand)]
enum SceneCommand {
    /// Write a scene's ground-truth triangle mesh: world frame, metres, binary PLY with vertex
    /// colours (textures baked to their mean colour); with --gaussians, a Gaussian-splat capture
    /// of it instead.
    Export {
        /// Built-in scene (room0 … office4) or a mesh file (.ply, .gltf, .glb, .obj).
        scene: String,
        #[arg(long)]
        out: PathBuf,
        /// Write a capture of about N Gaussians (3DGS PLY, metres): flat discs sampled over the
        /// surfaces by area, as wide as their spacing, coloured by the surface under each.
        #[arg(long)]
        gaussians: Option<usize>,
    },
    /// Write a built-in scene's default trajectory as a Replica traj.txt (2000 poses, 20 Hz).
    Traj {
        /// Built-in scene (room0 … office4).
        scene: String,
        #[arg(long)]
        out: PathBuf,
    },
    /// Per-frame image statistics to set beside real data: FAST corners at ORB-SLAM's threshold,
    /// gradient magnitudes, saturation, low-texture cells.
    Stats(super::scene_stats::StatsArgs),
    /// List the built-in scenes.
    List,
}

pub fn run(args: SceneArgs) -> anyhow::Result<ExitCode> {
    match args.command {
        SceneCommand::Export {
            scene,
            out,
            gaussians: Some(count),
        } => {
            let loaded = load_scene(&scene)?;
            anyhow::ensure!(count > 0, "--gaussians 0: expected at least one Gaussian");
            anyhow::ensure!(
                loaded.splats.is_none(),
                "'{scene}' is a Gaussian-splat capture already: --gaussians samples a mesh"
            );
            let cloud = capture_of_mesh(&loaded, count);
            std::fs::write(&out, write_splat_ply(&cloud))
                .with_context(|| format!("writing {}", out.display()))?;
            println!(
                "wrote {}: a capture of {} Gaussians of '{scene}'",
                out.display(),
                cloud.len()
            );
        }
        SceneCommand::Export {
            scene,
            out,
            gaussians: None,
        } => {
            let loaded = load_scene(&scene)?;
            export::write_ply(&loaded, &out)
                .with_context(|| format!("exporting scene '{scene}'"))?;
            println!(
                "wrote {}: {} triangles, content hash {}",
                out.display(),
                loaded.mesh.triangle_count(),
                loaded.content_hash()
            );
        }
        SceneCommand::Traj { scene, out } => {
            let loaded = load_scene(&scene)?;
            let trajectory = loaded.default_trajectory.with_context(|| {
                format!(
                    "scene '{scene}' has no default trajectory: only the built-in scenes ({}) have one",
                    BUILTIN_SCENES.join(", ")
                )
            })?;
            rslam_core::trajectory_io::write_replica(&out, &trajectory)
                .with_context(|| format!("writing the trajectory of scene '{scene}'"))?;
            println!("wrote {}: {} poses", out.display(), trajectory.len());
        }
        SceneCommand::Stats(stats) => super::scene_stats::run(stats)?,
        SceneCommand::List => {
            for name in BUILTIN_SCENES {
                println!("{name}");
            }
        }
    }
    Ok(ExitCode::SUCCESS)
}
