//! What the grouped bar charts share (`runs`' per-category bars, the robustness profile's
//! chart): one colour per method with a legend above the plot, and where each method's bar sits
//! inside its group's slot.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

pub(crate) const FONT: &str = "sans-serif";
/// Rough width of a 13 px sans-serif character, to keep names apart.
pub(crate) const CHAR_WIDTH: u32 = 7;
pub(crate) const TITLE_HEIGHT: u32 = 34;
const LEGEND_ROW_HEIGHT: u32 = 22;
/// The largest share of a group's slot that its bars fill.
const BARS_SPAN: f64 = 0.8;
const MAX_BAR_WIDTH: f64 = 40.0;

/// A swatch and a name per method, in as many rows as the width needs, starting `left` pixels
/// in (where the plot starts).
pub(crate) struct Legend<'a> {
    pub names: Vec<&'a str>,
    pub left: u32,
}

impl Legend<'_> {
    /// The width of one entry.
    pub fn slot(&self) -> u32 {
        let longest = self.names.iter().map(|n| n.chars().count()).max();
        longest.unwrap_or(0) as u32 * CHAR_WIDTH + 34
    }

    fn columns(&self, width: u32) -> u32 {
        (width.saturating_sub(self.left) / self.slot()).max(1)
    }

    pub fn height(&self, width: u32) -> u32 {
        let rows = (self.names.len() as u32).div_ceil(self.columns(width));
        rows.max(1) * LEGEND_ROW_HEIGHT
    }

    pub fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let columns = self.columns(area.dim_in_pixel().0);
        for (m, name) in self.names.iter().enumerate() {
            let (row, column) = (m as u32 / columns, m as u32 % columns);
            let x = (self.left + column * self.slot()) as i32;
            let y = (row * LEGEND_ROW_HEIGHT + LEGEND_ROW_HEIGHT / 2) as i32;
            area.draw(&Rectangle::new(
                [(x, y - 6), (x + 14, y + 6)],
                method_color(m).filled(),
            ))
            .map_err(|e| e.to_string())?;
            let style = TextStyle::from((FONT, 14)).pos(Pos::new(HPos::Left, VPos::Center));
            area.draw_text(name, &style, (x + 20, y))
                .map_err(|e| e.to_string())?;
        }
        Ok(())
    }
}

/// Method `m`'s colour.
pub(crate) fn method_color(m: usize) -> RGBAColor {
    Palette99::pick(m).to_rgba()
}

/// Where bar `m` of `bars` sits inside a group's slot `slot` pixels wide, in [0, 1]: the bars
/// are centred and no wider than [`MAX_BAR_WIDTH`] where few groups leave wide slots.
pub(crate) fn bar_span(m: usize, bars: usize, slot: f64) -> (f64, f64) {
    let bars = bars as f64;
    let span = (bars * MAX_BAR_WIDTH / slot).min(BARS_SPAN);
    let width = span / bars;
    let start = (1.0 - span) / 2.0 + m as f64 * width;
    (start, start + width)
}
