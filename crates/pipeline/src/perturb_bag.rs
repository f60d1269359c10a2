//! `rslam perturb` on a recorded ROS 2 bag: its camera's colour (and depth) messages decoded,
//! perturbed and written back in their encodings into a bag of the same topics, every other
//! message copied ([`rslam_core::dataset::ros2::RecordedBagCamera`]). `misalign` moves the depth
//! stamps; `fast` is refused, since the copied topics keep their times. Like a bag rslam renders,
//! it is written from its first message on every run.

use std::path::Path;
use std::sync::Arc;

use rslam_core::dataset::ros2::{PerturbedBag, RecordedBag, RecordedBagCamera};
use rslam_core::dataset::{ContentWriter, DatasetFormat, DepthPng, Manifest};
use rslam_gpu::GpuContext;
use rslam_perturb::PerturbSpec;

use crate::job::{Planned, Streams, Writing};
use crate::manifest::ManifestParts;
use crate::output_folder::Written;
use crate::pipeline::Pipeline;
use crate::plan::{FramePlan, SourceTiming};
use crate::sink::PerturbedBagSink;
use crate::source::BagSource;
use crate::{settings, PipelineError};

pub(crate) struct BagPerturb<'a> {
    spec: &'a PerturbSpec,
    seed: u64,
    camera: Arc<RecordedBagCamera>,
    /// Per source frame: its colour and depth stamps, in seconds.
    recorded_times: Vec<(f64, f64)>,
    plan: FramePlan,
    manifest: Manifest,
}

pub(crate) fn plan<'a>(
    input: &Path,
    spec: &'a PerturbSpec,
    seed: u64,
    command: &[String],
) -> Result<BagPerturb<'a>, PipelineError> {
    let camera = RecordedBagCamera::read(RecordedBag::open(input)?)?;
    settings::check(spec, &settings::recorded_bag(&camera))?;
    let recorded_times: Vec<(f64, f64)> = camera
        .colour
        .messages
        .iter()
        .enumerate()
        .map(|(i, colour)| {
            let rgb = colour.stamp.seconds();
            let depth = camera
                .depth
                .as_ref()
                .map_or(rgb, |d| d.messages[i].stamp.seconds());
            (rgb, depth)
        })
        .collect();
    let rgb_times: Vec<f64> = recorded_times.iter().map(|t| t.0).collect();
    let depth_offsets: Vec<f64> = recorded_times.iter().map(|t| t.1 - t.0).collect();
    let plan = FramePlan::recorded(
        &SourceTiming {
            rgb_times: &rgb_times,
            depth_offsets: &depth_offsets,
            rate_hz: camera.rate_hz,
        },
        spec,
        seed,
    );
    let manifest = ManifestParts {
        command,
        source: input.display().to_string(),
        source_hash: String::new(),
        format: Some(DatasetFormat::Ros2),
        camera: Some(camera.intrinsics),
        distortion: camera.distortion,
        depth_png: DepthPng::default(),
        rate_hz: camera.rate_hz,
        seed,
        spec,
        plan: &plan,
        extra: serde_json::json!({
            "colour_topic": camera.colour.name,
            "depth_topic": camera.depth.as_ref().map(|d| d.name.clone()),
        }),
    }
    .build()?;
    Ok(BagPerturb {
        spec,
        seed,
        camera: Arc::new(camera),
        recorded_times,
        plan,
        manifest,
    })
}

impl Planned for BagPerturb<'_> {
    fn manifest(&self) -> &Manifest {
        &self.manifest
    }

    fn streams(&self) -> Streams {
        Streams::Frames(self.plan.len())
    }

    fn open<'a>(&'a self, ctx: &'a GpuContext) -> Result<Writing<'a>, PipelineError> {
        let source = BagSource::new(self.camera.clone());
        let mut pipeline = Pipeline::new(ctx, source, self.spec, self.seed)?;
        Ok(Box::new(move |out, _found, manifest, progress| {
            let bag = PerturbedBag::create(out, self.camera.clone())?;
            let content = ContentWriter::new(out);
            let mut sink = PerturbedBagSink::new(bag, content, &self.plan, &self.recorded_times);
            let sources = self.plan.needed_sources();
            progress.start(sources.len(), "perturbing");
            pipeline.run(ctx, &sources, progress, &mut sink)?;
            progress.finish();
            let manifest = sink.finish(manifest)?;
            Ok(Written {
                made: sources.len(),
                manifest,
            })
        }))
    }
}
