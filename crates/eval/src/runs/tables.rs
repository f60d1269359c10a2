//! The per-setting metric tables, described once for the CSV, Markdown and HTML reports, and the
//! number formats they share.

use super::summary::{MethodSummary, SettingCell};

/// One metric per method × setting, with two columns over the settings.
pub(super) struct MetricTable {
    pub csv: &'static str,
    pub title: &'static str,
    pub note: &'static str,
    pub decimals: usize,
    pub cell: fn(&SettingCell) -> Option<f64>,
    /// The names of the two columns over the settings, and a method's values in them.
    pub over_settings: [&'static str; 2],
    pub over_settings_values: fn(&MethodSummary) -> [Option<f64>; 2],
    /// Whether the table carries the survival upper bound (best method per setting).
    pub survival: bool,
}

pub(super) const ATE_TABLE: MetricTable = MetricTable {
    csv: "ate.csv",
    title: "ATE [m] per method × setting",
    note: "A failed run counts as the failure ATE.",
    decimals: 4,
    cell: |c| Some(c.ate_mean),
    over_settings: ["mean", "max"],
    over_settings_values: |m| [Some(m.ate_mean), Some(m.ate_max)],
    survival: true,
};

const MEAN_AND_MIN: [&str; 2] = ["mean", "min"];

pub(super) const TRACKING_TABLES: [MetricTable; 3] = [
    MetricTable {
        csv: "sr.csv",
        title: "SR (covered fraction of the ground-truth path) per method × setting",
        note: "Ground-truth segments whose two ends are paired with an estimate pose, over the \
               whole ground-truth path: in [0, 1], jitter does not change it.",
        decimals: 3,
        cell: |c| c.sr_mean,
        over_settings: MEAN_AND_MIN,
        over_settings_values: |m| [m.sr.mean, m.sr.min],
        survival: false,
    },
    MetricTable {
        csv: "sr_path_ratio.csv",
        title: "SR path ratio (the paper's SR formula) per method × setting",
        note: "Estimate path length over ground-truth path length, as the paper writes SR, for \
               comparing with it: jitter adds path length, so it grows when tracking gets worse \
               and can exceed 1.",
        decimals: 3,
        cell: |c| c.sr_path_ratio_mean,
        over_settings: MEAN_AND_MIN,
        over_settings_values: |m| [m.sr_path_ratio.mean, m.sr_path_ratio.min],
        survival: false,
    },
    MetricTable {
        csv: "tracked_fraction.csv",
        title: "Tracked fraction of frames per method × setting",
        note: "Ground-truth poses paired with an estimate pose, over all ground-truth poses.",
        decimals: 3,
        cell: |c| c.tracked_fraction_mean,
        over_settings: MEAN_AND_MIN,
        over_settings_values: |m| [m.tracked_fraction.mean, m.tracked_fraction.min],
        survival: false,
    },
];

/// `v` with `decimals` decimals, `n/a` when absent.
pub(super) fn optional(v: Option<f64>, decimals: usize) -> String {
    v.map_or("n/a".to_string(), |v| format!("{v:.decimals$}"))
}
