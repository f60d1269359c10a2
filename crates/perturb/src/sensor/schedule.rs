//! Which renders make one frame under a shutter: the sub-frames of an exposure within each band
//! of rows of a rolling shutter, each from the pose the camera had at that instant (the path
//! interpolated on SE(3)), with its weight in the linear-light sum and the interval of time whose
//! light it shows (for the light items).

use std::ops::Range;

use rslam_core::se3::pose_along;
use rslam_core::{Intrinsics, Pose};

use super::exposure::Exposure;
use super::pixel_motion::max_pixel_motion;
use super::rolling_shutter::{Band, RollingShutter};
use crate::PerturbSpec;

/// The most renders one frame may take; an automatic sub-frame count is lowered to fit the
/// rolling shutter's bands.
pub const MAX_RENDERS: u32 = 256;

/// A spec's sensor items: how light is collected over the time a frame is captured.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Shutter {
    pub exposure: Option<Exposure>,
    pub rolling: Option<RollingShutter>,
    /// The lamps' flicker (`flicker:HZ`): a rolling shutter reads rows in bands of at most an
    /// eighth of its period, so that the bands it makes show.
    pub flicker_hz: Option<f64>,
}

/// Bands of a rolling shutter per flicker period.
const BANDS_PER_FLICKER_PERIOD: f64 = 8.0;

/// The camera path the frames are taken along: `poses[i]` at time i / `rate_hz`.
#[derive(Clone, Copy, Debug)]
pub struct CameraPath<'a> {
    pub poses: &'a [Pose],
    pub rate_hz: f64,
    pub camera: Intrinsics,
}

/// One render of a frame under a shutter.
#[derive(Clone, Debug, PartialEq)]
pub struct SubRender {
    pub world_from_camera: Pose,
    /// The rows it contributes.
    pub rows: Range<u32>,
    /// Its weight in the rows' linear-light sum; 0 for a render that gives depth only.
    pub weight: f32,
    /// The first weighted render of its rows: it starts their sum.
    pub starts_sum: bool,
    /// Its depth (and instance mask) is the frame's in `rows` (the render at the rows' read-out
    /// instant).
    pub depth: bool,
    /// The time it exposes, in seconds from the frame's timestamp (equal ends: one instant).
    pub light_window: (f64, f64),
}

impl Shutter {
    pub fn of(spec: &PerturbSpec) -> Self {
        Self {
            exposure: spec.exposure,
            rolling: spec.rolling_shutter,
            flicker_hz: spec.light.flicker.map(|f| f.hz),
        }
    }

    /// The time a frame exposes, in seconds from its timestamp: the exposure around it, or the
    /// instant itself.
    pub fn window(&self) -> (f64, f64) {
        let half = self.exposure.map_or(0.0, |e| e.seconds() / 2.0);
        (-half, half)
    }

    pub fn is_none(&self) -> bool {
        self.exposure.is_none() && self.rolling.is_none()
    }

    /// The renders of frame `index` of `path`, rows top to bottom; empty where one render at the
    /// frame's own pose is the frame (no shutter, a zero time, or a camera at rest).
    pub fn schedule(&self, path: &CameraPath, index: usize) -> Vec<SubRender> {
        let pose_at = |t: f64| pose_along(path.poses, index as f64 + t * path.rate_hz);
        let motion_over = |seconds: f64| {
            max_pixel_motion(
                &path.camera,
                &pose_at(-seconds / 2.0),
                &pose_at(seconds / 2.0),
            )
        };
        let height = path.camera.height;
        let bands = match self.rolling {
            Some(rolling) => {
                let read_out = rolling.ms / 1000.0;
                let flicker = self.flicker_hz.map_or(0.0, |hz| {
                    read_out * hz * BANDS_PER_FLICKER_PERIOD * super::rolling_shutter::STEP_PX
                });
                rolling.bands(motion_over(read_out).max(flicker), height)
            }
            None => vec![Band {
                rows: 0..height,
                offset: 0.0,
            }],
        };
        let offsets = match self.exposure {
            Some(exposure) => {
                let mut k = exposure.subframes_for(motion_over(exposure.seconds()));
                if exposure.subframes.is_none() {
                    k = k.min((MAX_RENDERS / bands.len() as u32).max(1));
                }
                exposure.offsets(k)
            }
            None => vec![0.0],
        };
        if bands.len() == 1 && offsets == [0.0] {
            return Vec::new();
        }
        let k = offsets.len();
        let span = self.exposure.map_or(0.0, |e| e.seconds() / k as f64);
        // With an odd count the middle sub-frame is at the band's instant and gives its depth.
        let middle = (k % 2 == 1).then_some(k / 2);
        let mut renders = Vec::with_capacity(bands.len() * (k + 1));
        for band in &bands {
            if middle.is_none() {
                renders.push(SubRender {
                    world_from_camera: pose_at(band.offset),
                    rows: band.rows.clone(),
                    weight: 0.0,
                    starts_sum: false,
                    depth: true,
                    light_window: (band.offset, band.offset),
                });
            }
            renders.extend(offsets.iter().enumerate().map(|(j, offset)| SubRender {
                world_from_camera: pose_at(band.offset + offset),
                rows: band.rows.clone(),
                weight: 1.0 / k as f32,
                starts_sum: j == 0,
                depth: middle == Some(j),
                light_window: (
                    band.offset + offset - span / 2.0,
                    band.offset + offset + span / 2.0,
                ),
            }));
        }
        renders
    }
}

#[cfg(test)]
mod tests {
    use glam::{DQuat, DVec3};

    use super::*;

    const CAMERA: Intrinsics = Intrinsics {
        width: 64,
        height: 48,
        fx: 40.0,
        fy: 40.0,
        cx: 31.5,
        cy: 23.5,
    };

    /// 1 m/s sideways at 10 Hz.
    fn sideways() -> Vec<Pose> {
        (0..5)
            .map(|i| Pose::new(DQuat::IDENTITY, DVec3::new(0.1 * i as f64, 0.0, 0.0)))
            .collect()
    }

    fn path(poses: &[Pose]) -> CameraPath<'_> {
        CameraPath {
            poses,
            rate_hz: 10.0,
            camera: CAMERA,
        }
    }

    fn shutter(spec: &str) -> Shutter {
        Shutter::of(&PerturbSpec::parse(spec).unwrap())
    }

    #[test]
    fn exposure_spreads_subframes_over_the_motion_with_weights_summing_to_one() {
        let poses = sideways();
        let renders = shutter("exposure:20@4").schedule(&path(&poses), 2);
        // K even: one depth render at the timestamp, then four weighted sub-frames.
        assert_eq!(renders.len(), 5);
        assert!(renders[0].depth && renders[0].weight == 0.0);
        assert!((renders[0].world_from_camera.translation.x - 0.2).abs() < 1e-12);
        let xs: Vec<f64> = renders[1..]
            .iter()
            .map(|r| r.world_from_camera.translation.x)
            .collect();
        for (x, want) in xs.iter().zip([0.1925, 0.1975, 0.2025, 0.2075]) {
            assert!((x - want).abs() < 1e-12, "{xs:?}");
        }
        let total: f32 = renders.iter().map(|r| r.weight).sum();
        assert!((total - 1.0).abs() < 1e-6);
        assert!(renders[1].starts_sum && !renders[2].starts_sum);
        // Automatic K: 20 mm of travel at f = 40 seen at 0.5 m is 1.6 px: 2 sub-frames.
        assert_eq!(shutter("exposure:20").schedule(&path(&poses), 2).len(), 3);
    }

    #[test]
    fn nothing_to_do_without_time_or_motion() {
        let poses = sideways();
        assert!(shutter("exposure:0").schedule(&path(&poses), 1).is_empty());
        assert!(shutter("rolling_shutter:0")
            .schedule(&path(&poses), 1)
            .is_empty());
        let still = vec![Pose::IDENTITY; 3];
        assert!(shutter("exposure:30,rolling_shutter:30")
            .schedule(&path(&still), 1)
            .is_empty());
    }

    #[test]
    fn rolling_shutter_renders_each_band_at_its_read_out_time() {
        let poses = sideways();
        // 100 ms read-out: 0.1 m of travel, 8 px at 0.5 m → 16 bands of 3 rows.
        let renders = shutter("rolling_shutter:100").schedule(&path(&poses), 2);
        assert_eq!(renders.len(), 16);
        assert!(renders
            .iter()
            .all(|r| r.depth && r.weight == 1.0 && r.starts_sum));
        let first = &renders[0];
        assert_eq!(first.rows, 0..3);
        // Row 1 (the band's middle) is read (1.5/48 − 0.5)·0.1 s before the timestamp.
        let want = 0.2 + (1.5 / 48.0 - 0.5) * 0.1;
        assert!((first.world_from_camera.translation.x - want).abs() < 1e-12);
    }
}
