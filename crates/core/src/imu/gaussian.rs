//! Standard normal draws from the counter-based hash: each is a pure function of (seed, sample
//! index, axis, purpose), so a sequence is reproducible from its seed, any sample can be drawn
//! alone and no RNG state is shared.

use crate::hash::splitmix64;

/// What a draw is for; each purpose is an independent stream.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NoisePurpose {
    GyroscopeWhite = 1,
    AccelerometerWhite = 2,
    GyroscopeBiasWalk = 3,
    AccelerometerBiasWalk = 4,
}

/// 2⁻⁵³: a 53-bit integer times this is a double in [0, 1).
const UNIT_53: f64 = 1.0 / (1u64 << 53) as f64;

/// A uniform draw in (0, 1), never 0 (it goes into a logarithm).
fn uniform_open(seed: u64, index: u64, axis: usize, purpose: NoisePurpose, draw: u64) -> f64 {
    let stream = ((purpose as u64) << 8) | ((axis as u64) << 1) | draw;
    let h = splitmix64(seed ^ splitmix64(index ^ splitmix64(stream)));
    ((h >> 11) as f64 + 0.5) * UNIT_53
}

/// A standard normal draw by the Box–Muller transform of two uniform draws.
pub fn standard_normal(seed: u64, index: u64, axis: usize, purpose: NoisePurpose) -> f64 {
    let u1 = uniform_open(seed, index, axis, purpose, 0);
    let u2 = uniform_open(seed, index, axis, purpose, 1);
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Draws per check; the sample mean's standard error is 1/√N ≈ 0.0022.
    const DRAWS: u64 = 200_000;
    /// About five standard errors of the mean, variance and correlation estimates.
    const MOMENT_TOLERANCE: f64 = 0.015;

    #[test]
    fn draws_are_standard_normal_and_streams_independent() {
        let (mut sum, mut squares, mut fourth, mut cross) = (0.0, 0.0, 0.0, 0.0);
        let mut within_one_sigma = 0;
        for i in 0..DRAWS {
            let x = standard_normal(7, i, 0, NoisePurpose::GyroscopeWhite);
            let y = standard_normal(7, i, 1, NoisePurpose::GyroscopeWhite);
            let z = standard_normal(7, i, 0, NoisePurpose::GyroscopeBiasWalk);
            sum += x;
            squares += x * x;
            fourth += x.powi(4);
            cross += x * y + x * z;
            within_one_sigma += usize::from(x.abs() < 1.0);
        }
        let n = DRAWS as f64;
        assert!((sum / n).abs() < MOMENT_TOLERANCE, "mean {}", sum / n);
        assert!(
            (squares / n - 1.0).abs() < MOMENT_TOLERANCE,
            "variance {}",
            squares / n
        );
        // Kurtosis 3 and 68.27 % within one σ: the shape, not only the moments.
        assert!(
            (fourth / n - 3.0).abs() < 4.0 * MOMENT_TOLERANCE,
            "{}",
            fourth / n
        );
        let inside = within_one_sigma as f64 / n;
        assert!((inside - 0.6827).abs() < 0.005, "{inside}");
        assert!(
            (cross / (2.0 * n)).abs() < MOMENT_TOLERANCE,
            "correlation {}",
            cross / n
        );
    }
}
