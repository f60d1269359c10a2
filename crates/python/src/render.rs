//! `rslam.render` and `rslam.scene_poses`: a scene drawn along poses through the pipeline's
//! in-memory API (rasterizer, then the spec's corruptions), frames back as numpy arrays.

use std::path::PathBuf;

use numpy::PyArrayMethods;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use rslam_core::{MaskImage, Pose};
use rslam_perturb::PerturbSpec;
use rslam_pipeline::{ActorFiles, FramesInMemory, SceneJob};
use rslam_render::splat::{CaptureOptions, SplatDepth, SplatSettings};

use crate::arrays::{colors_to_numpy, depth_to_numpy, masks_to_numpy, ColorLayout, DepthUnits};
use crate::camera;
use crate::frames::RunError;
use crate::gpu;

fn poses_from(obj: &Bound<'_, PyAny>) -> PyResult<Vec<Pose>> {
    let matrices: Vec<[[f64; 4]; 4]> = obj.extract().map_err(|_| {
        PyValueError::new_err(
            "poses: expected an Nx4x4 array of camera-to-world matrices (OpenCV camera axes)",
        )
    })?;
    Ok(matrices.iter().map(pose_of_matrix).collect())
}

/// A 4x4 camera-to-world matrix (as numpy gives it, rows first) as a pose.
pub(crate) fn pose_of_matrix(m: &[[f64; 4]; 4]) -> Pose {
    let mut rows = [0.0; 16];
    for (r, row) in m.iter().enumerate() {
        rows[r * 4..r * 4 + 4].copy_from_slice(row);
    }
    Pose::from_row_major(&rows)
}

/// Renders a scene along camera poses on the GPU.
///
/// Args:
///     scene: a built-in scene (room0-room2, office0-office4), a mesh file (.ply, .glb,
///         .gltf, .obj) or a Gaussian-splat capture (3DGS .ply), as ``rslam render --scene``.
///     poses: Nx4x4 camera-to-world matrices (metres; camera x right, y down, z forward), as
///         Replica ``traj.txt`` rows; e.g. ``rslam.scene_poses('room0')[:10]``.
///     camera: 'replica' (1200x680, default), 'tum', "W,H,FX,FY,CX,CY" or a 6-tuple.
///     perturb: optional ``--perturb`` spec applied as ``rslam render`` does (rot/trans deviate
///         the poses, image and depth corruptions follow, fast/misalign choose output frames).
///     seed: seed of the perturbations.
///     rate: frame rate of the poses in Hz (timestamps i / rate).
///     capture_scale: a capture's metres per unit (``--capture-scale``); without it, items in
///         metres are refused on a capture.
///     capture_depth: a capture's depth, 'expected' (default) or 'median'.
///     capture_min_opacity: a capture's pixels under this accumulated opacity get depth 0.
///     actors: a user's actors, a list of (mesh file, path file) pairs, as ``rslam render
///         --actor MESH PATH``: rigid meshes moved along trajectory files (a built-in scene).
///     masks: also return the instance masks (``actors``): which actor each pixel sees.
///
/// Returns:
///     (rgb, depth): uint8 NxHxWx3 sRGB and float32 NxHxW z-depth in metres (0 = nothing hit),
///     one frame per output frame (N poses, fewer under fast:K). N frames are held in memory:
///     1200x680 costs about 5.7 MB a frame. With ``masks=True``, (rgb, depth, mask): mask is
///     uint16 NxHxW, 0 the static scene and k walker k, at each colour frame's instant (all 0
///     without ``actors``), as ``rslam render`` writes mask PNGs.
#[pyfunction]
#[pyo3(signature = (
    scene,
    poses,
    camera = None,
    perturb = None,
    seed = 0,
    rate = 20.0,
    capture_scale = None,
    capture_depth = "expected",
    capture_min_opacity = 0.5,
    actors = Vec::new(),
    masks = false,
))]
#[allow(clippy::too_many_arguments)] // Python's keyword arguments
pub fn render<'py>(
    py: Python<'py>,
    scene: &str,
    poses: &Bound<'py, PyAny>,
    camera: Option<&Bound<'py, PyAny>>,
    perturb: Option<&str>,
    seed: u64,
    rate: f64,
    capture_scale: Option<f64>,
    capture_depth: &str,
    capture_min_opacity: f32,
    actors: Vec<(PathBuf, PathBuf)>,
    masks: bool,
) -> PyResult<Bound<'py, PyTuple>> {
    let depth: SplatDepth =
        (capture_depth.parse()).map_err(|e| PyValueError::new_err(format!("capture_depth {e}")))?;
    let poses = poses_from(poses)?;
    let camera = match camera {
        Some(c) => camera::intrinsics(c)?,
        None => rslam_core::Intrinsics::REPLICA,
    };
    let spec = match perturb {
        Some(text) => PerturbSpec::parse(text).map_err(crate::errors::perturb)?,
        None => PerturbSpec::default(),
    };
    let job = SceneJob {
        scene: scene.to_string(),
        trajectory: None,
        frames: None,
        camera,
        rate_hz: rate,
        spec,
        seed,
        agent: None,
        capture: CaptureOptions {
            metres_per_unit: capture_scale,
            settings: SplatSettings {
                depth,
                min_opacity: capture_min_opacity,
            },
            dataparser_transforms: None,
        },
        actor_files: (actors.into_iter())
            .map(|(mesh, path)| ActorFiles { mesh, path })
            .collect(),
    };
    let frames = py.detach(|| -> Result<_, RunError> {
        let ctx = gpu::context().map_err(RunError::NoGpu)?;
        let mut frames = FramesInMemory::scene_along(ctx, &job, poses)?;
        let count = frames.plan().len();
        let mut out = Vec::with_capacity(count);
        frames.frames(ctx, 0..count, |frame| {
            out.push(frame);
            Ok(())
        })?;
        Ok(out)
    })?;
    let mut colors = Vec::with_capacity(frames.len());
    let mut depths = Vec::with_capacity(frames.len());
    let mut instance_masks = Vec::with_capacity(frames.len());
    for frame in frames {
        let (width, height) = (frame.color.width, frame.color.height);
        instance_masks.push(frame.mask.unwrap_or_else(|| MaskImage::new(width, height)));
        colors.push((frame.color, None));
        depths.extend(frame.depth);
    }
    let mut arrays = vec![
        colors_to_numpy(py, colors, ColorLayout::Rgb)?,
        depth_to_numpy(py, depths, DepthUnits::Metres, true)?,
    ];
    if masks {
        arrays.push(masks_to_numpy(py, instance_masks)?);
    }
    PyTuple::new(py, arrays)
}

/// The default camera path of a built-in scene as Nx4x4 camera-to-world matrices (float64), at
/// 20 Hz; the poses ``rslam render --scene NAME`` uses without ``--traj``.
#[pyfunction]
pub fn scene_poses<'py>(py: Python<'py>, scene: &str) -> PyResult<Bound<'py, PyAny>> {
    let loaded = py
        .detach(|| rslam_render::load_scene(scene))
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    let path = loaded.default_trajectory.ok_or_else(|| {
        PyValueError::new_err(format!("scene '{scene}' has no default camera path"))
    })?;
    let flat: Vec<f64> = path.poses.iter().flat_map(|p| p.to_row_major()).collect();
    Ok(numpy::PyArray1::from_vec(py, flat)
        .reshape([path.poses.len(), 4, 4])?
        .into_any())
}
