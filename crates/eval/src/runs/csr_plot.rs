//! CSR curves: one line per method, CSR (%) over the ATE threshold (log scale).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::summary::RunsSummary;
use crate::plot::Figure;

pub(super) struct CsrFigure<'a>(pub(super) &'a RunsSummary);

impl Figure for CsrFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (900, 600)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let s = self.0;
        let err = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
        root.fill(&WHITE).map_err(err)?;
        let lo = s.csr_curve_thresholds.first().copied().unwrap_or(1e-3);
        let hi = s.csr_curve_thresholds.last().copied().unwrap_or(1.0);
        let mut chart = ChartBuilder::on(root)
            .caption("cumulative success rate", ("sans-serif", 22))
            .margin(14)
            .x_label_area_size(40)
            .y_label_area_size(50)
            .build_cartesian_2d((lo..hi).log_scale(), 0.0..100.0)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("ATE threshold τ [m]")
            .y_desc("CSR [%]")
            .draw()
            .map_err(err)?;
        for (i, m) in s.methods.iter().enumerate() {
            let color = Palette99::pick(i).to_rgba();
            let points = s
                .csr_curve_thresholds
                .iter()
                .copied()
                .zip(m.csr_curve.iter().copied());
            chart
                .draw_series(LineSeries::new(points, color.stroke_width(2)))
                .map_err(err)?
                .label(&m.method)
                .legend(move |(x, y)| {
                    PathElement::new([(x, y), (x + 20, y)], color.stroke_width(2))
                });
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(err)?;
        Ok(())
    }
}
