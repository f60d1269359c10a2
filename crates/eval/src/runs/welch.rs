//! Welch's unequal-variance t-test (two-sided), on log ATE of a setting against clean.

use serde::Serialize;
use statrs::distribution::{ContinuousCDF, StudentsT};

#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct WelchTest {
    /// (mean(a) − mean(b)) / standard error.
    pub t: f64,
    /// Welch–Satterthwaite degrees of freedom.
    pub df: f64,
    /// Two-sided p-value.
    pub p: f64,
}

/// Welch's t-test of `a` against `b`. `None` when either has fewer than two samples or both have
/// zero variance (the test is undefined).
pub fn welch_t_test(a: &[f64], b: &[f64]) -> Option<WelchTest> {
    let (mean_a, var_a) = mean_and_sample_variance(a)?;
    let (mean_b, var_b) = mean_and_sample_variance(b)?;
    let (sa, sb) = (var_a / a.len() as f64, var_b / b.len() as f64);
    let se2 = sa + sb;
    if se2 <= 0.0 {
        return None;
    }
    let t = (mean_a - mean_b) / se2.sqrt();
    let df = se2 * se2 / (sa * sa / (a.len() - 1) as f64 + sb * sb / (b.len() - 1) as f64);
    let distribution = StudentsT::new(0.0, 1.0, df).ok()?;
    Some(WelchTest {
        t,
        df,
        p: 2.0 * distribution.sf(t.abs()),
    })
}

fn mean_and_sample_variance(x: &[f64]) -> Option<(f64, f64)> {
    if x.len() < 2 {
        return None;
    }
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    let variance = x.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / (n - 1.0);
    Some((mean, variance))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Expected values from scipy 1.17.1 `stats.ttest_ind(a, b, equal_var=False)`.
    const TOL: f64 = 1e-9;

    #[test]
    fn matches_scipy_on_a_textbook_sample() {
        let a = [19.8, 20.4, 19.6, 17.8, 18.5, 18.9, 18.3, 18.9, 19.5, 22.0];
        let b = [
            28.2, 26.6, 20.1, 23.3, 25.2, 22.1, 17.7, 27.6, 20.6, 13.7, 23.2, 17.5, 20.6, 18.0,
            23.9, 21.6, 24.3, 20.4, 23.9, 13.3,
        ];
        let w = welch_t_test(&a, &b).unwrap();
        assert!((w.t - -2.225512039969852).abs() < TOL);
        assert!((w.df - 24.524634944257343).abs() < TOL);
        assert!((w.p - 0.035484530830010394).abs() < TOL);
    }

    #[test]
    fn matches_scipy_on_log_ate_with_a_failure() {
        let ln = |v: &[f64]| v.iter().map(|x| x.ln()).collect::<Vec<_>>();
        let w = welch_t_test(&ln(&[0.05, 1.0, 0.08]), &ln(&[0.01, 0.012, 0.011, 0.013])).unwrap();
        assert!((w.t - 2.8218401401820876).abs() < TOL);
        assert!((w.df - 2.014748771385747).abs() < TOL);
        assert!((w.p - 0.10512306915172881).abs() < TOL);
    }

    #[test]
    fn undefined_cases_give_none() {
        assert!(welch_t_test(&[1.0], &[1.0, 2.0]).is_none());
        assert!(welch_t_test(&[1.0, 1.0], &[2.0, 2.0]).is_none());
    }
}
