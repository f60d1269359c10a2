//! Mapping metrics of every run that left a reconstruction, against its scene's ground-truth
//! mesh (exported once per scene into the report folder). The reconstruction must be in the
//! scene's world frame, as NICE-SLAM and Co-SLAM write theirs (they start from the ground-truth
//! first pose); one in the method's own frame would need the trajectory alignment applied first.
//! Both surfaces are culled to what the sequence's ground-truth cameras saw (its dataset's
//! views), by default as Co-SLAM does ([`Culling`]).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use rslam_core::dataset::{read_views, DatasetViews};
use rslam_eval::recon::{Culling, GroundTruthSurface, ReconMetrics, ReconOptions};
use serde::Serialize;

use rslam_pipeline::PipelineError;

use super::measured_csv::measures_or_failure;
use super::record::succeeded_runs_keeping;
use crate::sequence::Sequence;
use crate::{Suite, SuiteError};

/// One run's reconstruction metrics, or why its reconstruction could not be measured.
#[derive(Clone, Debug, Serialize)]
pub struct ReconRow {
    pub method: String,
    pub sequence: String,
    pub repeat: usize,
    pub metrics: Option<ReconMetrics>,
    /// Why the reconstruction could not be measured (`metrics` is then `None`).
    pub failure: Option<String>,
}

/// Evaluates the mesh of every finished run under `runs/` that wrote one, culled by `culling`,
/// and, when there is any, writes `out/reconstruction.csv` and `.json`; ground-truth meshes go
/// to `out/ground_truth/<scene>.ply`. Returns the rows and the files written.
pub fn report_reconstructions(
    suite: &Suite,
    out: &Path,
    culling: Culling,
) -> Result<(Vec<ReconRow>, Vec<PathBuf>), SuiteError> {
    let options = ReconOptions {
        culling,
        ..ReconOptions::default()
    };
    let runs = succeeded_runs_keeping(suite, |record| record.mesh.clone());
    let mut views: BTreeMap<&str, DatasetViews> = BTreeMap::new();
    if culling != Culling::None {
        for (sequence, ..) in &runs {
            if !views.contains_key(sequence.name.as_str()) {
                let read = read_views(&sequence.dir(&suite.dir)).map_err(PipelineError::from)?;
                views.insert(&sequence.name, read);
            }
        }
    }
    let mut meshes: BTreeMap<&str, PathBuf> = BTreeMap::new();
    // The ground truth of a sequence is sampled and culled once for all its runs.
    let mut ground_truths: BTreeMap<&str, Result<GroundTruthSurface, String>> = BTreeMap::new();
    let mut rows = Vec::new();
    for (sequence, method, repeat, mesh) in runs {
        if !ground_truths.contains_key(sequence.name.as_str()) {
            let path = match meshes.get(sequence.scene.as_str()) {
                Some(path) => path.clone(),
                None => {
                    let path = export_ground_truth(suite, sequence, out)?;
                    meshes.insert(&sequence.scene, path.clone());
                    path
                }
            };
            let prepared =
                GroundTruthSurface::prepare(&path, &options, views.get(sequence.name.as_str()));
            ground_truths.insert(&sequence.name, prepared.map_err(|e| e.to_string()));
        }
        // The ground truth is rslam's own export: what fails here is the method's file.
        let measured = match &ground_truths[sequence.name.as_str()] {
            Ok(ground_truth) => ground_truth.evaluate(&mesh).map_err(|e| e.to_string()),
            Err(failure) => Err(failure.clone()),
        };
        let (metrics, failure) = match measured {
            Ok(metrics) => (Some(metrics), None),
            Err(e) => (None, Some(e)),
        };
        rows.push(ReconRow {
            method,
            sequence: sequence.name.clone(),
            repeat,
            metrics,
            failure,
        });
    }
    if rows.is_empty() {
        return Ok((rows, Vec::new()));
    }
    let csv = out.join("reconstruction.csv");
    let json = out.join("reconstruction.json");
    let json_text =
        serde_json::to_string_pretty(&rows).map_err(|e| SuiteError::io(&json, e.into()))?;
    for (path, text) in [(&csv, reconstruction_csv(&rows)), (&json, json_text + "\n")] {
        std::fs::write(path, text).map_err(|e| SuiteError::io(path, e))?;
    }
    Ok((rows, vec![csv, json]))
}

fn export_ground_truth(
    suite: &Suite,
    sequence: &Sequence,
    out: &Path,
) -> Result<PathBuf, SuiteError> {
    let dir = out.join("ground_truth");
    std::fs::create_dir_all(&dir).map_err(|e| SuiteError::io(&dir, e))?;
    let name = Path::new(&sequence.scene)
        .file_stem()
        .map_or(sequence.scene.clone(), |s| s.to_string_lossy().into_owned());
    let path = dir.join(format!("{name}.ply"));
    let scene =
        rslam_render::load_scene(&sequence.scene_path(&suite.dir)).map_err(PipelineError::from)?;
    rslam_render::scene::export::write_ply(&scene, &path).map_err(PipelineError::from)?;
    Ok(path)
}

/// `reconstruction.csv`: one row per run with a mesh.
fn reconstruction_csv(rows: &[ReconRow]) -> String {
    let mut text = String::from(
        "method,sequence,repeat,accuracy_cm,completion_cm,completion_ratio_percent,\
         culling,reconstruction_kept_percent,ground_truth_kept_percent,failure\n",
    );
    for r in rows {
        let measures = r.metrics.as_ref().map(|m| {
            format!(
                "{:.4},{:.4},{:.2},{},{:.2},{:.2}",
                m.accuracy_cm,
                m.completion_cm,
                m.completion_ratio_percent,
                m.options.culling,
                m.reconstruction.kept_percent(),
                m.ground_truth.kept_percent()
            )
        });
        let values = measures_or_failure(measures, 6, r.failure.as_deref());
        text.push_str(&format!(
            "{},{},{},{values}\n",
            r.method, r.sequence, r.repeat
        ));
    }
    text
}
