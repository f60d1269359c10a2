//! Per category of settings, grouped bars: mean ATE (log scale) and mean SR per setting, one bar
//! per method. Failed runs count with the failure ATE and SR 0, so failures show as tall ATE bars;
//! an ATE bar with failures carries their count (`2F`).

use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::naming::category;
use super::summary::{RunsSummary, SettingCell};
use crate::grouped_bars::{bar_span, method_color, Legend, CHAR_WIDTH, FONT, TITLE_HEIGHT};
use crate::plot::Figure;

/// The bars of one category: its settings, as indices into [`RunsSummary::settings`].
pub(super) struct CategoryBars<'a> {
    summary: &'a RunsSummary,
    pub(super) category: String,
    settings: Vec<usize>,
}

/// One figure per category, in settings order (clean first).
pub(super) fn category_bars(summary: &RunsSummary) -> Vec<CategoryBars<'_>> {
    let mut figures: Vec<CategoryBars> = Vec::new();
    for (i, setting) in summary.settings.iter().enumerate() {
        let name = category(setting);
        match figures.iter_mut().find(|f| f.category == name) {
            Some(figure) => figure.settings.push(i),
            None => figures.push(CategoryBars {
                summary,
                category: name,
                settings: vec![i],
            }),
        }
    }
    figures
}

const PANEL_HEIGHT: u32 = 250;
/// Left of the plot: the y labels and the margin.
const Y_LABEL_AREA: u32 = 70;
const PLOT_MARGIN: u32 = 10;
const MIN_WIDTH: u32 = 480;
const BAR_WIDTH: u32 = 16;
const GROUP_GAP: u32 = 24;
/// Headroom above the highest ATE bar (log scale) for the failure counts.
const ATE_HEADROOM: f64 = 3.0;
/// The lowest ATE shown, metres: a perfect run still gets a visible stub.
const ATE_FLOOR: f64 = 1e-4;

impl CategoryBars<'_> {
    fn names(&self) -> Vec<&str> {
        self.settings
            .iter()
            .map(|&i| self.summary.settings[i].as_str())
            .collect()
    }

    fn legend(&self) -> Legend<'_> {
        Legend {
            names: self
                .summary
                .methods
                .iter()
                .map(|m| m.method.as_str())
                .collect(),
            left: Y_LABEL_AREA,
        }
    }

    /// The cells of method `m` that hold runs, with their setting's position in this category.
    fn cells(&self, m: usize) -> impl Iterator<Item = (usize, &SettingCell)> {
        let method = &self.summary.methods[m];
        self.settings
            .iter()
            .map(|&i| &method.cells[i])
            .enumerate()
            .filter(|(_, cell)| cell.runs > 0)
    }

    /// The slot of method `m`'s bar inside a setting's group, in [0, 1].
    fn bar_span(&self, m: usize) -> (f64, f64) {
        let plot_width = self.size().0 - Y_LABEL_AREA - PLOT_MARGIN;
        let slot = f64::from(plot_width) / self.settings.len() as f64;
        bar_span(m, self.summary.methods.len(), slot)
    }

    fn ate_range(&self) -> (f64, f64) {
        let ates = (0..self.summary.methods.len())
            .flat_map(|m| self.cells(m).map(|(_, c)| c.ate_mean))
            .filter(|a| a.is_finite() && *a > 0.0);
        let (lo, hi) = ates.fold((f64::INFINITY, self.summary.failure_ate), |(lo, hi), a| {
            (lo.min(a), hi.max(a))
        });
        ((lo.min(hi) / 2.0).max(ATE_FLOOR), hi * ATE_HEADROOM)
    }

    /// One panel: a bar per method and setting from `base` up to `value` of the cell.
    fn draw_panel<DB, Y>(
        &self,
        area: &DrawingArea<DB, Shift>,
        panel: Panel<Y>,
    ) -> Result<(), String>
    where
        DB: DrawingBackend,
        Y: AsRangedCoord<Value = f64>,
        Y::CoordDescType: ValueFormatter<f64>,
    {
        let err = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
        let names = self.names();
        let at = |setting: usize, x: f64| NestedValue::Value(setting, x);
        // An integer range includes its end: 0..n-1 is one slot per setting.
        let slots = (0..names.len() - 1).nested_coord(|_| 0.0..1.0);
        let mut chart = ChartBuilder::on(area)
            .margin(PLOT_MARGIN)
            .x_label_area_size(30)
            .y_label_area_size(Y_LABEL_AREA - PLOT_MARGIN)
            .build_cartesian_2d(slots, panel.y)
            .map_err(err)?;
        chart
            .configure_mesh()
            .disable_x_mesh()
            .y_max_light_lines(1)
            .x_labels(names.len())
            .x_label_formatter(&|v| names[*v.category()].to_string())
            .x_label_style((FONT, 13))
            .y_desc(panel.y_desc)
            .draw()
            .map_err(err)?;
        if panel.marks_failures {
            let failure_ate = self.summary.failure_ate;
            let end = at(names.len() - 1, 1.0);
            let line = [(at(0, 0.0), failure_ate), (end.clone(), failure_ate)];
            let style = BLACK.mix(0.6).stroke_width(2);
            chart
                .draw_series(DashedLineSeries::new(line, 8, 5, style))
                .map_err(err)?;
            let label = TextStyle::from((FONT, 12)).pos(Pos::new(HPos::Right, VPos::Bottom));
            chart
                .draw_series([EmptyElement::at((end, failure_ate))
                    + Text::new("failure ATE", (-2, -4), label)])
                .map_err(err)?;
        }
        let count_style = (FONT, 13)
            .into_font()
            .color(&RGBColor(200, 0, 0))
            .pos(Pos::new(HPos::Center, VPos::Bottom));
        for m in 0..self.summary.methods.len() {
            let color = method_color(m);
            let (x0, x1) = self.bar_span(m);
            let bars = self.cells(m).filter_map(|(k, cell)| {
                let top = (panel.value)(cell)?.max(panel.base);
                Some(Rectangle::new(
                    [(at(k, x0), panel.base), (at(k, x1), top)],
                    color.filled(),
                ))
            });
            chart.draw_series(bars).map_err(err)?;
            if panel.marks_failures {
                let counts = self
                    .cells(m)
                    .filter(|(_, c)| c.failures > 0)
                    .map(|(k, cell)| {
                        let top = cell.ate_mean.max(panel.base);
                        Text::new(
                            format!("{}F", cell.failures),
                            (at(k, (x0 + x1) / 2.0), top),
                            count_style.clone(),
                        )
                    });
                chart.draw_series(counts).map_err(err)?;
            }
        }
        Ok(())
    }
}

/// What one panel shows: its y axis and the cell value its bars reach.
struct Panel<Y> {
    y: Y,
    y_desc: &'static str,
    value: fn(&SettingCell) -> Option<f64>,
    base: f64,
    /// Draws the failure ATE as a line and each bar's failure count.
    marks_failures: bool,
}

impl Figure for CategoryBars<'_> {
    fn size(&self) -> (u32, u32) {
        let longest_name = self.names().iter().map(|n| n.chars().count()).max();
        let group = (self.summary.methods.len() as u32 * BAR_WIDTH + GROUP_GAP)
            .max(longest_name.unwrap_or(0) as u32 * CHAR_WIDTH + 12);
        let width =
            (Y_LABEL_AREA + PLOT_MARGIN + group * self.settings.len() as u32).max(MIN_WIDTH);
        (
            width,
            TITLE_HEIGHT + self.legend().height(width) + 2 * PANEL_HEIGHT,
        )
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let err = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
        root.fill(&WHITE).map_err(err)?;
        let title = format!("{}: mean ATE and SR per setting", self.category);
        let body = root.titled(&title, (FONT, 18)).map_err(err)?;
        let legend = self.legend();
        let (legend_area, panels) = body.split_vertically(legend.height(body.dim_in_pixel().0));
        legend.draw(&legend_area)?;
        let (top, bottom) = panels.split_vertically(PANEL_HEIGHT);
        let (lo, hi) = self.ate_range();
        self.draw_panel(
            &top,
            Panel {
                y: (lo..hi).log_scale(),
                y_desc: "mean ATE [m] (log)",
                value: |c| Some(c.ate_mean),
                base: lo,
                marks_failures: true,
            },
        )?;
        self.draw_panel(
            &bottom,
            Panel {
                y: 0.0..1.05,
                y_desc: "mean SR",
                value: |c| c.sr_mean,
                base: 0.0,
                marks_failures: false,
            },
        )
    }
}
