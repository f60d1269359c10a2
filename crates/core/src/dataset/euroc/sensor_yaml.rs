//! `sensor.yaml` of a EuRoC camera or IMU, written as the published MH_01_easy files are (the
//! same keys, order and comments; `T_BS` as a 4×4 row-major `data:` list) and read back with a
//! reader for the YAML subset they use: `key: value`, one nested map (`T_BS`), flow lists
//! `[a, b, …]` that may span lines, `#` comments, `%` directives.

use std::collections::BTreeMap;
use std::path::Path;

use super::{CameraColour, EurocCamera, EurocImu, RadialTangential};
use crate::limits::MAX_IMAGE_SIDE;
use crate::trajectory_io::lines::LineRef;
use crate::{printable, read_text_file, CoreError, Intrinsics, Pose};

/// First line of a camera's sensor.yaml in the published dataset.
pub const CAMERA_YAML_FIRST_LINE: &str = "# General sensor definitions.";
/// First line of the IMU's sensor.yaml in the published dataset.
pub const IMU_YAML_FIRST_LINE: &str = "#Default imu sensor yaml file";

/// A number as YAML 1.1 readers (PyYAML, yaml-cpp, OpenCV) all read as a float: Rust's shortest
/// round-trip digits, never an exponent, always a decimal point.
pub(super) fn float(v: f64) -> String {
    let text = format!("{v}");
    if text.contains('.') {
        text
    } else {
        format!("{text}.0")
    }
}

/// A rate as EuRoC writes it: `20`, not `20.0`, when whole.
fn rate(v: f64) -> String {
    format!("{v}")
}

fn t_bs(pose: &Pose) -> String {
    let m = pose.to_row_major();
    let rows: Vec<String> = m
        .chunks_exact(4)
        .map(|row| row.iter().map(|v| float(*v)).collect::<Vec<_>>().join(", "))
        .collect();
    format!(
        "T_BS:\n  cols: 4\n  rows: 4\n  data: [{}]\n",
        rows.join(",\n         ")
    )
}

/// A comment on one line (a line break would end the YAML value).
fn one_line(text: &str) -> String {
    printable(text)
}

pub fn camera_yaml(camera: &EurocCamera) -> String {
    let k = &camera.intrinsics;
    let d = camera.distortion.to_array().map(float);
    format!(
        "{CAMERA_YAML_FIRST_LINE}\nsensor_type: camera\ncomment: {comment}\n\n\
         # Sensor extrinsics wrt. the body-frame.\n{t_bs}\n\
         # Camera specific definitions.\nrate_hz: {rate}\nresolution: [{w}, {h}]\n\
         camera_model: pinhole\nintrinsics: [{fu}, {fv}, {cu}, {cv}] #fu, fv, cu, cv\n\
         distortion_model: radial-tangential\ndistortion_coefficients: [{d}]\n",
        comment = one_line(&camera.comment),
        t_bs = t_bs(&camera.body_from_camera),
        rate = rate(camera.rate_hz),
        w = k.width,
        h = k.height,
        fu = float(k.fx),
        fv = float(k.fy),
        cu = float(k.cx),
        cv = float(k.cy),
        d = d.join(", "),
    )
}

pub fn imu_yaml(imu: &EurocImu) -> String {
    format!(
        "{IMU_YAML_FIRST_LINE}\nsensor_type: imu\ncomment: {comment}\n\n\
         # Sensor extrinsics wrt. the body-frame.\n{t_bs}rate_hz: {rate}\n\n\
         # inertial sensor noise model parameters (static)\n\
         gyroscope_noise_density: {gn}     # [ rad / s / sqrt(Hz) ]   ( gyro \"white noise\" )\n\
         gyroscope_random_walk: {gw}       # [ rad / s^2 / sqrt(Hz) ] ( gyro bias diffusion )\n\
         accelerometer_noise_density: {an}  # [ m / s^2 / sqrt(Hz) ]   ( accel \"white noise\" )\n\
         accelerometer_random_walk: {aw}    # [ m / s^3 / sqrt(Hz) ].  ( accel bias diffusion )\n",
        comment = one_line(&imu.comment),
        t_bs = t_bs(&imu.body_from_imu),
        rate = rate(imu.rate_hz),
        gn = float(imu.gyroscope_noise_density),
        gw = float(imu.gyroscope_random_walk),
        an = float(imu.accelerometer_noise_density),
        aw = float(imu.accelerometer_random_walk),
    )
}

/// One value of the YAML subset, with the line it starts on.
#[derive(Debug)]
struct Entry {
    line: usize,
    value: Value,
}

#[derive(Debug)]
enum Value {
    Scalar(String),
    List(Vec<String>),
    Map(BTreeMap<String, Entry>),
}

/// `text` up to a `#` that starts a comment (at the start or after a blank), trimmed at the end.
pub(super) fn without_comment(text: &str) -> &str {
    let bytes = text.as_bytes();
    let end = (0..bytes.len())
        .find(|&i| bytes[i] == b'#' && (i == 0 || bytes[i - 1].is_ascii_whitespace()))
        .unwrap_or(bytes.len());
    text[..end].trim_end()
}

/// A parsed sensor.yaml: its top-level keys.
struct Document<'p> {
    path: &'p Path,
    keys: BTreeMap<String, Entry>,
}

fn parse<'p>(path: &'p Path, text: &str) -> Result<Document<'p>, CoreError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let lines: Vec<(usize, &str)> = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, without_comment(l)))
        .filter(|(_, l)| !l.trim().is_empty() && !l.starts_with('%') && l.trim() != "---")
        .collect();
    let mut keys = BTreeMap::new();
    let mut open_map: Option<(String, usize, BTreeMap<String, Entry>)> = None;
    let mut i = 0;
    while i < lines.len() {
        let (line, content) = lines[i];
        let at = LineRef { path, line };
        let indented = content.starts_with([' ', '\t']);
        let Some((key, rest)) = content.trim().split_once(':') else {
            return Err(at.error(format!(
                "expected 'key: value', found '{}'",
                printable(content.trim())
            )));
        };
        let (key, rest) = (key.trim().to_string(), rest.trim());
        if key.chars().any(char::is_control) {
            return Err(at.error(format!(
                "key '{}': expected letters, digits and '_'",
                printable(&key)
            )));
        }
        i += 1;
        let value = if let Some(list) = rest.strip_prefix('[') {
            // A flow list, possibly continued on the following lines up to its ']'.
            let mut joined = list.to_string();
            // Continuation lines are indented deeper than the key; a line that is not ends it.
            let indent = |text: &str| text.len() - text.trim_start().len();
            while !joined.contains(']') {
                let Some((_, more)) = lines.get(i).filter(|(_, l)| indent(l) > indent(content))
                else {
                    return Err(at.error(format!("'{key}': list opened with '[' is not closed")));
                };
                joined.push(' ');
                joined.push_str(more.trim());
                i += 1;
            }
            let (inside, after) = joined.split_once(']').unwrap_or((&joined, ""));
            if !after.trim().is_empty() {
                return Err(at.error(format!(
                    "'{key}': unexpected '{}' after the list's ']'",
                    printable(after.trim())
                )));
            }
            let items: Vec<String> = inside.split(',').map(|s| s.trim().to_string()).collect();
            Value::List(if items.len() == 1 && items[0].is_empty() {
                Vec::new()
            } else {
                items
            })
        } else if rest.is_empty() && !indented {
            // A nested map follows on the indented lines.
            close_map(&mut keys, open_map.take());
            open_map = Some((key, line, BTreeMap::new()));
            continue;
        } else {
            Value::Scalar(rest.to_string())
        };
        let entry = Entry { line, value };
        match (&mut open_map, indented) {
            (Some((_, _, map)), true) => {
                map.insert(key, entry);
            }
            (None, true) => {
                return Err(at.error(format!(
                    "'{key}' is indented but belongs to no map; expected 'key: value' at the start of the line"
                )))
            }
            (_, false) => {
                close_map(&mut keys, open_map.take());
                keys.insert(key, entry);
            }
        }
    }
    close_map(&mut keys, open_map);
    Ok(Document { path, keys })
}

/// Stores a nested map whose indented lines have ended under its key.
fn close_map(
    keys: &mut BTreeMap<String, Entry>,
    map: Option<(String, usize, BTreeMap<String, Entry>)>,
) {
    if let Some((name, line, map)) = map {
        keys.insert(
            name,
            Entry {
                line,
                value: Value::Map(map),
            },
        );
    }
}

impl Document<'_> {
    fn entry<'d>(
        &'d self,
        map: &'d BTreeMap<String, Entry>,
        key: &str,
        what: &str,
    ) -> Result<&'d Entry, CoreError> {
        map.get(key).ok_or_else(|| {
            CoreError::bad_file(self.path, format!("missing key '{key}' (expected {what})"))
        })
    }

    fn at(&self, entry: &Entry) -> LineRef<'_> {
        LineRef {
            path: self.path,
            line: entry.line,
        }
    }

    fn scalar_in<'d>(
        &'d self,
        map: &'d BTreeMap<String, Entry>,
        key: &str,
        what: &str,
    ) -> Result<(&'d str, LineRef<'d>), CoreError> {
        let entry = self.entry(map, key, what)?;
        match &entry.value {
            Value::Scalar(text) => Ok((text.as_str(), self.at(entry))),
            _ => Err(self.at(entry).error(format!("'{key}': expected {what}"))),
        }
    }

    /// The optional free-text `comment:`.
    fn comment(&self) -> String {
        match self.keys.get("comment").map(|e| &e.value) {
            Some(Value::Scalar(text)) => text.clone(),
            _ => String::new(),
        }
    }

    fn expect_text(&self, key: &str, expected: &str, why: &str) -> Result<(), CoreError> {
        let (text, at) = self.scalar_in(&self.keys, key, &format!("'{expected}'"))?;
        if text == expected {
            Ok(())
        } else {
            Err(at.error(format!(
                "{key} '{}': expected '{expected}'{why}",
                printable(text)
            )))
        }
    }

    fn number_in<'d>(
        &'d self,
        map: &'d BTreeMap<String, Entry>,
        key: &str,
        what: &str,
    ) -> Result<(f64, LineRef<'d>), CoreError> {
        let (text, at) = self.scalar_in(map, key, what)?;
        match text.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok((v, at)),
            _ => Err(at.error(format!("{key} '{}': expected {what}", printable(text)))),
        }
    }

    fn positive(&self, key: &str, what: &str) -> Result<f64, CoreError> {
        let (v, at) = self.number_in(&self.keys, key, what)?;
        if v > 0.0 {
            Ok(v)
        } else {
            Err(at.error(format!("{key} {v}: expected {what}")))
        }
    }

    fn non_negative(&self, key: &str, what: &str) -> Result<f64, CoreError> {
        let (v, at) = self.number_in(&self.keys, key, what)?;
        if v >= 0.0 {
            Ok(v)
        } else {
            Err(at.error(format!("{key} {v}: expected {what}")))
        }
    }

    fn numbers_in<'d, const N: usize>(
        &'d self,
        map: &'d BTreeMap<String, Entry>,
        key: &str,
        what: &str,
    ) -> Result<([f64; N], LineRef<'d>), CoreError> {
        let entry = self.entry(map, key, what)?;
        let at = self.at(entry);
        let Value::List(items) = &entry.value else {
            return Err(at.error(format!("'{key}': expected a list [..] of {what}")));
        };
        let values = at.numbers::<N>(items.iter().map(String::as_str), true, what)?;
        Ok((values, at))
    }

    /// `T_BS: {cols: 4, rows: 4, data: [16 numbers]}`, row-major, a rigid transform.
    fn t_bs(&self) -> Result<Pose, CoreError> {
        const WHAT: &str = "'cols: 4', 'rows: 4' and 'data: [16 numbers]' (row-major 4x4)";
        let entry = self.entry(&self.keys, "T_BS", WHAT)?;
        let Value::Map(map) = &entry.value else {
            return Err(self.at(entry).error(format!("'T_BS': expected {WHAT}")));
        };
        for key in ["cols", "rows"] {
            let (v, at) = self.number_in(map, key, "4")?;
            if v != 4.0 {
                return Err(at.error(format!("T_BS {key} {v}: expected 4")));
            }
        }
        let (data, at) = self.numbers_in::<16>(map, "data", "16 numbers (row-major 4x4 T_BS)")?;
        at.pose_from_rows(&data)
    }
}

/// `resolution: [w, h]` as whole pixels, each 1 to [`MAX_IMAGE_SIDE`].
pub(super) fn resolution(at: &LineRef, [w, h]: [f64; 2]) -> Result<(u32, u32), CoreError> {
    let pixels =
        |v: f64| (v >= 1.0 && v.fract() == 0.0 && v <= MAX_IMAGE_SIDE as f64).then_some(v as u32);
    match (pixels(w), pixels(h)) {
        (Some(width), Some(height)) => Ok((width, height)),
        _ => Err(at.error(format!(
            "resolution [{w}, {h}]: expected two whole numbers of pixels [w, h], each 1 to {MAX_IMAGE_SIDE}"
        ))),
    }
}

/// A camera's sensor.yaml; `name` is its folder (`cam0`). The colour is not in the file: it
/// comes back as [`CameraColour::Grey`] for the reader to settle.
pub fn read_camera_yaml(path: &Path, name: &str) -> Result<EurocCamera, CoreError> {
    let text = read_text_file(path, "a EuRoC camera sensor.yaml")?;
    let doc = parse(path, &text)?;
    doc.expect_text("sensor_type", "camera", "")?;
    doc.expect_text(
        "camera_model",
        "pinhole",
        " (the only camera model rslam reads)",
    )?;
    doc.expect_text(
        "distortion_model",
        "radial-tangential",
        " (the only distortion model rslam reads)",
    )?;
    let body_from_camera = doc.t_bs()?;
    let rate_hz = doc.positive("rate_hz", "a positive frame rate in Hz")?;
    let (wh, at) = doc.numbers_in::<2>(&doc.keys, "resolution", "two numbers [w, h]")?;
    let size = resolution(&at, wh)?;
    let ([fx, fy, cx, cy], at) =
        doc.numbers_in::<4>(&doc.keys, "intrinsics", "4 numbers [fu, fv, cu, cv]")?;
    let intrinsics = Intrinsics::from_pinhole(size, [fx, fy, cx, cy])
        .map_err(|message| at.error(format!("intrinsics: {message}")))?;
    let (distortion, _) = doc.numbers_in::<4>(
        &doc.keys,
        "distortion_coefficients",
        "4 numbers [k1, k2, p1, p2]",
    )?;
    Ok(EurocCamera {
        name: name.to_string(),
        comment: doc.comment(),
        body_from_camera,
        rate_hz,
        intrinsics,
        distortion: RadialTangential::from_array(distortion),
        colour: CameraColour::Grey,
    })
}

/// The IMU's sensor.yaml.
pub fn read_imu_yaml(path: &Path) -> Result<EurocImu, CoreError> {
    let text = read_text_file(path, "a EuRoC IMU sensor.yaml")?;
    let doc = parse(path, &text)?;
    doc.expect_text("sensor_type", "imu", "")?;
    let density = "a non-negative noise density or random walk";
    Ok(EurocImu {
        comment: doc.comment(),
        body_from_imu: doc.t_bs()?,
        rate_hz: doc.positive("rate_hz", "a positive sample rate in Hz")?,
        gyroscope_noise_density: doc.non_negative("gyroscope_noise_density", density)?,
        gyroscope_random_walk: doc.non_negative("gyroscope_random_walk", density)?,
        accelerometer_noise_density: doc.non_negative("accelerometer_noise_density", density)?,
        accelerometer_random_walk: doc.non_negative("accelerometer_random_walk", density)?,
    })
}

/// Kalibr's IMU file as TUM-VI ships it (`dso/imu_config.yaml`: the four noise parameters,
/// `update_rate`, `rostopic`). TUM-VI's body frame is its IMU's, so `T_BS` is the identity.
pub fn read_kalibr_imu_yaml(path: &Path) -> Result<EurocImu, CoreError> {
    let text = read_text_file(path, "a Kalibr IMU yaml")?;
    let doc = parse(path, &text)?;
    let density = "a non-negative noise density or random walk";
    Ok(EurocImu {
        comment: match doc.keys.get("rostopic").map(|e| &e.value) {
            Some(Value::Scalar(topic)) => topic.clone(),
            _ => String::new(),
        },
        body_from_imu: Pose::IDENTITY,
        rate_hz: doc.positive("update_rate", "a positive sample rate in Hz")?,
        gyroscope_noise_density: doc.non_negative("gyroscope_noise_density", density)?,
        gyroscope_random_walk: doc.non_negative("gyroscope_random_walk", density)?,
        accelerometer_noise_density: doc.non_negative("accelerometer_noise_density", density)?,
        accelerometer_random_walk: doc.non_negative("accelerometer_random_walk", density)?,
    })
}
