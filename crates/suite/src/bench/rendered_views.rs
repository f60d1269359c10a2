//! Rendered-view quality of every finished run that rendered its map at the ground-truth poses
//! (`renders` in its method file): each rendered frame against the clean frame of the same job —
//! the sequence without the items that change what a frame shows
//! ([`Sequence::clean_job`], made once per sequence into `out/clean/<sequence>/`) — by PSNR and
//! SSIM of colour and L1 of depth ([`rslam_eval::view_quality`]), averaged over the frames.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use rayon::prelude::*;
use rslam_core::dataset::{decode_depth_png, read_dataset, read_rgb8, DatasetOverrides, Layout};
use rslam_eval::correlation::{pearson, spearman};
use rslam_eval::view_quality::{depth_l1_m, psnr_db, ssim};
use rslam_eval::{plot_view_quality_against_ate, ViewQualityPoint};
use rslam_gpu::GpuContext;
use rslam_pipeline::{PipelineError, SceneCache, Silent};
use serde::Serialize;

use super::measured_csv::measures_or_failure;
use super::record::succeeded_runs_keeping;
use crate::sequence::Sequence;
use crate::{Suite, SuiteError};

/// Where the clean frames go, inside the report folder.
pub const CLEAN_DIR: &str = "clean";

/// Means over the frames a run rendered.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ViewQuality {
    pub colour_frames: usize,
    /// Mean of the frames' PSNR, dB; infinite (JSON `null`) when a frame is identical.
    pub psnr_db: Option<f64>,
    pub ssim: Option<f64>,
    pub depth_frames: usize,
    /// Mean of the frames' depth L1, cm.
    pub depth_l1_cm: Option<f64>,
}

/// One run's rendered-view quality, or why it could not be measured.
#[derive(Clone, Debug, Serialize)]
pub struct RenderedViewRow {
    pub method: String,
    pub sequence: String,
    pub repeat: usize,
    /// The run's ATE (rmse, m), to set the views' quality beside tracking.
    pub ate_m: Option<f64>,
    pub quality: Option<ViewQuality>,
    pub failure: Option<String>,
}

/// How a measure of the rendered views goes with ATE over the runs that have both.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct AteCorrelation {
    /// `psnr_db`, `ssim` or `depth_l1_cm`.
    pub measure: &'static str,
    pub runs: usize,
    pub spearman: Option<f64>,
    pub pearson: Option<f64>,
}

/// One number of a run's [`ViewQuality`].
type Measure = fn(&ViewQuality) -> Option<f64>;

/// Spearman's ρ and Pearson's r of each measure against ATE, over the runs with finite values.
pub fn ate_correlations(rows: &[RenderedViewRow]) -> Vec<AteCorrelation> {
    let measures: [(&'static str, Measure); 3] = [
        ("psnr_db", |q| q.psnr_db),
        ("ssim", |q| q.ssim),
        ("depth_l1_cm", |q| q.depth_l1_cm),
    ];
    measures
        .into_iter()
        .map(|(measure, value)| {
            let (x, y): (Vec<f64>, Vec<f64>) = rows
                .iter()
                .filter_map(|r| Some((value(r.quality.as_ref()?)?, r.ate_m?)))
                .filter(|(v, ate)| v.is_finite() && ate.is_finite())
                .unzip();
            AteCorrelation {
                measure,
                runs: x.len(),
                spearman: spearman(&x, &y),
                pearson: pearson(&x, &y),
            }
        })
        .collect()
}

/// Measures the renders of every finished run that kept some, making the clean frames first
/// (on the GPU `gpu` gives, asked only when there is a run to measure), with each run's ATE from
/// `ate_of(method, sequence, repeat)`, and writes `out/rendered_views.csv` and `.json`, and the
/// measures against ATE as `rendered_views.png` and `.svg`. Returns the rows and the files
/// written.
pub fn report_rendered_views(
    suite: &Suite,
    out: &Path,
    gpu: impl FnOnce() -> Result<GpuContext, SuiteError>,
    ate_of: &dyn Fn(&str, &str, usize) -> Option<f64>,
) -> Result<(Vec<RenderedViewRow>, Vec<PathBuf>), SuiteError> {
    let runs = succeeded_runs_keeping(suite, |record| record.renders.clone());
    if runs.is_empty() {
        return Ok((Vec::new(), Vec::new()));
    }
    let ctx = gpu()?;
    let scenes = SceneCache::default();
    // Per sequence, its clean frames, or why its renders cannot be compared.
    let mut clean: BTreeMap<&str, Result<CleanFrames, String>> = BTreeMap::new();
    let mut rows = Vec::new();
    for (sequence, method, repeat, renders) in runs {
        if !clean.contains_key(sequence.name.as_str()) {
            let frames = match sequence.layout() {
                Layout::Camera(_) => Ok(make_clean_frames(&ctx, &scenes, suite, sequence, out)?),
                layout => Err(format!(
                    "{}: rendered views are compared in the replica and tum layouts, not {layout}",
                    sequence.name
                )),
            };
            clean.insert(&sequence.name, frames);
        }
        let compared = match &clean[sequence.name.as_str()] {
            Ok(frames) => frames.compare(&renders),
            Err(failure) => Err(failure.clone()),
        };
        let (quality, failure) = match compared {
            Ok(quality) => (Some(quality), None),
            Err(failure) => (None, Some(failure)),
        };
        rows.push(RenderedViewRow {
            ate_m: ate_of(&method, &sequence.name, repeat),
            method,
            sequence: sequence.name.clone(),
            repeat,
            quality,
            failure,
        });
    }
    let csv = out.join("rendered_views.csv");
    let json = out.join("rendered_views.json");
    let json_text =
        serde_json::to_string_pretty(&rows).map_err(|e| SuiteError::io(&json, e.into()))?;
    for (path, text) in [(&csv, rendered_views_csv(&rows)), (&json, json_text + "\n")] {
        std::fs::write(path, text).map_err(|e| SuiteError::io(path, e))?;
    }
    let points: Vec<ViewQualityPoint> = rows
        .iter()
        .filter_map(|r| {
            let quality = r.quality.as_ref()?;
            Some(ViewQualityPoint {
                method: r.method.clone(),
                ate_m: r.ate_m?,
                psnr_db: quality.psnr_db,
                depth_l1_cm: quality.depth_l1_cm,
            })
        })
        .collect();
    let mut written = vec![csv, json];
    for figure in ["rendered_views.png", "rendered_views.svg"] {
        let path = out.join(figure);
        plot_view_quality_against_ate(&path, &points)?;
        written.push(path);
    }
    Ok((rows, written))
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Stream {
    Colour,
    Depth,
}

/// The clean frames of one sequence, by their path in the dataset without the extension.
struct CleanFrames {
    by_stem: BTreeMap<PathBuf, (Stream, PathBuf)>,
    /// The first colour frame's path in the dataset, for messages.
    example: String,
    depth_scale: f64,
}

fn make_clean_frames(
    ctx: &GpuContext,
    scenes: &SceneCache,
    suite: &Suite,
    sequence: &Sequence,
    out: &Path,
) -> Result<CleanFrames, SuiteError> {
    let dir = out.join(CLEAN_DIR).join(&sequence.name);
    sequence
        .clean_job(&suite.dir, dir.clone())
        .plan_with(scenes)?
        .run(ctx, &Silent)?;
    let dataset = read_dataset(&dir, &DatasetOverrides::default()).map_err(PipelineError::from)?;
    let stem = |path: &Path| path.strip_prefix(&dir).unwrap_or(path).with_extension("");
    let mut by_stem = BTreeMap::new();
    for frame in &dataset.frames {
        by_stem.insert(stem(&frame.rgb), (Stream::Colour, frame.rgb.clone()));
        if let Some(depth) = &frame.depth {
            by_stem.insert(stem(depth), (Stream::Depth, depth.clone()));
        }
    }
    let example = dataset.frames.first().map_or(String::new(), |f| {
        f.rgb
            .strip_prefix(&dir)
            .unwrap_or(&f.rgb)
            .display()
            .to_string()
    });
    Ok(CleanFrames {
        by_stem,
        example,
        depth_scale: dataset.format.depth_scale(),
    })
}

/// One rendered frame's numbers.
enum FrameScore {
    Colour { psnr_db: f64, ssim: Option<f64> },
    Depth { l1_m: Option<f64> },
}

impl CleanFrames {
    /// Every image under `renders` against the clean frame named as it is; an error (one line,
    /// naming the file) for an image named like no frame, of another size, or unreadable.
    fn compare(&self, renders: &Path) -> Result<ViewQuality, String> {
        let mut pairs = Vec::new();
        for path in images_under(renders)? {
            let relative = path
                .strip_prefix(renders)
                .unwrap_or(&path)
                .with_extension("");
            let Some((stream, clean)) = self.by_stem.get(&relative) else {
                return Err(format!(
                    "{}: named like no frame of the dataset (expected e.g. {})",
                    path.display(),
                    self.example
                ));
            };
            pairs.push((*stream, path, clean.clone()));
        }
        if pairs.is_empty() {
            return Err(format!(
                "{}: no rendered frame (PNG or JPEG named like the dataset's frames)",
                renders.display()
            ));
        }
        let scores = pairs
            .par_iter()
            .map(|(stream, rendered, clean)| self.score(*stream, rendered, clean))
            .collect::<Result<Vec<_>, String>>()?;
        let mut quality = ViewQuality {
            colour_frames: 0,
            psnr_db: None,
            ssim: None,
            depth_frames: 0,
            depth_l1_cm: None,
        };
        let (mut psnr, mut ssims, mut l1) = (Vec::new(), Vec::new(), Vec::new());
        for score in scores {
            match score {
                FrameScore::Colour { psnr_db, ssim } => {
                    quality.colour_frames += 1;
                    psnr.push(psnr_db);
                    ssims.extend(ssim);
                }
                FrameScore::Depth { l1_m } => {
                    quality.depth_frames += 1;
                    l1.extend(l1_m.map(|m| m * 100.0));
                }
            }
        }
        quality.psnr_db = mean(&psnr);
        quality.ssim = mean(&ssims);
        quality.depth_l1_cm = mean(&l1);
        Ok(quality)
    }

    fn score(&self, stream: Stream, rendered: &Path, clean: &Path) -> Result<FrameScore, String> {
        let size_error = |got: (u32, u32), want: (u32, u32)| {
            format!(
                "{}: {}x{}, but the dataset's frames are {}x{}",
                rendered.display(),
                got.0,
                got.1,
                want.0,
                want.1
            )
        };
        match stream {
            Stream::Colour => {
                let a = read_rgb8(rendered).map_err(|e| e.to_string())?;
                let b = read_rgb8(clean).map_err(|e| e.to_string())?;
                if (a.width, a.height) != (b.width, b.height) {
                    return Err(size_error((a.width, a.height), (b.width, b.height)));
                }
                Ok(FrameScore::Colour {
                    psnr_db: psnr_db(&a, &b),
                    ssim: ssim(&a, &b),
                })
            }
            Stream::Depth => {
                let a = decode_depth_png(rendered, self.depth_scale).map_err(|e| e.to_string())?;
                let b = decode_depth_png(clean, self.depth_scale).map_err(|e| e.to_string())?;
                if (a.width, a.height) != (b.width, b.height) {
                    return Err(size_error((a.width, a.height), (b.width, b.height)));
                }
                Ok(FrameScore::Depth {
                    l1_m: depth_l1_m(&a, &b),
                })
            }
        }
    }
}

/// The PNG and JPEG files under `dir`, at any depth, in path order.
fn images_under(dir: &Path) -> Result<Vec<PathBuf>, String> {
    let mut found = Vec::new();
    let mut folders = vec![dir.to_path_buf()];
    while let Some(folder) = folders.pop() {
        let entries =
            std::fs::read_dir(&folder).map_err(|e| format!("{}: {e}", folder.display()))?;
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                folders.push(path);
            } else if path.extension().is_some_and(|e| {
                ["png", "jpg", "jpeg"].contains(&e.to_string_lossy().to_lowercase().as_str())
            }) {
                found.push(path);
            }
        }
    }
    found.sort();
    Ok(found)
}

fn mean(values: &[f64]) -> Option<f64> {
    (!values.is_empty()).then(|| values.iter().sum::<f64>() / values.len() as f64)
}

/// `rendered_views.csv`: one row per run with renders.
fn rendered_views_csv(rows: &[RenderedViewRow]) -> String {
    let mut text = String::from(
        "method,sequence,repeat,ate_m,colour_frames,psnr_db,ssim,depth_frames,depth_l1_cm,failure\n",
    );
    let number =
        |v: Option<f64>, decimals: usize| v.map_or(String::new(), |v| format!("{v:.decimals$}"));
    for r in rows {
        let measures = r.quality.as_ref().map(|q| {
            format!(
                "{},{},{},{},{}",
                q.colour_frames,
                number(q.psnr_db, 4),
                number(q.ssim, 6),
                q.depth_frames,
                number(q.depth_l1_cm, 4)
            )
        });
        let values = measures_or_failure(measures, 5, r.failure.as_deref());
        text.push_str(&format!(
            "{},{},{},{},{values}\n",
            r.method,
            r.sequence,
            r.repeat,
            number(r.ate_m, 6)
        ));
    }
    text
}
