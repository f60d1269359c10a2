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
    /// Per sample, the index of the input sample it is (the others were dropped).
    pub input_index: Vec<usize>,
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
        let mut input_index: Vec<usize> = (0..samples.len()).collect();
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
            let (samples_kept, index_kept) = samples
                .iter()
                .zip(&input_index)
                .zip(keep)
                .filter(|(_, keep)| *keep)
                .map(|((s, &i), _)| (*s, i))
                .unzip();
            (samples, input_index) = (samples_kept, index_kept);
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
            input_index,
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
mod tests {
    //! The IMU items on streams made here: a still, noisy recording (statistics of `imu_noise`), a
    //! stream with ground truth at its own stamps as EuRoC's (the bias step in both), drops and
    //! jitter together.

    use glam::DVec3;
    use rslam_core::dataset::euroc::{GroundTruthState, ImuSample};
    use rslam_core::imu::allan::{allan_variance, fit_white_and_walk};
    use rslam_core::imu::{ImuBias, ImuNoise, ImuReading, NoisyImu, GRAVITY_WORLD};
    use rslam_core::Pose;

    use super::*;
    use crate::PerturbSpec;

    const RATE_HZ: f64 = 200.0;
    const PERIOD_NS: u64 = 5_000_000;
    const START_NS: u64 = 1_403_636_579_758_555_392;
    const NOMINAL: ImuNoise = ImuNoise::ADIS16448_EUROC;

    fn imu_spec(text: &str) -> ImuSpec {
        PerturbSpec::parse(text).unwrap().imu
    }

    /// `n` samples of a still IMU recorded with the nominal noise, seeded by `seed`.
    fn still_recording(n: usize, seed: u64) -> Vec<ImuSample> {
        let truth = ImuReading {
            gyroscope: DVec3::ZERO,
            accelerometer: -GRAVITY_WORLD,
        };
        let mut imu = NoisyImu::new(NOMINAL, RATE_HZ, seed, ImuBias::default()).unwrap();
        (0..n as u64)
            .map(|k| {
                let s = imu.measure(k as f64 / RATE_HZ, truth);
                ImuSample {
                    t_ns: START_NS + k * PERIOD_NS,
                    gyro: s.measured.gyroscope,
                    accel: s.measured.accelerometer,
                }
            })
            .collect()
    }

    /// Ground-truth states between the samples' stamps (as EuRoC's, from another clock tick), with
    /// biases that differ per state.
    fn ground_truth(n: usize) -> Vec<GroundTruthState> {
        (0..n as u64)
            .map(|k| GroundTruthState {
                t_ns: START_NS + k * PERIOD_NS + 1_234,
                world_from_body: Pose::IDENTITY,
                velocity: DVec3::ZERO,
                gyro_bias: DVec3::splat(k as f64 * 1e-6),
                accel_bias: DVec3::splat(-(k as f64) * 1e-5),
            })
            .collect()
    }

    fn recorded<'a>(samples: &'a [ImuSample], gt: &'a [GroundTruthState]) -> ImuStream<'a> {
        ImuStream {
            samples,
            ground_truth: gt,
            rate_hz: RATE_HZ,
            origin: ImuOrigin::Recorded(NOMINAL),
        }
    }

    /// Per axis, the running integral of the readings' error, binned by `bin` samples (the phase
    /// data [`allan_variance`] takes).
    fn phase(
        samples: &[ImuSample],
        bin: usize,
        reading: impl Fn(&ImuSample) -> DVec3,
    ) -> [Vec<f64>; 3] {
        let truth = reading(&ImuSample {
            t_ns: 0,
            gyro: DVec3::ZERO,
            accel: -GRAVITY_WORLD,
        });
        std::array::from_fn(|axis| {
            let mut x = vec![0.0];
            for chunk in samples.chunks_exact(bin) {
                let sum: f64 = chunk.iter().map(|s| (reading(s) - truth)[axis]).sum();
                x.push(x[x.len() - 1] + sum / RATE_HZ);
            }
            x
        })
    }

    fn allan_deviation(x: &[Vec<f64>; 3], m: usize, bin_s: f64) -> f64 {
        (x.iter().map(|x| allan_variance(x, m, bin_s)).sum::<f64>() / 3.0).sqrt()
    }

    /// Recorded readings under `imu_noise:K`: the white noise's std (from first differences, which
    /// the slow walk does not reach) and the Allan deviation from 0.1 s to 10 s grow by K, and the
    /// accelerometer's fitted N and K are K× the nominal ones. One hour still at 200 Hz; the Allan
    /// variance at τ = 10 s is known to about 5 % there (√(τ / T)), so 10 % is four σ.
    #[test]
    fn noise_scale_multiplies_white_noise_and_allan_deviation() {
        const SCALE: f64 = 3.0;
        const TOLERANCE: f64 = 0.10;
        const WHITE_TOLERANCE: f64 = 0.01;
        let samples = still_recording(720_000, 7);
        let perturbed = imu_spec("imu_noise:3")
            .apply(&recorded(&samples, &[]), 1)
            .unwrap();
        let added = perturbed.report.noise_added.unwrap();
        assert!(
            (added.gyroscope_noise_density / NOMINAL.gyroscope_noise_density - 8f64.sqrt()).abs()
                < 1e-12
        );
        let white_std = |s: &[ImuSample], f: &dyn Fn(&ImuSample) -> f64| {
            let d: Vec<f64> = s.windows(2).map(|w| f(&w[1]) - f(&w[0])).collect();
            (d.iter().map(|v| v * v).sum::<f64>() / d.len() as f64 / 2.0).sqrt()
        };
        for (name, f) in [
            (
                "gyro x",
                &(|s: &ImuSample| s.gyro.x) as &dyn Fn(&ImuSample) -> f64,
            ),
            ("accel z", &|s: &ImuSample| s.accel.z),
        ] {
            let ratio = white_std(&perturbed.samples, f) / white_std(&samples, f);
            assert!(
                (ratio / SCALE - 1.0).abs() < WHITE_TOLERANCE,
                "{name}: {ratio}"
            );
        }
        const BIN: usize = 20;
        let bin_s = BIN as f64 / RATE_HZ;
        for (name, reading, nominal_fit) in [
            (
                "gyroscope",
                (|s: &ImuSample| s.gyro) as fn(&ImuSample) -> DVec3,
                None,
            ),
            (
                "accelerometer",
                |s: &ImuSample| s.accel,
                Some((
                    NOMINAL.accelerometer_noise_density,
                    NOMINAL.accelerometer_random_walk,
                )),
            ),
        ] {
            let (before, after) = (
                phase(&samples, BIN, reading),
                phase(&perturbed.samples, BIN, reading),
            );
            for m in [1, 10, 100] {
                let ratio = allan_deviation(&after, m, bin_s) / allan_deviation(&before, m, bin_s);
                eprintln!("{name}: σ_A({} s) ratio {ratio:.4}", m as f64 * bin_s);
                assert!(
                    (ratio / SCALE - 1.0).abs() < TOLERANCE,
                    "{name} τ = {m} bins: {ratio}"
                );
            }
            if let Some((n, k)) = nominal_fit {
                let points: Vec<(f64, f64)> = [1, 2, 5, 10, 20, 50, 100, 200, 500, 1000]
                    .iter()
                    .map(|&m| (m as f64 * bin_s, allan_deviation(&after, m, bin_s).powi(2)))
                    .collect();
                let fit = fit_white_and_walk(&points);
                eprintln!(
                    "{name}: N/(K·N₀) = {:.4}, K/(K·K₀) = {:.4}",
                    fit.noise_density / (SCALE * n),
                    fit.random_walk / (SCALE * k)
                );
                assert!((fit.noise_density / (SCALE * n) - 1.0).abs() < TOLERANCE);
                assert!((fit.random_walk / (SCALE * k) - 1.0).abs() < TOLERANCE);
            }
        }
    }

    #[test]
    fn a_noise_scale_below_one_cannot_be_taken_out_of_recorded_readings() {
        let samples = still_recording(10, 1);
        let err = imu_spec("imu_noise:0.5")
            .apply(&recorded(&samples, &[]), 0)
            .unwrap_err()
            .to_string();
        assert_eq!(
            err,
            "imu_noise:0.5: recorded readings hold their sensor's noise already; only a scale K ≥ 1 can be added"
        );
        // Synthesised readings have the scale in them already: nothing is added.
        let synthesised = ImuStream {
            origin: ImuOrigin::Synthesised,
            ..recorded(&samples, &[])
        };
        let out = imu_spec("imu_noise:0.5").apply(&synthesised, 0).unwrap();
        assert_eq!(out.samples, samples);
        assert!(!out.ground_truth_changed && out.report.noise_added.is_none());
    }

    /// The step is in the readings and in the ground-truth biases from the recorded time on, with
    /// the recorded size, and nowhere before; the added noise's walk is in the biases as well.
    #[test]
    fn the_bias_step_is_where_the_report_says_in_readings_and_ground_truth() {
        let (samples, gt) = (still_recording(2000, 3), ground_truth(2000));
        let out = imu_spec("imu_bias_step:0.02/0.3")
            .apply(&recorded(&samples, &gt), 9)
            .unwrap();
        let step = out.report.bias_step.unwrap();
        let (g, a) = (
            DVec3::from_array(step.gyroscope),
            DVec3::from_array(step.accelerometer),
        );
        assert!((g.length() - 0.02).abs() < 1e-15 && (a.length() - 0.3).abs() < 1e-14);
        let stepped = samples.iter().filter(|s| s.t_ns >= step.at_ns).count();
        assert!((200..=1800).contains(&stepped), "{stepped}");
        for (before, after) in samples.iter().zip(&out.samples) {
            let expected = if before.t_ns >= step.at_ns {
                (g, a)
            } else {
                (DVec3::ZERO, DVec3::ZERO)
            };
            assert!((after.gyro - before.gyro - expected.0).length() < 1e-15);
            assert!((after.accel - before.accel - expected.1).length() < 1e-13);
        }
        assert!(out.ground_truth_changed);
        // A state takes the step with the last sample at or before it.
        let first_stepped = samples.iter().find(|s| s.t_ns >= step.at_ns).unwrap().t_ns;
        for (before, after) in gt.iter().zip(&out.ground_truth) {
            let on = before.t_ns >= first_stepped;
            let expected = if on {
                (g, a)
            } else {
                (DVec3::ZERO, DVec3::ZERO)
            };
            assert!((after.gyro_bias - before.gyro_bias - expected.0).length() < 1e-15);
            assert!((after.accel_bias - before.accel_bias - expected.1).length() < 1e-13);
            assert_eq!(after.world_from_body, before.world_from_body);
        }

        let noisy = imu_spec("imu_noise:2")
            .apply(&recorded(&samples, &gt), 9)
            .unwrap();
        let last = noisy.ground_truth.last().unwrap().gyro_bias - gt.last().unwrap().gyro_bias;
        assert!(last.length() > 0.0, "the added walk is in the true bias");
    }

    /// Drops, then jitter on what is left: the order holds, the ground truth stays whole, the report
    /// counts what happened, and the seed fixes it.
    #[test]
    fn drops_and_jitter_keep_order_and_ground_truth_and_follow_the_seed() {
        let (samples, gt) = (still_recording(20_000, 2), ground_truth(20_000));
        let spec = imu_spec("imu_drop:0.1/4,imu_jitter:0.5,imu_saturation:0.001/9.81");
        let out = spec.apply(&recorded(&samples, &gt), 5).unwrap();
        let dropped = out.report.dropped.unwrap();
        assert_eq!(out.samples.len(), samples.len() - dropped.dropped);
        assert_eq!(out.input_index.len(), out.samples.len());
        assert!(dropped.longest_run > 1, "bursts");
        // Each sample is its input's, saturated and moved by less than half a period.
        let half_period = 2_500_000;
        for (sample, &i) in out.samples.iter().zip(&out.input_index) {
            assert!(sample.t_ns.abs_diff(samples[i].t_ns) < half_period);
            let clipped = samples[i]
                .gyro
                .clamp(DVec3::splat(-0.001), DVec3::splat(0.001));
            assert_eq!(sample.gyro, clipped);
        }
        assert!(out.samples.windows(2).all(|w| w[0].t_ns < w[1].t_ns));
        assert_eq!(out.ground_truth, gt);
        assert!(!out.ground_truth_changed);
        let saturated = out.report.saturated.unwrap();
        // σ_gyro ≈ 2.4e-3 rad/s per sample: most samples pass 1 mrad/s on some axis.
        assert!(saturated.gyroscope_samples > samples.len() / 2);
        assert!(out
            .samples
            .iter()
            .all(|s| s.gyro.abs().max_element() <= 0.001 && s.accel.abs().max_element() <= 9.81));
        assert_eq!(out, spec.apply(&recorded(&samples, &gt), 5).unwrap());
        assert_ne!(out, spec.apply(&recorded(&samples, &gt), 6).unwrap());
    }

    #[test]
    fn camera_stamps_shift_by_whole_nanoseconds_and_never_below_zero() {
        let spec = imu_spec("cam_imu_offset:-2.5");
        assert_eq!(spec.cam_imu_offset_ns(), Some(-2_500_000));
        assert!(!spec.changes_imu());
        let samples = still_recording(10, 1);
        let out = spec.apply(&recorded(&samples, &[]), 0).unwrap();
        assert!(!out.samples_changed && !out.ground_truth_changed);
        assert_eq!(out.samples, samples);
        assert!(imu_spec("imu_jitter:1,cam_imu_offset:1").changes_imu());
        assert_eq!(
            shift_stamp(START_NS, -2_500_000),
            Some(START_NS - 2_500_000)
        );
        assert_eq!(shift_stamp(1_000_000, -2_500_000), None);
        assert_eq!(shift_stamp(u64::MAX, 1), None);
    }
}
