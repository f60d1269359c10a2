//! The summary statistics evo reports for an error series (numpy semantics).

use serde::Serialize;

/// rmse, mean, median, std (population), min, max and sse (sum of squared errors) of a series.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ErrorStatistics {
    pub rmse: f64,
    pub mean: f64,
    pub median: f64,
    pub std: f64,
    pub min: f64,
    pub max: f64,
    pub sse: f64,
    /// Number of error values.
    pub n: usize,
}

impl ErrorStatistics {
    /// `None` for an empty series.
    pub fn of(errors: &[f64]) -> Option<Self> {
        if errors.is_empty() {
            return None;
        }
        let n = errors.len() as f64;
        let sse: f64 = errors.iter().map(|e| e * e).sum();
        let mean = errors.iter().sum::<f64>() / n;
        let variance = errors.iter().map(|e| (e - mean) * (e - mean)).sum::<f64>() / n;
        Some(Self {
            rmse: (sse / n).sqrt(),
            mean,
            median: median(errors),
            std: variance.sqrt(),
            min: errors.iter().copied().fold(f64::INFINITY, f64::min),
            max: errors.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            sse,
            n: errors.len(),
        })
    }
}

/// numpy's median: the middle value, or the mean of the two middle values.
fn median(values: &[f64]) -> f64 {
    let mut sorted = values.to_vec();
    let mid = sorted.len() / 2;
    let (below, upper, _) = sorted.select_nth_unstable_by(mid, f64::total_cmp);
    let upper = *upper;
    if values.len() % 2 == 1 {
        return upper;
    }
    let lower = below.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    (lower + upper) / 2.0
}

#[cfg(test)]
mod tests {
    use super::*;

    const TOL: f64 = 1e-15;

    #[test]
    fn hand_computed_series() {
        // errors 3, 1, 4, 1, 5: sse 52, mean 14/5, var = (0.04+3.24+1.44+3.24+4.84)/5 = 2.56.
        let s = ErrorStatistics::of(&[3.0, 1.0, 4.0, 1.0, 5.0]).unwrap();
        assert_eq!(s.sse, 52.0);
        assert!((s.rmse - (52.0_f64 / 5.0).sqrt()).abs() < TOL);
        assert!((s.mean - 2.8).abs() < TOL);
        assert!((s.std - 1.6).abs() < TOL);
        assert_eq!((s.median, s.min, s.max, s.n), (3.0, 1.0, 5.0, 5));
    }

    #[test]
    fn even_count_median_is_the_mean_of_the_middle_two() {
        let s = ErrorStatistics::of(&[4.0, 1.0, 2.0, 10.0]).unwrap();
        assert_eq!(s.median, 3.0);
        assert!(ErrorStatistics::of(&[]).is_none());
    }
}
