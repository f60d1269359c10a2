//! `imu_drop:P[/L]`: samples lost in transport. Without L each sample is dropped independently
//! with probability P; with L, drops come in bursts from a two-state Markov chain (Gilbert's
//! channel) that leaves a burst with probability 1/L per sample and enters one with probability
//! P / (L (1 − P)), so that a fraction P is dropped in bursts of mean length L.

use serde::Serialize;

use super::items::{SampleDrop, DROP};
use crate::rng::RngKey;

/// What was dropped.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Dropped {
    pub dropped: usize,
    pub of: usize,
    /// The most consecutive samples dropped.
    pub longest_run: usize,
}

/// Per sample, whether it is kept; sample `k`'s draw is keyed by (seed, `imu_drop`, k).
pub fn kept(samples: usize, drop: SampleDrop, seed: u64) -> (Vec<bool>, Dropped) {
    let u = |k: usize| RngKey::new(seed, DROP, k as u32, 0).uniform_f64([0; 4]);
    let p = drop.probability;
    let mut in_burst = false;
    let keep: Vec<bool> = (0..samples)
        .map(|k| {
            let dropped = match drop.burst {
                None => u(k) < p,
                Some(l) => {
                    // The first sample starts in the chain's stationary state.
                    in_burst = match (k, in_burst) {
                        (0, _) => u(k) < p,
                        (_, true) => u(k) >= 1.0 / l,
                        (_, false) => u(k) < p / (l * (1.0 - p)),
                    };
                    in_burst
                }
            };
            !dropped
        })
        .collect();
    let mut report = Dropped {
        of: samples,
        ..Dropped::default()
    };
    let mut run = 0;
    for &k in &keep {
        run = if k { 0 } else { run + 1 };
        report.dropped += usize::from(!k);
        report.longest_run = report.longest_run.max(run);
    }
    (keep, report)
}

#[cfg(test)]
mod tests {
    use super::*;

    const N: usize = 200_000;

    /// Lengths of the runs of dropped samples.
    fn runs(keep: &[bool]) -> Vec<usize> {
        keep.split(|&k| k)
            .map(<[bool]>::len)
            .filter(|&n| n > 0)
            .collect()
    }

    #[test]
    fn independent_drops_hit_the_rate_within_a_binomial_bound() {
        for p in [0.001, 0.05, 0.5] {
            let (keep, report) = kept(
                N,
                SampleDrop {
                    probability: p,
                    burst: None,
                },
                11,
            );
            let dropped = keep.iter().filter(|&&k| !k).count();
            assert_eq!(report.dropped, dropped);
            let sd = (N as f64 * p * (1.0 - p)).sqrt();
            assert!(
                (dropped as f64 - N as f64 * p).abs() < 5.0 * sd,
                "P = {p}: {dropped}"
            );
            assert_eq!(report.longest_run, runs(&keep).into_iter().max().unwrap());
        }
        let (keep, report) = kept(
            1000,
            SampleDrop {
                probability: 0.0,
                burst: None,
            },
            1,
        );
        assert!(keep.iter().all(|&k| k) && report.dropped == 0);
    }

    /// Bursts: the fraction dropped is P and runs average L. The chain's correlation
    /// ρ = 1 − 1/L − P/(L(1 − P)) widens the binomial bound by √((1 + ρ)/(1 − ρ)).
    #[test]
    fn bursts_drop_the_fraction_in_runs_of_the_mean_length() {
        let (p, l) = (0.05, 10.0);
        let (keep, report) = kept(
            N,
            SampleDrop {
                probability: p,
                burst: Some(l),
            },
            5,
        );
        let rho = 1.0 - 1.0 / l - p / (l * (1.0 - p));
        let sd = (N as f64 * p * (1.0 - p) * (1.0 + rho) / (1.0 - rho)).sqrt();
        assert!(
            (report.dropped as f64 - N as f64 * p).abs() < 5.0 * sd,
            "{}",
            report.dropped
        );
        let runs = runs(&keep);
        let mean = runs.iter().sum::<usize>() as f64 / runs.len() as f64;
        // Run lengths are geometric with mean L and standard deviation √(L(L − 1)).
        let se = (l * (l - 1.0) / runs.len() as f64).sqrt();
        assert!((mean - l).abs() < 5.0 * se, "mean run {mean}");
    }
}
