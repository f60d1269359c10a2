//! Writes the EuRoC layout under `<root>/mav0/`: camera frames as they arrive, then at
//! [`EurocWriter::finish`] the data.csv files, sensor.yaml files, ORB-SLAM3's stereo(-inertial)
//! settings in `<root>/`, checksum list and manifest.

use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use super::csv::{camera_csv, ground_truth_csv, imu_csv};
use super::sensor_yaml::{camera_yaml, imu_yaml};
use super::{
    nanoseconds_from_seconds, CameraColour, EurocCamera, EurocImu, GroundTruthState, ImuSample,
};
use crate::dataset::dynamic_fractions::{DynamicFractions, MASK_IDS};
use crate::dataset::orbslam3::{stereo_inertial_settings, stereo_pair_problem, stereo_settings};
use crate::dataset::{
    encode_grey16_png, encode_grey_png, encode_mask_png, encode_png, is_bookkeeping,
    refuse_symlinks, ContentWriter, Manifest,
};
use crate::{CoreError, MaskImage, Pose, RgbImage};

/// The folder under the dataset root that holds every sensor, as in the published dataset.
pub const MAV_DIR: &str = "mav0";
/// The IMU's folder under `mav0/`.
pub const IMU_DIR: &str = "imu0";
/// The ground truth's folder under `mav0/`.
pub const GROUND_TRUTH_DIR: &str = "state_groundtruth_estimate0";
/// TUM-VI's motion-capture poses (`T_world_imu`, no velocity or biases) under `mav0/`.
pub const MOCAP_DIR: &str = "mocap0";
/// ORB-SLAM3 v1.0 stereo settings for cam0 and cam1, in the dataset root (next to `mav0/`),
/// written when the rig has two cameras or more.
pub const ORBSLAM3_STEREO_FILE: &str = "orbslam3_stereo.yaml";
/// ORB-SLAM3 v1.0 stereo-inertial settings for cam0, cam1 and imu0, in the dataset root, written
/// when the rig has two cameras or more and an IMU.
pub const ORBSLAM3_STEREO_INERTIAL_FILE: &str = "orbslam3_stereo_inertial.yaml";

struct CameraStream {
    camera: EurocCamera,
    /// Timestamps of the frames written so far, increasing.
    times_ns: Mutex<Vec<u64>>,
}

/// Rows of one stream as they arrive, each after the last.
struct Rows<T> {
    name: &'static str,
    rows: Mutex<Vec<T>>,
}

/// Writes one EuRoC dataset. Frames of different cameras may be written from different threads
/// (`&self`); each camera's frames must arrive in time order. Every file is written through a
/// temporary name and a rename, so no reader sees half a file, and hashed on the way.
pub struct EurocWriter {
    content: ContentWriter,
    cameras: Vec<CameraStream>,
    imu: Option<EurocImu>,
    imu_rows: Rows<ImuSample>,
    ground_truth: Rows<GroundTruthState>,
    /// Files under `mav0/` copied as they are ([`EurocWriter::copy_sensor_file`]); `finish`
    /// does not write its own in their place.
    copied: Mutex<HashSet<String>>,
    /// Whether `finish` writes the sensor.yaml files and ORB-SLAM3's settings (EuRoC), or the
    /// calibration lives elsewhere ([`EurocWriter::open_calibration_elsewhere`]).
    sensor_yaml: bool,
    /// With instance masks (`mav0/<cam>/mask/<t_ns>.png`): each frame's dynamic fraction.
    masks: Option<DynamicFractions<(usize, u64)>>,
}

/// A folder name made of letters, digits and `_` (as `cam0`): nothing that leaves `mav0/`.
fn plain_name(name: &str) -> bool {
    !name.is_empty() && name.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_')
}

fn finite_pose(pose: &Pose) -> bool {
    pose.rotation.is_finite() && pose.translation.is_finite()
}

fn check_camera(camera: &EurocCamera, root: &Path) -> Result<(), CoreError> {
    let bad = |message: String| CoreError::bad_file(root.join(MAV_DIR).join(&camera.name), message);
    if !plain_name(&camera.name) || camera.name == IMU_DIR || camera.name == GROUND_TRUTH_DIR {
        return Err(bad(format!(
            "camera name '{}': expected a folder name of letters, digits and '_', such as cam0",
            crate::printable(&camera.name)
        )));
    }
    camera
        .intrinsics
        .check()
        .map_err(|message| bad(format!("{}: {message}", camera.name)))?;
    if !(camera.rate_hz.is_finite() && camera.rate_hz > 0.0) {
        return Err(bad(format!(
            "{}: rate {} Hz: expected a positive rate",
            camera.name, camera.rate_hz
        )));
    }
    if !finite_pose(&camera.body_from_camera)
        || !camera.distortion.to_array().iter().all(|v| v.is_finite())
    {
        return Err(bad(format!(
            "{}: T_BS and distortion must be finite numbers",
            camera.name
        )));
    }
    Ok(())
}

fn check_imu(imu: &EurocImu, root: &Path) -> Result<(), CoreError> {
    let noise = [
        imu.gyroscope_noise_density,
        imu.gyroscope_random_walk,
        imu.accelerometer_noise_density,
        imu.accelerometer_random_walk,
    ];
    let ok = imu.rate_hz.is_finite()
        && imu.rate_hz > 0.0
        && finite_pose(&imu.body_from_imu)
        && noise.iter().all(|v| v.is_finite() && *v >= 0.0);
    if ok {
        Ok(())
    } else {
        Err(CoreError::bad_file(
            root.join(MAV_DIR).join(IMU_DIR),
            "imu0: expected a positive rate, a finite T_BS and non-negative noise parameters",
        ))
    }
}

/// The IMU's and the ground truth's files as the EuRoC layout has them under `mav0/`, paths
/// relative to the folder that holds the sensors: `imu0/data.csv` and `imu0/sensor.yaml` when
/// there is an IMU, `state_groundtruth_estimate0/data.csv` when there are states. The `rgbd-imu`
/// rig writes them beside a TUM dataset the same way.
pub fn inertial_files(
    imu: Option<&EurocImu>,
    samples: &[ImuSample],
    states: &[GroundTruthState],
) -> Vec<(String, String)> {
    let mut files = Vec::new();
    if let Some(imu) = imu {
        files.push((format!("{IMU_DIR}/data.csv"), imu_csv(samples)));
        files.push((format!("{IMU_DIR}/sensor.yaml"), imu_yaml(imu)));
    }
    if !states.is_empty() {
        files.push((
            format!("{GROUND_TRUTH_DIR}/data.csv"),
            ground_truth_csv(states),
        ));
    }
    files
}

/// Refuses a row of `stream` at `t_ns` that does not come after `previous`.
fn not_after(path: PathBuf, stream: &str, what: &str, t_ns: u64, previous: u64) -> CoreError {
    CoreError::bad_file(
        path,
        format!(
            "{stream}: {what} at {t_ns} ns does not come after the previous one at {previous} ns; expected increasing timestamps in each stream"
        ),
    )
}

impl EurocWriter {
    /// Creates `root/mav0/` with a folder for each camera (and its `data/`) and the IMU when
    /// there is one (the ground truth's is made when it has rows). Refuses a `root` with a
    /// symbolic link inside, a camera without a plain, unique folder name or a usable camera,
    /// IMU parameters that are not finite, and a first two cameras of different resolutions or
    /// rates (ORB-SLAM3's stereo settings describe them as one pair). Files already there stay
    /// (a resumed run keeps its complete frames).
    pub fn open(
        root: &Path,
        cameras: Vec<EurocCamera>,
        imu: Option<EurocImu>,
    ) -> Result<Self, CoreError> {
        Self::open_with(root, cameras, imu, true)
    }

    /// [`EurocWriter::open`] for a layout whose calibration is not in sensor.yaml files
    /// (TUM-VI's export keeps it in `dso/`, written with [`EurocWriter::copy_file`]): `finish`
    /// writes the data.csv files only, no sensor.yaml and no ORB-SLAM3 settings (so the first two
    /// cameras need not make one stereo pair for them).
    pub fn open_calibration_elsewhere(
        root: &Path,
        cameras: Vec<EurocCamera>,
        imu: Option<EurocImu>,
    ) -> Result<Self, CoreError> {
        Self::open_with(root, cameras, imu, false)
    }

    fn open_with(
        root: &Path,
        cameras: Vec<EurocCamera>,
        imu: Option<EurocImu>,
        sensor_yaml: bool,
    ) -> Result<Self, CoreError> {
        refuse_symlinks(root, root)?;
        for (i, camera) in cameras.iter().enumerate() {
            check_camera(camera, root)?;
            if cameras[..i].iter().any(|c| c.name == camera.name) {
                return Err(CoreError::bad_file(
                    root.join(MAV_DIR).join(&camera.name),
                    format!(
                        "camera name '{}' is given twice; expected one folder per camera",
                        camera.name
                    ),
                ));
            }
        }
        if let ([left, right, ..], true) = (cameras.as_slice(), sensor_yaml) {
            if let Some(problem) = stereo_pair_problem(left, right) {
                return Err(CoreError::bad_file(
                    root.join(ORBSLAM3_STEREO_FILE),
                    problem,
                ));
            }
        }
        if let Some(imu) = &imu {
            check_imu(imu, root)?;
        }
        let mav = root.join(MAV_DIR);
        let mut dirs: Vec<PathBuf> = cameras
            .iter()
            .map(|c| mav.join(&c.name).join("data"))
            .collect();
        if imu.is_some() {
            dirs.push(mav.join(IMU_DIR));
        }
        for dir in &dirs {
            std::fs::create_dir_all(dir).map_err(|e| CoreError::io(dir, e))?;
        }
        Ok(Self {
            content: ContentWriter::new(root),
            cameras: cameras
                .into_iter()
                .map(|camera| CameraStream {
                    camera,
                    times_ns: Mutex::new(Vec::new()),
                })
                .collect(),
            imu,
            imu_rows: Rows {
                name: IMU_DIR,
                rows: Mutex::new(Vec::new()),
            },
            ground_truth: Rows {
                name: GROUND_TRUTH_DIR,
                rows: Mutex::new(Vec::new()),
            },
            copied: Mutex::new(HashSet::new()),
            sensor_yaml,
            masks: None,
        })
    }

    /// Writes an instance mask beside each camera frame ([`EurocWriter::write_mask`]).
    pub fn with_masks(self) -> Result<Self, CoreError> {
        for stream in &self.cameras {
            let dir = self.mask_dir(&stream.camera.name);
            std::fs::create_dir_all(&dir).map_err(|e| CoreError::io(&dir, e))?;
        }
        Ok(Self {
            masks: Some(DynamicFractions::default()),
            ..self
        })
    }

    pub fn has_masks(&self) -> bool {
        self.masks.is_some()
    }

    fn mask_dir(&self, camera_name: &str) -> PathBuf {
        self.root().join(MAV_DIR).join(camera_name).join("mask")
    }

    /// Camera `camera`'s instance mask of its frame at `t_ns`, as `mav0/<cam>/mask/<t_ns>.png`
    /// (a 16-bit PNG: 0 static, k actor k). Written before the frame itself, so that a kept
    /// frame ([`EurocWriter::keep_written_frames`]) has its mask.
    pub fn write_mask(&self, camera: usize, t_ns: u64, mask: &MaskImage) -> Result<(), CoreError> {
        let stream = self.camera(camera)?;
        let name = &stream.camera.name;
        let Some(fractions) = &self.masks else {
            return Err(CoreError::bad_file(
                self.root().join(MAV_DIR).join(name),
                "an instance mask for a dataset opened without masks",
            ));
        };
        self.content.write(
            &format!("{MAV_DIR}/{name}/mask/{t_ns}.png"),
            &encode_mask_png(mask)?,
        )?;
        fractions.record((camera, t_ns), mask);
        Ok(())
    }

    pub fn root(&self) -> &Path {
        self.content.root()
    }

    pub fn cameras(&self) -> impl Iterator<Item = &EurocCamera> {
        self.cameras.iter().map(|s| &s.camera)
    }

    /// Writes camera `camera`'s (index into the cameras given to [`EurocWriter::open`]) frame
    /// captured at `time_s` seconds as `mav0/<cam>/data/<t_ns>.png`, grey or RGB as the camera
    /// says, `t_ns` the time rounded to whole nanoseconds. Refuses a time that does not come
    /// after the camera's previous frame, and an image not of the camera's size. Returns `t_ns`.
    /// A recorded timestamp (19 digits of ns) does not survive f64 seconds: use
    /// [`EurocWriter::write_frame_ns`] for it.
    pub fn write_frame(
        &self,
        camera: usize,
        time_s: f64,
        image: &RgbImage,
    ) -> Result<u64, CoreError> {
        let Some(t_ns) = nanoseconds_from_seconds(time_s) else {
            let name = self.camera(camera)?.camera.name.as_str();
            return Err(CoreError::bad_file(
                self.root().join(MAV_DIR).join(name),
                format!("{name}: frame time {time_s} s: expected a finite time from 0 to about 1.8e10 s"),
            ));
        };
        self.write_frame_ns(camera, t_ns, image)?;
        Ok(t_ns)
    }

    /// [`EurocWriter::write_frame`] at `t_ns` nanoseconds exactly (a recorded dataset's own
    /// timestamps, kept to the nanosecond).
    pub fn write_frame_ns(
        &self,
        camera: usize,
        t_ns: u64,
        image: &RgbImage,
    ) -> Result<(), CoreError> {
        let stream = self.camera(camera)?;
        let name = &stream.camera.name;
        let k = &stream.camera.intrinsics;
        if (image.width, image.height) != (k.width, k.height) {
            return Err(CoreError::bad_file(
                self.root().join(MAV_DIR).join(name),
                format!(
                    "{name}: {}x{} image: expected the camera's {}x{}",
                    image.width, image.height, k.width, k.height
                ),
            ));
        }
        self.take_stamp(stream, t_ns)?;
        let bytes = match stream.camera.colour {
            CameraColour::Grey => encode_grey_png(image)?,
            CameraColour::Rgb => encode_png(image)?,
            CameraColour::Grey16 => encode_grey16_png(image)?,
        };
        self.content
            .write(&format!("{MAV_DIR}/{name}/data/{t_ns}.png"), &bytes)
    }

    /// Writes `png` (a recorded frame's file, copied byte for byte) as camera `camera`'s frame
    /// at `t_ns`, in time order as [`EurocWriter::write_frame_ns`].
    pub fn copy_frame_ns(&self, camera: usize, t_ns: u64, png: &[u8]) -> Result<(), CoreError> {
        let stream = self.camera(camera)?;
        self.take_stamp(stream, t_ns)?;
        let name = &stream.camera.name;
        self.content
            .write(&format!("{MAV_DIR}/{name}/data/{t_ns}.png"), png)
    }

    /// Keeps the frames an interrupted run of the same job wrote for camera `camera`: the longest
    /// run of `times_ns` from the first whose `<t_ns>.png` is there (frames are written in time
    /// order, each whole through a rename), recorded as written. Returns how many; frames after
    /// them are to be written again.
    pub fn keep_written_frames(&self, camera: usize, times_ns: &[u64]) -> Result<usize, CoreError> {
        let stream = self.camera(camera)?;
        let data = self
            .root()
            .join(MAV_DIR)
            .join(&stream.camera.name)
            .join("data");
        let mut kept = 0;
        for &t_ns in times_ns {
            if !data.join(format!("{t_ns}.png")).is_file() {
                break;
            }
            self.take_stamp(stream, t_ns)?;
            kept += 1;
        }
        Ok(kept)
    }

    /// Records a frame of `stream` at `t_ns`, refusing one not after the previous.
    fn take_stamp(&self, stream: &CameraStream, t_ns: u64) -> Result<(), CoreError> {
        let mut times = stream.times_ns.lock().unwrap_or_else(|p| p.into_inner());
        if let Some(&previous) = times.last().filter(|&&previous| t_ns <= previous) {
            let name = &stream.camera.name;
            let dir = self.root().join(MAV_DIR).join(name);
            return Err(not_after(dir, name, "frame", t_ns, previous));
        }
        times.push(t_ns);
        Ok(())
    }

    fn camera(&self, camera: usize) -> Result<&CameraStream, CoreError> {
        self.cameras.get(camera).ok_or_else(|| {
            CoreError::bad_file(
                self.root().join(MAV_DIR),
                format!(
                    "camera {camera}: there are only {} cameras",
                    self.cameras.len()
                ),
            )
        })
    }

    /// Writes `bytes` as `mav0/<sensor>/<file>` as they are (a recorded dataset's own
    /// sensor.yaml, IMU readings or ground truth, copied unchanged), in place of the file
    /// [`EurocWriter::finish`] would make from the values given: `file` is `sensor.yaml` or
    /// `data.csv` (a camera's data.csv always lists the frames written). Hashed like every
    /// other file.
    pub fn copy_sensor_file(
        &self,
        sensor: &str,
        file: &str,
        bytes: &[u8],
    ) -> Result<(), CoreError> {
        let is_camera = self.cameras.iter().any(|c| c.camera.name == sensor);
        let allowed = match file {
            "sensor.yaml" => is_camera || sensor == IMU_DIR,
            "data.csv" => [IMU_DIR, GROUND_TRUTH_DIR, MOCAP_DIR].contains(&sensor),
            _ => false,
        };
        if !allowed || !plain_name(sensor) {
            return Err(CoreError::bad_file(
                self.root().join(MAV_DIR).join(crate::printable(sensor)),
                format!(
                    "{}/{}: expected a camera's or imu0's sensor.yaml, or the data.csv of imu0, {GROUND_TRUTH_DIR} or {MOCAP_DIR}",
                    crate::printable(sensor),
                    crate::printable(file)
                ),
            ));
        }
        let dir = self.root().join(MAV_DIR).join(sensor);
        std::fs::create_dir_all(&dir).map_err(|e| CoreError::io(&dir, e))?;
        let relative = format!("{MAV_DIR}/{sensor}/{file}");
        self.content.write(&relative, bytes)?;
        self.copied
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .insert(relative);
        Ok(())
    }

    /// Writes `bytes` as `<root>/<name>`, beside the manifest: a record of the run that does not
    /// fit in it (per-frame values). `name` is a plain file name; hashed like every other file.
    pub fn write_record(&self, name: &str, bytes: &[u8]) -> Result<(), CoreError> {
        let plain = !name.starts_with('.')
            && name
                .bytes()
                .all(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'.' || b == b'-');
        if !plain || name.is_empty() || name == MAV_DIR {
            return Err(CoreError::bad_file(
                self.root().join(crate::printable(name)),
                "expected a plain file name for a record beside the manifest",
            ));
        }
        self.content.write(name, bytes)
    }

    /// Writes `bytes` as `<root>/<relative>`, a file of a recorded dataset outside `mav0/`
    /// (TUM-VI's `dso/camchain.yaml`, `dso/cam0/vignette.png`, …), copied or rewritten. `relative`
    /// is made of plain names (letters, digits, `_`, `-`, `.`; none starting with `.`) joined by
    /// `/`, not under `mav0/` and not the manifest's files. Hashed like every other file.
    pub fn copy_file(&self, relative: &str, bytes: &[u8]) -> Result<(), CoreError> {
        let plain = |part: &str| {
            !part.is_empty()
                && !part.starts_with('.')
                && part
                    .bytes()
                    .all(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'.' || b == b'-')
        };
        let parts: Vec<&str> = relative.split('/').collect();
        if !parts.iter().all(|p| plain(p)) || parts[0] == MAV_DIR || is_bookkeeping(relative) {
            return Err(CoreError::bad_file(
                self.root().join(crate::printable(relative)),
                "expected a path of plain names outside mav0/ for a file copied from the input",
            ));
        }
        let path = self.root().join(relative);
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir).map_err(|e| CoreError::io(dir, e))?;
        }
        self.content.write(relative, bytes)
    }

    /// Appends IMU samples, each after the last one. Requires an IMU given to `open`.
    pub fn write_imu(&self, samples: &[ImuSample]) -> Result<(), CoreError> {
        if self.imu.is_none() {
            return Err(CoreError::bad_file(
                self.root().join(MAV_DIR).join(IMU_DIR),
                "imu0: IMU samples, but the writer was opened without an IMU",
            ));
        }
        self.append(&self.imu_rows, samples, |s| s.t_ns, "IMU sample")
    }

    /// Appends ground-truth states, each after the last one.
    pub fn write_ground_truth(&self, states: &[GroundTruthState]) -> Result<(), CoreError> {
        self.append(&self.ground_truth, states, |s| s.t_ns, "ground-truth state")
    }

    fn append<T: Copy>(
        &self,
        stream: &Rows<T>,
        new: &[T],
        time: impl Fn(&T) -> u64,
        what: &str,
    ) -> Result<(), CoreError> {
        let mut rows = stream.rows.lock().unwrap_or_else(|p| p.into_inner());
        let mut previous = rows.last().map(&time);
        for row in new {
            let t_ns = time(row);
            if let Some(before) = previous.filter(|&before| t_ns <= before) {
                return Err(not_after(
                    self.root().join(MAV_DIR).join(stream.name),
                    stream.name,
                    what,
                    t_ns,
                    before,
                ));
            }
            previous = Some(t_ns);
        }
        rows.extend_from_slice(new);
        Ok(())
    }

    /// Each camera's data.csv and sensor.yaml, the IMU's, the ground truth's data.csv (when any
    /// state was written), ORB-SLAM3's settings for cam0 and cam1 ([`ORBSLAM3_STEREO_FILE`]
    /// with two cameras or more, and [`ORBSLAM3_STEREO_INERTIAL_FILE`] when there is an IMU as
    /// well), the checksum list (frames an earlier, interrupted run wrote are hashed now), then the
    /// manifest with the content digest, last. Returns the manifest as written.
    pub fn finish(self, mut manifest: Manifest) -> Result<Manifest, CoreError> {
        if let Some(fractions) = &self.masks {
            let mut cameras = serde_json::Map::new();
            for (camera, stream) in self.cameras.iter().enumerate() {
                let name = &stream.camera.name;
                let times = stream.times_ns.lock().unwrap_or_else(|p| p.into_inner());
                let of_camera: Vec<f64> = (times.iter())
                    .map(|&t| {
                        let path = self.mask_dir(name).join(format!("{t}.png"));
                        fractions.of(&(camera, t), &path)
                    })
                    .collect::<Result<_, _>>()?;
                cameras.insert(name.clone(), of_camera.into());
            }
            manifest.extra["masks"] = serde_json::json!({
                "ids": MASK_IDS,
                "dynamic_fraction": cameras,
            });
        }
        for stream in &self.cameras {
            let name = &stream.camera.name;
            let times = stream.times_ns.lock().unwrap_or_else(|p| p.into_inner());
            self.write_text(&format!("{MAV_DIR}/{name}/data.csv"), &camera_csv(&times))?;
            if !self.sensor_yaml {
                continue;
            }
            self.write_text(
                &format!("{MAV_DIR}/{name}/sensor.yaml"),
                &camera_yaml(&stream.camera),
            )?;
        }
        let imu_rows = self.imu_rows.rows.lock().unwrap_or_else(|p| p.into_inner());
        let states = self
            .ground_truth
            .rows
            .lock()
            .unwrap_or_else(|p| p.into_inner());
        for (relative, text) in inertial_files(self.imu.as_ref(), &imu_rows, &states) {
            if !self.sensor_yaml && relative.ends_with("sensor.yaml") {
                continue;
            }
            let relative = format!("{MAV_DIR}/{relative}");
            let path = self.root().join(&relative);
            if let Some(dir) = path.parent() {
                std::fs::create_dir_all(dir).map_err(|e| CoreError::io(dir, e))?;
            }
            self.write_text(&relative, &text)?;
        }
        drop((imu_rows, states));
        if let ([left, right, ..], true) = (self.cameras.as_slice(), self.sensor_yaml) {
            let (left, right) = (&left.camera, &right.camera);
            self.write_text(ORBSLAM3_STEREO_FILE, &stereo_settings(left, right))?;
            if let Some(imu) = &self.imu {
                self.write_text(
                    ORBSLAM3_STEREO_INERTIAL_FILE,
                    &stereo_inertial_settings(left, right, imu),
                )?;
            }
        }
        self.content.finish(manifest)
    }

    /// Writes a file `finish` makes, unless it was copied as it is.
    fn write_text(&self, relative: &str, text: &str) -> Result<(), CoreError> {
        let copied = self.copied.lock().unwrap_or_else(|p| p.into_inner());
        if copied.contains(relative) {
            return Ok(());
        }
        drop(copied);
        self.content.write(relative, text.as_bytes())
    }
}
