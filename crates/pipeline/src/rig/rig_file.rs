//! A rig file (`FILE.toml`): a rig of the user's own, written in the EuRoC layout. Cameras are `cam0`,
//! `cam1`, … in the order given; the keys are those of EuRoC's sensor.yaml (`T_BS` camera-to-body
//! row-major, `rate_hz`, `resolution`, `intrinsics`) and Kalibr's IMU noise names:
//!
//! ```toml
//! name = "wide-stereo"            # optional: the file's stem
//!
//! [[camera]]
//! T_BS = [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]
//! rate_hz = 20
//! resolution = [752, 480]
//! intrinsics = [458.654, 457.296, 367.215, 248.375]   # fu, fv, cu, cv
//! colour = "grey"                 # or "rgb"; optional, grey
//! time_offset_ms = 0              # optional: stamps = capture time + offset
//! comment = "left"                # optional
//!
//! [imu]                           # optional
//! T_BS = [...]                    # optional: the identity (the body is the IMU)
//! rate_hz = 200
//! gyroscope_noise_density = 1.6968e-4
//! gyroscope_random_walk = 1.9393e-5
//! accelerometer_noise_density = 2.0e-3
//! accelerometer_random_walk = 3.0e-3
//! comment = "ADIS16448"           # optional
//!
//! [ros2]                          # optional: names in a ROS 2 bag (rig_bag_names.rs)
//! cam0 = { topic = "/left/image_raw", frame_id = "left" }
//! ```
//!
//! The cameras are pinhole without distortion (rendered frames); the EuRoC layout has no depth.

use std::path::Path;

use rslam_core::dataset::euroc::{CameraColour, EurocCamera, EurocImu, RadialTangential};
use rslam_core::dataset::ros2::BagNames;
use rslam_core::limits::MAX_EUROC_CAMERAS;
use rslam_core::{read_text_file, CoreError, Intrinsics, Pose};
use serde::Deserialize;

use super::preset::Rig;
use super::rig_bag_names::bag_names;
use crate::PipelineError;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RigFile {
    name: Option<String>,
    #[serde(default)]
    camera: Vec<toml::Spanned<CameraFields>>,
    imu: Option<toml::Spanned<ImuFields>>,
    ros2: Option<toml::Spanned<toml::Table>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CameraFields {
    #[serde(rename = "T_BS")]
    t_bs: Vec<f64>,
    rate_hz: f64,
    resolution: [u32; 2],
    intrinsics: [f64; 4],
    #[serde(default)]
    colour: Colour,
    #[serde(default)]
    time_offset_ms: f64,
    comment: Option<String>,
}

#[derive(Deserialize, Default)]
#[serde(rename_all = "lowercase")]
enum Colour {
    #[default]
    Grey,
    Rgb,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ImuFields {
    #[serde(rename = "T_BS")]
    t_bs: Option<Vec<f64>>,
    rate_hz: f64,
    gyroscope_noise_density: f64,
    gyroscope_random_walk: f64,
    accelerometer_noise_density: f64,
    accelerometer_random_walk: f64,
    comment: Option<String>,
}

/// The rig file at `path`; errors name the file and line.
pub fn read_rig_file(path: &Path) -> Result<Rig, PipelineError> {
    let text = read_text_file(path, "a rig file (TOML)")?;
    let at = |offset: usize, message: String| -> PipelineError {
        CoreError::BadLine {
            path: path.to_path_buf(),
            line: text[..offset.min(text.len())].matches('\n').count() + 1,
            message,
        }
        .into()
    };
    let file: RigFile = toml::from_str(&text).map_err(|e| {
        at(
            e.span().map_or(0, |span| span.start),
            e.message().trim_end().replace('\n', "; "),
        )
    })?;
    if file.camera.is_empty() || file.camera.len() > MAX_EUROC_CAMERAS {
        return Err(at(
            0,
            format!(
                "{} [[camera]] tables: expected 1 to {MAX_EUROC_CAMERAS}",
                file.camera.len()
            ),
        ));
    }
    let mut cameras = Vec::new();
    let mut time_offsets_ns = Vec::new();
    for (i, spanned) in file.camera.iter().enumerate() {
        let fields = spanned.get_ref();
        let bad = |message: String| at(spanned.span().start, format!("cam{i}: {message}"));
        let [width, height] = fields.resolution;
        let intrinsics =
            Intrinsics::from_pinhole((width, height), fields.intrinsics).map_err(&bad)?;
        positive_rate(fields.rate_hz).map_err(&bad)?;
        let offset_ns = fields.time_offset_ms * 1e6;
        if !(offset_ns.is_finite() && offset_ns.abs() < 1e12) {
            return Err(bad(format!(
                "time_offset_ms {}: expected a finite number of milliseconds (under 1000 s)",
                fields.time_offset_ms
            )));
        }
        time_offsets_ns.push(offset_ns.round() as i64);
        cameras.push(EurocCamera {
            name: format!("cam{i}"),
            comment: fields
                .comment
                .clone()
                .unwrap_or_else(|| format!("rslam rig camera {i}")),
            body_from_camera: rigid(&fields.t_bs).map_err(&bad)?,
            rate_hz: fields.rate_hz,
            intrinsics,
            distortion: RadialTangential::NONE,
            colour: match fields.colour {
                Colour::Grey => CameraColour::Grey,
                Colour::Rgb => CameraColour::Rgb,
            },
        });
    }
    let imu = file
        .imu
        .as_ref()
        .map(|spanned| {
            let fields = spanned.get_ref();
            let bad = |message: String| at(spanned.span().start, format!("imu: {message}"));
            positive_rate(fields.rate_hz).map_err(&bad)?;
            let noise = [
                ("gyroscope_noise_density", fields.gyroscope_noise_density),
                ("gyroscope_random_walk", fields.gyroscope_random_walk),
                (
                    "accelerometer_noise_density",
                    fields.accelerometer_noise_density,
                ),
                (
                    "accelerometer_random_walk",
                    fields.accelerometer_random_walk,
                ),
            ];
            if let Some((key, value)) = noise.iter().find(|(_, v)| !(v.is_finite() && *v >= 0.0)) {
                return Err(bad(format!(
                    "{key} {value}: expected a finite number, 0 or more"
                )));
            }
            Ok(EurocImu {
                comment: fields
                    .comment
                    .clone()
                    .unwrap_or_else(|| "rslam rig IMU".into()),
                body_from_imu: match &fields.t_bs {
                    Some(rows) => rigid(rows).map_err(&bad)?,
                    None => Pose::IDENTITY,
                },
                rate_hz: fields.rate_hz,
                gyroscope_noise_density: fields.gyroscope_noise_density,
                gyroscope_random_walk: fields.gyroscope_random_walk,
                accelerometer_noise_density: fields.accelerometer_noise_density,
                accelerometer_random_walk: fields.accelerometer_random_walk,
            })
        })
        .transpose()?;
    let name = match file.name {
        Some(name) => name,
        None => path
            .file_stem()
            .map_or_else(|| "rig".into(), |s| s.to_string_lossy().into_owned()),
    };
    let bag_names = match &file.ros2 {
        Some(spanned) => bag_names(spanned.get_ref(), cameras.len(), imu.is_some())
            .map_err(|message| at(spanned.span().start, format!("ros2: {message}")))?,
        None => BagNames::default(),
    };
    Ok(Rig {
        name,
        cameras,
        time_offsets_ns,
        imu,
        bag_names,
    })
}

fn positive_rate(rate_hz: f64) -> Result<(), String> {
    match rate_hz.is_finite() && rate_hz > 0.0 {
        true => Ok(()),
        false => Err(format!(
            "rate_hz {rate_hz}: expected a positive number of Hz"
        )),
    }
}

fn rigid(rows: &[f64]) -> Result<Pose, String> {
    if rows.len() != 16 {
        return Err(format!(
            "T_BS has {} numbers: expected 16 (a row-major 4x4 camera-to-body transform)",
            rows.len()
        ));
    }
    Pose::rigid_from_rows(rows).map_err(|m| format!("T_BS: {m}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    const IDENTITY: &str = "[1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]";

    fn write(text: &str) -> (tempfile::TempDir, std::path::PathBuf) {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("wide.toml");
        std::fs::write(&path, text).unwrap();
        (dir, path)
    }

    fn camera(extra: &str) -> String {
        format!(
            "[[camera]]\nT_BS = {IDENTITY}\nrate_hz = 20\nresolution = [640, 480]\nintrinsics = [500, 501, 320, 240]\n{extra}"
        )
    }

    #[test]
    fn a_rig_file_gives_its_cameras_in_order_and_its_imu() {
        let moved = "T_BS = [0, -1, 0, 0.25,  1, 0, 0, 0,  0, 0, 1, -0.5,  0, 0, 0, 1]";
        let text = format!(
            "{}\n[[camera]]\n{moved}\nrate_hz = 10\nresolution = [320, 240]\nintrinsics = [250, 250, 160, 120]\ncolour = \"rgb\"\ntime_offset_ms = -2.5\n\n[imu]\nrate_hz = 400\ngyroscope_noise_density = 1e-4\ngyroscope_random_walk = 2e-5\naccelerometer_noise_density = 3e-3\naccelerometer_random_walk = 4e-4\n",
            camera("comment = \"left\"\n")
        );
        let (_dir, path) = write(&text);
        let rig = read_rig_file(&path).unwrap();
        assert_eq!(rig.name, "wide", "the file's stem");
        let names: Vec<&str> = rig.cameras.iter().map(|c| c.name.as_str()).collect();
        assert_eq!(names, ["cam0", "cam1"]);
        let (cam0, cam1) = (&rig.cameras[0], &rig.cameras[1]);
        assert_eq!(cam0.comment, "left");
        assert_eq!(cam0.colour, CameraColour::Grey);
        assert_eq!(
            cam0.intrinsics,
            Intrinsics::parse("640,480,500,501,320,240").unwrap()
        );
        assert_eq!(cam0.body_from_camera, Pose::IDENTITY);
        assert_eq!(cam1.colour, CameraColour::Rgb);
        assert_eq!(cam1.rate_hz, 10.0);
        let expected = Pose::new(
            glam::DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2),
            glam::DVec3::new(0.25, 0.0, -0.5),
        );
        assert!(cam1.body_from_camera.translation == expected.translation);
        assert!(
            cam1.body_from_camera
                .rotation
                .angle_between(expected.rotation)
                < 1e-12
        );
        assert_eq!(rig.time_offsets_ns, [0, -2_500_000]);
        let imu = rig.imu.unwrap();
        assert_eq!(imu.body_from_imu, Pose::IDENTITY);
        assert_eq!(imu.rate_hz, 400.0);
        assert_eq!(
            [
                imu.gyroscope_noise_density,
                imu.gyroscope_random_walk,
                imu.accelerometer_noise_density,
                imu.accelerometer_random_walk
            ],
            [1e-4, 2e-5, 3e-3, 4e-4]
        );
    }

    #[test]
    fn a_bad_rig_file_is_one_line_naming_the_file_line_and_what_was_expected() {
        let noise = "gyroscope_noise_density = 1e-4\ngyroscope_random_walk = 2e-5\naccelerometer_noise_density = 3e-3\naccelerometer_random_walk = 4e-4\n";
        for (text, line, expected) in [
            (
                "name = \"x\"\n".to_string(),
                1,
                "0 [[camera]] tables: expected 1 to 64",
            ),
            (camera("lens = \"fisheye\"\n"), 6, "unknown field `lens`"),
            (
                camera("").replace(IDENTITY, "[1, 0, 0, 0]"),
                1,
                "cam0: T_BS has 4 numbers: expected 16",
            ),
            (
                camera("").replace(
                    IDENTITY,
                    "[2, 0, 0, 0,  0, 2, 0, 0,  0, 0, 2, 0,  0, 0, 0, 1]",
                ),
                1,
                "cam0: T_BS: rotation block is not a rotation",
            ),
            (
                camera("").replace("rate_hz = 20", "rate_hz = 0"),
                1,
                "cam0: rate_hz 0: expected a positive number",
            ),
            (
                camera("").replace("[640, 480]", "[0, 480]"),
                1,
                "cam0: width 0",
            ),
            (
                format!(
                    "{}\n[imu]\nrate_hz = 200\n{}",
                    camera(""),
                    noise.replace("3e-3", "-1")
                ),
                7,
                "imu: accelerometer_noise_density -1: expected a finite number, 0 or more",
            ),
            (
                format!("{}\n[imu]\n{noise}", camera("")),
                7,
                "missing field `rate_hz`",
            ),
            (
                format!("{}\n[ros2]\ncam1 = {{ topic = \"/right\" }}\n", camera("")),
                7,
                "ros2: unknown key 'cam1': expected body_frame, ground_truth_topic or a sensor of the rig (cam0)",
            ),
        ] {
            let (_dir, path) = write(&text);
            let err = read_rig_file(&path).unwrap_err().to_string();
            let prefix = format!("{}:{line}: ", path.display());
            assert!(err.starts_with(&prefix), "{text}\n{err}");
            assert!(err.contains(expected), "{text}\n{err}");
            assert!(!err.contains('\n'), "{err}");
        }
    }

    #[test]
    fn the_example_rig_file_is_the_stereo_imu_preset() {
        let path =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/rigs/stereo_imu.toml");
        let file = read_rig_file(&path).unwrap();
        let preset = Rig::stereo_imu();
        assert_eq!(file.imu, preset.imu);
        assert_eq!(file.time_offsets_ns, [0, 0]);
        for (f, p) in file.cameras.iter().zip(&preset.cameras) {
            assert_eq!(
                (f.intrinsics, f.rate_hz, f.colour),
                (p.intrinsics, p.rate_hz, p.colour)
            );
            let (a, b) = (f.body_from_camera, p.body_from_camera);
            assert!((a.translation - b.translation).length() < 1e-12);
            assert!(a.rotation.dot(b.rotation).abs() > 1.0 - 1e-12);
        }
        assert_eq!(file.cameras.len(), 2);
    }
}
