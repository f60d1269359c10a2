//! The data.csv files of a EuRoC dataset: each opens with a `#` header naming its columns (the
//! published ones, exactly), then one comma-separated line per row, timestamps in integer
//! nanoseconds. Written here, and read back strictly: the header must name the expected columns
//! (blanks after the commas are allowed, as the published ground truth has them), each line must
//! have every column, and timestamps must increase.

use std::path::{Path, PathBuf};

use glam::DVec3;

use super::{EurocFrame, GroundTruthState, ImuSample};
use crate::limits::MAX_POSES;
use crate::trajectory_io::euroc::{fields, pose_from_columns};
use crate::trajectory_io::lines::{data_lines, LineRef};
use crate::{printable, read_text_file, CoreError};

/// Header of `camN/data.csv`.
pub const CAMERA_HEADER: &str = "#timestamp [ns],filename";
/// Header of `imu0/data.csv`.
pub const IMU_HEADER: &str = "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]";
/// Header of `state_groundtruth_estimate0/data.csv`, with its blanks after the commas.
pub const GROUND_TRUTH_HEADER: &str = "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], q_RS_z [], v_RS_R_x [m s^-1], v_RS_R_y [m s^-1], v_RS_R_z [m s^-1], b_w_RS_S_x [rad s^-1], b_w_RS_S_y [rad s^-1], b_w_RS_S_z [rad s^-1], b_a_RS_S_x [m s^-2], b_a_RS_S_y [m s^-2], b_a_RS_S_z [m s^-2]";

const CAMERA_LAYOUT: &str = "'<t_ns>,<t_ns>.png'";
const IMU_LAYOUT: &str = "7 comma-separated numbers 't[ns],wx,wy,wz,ax,ay,az'";
const GROUND_TRUTH_LAYOUT: &str =
    "17 comma-separated numbers 't[ns],px,py,pz,qw,qx,qy,qz,vx,vy,vz,bwx,bwy,bwz,bax,bay,baz'";

fn number(v: f64) -> String {
    format!("{v}")
}

fn vec3(v: DVec3) -> String {
    format!("{},{},{}", number(v.x), number(v.y), number(v.z))
}

/// `camN/data.csv` for frames at `times_ns`, each named `<t_ns>.png`.
pub fn camera_csv(times_ns: &[u64]) -> String {
    let mut text = format!("{CAMERA_HEADER}\n");
    for t in times_ns {
        text.push_str(&format!("{t},{t}.png\n"));
    }
    text
}

pub fn imu_csv(samples: &[ImuSample]) -> String {
    let mut text = format!("{IMU_HEADER}\n");
    for s in samples {
        text.push_str(&format!("{},{},{}\n", s.t_ns, vec3(s.gyro), vec3(s.accel)));
    }
    text
}

pub fn ground_truth_csv(states: &[GroundTruthState]) -> String {
    let mut text = format!("{GROUND_TRUTH_HEADER}\n");
    for s in states {
        let p = s.world_from_body.translation;
        let q = s.world_from_body.rotation;
        text.push_str(&format!(
            "{},{},{},{},{},{},{},{},{}\n",
            s.t_ns,
            vec3(p),
            number(q.w),
            number(q.x),
            number(q.y),
            number(q.z),
            vec3(s.velocity),
            vec3(s.gyro_bias),
            vec3(s.accel_bias),
        ));
    }
    text
}

/// Reads `path` (within the text-file limit), checks its header names the columns of `header`
/// and that it has at most [`MAX_POSES`] rows; returns the text for [`data_lines`].
fn read_checked(path: &Path, header: &str, what: &str) -> Result<String, CoreError> {
    let text = read_text_file(path, what)?;
    let first = text
        .strip_prefix('\u{feff}')
        .unwrap_or(&text)
        .lines()
        .next()
        .unwrap_or("")
        .trim();
    let columns = |h: &str| -> Vec<String> {
        fields(h.trim_start_matches('#'))
            .map(str::to_string)
            .collect()
    };
    if !first.starts_with('#') || columns(first) != columns(header) {
        return Err(LineRef { path, line: 1 }.error(format!(
            "expected the header '{header}', found '{}'",
            printable(first)
        )));
    }
    if let Some((line, _)) = data_lines(&text).nth(MAX_POSES) {
        return Err(LineRef { path, line }.error(format!(
            "more than {MAX_POSES} rows, the most a EuRoC data.csv may hold"
        )));
    }
    Ok(text)
}

/// Refuses a timestamp that does not come after the previous line's.
fn check_increasing(at: &LineRef, previous: Option<u64>, t_ns: u64) -> Result<(), CoreError> {
    match previous {
        Some(before) if t_ns <= before => Err(at.error(format!(
            "timestamp {t_ns} ns does not come after the previous line's {before} ns; expected increasing timestamps"
        ))),
        _ => Ok(()),
    }
}

/// The exactly `N` fields of a line, all finite numbers, the first an integer nanosecond stamp.
fn row<const N: usize>(
    at: &LineRef,
    content: &str,
    layout: &str,
) -> Result<(u64, [f64; N]), CoreError> {
    let parts: Vec<&str> = fields(content).collect();
    let values = at.numbers::<N>(parts.iter().copied(), true, layout)?;
    Ok((at.nanoseconds(1, parts[0], layout)?, values))
}

/// `camN/data.csv`: its frames, each image in `data_dir`, which must be there unless
/// `images_deleted` (frames deleted after use: only their times are read).
pub fn read_camera_csv(
    path: &Path,
    data_dir: &Path,
    images_deleted: bool,
) -> Result<Vec<EurocFrame>, CoreError> {
    let text = read_checked(path, CAMERA_HEADER, "a EuRoC camera data.csv")?;
    let mut frames: Vec<EurocFrame> = Vec::new();
    for (line, content) in data_lines(&text) {
        let at = LineRef { path, line };
        let parts: Vec<&str> = fields(content).collect();
        let [t, name] = parts.as_slice() else {
            return Err(at.error(format!(
                "expected {CAMERA_LAYOUT}, found {} field{}",
                parts.len(),
                if parts.len() == 1 { "" } else { "s" }
            )));
        };
        let t_ns = at.nanoseconds(1, t, CAMERA_LAYOUT)?;
        check_increasing(&at, frames.last().map(|f| f.t_ns), t_ns)?;
        let plain = !name.is_empty()
            && !name.contains(['/', '\\'])
            && !name.chars().any(char::is_control)
            && *name != "."
            && *name != "..";
        if !plain {
            return Err(at.error(format!(
                "file name '{}': expected a plain name inside {}",
                printable(name),
                data_dir.display()
            )));
        }
        let image: PathBuf = data_dir.join(name);
        if !images_deleted && !image.is_file() {
            return Err(at.error(format!(
                "names {}, which is missing; expected an image there",
                printable(&image.display().to_string())
            )));
        }
        frames.push(EurocFrame { t_ns, path: image });
    }
    Ok(frames)
}

pub fn read_imu_csv(path: &Path) -> Result<Vec<ImuSample>, CoreError> {
    let text = read_checked(path, IMU_HEADER, "a EuRoC IMU data.csv")?;
    let mut samples: Vec<ImuSample> = Vec::new();
    for (line, content) in data_lines(&text) {
        let at = LineRef { path, line };
        let (t_ns, [_, wx, wy, wz, ax, ay, az]) = row::<7>(&at, content, IMU_LAYOUT)?;
        check_increasing(&at, samples.last().map(|s| s.t_ns), t_ns)?;
        samples.push(ImuSample {
            t_ns,
            gyro: DVec3::new(wx, wy, wz),
            accel: DVec3::new(ax, ay, az),
        });
    }
    Ok(samples)
}

pub fn read_ground_truth_csv(path: &Path) -> Result<Vec<GroundTruthState>, CoreError> {
    let text = read_checked(path, GROUND_TRUTH_HEADER, "a EuRoC ground-truth data.csv")?;
    let mut states: Vec<GroundTruthState> = Vec::new();
    for (line, content) in data_lines(&text) {
        let at = LineRef { path, line };
        let (t_ns, v) = row::<17>(&at, content, GROUND_TRUTH_LAYOUT)?;
        check_increasing(&at, states.last().map(|s| s.t_ns), t_ns)?;
        let pose_columns: [f64; 7] = std::array::from_fn(|i| v[1 + i]);
        states.push(GroundTruthState {
            t_ns,
            world_from_body: pose_from_columns(&at, pose_columns)?,
            velocity: DVec3::new(v[8], v[9], v[10]),
            gyro_bias: DVec3::new(v[11], v[12], v[13]),
            accel_bias: DVec3::new(v[14], v[15], v[16]),
        });
    }
    Ok(states)
}
