//! Reads an existing dataset in the Replica or TUM layout (rslam's own or the original ones).

use std::path::{Path, PathBuf};

use crate::dataset::{DatasetFormat, Manifest, MANIFEST_FILE};
use crate::limits::{MAX_IMAGE_SIDE, MAX_POSES};
use crate::trajectory_io::{read_trajectory_with, ReadOptions, TrajectoryFormat};
use crate::{nearest_time, read_text_file, CoreError, Distortion, Intrinsics, Trajectory};

/// Largest RGB–depth time difference when pairing TUM rgb.txt and depth.txt without associations.
const TUM_PAIR_MAX_DIFF_S: f64 = 0.02;

/// One frame of a source dataset: its colour file and, where present, its depth file.
#[derive(Clone, Debug, PartialEq)]
pub struct DatasetFrame {
    pub rgb: PathBuf,
    pub rgb_time: f64,
    pub depth: Option<PathBuf>,
    pub depth_time: f64,
}

/// What the reader cannot know from every dataset and must not guess: the camera (TUM sequences
/// and Replica scenes without `cam_params.json` have no camera file) and the frame rate (Replica
/// frames have no timestamps). Where given, they take precedence over the dataset's own.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DatasetOverrides {
    pub camera: Option<Intrinsics>,
    pub rate_hz: Option<f64>,
}

#[derive(Clone, Debug)]
pub struct SourceDataset {
    pub root: PathBuf,
    pub format: DatasetFormat,
    pub intrinsics: Intrinsics,
    /// The lens the frames were seen through: the manifest's, else cam_params.json's.
    pub distortion: Option<Distortion>,
    pub rate_hz: f64,
    pub frames: Vec<DatasetFrame>,
    /// traj.txt / groundtruth.txt, if the dataset has one.
    pub ground_truth: Option<Trajectory>,
    pub manifest: Option<Manifest>,
}

/// Detects the layout of `root` (Replica: `results/`; TUM: `rgb.txt`) and lists its frames. The
/// camera comes from `overrides`, the manifest or `cam_params.json`, the rate from `overrides`,
/// the manifest or the TUM timestamps; where neither is known the error says so.
pub fn read_dataset(root: &Path, overrides: &DatasetOverrides) -> Result<SourceDataset, CoreError> {
    let manifest = if root.join(MANIFEST_FILE).exists() {
        Some(Manifest::read(root)?)
    } else {
        None
    };
    if root.join("rgb.txt").is_file() {
        read_tum(root, manifest, overrides)
    } else if root.join("results").is_dir() {
        read_replica(root, manifest, overrides)
    } else {
        Err(CoreError::bad_file(
            root,
            "not a dataset: expected the Replica layout (results/frame*.jpg, results/depth*.png) or the TUM layout (rgb.txt, depth.txt)",
        ))
    }
}

fn sorted_with_prefix(dir: &Path, prefix: &str) -> Result<Vec<PathBuf>, CoreError> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| CoreError::io(dir, e))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            let name = p
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            name.starts_with(prefix) && !name.ends_with(".partial")
        })
        .collect();
    files.sort();
    Ok(files)
}

/// The camera and lens of a cam_params.json.
struct CamParams {
    camera: Intrinsics,
    distortion: Option<Distortion>,
}

/// cam_params.json in the dataset or its parent (Replica SLAM keeps one beside the scenes).
fn replica_camera(root: &Path) -> Result<Option<CamParams>, CoreError> {
    let candidates = [
        root.join("cam_params.json"),
        root.join("../cam_params.json"),
    ];
    let Some(path) = candidates.iter().find(|p| p.is_file()) else {
        return Ok(None);
    };
    let text = read_text_file(path, "the camera as JSON")?;
    let json: serde_json::Value = serde_json::from_str(&text)
        .map_err(|e| CoreError::bad_file(path, format!("not JSON: {e}")))?;
    let camera = &json["camera"];
    let number = |key: &str| {
        camera[key]
            .as_f64()
            .ok_or_else(|| CoreError::bad_file(path, format!("expected a number at camera.{key}")))
    };
    let size = |key: &str| {
        let value = number(key)?;
        if value >= 1.0 && value.fract() == 0.0 && value <= MAX_IMAGE_SIDE as f64 {
            Ok(value as u32)
        } else {
            Err(CoreError::bad_file(
                path,
                format!(
                    "expected a whole number of pixels from 1 to {MAX_IMAGE_SIDE} at camera.{key}, got {value}"
                ),
            ))
        }
    };
    let camera = Intrinsics {
        width: size("w")?,
        height: size("h")?,
        fx: number("fx")?,
        fy: number("fy")?,
        cx: number("cx")?,
        cy: number("cy")?,
    };
    camera
        .check()
        .map_err(|message| CoreError::bad_file(path, format!("camera.{message}")))?;
    Ok(Some(CamParams {
        camera,
        distortion: cam_params_lens(path, &json["camera"])?,
    }))
}

/// `camera.distortion_model` and `camera.distortion` as rslam writes them, if there.
fn cam_params_lens(
    path: &Path,
    camera: &serde_json::Value,
) -> Result<Option<Distortion>, CoreError> {
    let (model, coefficients) = (&camera["distortion_model"], &camera["distortion"]);
    if model.is_null() && coefficients.is_null() {
        return Ok(None);
    }
    let numbers: Option<Vec<f64>> = coefficients
        .as_array()
        .and_then(|a| a.iter().map(|v| v.as_f64()).collect());
    let lens = match (model.as_str(), numbers.as_deref()) {
        (Some(model), Some(&[a, b, c, d])) => Distortion::from_coefficients(model, [a, b, c, d]),
        _ => None,
    };
    lens.map(Some).ok_or_else(|| {
        CoreError::bad_file(
            path,
            "expected camera.distortion_model \"radtan\" or \"equidistant\" with camera.distortion holding its 4 coefficients",
        )
    })
}

fn no_camera(root: &Path, looked_in: &str) -> CoreError {
    CoreError::bad_file(
        root,
        format!("no camera intrinsics ({looked_in}); give them explicitly (rslam: --camera)"),
    )
}

fn rate_or_error(rate_hz: Option<f64>, root: &Path, why: &str) -> Result<f64, CoreError> {
    match rate_hz {
        Some(hz) if hz.is_finite() && hz > 0.0 => Ok(hz),
        Some(hz) => Err(CoreError::bad_file(
            root,
            format!(
                "frame rate {hz} Hz (given, from rslam.json or from the frame times): expected a positive finite rate"
            ),
        )),
        None => Err(CoreError::bad_file(
            root,
            format!("unknown frame rate ({why}); give it explicitly (rslam: --rate)"),
        )),
    }
}

fn read_replica(
    root: &Path,
    manifest: Option<Manifest>,
    overrides: &DatasetOverrides,
) -> Result<SourceDataset, CoreError> {
    let results = root.join("results");
    let rgb = sorted_with_prefix(&results, "frame")?;
    let depth = sorted_with_prefix(&results, "depth")?;
    if rgb.is_empty() {
        return Err(CoreError::bad_file(
            &results,
            "no frame*.jpg/png colour images",
        ));
    }
    if !depth.is_empty() && depth.len() != rgb.len() {
        return Err(CoreError::bad_file(
            &results,
            format!(
                "{} colour frames but {} depth frames",
                rgb.len(),
                depth.len()
            ),
        ));
    }
    let rate_hz = rate_or_error(
        overrides.rate_hz.or(manifest.as_ref().map(|m| m.rate_hz)),
        root,
        "Replica frames carry no timestamps and there is no rslam.json",
    )?;
    let traj_path = root.join("traj.txt");
    let ground_truth = if traj_path.is_file() {
        let options = ReadOptions {
            format: Some(TrajectoryFormat::Replica),
            replica_rate_hz: rate_hz,
            ..ReadOptions::default()
        };
        Some(read_trajectory_with(&traj_path, &options)?.trajectory)
    } else {
        None
    };
    let manifest_lens = manifest.as_ref().and_then(|m| m.distortion);
    let (intrinsics, distortion) = match overrides
        .camera
        .or(manifest.as_ref().and_then(|m| m.camera))
    {
        Some(camera) => (camera, manifest_lens),
        None => {
            let cam_params = replica_camera(root)?.ok_or_else(|| {
                no_camera(root, "no rslam.json, no cam_params.json here or one up")
            })?;
            (cam_params.camera, cam_params.distortion)
        }
    };
    let frames = rgb
        .into_iter()
        .enumerate()
        .map(|(i, rgb)| DatasetFrame {
            rgb,
            rgb_time: i as f64 / rate_hz,
            depth: depth.get(i).cloned(),
            depth_time: i as f64 / rate_hz,
        })
        .collect();
    Ok(SourceDataset {
        root: root.to_path_buf(),
        format: DatasetFormat::Replica,
        intrinsics,
        distortion,
        rate_hz,
        frames,
        ground_truth,
        manifest,
    })
}

/// `<t> <file>` lines of rgb.txt / depth.txt, `#` comments skipped.
fn tum_list(path: &Path) -> Result<Vec<(f64, PathBuf)>, CoreError> {
    let text = read_text_file(path, "'<timestamp> <file>' lines")?;
    check_frame_count(path, &text)?;
    let root = path.parent().unwrap_or(Path::new("."));
    let mut entries = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let bad = |message: &str| CoreError::BadLine {
            path: path.to_path_buf(),
            line: i + 1,
            message: message.to_string(),
        };
        let mut parts = line.split_whitespace();
        let time = parts
            .next()
            .and_then(|t| t.parse::<f64>().ok())
            .filter(|t| t.is_finite())
            .ok_or_else(|| bad("expected '<timestamp> <file>' with a numeric timestamp"))?;
        let file = parts
            .next()
            .ok_or_else(|| bad("expected '<timestamp> <file>': file missing"))?;
        entries.push((time, root.join(file)));
    }
    Ok(entries)
}

fn read_tum(
    root: &Path,
    manifest: Option<Manifest>,
    overrides: &DatasetOverrides,
) -> Result<SourceDataset, CoreError> {
    let associations = root.join("associations.txt");
    let listed_in = if associations.is_file() {
        associations.clone()
    } else {
        root.join("rgb.txt")
    };
    let frames: Vec<DatasetFrame> = if associations.is_file() {
        read_associations(&associations)?
    } else {
        let rgb = tum_list(&root.join("rgb.txt"))?;
        let depth_path = root.join("depth.txt");
        let depth = if depth_path.is_file() {
            tum_list(&depth_path)?
        } else {
            Vec::new()
        };
        rgb.into_iter()
            .map(|(rgb_time, rgb)| {
                let nearest =
                    nearest_time(depth.iter().map(|d| d.0), rgb_time, TUM_PAIR_MAX_DIFF_S)
                        .map(|i| &depth[i]);
                DatasetFrame {
                    rgb,
                    rgb_time,
                    depth: nearest.map(|d| d.1.clone()),
                    depth_time: nearest.map_or(rgb_time, |d| d.0),
                }
            })
            .collect()
    };
    if frames.is_empty() {
        return Err(CoreError::bad_file(listed_in, "lists no frames"));
    }
    let gt_path = root.join("groundtruth.txt");
    let ground_truth = if gt_path.is_file() {
        let options = ReadOptions {
            format: Some(TrajectoryFormat::Tum),
            ..ReadOptions::default()
        };
        Some(read_trajectory_with(&gt_path, &options)?.trajectory)
    } else {
        None
    };
    let rate_hz = rate_or_error(
        overrides
            .rate_hz
            .or(manifest.as_ref().map(|m| m.rate_hz))
            .or_else(|| measured_rate(&frames)),
        root,
        "fewer than two distinct colour timestamps and no rslam.json",
    )?;
    let intrinsics = overrides
        .camera
        .or(manifest.as_ref().and_then(|m| m.camera))
        .ok_or_else(|| {
            no_camera(
                root,
                "TUM sequences have no camera file, and there is no rslam.json",
            )
        })?;
    Ok(SourceDataset {
        root: root.to_path_buf(),
        format: DatasetFormat::Tum,
        intrinsics,
        distortion: manifest.as_ref().and_then(|m| m.distortion),
        rate_hz,
        frames,
        ground_truth,
        manifest,
    })
}

fn read_associations(path: &Path) -> Result<Vec<DatasetFrame>, CoreError> {
    let text = read_text_file(path, "'t_rgb rgb t_depth depth' lines")?;
    check_frame_count(path, &text)?;
    let root = path.parent().unwrap_or(Path::new("."));
    let mut frames = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let parts: Vec<&str> = line.split_whitespace().collect();
        let time = |text: &str| text.parse::<f64>().ok().filter(|t| t.is_finite());
        let times = match parts.as_slice() {
            [t0, _, t1, _] => time(t0).zip(time(t1)),
            _ => None,
        };
        let Some((rgb_time, depth_time)) = times else {
            return Err(CoreError::BadLine {
                path: path.to_path_buf(),
                line: i + 1,
                message:
                    "expected 't_rgb rgb/<t>.png t_depth depth/<t>.png' with finite timestamps"
                        .into(),
            });
        };
        frames.push(DatasetFrame {
            rgb: root.join(parts[1]),
            rgb_time,
            depth: Some(root.join(parts[3])),
            depth_time,
        });
    }
    Ok(frames)
}

/// Refuses a frame list of more than [`MAX_POSES`] lines before any is parsed.
fn check_frame_count(path: &Path, text: &str) -> Result<(), CoreError> {
    if text.lines().nth(MAX_POSES).is_some() {
        return Err(CoreError::bad_file(
            path,
            format!("more than {MAX_POSES} lines, the most frames a dataset may hold"),
        ));
    }
    Ok(())
}

/// Median frame interval of the colour stream, as a rate; `None` without two distinct times.
fn measured_rate(frames: &[DatasetFrame]) -> Option<f64> {
    let mut gaps: Vec<f64> = frames
        .windows(2)
        .map(|w| w[1].rgb_time - w[0].rgb_time)
        .filter(|g| *g > 0.0)
        .collect();
    if gaps.is_empty() {
        return None;
    }
    gaps.sort_by(f64::total_cmp);
    Some(1.0 / gaps[gaps.len() / 2])
}
