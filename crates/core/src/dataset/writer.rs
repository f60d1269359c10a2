use std::path::{Path, PathBuf};

use crate::dataset::{
    encode_depth_png, encode_jpeg, encode_png, orbslam3, DatasetFormat, Manifest, MANIFEST_FILE,
};
use crate::trajectory_io::{write_replica, write_tum};
use crate::{CoreError, DepthImage, Intrinsics, RgbImage, Trajectory};

/// JPEG quality of Replica-layout colour frames (formats.md: ≥ 95).
pub const JPEG_QUALITY: u8 = 95;

/// One output frame's timing: when its colour was captured and when the depth it carries was.
/// They differ only under RGB–depth misalignment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OutputFrame {
    pub rgb_time: f64,
    pub depth_time: f64,
}

/// Writes one dataset. Frame files may be written from many threads (`&self`), each through a
/// temporary name and a rename, so no reader sees half a file; [`DatasetWriter::finish`] writes
/// the trajectory and index files and then the manifest, last.
pub struct DatasetWriter {
    root: PathBuf,
    format: DatasetFormat,
    intrinsics: Intrinsics,
}

fn tum_name(dir: &str, time: f64) -> String {
    format!("{dir}/{time:.6}.png")
}

impl DatasetWriter {
    /// Prepares `root`: an empty or missing folder, or an earlier rslam dataset, whose manifest and
    /// frames are removed first so that an interrupted run never looks complete.
    pub fn create(
        root: &Path,
        format: DatasetFormat,
        intrinsics: Intrinsics,
    ) -> Result<Self, CoreError> {
        if root.exists() {
            let is_dataset = root.join(MANIFEST_FILE).exists();
            let mut entries = std::fs::read_dir(root).map_err(|e| CoreError::io(root, e))?;
            if !is_dataset && entries.next().is_some() {
                return Err(CoreError::bad_file(
                    root,
                    "output folder is not empty and holds no rslam dataset (rslam.json); choose an empty or new folder",
                ));
            }
            if is_dataset {
                remove_path(&root.join(MANIFEST_FILE))?;
                for old in ["results", "rgb", "depth"] {
                    remove_path(&root.join(old))?;
                }
            }
        }
        let dirs: &[&str] = match format {
            DatasetFormat::Replica => &["results"],
            DatasetFormat::Tum => &["rgb", "depth"],
        };
        for dir in dirs {
            let path = root.join(dir);
            std::fs::create_dir_all(&path).map_err(|e| CoreError::io(&path, e))?;
        }
        Ok(Self {
            root: root.to_path_buf(),
            format,
            intrinsics,
        })
    }

    pub fn root(&self) -> &Path {
        &self.root
    }

    pub fn intrinsics(&self) -> Intrinsics {
        self.intrinsics
    }

    pub fn format(&self) -> DatasetFormat {
        self.format
    }

    fn write_atomic(&self, rel: &str, bytes: &[u8]) -> Result<(), CoreError> {
        let path = self.root.join(rel);
        let tmp = self.root.join(format!("{rel}.partial"));
        std::fs::write(&tmp, bytes).map_err(|e| CoreError::io(&tmp, e))?;
        std::fs::rename(&tmp, &path).map_err(|e| CoreError::io(&path, e))
    }

    /// Colour of output frame `index`, captured at `time`.
    pub fn write_rgb(&self, index: usize, time: f64, image: &RgbImage) -> Result<(), CoreError> {
        match self.format {
            DatasetFormat::Replica => self.write_atomic(
                &format!("results/frame{index:06}.jpg"),
                &encode_jpeg(image, JPEG_QUALITY)?,
            ),
            DatasetFormat::Tum => self.write_atomic(&tum_name("rgb", time), &encode_png(image)?),
        }
    }

    /// One depth image, captured at `time`, delivered with each of the output frames `outputs`
    /// (several under misalignment). Replica writes it once per output frame; TUM once, named by
    /// its capture time.
    pub fn write_depth(
        &self,
        outputs: &[usize],
        time: f64,
        depth: &DepthImage,
    ) -> Result<(), CoreError> {
        if outputs.is_empty() {
            return Ok(());
        }
        let bytes = encode_depth_png(depth, self.format.depth_scale())?;
        match self.format {
            DatasetFormat::Replica => outputs.iter().try_for_each(|index| {
                self.write_atomic(&format!("results/depth{index:06}.png"), &bytes)
            }),
            DatasetFormat::Tum => self.write_atomic(&tum_name("depth", time), &bytes),
        }
    }

    /// Index and trajectory files, then the manifest. `ground_truth` holds one pose per output
    /// frame, stamped with its colour capture time.
    pub fn finish(
        self,
        frames: &[OutputFrame],
        ground_truth: &Trajectory,
        manifest: &Manifest,
    ) -> Result<(), CoreError> {
        match self.format {
            DatasetFormat::Replica => {
                write_replica(&self.root.join("traj.txt"), ground_truth)?;
                self.write_text("cam_params.json", &self.cam_params_json())?;
            }
            DatasetFormat::Tum => {
                write_tum(&self.root.join("groundtruth.txt"), ground_truth)?;
                self.write_text(
                    "rgb.txt",
                    &tum_list("rgb", frames.iter().map(|f| f.rgb_time)),
                )?;
                let mut depth_times: Vec<f64> = frames.iter().map(|f| f.depth_time).collect();
                depth_times.sort_by(f64::total_cmp);
                depth_times.dedup_by(|a, b| format!("{a:.6}") == format!("{b:.6}"));
                self.write_text("depth.txt", &tum_list("depth", depth_times.into_iter()))?;
                let associations: String = frames
                    .iter()
                    .map(|f| {
                        format!(
                            "{:.6} {} {:.6} {}\n",
                            f.rgb_time,
                            tum_name("rgb", f.rgb_time),
                            f.depth_time,
                            tum_name("depth", f.depth_time)
                        )
                    })
                    .collect();
                self.write_text("associations.txt", &associations)?;
                self.write_text(
                    "orbslam3.yaml",
                    &orbslam3::settings(&self.intrinsics, manifest.rate_hz),
                )?;
            }
        }
        manifest.write(&self.root)
    }

    fn write_text(&self, rel: &str, text: &str) -> Result<(), CoreError> {
        let path = self.root.join(rel);
        std::fs::write(&path, text).map_err(|e| CoreError::io(&path, e))
    }

    fn cam_params_json(&self) -> String {
        let k = &self.intrinsics;
        let json = serde_json::json!({
            "camera": {
                "w": k.width, "h": k.height,
                "fx": k.fx, "fy": k.fy, "cx": k.cx, "cy": k.cy,
                "scale": self.format.depth_scale(),
            }
        });
        format!("{json:#}\n")
    }
}

fn tum_list(dir: &str, times: impl Iterator<Item = f64>) -> String {
    let kind = if dir == "rgb" { "color" } else { "depth" };
    let mut text = format!("# {kind} images\n# file: 'rslam'\n# timestamp filename\n");
    for t in times {
        text.push_str(&format!("{t:.6} {}\n", tum_name(dir, t)));
    }
    text
}

fn remove_path(path: &Path) -> Result<(), CoreError> {
    let result = if path.is_dir() {
        std::fs::remove_dir_all(path)
    } else if path.exists() {
        std::fs::remove_file(path)
    } else {
        Ok(())
    };
    result.map_err(|e| CoreError::io(path, e))
}
