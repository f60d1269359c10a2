//! The noise model against its own definition: the overlapping Allan deviation of a long still
//! sequence follows σ²(τ) = N²/τ + K²τ/3 with the configured noise density N and random walk K
//! (IEEE Std 952-1997, annex C; Kalibr's "IMU Noise Model").

use glam::DVec3;

use super::allan::{allan_variance, fit_white_and_walk};
use super::*;

const RATE_HZ: f64 = 200.0;
/// Six hours still (4.32 M samples, about 2.5 s in a debug build). The gyroscope's random walk
/// only dominates its Allan variance past τ ≈ 15 s, where few clusters fit: over seven seeds
/// the fitted K scattered by −2.5 … +6.5 % at three hours, −4 … +4.6 % at six, −3 … +2 % at
/// twelve.
const DURATION_S: f64 = 6.0 * 3600.0;
/// Samples are averaged in bins of this many first (100 ms), so that the cluster sums take
/// little memory; the Allan variance of the bin means at τ = m bins is the overlapping Allan
/// variance of the samples, with clusters stepping one bin instead of one sample.
const SAMPLES_PER_BIN: usize = 20;
/// The bar on the recovered parameters.
const PARAMETER_TOLERANCE: f64 = 0.10;

/// Running integrals of the bin means of the measurement error, per sensor and axis.
struct StillRecording {
    gyroscope: [Vec<f64>; 3],
    accelerometer: [Vec<f64>; 3],
}

fn record_still(noise: ImuNoise, seed: u64) -> StillRecording {
    let truth = ImuReading {
        gyroscope: DVec3::ZERO,
        accelerometer: -GRAVITY_WORLD,
    };
    let mut imu = NoisyImu::new(noise, RATE_HZ, seed, ImuBias::default()).unwrap();
    let bins = (DURATION_S * RATE_HZ) as usize / SAMPLES_PER_BIN;
    let start = || std::array::from_fn(|_| Vec::from([0.0]));
    let mut out = StillRecording {
        gyroscope: start(),
        accelerometer: start(),
    };
    let mut k = 0;
    for _ in 0..bins {
        let (mut g, mut a) = (DVec3::ZERO, DVec3::ZERO);
        for _ in 0..SAMPLES_PER_BIN {
            let s = imu.measure(k as f64 / RATE_HZ, truth);
            g += s.measured.gyroscope - truth.gyroscope;
            a += s.measured.accelerometer - truth.accelerometer;
            k += 1;
        }
        for axis in 0..3 {
            let (gx, ax) = (&mut out.gyroscope[axis], &mut out.accelerometer[axis]);
            gx.push(gx[gx.len() - 1] + g[axis] / RATE_HZ);
            ax.push(ax[ax.len() - 1] + a[axis] / RATE_HZ);
        }
    }
    out
}

/// Fits one sensor's three axes (their Allan variances averaged) at cluster times from 0.1 s to
/// a tenth of the record, and checks N, K and σ(1 s) against the configuration.
fn check_sensor(name: &str, axes: &[Vec<f64>; 3], density: f64, walk: f64) {
    let bin_s = SAMPLES_PER_BIN as f64 / RATE_HZ;
    let largest = (axes[0].len() - 1) / 10;
    let mut clusters: Vec<usize> = (0..=40)
        .map(|i| 10f64.powf(i as f64 * (largest as f64).log10() / 40.0) as usize)
        .collect();
    clusters.dedup();
    let points: Vec<(f64, f64)> = clusters
        .iter()
        .map(|&m| {
            let mean = axes
                .iter()
                .map(|x| allan_variance(x, m, bin_s))
                .sum::<f64>()
                / 3.0;
            (m as f64 * bin_s, mean)
        })
        .collect();
    let fit = fit_white_and_walk(&points);
    let (n, k) = (fit.noise_density, fit.random_walk);
    let one_second = (1.0 / bin_s).round() as usize;
    let expected_at_1s = (density * density + walk * walk / 3.0).sqrt();
    eprintln!(
        "{name}: fitted N/N₀ = {:.4}, K/K₀ = {:.4} over τ = {:.1}–{:.0} s",
        n / density,
        k / walk,
        points[0].0,
        points[points.len() - 1].0,
    );
    for (axis, x) in axes.iter().enumerate() {
        let at_1s = allan_variance(x, one_second, bin_s).sqrt();
        eprintln!(
            "{name} axis {axis}: σ(1 s) = {at_1s:.4e}, σ(1 s)/N₀ = {:.4}, \
             against N²/τ + K²τ/3: {:.4}",
            at_1s / density,
            at_1s / expected_at_1s
        );
        let ratio = at_1s / expected_at_1s;
        assert!(
            (ratio - 1.0).abs() < PARAMETER_TOLERANCE,
            "{name} axis {axis}"
        );
    }
    assert!((n / density - 1.0).abs() < PARAMETER_TOLERANCE, "{name} N");
    assert!((k / walk - 1.0).abs() < PARAMETER_TOLERANCE, "{name} K");
}

#[test]
fn allan_deviation_recovers_the_noise_density_and_random_walk() {
    let noise = ImuNoise::ADIS16448_EUROC;
    let still = record_still(noise, 2024);
    check_sensor(
        "gyroscope",
        &still.gyroscope,
        noise.gyroscope_noise_density,
        noise.gyroscope_random_walk,
    );
    check_sensor(
        "accelerometer",
        &still.accelerometer,
        noise.accelerometer_noise_density,
        noise.accelerometer_random_walk,
    );
}

/// The fit on an exact curve gives the exact parameters (the fit itself is not the error).
#[test]
fn the_fit_recovers_an_exact_curve() {
    let (n, k) = (2e-3, 3e-3);
    let points: Vec<(f64, f64)> = [0.1, 1.0, 10.0, 100.0]
        .iter()
        .map(|&t| (t, n * n / t + k * k * t / 3.0))
        .collect();
    let fit = fit_white_and_walk(&points);
    let (fit_n, fit_k) = (fit.noise_density, fit.random_walk);
    assert!((fit_n / n - 1.0).abs() < 1e-9 && (fit_k / k - 1.0).abs() < 1e-9);
}
