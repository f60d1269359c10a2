use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use rslam_core::dataset::ros2::{BagCompression, BagDepth, BagOptions};
use rslam_core::dataset::{DatasetFormat, DepthPng, Layout};
use rslam_core::Intrinsics;
use rslam_perturb::PerturbSpec;
use rslam_pipeline::{agent_folders, agent_scene_job, Job, RigPreset, SceneJob, Sensors, Source};
use rslam_render::splat::{CaptureOptions, SplatDepth, SplatSettings};

use super::actor_args::ActorArgs;
use super::make::make;

#[derive(clap::Args)]
pub struct RenderArgs {
    /// Built-in scene (room0 room1 room2 office0 … office4), a mesh file (.ply, .gltf, .glb,
    /// .obj) or a Gaussian-splat capture (a 3DGS .ply).
    #[arg(long)]
    scene: String,
    #[command(flatten)]
    actors: ActorArgs,
    /// A capture's metric scale: metres per unit of its coordinates (COLMAP and phone captures
    /// have none of their own). Without it, items in metres (depth items, `trans`, IMU and
    /// calibration items) are refused.
    #[arg(long)]
    capture_scale: Option<f64>,
    /// A capture's depth: `expected` (Σ wᵢzᵢ / Σ wᵢ over the blended Gaussians) or `median`
    /// (where the transmittance falls below 0.5).
    #[arg(long, default_value = "expected")]
    capture_depth: SplatDepth,
    /// A capture's pixels whose accumulated opacity stays below this get no depth (0).
    #[arg(long, default_value_t = 0.5)]
    capture_min_opacity: f32,
    /// nerfstudio's dataparser_transforms.json: moves a --traj transforms.json (the capture's
    /// own cameras) into the frame its splats were trained in.
    #[arg(long)]
    dataparser_transforms: Option<PathBuf>,
    /// Output folder: new or empty; or the same command's unfinished output, which is resumed.
    #[arg(long)]
    out: PathBuf,
    /// Camera path: Replica traj.txt, a TUM or EuRoC trajectory, COLMAP images.txt or nerfstudio's
    /// camera_path.json / transforms.json; default: the scene's own.
    #[arg(long)]
    traj: Option<PathBuf>,
    /// Render only the first N poses.
    #[arg(long)]
    frames: Option<usize>,
    /// `replica` (1200x680, f=600, 20 Hz), `tum` (640x480, f=525, 30 Hz) or W,H,FX,FY,CX,CY
    /// [default: replica]; the RGB-D camera of --rig rgbd and rgbd-imu (stereo rigs have their own).
    #[arg(long)]
    camera: Option<String>,
    /// Sensors: `rgbd` (one RGB-D camera, the default), `rgbd-imu` (that camera at a RealSense
    /// D435i's colour-camera pose and its 200 Hz IMU; needs --format tum or ros2), `stereo` (two
    /// 752x480 grey cameras, 0.11 m apart, 20 Hz), `stereo-imu` (the same and a 200 Hz IMU) or a
    /// rig file FILE.toml (cameras and an IMU of your own, see docs/src/rigs.md, "Rig files"); the
    /// stereo rigs and rig files need --format euroc or ros2. The scene's path (or --traj) is the
    /// (first) camera's.
    #[arg(long)]
    rig: Option<String>,
    /// Frame rate in Hz (with a stereo rig: the rate of the path's poses); default: 30 for the
    /// tum camera, else 20.
    #[arg(long)]
    rate: Option<f64>,
    /// Output layout: replica (NICE-SLAM, SplaTAM, Co-SLAM, GO-SLAM), tum (ORB-SLAM3; with
    /// --rig rgbd-imu plus imu0/), ros2 (a rosbag2 in MCAP storage for `ros2 bag play`, of one
    /// camera or of any --rig) or euroc (the stereo rigs; needs --rig).
    #[arg(long, value_enum, default_value = "replica")]
    format: OutputFormat,
    /// Depth PNG compression: `fast`, or `small` (about a third of the size for 2–3× the
    /// encoding time; lossless either way, see docs/src/formats.md, "Depth PNGs").
    #[arg(long, default_value = "fast")]
    depth_png: DepthPng,
    /// With --format ros2: the depth topic's encoding, `16UC1` (millimetres, 0 = none; the
    /// default) or `32FC1` (metres, NaN = none).
    #[arg(long, default_value = "16UC1")]
    bag_depth: BagDepth,
    /// With --format ros2: the ground truth also as `world → body` transforms on /tf.
    #[arg(long)]
    bag_tf: bool,
    /// With --format ros2: the MCAP chunks' compression, `none` (default), `zstd` or `lz4`.
    #[arg(long, default_value = "none")]
    bag_compression: BagCompression,
    /// Seed of every random draw.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Perturbations, e.g. `fog:3,depth_missing:5,rot:1,fast:2` (see `rslam list`); with
    /// `--rig` per camera (`cam1:fog:3`) and calibration items (`baseline:0.01`,
    /// `cam1:extrinsic_rot:0.5@calibration`).
    #[arg(long)]
    perturb: Option<String>,
    /// Replace what --out holds if it is another rslam output (never a folder of other files).
    #[arg(long)]
    force: bool,
    /// N agents in one built-in scene, each on a path of its own, all in the scene's world frame:
    /// OUT/agent0 … OUT/agentN-1, each a dataset (agent k draws with seed + k), the folder
    /// `rslam eval --agents` reads.
    #[arg(long, conflicts_with = "traj")]
    agents: Option<usize>,
    /// Use the GPU whose name contains this text (default: a real GPU if any, else lavapipe).
    #[arg(long)]
    adapter: Option<String>,
}

/// `--format`: the layouts of one RGB-D camera (folders, or a ROS 2 bag), or EuRoC for a rig.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum OutputFormat {
    Replica,
    Tum,
    /// A rosbag2 folder (MCAP storage) of one RGB-D camera (and the rgbd-imu rig's IMU), for
    /// `ros2 bag play`.
    Ros2,
    Euroc,
}

impl OutputFormat {
    fn layout(self) -> Layout {
        match self {
            Self::Replica => Layout::Camera(DatasetFormat::Replica),
            Self::Tum => Layout::Camera(DatasetFormat::Tum),
            Self::Ros2 => Layout::Camera(DatasetFormat::Ros2),
            Self::Euroc => Layout::Euroc,
        }
    }
}

/// `--camera` when not given.
const DEFAULT_CAMERA: &str = "replica";

pub fn run(args: RenderArgs) -> anyhow::Result<ExitCode> {
    let jobs = jobs(&args)?;
    make(&jobs, args.adapter)?;
    Ok(ExitCode::SUCCESS)
}

/// One job, or one per agent with `--agents`.
fn jobs(args: &RenderArgs) -> anyhow::Result<Vec<Job>> {
    let scene = scene_job(args)?;
    let preset = match args.rig.as_deref() {
        Some(name) => RigPreset::by_name(name)?,
        None => RigPreset::Rgbd,
    };
    if let (RigPreset::Euroc(rig), Some(_)) = (&preset, &args.camera) {
        anyhow::bail!(
            "--camera: the '{}' rig has its own cameras; leave --camera out with --rig {0}",
            rig.name
        );
    }
    // Made first so that bad flags are refused before any folder is looked at.
    let bag = BagOptions {
        depth: args.bag_depth,
        tf: args.bag_tf,
        compression: args.bag_compression,
    };
    let sensors = Sensors::new(preset, args.format.layout(), args.depth_png, bag)?;
    let job = |scene: SceneJob, out: PathBuf| Job {
        source: Source::Scene {
            scene,
            sensors: sensors.clone(),
        },
        out,
        force: args.force,
        command: super::typed_command(),
    };
    let Some(count) = args.agents else {
        return Ok(vec![job(scene, args.out.clone())]);
    };
    Ok(agent_folders(&args.out, count)?
        .into_iter()
        .enumerate()
        .map(|(agent, out)| job(agent_scene_job(&scene, agent), out))
        .collect())
}

fn scene_job(args: &RenderArgs) -> anyhow::Result<SceneJob> {
    let spec = match &args.perturb {
        Some(text) => PerturbSpec::parse(text).context("--perturb")?,
        None => PerturbSpec::default(),
    };
    let camera_text = args.camera.as_deref().unwrap_or(DEFAULT_CAMERA);
    let camera = Intrinsics::parse(camera_text).context("--camera")?;
    Ok(SceneJob {
        scene: args.scene.clone(),
        trajectory: args.traj.clone(),
        frames: args.frames,
        camera,
        rate_hz: args.rate.unwrap_or(Intrinsics::preset_rate_hz(camera_text)),
        spec,
        seed: args.seed,
        agent: None,
        capture: CaptureOptions {
            metres_per_unit: args.capture_scale,
            settings: SplatSettings {
                depth: args.capture_depth,
                min_opacity: args.capture_min_opacity,
            },
            dataparser_transforms: args.dataparser_transforms.clone(),
        },
        actor_files: args.actors.files(),
    })
}
