//! Mapping metrics of every run that left a reconstruction, against its scene's ground-truth
//! mesh (exported once per scene into the report folder). The reconstruction must be in the
//! scene's world frame, as NICE-SLAM and Co-SLAM write theirs (they start from the ground-truth
//! first pose); one in the method's own frame would need the trajectory alignment applied first.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use rslam_eval::recon::{evaluate_reconstruction, ReconMetrics, ReconOptions};
use serde::Serialize;

use rslam_pipeline::PipelineError;

use super::record::RunFiles;
use crate::sequence::Sequence;
use crate::{Suite, SuiteError};

/// One run's reconstruction metrics.
#[derive(Clone, Debug, Serialize)]
pub struct ReconRow {
    pub method: String,
    pub sequence: String,
    pub repeat: usize,
    pub metrics: ReconMetrics,
}

/// Evaluates the mesh of every finished run under `runs/` that wrote one and, when there is any,
/// writes `out/reconstruction.csv` and `.json`; ground-truth meshes go to
/// `out/ground_truth/<scene>.ply`. Returns the rows and the files written.
pub fn report_reconstructions(
    suite: &Suite,
    out: &Path,
) -> Result<(Vec<ReconRow>, Vec<PathBuf>), SuiteError> {
    let mut ground_truth: BTreeMap<&str, PathBuf> = BTreeMap::new();
    let mut rows = Vec::new();
    for (method, sequence, repeat, mesh) in meshes(suite)? {
        let gt = match ground_truth.get(sequence.scene.as_str()) {
            Some(path) => path.clone(),
            None => {
                let path = export_ground_truth(suite, sequence, out)?;
                ground_truth.insert(&sequence.scene, path.clone());
                path
            }
        };
        let metrics = evaluate_reconstruction(&mesh, &gt, &ReconOptions::default())?;
        rows.push(ReconRow {
            method,
            sequence: sequence.name.clone(),
            repeat,
            metrics,
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

/// (method, sequence, repeat, mesh) of every finished run whose record names a mesh.
fn meshes(suite: &Suite) -> Result<Vec<(String, &Sequence, usize, PathBuf)>, SuiteError> {
    let runs = suite.dir.join(super::RUNS_DIR);
    let mut found = Vec::new();
    let Ok(methods) = std::fs::read_dir(&runs) else {
        return Ok(found);
    };
    let mut methods: Vec<String> = methods
        .flatten()
        .filter(|e| e.path().is_dir())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    methods.sort();
    for method in methods {
        for sequence in &suite.sequences {
            for repeat in 0.. {
                let files = RunFiles::new(&suite.dir, &method, &sequence.name, repeat);
                let Some(record) = files.read_record() else {
                    break;
                };
                if let (None, Some(mesh)) = (&record.failure, record.mesh) {
                    found.push((method.clone(), sequence, repeat, mesh));
                }
            }
        }
    }
    Ok(found)
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
    let mut text =
        String::from("method,sequence,repeat,accuracy_cm,completion_cm,completion_ratio_percent\n");
    for r in rows {
        text.push_str(&format!(
            "{},{},{},{:.4},{:.4},{:.2}\n",
            r.method,
            r.sequence,
            r.repeat,
            r.metrics.accuracy_cm,
            r.metrics.completion_cm,
            r.metrics.completion_ratio_percent
        ));
    }
    text
}
