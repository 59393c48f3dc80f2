//! The pixel inspector (Falcor's, tev's): for the pixel under the cursor (the last one hovered,
//! in any pane: the panes are in step), each lane's mean with its standard error from the film's
//! per-pixel variance, its spp, the reference's value, and a magnifier of the neighbourhood in
//! every pane. Display only.

use super::app::ViewerApp;
use super::image_area::Pane;
use super::textures::Picture;
use super::tonemap::{Content, luminance};
use super::wipe::Source;
use super::worker::LaneView;
use glam::Vec3;

/// Pixels across the magnifier (odd: the inspected pixel is in the middle).
pub const MAGNIFIER_PIXELS: u32 = 11;
/// Points per pixel in the magnifier.
const MAGNIFIER_SCALE: f32 = 11.0;

/// One lane at the inspected pixel.
#[derive(Clone, Debug, PartialEq)]
pub struct LaneSample {
    /// The lane's name.
    pub label: String,
    /// Samples per pixel.
    pub spp: u32,
    /// The mean (linear RGB); `None` while the lane shows a preview.
    pub mean: Option<Vec3>,
    /// Standard error of the mean per channel, `sqrt(s²/n)` (infinite below 2 samples).
    pub std_error: Option<Vec3>,
}

/// Everything the inspector shows about pixel (`x`, `y`).
#[derive(Clone, Debug, PartialEq)]
pub struct Inspection {
    /// The pixel.
    pub pixel: (u32, u32),
    /// Per lane.
    pub lanes: Vec<LaneSample>,
    /// The reference's value, when one is loaded.
    pub reference: Option<Vec3>,
}

/// What the inspector shows at (`x`, `y`) of a `width`-wide film.
pub fn inspect(
    lanes: &[LaneView],
    reference: Option<&[Vec3]>,
    width: u32,
    (x, y): (u32, u32),
) -> Inspection {
    let i = (y * width + x) as usize;
    Inspection {
        pixel: (x, y),
        lanes: lanes
            .iter()
            .map(|l| {
                let full = !l.preview && l.width == width;
                LaneSample {
                    label: l.label.clone(),
                    spp: l.spp,
                    mean: full.then(|| l.pixels.get(i).copied()).flatten(),
                    std_error: full
                        .then(|| l.variance.get(i).map(|v| v.map(f32::sqrt)))
                        .flatten(),
                }
            })
            .collect(),
        reference: reference.and_then(|r| r.get(i).copied()),
    }
}

/// `r g b` with 4 significant digits.
fn rgb(v: Vec3) -> String {
    format!("{:.4e} {:.4e} {:.4e}", v.x, v.y, v.z)
}

impl ViewerApp {
    /// The inspection of the current pixel (the last hovered; the image centre at first).
    pub fn inspection(&self) -> Option<Inspection> {
        let c = &self.desc.as_ref()?.camera;
        let pixel = self
            .inspect
            .filter(|&(x, y)| x < c.width && y < c.height)
            .unwrap_or((c.width / 2, c.height / 2));
        let reference = self.reference.as_ref().map(|(_, r)| r.as_slice());
        Some(inspect(&self.output.lanes, reference, c.width, pixel))
    }

    pub(crate) fn inspector_panel(&mut self, ui: &mut egui::Ui) {
        if !self.show_inspector {
            return;
        }
        egui::Panel::right("inspector")
            .default_size(250.0)
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| {
                    ui.heading("Pixel inspector (I)");
                    let Some(ins) = self.inspection() else { return };
                    ui.label(format!(
                        "pixel {} {}{}",
                        ins.pixel.0,
                        ins.pixel.1,
                        if self.inspect_pinned {
                            " (pinned: Ctrl+click to release)"
                        } else {
                            " (Ctrl+click to pin)"
                        }
                    ));
                    for (i, l) in ins.lanes.iter().enumerate() {
                        ui.separator();
                        ui.label(format!("{}: {} spp", l.label, l.spp));
                        match (l.mean, l.std_error) {
                            (Some(m), Some(se)) => {
                                ui.label(format!("mean {}", rgb(m)));
                                ui.label(format!("± {}", rgb(se)));
                                ui.label(format!(
                                    "luminance {:.4e} ± {:.1} %",
                                    luminance(m),
                                    100.0 * luminance(se) / luminance(m).abs().max(1e-12)
                                ));
                            }
                            _ => {
                                ui.label("(preview)");
                            }
                        }
                        self.magnifier(ui, Source::Lane(i), ins.pixel);
                    }
                    if let Some(r) = ins.reference {
                        ui.separator();
                        ui.label("reference");
                        ui.label(format!("value {}", rgb(r)));
                        self.magnifier(ui, Source::Reference, ins.pixel);
                    }
                });
            });
    }

    /// The `MAGNIFIER_PIXELS`² neighbourhood of `pixel` in `source`, as the panes show it
    /// (same content and exposure), nearest-neighbour, the pixel itself outlined.
    fn magnifier(&mut self, ui: &mut egui::Ui, source: Source, (x, y): (u32, u32)) {
        let Some(c) = self.desc.as_ref().map(|d| d.camera.clone()) else {
            return;
        };
        let picture = match self.panes().first() {
            // The wipe's difference view is one picture, A − B: every magnifier shows it.
            Some(&Pane::Wipe([a, b])) if self.display.content == Content::Difference => {
                Picture::Difference(a, b)
            }
            _ => Picture::of(source, self.display.content, self.difference_base(source)),
        };
        let Some(tex) = self.texture(ui.ctx(), picture) else {
            return;
        };
        let side = MAGNIFIER_PIXELS as f32 * MAGNIFIER_SCALE;
        let (rect, _) = ui.allocate_exact_size(egui::vec2(side, side), egui::Sense::hover());
        let half = (MAGNIFIER_PIXELS / 2) as f32;
        let (w, h) = (c.width as f32, c.height as f32);
        let uv = egui::Rect::from_min_max(
            egui::pos2((x as f32 - half) / w, (y as f32 - half) / h),
            egui::pos2((x as f32 + half + 1.0) / w, (y as f32 + half + 1.0) / h),
        );
        let painter = ui.painter_at(rect);
        painter.rect_filled(rect, 0.0, egui::Color32::from_gray(20));
        painter.image(tex, rect, uv, egui::Color32::WHITE);
        let centre = egui::Rect::from_min_size(
            rect.min + egui::Vec2::splat(half * MAGNIFIER_SCALE),
            egui::Vec2::splat(MAGNIFIER_SCALE),
        );
        painter.rect_stroke(
            centre,
            0.0,
            egui::Stroke::new(1.5, egui::Color32::from_rgb(255, 64, 255)),
            egui::StrokeKind::Outside,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;

    #[test]
    fn reads_mean_and_standard_error_at_the_pixel() {
        let (w, h) = (4u32, 3u32);
        let pixels: Vec<Vec3> = (0..w * h).map(|i| Vec3::splat(i as f32)).collect();
        let variance: Vec<Vec3> = (0..w * h).map(|i| Vec3::splat((i * i) as f32)).collect();
        let lane = LaneView {
            width: w,
            height: h,
            preview: false,
            pixels: Arc::new(pixels),
            variance: Arc::new(variance),
            spp: 9,
            ..crate::viewer::worker::empty_lane_view("mis")
        };
        let reference: Vec<Vec3> = (0..w * h).map(|i| Vec3::splat(-(i as f32))).collect();
        let ins = inspect(std::slice::from_ref(&lane), Some(&reference), w, (3, 2));
        let l = &ins.lanes[0];
        assert_eq!(
            (l.spp, l.mean, l.std_error),
            (9, Some(Vec3::splat(11.0)), Some(Vec3::splat(11.0)))
        );
        assert_eq!(ins.reference, Some(Vec3::splat(-11.0)));
        // A preview has no per-pixel statistics of the film.
        let preview = LaneView {
            preview: true,
            ..lane
        };
        let ins = inspect(&[preview], None, w, (3, 2));
        assert_eq!((ins.lanes[0].mean, ins.reference), (None, None));
    }
}
