use std::path::Path;

use crate::dataset::dynamic_fractions::{DynamicFractions, MASK_IDS};
use crate::dataset::{
    encode_depth_png, encode_jpeg, encode_mask_png, encode_png, orbslam3, ContentWriter,
    DatasetFormat, DepthPng, Manifest,
};
use crate::trajectory_io::{write_replica, write_tum};
use crate::{CoreError, DepthImage, Distortion, Intrinsics, MaskImage, RgbImage, Trajectory};

/// JPEG quality of Replica-layout colour frames (docs/src/formats.md, "Replica layout": quality 95).
pub const JPEG_QUALITY: u8 = 95;

/// One output frame's timing: when its colour was captured and when the depth it carries was.
/// They differ only under RGB–depth misalignment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OutputFrame {
    pub rgb_time: f64,
    pub depth_time: f64,
}

/// Where one output frame's colour and depth go, relative to the dataset root.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FrameFiles {
    pub rgb: String,
    pub depth: String,
}

/// Writes one dataset. Frame files may be written from many threads (`&self`), each through a
/// temporary name and a rename, so no reader sees half a file; each is hashed as it is written.
/// [`DatasetWriter::finish`] writes the trajectory and index files, the checksum list and then the
/// manifest, last.
pub struct DatasetWriter {
    content: ContentWriter,
    files: FileLayout,
    intrinsics: Intrinsics,
    /// The lens the frames were taken through, written beside the intrinsics.
    distortion: Option<Distortion>,
    depth_png: DepthPng,
    /// With instance masks: each output frame's dynamic fraction, as its mask was written.
    masks: Option<DynamicFractions<usize>>,
}

/// The layouts written a file per frame; a bag is one file ([`super::ros2::CameraBag`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum FileLayout {
    Replica,
    Tum,
}

impl FileLayout {
    fn format(self) -> DatasetFormat {
        match self {
            Self::Replica => DatasetFormat::Replica,
            Self::Tum => DatasetFormat::Tum,
        }
    }
}

fn tum_name(dir: &str, time: f64) -> String {
    format!("{dir}/{time:.6}.png")
}

impl DatasetWriter {
    /// Creates the layout's folders under `root`; files already there stay (a resumed run keeps
    /// its complete frames). Deciding whether `root` may be written is the caller's job.
    pub fn open(
        root: &Path,
        format: DatasetFormat,
        intrinsics: Intrinsics,
        depth_png: DepthPng,
    ) -> Result<Self, CoreError> {
        let (files, dirs): (FileLayout, &[&str]) = match format {
            DatasetFormat::Replica => (FileLayout::Replica, &["results"]),
            DatasetFormat::Tum => (FileLayout::Tum, &["rgb", "depth"]),
            DatasetFormat::Ros2 => {
                return Err(CoreError::bad_file(
                    root,
                    "a ROS 2 bag is one file, written by ros2::CameraBag, not frame by frame",
                ))
            }
        };
        for dir in dirs {
            let path = root.join(dir);
            std::fs::create_dir_all(&path).map_err(|e| CoreError::io(&path, e))?;
        }
        Ok(Self {
            content: ContentWriter::new(root),
            files,
            intrinsics,
            distortion: None,
            depth_png,
            masks: None,
        })
    }

    /// Writes an instance mask beside each frame's colour ([`DatasetWriter::write_mask`]).
    pub fn with_masks(self) -> Result<Self, CoreError> {
        if self.files == FileLayout::Tum {
            let path = self.root().join("mask");
            std::fs::create_dir_all(&path).map_err(|e| CoreError::io(&path, e))?;
        }
        Ok(Self {
            masks: Some(DynamicFractions::default()),
            ..self
        })
    }

    pub fn has_masks(&self) -> bool {
        self.masks.is_some()
    }

    /// Where output frame `index`'s instance mask goes: named like its colour, at its colour's
    /// capture time.
    pub fn mask_file(&self, index: usize, frame: &OutputFrame) -> String {
        match self.files {
            FileLayout::Replica => format!("results/mask{index:06}.png"),
            FileLayout::Tum => tum_name("mask", frame.rgb_time),
        }
    }

    /// The instance mask of output frame `index` (a 16-bit PNG: 0 static, k actor k).
    pub fn write_mask(
        &self,
        index: usize,
        frame: &OutputFrame,
        mask: &MaskImage,
    ) -> Result<(), CoreError> {
        let Some(fractions) = &self.masks else {
            return Err(CoreError::bad_file(
                self.root(),
                "an instance mask for a dataset opened without masks",
            ));
        };
        self.content
            .write(&self.mask_file(index, frame), &encode_mask_png(mask)?)?;
        fractions.record(index, mask);
        Ok(())
    }

    /// Frames seen through `distortion`: the camera files (`cam_params.json`, `orbslam3.yaml`)
    /// carry it so that consumers can undistort.
    pub fn with_distortion(self, distortion: Option<Distortion>) -> Self {
        Self { distortion, ..self }
    }

    /// The files output frame `index` is written to.
    pub fn frame_files(&self, index: usize, frame: &OutputFrame) -> FrameFiles {
        match self.files {
            FileLayout::Replica => FrameFiles {
                rgb: format!("results/frame{index:06}.jpg"),
                depth: format!("results/depth{index:06}.png"),
            },
            FileLayout::Tum => FrameFiles {
                rgb: tum_name("rgb", frame.rgb_time),
                depth: tum_name("depth", frame.depth_time),
            },
        }
    }

    pub fn root(&self) -> &Path {
        self.content.root()
    }

    pub fn intrinsics(&self) -> Intrinsics {
        self.intrinsics
    }

    pub fn format(&self) -> DatasetFormat {
        self.files.format()
    }

    /// Colour of output frame `index`, captured at `frame.rgb_time`.
    pub fn write_rgb(
        &self,
        index: usize,
        frame: &OutputFrame,
        image: &RgbImage,
    ) -> Result<(), CoreError> {
        let bytes = match self.files {
            FileLayout::Replica => encode_jpeg(image, JPEG_QUALITY)?,
            FileLayout::Tum => encode_png(image)?,
        };
        self.content
            .write(&self.frame_files(index, frame).rgb, &bytes)
    }

    /// One depth image delivered with each of the output frames `outputs` (several under
    /// misalignment, all carrying the same depth capture time). Replica writes it once per
    /// output frame; TUM once, named by its capture time.
    pub fn write_depth(
        &self,
        outputs: &[(usize, OutputFrame)],
        depth: &DepthImage,
    ) -> Result<(), CoreError> {
        let bytes = encode_depth_png(depth, self.files.format().depth_scale(), self.depth_png)?;
        let mut names: Vec<String> = outputs
            .iter()
            .map(|(index, frame)| self.frame_files(*index, frame).depth)
            .collect();
        names.dedup();
        names
            .iter()
            .try_for_each(|name| self.content.write(name, &bytes))
    }

    /// Index and trajectory files, the checksum list (frames written by an earlier, interrupted
    /// run are hashed now), then the manifest with the content digest, last. `ground_truth` holds
    /// one pose per output frame, stamped with its colour capture time. Returns the manifest as
    /// written.
    pub fn finish(
        self,
        frames: &[OutputFrame],
        ground_truth: &Trajectory,
        mut manifest: Manifest,
    ) -> Result<Manifest, CoreError> {
        if let Some(fractions) = &self.masks {
            let fractions: Vec<f64> = (frames.iter().enumerate())
                .map(|(j, frame)| fractions.of(&j, &self.root().join(self.mask_file(j, frame))))
                .collect::<Result<_, _>>()?;
            manifest.extra["masks"] = serde_json::json!({
                "ids": MASK_IDS,
                "dynamic_fraction": fractions,
            });
            if self.files == FileLayout::Tum {
                let list = tum_list("mask", frames.iter().map(|f| f.rgb_time));
                self.write_text("mask.txt", &list)?;
            }
        }
        match self.files {
            FileLayout::Replica => {
                write_replica(&self.root().join("traj.txt"), ground_truth)?;
                self.write_text("cam_params.json", &self.cam_params_json())?;
            }
            FileLayout::Tum => {
                write_tum(&self.root().join("groundtruth.txt"), ground_truth)?;
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
                    &orbslam3::settings(
                        &self.intrinsics,
                        self.distortion.as_ref(),
                        manifest.rate_hz,
                    ),
                )?;
            }
        }
        self.content.finish(manifest)
    }

    /// A text file of the dataset at `rel` (written whole, counted in its checksums), its folder
    /// made if need be.
    pub fn write_text(&self, rel: &str, text: &str) -> Result<(), CoreError> {
        if let Some(dir) = self.root().join(rel).parent() {
            std::fs::create_dir_all(dir).map_err(|e| CoreError::io(dir, e))?;
        }
        self.content.write(rel, text.as_bytes())
    }

    fn cam_params_json(&self) -> String {
        let k = &self.intrinsics;
        let mut json = serde_json::json!({
            "camera": {
                "w": k.width, "h": k.height,
                "fx": k.fx, "fy": k.fy, "cx": k.cx, "cy": k.cy,
                "scale": self.files.format().depth_scale(),
            }
        });
        if let Some(lens) = &self.distortion {
            // OpenCV's order: [k1, k2, p1, p2] (cv::undistort) or [k1, k2, k3, k4] (cv::fisheye).
            json["camera"]["distortion_model"] = lens.model().into();
            json["camera"]["distortion"] = lens.coefficients().to_vec().into();
        }
        format!("{json:#}\n")
    }
}

fn tum_list(dir: &str, times: impl Iterator<Item = f64>) -> String {
    let kind = match dir {
        "rgb" => "color",
        "mask" => "instance mask",
        _ => "depth",
    };
    let mut text = format!("# {kind} images\n# file: 'rslam'\n# timestamp filename\n");
    for t in times {
        text.push_str(&format!("{t:.6} {}\n", tum_name(dir, t)));
    }
    text
}
