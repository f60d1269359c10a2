//! Mapping metrics of every run that left a reconstruction, against its scene's ground-truth
//! mesh (exported once per scene into the report folder). The reconstruction must be in the
//! scene's world frame, as NICE-SLAM and Co-SLAM write theirs (they start from the ground-truth
//! first pose); one in the method's own frame would need the trajectory alignment applied first.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use rslam_eval::recon::{evaluate_reconstruction, ReconMetrics, ReconOptions};
use serde::Serialize;

use super::record::RunFiles;
use crate::{Suite, SuiteError};

/// One run's reconstruction metrics.
#[derive(Clone, Debug, Serialize)]
pub struct ReconRow {
    pub method: String,
    pub sequence: String,
    pub repeat: usize,
    pub metrics: ReconMetrics,
}

/// Evaluates the mesh of every finished run under `runs/` that wrote one; ground-truth meshes go
/// to `out/ground_truth/<scene>.ply`.
pub fn evaluate_reconstructions(suite: &Suite, out: &Path) -> Result<Vec<ReconRow>, SuiteError> {
    let mut ground_truth: BTreeMap<String, PathBuf> = BTreeMap::new();
    let mut rows = Vec::new();
    for (method, sequence, repeat, mesh) in meshes(suite)? {
        let Some(row) = suite.sequences.iter().find(|s| s.name == sequence) else {
            continue;
        };
        let gt = match ground_truth.get(&row.scene) {
            Some(path) => path.clone(),
            None => {
                let path = export_ground_truth(suite, &row.scene, out)?;
                ground_truth.insert(row.scene.clone(), path.clone());
                path
            }
        };
        let metrics = evaluate_reconstruction(&mesh, &gt, &ReconOptions::default())?;
        rows.push(ReconRow {
            method,
            sequence,
            repeat,
            metrics,
        });
    }
    Ok(rows)
}

/// (method, sequence, repeat, mesh) of every finished run whose record names a mesh.
fn meshes(suite: &Suite) -> Result<Vec<(String, String, usize, PathBuf)>, SuiteError> {
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
                    found.push((method.clone(), sequence.name.clone(), repeat, mesh));
                }
            }
        }
    }
    Ok(found)
}

fn export_ground_truth(suite: &Suite, scene: &str, out: &Path) -> Result<PathBuf, SuiteError> {
    let dir = out.join("ground_truth");
    std::fs::create_dir_all(&dir).map_err(|e| SuiteError::io(&dir, e))?;
    let file_name = Path::new(scene)
        .file_stem()
        .map_or(scene.into(), |s| s.to_string_lossy().into_owned());
    let path = dir.join(format!("{file_name}.ply"));
    let source = if rslam_render::builtin_path_length(scene).is_some() {
        scene.to_string()
    } else {
        suite.dir.join(scene).display().to_string()
    };
    let loaded = rslam_render::load_scene(&source).map_err(rslam_pipeline::PipelineError::from)?;
    rslam_render::scene::export::write_ply(&loaded, &path)
        .map_err(rslam_pipeline::PipelineError::from)?;
    Ok(path)
}

/// `reconstruction.csv`: one row per run with a mesh.
pub fn reconstruction_csv(rows: &[ReconRow]) -> String {
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
