//! Applies a spec's image and depth corruptions to frames on the GPU.

use rslam_core::Intrinsics;
use rslam_gpu::{FrameTextures, GpuContext};
use serde::Serialize;

use crate::perturbation::{FrameKey, GpuPerturbation, Kit, Scratch};
use crate::rng::RngKey;
use crate::severity::Severity;
use crate::spec::{Level, PerturbSpec};
use crate::{catalogue, PerturbError};

/// Purpose of the draw that picks a frame's severity in `@dynamic` mode.
const PURPOSE_DYNAMIC_SEVERITY: u32 = 0xD1_0000;

/// The severity `name` gets on `frame` in `@dynamic` mode: uniform in {0, 1, …, max} for a
/// whole `max`, uniform over [0, max] in steps of 0.01 for a real one.
pub fn dynamic_severity(seed: u64, name: &str, frame: u32, max: Severity) -> Severity {
    let u = RngKey::new(seed, name, frame, PURPOSE_DYNAMIC_SEVERITY).uniform_f64([0; 4]);
    let (steps, step) = match max.as_whole() {
        Some(whole) => (whole as u16, 100),
        None => (max.hundredths(), 1),
    };
    let drawn = ((u * (steps as f64 + 1.0)) as u16).min(steps);
    Severity::from_hundredths(drawn * step).expect("a draw up to the maximum")
}

/// The severity an item named `name` at `level` gives `frame` (pure): its severity, a draw in
/// [0, severity] under `@dynamic`, and 5 for an explicit parameter form.
pub fn severity_on(name: &str, level: &Level, seed: u64, frame: u32) -> Severity {
    match *level {
        Level::Severity {
            severity,
            dynamic: false,
        } => severity,
        Level::Severity {
            severity,
            dynamic: true,
        } => dynamic_severity(seed, name, frame, severity),
        Level::Explicit { .. } => Severity::MAX,
    }
}

/// The severity one item received on one frame (0 = the frame was left clean by it; explicit
/// parameter forms report 5).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct ItemSeverity {
    pub name: &'static str,
    pub severity: Severity,
}

/// What one frame received, for the manifest.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct FrameSeverities {
    pub frame: u32,
    pub items: Vec<ItemSeverity>,
}

struct Item {
    name: &'static str,
    state_fields: Option<[&'static str; 4]>,
    level: Level,
    perturbation: Box<dyn GpuPerturbation>,
}

/// Every image and depth corruption of a spec, built once for one frame size and seed.
pub struct Perturber {
    width: u32,
    height: u32,
    seed: u64,
    camera: Option<Intrinsics>,
    scratch: Scratch,
    items: Vec<Item>,
}

impl Perturber {
    /// Builds pipelines and buffers for every image and depth item of `spec` (trajectory and
    /// stream items are not frame operations and are ignored here). `camera` is the camera of
    /// the frames where one is known (`None` for image files); items computed from the geometry
    /// (`depth_sensor`) fail to build without it.
    pub fn new(
        ctx: &GpuContext,
        spec: &PerturbSpec,
        width: u32,
        height: u32,
        seed: u64,
        camera: Option<Intrinsics>,
    ) -> Result<Self, PerturbError> {
        // A rig hands each camera its own spec (`PerturbSpec::for_camera`); whatever else
        // arrives here perturbs one camera.
        if let Some(problem) = spec.one_camera_problem() {
            return Err(problem);
        }
        let scratch = Scratch::new(ctx, width, height);
        let kit = Kit {
            ctx,
            width,
            height,
            scratch: &scratch,
            camera,
        };
        let mut items = Vec::new();
        for item in spec.frame_items() {
            let entry = catalogue::find(&item.name).ok_or_else(|| {
                PerturbError::spec(
                    &item.name,
                    format!("unknown perturbation; valid: {}", catalogue::names()),
                )
            })?;
            items.push(Item {
                name: entry.name,
                state_fields: entry.state_fields(),
                level: item.level.clone(),
                perturbation: (entry.build)(&kit)?,
            });
        }
        ctx.check()?;
        Ok(Self {
            width,
            height,
            seed,
            camera,
            scratch,
            items,
        })
    }

    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// Whether an item carries a state from frame to frame (see
    /// [`crate::CatalogueEntry::carries_state`]): frames must then run in order from the first,
    /// and a resumed run redoes them all.
    pub fn carries_state(&self) -> bool {
        self.items.iter().any(|item| item.state_fields.is_some())
    }

    /// The columns of the per-frame state log, `name.field` for each value of each item that
    /// carries a state, in spec order: one row is [`Perturber::state_row_bytes`] of f32.
    pub fn state_columns(&self) -> Vec<String> {
        self.items
            .iter()
            .filter_map(|item| item.state_fields.map(|fields| (item.name, fields)))
            .flat_map(|(name, fields)| fields.map(|field| format!("{name}.{field}")))
            .collect()
    }

    pub fn state_row_bytes(&self) -> u64 {
        self.state_columns().len() as u64 * 4
    }

    /// Records a copy of the state each stateful item made frame `got` with into `log` at byte
    /// `offset` (one row of [`Perturber::state_columns`]); an item that did not run on the
    /// frame (severity 0) leaves its cells as they were.
    pub fn encode_state_copy(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        got: &FrameSeverities,
        log: &wgpu::Buffer,
        offset: u64,
    ) {
        let mut at = offset;
        for (item, severity) in self.items.iter().zip(&got.items) {
            if item.state_fields.is_none() {
                continue;
            }
            if let (Some(state), true) = (item.perturbation.state(), !severity.severity.is_clean())
            {
                encoder.copy_buffer_to_buffer(state, 0, log, at, Some(16));
            }
            at += 16;
        }
    }

    /// Takes the levels and seed of `spec` when it has this perturber's frame items in the same
    /// order (a severity, mode or seed change: nothing is rebuilt) and says whether it could;
    /// `false` leaves it unchanged, and a new [`Perturber`] is needed.
    pub fn set_levels(&mut self, spec: &PerturbSpec, seed: u64) -> bool {
        // A spec this one camera cannot take goes to `Perturber::new`, which says why.
        let same_items = spec.one_camera_problem().is_none()
            && spec.frame_items().count() == self.items.len()
            && spec
                .frame_items()
                .zip(&self.items)
                .all(|(wanted, item)| wanted.name == item.name);
        if !same_items {
            return false;
        }
        for (wanted, item) in spec.frame_items().zip(&mut self.items) {
            item.level = wanted.level.clone();
        }
        self.seed = seed;
        true
    }

    /// The severity every item gets on `frame` (pure: no GPU work).
    pub fn severities(&self, frame: u32) -> FrameSeverities {
        let items = self
            .items
            .iter()
            .map(|item| ItemSeverity {
                name: item.name,
                severity: severity_on(item.name, &item.level, self.seed, frame),
            })
            .collect();
        FrameSeverities { frame, items }
    }

    /// Records every item's passes for frame `frame_index` into `encoder` (image items, then
    /// depth items, in spec order), skipping items whose severity on this frame is 0.
    pub fn encode(
        &mut self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        frame_index: u32,
    ) -> Result<FrameSeverities, PerturbError> {
        if (frame.width, frame.height) != (self.width, self.height) {
            return Err(PerturbError::Unsupported {
                name: "perturber".into(),
                message: format!(
                    "built for {}x{} frames, given {}x{}",
                    self.width, self.height, frame.width, frame.height
                ),
            });
        }
        let severities = self.severities(frame_index);
        let kit = Kit {
            ctx,
            width: self.width,
            height: self.height,
            scratch: &self.scratch,
            camera: self.camera,
        };
        for (item, got) in self.items.iter_mut().zip(&severities.items) {
            if got.severity.is_clean() {
                continue;
            }
            let explicit = match &item.level {
                Level::Explicit { values } => Some(values.as_slice()),
                Level::Severity { .. } => None,
            };
            let key = FrameKey {
                seed: self.seed,
                frame: frame_index,
                severity: got.severity,
                explicit,
                camera: self.camera,
            };
            item.perturbation.encode(&kit, encoder, frame, &key)?;
        }
        Ok(severities)
    }
}

#[cfg(test)]
mod tests {
    use rslam_gpu::FrameReadback;

    use super::*;
    use crate::image::brightness;
    use crate::image_f32::RgbF32;
    use crate::testing;

    #[test]
    fn dynamic_severities_are_uniform_over_zero_to_max() {
        let frames = 6000u32;
        let mut histogram = [0u32; 6];
        let whole = |s: u8| Severity::whole(s).unwrap();
        for frame in 0..frames {
            histogram[dynamic_severity(4, "fog", frame, whole(5)).floor() as usize] += 1;
        }
        let p = 1.0 / 6.0;
        let expected = frames as f64 * p;
        let tol = 5.0 * (frames as f64 * p * (1.0 - p)).sqrt();
        for (s, &n) in histogram.iter().enumerate() {
            assert!(
                (n as f64 - expected).abs() < tol,
                "severity {s}: {histogram:?}"
            );
        }
        assert!((0..100).all(|f| dynamic_severity(4, "fog", f, whole(2)) <= whole(2)));
    }

    /// A real maximum draws real severities, uniform over [0, max]: the mean is max/2 and the
    /// draws spread over the whole interval, not onto the whole severities.
    #[test]
    fn dynamic_real_severities_are_uniform_over_the_interval() {
        let max = Severity::parse("2.5").unwrap();
        let draws: Vec<f64> = (0..6000)
            .map(|f| dynamic_severity(4, "fog", f, max).value())
            .collect();
        assert!(draws.iter().all(|&s| (0.0..=2.5).contains(&s)));
        let mean = draws.iter().sum::<f64>() / draws.len() as f64;
        // σ of the mean of a uniform over [0, 2.5]: 2.5 / √12 / √6000 ≈ 0.0093.
        assert!((mean - 1.25).abs() < 0.05, "{mean}");
        let below = |x: f64| draws.iter().filter(|&&s| s < x).count() as f64 / 6000.0;
        for quarter in [0.625, 1.25, 1.875] {
            assert!((below(quarter) - quarter / 2.5).abs() < 0.03, "{quarter}");
        }
        assert!(draws.iter().filter(|s| s.fract() != 0.0).count() > 5000);
    }

    /// Frames run through the perturber get what `severities` reports: a clean image on
    /// severity 0, the corruption at the drawn severity otherwise, depth items after image items.
    #[test]
    fn encode_applies_the_reported_severities_in_order() {
        let ctx = testing::context();
        let (w, h) = (64, 48);
        let spec = PerturbSpec::parse("brightness:5@dynamic,depth_range:0.42-3").unwrap();
        let mut perturber = Perturber::new(ctx, &spec, w, h, 9, None).unwrap();
        let clean = testing::test_image(w, h);
        let depth = testing::test_depth(w, h);
        let frame = FrameTextures::new(ctx, w, h);
        let readback = FrameReadback::new(ctx, w, h, true);
        let mut seen = [false; 6];
        for index in 0..40 {
            frame.upload(ctx, &clean, Some(&depth));
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            let got = perturber.encode(ctx, &mut encoder, &frame, index).unwrap();
            readback.encode_copy(&mut encoder, &frame);
            let (color, out_depth) = readback
                .read(ctx, ctx.queue.submit([encoder.finish()]))
                .unwrap();
            let out_depth = out_depth.expect("depth was asked for");
            assert_eq!(got, perturber.severities(index));
            let severity = got.items[0].severity;
            assert_eq!(
                got.items[1],
                ItemSeverity {
                    name: "depth_range",
                    severity: Severity::MAX
                }
            );
            seen[severity.floor() as usize] = true;
            let expected = match severity.floor() {
                0 => clean.clone(),
                s => brightness::twin(&RgbF32::from_rgb8(&clean), &testing::key(0, s)).to_rgb8(),
            };
            testing::assert_close(&color, &expected, 1, &format!("perturber-frame{index}"));
            assert!(out_depth
                .data
                .iter()
                .all(|&z| z == 0.0 || (0.42..=3.0).contains(&z)));
        }
        assert!(
            seen.iter().all(|&s| s),
            "40 frames drew every severity: {seen:?}"
        );
    }

    /// A new severity through `set_levels` gives what a perturber built for it gives; another
    /// list of items is refused.
    #[test]
    fn set_levels_matches_a_rebuilt_perturber() {
        let ctx = testing::context();
        let (w, h) = (32, 24);
        let run = |perturber: &mut Perturber| {
            let frame = FrameTextures::new(ctx, w, h);
            frame.upload(
                ctx,
                &testing::test_image(w, h),
                Some(&testing::test_depth(w, h)),
            );
            let readback = FrameReadback::new(ctx, w, h, false);
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            perturber.encode(ctx, &mut encoder, &frame, 3).unwrap();
            readback.encode_copy(&mut encoder, &frame);
            readback
                .read(ctx, ctx.queue.submit([encoder.finish()]))
                .unwrap()
                .0
        };
        let two = PerturbSpec::parse("brightness:2").unwrap();
        let five = PerturbSpec::parse("brightness:5").unwrap();
        let mut relevelled = Perturber::new(ctx, &two, w, h, 1, None).unwrap();
        assert!(relevelled.set_levels(&five, 1));
        let mut built = Perturber::new(ctx, &five, w, h, 1, None).unwrap();
        assert_eq!(run(&mut relevelled), run(&mut built));
        let other = PerturbSpec::parse("contrast:5").unwrap();
        assert!(!relevelled.set_levels(&other, 1));
        assert_eq!(relevelled.severities(0).items[0].name, "brightness");
        // The same item for another sensor is no new level for this one camera.
        let cam1 = PerturbSpec::parse("cam1:brightness:5").unwrap();
        assert!(!relevelled.set_levels(&cam1, 1));
        let err = Perturber::new(ctx, &cam1, w, h, 1, None)
            .err()
            .unwrap()
            .to_string();
        assert!(err.contains("this input has one camera, cam0"), "{err}");
        let cam0 = PerturbSpec::parse("cam0:brightness:5").unwrap();
        assert!(relevelled.set_levels(&cam0, 1));
        assert_eq!(run(&mut relevelled), run(&mut built));
    }

    /// Severity 0 is the clean frame, bytes for bytes, for image and depth items alike.
    #[test]
    fn severity_zero_leaves_the_frame_clean() {
        let ctx = testing::context();
        let (w, h) = (40, 30);
        let spec = PerturbSpec::parse("fog:0,gaussian_noise:0,depth_noise:0").unwrap();
        let mut perturber = Perturber::new(ctx, &spec, w, h, 3, None).unwrap();
        let (clean, depth) = (testing::test_image(w, h), testing::test_depth(w, h));
        let frame = FrameTextures::new(ctx, w, h);
        frame.upload(ctx, &clean, Some(&depth));
        let readback = FrameReadback::new(ctx, w, h, true);
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        let got = perturber.encode(ctx, &mut encoder, &frame, 0).unwrap();
        readback.encode_copy(&mut encoder, &frame);
        let (color, out_depth) = readback
            .read(ctx, ctx.queue.submit([encoder.finish()]))
            .unwrap();
        assert!(got.items.iter().all(|item| item.severity.is_clean()));
        assert!(color == clean);
        assert!(out_depth.unwrap() == depth);
    }

    #[test]
    fn wrong_frame_size_is_an_error() {
        let ctx = testing::context();
        let spec = PerturbSpec::parse("contrast:1").unwrap();
        let mut perturber = Perturber::new(ctx, &spec, 32, 32, 0, None).unwrap();
        let frame = FrameTextures::new(ctx, 40, 32);
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        let e = perturber
            .encode(ctx, &mut encoder, &frame, 0)
            .unwrap_err()
            .to_string();
        assert!(e.contains("32x32") && e.contains("40x32"), "{e}");
    }
}
