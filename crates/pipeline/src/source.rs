//! Where source frames come from: a source records frame `index` into the frame textures on
//! the GPU — a scene draws it from its pose, a recording ([`RecordedSource`]: a dataset, one
//! camera of a EuRoC recording) uploads its decoded images, buffers in memory are uploaded as
//! they are. A rig of several sensors is several sources, one per camera, each with its own plan
//! and sink.

mod bag;
mod recorded;

pub use bag::BagSource;
pub use recorded::{ColourReader, RecordedFrame, RecordedSource};

use std::collections::HashMap;
use std::sync::Arc;

use rslam_core::{DepthImage, Intrinsics, Pose, RgbImage};
use rslam_gpu::{wgpu, FrameTextures, GpuContext};
use rslam_perturb::light::{LightSchedule, LightSpec};
use rslam_perturb::sensor::Shutter;
use rslam_perturb::PerturbSpec;
use rslam_render::actors::Actors;
use rslam_render::splat::SplatSettings;
use rslam_render::{Rasterizer, Scene};

use crate::lens_render::LensRender;
use crate::scene_light;
use crate::shutter_render::ShutterRender;
use crate::{JobPart, PipelineError};

pub trait FrameSource {
    /// Width and height of every frame.
    fn size(&self) -> (u32, u32);
    /// Whether frames carry depth.
    fn has_depth(&self) -> bool;
    /// Whether frames carry an instance mask (a scene with actors).
    fn has_mask(&self) -> bool {
        false
    }
    /// The camera the frames were taken with, where it is known (perturbations computed from
    /// the geometry, `depth_sensor`, need it).
    fn camera(&self) -> Option<Intrinsics>;
    /// Called once per run with the source frames it will record, in that order (decoding
    /// starts here).
    fn prepare(&mut self, ctx: &GpuContext, sources: &[usize]) -> Result<(), PipelineError>;
    /// Records source frame `index` into `frame`.
    fn record(
        &mut self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        index: usize,
    ) -> Result<(), PipelineError>;
}

/// A mesh drawn along a path: source frame `i` is the view from `poses[i]`, or under a shutter
/// the views from the poses around it during capture; under a lens, drawn wider and resampled;
/// under light items, each render lit by the light of the time it exposes; with actors, each
/// render shows them where they are at the middle of what it exposes.
pub struct SceneSource {
    scene: Arc<Scene>,
    /// Draws with `camera`, or under a lens with the lens view's wider pinhole.
    rasterizer: Rasterizer,
    /// The camera of the frames.
    camera: Intrinsics,
    poses: Vec<Pose>,
    shutter: Option<ShutterRender>,
    lens: Option<LensRender>,
    light: Option<LightSchedule>,
    /// What the light was made from: the spec's light items and the seed.
    light_key: Option<(LightSpec, u64)>,
    /// Source frames per second of capture (the path's rate, times `fast`'s K).
    rate_hz: f64,
    /// Capture time of each source frame, where not `i / rate_hz`.
    times_s: Option<Vec<f64>>,
    /// Actors are drawn: frames carry their instance masks through the lens and shutter.
    with_mask: bool,
}

impl SceneSource {
    pub fn new(
        ctx: &GpuContext,
        scene: &Arc<Scene>,
        camera: Intrinsics,
        poses: Vec<Pose>,
        capture: SplatSettings,
        actors: Option<Arc<Actors>>,
    ) -> Result<Self, PipelineError> {
        Ok(Self {
            scene: scene.clone(),
            with_mask: actors.is_some(),
            rasterizer: Rasterizer::with_actors(ctx, scene, camera, capture, actors)?,
            camera,
            poses,
            shutter: None,
            lens: None,
            light: None,
            light_key: None,
            rate_hz: 1.0,
            times_s: None,
        })
    }

    /// Captures frames with the sensor of `spec`: its shutter (`exposure`, `rolling_shutter`),
    /// the path sampled at `rate_hz`, its lens (`distortion`) and the light items' light (from
    /// `seed`); says whether that changes the frames. Under `fast:K` the camera covers K samples
    /// of the path per frame interval, during capture too.
    pub fn set_sensor(
        &mut self,
        ctx: &GpuContext,
        spec: &PerturbSpec,
        rate_hz: f64,
        seed: u64,
    ) -> Result<bool, PipelineError> {
        let last = (self.times_s.as_ref()).and_then(|t| t.last().copied());
        let horizon = last.unwrap_or(0.0).max(self.poses.len() as f64 / rate_hz) + 1.0;
        let light_key = (!spec.light.is_empty()).then_some((spec.light, seed));
        let light_changed = light_key != self.light_key;
        self.light = scene_light::schedule(&self.scene, spec, seed, horizon)?;
        self.light_key = light_key;
        let lens_changed = self.lens.as_ref().map(|l| *l.lens()) != spec.distortion;
        if lens_changed {
            self.lens = spec
                .distortion
                .map(|lens| LensRender::new(ctx, &self.camera, lens, self.with_mask))
                .transpose()?;
            let drawn = self.lens.as_ref().map_or(self.camera, |l| l.wide_camera());
            self.rasterizer.set_intrinsics(ctx, drawn)?;
        }
        let shutter = Shutter::of(spec);
        let rate_hz = rate_hz * f64::from(crate::plan::speed_up(spec));
        self.rate_hz = rate_hz;
        let same_shutter = !lens_changed
            && match &self.shutter {
                Some(current) => current.is(&shutter, rate_hz),
                None => shutter.is_none(),
            };
        if !same_shutter {
            let drawn = self.rasterizer.intrinsics();
            let size = (drawn.width, drawn.height);
            self.shutter = ShutterRender::new(ctx, shutter, rate_hz, size, self.with_mask)?;
        }
        Ok(!same_shutter || light_changed)
    }

    /// Takes source frame `i` at `times_s[i]` seconds (a rig camera's sample times) instead of
    /// `i` over the rate: the time its light is taken at. Set before [`Self::set_sensor`].
    pub fn set_times(&mut self, times_s: Vec<f64>) {
        self.times_s = Some(times_s);
    }

    pub fn poses(&self) -> &[Pose] {
        &self.poses
    }

    /// Draws `actors` from now on (the scene uploaded again with room for their vertices); call
    /// [`Self::set_sensor`] after it: the lens and shutter are made again when frames gain or lose
    /// their instance masks.
    pub fn set_actors(
        &mut self,
        ctx: &GpuContext,
        actors: Option<Arc<Actors>>,
    ) -> Result<(), PipelineError> {
        if actors.is_some() != self.with_mask {
            self.with_mask = actors.is_some();
            self.lens = None;
            self.shutter = None;
        }
        let drawn = *self.rasterizer.intrinsics();
        let settings = SplatSettings::default();
        self.rasterizer = Rasterizer::with_actors(ctx, &self.scene, drawn, settings, actors)?;
        Ok(())
    }

    pub fn scene(&self) -> &Arc<Scene> {
        &self.scene
    }

    /// Replaces the path (a new deviation of it); frame `i` is then the view from `poses[i]`.
    pub fn set_poses(&mut self, poses: Vec<Pose>) {
        self.poses = poses;
    }

    /// Records the view from `world_from_camera`, off the path (a free camera, at rest: no
    /// shutter effect; through the lens; in the light of the sequence's start).
    pub fn record_from(
        &mut self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        world_from_camera: &Pose,
    ) -> Result<(), PipelineError> {
        self.light_for(ctx, 0.0, (0.0, 0.0))?;
        let drawn = self.lens.as_ref().map_or(frame, |l| l.wide());
        self.rasterizer
            .encode(ctx, encoder, drawn, world_from_camera)?;
        self.through_lens(ctx, encoder, frame);
        Ok(())
    }

    /// Lights the next render with the light of `window` (seconds from `time`); the baked light
    /// without light items.
    fn light_for(
        &self,
        ctx: &GpuContext,
        time: f64,
        window: (f64, f64),
    ) -> Result<(), PipelineError> {
        let light = FrameLight {
            schedule: self.light.as_ref(),
            time,
        };
        light.apply(ctx, &self.rasterizer, window)?;
        self.rasterizer.pose_actors(ctx, light.instant(window));
        Ok(())
    }

    fn through_lens(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
    ) {
        if let Some(lens) = &self.lens {
            lens.record(ctx, encoder, frame);
        }
    }
}

impl FrameSource for SceneSource {
    fn size(&self) -> (u32, u32) {
        (self.camera.width, self.camera.height)
    }

    fn has_depth(&self) -> bool {
        true
    }

    fn has_mask(&self) -> bool {
        self.with_mask
    }

    fn camera(&self) -> Option<Intrinsics> {
        Some(self.camera)
    }

    fn prepare(&mut self, _ctx: &GpuContext, sources: &[usize]) -> Result<(), PipelineError> {
        check_in_range(sources, self.poses.len(), "poses of the path")
    }

    fn record(
        &mut self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        index: usize,
    ) -> Result<(), PipelineError> {
        let drawn = self.lens.as_ref().map_or(frame, |l| l.wide());
        let renders = match &self.shutter {
            Some(shutter) => shutter.schedule(&self.rasterizer, &self.poses, index),
            None => Vec::new(),
        };
        let time = match &self.times_s {
            Some(times) => times[index],
            None => index as f64 / self.rate_hz,
        };
        match (&self.shutter, renders.is_empty()) {
            (Some(shutter), false) => {
                let light = FrameLight {
                    schedule: self.light.as_ref(),
                    time,
                };
                shutter.record(ctx, &mut self.rasterizer, &renders, encoder, drawn, &light)?
            }
            _ => {
                let window = self.shutter.as_ref().map_or((0.0, 0.0), |s| s.window());
                self.light_for(ctx, time, window)?;
                self.rasterizer
                    .encode(ctx, encoder, drawn, &self.poses[index])?;
            }
        }
        self.through_lens(ctx, encoder, frame);
        Ok(())
    }
}

/// The light of one frame: the light items' schedule (`None`: the baked light) around the
/// frame's capture time.
pub(crate) struct FrameLight<'a> {
    schedule: Option<&'a LightSchedule>,
    time: f64,
}

impl FrameLight<'_> {
    /// The middle of `window` (seconds from the frame's time), in seconds from the start: the
    /// instant a render of that window shows the actors at.
    pub fn instant(&self, window: (f64, f64)) -> f64 {
        self.time + (window.0 + window.1) / 2.0
    }

    /// Lights `rasterizer`'s next render with the light over `window` (seconds from the
    /// frame's time).
    pub fn apply(
        &self,
        ctx: &GpuContext,
        rasterizer: &Rasterizer,
        window: (f64, f64),
    ) -> Result<(), PipelineError> {
        let weights =
            (self.schedule).map(|l| l.weights(self.time + window.0, self.time + window.1));
        Ok(rasterizer.set_light(ctx, weights.as_deref())?)
    }
}

/// Every source frame asked for is one of the `count` there are.
pub(crate) fn check_in_range(
    sources: &[usize],
    count: usize,
    what: &str,
) -> Result<(), PipelineError> {
    match sources.iter().find(|&&s| s >= count) {
        Some(s) => Err(PipelineError::option(
            JobPart::Frame,
            format!("{s} is past the {count} {what}"),
        )),
        None => Ok(()),
    }
}

/// Frames already in memory (numpy arrays from Python, images the viewer holds), all of one size.
/// Each buffer is one frame of a sequence: its frame number keys the perturbations' randomness,
/// as the frame index does in `rslam perturb`.
pub struct BufferSource {
    width: u32,
    height: u32,
    frames: Vec<(RgbImage, Option<DepthImage>)>,
    /// Frame number of each buffer, all different.
    numbers: Vec<usize>,
    /// Buffer of each frame number.
    buffer_of: HashMap<usize, usize>,
    camera: Option<Intrinsics>,
}

impl BufferSource {
    /// Fails unless every colour and depth image has the first colour image's size and either
    /// every frame or none has depth.
    pub fn new(frames: Vec<(RgbImage, Option<DepthImage>)>) -> Result<Self, PipelineError> {
        let Some((first, first_depth)) = frames.first() else {
            return Err(PipelineError::option(
                JobPart::Frames,
                "expected at least one frame",
            ));
        };
        let (width, height) = (first.width, first.height);
        let with_depth = first_depth.is_some();
        for (i, (color, depth)) in frames.iter().enumerate() {
            let sizes_agree = (color.width, color.height) == (width, height)
                && depth
                    .as_ref()
                    .is_none_or(|d| (d.width, d.height) == (width, height));
            if !sizes_agree || depth.is_some() != with_depth {
                return Err(PipelineError::option(
                    JobPart::Frames,
                    format!(
                        "frame {i}: expected {width}x{height} colour{} like frame 0",
                        if with_depth { " and depth" } else { "" }
                    ),
                ));
            }
        }
        let numbers: Vec<usize> = (0..frames.len()).collect();
        let buffer_of = numbers.iter().map(|&n| (n, n)).collect();
        Ok(Self {
            width,
            height,
            frames,
            numbers,
            buffer_of,
            camera: None,
        })
    }

    /// The same frames, taken with `camera` (what `depth_sensor` needs); fails unless the
    /// camera has the frames' size.
    pub fn with_camera(mut self, camera: Intrinsics) -> Result<Self, PipelineError> {
        if (camera.width, camera.height) != (self.width, self.height) {
            return Err(PipelineError::option(
                JobPart::Camera,
                format!(
                    "a {}x{} camera for {}x{} frames: expected the frames' size",
                    camera.width, camera.height, self.width, self.height
                ),
            ));
        }
        self.camera = Some(camera);
        Ok(self)
    }

    /// Like [`BufferSource::new`], with buffer i as frame `numbers[i]` of the sequence (a data
    /// loader's batch of frames 40, 7, 12, …); fails unless there is one number per buffer and
    /// no number is given twice.
    pub fn at_frames(
        frames: Vec<(RgbImage, Option<DepthImage>)>,
        numbers: Vec<usize>,
    ) -> Result<Self, PipelineError> {
        if numbers.len() != frames.len() {
            return Err(PipelineError::option(
                JobPart::FrameIndices,
                format!(
                    "{} frame indices for {} frames: expected one per frame",
                    numbers.len(),
                    frames.len()
                ),
            ));
        }
        let mut source = Self::new(frames)?;
        let mut buffer_of = HashMap::with_capacity(numbers.len());
        for (i, &n) in numbers.iter().enumerate() {
            if buffer_of.insert(n, i).is_some() {
                return Err(PipelineError::option(
                    JobPart::FrameIndices,
                    format!("frame index {n} is given twice"),
                ));
            }
        }
        source.numbers = numbers;
        source.buffer_of = buffer_of;
        Ok(source)
    }

    /// The frame number of each buffer, in buffer order.
    pub fn frame_numbers(&self) -> &[usize] {
        &self.numbers
    }

    pub fn len(&self) -> usize {
        self.frames.len()
    }

    pub fn is_empty(&self) -> bool {
        self.frames.is_empty()
    }
}

impl FrameSource for BufferSource {
    fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    fn has_depth(&self) -> bool {
        self.frames[0].1.is_some()
    }

    /// Frames handed over in memory come without a camera unless one was given.
    fn camera(&self) -> Option<Intrinsics> {
        self.camera
    }

    fn prepare(&mut self, _ctx: &GpuContext, sources: &[usize]) -> Result<(), PipelineError> {
        match sources.iter().find(|s| !self.buffer_of.contains_key(s)) {
            Some(s) => Err(PipelineError::option(
                JobPart::Frame,
                format!("{s} is not one of the frames given"),
            )),
            None => Ok(()),
        }
    }

    fn record(
        &mut self,
        ctx: &GpuContext,
        _encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        index: usize,
    ) -> Result<(), PipelineError> {
        let buffer = *self.buffer_of.get(&index).ok_or_else(|| {
            PipelineError::option(
                JobPart::Frame,
                format!("{index} is not one of the frames given"),
            )
        })?;
        let (color, depth) = &self.frames[buffer];
        frame.upload(ctx, color, depth.as_ref());
        Ok(())
    }
}
