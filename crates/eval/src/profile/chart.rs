//! One scene's breaking severities: per family a group of bars, one per method, from 0 up to the
//! breaking severity with a whisker over the search's interval; a method that never broke gets a
//! pale bar to the top marked "> 5".

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::{RobustnessProfile, TOP_SEVERITY};
use crate::grouped_bars::{bar_span, method_color, Legend, CHAR_WIDTH, FONT, TITLE_HEIGHT};
use crate::plot::Figure;

const PLOT_HEIGHT: u32 = 300;
const Y_LABEL_AREA: u32 = 60;
const PLOT_MARGIN: u32 = 10;
const MIN_WIDTH: u32 = 480;
const BAR_WIDTH: u32 = 22;
const GROUP_GAP: u32 = 30;

pub(super) struct SceneChart<'a> {
    pub profile: &'a RobustnessProfile,
    pub scene: &'a str,
    pub families: Vec<&'a str>,
    pub methods: Vec<&'a str>,
}

impl SceneChart<'_> {
    fn legend(&self) -> Legend<'_> {
        Legend {
            names: self.methods.clone(),
            left: Y_LABEL_AREA,
        }
    }
}

impl Figure for SceneChart<'_> {
    fn size(&self) -> (u32, u32) {
        let longest_name = self.families.iter().map(|n| n.chars().count()).max();
        let group = (self.methods.len() as u32 * BAR_WIDTH + GROUP_GAP)
            .max(longest_name.unwrap_or(0) as u32 * CHAR_WIDTH + 12);
        let width = (Y_LABEL_AREA + PLOT_MARGIN + group * self.families.len() as u32)
            .max(MIN_WIDTH)
            .max(Y_LABEL_AREA + self.legend().slot() * self.methods.len() as u32);
        (
            width,
            TITLE_HEIGHT + self.legend().height(width) + PLOT_HEIGHT,
        )
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let err = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
        root.fill(&WHITE).map_err(err)?;
        let title = format!("{}: breaking severity per family", self.scene);
        let body = root.titled(&title, (FONT, 18)).map_err(err)?;
        let legend = self.legend();
        let (legend_area, plot) = body.split_vertically(legend.height(body.dim_in_pixel().0));
        legend.draw(&legend_area)?;
        let families = &self.families;
        let at = |family: usize, x: f64| NestedValue::Value(family, x);
        // An integer range includes its end: 0..n-1 is one slot per family.
        let slots = (0..families.len() - 1).nested_coord(|_| 0.0..1.0);
        let mut chart = ChartBuilder::on(&plot)
            .margin(PLOT_MARGIN)
            .x_label_area_size(30)
            .y_label_area_size(Y_LABEL_AREA - PLOT_MARGIN)
            .build_cartesian_2d(slots, 0.0..TOP_SEVERITY + 0.6)
            .map_err(err)?;
        chart
            .configure_mesh()
            .disable_x_mesh()
            .y_max_light_lines(1)
            .x_labels(families.len())
            .x_label_formatter(&|v| families[*v.category()].to_string())
            .x_label_style((FONT, 13))
            .y_desc("breaking severity")
            .draw()
            .map_err(err)?;
        let slot = f64::from(self.size().0 - Y_LABEL_AREA - PLOT_MARGIN) / families.len() as f64;
        let label = TextStyle::from((FONT, 12)).pos(Pos::new(HPos::Center, VPos::Bottom));
        for (m, method) in self.methods.iter().enumerate() {
            let color = method_color(m);
            let (x0, x1) = bar_span(m, self.methods.len(), slot);
            let centre = (x0 + x1) / 2.0;
            for (k, family) in families.iter().enumerate() {
                let Some(point) = self.profile.point(method, family, self.scene) else {
                    continue;
                };
                let (top, style) = match point.breaking_severity {
                    Some(s) => (s, color.filled()),
                    None => (TOP_SEVERITY, color.mix(0.3).filled()),
                };
                chart
                    .draw_series([Rectangle::new([(at(k, x0), 0.0), (at(k, x1), top)], style)])
                    .map_err(err)?;
                match point.high {
                    Some(high) => {
                        let whisker = [(at(k, centre), point.low), (at(k, centre), high)];
                        chart
                            .draw_series([PathElement::new(whisker, BLACK.stroke_width(2))])
                            .map_err(err)?;
                    }
                    None => {
                        let text = format!("> {TOP_SEVERITY}");
                        chart
                            .draw_series([Text::new(text, (at(k, centre), top), label.clone())])
                            .map_err(err)?;
                    }
                }
            }
        }
        Ok(())
    }
}
