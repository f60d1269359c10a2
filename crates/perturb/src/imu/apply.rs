//! An [`ImuSpec`] applied to an IMU stream and its ground truth, in the physical order: the
//! sensor's noise and bias step, its range, the samples lost in transport, the stamping clock.

use rslam_core::dataset::euroc::{GroundTruthState, ImuSample};
use rslam_core::imu::{ImuBias, ImuNoise};
use serde::Serialize;

use super::added_noise::{add_noise, added_noise, AddedNoise};
use super::bias_step::BiasStep;
use super::items::{ImuSpec, NOISE};
use super::jitter::{jitter, Jittered};
use super::sample_drop::{kept, Dropped};
use super::saturation::{saturate, Saturated};
use crate::PerturbError;

/// Where the readings come from, which decides what `imu_noise:K` does.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ImuOrigin {
    /// Synthesised with the scaled noise already ([`ImuSpec::synthesis_noise`]): nothing to add.
    Synthesised,
    /// Recorded by a sensor of this noise (imu0/sensor.yaml): `K² − 1` times its variances are
    /// added.
    Recorded(ImuNoise),
}

/// An IMU stream: its samples, time-ordered, at `rate_hz`, and the ground-truth states whose
/// biases are the samples' true ones.
pub struct ImuStream<'a> {
    pub samples: &'a [ImuSample],
    pub ground_truth: &'a [GroundTruthState],
    pub rate_hz: f64,
    pub origin: ImuOrigin,
}

/// What was drawn and done, for the manifest.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct ImuReport {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub noise_added: Option<AddedNoise>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bias_step: Option<BiasStep>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub saturated: Option<Saturated>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dropped: Option<Dropped>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub jitter: Option<Jittered>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cam_imu_offset_ns: Option<i64>,
}

/// The stream after the spec.
#[derive(Clone, Debug, PartialEq)]
pub struct PerturbedImu {
    pub samples: Vec<ImuSample>,
    pub ground_truth: Vec<GroundTruthState>,
    /// Whether the samples changed (any IMU item but `cam_imu_offset`).
    pub samples_changed: bool,
    /// Whether the ground truth's biases changed (a bias step, or a bias walk added).
    pub ground_truth_changed: bool,
    pub report: ImuReport,
}

impl ImuSpec {
    /// The noise to synthesise an IMU of nominal noise `nominal` with: scaled by `imu_noise:K`.
    pub fn synthesis_noise(&self, nominal: ImuNoise) -> ImuNoise {
        let k = self.noise_scale.unwrap_or(1.0);
        ImuNoise {
            gyroscope_noise_density: nominal.gyroscope_noise_density * k,
            gyroscope_random_walk: nominal.gyroscope_random_walk * k,
            accelerometer_noise_density: nominal.accelerometer_noise_density * k,
            accelerometer_random_walk: nominal.accelerometer_random_walk * k,
        }
    }

    /// `cam_imu_offset` in whole nanoseconds.
    pub fn cam_imu_offset_ns(&self) -> Option<i64> {
        self.cam_imu_offset_ms.map(|ms| (ms * 1e6).round() as i64)
    }

    /// The items that change the IMU stream (all but `cam_imu_offset`).
    pub fn changes_imu(&self) -> bool {
        Self {
            cam_imu_offset_ms: None,
            ..*self
        } != Self::default()
    }

    /// Applies the spec to `stream`; draws keyed by `seed`.
    pub fn apply(&self, stream: &ImuStream, seed: u64) -> Result<PerturbedImu, PerturbError> {
        let mut samples = stream.samples.to_vec();
        let mut ground_truth = stream.ground_truth.to_vec();
        let mut report = ImuReport {
            cam_imu_offset_ns: self.cam_imu_offset_ns(),
            ..ImuReport::default()
        };
        // The bias each sample gained, for the ground truth.
        let mut gained = vec![ImuBias::default(); samples.len()];
        if let (Some(k), ImuOrigin::Recorded(nominal)) = (self.noise_scale, stream.origin) {
            let noise = added_noise(nominal, k).ok_or_else(|| PerturbError::Stream {
                operation: format!("{NOISE}:{k}"),
                message: "recorded readings hold their sensor's noise already; only a scale K ≥ 1 can be added".into(),
            })?;
            gained = add_noise(&mut samples, noise, stream.rate_hz, seed).map_err(|e| {
                PerturbError::Stream {
                    operation: format!("{NOISE}:{k}"),
                    message: e.to_string(),
                }
            })?;
            report.noise_added = Some(noise.into());
        }
        if let (Some(size), Some(first), Some(last)) =
            (self.bias_step, samples.first(), samples.last())
        {
            let step = BiasStep::draw(size, first.t_ns, last.t_ns, seed);
            for (s, gain) in samples.iter_mut().zip(&mut gained) {
                let (g, a) = step.at(s.t_ns);
                s.gyro += g;
                s.accel += a;
                gain.gyroscope += g;
                gain.accelerometer += a;
            }
            report.bias_step = Some(step);
        }
        let ground_truth_changed = report.noise_added.is_some() || report.bias_step.is_some();
        if ground_truth_changed {
            add_gains(&mut ground_truth, &samples, &gained);
        }
        if let Some(range) = self.saturation {
            report.saturated = Some(saturate(&mut samples, range));
        }
        if let Some(drop) = self.drop {
            let (keep, dropped) = kept(samples.len(), drop, seed);
            let mut keep = keep.into_iter();
            samples.retain(|_| keep.next().unwrap_or(true));
            report.dropped = Some(dropped);
        }
        if let Some(ms) = self.jitter_ms {
            let times: Vec<u64> = samples.iter().map(|s| s.t_ns).collect();
            let (moved, jittered) = jitter(&times, ms, seed);
            for (s, t) in samples.iter_mut().zip(moved) {
                s.t_ns = t;
            }
            report.jitter = Some(jittered);
        }
        Ok(PerturbedImu {
            samples,
            ground_truth,
            samples_changed: self.changes_imu(),
            ground_truth_changed,
            report,
        })
    }
}

/// Adds to each state's biases what the last sample stamped at or before it gained (nothing
/// before the first sample). `samples` are still at their own stamps, time-ordered.
fn add_gains(states: &mut [GroundTruthState], samples: &[ImuSample], gained: &[ImuBias]) {
    for state in states {
        let after = samples.partition_point(|s| s.t_ns <= state.t_ns);
        let gain = after
            .checked_sub(1)
            .map_or(ImuBias::default(), |i| gained[i]);
        state.gyro_bias += gain.gyroscope;
        state.accel_bias += gain.accelerometer;
    }
}

/// A camera stamp moved by `offset_ns`, or `None` when it would fall below 0 or past u64.
pub fn shift_stamp(t_ns: u64, offset_ns: i64) -> Option<u64> {
    t_ns.checked_add_signed(offset_ns)
}

#[cfg(test)]
#[path = "apply_tests.rs"]
mod tests;
