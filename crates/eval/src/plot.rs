//! Figures as PNG or SVG (chosen by the file extension): the top view of one evaluation and,
//! for `runs`, the CSR curves and the per-category bars.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::{EvalError, Evaluation};

/// Something drawable on any plotters backend.
pub(crate) trait Figure {
    /// Width and height in pixels.
    fn size(&self) -> (u32, u32);
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String>;
}

/// Draws `figure` into `path`: `.png` or `.svg`.
pub(crate) fn render_figure<F: Figure>(path: &Path, figure: &F) -> Result<(), EvalError> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let result = match extension.as_deref() {
        Some("png") => draw_on(BitMapBackend::new(path, figure.size()), figure),
        Some("svg") => draw_on(SVGBackend::new(path, figure.size()), figure),
        _ => Err("expected a file name ending in .png or .svg".to_string()),
    };
    result.map_err(|message| EvalError::Plot {
        path: path.to_path_buf(),
        message,
    })
}

/// The SVG document of `figure`, for writing or embedding; `path` names it in errors.
pub(crate) fn svg_text<F: Figure>(path: &Path, figure: &F) -> Result<String, EvalError> {
    let mut text = String::new();
    draw_on(SVGBackend::with_string(&mut text, figure.size()), figure).map_err(|message| {
        EvalError::Plot {
            path: path.to_path_buf(),
            message,
        }
    })?;
    Ok(text)
}

fn draw_on<DB: DrawingBackend, F: Figure>(backend: DB, figure: &F) -> Result<(), String> {
    let root = backend.into_drawing_area();
    figure.draw(&root)?;
    root.present().map_err(|e| e.to_string())
}

/// Draws the top view (x–y) of the ground truth and the aligned estimate, beside the ATE of each
/// associated pose over time.
pub fn plot_evaluation(path: &Path, evaluation: &Evaluation) -> Result<(), EvalError> {
    render_figure(path, &EvaluationFigure(evaluation))
}

struct EvaluationFigure<'a>(&'a Evaluation);

const GROUND_TRUTH_COLOR: RGBColor = RGBColor(90, 90, 90);
const ESTIMATE_COLOR: RGBColor = RGBColor(31, 119, 180);
const ERROR_COLOR: RGBColor = RGBColor(214, 39, 40);

impl Figure for EvaluationFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1400, 640)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let e = self.0;
        let err = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
        root.fill(&WHITE).map_err(err)?;
        let (left, right) = root.split_horizontally(640);

        // Equal axis scales: both ranges get the larger span.
        let points = || e.series.gt_positions.iter().chain(&e.series.est_positions);
        let (lo, hi) = points().fold(
            (glam::DVec2::INFINITY, glam::DVec2::NEG_INFINITY),
            |(lo, hi), p| (lo.min(p.truncate()), hi.max(p.truncate())),
        );
        let half = ((hi - lo).max_element() * 0.55).max(1e-3);
        let centre = (lo + hi) / 2.0;
        let mut top = ChartBuilder::on(&left)
            .caption("top view (x-y), estimate aligned", ("sans-serif", 20))
            .margin(12)
            .x_label_area_size(36)
            .y_label_area_size(56)
            .build_cartesian_2d(
                centre.x - half..centre.x + half,
                centre.y - half..centre.y + half,
            )
            .map_err(err)?;
        top.configure_mesh()
            .x_desc("x [m]")
            .y_desc("y [m]")
            .draw()
            .map_err(err)?;
        let xy = |v: &Vec<glam::DVec3>| v.iter().map(|p| (p.x, p.y)).collect::<Vec<_>>();
        top.draw_series(LineSeries::new(
            xy(&e.series.gt_positions),
            GROUND_TRUTH_COLOR.stroke_width(2),
        ))
        .map_err(err)?
        .label("ground truth")
        .legend(|(x, y)| {
            PathElement::new([(x, y), (x + 20, y)], GROUND_TRUTH_COLOR.stroke_width(2))
        });
        top.draw_series(LineSeries::new(
            xy(&e.series.est_positions),
            ESTIMATE_COLOR.stroke_width(2),
        ))
        .map_err(err)?
        .label("estimate")
        .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], ESTIMATE_COLOR.stroke_width(2)));
        top.configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(err)?;

        let t_end = e.series.pair_times.last().copied().unwrap_or(0.0).max(1e-6);
        let e_max = (e.ate.max * 1.1).max(1e-9);
        let mut errors = ChartBuilder::on(&right)
            .caption(
                format!("ATE per pose (rmse {:.4} m)", e.ate.rmse),
                ("sans-serif", 20),
            )
            .margin(12)
            .x_label_area_size(36)
            .y_label_area_size(64)
            .build_cartesian_2d(0.0..t_end, 0.0..e_max)
            .map_err(err)?;
        errors
            .configure_mesh()
            .x_desc("time since first pair [s]")
            .y_desc("ATE [m]")
            .draw()
            .map_err(err)?;
        let series = e
            .series
            .pair_times
            .iter()
            .copied()
            .zip(e.series.ate_errors.iter().copied());
        errors
            .draw_series(LineSeries::new(series, ERROR_COLOR.stroke_width(1)))
            .map_err(err)?;
        errors
            .draw_series(LineSeries::new(
                [(0.0, e.ate.rmse), (t_end, e.ate.rmse)],
                BLACK.stroke_width(1),
            ))
            .map_err(err)?;
        Ok(())
    }
}
