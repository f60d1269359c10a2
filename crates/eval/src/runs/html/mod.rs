//! `report.html`: the whole report in one file: the tables, the failed runs and the figures as
//! inline SVG.

mod sections;

use crate::html_page::{page, paragraph};

use super::figures::Figures;
use super::tables::{ATE_TABLE, TRACKING_TABLES};
use super::RunsReport;

/// The HTML report of `report`, embedding the SVG text of `figures`.
pub(super) fn html_report(report: &RunsReport, figures: &Figures) -> String {
    let s = &report.summary;
    let title = format!(
        "rslam eval: {} methods × {} settings",
        s.methods.len(),
        s.settings.len()
    );
    let mut parts = vec![
        sections::metric(s, &ATE_TABLE),
        sections::survival_by_category(s),
        sections::csr(s, &figures.csr_svg),
        sections::category_plots(&figures.category_svgs),
    ];
    parts.extend(
        TRACKING_TABLES
            .iter()
            .map(|table| sections::metric(s, table)),
    );
    parts.extend([sections::welch(s), sections::failures(&report.runs)]);
    parts.extend(sections::ignored(&report.unmatched));
    page(&title, &overview(report), &parts)
}

fn overview(report: &RunsReport) -> String {
    let failed = report.runs.iter().filter(|r| r.failed()).count();
    paragraph(&format!(
        "{} runs, {failed} failed. A failed run (the runner's .failed record, or a missing, \
         empty, unreadable or unassociable estimate) counts as ATE {} m and 0 for SR, SR path \
         ratio and tracked fraction. In the tables, F n/n marks a setting where all n runs \
         (scenes × repeats) failed, k/n F one where k of them did.",
        report.runs.len(),
        report.summary.failure_ate
    ))
}
