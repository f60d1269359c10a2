//! The manifest of a run, assembled from its job and its plan before the first frame: what
//! lets someone regenerate the output bit for bit. No timings or dates: the same job writes the
//! same bytes.

use rslam_core::dataset::ros2::BagOptions;
use rslam_core::dataset::{DatasetFormat, DepthPng, Manifest};
use rslam_core::{Distortion, Intrinsics};
use rslam_perturb::PerturbSpec;

use crate::plan::FramePlan;
use crate::{JobPart, PipelineError};

pub struct ManifestParts<'a> {
    pub command: &'a [String],
    /// Built-in scene name, mesh path, or input folder.
    pub source: String,
    pub source_hash: String,
    pub format: Option<DatasetFormat>,
    pub camera: Option<Intrinsics>,
    /// The lens the frames were seen through (written into the camera files too).
    pub distortion: Option<Distortion>,
    pub depth_png: DepthPng,
    pub bag: BagOptions,
    pub rate_hz: f64,
    pub seed: u64,
    pub spec: &'a PerturbSpec,
    pub plan: &'a FramePlan,
    pub extra: serde_json::Value,
}

impl ManifestParts<'_> {
    pub fn build(self) -> Result<Manifest, PipelineError> {
        let perturbation_parsed = serde_json::to_value(self.spec)
            .map_err(|e| PipelineError::option(JobPart::Spec, e.to_string()))?;
        Ok(Manifest {
            tool: "rslam".into(),
            tool_version: env!("CARGO_PKG_VERSION").into(),
            command: self.command.to_vec(),
            source: self.source,
            source_hash: self.source_hash,
            format: self.format,
            camera: self.camera,
            distortion: self.distortion,
            depth_png: self.depth_png,
            bag: self.bag,
            rate_hz: self.rate_hz,
            frame_count: self.plan.len(),
            seed: self.seed,
            perturbation: self.spec.to_string(),
            perturbation_parsed,
            severities: self.plan.severities.clone(),
            rgb_source: self.plan.rgb_source.clone(),
            depth_source: self.plan.depth_source.clone(),
            extra: self.extra,
            content_digest: String::new(),
        })
    }
}
