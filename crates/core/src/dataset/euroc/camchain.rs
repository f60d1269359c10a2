//! TUM-VI's calibration of its EuRoC-style export, `dso/camchain.yaml`: Kalibr's camera chain,
//! one block per camera (`cam0:`, `cam1:`, …) with `T_cam_imu` (IMU to camera, 4×4, one `- [..]`
//! line per row), pinhole `intrinsics` and `resolution`, and for every camera after the first
//! `T_cn_cnm1` (the camera before it to this one). Read for the cameras' poses and sizes;
//! [`Camchain::rewritten`] replaces the rows of the matrices that a moved camera changes and keeps
//! every other byte of the file.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use super::sensor_yaml::{float, resolution, without_comment};
use crate::trajectory_io::lines::LineRef;
use crate::{printable, read_text_file, CoreError, Intrinsics, Pose};

/// A 4×4 matrix of the file: its value and the lines (0-based) of its four rows.
#[derive(Clone, Debug, PartialEq)]
struct Matrix {
    pose: Pose,
    row_lines: [usize; 4],
}

/// One camera's block.
#[derive(Clone, Debug, PartialEq)]
pub struct CamchainCamera {
    /// The block's key: `cam0`, `cam1`, …
    pub name: String,
    /// `T_cam_imu`: IMU (the body) to camera.
    pub camera_from_imu: Pose,
    pub intrinsics: Intrinsics,
    /// `rostopic:` (empty without one).
    pub rostopic: String,
    t_cam_imu: Matrix,
    t_cn_cnm1: Option<Matrix>,
}

/// A parsed camchain.yaml with its text.
#[derive(Clone, Debug, PartialEq)]
pub struct Camchain {
    pub path: PathBuf,
    /// In the file's order.
    pub cameras: Vec<CamchainCamera>,
    text: String,
}

/// A value under a camera's key: a scalar, a flow list `[..]`, or the `- [..]` rows after a
/// bare `key:` line (with their lines, 0-based).
#[derive(Debug)]
enum Value {
    Scalar(String),
    List(Vec<String>),
    Rows(Vec<(usize, Vec<String>)>),
}

/// One `camN:` block: key → (line, 1-based, of the key; value).
struct Block {
    name: String,
    line: usize,
    keys: BTreeMap<String, (usize, Value)>,
}

fn flow_list(at: &LineRef, key: &str, text: &str) -> Result<Vec<String>, CoreError> {
    let inside = text
        .strip_prefix('[')
        .and_then(|t| t.strip_suffix(']'))
        .ok_or_else(|| {
            at.error(format!(
                "'{key}': expected a list [a, b, …] on one line, found '{}'",
                printable(text)
            ))
        })?;
    Ok(inside.split(',').map(|s| s.trim().to_string()).collect())
}

fn parse_blocks(path: &Path, text: &str) -> Result<Vec<Block>, CoreError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut blocks: Vec<Block> = Vec::new();
    // The bare `key:` whose rows follow.
    let mut rows_of: Option<String> = None;
    for (index, raw) in text.lines().enumerate() {
        let content = without_comment(raw);
        let at = LineRef {
            path,
            line: index + 1,
        };
        let trimmed = content.trim();
        if trimmed.is_empty() || content.starts_with('%') || trimmed == "---" {
            continue;
        }
        if !content.starts_with([' ', '\t']) {
            let name = trimmed.strip_suffix(':').filter(|n| is_camera_key(n));
            let Some(name) = name else {
                return Err(at.error(format!(
                    "'{}': expected a camera block 'cam0:', 'cam1:', … (a Kalibr camchain)",
                    printable(trimmed)
                )));
            };
            if blocks.iter().any(|b| b.name == name) {
                return Err(at.error(format!("'{name}:' is given twice")));
            }
            blocks.push(Block {
                name: name.to_string(),
                line: index + 1,
                keys: BTreeMap::new(),
            });
            rows_of = None;
            continue;
        }
        let Some(block) = blocks.last_mut() else {
            return Err(at.error("indented line before any 'cam0:' block"));
        };
        if let Some(row) = trimmed.strip_prefix('-') {
            let Some(key) = &rows_of else {
                return Err(at.error("a '- [..]' row that follows no 'T_…:' key"));
            };
            let items = flow_list(&at, key, row.trim())?;
            if let Some((_, Value::Rows(rows))) = block.keys.get_mut(key) {
                rows.push((index, items));
            }
            continue;
        }
        let Some((key, rest)) = trimmed.split_once(':') else {
            return Err(at.error(format!(
                "expected 'key: value', found '{}'",
                printable(trimmed)
            )));
        };
        let (key, rest) = (key.trim().to_string(), rest.trim());
        let value = if rest.is_empty() {
            rows_of = Some(key.clone());
            Value::Rows(Vec::new())
        } else {
            rows_of = None;
            if rest.starts_with('[') {
                Value::List(flow_list(&at, &key, rest)?)
            } else {
                Value::Scalar(rest.to_string())
            }
        };
        if block.keys.contains_key(&key) {
            return Err(at.error(format!(
                "'{}' is given twice in '{}:'",
                printable(&key),
                block.name
            )));
        }
        block.keys.insert(key, (index + 1, value));
    }
    Ok(blocks)
}

/// `cam` followed by digits.
fn is_camera_key(name: &str) -> bool {
    name.strip_prefix("cam")
        .is_some_and(|d| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit()))
}

impl Block {
    fn get(&self, path: &Path, key: &str, what: &str) -> Result<(usize, &Value), CoreError> {
        let (line, value) = self.keys.get(key).ok_or_else(|| {
            LineRef {
                path,
                line: self.line,
            }
            .error(format!("'{}:' has no '{key}' (expected {what})", self.name))
        })?;
        Ok((*line, value))
    }

    fn numbers<'p, const N: usize>(
        &self,
        path: &'p Path,
        key: &str,
        what: &str,
    ) -> Result<([f64; N], LineRef<'p>), CoreError> {
        let (line, value) = self.get(path, key, what)?;
        let at = LineRef { path, line };
        let Value::List(items) = value else {
            return Err(at.error(format!("'{key}': expected a list [..] of {what}")));
        };
        let values = at.numbers::<N>(items.iter().map(String::as_str), true, what)?;
        Ok((values, at))
    }

    fn matrix(&self, path: &Path, key: &str) -> Result<Option<Matrix>, CoreError> {
        const WHAT: &str = "4 rows '- [a, b, c, d]' of a rigid 4x4 transform";
        let Some((line, value)) = self.keys.get(key) else {
            return Ok(None);
        };
        let at = LineRef { path, line: *line };
        let Value::Rows(rows) = value else {
            return Err(at.error(format!("'{key}': expected {WHAT}")));
        };
        if rows.len() != 4 {
            return Err(at.error(format!("'{key}': {} rows; expected {WHAT}", rows.len())));
        }
        let mut data = [0.0; 16];
        for (r, (row_line, items)) in rows.iter().enumerate() {
            let row_at = LineRef {
                path,
                line: row_line + 1,
            };
            let row = row_at.numbers::<4>(items.iter().map(String::as_str), true, WHAT)?;
            data[4 * r..4 * r + 4].copy_from_slice(&row);
        }
        Ok(Some(Matrix {
            pose: at.pose_from_rows(&data)?,
            row_lines: [rows[0].0, rows[1].0, rows[2].0, rows[3].0],
        }))
    }

    fn camera(&self, path: &Path) -> Result<CamchainCamera, CoreError> {
        match self.get(path, "camera_model", "'pinhole'")? {
            (_, Value::Scalar(model)) if model == "pinhole" => {}
            (line, _) => {
                return Err(LineRef { path, line }.error(format!(
                    "{}: camera_model: expected 'pinhole' (the only camera model rslam reads)",
                    self.name
                )))
            }
        }
        let Some(t_cam_imu) = self.matrix(path, "T_cam_imu")? else {
            return Err(LineRef {
                path,
                line: self.line,
            }
            .error(format!(
                "'{}:' has no 'T_cam_imu' (expected 4 rows of the IMU-to-camera transform)",
                self.name
            )));
        };
        let side = "two whole numbers of pixels [w, h]";
        let (wh, at) = self.numbers::<2>(path, "resolution", side)?;
        let size = resolution(&at, wh)?;
        let ([fx, fy, cx, cy], at) =
            self.numbers::<4>(path, "intrinsics", "4 numbers [fu, fv, pu, pv]")?;
        let intrinsics = Intrinsics::from_pinhole(size, [fx, fy, cx, cy])
            .map_err(|message| at.error(format!("intrinsics: {message}")))?;
        let rostopic = match self.keys.get("rostopic") {
            Some((_, Value::Scalar(topic))) => topic.clone(),
            _ => String::new(),
        };
        Ok(CamchainCamera {
            name: self.name.clone(),
            camera_from_imu: t_cam_imu.pose,
            intrinsics,
            rostopic,
            t_cam_imu,
            t_cn_cnm1: self.matrix(path, "T_cn_cnm1")?,
        })
    }
}

/// Reads `dso/camchain.yaml`.
pub fn read_camchain(path: &Path) -> Result<Camchain, CoreError> {
    let text = read_text_file(path, "a Kalibr camchain.yaml")?;
    let cameras = parse_blocks(path, &text)?
        .iter()
        .map(|block| block.camera(path))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Camchain {
        path: path.to_path_buf(),
        cameras,
        text,
    })
}

/// `[a, b, c, d]` of each row of `pose`.
fn rows(pose: &Pose) -> [String; 4] {
    let m = pose.to_row_major();
    std::array::from_fn(|r| {
        let row: Vec<String> = m[4 * r..4 * r + 4].iter().map(|v| float(*v)).collect();
        format!("[{}]", row.join(", "))
    })
}

impl Camchain {
    pub fn camera(&self, name: &str) -> Option<&CamchainCamera> {
        self.cameras.iter().find(|c| c.name == name)
    }

    /// The file's bytes with the cameras named in `camera_from_imu` at their new `T_cam_imu`:
    /// their rows are rewritten, and `T_cn_cnm1` of each camera that moved or whose previous
    /// camera (`cam<n-1>`) moved. Every other line stays byte for byte.
    pub fn rewritten(&self, camera_from_imu: &BTreeMap<String, Pose>) -> String {
        let pose_of = |name: &str| {
            camera_from_imu
                .get(name)
                .copied()
                .or_else(|| self.camera(name).map(|c| c.camera_from_imu))
        };
        let mut replaced: BTreeMap<usize, String> = BTreeMap::new();
        let mut set = |matrix: &Matrix, pose: &Pose| {
            for (line, row) in matrix.row_lines.iter().zip(rows(pose)) {
                replaced.insert(*line, row);
            }
        };
        for camera in &self.cameras {
            let moved = camera_from_imu.contains_key(&camera.name);
            if let Some(pose) = camera_from_imu.get(&camera.name) {
                set(&camera.t_cam_imu, pose);
            }
            let previous = camera
                .name
                .strip_prefix("cam")
                .and_then(|n| n.parse::<usize>().ok())
                .and_then(|n| n.checked_sub(1))
                .map(|n| format!("cam{n}"));
            let (Some(matrix), Some(previous)) = (&camera.t_cn_cnm1, previous) else {
                continue;
            };
            if !moved && !camera_from_imu.contains_key(&previous) {
                continue;
            }
            if let (Some(this), Some(before)) = (pose_of(&camera.name), pose_of(&previous)) {
                set(matrix, &this.compose(&before.inverse()));
            }
        }
        self.text
            .split_inclusive('\n')
            .enumerate()
            .map(|(index, line)| match replaced.get(&index) {
                Some(row) => {
                    let content = line.trim_end_matches(['\n', '\r']);
                    let ending = &line[content.len()..];
                    let prefix = content.split('[').next().unwrap_or("");
                    format!("{prefix}{row}{ending}")
                }
                None => line.to_string(),
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;

    /// TUM-VI's 512×512 calibration as OpenVINS ships it (config/tum_vi/kalibr_imucam_chain.yaml:
    /// a `%YAML` line, comments after keys, rows indented under their key), cam1 with a
    /// `T_cn_cnm1` added, Windows line endings.
    const OPENVINS_STYLE: &str = "%YAML:1.0 # need to specify the file type at the top!\r
\r
cam0:\r
  T_cam_imu: #rotation from IMU to camera R_ItoC, position of IMU in camera p_IinC\r
    - [-0.9995250378696743, 0.029615343885863205, -0.008522328211654736, 0.04727988224914392]\r
    - [0.0075019185074052044, -0.03439736061393144, -0.9993800792498829, -0.047443232143367084]\r
    - [-0.02989013031643309, -0.998969345370175, 0.03415885127385616, -0.0681999605066297]\r
    - [0.0, 0.0, 0.0, 1.0]\r
  cam_overlaps: [1]\r
  camera_model: pinhole\r
  distortion_coeffs: [0.0034823894022493434, 0.0007150348452162257, -0.0020532361418706202, 0.00020293673591811182]\r
  distortion_model: equidistant\r
  intrinsics: [190.97847715128717, 190.9733070521226, 254.93170605935475, 256.8974428996504]\r
  resolution: [512, 512]\r
  rostopic: /cam0/image_raw\r
cam1:\r
  T_cam_imu: #rotation from IMU to camera R_ItoC, position of IMU in camera p_IinC\r
    - [-0.9995110484978581, 0.030299116376600627, -0.0077218830287333565, -0.053697434688869734]\r
    - [0.008104079263822521, 0.012511643720192351, -0.9998888851620987, -0.046131737923635924]\r
    - [-0.030199136245891378, -0.9994625667418545, -0.012751072573940885, -0.07149261284195751]\r
    - [0.0, 0.0, 0.0, 1.0]\r
  T_cn_cnm1:\r
    - [0.9999994457734942, -0.0008233639921576, -0.0006561436136444, -0.1010611027518054]\r
    - [0.0007916877528168, 0.9988994619156748, -0.0468960362405898, -0.0019764575873431]\r
    - [0.0006940340102243, 0.0468954907887005, 0.9988995601463044, -0.0011756424802046]\r
    - [0.0, 0.0, 0.0, 1.0]\r
  camera_model: pinhole\r
  intrinsics: [190.44236969414825, 190.4344384721956, 252.59949716835982, 254.91723064636983]\r
  resolution: [512, 512]\r
";

    fn read(text: &str) -> (tempfile::TempDir, Camchain) {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("camchain.yaml");
        std::fs::write(&path, text).unwrap();
        let chain = read_camchain(&path).unwrap();
        (dir, chain)
    }

    fn changed_lines(a: &str, b: &str) -> Vec<usize> {
        assert_eq!(a.lines().count(), b.lines().count());
        (a.lines().zip(b.lines()).enumerate())
            .filter(|(_, (x, y))| x != y)
            .map(|(i, _)| i + 1)
            .collect()
    }

    #[test]
    fn a_kalibr_camchain_is_read_with_each_camera_s_pose_and_size() {
        let (_dir, chain) = read(OPENVINS_STYLE);
        assert_eq!(chain.cameras.len(), 2);
        let cam0 = chain.camera("cam0").unwrap();
        assert_eq!(
            cam0.camera_from_imu.translation,
            DVec3::new(
                0.04727988224914392,
                -0.047443232143367084,
                -0.0681999605066297
            )
        );
        let row0 = cam0.camera_from_imu.to_row_major();
        assert!((row0[1] - 0.029615343885863205).abs() < 1e-9, "{row0:?}");
        assert_eq!((cam0.intrinsics.width, cam0.intrinsics.height), (512, 512));
        assert_eq!(cam0.intrinsics.fx, 190.97847715128717);
        assert_eq!(cam0.rostopic, "/cam0/image_raw");
        assert_eq!(chain.camera("cam1").unwrap().rostopic, "");
        assert!(chain.camera("cam2").is_none());
    }

    #[test]
    fn rewriting_replaces_the_moved_camera_s_rows_and_the_t_cn_cnm1_it_is_part_of_only() {
        let (dir, chain) = read(OPENVINS_STYLE);
        assert_eq!(chain.rewritten(&BTreeMap::new()), OPENVINS_STYLE);

        let cam0 = chain.cameras[0].camera_from_imu;
        let cam1 = chain.cameras[1].camera_from_imu;
        let nudge = Pose::new(
            glam::DQuat::from_rotation_y(0.01),
            DVec3::new(0.003, -0.002, 0.001),
        );
        let moved_cam1 = nudge.compose(&cam1);
        let text = chain.rewritten(&BTreeMap::from([("cam1".to_string(), moved_cam1)]));
        // cam1's T_cam_imu rows (18–20) and T_cn_cnm1 rows (23–25); 0 0 0 1 is written as it was.
        assert_eq!(
            changed_lines(OPENVINS_STYLE, &text),
            [18, 19, 20, 23, 24, 25]
        );
        assert_eq!(
            text.matches("\r\n").count(),
            OPENVINS_STYLE.matches("\r\n").count()
        );
        assert!(text.contains("    - [0.0, 0.0, 0.0, 1.0]\r\n  T_cn_cnm1:"));
        let path = dir.path().join("camchain.yaml");
        std::fs::write(&path, &text).unwrap();
        let again = read_camchain(&path).unwrap();
        assert_eq!(again.cameras[0].camera_from_imu, cam0);
        let back = again.cameras[1].camera_from_imu;
        assert!((back.translation - moved_cam1.translation).length() < 1e-15);
        assert!(back.rotation.angle_between(moved_cam1.rotation) < 1e-9);
        let t_cn_cnm1 = again.cameras[1].t_cn_cnm1.as_ref().unwrap().pose;
        let expected = moved_cam1.compose(&cam0.inverse());
        assert!((t_cn_cnm1.translation - expected.translation).length() < 1e-15);

        // cam0 moved: its rows, and cam1's T_cn_cnm1 (cam1 relative to it).
        let text = chain.rewritten(&BTreeMap::from([(
            "cam0".to_string(),
            nudge.compose(&cam0),
        )]));
        assert_eq!(changed_lines(OPENVINS_STYLE, &text), [5, 6, 7, 23, 24, 25]);
    }

    #[test]
    fn malformed_blocks_name_the_file_line_and_what_was_expected() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("camchain.yaml");
        for (from, to, expected) in [
            (
                "  camera_model: pinhole\r\n  intrinsics: [190.44",
                "  camera_model: omni\r\n  intrinsics: [190.44",
                "camchain.yaml:27: cam1: camera_model: expected 'pinhole'",
            ),
            (
                "  resolution: [512, 512]\r\n  rostopic",
                "  resolution: [512, 0]\r\n  rostopic",
                "camchain.yaml:14: resolution [512, 0]: expected two whole numbers",
            ),
            (
                "    - [0.0, 0.0, 0.0, 1.0]\r\n  cam_overlaps",
                "    - [0.0, 0.0, 1.0, 1.0]\r\n  cam_overlaps",
                "camchain.yaml:4: last matrix row is",
            ),
            (
                "  intrinsics: [190.97847715128717, ",
                "  intrinsics: [",
                "camchain.yaml:13: expected 4 numbers [fu, fv, pu, pv], found 3 fields",
            ),
            (
                "cam1:\r\n  T_cam_imu: #rotation",
                "cam1:\r\n  T_cam_imuu: #rotation",
                "camchain.yaml:16: 'cam1:' has no 'T_cam_imu'",
            ),
            (
                "    - [0.0007916877528168,",
                "    - (0.0007916877528168,",
                "camchain.yaml:24: 'T_cn_cnm1': expected a list [a, b, …] on one line",
            ),
            (
                "  cam_overlaps: [1]",
                "  cam_overlaps [1]",
                "camchain.yaml:9: expected 'key: value'",
            ),
        ] {
            assert!(OPENVINS_STYLE.contains(from), "{from}");
            std::fs::write(&path, OPENVINS_STYLE.replacen(from, to, 1)).unwrap();
            let err = read_camchain(&path).unwrap_err().to_string();
            assert!(err.contains(expected), "{err}\nexpected: {expected}");
            assert!(!err.contains('\n'), "{err}");
        }
    }
}
