//! nerfstudio's camera files, JSON: a camera path (`camera_path.json`, written by its viewer and
//! read by `ns-render`: `camera_path[i].camera_to_world`, 16 numbers row-major, and `fps`) or a
//! dataset's `transforms.json` (`frames[i].transform_matrix`, 4×4 row-major, with
//! `file_path`). Both hold camera-to-world transforms with OpenGL camera axes (x right, y up,
//! z backward), converted here to rslam's OpenCV axes (x right, y down, z forward).
//!
//! A camera path is in the frame the model (and its exported splats) lives in. A
//! `transforms.json` is in the capture's original frame; nerfstudio's dataparser moves it into
//! the model's with the `transform` (3×4) and `scale` of `dataparser_transforms.json`, which
//! [`ReadOptions::dataparser_transforms`](super::ReadOptions) applies the same way: the
//! transform first, then the translation scaled.
//!
//! Frames of a camera path are stamped `i / fps`; those of a `transforms.json`, put in name
//! order like COLMAP's images, `i / rate`.

use std::path::Path;

use glam::{DMat4, DVec4};
use serde_json::Value;

use crate::{read_text_file, CoreError, Pose, Trajectory};

/// Whether `text` is JSON (an object), which of the formats read only nerfstudio's is.
pub(super) fn is_json(text: &str) -> bool {
    text.trim_start_matches('\u{feff}')
        .trim_start()
        .starts_with('{')
}

/// The camera path or dataset cameras of `text`, moved by the dataparser transform read from
/// `dataparser` (a `transforms.json` only).
pub(super) fn parse(
    path: &Path,
    text: &str,
    rate_hz: f64,
    dataparser: Option<&Path>,
) -> Result<Trajectory, CoreError> {
    let bad = |message: String| CoreError::bad_file(path, message);
    let json: Value = serde_json::from_str(text.trim_start_matches('\u{feff}'))
        .map_err(|e| bad(format!("not JSON: {e}")))?;
    if let Some(cameras) = json.get("camera_path") {
        if dataparser.is_some() {
            return Err(bad(
                "a camera path is already in the model's frame: expected no dataparser transforms (they move a transforms.json)".into(),
            ));
        }
        let fps = json.get("fps").and_then(Value::as_f64).unwrap_or(rate_hz);
        if !(fps.is_finite() && fps > 0.0) {
            return Err(bad(format!("fps {fps}: expected a positive number")));
        }
        let cameras = cameras
            .as_array()
            .ok_or_else(|| bad("camera_path: expected an array of cameras".into()))?;
        let poses = (cameras.iter().enumerate())
            .map(|(i, camera)| {
                let at = format!("camera_path[{i}].camera_to_world");
                let numbers = numbers(camera.get("camera_to_world"), &at).map_err(&bad)?;
                opencv_pose(&numbers, None).map_err(|e| bad(format!("{at}: {e}")))
            })
            .collect::<Result<Vec<_>, _>>()?;
        return Ok(Trajectory::from_poses_at_rate(poses, fps));
    }
    let Some(frames) = json.get("frames") else {
        return Err(bad(
            "a JSON trajectory: expected nerfstudio's 'camera_path' (a camera path) or 'frames' (a transforms.json)".into(),
        ));
    };
    let frames = frames
        .as_array()
        .ok_or_else(|| bad("frames: expected an array of frames".into()))?;
    let moved = dataparser.map(read_dataparser_transforms).transpose()?;
    let mut named = (frames.iter().enumerate())
        .map(|(i, frame)| {
            let name = frame.get("file_path").and_then(Value::as_str).unwrap_or("");
            let at = format!("frames[{i}].transform_matrix");
            let numbers = numbers(frame.get("transform_matrix"), &at).map_err(&bad)?;
            let pose =
                opencv_pose(&numbers, moved.as_ref()).map_err(|e| bad(format!("{at}: {e}")))?;
            Ok((name.to_string(), pose))
        })
        .collect::<Result<Vec<_>, CoreError>>()?;
    named.sort_by(|a, b| a.0.cmp(&b.0));
    let poses = named.into_iter().map(|(_, pose)| pose).collect();
    Ok(Trajectory::from_poses_at_rate(poses, rate_hz))
}

/// nerfstudio's dataparser transform: `transform` (3×4) then `scale` on the translation.
pub(super) struct DataparserTransform {
    transform: DMat4,
    scale: f64,
}

fn read_dataparser_transforms(path: &Path) -> Result<DataparserTransform, CoreError> {
    let bad = |message: String| CoreError::bad_file(path, message);
    let text = read_text_file(path, "a dataparser_transforms.json")?;
    let json: Value = serde_json::from_str(&text).map_err(|e| bad(format!("not JSON: {e}")))?;
    let rows = numbers(json.get("transform"), "transform").map_err(&bad)?;
    if rows.len() != 12 {
        return Err(bad(format!(
            "transform: {} numbers, expected 3 rows of 4",
            rows.len()
        )));
    }
    let scale = json.get("scale").and_then(Value::as_f64);
    let scale = scale
        .filter(|s| s.is_finite() && *s > 0.0)
        .ok_or_else(|| bad("scale: expected a positive number".into()))?;
    let transform = Pose::rigid_from_rows(&rows).map_err(|e| bad(format!("transform: {e}")))?;
    Ok(DataparserTransform {
        transform: transform.to_mat4(),
        scale,
    })
}

/// The numbers of `value`, a flat array or an array of rows.
fn numbers(value: Option<&Value>, at: &str) -> Result<Vec<f64>, String> {
    let missing = || format!("{at}: expected a matrix of numbers");
    let rows = value.and_then(Value::as_array).ok_or_else(missing)?;
    let mut out = Vec::new();
    for row in rows {
        match row {
            Value::Array(items) => {
                for item in items {
                    out.push(item.as_f64().ok_or_else(missing)?);
                }
            }
            item => out.push(item.as_f64().ok_or_else(missing)?),
        }
    }
    Ok(out)
}

/// A camera-to-world matrix with OpenGL camera axes (row-major, 16 or 12 numbers), moved by the
/// dataparser transform, as a pose with OpenCV camera axes.
fn opencv_pose(rows: &[f64], moved: Option<&DataparserTransform>) -> Result<Pose, String> {
    let pose = Pose::rigid_from_rows(rows)?;
    let mut m = pose.to_mat4();
    if let Some(d) = moved {
        m = d.transform * m;
        m.w_axis = DVec4::new(
            d.scale * m.w_axis.x,
            d.scale * m.w_axis.y,
            d.scale * m.w_axis.z,
            1.0,
        );
    }
    // OpenGL camera axes to OpenCV's: y and z turned round.
    let flip = DMat4::from_diagonal(DVec4::new(1.0, -1.0, -1.0, 1.0));
    Ok(Pose::from_mat4(&(m * flip)))
}

#[cfg(test)]
mod tests;
