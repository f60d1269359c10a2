//! The sections of the HTML report, one function each.

use std::path::PathBuf;

use crate::html_page::{escape, paragraph, Cell, Section, Table};
use crate::runs::collect::RunRecord;
use crate::runs::summary::{RunsSummary, SettingCell, CSR_THRESHOLDS};
use crate::runs::tables::{optional, MetricTable};

/// A metric per setting (rows) and method (columns), the survival upper bound beside the ATE,
/// and the values over settings at the foot.
pub(super) fn metric(s: &RunsSummary, table: &MetricTable) -> Section {
    let survival = table.survival.then_some("survival upper bound");
    let mut html = Table::with_head(
        std::iter::once("setting")
            .chain(s.methods.iter().map(|m| m.method.as_str()))
            .chain(survival),
    );
    for (i, setting) in s.settings.iter().enumerate() {
        let cells = s.methods.iter().map(|m| {
            let cell = &m.cells[i];
            metric_cell(cell, (table.cell)(cell), table.decimals)
        });
        let bound = survival.map(|_| Cell::text(&optional(Some(s.survival.per_setting[i]), 4)));
        html.rows.push(
            std::iter::once(Cell::text(setting))
                .chain(cells)
                .chain(bound)
                .collect(),
        );
    }
    let survival_over_settings = [s.survival.mean, s.survival.max];
    for (k, name) in table.over_settings.iter().enumerate() {
        let values = s.methods.iter().map(|m| {
            Cell::text(&optional(
                (table.over_settings_values)(m)[k],
                table.decimals,
            ))
        });
        let bound = survival.map(|_| Cell::text(&optional(Some(survival_over_settings[k]), 4)));
        html.foot.push(
            std::iter::once(Cell::text(&format!("{name} over settings")))
                .chain(values)
                .chain(bound)
                .collect(),
        );
    }
    Section {
        id: table.csv.trim_end_matches(".csv"),
        title: table.title.to_string(),
        body: paragraph(&format!("{} Mean over scenes and repeats.", table.note)) + &html.to_html(),
    }
}

/// A cell's value, with its failures: `F n/n` when every run failed, `k/n F` when some did.
fn metric_cell(cell: &SettingCell, value: Option<f64>, decimals: usize) -> Cell {
    let runs = cell.runs;
    match cell.failures {
        _ if runs == 0 => Cell::text("no run").with_class("none"),
        0 => Cell::text(&optional(value, decimals)),
        f if f == runs => Cell::html(format!("F <small>{f}/{runs}</small>")).with_class("fail"),
        f => Cell::html(format!(
            "{} <small>{f}/{runs} F</small>",
            escape(&optional(value, decimals))
        ))
        .with_class("part"),
    }
}

pub(super) fn survival_by_category(s: &RunsSummary) -> Section {
    let mut table = Table::with_head(["category", "settings", "mean bound [m]"]);
    for c in &s.survival.categories {
        table.rows.push(vec![
            Cell::text(&c.category),
            Cell::text(&c.settings.to_string()),
            Cell::text(&optional(Some(c.mean), 4)),
        ]);
    }
    Section {
        id: "survival",
        title: "Survival upper bound per category [m]".to_string(),
        body: paragraph(
            "The survival upper bound of a setting is the lowest mean ATE any method reached \
             there (last column of the ATE table); here its mean over each category's settings.",
        ) + &table.to_html(),
    }
}

pub(super) fn csr(s: &RunsSummary, curve_svg: &str) -> Section {
    let thresholds: Vec<String> = CSR_THRESHOLDS
        .iter()
        .map(|t| format!("CSR@{t} m"))
        .collect();
    let mut table = Table::with_head(
        ["method", "runs", "failed"]
            .into_iter()
            .chain(thresholds.iter().map(String::as_str)),
    );
    for m in &s.methods {
        table.rows.push(
            [
                Cell::text(&m.method),
                Cell::text(&m.runs.to_string()),
                Cell::text(&m.failures.to_string()),
            ]
            .into_iter()
            .chain(m.csr.iter().map(|p| Cell::text(&format!("{:.1} %", p.csr))))
            .collect(),
        );
    }
    Section {
        id: "csr",
        title: "Cumulative success rate".to_string(),
        body: paragraph(
            "CSR(τ): the share of all runs of a method that succeeded with ATE ≤ τ; failed runs \
             stay in the denominator and never count as successes.",
        ) + &table.to_html()
            + &format!("<figure>\n{curve_svg}</figure>\n"),
    }
}

pub(super) fn category_plots(category_svgs: &[(String, String)]) -> Section {
    let figures: String = category_svgs
        .iter()
        .map(|(category, svg)| {
            format!(
                "<figure id=\"bars-{}\">\n{svg}</figure>\n",
                escape(category)
            )
        })
        .collect();
    Section {
        id: "bars",
        title: "Mean ATE and SR per setting, by category".to_string(),
        body: paragraph(
            "One bar per method; a failed run counts with the failure ATE (dashed line) and SR 0, \
             and the red count above an ATE bar is its number of failed runs.",
        ) + &format!("<div class=\"plots\">\n{figures}</div>\n"),
    }
}

pub(super) fn welch(s: &RunsSummary) -> Section {
    let mut table = Table::with_head([
        "method",
        "setting",
        "n",
        "n clean",
        "mean ln ATE",
        "mean ln ATE clean",
        "t",
        "df",
        "p",
    ]);
    for t in &s.t_tests {
        table.rows.push(vec![
            Cell::text(&t.method),
            Cell::text(&t.setting),
            Cell::text(&t.n.to_string()),
            Cell::text(&t.n_clean.to_string()),
            Cell::text(&optional(Some(t.mean_log_ate), 3)),
            Cell::text(&optional(Some(t.mean_log_ate_clean), 3)),
            Cell::text(&optional(t.test.map(|w| w.t), 3)),
            Cell::text(&optional(t.test.map(|w| w.df), 1)),
            Cell::text(&t.test.map_or("n/a".to_string(), |w| format!("{:.3e}", w.p))),
        ]);
    }
    let body = if s.t_tests.is_empty() {
        paragraph("No method has clean runs to compare with.")
    } else {
        paragraph(
            "Each setting against clean, per method, on ln max(ATE, 1 µm) over scenes and \
             repeats (failed runs with the failure ATE); n/a where a side has fewer than two \
             runs or no variance.",
        ) + &table.to_html()
    };
    Section {
        id: "welch",
        title: "Welch's t-test against clean".to_string(),
        body,
    }
}

pub(super) fn failures(runs: &[RunRecord]) -> Section {
    let mut table = Table::with_head(["method", "sequence", "repeat", "reason"]);
    for r in runs.iter().filter(|r| r.failed()) {
        table.rows.push(vec![
            Cell::text(&r.method),
            Cell::text(&r.sequence),
            Cell::text(r.repeat.as_deref().unwrap_or("-")),
            Cell::text(r.failure.as_deref().unwrap_or("")).with_class("reason"),
        ]);
    }
    Section {
        id: "failures",
        title: format!("Failed runs ({})", table.rows.len()),
        body: if table.rows.is_empty() {
            paragraph("No run failed.")
        } else {
            table.to_html()
        },
    }
}

/// The estimate files that matched no dataset sequence; `None` when there are none.
pub(super) fn ignored(unmatched: &[PathBuf]) -> Option<Section> {
    let items: String = unmatched
        .iter()
        .map(|p| format!("<li>{}</li>\n", escape(&p.display().to_string())))
        .collect();
    (!unmatched.is_empty()).then(|| Section {
        id: "ignored",
        title: "Ignored (no dataset of that name)".to_string(),
        body: format!("<ul>\n{items}</ul>\n"),
    })
}
