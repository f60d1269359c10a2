//! The report files of `rslam eval --runs`: Markdown, CSV, JSON, HTML and the figures.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::collect::RunRecord;
use super::figures::write_figures;
use super::html::html_report;
use super::summary::{RunsSummary, SettingCell};
use super::tables::{optional, MetricTable, ATE_TABLE, TRACKING_TABLES};
use super::RunsReport;
use crate::EvalError;

/// Writes every report file into `out` (created if needed); returns the paths written.
pub fn write_report(report: &RunsReport, out: &Path) -> Result<Vec<PathBuf>, EvalError> {
    std::fs::create_dir_all(out).map_err(|e| EvalError::io(out, e))?;
    let s = &report.summary;
    let json = serde_json::to_string_pretty(report).map_err(|e| EvalError::BadRuns {
        path: out.join("report.json"),
        message: e.to_string(),
    })?;
    let mut files = vec![("report.md", markdown(report)), ("report.json", json)];
    for table in std::iter::once(&ATE_TABLE).chain(&TRACKING_TABLES) {
        files.push((table.csv, matrix_csv(s, table)));
    }
    files.extend([
        ("csr.csv", csr_csv(s)),
        ("csr_curve.csv", csr_curve_csv(s)),
        ("welch.csv", welch_csv(s)),
        ("runs.csv", runs_csv(&report.runs)),
    ]);
    let mut written = Vec::new();
    for (name, text) in files {
        written.push(write_text(out, name, &text)?);
    }
    let figures = write_figures(s, out)?;
    let html = html_report(report, &figures);
    written.extend(figures.files);
    written.push(write_text(out, "report.html", &html)?);
    Ok(written)
}

fn write_text(out: &Path, name: &str, text: &str) -> Result<PathBuf, EvalError> {
    let path = out.join(name);
    std::fs::write(&path, text).map_err(|e| EvalError::io(&path, e))?;
    Ok(path)
}

fn matrix_csv(s: &RunsSummary, table: &MetricTable) -> String {
    let mut out = format!(
        "method,{},{}\n",
        s.settings
            .iter()
            .map(|x| csv_field(x))
            .collect::<Vec<_>>()
            .join(","),
        table.over_settings.join(",")
    );
    for m in &s.methods {
        let cells: Vec<String> = m.cells.iter().map(|c| number((table.cell)(c))).collect();
        let [first, second] = (table.over_settings_values)(m);
        let _ = writeln!(
            out,
            "{},{},{},{}",
            csv_field(&m.method),
            cells.join(","),
            number(first),
            number(second)
        );
    }
    if table.survival {
        let b = &s.survival;
        let cells: Vec<String> = b.per_setting.iter().map(|v| number(Some(*v))).collect();
        let _ = writeln!(
            out,
            "survival upper bound,{},{},{}",
            cells.join(","),
            number(Some(b.mean)),
            number(Some(b.max))
        );
    }
    out
}

fn csr_csv(s: &RunsSummary) -> String {
    let mut out = String::from("method,runs,failures");
    for t in super::summary::CSR_THRESHOLDS {
        let _ = write!(out, ",csr_{t}");
    }
    out.push('\n');
    for m in &s.methods {
        let values: Vec<String> = m.csr.iter().map(|p| number(Some(p.csr))).collect();
        let _ = writeln!(
            out,
            "{},{},{},{}",
            csv_field(&m.method),
            m.runs,
            m.failures,
            values.join(",")
        );
    }
    out
}

fn csr_curve_csv(s: &RunsSummary) -> String {
    let names: Vec<String> = s.methods.iter().map(|m| csv_field(&m.method)).collect();
    let mut out = format!("threshold_m,{}\n", names.join(","));
    for (i, t) in s.csr_curve_thresholds.iter().enumerate() {
        let values: Vec<String> = s
            .methods
            .iter()
            .map(|m| number(Some(m.csr_curve[i])))
            .collect();
        let _ = writeln!(out, "{t},{}", values.join(","));
    }
    out
}

fn welch_csv(s: &RunsSummary) -> String {
    let mut out = String::from("method,setting,n,n_clean,mean_log_ate,mean_log_ate_clean,t,df,p\n");
    for t in &s.t_tests {
        let _ = writeln!(
            out,
            "{},{},{},{},{},{},{},{},{}",
            csv_field(&t.method),
            csv_field(&t.setting),
            t.n,
            t.n_clean,
            number(Some(t.mean_log_ate)),
            number(Some(t.mean_log_ate_clean)),
            number(t.test.map(|w| w.t)),
            number(t.test.map(|w| w.df)),
            number(t.test.map(|w| w.p)),
        );
    }
    out
}

fn runs_csv(runs: &[RunRecord]) -> String {
    let mut out = String::from(
        "method,sequence,scene,setting,repeat,status,ate,sr,sr_path_ratio,tracked_fraction,rpe_trans,\
         rpe_rot_deg,pairs,failure\n",
    );
    for r in runs {
        let _ = writeln!(
            out,
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
            csv_field(&r.method),
            csv_field(&r.sequence),
            csv_field(&r.scene),
            csv_field(&r.setting),
            csv_field(r.repeat.as_deref().unwrap_or("")),
            if r.failed() { "F" } else { "ok" },
            number(Some(r.ate)),
            number(r.sr),
            number(r.sr_path_ratio),
            number(Some(r.tracked_fraction)),
            number(r.rpe_trans),
            number(r.rpe_rot_deg),
            r.pairs.map_or(String::new(), |p| p.to_string()),
            csv_field(r.failure.as_deref().unwrap_or("")),
        );
    }
    out
}

fn markdown(report: &RunsReport) -> String {
    let s = &report.summary;
    let runs = report.runs.len();
    let failures = report.runs.iter().filter(|r| r.failed()).count();
    let mut out = format!(
        "# rslam eval: {} methods × {} settings\n\n{runs} runs, {failures} failed (F: counted as \
         ATE {} m; SR, SR path ratio and tracked fraction 0).\n\n",
        s.methods.len(),
        s.settings.len(),
        s.failure_ate
    );
    let header = |first: &str, last: [&str; 2]| {
        let cols: Vec<&str> = std::iter::once(first)
            .chain(s.settings.iter().map(String::as_str))
            .chain(last)
            .collect();
        format!("| {} |\n|{}\n", cols.join(" | "), "---|".repeat(cols.len()))
    };

    let _ = write!(
        out,
        "## {}\n\nMean over scenes and repeats; `(kF)`: k failed runs among them.\n\n",
        ATE_TABLE.title
    );
    out.push_str(&header("method", ATE_TABLE.over_settings));
    for m in &s.methods {
        let cells: Vec<String> = m.cells.iter().map(ate_cell).collect();
        let _ = writeln!(
            out,
            "| {} | {} | {:.4} | {:.4} |",
            m.method,
            cells.join(" | "),
            m.ate_mean,
            m.ate_max
        );
    }
    let bound: Vec<String> = s
        .survival
        .per_setting
        .iter()
        .map(|v| format!("{v:.4}"))
        .collect();
    let _ = writeln!(
        out,
        "| survival upper bound | {} | {:.4} | {:.4} |\n",
        bound.join(" | "),
        s.survival.mean,
        s.survival.max
    );

    out.push_str("## Survival upper bound per category [m]\n\n| category | settings | mean |\n|---|---|---|\n");
    for c in &s.survival.categories {
        let _ = writeln!(out, "| {} | {} | {:.4} |", c.category, c.settings, c.mean);
    }

    for table in &TRACKING_TABLES {
        let _ = write!(
            out,
            "\n## {}\n\n{} Mean over scenes and repeats (failures count 0).\n\n",
            table.title, table.note
        );
        out.push_str(&header("method", table.over_settings));
        for m in &s.methods {
            let cells: Vec<String> = m
                .cells
                .iter()
                .map(|c| optional((table.cell)(c), table.decimals))
                .collect();
            let [first, second] = (table.over_settings_values)(m);
            let _ = writeln!(
                out,
                "| {} | {} | {} | {} |",
                m.method,
                cells.join(" | "),
                optional(first, table.decimals),
                optional(second, table.decimals)
            );
        }
    }

    out.push_str("\n## CSR [%] over all runs of a method\n\n| method | runs | failed |");
    for t in super::summary::CSR_THRESHOLDS {
        let _ = write!(out, " CSR@{t} m |");
    }
    out.push_str("\n|---|---|---|---|---|---|\n");
    for m in &s.methods {
        let values: Vec<String> = m.csr.iter().map(|p| format!("{:.1}", p.csr)).collect();
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} |",
            m.method,
            m.runs,
            m.failures,
            values.join(" | ")
        );
    }

    out.push_str("\n## Welch's t-test against clean (ln ATE, over scenes and repeats)\n\n");
    out.push_str("| method | setting | n | n clean | mean ln ATE | mean ln ATE clean | t | df | p |\n|---|---|---|---|---|---|---|---|---|\n");
    for t in &s.t_tests {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {:.3} | {:.3} | {} | {} | {} |",
            t.method,
            t.setting,
            t.n,
            t.n_clean,
            t.mean_log_ate,
            t.mean_log_ate_clean,
            optional(t.test.map(|w| w.t), 3),
            optional(t.test.map(|w| w.df), 1),
            t.test.map_or("n/a".to_string(), |w| format!("{:.3e}", w.p)),
        );
    }

    let failed: Vec<&RunRecord> = report.runs.iter().filter(|r| r.failed()).collect();
    if !failed.is_empty() {
        out.push_str(
            "\n## Failed runs\n\n| method | sequence | repeat | reason |\n|---|---|---|---|\n",
        );
        for r in failed {
            let reason = r.failure.as_deref().unwrap_or("").replace('|', "\\|");
            let _ = writeln!(
                out,
                "| {} | {} | {} | {reason} |",
                r.method,
                r.sequence,
                r.repeat.as_deref().unwrap_or("-")
            );
        }
    }
    if !report.unmatched.is_empty() {
        out.push_str("\n## Ignored (no dataset of that name)\n\n");
        for p in &report.unmatched {
            let _ = writeln!(out, "- {}", p.display());
        }
    }
    out
}

/// A few lines per method for the console.
pub fn summary_text(report: &RunsReport) -> String {
    let s = &report.summary;
    let mut out = format!(
        "{} methods, {} settings, {} runs ({} failed)\n\n{:<16} {:>5} {:>6} {:>10} {:>10} {:>7} {:>7}",
        s.methods.len(),
        s.settings.len(),
        report.runs.len(),
        report.runs.iter().filter(|r| r.failed()).count(),
        "method",
        "runs",
        "failed",
        "ATE mean",
        "ATE max",
        "SR mean",
        "tracked"
    );
    for t in super::summary::CSR_THRESHOLDS {
        let _ = write!(out, " {:>9}", format!("CSR@{t}"));
    }
    out.push('\n');
    for m in &s.methods {
        let _ = write!(
            out,
            "{:<16} {:>5} {:>6} {:>10.4} {:>10.4} {:>7} {:>7}",
            m.method,
            m.runs,
            m.failures,
            m.ate_mean,
            m.ate_max,
            optional(m.sr.mean, 3),
            optional(m.tracked_fraction.mean, 3)
        );
        for p in &m.csr {
            let _ = write!(out, " {:>8.1}%", p.csr);
        }
        out.push('\n');
    }
    out
}

fn ate_cell(c: &SettingCell) -> String {
    match c.failures {
        0 => format!("{:.4}", c.ate_mean),
        f if f == c.runs => "F".to_string(),
        f => format!("{:.4} ({f}F)", c.ate_mean),
    }
}

/// Full precision in CSV; empty when absent or not finite.
fn number(v: Option<f64>) -> String {
    v.filter(|v| v.is_finite())
        .map_or(String::new(), |v| v.to_string())
}

/// `text` as one CSV field: quoted (quotes doubled) where it holds a comma, a quote or a line
/// break.
pub fn csv_field(text: &str) -> String {
    if text.contains([',', '"', '\n']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}
