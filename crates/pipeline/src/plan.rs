//! The frame plan, made before any frame is drawn: which source frame each output frame's colour
//! and depth come from, when each was captured, and the severity every frame corruption gives
//! every output frame. A pure function of the spec, the seed and the source's timing, recorded as
//! is in the manifest.

use std::collections::HashMap;
use std::ops::Range;

use rslam_core::dataset::{ItemSeverities, OutputFrame};
use rslam_core::{Pose, Trajectory};
use rslam_perturb::{severity_on, PerturbSpec};

#[derive(Clone, Debug, PartialEq)]
pub struct FramePlan {
    /// Per output frame: the source frame of its colour.
    pub rgb_source: Vec<usize>,
    /// Per output frame: the source frame of its depth (differs under `misalign`).
    pub depth_source: Vec<usize>,
    /// Per output frame: colour and depth capture times.
    pub frames: Vec<OutputFrame>,
    /// Per frame corruption of the spec (image items, then depth items): one digit per output
    /// frame, the severity it received (0 = clean).
    pub severities: Vec<ItemSeverities>,
}

/// The output frames one source frame contributes to, ascending.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SourceOutputs {
    pub rgb: Vec<usize>,
    pub depth: Vec<usize>,
}

/// When each source frame was captured.
pub struct SourceTiming<'a> {
    pub rgb_times: &'a [f64],
    /// Depth capture time minus colour capture time, per source frame.
    pub depth_offsets: &'a [f64],
    /// The sensor rate: under `fast` the kept frames are re-stamped at it.
    pub rate_hz: f64,
}

/// How many times faster than captured the sequence plays: `fast:K` keeps every K-th frame and
/// re-stamps the kept ones at the sensor rate, or, in a rig, plays the body's motion K times
/// faster. The one place `fast` is read.
pub fn speed_up(spec: &PerturbSpec) -> u32 {
    spec.fast.unwrap_or(1).max(1)
}

/// Whether the output frames are re-stamped (`fast`), so that the ground truth is taken at each
/// kept frame rather than kept whole.
pub fn restamps(spec: &PerturbSpec) -> bool {
    spec.fast.is_some()
}

/// The spec as one camera of a rig takes it for its frames: its items
/// ([`PerturbSpec::for_camera`]) without `fast`, which the rig's motion has taken already.
pub fn camera_frame_spec(spec: &PerturbSpec, camera: &str) -> PerturbSpec {
    PerturbSpec {
        fast: None,
        ..spec.for_camera(camera)
    }
}

impl FramePlan {
    /// Frames rendered along a path of `source_frames` poses at `rate_hz`, from time 0.
    pub fn rendered(source_frames: usize, rate_hz: f64, spec: &PerturbSpec, seed: u64) -> Self {
        let times: Vec<f64> = (0..source_frames).map(|i| i as f64 / rate_hz).collect();
        let offsets = vec![0.0; source_frames];
        Self::recorded(
            &SourceTiming {
                rgb_times: &times,
                depth_offsets: &offsets,
                rate_hz,
            },
            spec,
            seed,
        )
    }

    /// Frames recorded at `timing`. Without `fast` every output frame keeps its capture time;
    /// with `fast:K` every K-th frame is kept and re-stamped at the sensor rate from the first
    /// frame's time (the sequence plays K times faster). Under `misalign` a depth image keeps the
    /// capture time of its own frame.
    pub fn recorded(timing: &SourceTiming, spec: &PerturbSpec, seed: u64) -> Self {
        let stream = rslam_perturb::stream::plan(timing.rgb_times.len(), spec, seed);
        let t0 = timing.rgb_times.first().copied().unwrap_or(0.0);
        let rgb_time = |j: usize, source: usize| match spec.fast {
            Some(_) => t0 + j as f64 / timing.rate_hz,
            None => timing.rgb_times[source],
        };
        let time_of_source: HashMap<usize, f64> = stream
            .rgb_source
            .iter()
            .enumerate()
            .map(|(j, &s)| (s, rgb_time(j, s)))
            .collect();
        let frames = (0..stream.rgb_source.len())
            .map(|j| {
                let depth = stream.depth_source[j];
                OutputFrame {
                    rgb_time: rgb_time(j, stream.rgb_source[j]),
                    // The depth's source is always an output frame too: misalign only delays.
                    depth_time: time_of_source[&depth] + timing.depth_offsets[depth],
                }
            })
            .collect();
        let severities = severities(spec, seed, &stream.rgb_source, &stream.depth_source);
        Self {
            rgb_source: stream.rgb_source,
            depth_source: stream.depth_source,
            frames,
            severities,
        }
    }

    /// `count` separate images (with their depth, if `with_depth`): image i is output frame i
    /// and the RNG's frame i; no capture times.
    pub fn images(count: usize, with_depth: bool, spec: &PerturbSpec, seed: u64) -> Self {
        let sources: Vec<usize> = (0..count).collect();
        Self::images_at(&sources, with_depth, spec, seed)
    }

    /// Separate images that are frames `numbers` of a sequence: output frame i is source frame
    /// `numbers[i]`, which keys its randomness; no capture times.
    pub fn images_at(numbers: &[usize], with_depth: bool, spec: &PerturbSpec, seed: u64) -> Self {
        let sources = numbers.to_vec();
        let depth_source = if with_depth {
            sources.clone()
        } else {
            Vec::new()
        };
        Self {
            severities: severities(spec, seed, &sources, &depth_source),
            rgb_source: sources,
            depth_source,
            frames: Vec::new(),
        }
    }

    pub fn len(&self) -> usize {
        self.rgb_source.len()
    }

    pub fn is_empty(&self) -> bool {
        self.rgb_source.is_empty()
    }

    /// Every source frame some output needs, ascending.
    pub fn needed_sources(&self) -> Vec<usize> {
        let mut all: Vec<usize> = self
            .rgb_source
            .iter()
            .chain(&self.depth_source)
            .copied()
            .collect();
        all.sort_unstable();
        all.dedup();
        all
    }

    /// The source frames output frames `outputs` need (their depth too if `with_depth`),
    /// ascending.
    pub fn sources_for(&self, outputs: Range<usize>, with_depth: bool) -> Vec<usize> {
        let depth = if with_depth {
            &self.depth_source[outputs.clone()]
        } else {
            &[]
        };
        let mut sources: Vec<usize> = self.rgb_source[outputs]
            .iter()
            .chain(depth)
            .copied()
            .collect();
        sources.sort_unstable();
        sources.dedup();
        sources
    }

    /// For every source frame, the output frames showing its colour and those carrying its
    /// depth: one pass over the plan, for sinks that look it up per frame.
    pub fn outputs_by_source(&self) -> HashMap<usize, SourceOutputs> {
        let mut outputs: HashMap<usize, SourceOutputs> = HashMap::new();
        for (j, &s) in self.rgb_source.iter().enumerate() {
            outputs.entry(s).or_default().rgb.push(j);
        }
        for (j, &s) in self.depth_source.iter().enumerate() {
            outputs.entry(s).or_default().depth.push(j);
        }
        outputs
    }

    /// The ground truth of the output: the pose of each output frame's colour source, stamped
    /// with its capture time. `poses` holds one pose per source frame.
    pub fn ground_truth(&self, poses: &[Pose]) -> Trajectory {
        Trajectory::new(
            self.frames.iter().map(|f| f.rgb_time).collect(),
            self.rgb_source.iter().map(|&s| poses[s]).collect(),
        )
    }
}

/// Image corruptions are keyed by the colour's source frame, depth corruptions by the depth's.
fn severities(
    spec: &PerturbSpec,
    seed: u64,
    rgb_source: &[usize],
    depth_source: &[usize],
) -> Vec<ItemSeverities> {
    let column = |item: &rslam_perturb::FrameItem, sources: &[usize]| {
        let got: Vec<f64> = sources
            .iter()
            .map(|&s| severity_on(&item.name, &item.level, seed, s as u32).value())
            .collect();
        ItemSeverities::new(item.to_string(), &got)
    };
    spec.image
        .iter()
        .map(|item| column(item, rgb_source))
        .chain(spec.depth.iter().map(|item| column(item, depth_source)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(text: &str) -> PerturbSpec {
        PerturbSpec::parse(text).unwrap()
    }

    #[test]
    fn clean_render_maps_each_frame_to_itself_at_the_rate() {
        let plan = FramePlan::rendered(4, 20.0, &PerturbSpec::default(), 0);
        assert_eq!(plan.rgb_source, vec![0, 1, 2, 3]);
        assert_eq!(plan.depth_source, plan.rgb_source);
        assert_eq!(plan.frames[3].rgb_time, 0.15);
        assert_eq!(plan.frames[3].depth_time, 0.15);
        assert!(plan.severities.is_empty());
    }

    #[test]
    fn fast_restamps_kept_frames_at_the_sensor_rate() {
        let times = [10.0, 10.05, 10.1, 10.15, 10.2, 10.25];
        let offsets = [0.004; 6];
        let timing = SourceTiming {
            rgb_times: &times,
            depth_offsets: &offsets,
            rate_hz: 20.0,
        };
        let plan = FramePlan::recorded(&timing, &spec("fast:3"), 0);
        assert_eq!(plan.rgb_source, vec![0, 3]);
        assert_eq!(plan.frames[1].rgb_time, 10.05);
        assert!((plan.frames[1].depth_time - 10.054).abs() < 1e-12);
        let unchanged = FramePlan::recorded(&timing, &PerturbSpec::default(), 0);
        assert_eq!(unchanged.frames[3].rgb_time, 10.15, "no fast: times kept");
    }

    #[test]
    fn misaligned_depth_keeps_its_own_capture_time_and_outputs_are_listed() {
        let plan = FramePlan::rendered(6, 10.0, &spec("misalign:2"), 0);
        assert_eq!(plan.depth_source, vec![0, 0, 0, 1, 2, 3]);
        assert_eq!(plan.frames[4].depth_time, 0.2);
        let outputs = plan.outputs_by_source();
        assert_eq!(outputs[&0].depth, vec![0, 1, 2]);
        assert_eq!(outputs[&4].rgb, vec![4]);
        assert!(outputs[&5].depth.is_empty());
        assert_eq!(plan.needed_sources(), vec![0, 1, 2, 3, 4, 5]);
    }

    #[test]
    fn severities_follow_the_frame_each_item_acts_on() {
        let plan = FramePlan::rendered(
            40,
            20.0,
            &spec("fog:3@dynamic,depth_missing:2,misalign:5"),
            7,
        );
        assert_eq!(plan.severities.len(), 2);
        let fog = &plan.severities[0].per_frame;
        assert_eq!(fog.len(), 40);
        assert!(fog.chars().all(|c| ('0'..='3').contains(&c)));
        assert!(fog.chars().collect::<std::collections::BTreeSet<_>>().len() > 1);
        let three = rslam_perturb::Severity::whole(3).unwrap();
        for (j, c) in fog.chars().enumerate() {
            let expected = rslam_perturb::dynamic_severity(7, "fog", j as u32, three);
            assert_eq!(c, char::from(b'0' + expected.floor()), "frame {j}");
        }
        assert_eq!(plan.severities[1].per_frame, "2".repeat(40));
    }

    /// A real severity's column holds numbers: the static one's at every frame, a dynamic
    /// one's draws over [0, s], not only whole ones.
    #[test]
    fn real_severities_are_written_as_numbers() {
        let plan = FramePlan::rendered(30, 20.0, &spec("fog:2.5@dynamic,depth_missing:1.5"), 7);
        let fog = plan.severities[0].values().unwrap();
        assert_eq!(fog.len(), 30);
        assert!(fog.iter().all(|s| (0.0..=2.5).contains(s)));
        assert!(fog.iter().any(|s| s.fract() != 0.0));
        assert_eq!(plan.severities[1].per_frame, vec!["1.5"; 30].join(" "));
    }

    #[test]
    fn ground_truth_takes_the_colour_source_pose_at_the_output_time() {
        let poses: Vec<Pose> = (0..6)
            .map(|i| Pose::new(glam::DQuat::IDENTITY, glam::DVec3::new(i as f64, 0.0, 0.0)))
            .collect();
        let plan = FramePlan::rendered(6, 10.0, &spec("fast:2"), 0);
        let gt = plan.ground_truth(&poses);
        assert_eq!(gt.timestamps, vec![0.0, 0.1, 0.2]);
        assert_eq!(gt.poses[2].translation.x, 4.0);
    }
}
