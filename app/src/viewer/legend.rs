//! The colour bar under the panes when they show false colour: which map, its range and what
//! its ends mean.

use super::tonemap::{Content, ERROR_DECADES, difference_colour, error_colour, technique_hue};

/// Width of the colour bar (points).
const BAR: f32 = 220.0;

/// The map's colour at a position on the bar.
type ColourOf = fn(f32) -> [u8; 3];

/// Draws the legend of `content` into `rect` (nothing for the image).
pub fn legend(ui: &mut egui::Ui, rect: egui::Rect, content: Content, has_reference: bool) {
    let (lo, hi) = ERROR_DECADES;
    let (colour, range, text): (ColourOf, (f32, f32), String) = match content {
        Content::Image => return,
        Content::TechniqueMap => (
            |t| technique_hue(t).map(|c| (c * 255.0 + 0.5) as u8),
            (0.0, 1.0),
            "share of the direct light carried by BSDF samples (blue, left) or light samples \
             (orange, right), grey: both alike; brightness: the direct light; dark grey: none, \
             or a GPU lane (not recorded there)"
                .to_string(),
        ),
        Content::RelativeError => (
            |t| error_colour(10f32.powf(t)),
            (lo, hi),
            format!(
                "viridis, log: relative error of luminance 10^{lo}…10^{hi}, {} (grey: unknown)",
                if has_reference {
                    "against the reference"
                } else {
                    "half-buffer estimate"
                }
            ),
        ),
        Content::Difference => (
            // t in [−1, 1] over the bar: sign, and |d| on the same decades.
            |t| {
                let (lo, hi) = ERROR_DECADES;
                difference_colour(t.signum() * 10f32.powf(lo + (hi - lo) * t.abs()))
            },
            (-1.0, 1.0),
            format!(
                "cool-warm, signed log: (A−B)/(|B|+0.01) of luminance, ±10^{lo}…±1; \
                 red: A brighter, blue: B"
            ),
        ),
    };
    paint_bar(ui, rect, colour, range, text);
}

/// The bar of `colour` over `range`, and `text` beside it.
fn paint_bar(
    ui: &mut egui::Ui,
    rect: egui::Rect,
    colour: ColourOf,
    range: (f32, f32),
    text: String,
) {
    let bar = egui::Rect::from_min_size(
        rect.min + egui::vec2(0.0, 3.0),
        egui::vec2(BAR.min(rect.width()), rect.height() - 6.0),
    );
    let painter = ui.painter_at(rect);
    let steps = 64;
    for k in 0..steps {
        let t = range.0 + (range.1 - range.0) * (k as f32 + 0.5) / steps as f32;
        let [r, g, b] = colour(t);
        let x0 = bar.min.x + bar.width() * k as f32 / steps as f32;
        let x1 = bar.min.x + bar.width() * (k + 1) as f32 / steps as f32;
        painter.rect_filled(
            egui::Rect::from_x_y_ranges(x0..=x1 + 0.5, bar.y_range()),
            0.0,
            egui::Color32::from_rgb(r, g, b),
        );
    }
    let label = egui::Rect::from_min_max(egui::pos2(bar.max.x + 8.0, rect.min.y), rect.max);
    ui.put(label, egui::Label::new(text).truncate());
}
