//! The report's figures, each written as SVG and PNG: the CSR curves, and the bars of every
//! category in `bars/`. Their SVG text is kept for the HTML report, which embeds it.

use std::path::{Path, PathBuf};

use super::category_bars::category_bars;
use super::csr_plot::CsrFigure;
use super::summary::RunsSummary;
use crate::plot::{render_figure, svg_text, Figure};
use crate::EvalError;

/// The folder of the per-category bar plots inside the report folder.
pub const BARS_DIR: &str = "bars";

pub(super) struct Figures {
    pub csr_svg: String,
    /// Per category, in settings order (clean first): its name and its bars as SVG.
    pub category_svgs: Vec<(String, String)>,
    pub files: Vec<PathBuf>,
}

pub(super) fn write_figures(summary: &RunsSummary, out: &Path) -> Result<Figures, EvalError> {
    let mut files = Vec::new();
    let csr_svg = write_svg_and_png(out, "csr", &CsrFigure(summary), &mut files)?;
    let bars_dir = out.join(BARS_DIR);
    std::fs::create_dir_all(&bars_dir).map_err(|e| EvalError::io(&bars_dir, e))?;
    let category_svgs = category_bars(summary)
        .into_iter()
        .map(|bars| {
            let svg = write_svg_and_png(&bars_dir, &bars.category, &bars, &mut files)?;
            Ok((bars.category, svg))
        })
        .collect::<Result<_, EvalError>>()?;
    Ok(Figures {
        csr_svg,
        category_svgs,
        files,
    })
}

/// Writes `dir/<name>.png` and `dir/<name>.svg`; returns the SVG text.
fn write_svg_and_png<F: Figure>(
    dir: &Path,
    name: &str,
    figure: &F,
    files: &mut Vec<PathBuf>,
) -> Result<String, EvalError> {
    let png = dir.join(format!("{name}.png"));
    render_figure(&png, figure)?;
    files.push(png);
    let path = dir.join(format!("{name}.svg"));
    let svg = svg_text(&path, figure)?;
    std::fs::write(&path, &svg).map_err(|e| EvalError::io(&path, e))?;
    files.push(path);
    Ok(svg)
}
