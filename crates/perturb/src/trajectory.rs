//! Trajectory deviations (docs/src/perturbations.md §5): `rot:D` and `trans:M`, applied before rendering;
//! the deviated path is the new ground truth.
//!
//! i.i.d. (the benchmark's): each pose independently, R' = R·Rx(αx)·Ry(αy)·Rz(αz) with
//! α ~ N(0, D°) per axis, and t' = t + Δt with Δt ~ N(0, M) per world axis.
//! `@smooth` (hand-held shake): per axis a band-limited signal, the sum of [`SMOOTH_TONES`]
//! sinusoids with frequencies uniform in [`SMOOTH_BAND_HZ`] and random phases, scaled so that its
//! standard deviation is the same σ. It is a function of the timestamp alone, so a frame's
//! deviation does not depend on which other frames were rendered.

use glam::{DQuat, DVec3};
use rslam_core::{Pose, Trajectory};

use crate::applies::{ItemEntry, Need};
use crate::rng::RngKey;
use crate::spec::{Deviation, PerturbSpec};

/// Sinusoids per axis of a smooth deviation.
pub const SMOOTH_TONES: u32 = 8;
/// Frequency band of a smooth deviation: hand tremor and walking sway.
pub const SMOOTH_BAND_HZ: (f64, f64) = (0.3, 3.0);

pub static TRAJECTORY_ITEMS: &[ItemEntry] = &[
    ItemEntry {
        name: "rot",
        syntax: "rot:DEGREES[@smooth]",
        description: "R' = R·Rx·Ry·Rz, per-axis angles ~ N(0, D°), each pose independently (benchmark: 1, 3, 5); @smooth: temporally correlated instead, per axis a sum of 8 sinusoids with frequencies uniform in 0.3-3 Hz and random phases, same marginal σ",
        needs: &[Need::Scene],
    },
    ItemEntry {
        name: "trans",
        syntax: "trans:METRES[@smooth]",
        description: "t' = t + Δt, Δt ~ N(0, M) per world axis, each pose independently (benchmark: 0.0125, 0.025, 0.05); @smooth: temporally correlated instead, per axis a sum of 8 sinusoids with frequencies uniform in 0.3-3 Hz and random phases, same marginal σ",
        needs: &[Need::Scene],
    },
];

const PURPOSE_IID: u32 = 1;
const PURPOSE_TONE: u32 = 2;

/// One per-axis deviation sample for pose `index` at `time` (in units of σ·`deviation.sigma`).
fn axis_values(name: &str, deviation: &Deviation, seed: u64, index: usize, time: f64) -> DVec3 {
    let sigma = deviation.sigma;
    if !deviation.smooth {
        let key = RngKey::new(seed, name, index as u32, PURPOSE_IID);
        return DVec3::from_array(std::array::from_fn(|axis| {
            sigma * key.normal_f64([axis as u32, 0, 0, 0])
        }));
    }
    let amplitude = sigma * (2.0 / SMOOTH_TONES as f64).sqrt();
    DVec3::from_array(std::array::from_fn(|axis| {
        (0..SMOOTH_TONES)
            .map(|tone| {
                // Frame 0 of the key: the tones are fixed for the whole sequence.
                let key = RngKey::new(seed, name, 0, PURPOSE_TONE);
                let f = SMOOTH_BAND_HZ.0
                    + (SMOOTH_BAND_HZ.1 - SMOOTH_BAND_HZ.0)
                        * key.uniform_f64([axis as u32, tone, 0, 0]);
                let phase = std::f64::consts::TAU * key.uniform_f64([axis as u32, tone, 1, 0]);
                amplitude * (std::f64::consts::TAU * f * time + phase).sin()
            })
            .sum()
    }))
}

/// The deviated trajectory; without `rot` or `trans` in the spec, a copy of `clean`.
pub fn deviate(clean: &Trajectory, spec: &PerturbSpec, seed: u64) -> Trajectory {
    let poses = clean
        .poses
        .iter()
        .zip(&clean.timestamps)
        .enumerate()
        .map(|(i, (pose, &time))| {
            let mut out = *pose;
            if let Some(rot) = &spec.rotation {
                let a = axis_values("rot", rot, seed, i, time) * std::f64::consts::PI / 180.0;
                let delta = DQuat::from_rotation_x(a.x)
                    * DQuat::from_rotation_y(a.y)
                    * DQuat::from_rotation_z(a.z);
                out = Pose::new(pose.rotation * delta, out.translation);
            }
            if let Some(trans) = &spec.translation {
                out.translation += axis_values("trans", trans, seed, i, time);
            }
            out
        })
        .collect();
    Trajectory::new(clean.timestamps.clone(), poses)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_listed_descriptions_state_the_smooth_band_in_use() {
        let smooth = format!(
            "a sum of {SMOOTH_TONES} sinusoids with frequencies uniform in {}-{} Hz",
            SMOOTH_BAND_HZ.0, SMOOTH_BAND_HZ.1
        );
        for entry in TRAJECTORY_ITEMS {
            assert!(entry.description.contains(&smooth), "{}", entry.name);
        }
    }

    /// Sample std over 2000 poses must be within this fraction of σ (issue 4).
    const SIGMA_TOLERANCE: f64 = 0.10;

    fn straight_line(n: usize) -> Trajectory {
        let poses = (0..n)
            .map(|i| {
                Pose::new(
                    DQuat::from_rotation_z(0.01 * i as f64),
                    DVec3::new(0.02 * i as f64, 0.0, 1.5),
                )
            })
            .collect();
        Trajectory::from_poses_at_rate(poses, 20.0)
    }

    fn std(values: &[f64]) -> f64 {
        let mean = values.iter().sum::<f64>() / values.len() as f64;
        (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / values.len() as f64).sqrt()
    }

    /// Per-axis angles (degrees) of R⁻¹R' = Rx·Ry·Rz, and per-axis offsets.
    fn deviations(clean: &Trajectory, moved: &Trajectory) -> ([Vec<f64>; 3], [Vec<f64>; 3]) {
        let mut angles: [Vec<f64>; 3] = Default::default();
        let mut offsets: [Vec<f64>; 3] = Default::default();
        for (c, m) in clean.poses.iter().zip(&moved.poses) {
            let delta = c.rotation.inverse() * m.rotation;
            let (x, y, z) = delta.to_euler(glam::EulerRot::XYZ);
            for (axis, v) in [x, y, z].into_iter().enumerate() {
                angles[axis].push(v.to_degrees());
                offsets[axis].push((m.translation - c.translation)[axis]);
            }
        }
        (angles, offsets)
    }

    fn assert_sigma(values: &[f64], sigma: f64, what: &str) {
        let s = std(values);
        assert!(
            (s - sigma).abs() < SIGMA_TOLERANCE * sigma,
            "{what}: sample std {s} vs σ {sigma}"
        );
    }

    #[test]
    fn iid_and_smooth_deviations_have_the_requested_sigma_per_axis() {
        let clean = straight_line(2000);
        for mode in ["", "@smooth"] {
            let spec = PerturbSpec::parse(&format!("rot:3{mode},trans:0.025{mode}")).unwrap();
            let moved = deviate(&clean, &spec, 42);
            let (angles, offsets) = deviations(&clean, &moved);
            for axis in 0..3 {
                assert_sigma(&angles[axis], 3.0, &format!("rot{mode} axis {axis}"));
                assert_sigma(&offsets[axis], 0.025, &format!("trans{mode} axis {axis}"));
            }
        }
    }

    #[test]
    fn smooth_deviation_is_temporally_correlated_and_iid_is_not() {
        let clean = straight_line(2000);
        let lag1 = |spec: &str| {
            let (_, offsets) = deviations(
                &clean,
                &deviate(&clean, &PerturbSpec::parse(spec).unwrap(), 1),
            );
            let x = &offsets[0];
            let mean = x.iter().sum::<f64>() / x.len() as f64;
            let var: f64 = x.iter().map(|v| (v - mean).powi(2)).sum();
            x.windows(2)
                .map(|w| (w[0] - mean) * (w[1] - mean))
                .sum::<f64>()
                / var
        };
        assert!(lag1("trans:0.05@smooth") > 0.8);
        assert!(lag1("trans:0.05").abs() < 0.1);
    }

    #[test]
    fn deviation_is_deterministic_per_seed_and_absent_without_items() {
        let clean = straight_line(50);
        let spec = PerturbSpec::parse("rot:1,trans:0.0125").unwrap();
        assert_eq!(deviate(&clean, &spec, 5), deviate(&clean, &spec, 5));
        assert_ne!(deviate(&clean, &spec, 5), deviate(&clean, &spec, 6));
        assert_eq!(
            deviate(&clean, &PerturbSpec::parse("brightness:3").unwrap(), 5),
            clean
        );
    }
}
