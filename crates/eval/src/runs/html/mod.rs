//! `report.html`: the whole report in one file that opens offline: the tables, the failed runs
//! and the figures as inline SVG, with a small inline style; no script, nothing fetched.

mod markup;
mod sections;

use markup::{escape, paragraph, Section};

use super::figures::Figures;
use super::tables::{ATE_TABLE, TRACKING_TABLES};
use super::RunsReport;

const STYLE: &str = "
body { font: 14px/1.45 system-ui, sans-serif; color: #222; max-width: 1500px; margin: 0 auto;
       padding: 16px 24px; }
h1 { font-size: 22px; margin-bottom: 4px; }
h2 { font-size: 18px; border-bottom: 1px solid #ccc; padding-bottom: 3px; margin-top: 32px; }
nav ol { columns: 2; column-gap: 48px; font-size: 13px; }
nav li { break-inside: avoid; }
.scroll { overflow-x: auto; }
table { border-collapse: collapse; font-variant-numeric: tabular-nums; }
th, td { border: 1px solid #ddd; padding: 3px 8px; text-align: right; white-space: nowrap; }
thead th { background: #f0f0f0; position: sticky; top: 0; }
th:first-child { text-align: left; }
tbody th, tfoot th { font-weight: normal; }
tfoot { background: #f7f7f7; }
td.fail { background: #f8d7da; color: #a00; font-weight: 600; }
td.part { background: #fff3cd; }
td.none { color: #999; }
td.reason { text-align: left; white-space: normal; font-family: monospace; }
small { color: #555; }
.plots { display: flex; flex-wrap: wrap; gap: 20px; }
figure { margin: 8px 0; }
svg { max-width: 100%; height: auto; }
#csr svg { max-width: min(100%, 720px); }
";

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
    let nav: String = parts
        .iter()
        .map(|p| format!("<li><a href=\"#{}\">{}</a></li>\n", p.id, escape(&p.title)))
        .collect();
    let body: String = parts.iter().map(Section::to_html).collect();
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>{title}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n<h1>{title}</h1>\n\
         {overview}<nav><ol>\n{nav}</ol></nav>\n{body}</body>\n</html>\n",
        title = escape(&title),
        overview = overview(report),
    )
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
