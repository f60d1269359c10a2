//! The benchmark's tables over many runs (docs/src/metrics.md, "Failure convention and CSR (over many runs)").

use std::collections::BTreeMap;

use serde::Serialize;

use super::collect::RunRecord;
use super::naming::{category, sort_settings, CLEAN};
use super::welch::{welch_t_test, WelchTest};

/// Thresholds (m) at which CSR is tabulated.
pub const CSR_THRESHOLDS: [f64; 3] = [0.02, 0.1, 1.0];
/// The CSR curve's thresholds: 10^(k/20) m for k = −60..=0 (1 mm to 1 m, 20 per decade).
const CURVE_DECADES: i32 = 3;
const CURVE_STEPS_PER_DECADE: i32 = 20;
/// ATE floor (m) before the logarithm of the t-test, so that a perfect run (ATE 0) stays finite.
const LOG_ATE_FLOOR: f64 = 1e-6;

/// Runs of one method in one setting (over scenes and repeats); failures count with the
/// failure ATE and 0 for the other metrics.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SettingCell {
    pub runs: usize,
    pub failures: usize,
    pub ate_mean: f64,
    /// `None` when no run has an SR (ground truth without motion).
    pub sr_mean: Option<f64>,
    /// `None` when no run has one (ground truth without motion).
    pub sr_path_ratio_mean: Option<f64>,
    /// `None` when the cell has no run.
    pub tracked_fraction_mean: Option<f64>,
}

/// Over the settings of one method, the mean and the min of the per-setting means; `None` when
/// no setting has a value.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct MeanAndMin {
    pub mean: Option<f64>,
    pub min: Option<f64>,
}

impl MeanAndMin {
    fn of(values: &[f64]) -> Self {
        Self {
            mean: mean(values),
            min: values.iter().copied().reduce(f64::min),
        }
    }
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CsrPoint {
    pub threshold: f64,
    /// Percent.
    pub csr: f64,
}

/// One method over its settings.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MethodSummary {
    pub method: String,
    /// One per setting, in [`RunsSummary::settings`] order.
    pub cells: Vec<SettingCell>,
    /// Mean and max over settings of the per-setting mean ATE.
    pub ate_mean: f64,
    pub ate_max: f64,
    pub sr: MeanAndMin,
    pub sr_path_ratio: MeanAndMin,
    pub tracked_fraction: MeanAndMin,
    pub runs: usize,
    pub failures: usize,
    /// CSR over all runs of the method at [`CSR_THRESHOLDS`].
    pub csr: Vec<CsrPoint>,
    /// CSR at each of [`RunsSummary::csr_curve_thresholds`].
    pub csr_curve: Vec<f64>,
}

/// Per setting, the lowest mean ATE any method reached.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SurvivalBound {
    pub per_setting: Vec<f64>,
    pub mean: f64,
    pub max: f64,
    pub categories: Vec<CategoryBound>,
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CategoryBound {
    pub category: String,
    pub settings: usize,
    /// Mean over the category's settings of the survival upper bound.
    pub mean: f64,
}

/// Welch's t-test of one setting against clean, for one method, on ln(max(ATE, 1 µm)).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SettingTest {
    pub method: String,
    pub setting: String,
    pub n: usize,
    pub n_clean: usize,
    pub mean_log_ate: f64,
    pub mean_log_ate_clean: f64,
    /// `None` when undefined (fewer than two runs on a side, or no variance).
    pub test: Option<WelchTest>,
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RunsSummary {
    pub methods: Vec<MethodSummary>,
    pub settings: Vec<String>,
    pub failure_ate: f64,
    pub survival: SurvivalBound,
    pub csr_curve_thresholds: Vec<f64>,
    pub t_tests: Vec<SettingTest>,
}

pub fn summarize(runs: &[RunRecord], failure_ate: f64) -> RunsSummary {
    let mut settings: Vec<String> = runs.iter().map(|r| r.setting.clone()).collect();
    settings.sort();
    settings.dedup();
    sort_settings(&mut settings);
    let mut by_method: BTreeMap<&str, Vec<&RunRecord>> = BTreeMap::new();
    for run in runs {
        by_method.entry(&run.method).or_default().push(run);
    }
    let thresholds: Vec<f64> = (-CURVE_DECADES * CURVE_STEPS_PER_DECADE..=0)
        .map(|k| 10f64.powf(f64::from(k) / f64::from(CURVE_STEPS_PER_DECADE)))
        .collect();
    let methods: Vec<MethodSummary> = by_method
        .iter()
        .map(|(method, runs)| summarize_method(method, runs, &settings, &thresholds))
        .collect();
    let t_tests = by_method
        .iter()
        .flat_map(|(method, runs)| setting_tests(method, runs, &settings))
        .collect();
    RunsSummary {
        survival: survival_bound(&methods, &settings),
        methods,
        settings,
        failure_ate,
        csr_curve_thresholds: thresholds,
        t_tests,
    }
}

fn summarize_method(
    method: &str,
    runs: &[&RunRecord],
    settings: &[String],
    thresholds: &[f64],
) -> MethodSummary {
    let cells: Vec<SettingCell> = settings
        .iter()
        .map(|s| setting_cell(runs.iter().copied().filter(|r| &r.setting == s)))
        .collect();
    let present: Vec<&SettingCell> = cells.iter().filter(|c| c.runs > 0).collect();
    let ates: Vec<f64> = present.iter().map(|c| c.ate_mean).collect();
    let over_settings = |cell: fn(&SettingCell) -> Option<f64>| {
        MeanAndMin::of(&present.iter().filter_map(|c| cell(c)).collect::<Vec<_>>())
    };
    MethodSummary {
        method: method.to_string(),
        ate_mean: mean(&ates).unwrap_or(f64::NAN),
        ate_max: ates.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        sr: over_settings(|c| c.sr_mean),
        sr_path_ratio: over_settings(|c| c.sr_path_ratio_mean),
        tracked_fraction: over_settings(|c| c.tracked_fraction_mean),
        runs: runs.len(),
        failures: runs.iter().filter(|r| r.failed()).count(),
        csr: CSR_THRESHOLDS
            .iter()
            .map(|&threshold| CsrPoint {
                threshold,
                csr: csr(runs, threshold),
            })
            .collect(),
        csr_curve: thresholds.iter().map(|&t| csr(runs, t)).collect(),
        cells,
    }
}

fn setting_cell<'a>(runs: impl Iterator<Item = &'a RunRecord>) -> SettingCell {
    let runs: Vec<&RunRecord> = runs.collect();
    let ates: Vec<f64> = runs.iter().map(|r| r.ate).collect();
    let mean_of = |value: fn(&RunRecord) -> Option<f64>| {
        mean(&runs.iter().filter_map(|r| value(r)).collect::<Vec<_>>())
    };
    SettingCell {
        runs: runs.len(),
        failures: runs.iter().filter(|r| r.failed()).count(),
        ate_mean: mean(&ates).unwrap_or(f64::NAN),
        sr_mean: mean_of(|r| r.sr),
        sr_path_ratio_mean: mean_of(|r| r.sr_path_ratio),
        tracked_fraction_mean: mean_of(|r| Some(r.tracked_fraction)),
    }
}

/// CSR(τ) = 100 · #{successful runs with ATE ≤ τ} / #runs: failures stay in the denominator and
/// never count as successes, whatever their conventional ATE.
pub fn csr(runs: &[&RunRecord], threshold: f64) -> f64 {
    if runs.is_empty() {
        return 0.0;
    }
    let good = runs
        .iter()
        .filter(|r| !r.failed() && r.ate <= threshold)
        .count();
    100.0 * good as f64 / runs.len() as f64
}

fn survival_bound(methods: &[MethodSummary], settings: &[String]) -> SurvivalBound {
    let per_setting: Vec<f64> = (0..settings.len())
        .map(|i| {
            methods
                .iter()
                .filter(|m| m.cells[i].runs > 0)
                .map(|m| m.cells[i].ate_mean)
                .fold(f64::INFINITY, f64::min)
        })
        .collect();
    let mut by_category: BTreeMap<String, Vec<f64>> = BTreeMap::new();
    for (setting, bound) in settings.iter().zip(&per_setting) {
        by_category
            .entry(category(setting))
            .or_default()
            .push(*bound);
    }
    SurvivalBound {
        mean: mean(&per_setting).unwrap_or(f64::NAN),
        max: per_setting
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max),
        per_setting,
        categories: by_category
            .into_iter()
            .map(|(category, bounds)| CategoryBound {
                category,
                settings: bounds.len(),
                mean: mean(&bounds).unwrap_or(f64::NAN),
            })
            .collect(),
    }
}

fn setting_tests(method: &str, runs: &[&RunRecord], settings: &[String]) -> Vec<SettingTest> {
    let log_ates = |setting: &str| -> Vec<f64> {
        runs.iter()
            .filter(|r| r.setting == setting)
            .map(|r| r.ate.max(LOG_ATE_FLOOR).ln())
            .collect()
    };
    let clean = log_ates(CLEAN);
    if clean.is_empty() {
        return Vec::new();
    }
    settings
        .iter()
        .filter(|s| *s != CLEAN)
        .map(|setting| {
            let perturbed = log_ates(setting);
            SettingTest {
                method: method.to_string(),
                setting: setting.clone(),
                n: perturbed.len(),
                n_clean: clean.len(),
                mean_log_ate: mean(&perturbed).unwrap_or(f64::NAN),
                mean_log_ate_clean: mean(&clean).unwrap_or(f64::NAN),
                test: welch_t_test(&perturbed, &clean),
            }
        })
        .collect()
}

fn mean(values: &[f64]) -> Option<f64> {
    (!values.is_empty()).then(|| values.iter().sum::<f64>() / values.len() as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every successful run tracked 95 % of its frames over 90 % of the path, jittering to 1.2×
    /// the path length; a failure (`ate` None) has 0 for all three.
    fn run(method: &str, scene: &str, setting: &str, ate: Option<f64>) -> RunRecord {
        let ok = |v: f64| if ate.is_some() { v } else { 0.0 };
        RunRecord {
            method: method.into(),
            sequence: format!("{scene}__{setting}"),
            scene: scene.into(),
            setting: setting.into(),
            repeat: None,
            ate: ate.unwrap_or(1.0),
            sr: Some(ok(0.9)),
            sr_path_ratio: Some(ok(1.2)),
            tracked_fraction: ok(0.95),
            rpe_trans: None,
            rpe_rot_deg: None,
            pairs: None,
            failure: ate.is_none().then(|| "missing".to_string()),
        }
    }

    fn fixture() -> Vec<RunRecord> {
        vec![
            run("a", "r0", "clean", Some(0.01)),
            run("a", "r1", "clean", Some(0.03)),
            run("a", "r0", "fog-3", Some(0.05)),
            run("a", "r1", "fog-3", None),
            run("b", "r0", "clean", Some(0.02)),
            run("b", "r1", "clean", Some(0.02)),
            run("b", "r0", "fog-3", Some(0.15)),
            run("b", "r1", "fog-3", Some(0.25)),
        ]
    }

    #[test]
    fn cells_means_and_failures() {
        let s = summarize(&fixture(), 1.0);
        assert_eq!(s.settings, vec!["clean", "fog-3"]);
        let a = &s.methods[0];
        assert_eq!(a.method, "a");
        assert!((a.cells[0].ate_mean - 0.02).abs() < 1e-15);
        // The failure counts as 1.0 m: (0.05 + 1.0) / 2.
        assert!((a.cells[1].ate_mean - 0.525).abs() < 1e-15);
        assert_eq!((a.cells[1].runs, a.cells[1].failures), (2, 1));
        assert!((a.ate_mean - 0.2725).abs() < 1e-15);
        assert_eq!(a.ate_max, 0.525);
    }

    #[test]
    fn tracking_means_count_failures_as_zero() {
        let s = summarize(&fixture(), 1.0);
        let a = &s.methods[0];
        let fog = &a.cells[1];
        assert_eq!(fog.sr_mean, Some(0.45));
        assert_eq!(fog.sr_path_ratio_mean, Some(0.6));
        assert_eq!(fog.tracked_fraction_mean, Some(0.475));
        assert_eq!(a.sr.min, Some(0.45));
        assert!((a.sr.mean.unwrap() - 0.675).abs() < 1e-15);
        assert_eq!(a.sr_path_ratio.min, Some(0.6));
        let b = &s.methods[1];
        assert_eq!(
            (b.tracked_fraction.mean, b.tracked_fraction.min),
            (Some(0.95), Some(0.95))
        );
    }

    #[test]
    fn csr_keeps_failures_in_the_denominator_only() {
        let s = summarize(&fixture(), 1.0);
        let a = &s.methods[0];
        let at = |t: f64| a.csr.iter().find(|p| p.threshold == t).unwrap().csr;
        assert_eq!(at(0.02), 25.0);
        assert_eq!(at(0.1), 75.0);
        assert_eq!(at(1.0), 75.0);
        let b = &s.methods[1];
        assert_eq!(b.csr[1].csr, 50.0);
        assert_eq!(*b.csr_curve.last().unwrap(), 100.0);
        assert_eq!(s.csr_curve_thresholds.len(), 61);
    }

    #[test]
    fn survival_bound_is_the_best_method_per_setting() {
        let s = summarize(&fixture(), 1.0);
        assert!((s.survival.per_setting[0] - 0.02).abs() < 1e-15);
        assert!((s.survival.per_setting[1] - 0.2).abs() < 1e-15);
        let fog = s
            .survival
            .categories
            .iter()
            .find(|c| c.category == "fog")
            .unwrap();
        assert!((fog.mean - 0.2).abs() < 1e-15);
    }

    #[test]
    fn t_tests_compare_each_setting_with_clean_per_method() {
        let s = summarize(&fixture(), 1.0);
        assert_eq!(s.t_tests.len(), 2);
        let b = &s.t_tests[1];
        assert_eq!(
            (b.method.as_str(), b.setting.as_str(), b.n, b.n_clean),
            ("b", "fog-3", 2, 2)
        );
        assert!(b.test.unwrap().t > 0.0);
    }
}
