//! `imu_jitter:MS`: each IMU timestamp moves by a draw of N(0, MS ms) while its reading stays
//! (the clock stamping it is noisy, not the sensor). The draw is clipped to less than half the
//! gap to either neighbour, `|e_k| ≤ ⌊min(gap_before, gap_after) / 2⌋ − 1` ns, so consecutive
//! stamps keep at least 2 ns between them and stay strictly increasing.

use serde::Serialize;

use super::items::JITTER;
use crate::rng::RngKey;

/// What the jitter did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Jittered {
    /// The standard deviation of the moves made, ns.
    pub std_ns: f64,
    /// Draws clipped to keep the order.
    pub clipped: usize,
}

/// `times_ns` (strictly increasing) moved by the jitter; sample `k`'s draw is keyed by
/// (seed, `imu_jitter`, k).
pub fn jitter(times_ns: &[u64], sigma_ms: f64, seed: u64) -> (Vec<u64>, Jittered) {
    let sigma_ns = sigma_ms * 1e6;
    let gap = |a: usize, b: usize| times_ns[b] - times_ns[a];
    let mut report = Jittered::default();
    let mut sum_sq = 0.0;
    let moved = (0..times_ns.len())
        .map(|k| {
            let before = (k > 0).then(|| gap(k - 1, k));
            let after = (k + 1 < times_ns.len()).then(|| gap(k, k + 1));
            // A lone sample has no order to keep.
            let limit = match (before, after) {
                (Some(b), Some(a)) => (b.min(a) / 2).saturating_sub(1) as f64,
                (Some(g), None) | (None, Some(g)) => (g / 2).saturating_sub(1) as f64,
                (None, None) => f64::INFINITY,
            };
            let draw =
                (RngKey::new(seed, JITTER, k as u32, 0).normal_f64([0; 4]) * sigma_ns).round();
            let error = draw.clamp(-limit, limit);
            report.clipped += usize::from(error != draw);
            sum_sq += error * error;
            // In integers: f64 holds a recorded 19-digit stamp to 256 ns only. A first stamp near
            // 0 stops at 0, still before the second.
            times_ns[k].saturating_add_signed(error as i64)
        })
        .collect();
    if !times_ns.is_empty() {
        report.std_ns = (sum_sq / times_ns.len() as f64).sqrt();
    }
    (moved, report)
}

#[cfg(test)]
mod tests {
    use super::*;

    const N: usize = 100_000;
    const PERIOD_NS: u64 = 5_000_000;

    fn grid() -> Vec<u64> {
        (0..N as u64)
            .map(|k| 1_000_000_000 + k * PERIOD_NS)
            .collect()
    }

    #[test]
    fn jitter_has_the_given_std_and_keeps_the_order() {
        let times = grid();
        let (moved, report) = jitter(&times, 0.5, 3);
        assert!(moved.windows(2).all(|w| w[0] < w[1]));
        let errors: Vec<f64> = moved
            .iter()
            .zip(&times)
            .map(|(&m, &t)| (m as i64 - t as i64) as f64)
            .collect();
        let mean = errors.iter().sum::<f64>() / N as f64;
        let std = (errors.iter().map(|e| e * e).sum::<f64>() / N as f64).sqrt();
        // 0.5 ms is a tenth of the period: clipping (at 5 σ) is negligible. The std's relative
        // standard error is 1/√(2N) ≈ 0.22 %.
        assert_eq!(report.clipped, 0);
        assert!((std / 0.5e6 - 1.0).abs() < 0.011, "std {std} ns");
        assert!(mean.abs() < 5.0 * 0.5e6 / (N as f64).sqrt(), "mean {mean}");
        assert!((report.std_ns - std).abs() < 1e-6 * std);
    }

    #[test]
    fn a_jitter_near_the_period_is_clipped_and_stays_strictly_increasing() {
        let mut times = grid();
        times[10] = times[9] + 3; // an uneven recorded gap
        let (moved, report) = jitter(&times, 10.0, 4);
        assert!(moved.windows(2).all(|w| w[1] >= w[0] + 2), "order kept");
        assert!(report.clipped > N / 2, "{}", report.clipped);
        assert!(report.std_ns < PERIOD_NS as f64 / 2.0);
        let (none, zero) = jitter(&times, 0.0, 4);
        assert_eq!(none, times);
        assert_eq!(zero.std_ns, 0.0);
    }
}
