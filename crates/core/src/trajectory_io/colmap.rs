//! COLMAP's `images.txt` (the text model of a reconstruction, as COLMAP, nerfstudio's and gsplat's
//! COLMAP loaders read it): per image a line `IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME`
//! holding the world-to-camera transform (`x_cam = R(q) x_world + t`, camera axes x right, y down,
//! z forward: OpenCV's, rslam's), then a line of its 2D points (possibly empty), which is
//! skipped. Read as COLMAP reads it: comment and blank lines are skipped where an image line is
//! due, the line after each image line is its points. The images are put in capture order by
//! name (`frame_00001.png`, …), since the file lists them by id, and stamped `i / rate`: the
//! file holds no time.

use std::path::Path;

use super::lines::LineRef;
use crate::{printable, CoreError, Pose, Trajectory};

/// Whether `line` looks like an image line of `images.txt`: two integer ids around seven numbers,
/// then a name that is not a number (which tells it from a row of matrix numbers).
pub(super) fn is_image_line(line: &str) -> bool {
    let fields: Vec<&str> = line.split_whitespace().collect();
    let integer = |text: &str| !text.is_empty() && text.bytes().all(|b| b.is_ascii_digit());
    fields.len() >= 10
        && integer(fields[0])
        && integer(fields[8])
        && fields[1..8].iter().all(|f| f.parse::<f64>().is_ok())
        && fields[9].parse::<f64>().is_err()
}

pub(super) fn parse(path: &Path, text: &str, rate_hz: f64) -> Result<Trajectory, CoreError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l.trim()));
    let mut images: Vec<(String, usize, Pose)> = Vec::new();
    while let Some((line, content)) = lines.next() {
        if content.is_empty() || content.starts_with('#') {
            continue;
        }
        let (name, pose) = image(&LineRef { path, line }, content)?;
        images.push((name, line, pose));
        // The image's 2D points, whatever they hold.
        lines.next();
    }
    // Stable: of two images of one name, the one met first stays first.
    images.sort_by(|a, b| a.0.cmp(&b.0));
    if let Some([(name, first, _), (_, again, _)]) = images.windows(2).find(|w| w[0].0 == w[1].0) {
        return Err(LineRef { path, line: *again }.error(format!(
            "image '{}' again (first on line {first}); expected each image once",
            printable(name)
        )));
    }
    let poses = images.into_iter().map(|(_, _, pose)| pose).collect();
    Ok(Trajectory::from_poses_at_rate(poses, rate_hz))
}

/// The image's name and camera-to-world pose.
fn image(at: &LineRef, content: &str) -> Result<(String, Pose), CoreError> {
    let layout = super::TrajectoryFormat::Colmap.line_layout();
    if !is_image_line(content) {
        return Err(at.error(format!(
            "expected {layout}, found '{}'",
            printable(&content.chars().take(80).collect::<String>())
        )));
    }
    let fields: Vec<&str> = content.split_whitespace().collect();
    let [qw, qx, qy, qz, tx, ty, tz]: [f64; 7] =
        at.numbers(fields[1..8].iter().copied(), true, layout)?;
    let world_to_camera = at.quaternion(qx, qy, qz, qw)?;
    let camera_to_world = world_to_camera.inverse();
    let centre = -(camera_to_world * glam::DVec3::new(tx, ty, tz));
    Ok((fields[9..].join(" "), Pose::new(camera_to_world, centre)))
}
