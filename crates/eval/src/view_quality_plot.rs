//! The figure the paper draws for SplaTAM: each run's rendered-view quality against its ATE, PSNR
//! on the left and depth L1 on the right, one colour per method.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::plot::{render_figure, Figure};
use crate::EvalError;

/// One run: its method, ATE and the views' measures (non-finite values are left out).
#[derive(Clone, Debug, PartialEq)]
pub struct ViewQualityPoint {
    pub method: String,
    pub ate_m: f64,
    pub psnr_db: Option<f64>,
    pub depth_l1_cm: Option<f64>,
}

/// Draws the runs into `path` (`.png` or `.svg`).
pub fn plot_view_quality_against_ate(
    path: &Path,
    points: &[ViewQualityPoint],
) -> Result<(), EvalError> {
    render_figure(path, &ViewQualityFigure(points))
}

struct ViewQualityFigure<'a>(&'a [ViewQualityPoint]);

type Measure = fn(&ViewQualityPoint) -> Option<f64>;

impl Figure for ViewQualityFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1200, 500)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let err = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
        root.fill(&WHITE).map_err(err)?;
        let mut methods: Vec<&str> = self.0.iter().map(|p| p.method.as_str()).collect();
        methods.sort();
        methods.dedup();
        let panels = root.split_evenly((1, 2));
        let measures: [(&str, Measure); 2] = [
            ("PSNR [dB]", |p| p.psnr_db),
            ("depth L1 [cm]", |p| p.depth_l1_cm),
        ];
        for (panel, (label, measure)) in panels.iter().zip(measures) {
            let points: Vec<(&str, f64, f64)> = self
                .0
                .iter()
                .filter_map(|p| Some((p.method.as_str(), p.ate_m, measure(p)?)))
                .filter(|(_, ate, v)| ate.is_finite() && v.is_finite())
                .collect();
            let span = |values: &mut dyn Iterator<Item = f64>| {
                let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                    (lo.min(v), hi.max(v))
                });
                if lo.is_finite() {
                    let pad = ((hi - lo) * 0.05).max(1e-6);
                    (lo - pad)..(hi + pad)
                } else {
                    0.0..1.0
                }
            };
            let x_range = span(&mut points.iter().map(|p| p.1));
            let y_range = span(&mut points.iter().map(|p| p.2));
            let mut chart = ChartBuilder::on(panel)
                .caption(format!("{label} against ATE"), ("sans-serif", 20))
                .margin(14)
                .x_label_area_size(40)
                .y_label_area_size(56)
                .build_cartesian_2d(x_range, y_range)
                .map_err(err)?;
            chart
                .configure_mesh()
                .x_desc("ATE [m]")
                .y_desc(label)
                .draw()
                .map_err(err)?;
            for (i, method) in methods.iter().enumerate() {
                let color = Palette99::pick(i).to_rgba();
                let own = points.iter().filter(|p| p.0 == *method);
                chart
                    .draw_series(own.map(|p| Circle::new((p.1, p.2), 4, color.filled())))
                    .map_err(err)?
                    .label(*method)
                    .legend(move |(x, y)| Circle::new((x + 10, y), 4, color.filled()));
            }
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperRight)
                .background_style(WHITE.mix(0.8))
                .border_style(BLACK)
                .draw()
                .map_err(err)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_png_and_svg_with_every_method_named() {
        let dir = tempfile::tempdir().unwrap();
        let points = [
            ViewQualityPoint {
                method: "splatam".into(),
                ate_m: 0.01,
                psnr_db: Some(30.0),
                depth_l1_cm: Some(1.0),
            },
            ViewQualityPoint {
                method: "splatam".into(),
                ate_m: 0.2,
                psnr_db: Some(f64::INFINITY),
                depth_l1_cm: None,
            },
            ViewQualityPoint {
                method: "other".into(),
                ate_m: 0.1,
                psnr_db: Some(20.0),
                depth_l1_cm: Some(4.0),
            },
        ];
        let svg = dir.path().join("views.svg");
        plot_view_quality_against_ate(&svg, &points).unwrap();
        let text = std::fs::read_to_string(&svg).unwrap();
        assert!(text.contains("splatam") && text.contains("other") && text.contains("PSNR"));
        let png = dir.path().join("views.png");
        plot_view_quality_against_ate(&png, &points).unwrap();
        assert!(std::fs::metadata(&png).unwrap().len() > 1000);
        let bad = plot_view_quality_against_ate(&dir.path().join("views.txt"), &points);
        assert!(bad.unwrap_err().to_string().contains(".png or .svg"));
    }
}
