//! The manifest of a generated dataset, assembled from the job's parts.

use rslam_core::dataset::{DatasetFormat, ItemSeverities, Manifest};
use rslam_core::Intrinsics;
use rslam_perturb::{PerturbSpec, Perturber};

use super::sink::OutputPlan;

pub struct ManifestBuilder<'a> {
    pub command: &'a [String],
    pub source: &'a str,
    pub source_hash: String,
    pub format: DatasetFormat,
    pub camera: Intrinsics,
    pub rate_hz: f64,
    pub seed: u64,
    pub spec: &'a PerturbSpec,
    pub perturber: &'a Perturber,
    pub plan: &'a OutputPlan,
    pub extra: serde_json::Value,
}

impl ManifestBuilder<'_> {
    pub fn build(self) -> anyhow::Result<Manifest> {
        let plan = self.plan;
        let image_items = self.spec.image.len();
        let labels: Vec<String> = self
            .spec
            .frame_items()
            .map(|item| item.to_string())
            .collect();
        let severities = labels
            .iter()
            .enumerate()
            .map(|(i, label)| {
                // Image corruptions live on the colour frame, depth corruptions on the depth frame.
                let sources = if i < image_items {
                    &plan.rgb_source
                } else {
                    &plan.depth_source
                };
                let per_frame = sources
                    .iter()
                    .map(|&s| {
                        let got = self.perturber.severities(s as u32).items[i].severity;
                        char::from(b'0' + got)
                    })
                    .collect();
                ItemSeverities {
                    item: label.clone(),
                    per_frame,
                }
            })
            .collect();
        Ok(Manifest {
            tool: "rslam".into(),
            tool_version: env!("CARGO_PKG_VERSION").into(),
            command: self.command.to_vec(),
            source: self.source.to_string(),
            source_hash: self.source_hash,
            format: Some(self.format),
            camera: Some(self.camera),
            rate_hz: self.rate_hz,
            frame_count: plan.frames.len(),
            seed: self.seed,
            perturbation: self.spec.to_string(),
            perturbation_parsed: serde_json::to_value(self.spec)?,
            severities,
            rgb_source: plan.rgb_source.clone(),
            depth_source: plan.depth_source.clone(),
            extra: self.extra,
        })
    }
}
