//! When a method counts as broken at a severity: from all its runs there (repeats × sequences),
//! the median of one number per run against a threshold. A failed run (crashed, timed out, no or
//! unreadable estimate) counts as the worst value: broken, SR 0, ATE infinite.

use std::fmt;
use std::str::FromStr;

/// What one run gave.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunOutcome {
    /// `None` for a failed run.
    pub ate: Option<f64>,
    /// SR of the run; `None` for a failed run (or a ground truth that does not move).
    pub sr: Option<f64>,
}

impl RunOutcome {
    pub const FAILED: RunOutcome = RunOutcome {
        ate: None,
        sr: None,
    };
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Criterion {
    /// More than half of the runs failed.
    Failed,
    /// The median SR is below the value.
    SrBelow(f64),
    /// The median ATE is above this many times the median ATE of the clean runs.
    AteAboveClean(f64),
}

impl Criterion {
    /// Whether `runs` break the method; `clean` are the runs on the clean sequences.
    pub fn breaks(&self, runs: &[RunOutcome], clean: &[RunOutcome]) -> bool {
        match *self {
            Criterion::Failed => {
                median(runs.iter().map(|r| if r.ate.is_none() { 1.0 } else { 0.0 })) > 0.5
            }
            Criterion::SrBelow(threshold) => {
                median(
                    runs.iter()
                        .map(|r| r.sr.filter(|_| r.ate.is_some()).unwrap_or(0.0)),
                ) < threshold
            }
            Criterion::AteAboveClean(factor) => {
                let ate = |r: &RunOutcome| r.ate.unwrap_or(f64::INFINITY);
                let median_ate = median(runs.iter().map(ate));
                // Mostly failed runs break it, on the clean sequences too.
                median_ate.is_infinite() || median_ate > factor * median(clean.iter().map(ate))
            }
        }
    }
}

/// The median; the mean of the middle two for an even count; NaN for none.
fn median(values: impl Iterator<Item = f64>) -> f64 {
    let mut values: Vec<f64> = values.collect();
    values.sort_by(f64::total_cmp);
    match values.len() {
        0 => f64::NAN,
        n if n % 2 == 1 => values[n / 2],
        n => (values[n / 2 - 1] + values[n / 2]) / 2.0,
    }
}

impl FromStr for Criterion {
    type Err = String;

    /// `failed`, `sr<X` (X in (0, 1]), `ate>K×clean` (also `ate>Kxclean`, `ate>Kx`, `ate>K`).
    fn from_str(text: &str) -> Result<Self, String> {
        let bad = || {
            format!(
                "criterion '{text}': expected failed, sr<X (e.g. sr<0.5) or ate>K×clean (e.g. ate>3xclean)"
            )
        };
        let text = text.trim();
        if text == "failed" {
            return Ok(Criterion::Failed);
        }
        if let Some(value) = text.strip_prefix("sr<") {
            let x: f64 = value.trim().parse().map_err(|_| bad())?;
            return match x > 0.0 && x <= 1.0 {
                true => Ok(Criterion::SrBelow(x)),
                false => Err(format!(
                    "criterion '{text}': SR is in [0, 1]; expected 0 < X ≤ 1"
                )),
            };
        }
        let factor = text.strip_prefix("ate>").ok_or_else(bad)?;
        let factor = ["×clean", "xclean", "×", "x"]
            .iter()
            .find_map(|suffix| factor.strip_suffix(suffix))
            .unwrap_or(factor);
        let k: f64 = factor.trim().parse().map_err(|_| bad())?;
        match k.is_finite() && k >= 1.0 {
            true => Ok(Criterion::AteAboveClean(k)),
            false => Err(format!(
                "criterion '{text}': expected a factor K ≥ 1 of the clean ATE"
            )),
        }
    }
}

impl fmt::Display for Criterion {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Criterion::Failed => write!(f, "failed (more than half of the runs failed)"),
            Criterion::SrBelow(x) => write!(f, "sr<{x} (median SR below {x})"),
            Criterion::AteAboveClean(k) => {
                write!(f, "ate>{k}×clean (median ATE above {k}× the clean median)")
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ran(ate: f64, sr: f64) -> RunOutcome {
        RunOutcome {
            ate: Some(ate),
            sr: Some(sr),
        }
    }

    #[test]
    fn parses_the_three_forms_and_refuses_the_rest() {
        assert_eq!("failed".parse(), Ok(Criterion::Failed));
        assert_eq!("sr<0.5".parse(), Ok(Criterion::SrBelow(0.5)));
        for text in ["ate>3×clean", "ate>3xclean", "ate>3x", "ate>3"] {
            assert_eq!(text.parse(), Ok(Criterion::AteAboveClean(3.0)), "{text}");
        }
        for bad in ["sr<1.5", "sr<0", "ate>0.5", "ate>", "fails", "sr>0.5"] {
            let e = bad.parse::<Criterion>().unwrap_err();
            assert!(e.contains(bad), "{e}");
        }
    }

    #[test]
    fn the_median_run_decides_and_failures_count_as_the_worst() {
        let clean = [ran(0.01, 1.0), ran(0.02, 1.0), ran(0.03, 1.0)];
        let ate = Criterion::AteAboveClean(3.0);
        assert!(!ate.breaks(
            &[ran(0.03, 1.0), ran(0.05, 1.0), RunOutcome::FAILED],
            &clean
        ));
        assert!(ate.breaks(
            &[ran(0.05, 1.0), RunOutcome::FAILED, RunOutcome::FAILED],
            &clean
        ));
        assert!(ate.breaks(&[ran(0.01, 1.0), ran(0.07, 1.0), ran(0.9, 1.0)], &clean));
        let failed_clean = [RunOutcome::FAILED, RunOutcome::FAILED, ran(0.01, 1.0)];
        assert!(ate.breaks(&failed_clean, &failed_clean));
        let sr = Criterion::SrBelow(0.5);
        assert!(sr.breaks(
            &[ran(0.01, 0.4), ran(0.01, 0.9), RunOutcome::FAILED],
            &clean
        ));
        assert!(!sr.breaks(
            &[ran(0.01, 0.6), ran(0.01, 0.9), RunOutcome::FAILED],
            &clean
        ));
        let failed = Criterion::Failed;
        assert!(!failed.breaks(&[ran(9.0, 0.0), RunOutcome::FAILED], &clean));
        assert!(failed.breaks(
            &[RunOutcome::FAILED, RunOutcome::FAILED, ran(0.0, 1.0)],
            &clean
        ));
    }
}
