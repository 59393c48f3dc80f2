//! The image area: the panes (the single view, 2–3 strategies in the grid that shows them
//! largest, one of them alone, or the wipe), all at one shared zoom and pan, with the inspected
//! pixel outlined in each, the colour legend of a false-colour view and the key hints below. A
//! BSDF-only pane of a scene with delta lights says in its caption that their light is excluded.

use super::app::ViewerApp;
use super::gesture::{Gesture, gesture_of};
use super::layout::{best_grid, cell_rects};
use super::params::ViewMode;
use super::textures::Picture;
use super::tonemap::Content;
use super::wipe::{self, Source};
use super::worker::LaneView;
use super::zoom::{pixel_at, snap};
use crate::delta_lights::{self, missed_delta_lights};

/// Height of the legend and hint lines under the panes.
const FOOTER: f32 = 40.0;

/// One cell of the image area.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Pane {
    /// A lane on its own.
    Lane(usize),
    /// The reference (in the comparison, after the lanes, when one is loaded).
    Reference,
    /// The wipe's two sides, A left of the divider.
    Wipe([Source; 2]),
}

impl ViewerApp {
    /// The panes drawn, in order: the lanes (one alone when `solo`), and in the comparison the
    /// reference after them when one is loaded.
    pub fn panes(&self) -> Vec<Pane> {
        let n = self.output.lanes.len();
        match self.params.view {
            ViewMode::Wipe => vec![Pane::Wipe(wipe::sources(&self.params.wipe))],
            _ => match self.solo.filter(|&k| k < n) {
                Some(k) => vec![Pane::Lane(k)],
                None => {
                    let mut panes: Vec<Pane> = (0..n).map(Pane::Lane).collect();
                    if self.params.view == ViewMode::Compare && self.reference.is_some() {
                        panes.push(Pane::Reference);
                    }
                    panes
                }
            },
        }
    }

    /// What a difference of `source` is taken against: in the wipe, its other side; elsewhere
    /// the reference, or without one the first lane (none for the first lane itself).
    pub(crate) fn difference_base(&self, source: Source) -> Option<Source> {
        if self.params.view == ViewMode::Wipe {
            let [a, b] = wipe::sources(&self.params.wipe);
            return Some(if source == a { b } else { a });
        }
        if self.reference.is_some() {
            return Some(Source::Reference);
        }
        (source != Source::Lane(0)).then_some(Source::Lane(0))
    }

    fn source_caption(&self, s: Source) -> String {
        match s {
            Source::Reference if self.reference.is_some() => "reference".into(),
            Source::Reference => "reference (none loaded)".into(),
            Source::Lane(i) => match self.output.lanes.get(i) {
                Some(l) if l.preview => format!("{}: preview{}", l.label, self.excluded(l)),
                Some(l) => format!("{}: {} spp{}", l.label, l.spp, self.excluded(l)),
                None => "–".into(),
            },
        }
    }

    /// What a lane's caption adds when its image lacks the scene's delta lights
    /// ([`ViewerApp::misses_delta_lights`]).
    fn excluded(&self, lane: &LaneView) -> String {
        if self.misses_delta_lights(lane) {
            format!(" · {}", delta_lights::CAPTION)
        } else {
            String::new()
        }
    }

    /// Whether `lane`'s strategy never finds the delta lights of the scene it renders
    /// ([`crate::delta_lights`]), so that its image lacks their light.
    pub(crate) fn misses_delta_lights(&self, lane: &LaneView) -> bool {
        (self.output.scene.as_ref())
            .is_some_and(|s| !missed_delta_lights(lane.settings.strategy, s).is_empty())
    }

    fn pane_caption(&self, pane: Pane) -> String {
        let content = self.display.content;
        match pane {
            Pane::Lane(i) => {
                let own = self.source_caption(Source::Lane(i));
                match (content, self.difference_base(Source::Lane(i))) {
                    (Content::Difference, Some(Source::Reference)) => own + " − reference",
                    (Content::Difference, Some(Source::Lane(b))) => {
                        let base = self.output.lanes.get(b).map_or("", |l| l.label.as_str());
                        format!("{own} − {base}")
                    }
                    _ => own,
                }
            }
            Pane::Reference => self.source_caption(Source::Reference),
            Pane::Wipe([a, b]) => {
                let sep = if content == Content::Difference {
                    " − "
                } else {
                    "  |  "
                };
                format!(
                    "A {}{sep}B {}",
                    self.source_caption(a),
                    self.source_caption(b)
                )
            }
        }
    }

    pub(crate) fn central(&mut self, ui: &mut egui::Ui) {
        egui::CentralPanel::default().show(ui, |ui| {
            let Some(cam) = self.desc.as_ref().map(|d| &d.camera) else {
                ui.label("Open a scene: type its path above, or drop a .json file here.");
                return;
            };
            let image = egui::vec2(cam.width as f32, cam.height as f32);
            if let Some(e) = &self.output.error {
                ui.colored_label(ui.visuals().error_fg_color, format!("cannot render: {e}"));
                return;
            }
            let full = ui.available_rect_before_wrap();
            let area = egui::Rect::from_min_max(
                full.min,
                egui::pos2(full.max.x, (full.max.y - FOOTER).max(full.min.y + 40.0)),
            );
            let panes = self.panes();
            let grid = best_grid(panes.len(), area.size(), image);
            self.pane_rects.clear();
            self.pane_cells.clear();
            let mut gesture = None;
            for (i, &pane) in panes.iter().enumerate() {
                let (caption, cell) = cell_rects(area, &grid, i);
                ui.put(
                    caption,
                    egui::Label::new(self.pane_caption(pane)).truncate(),
                );
                if let Some(g) = self.draw_pane(ui, i, pane, cell, image) {
                    gesture = Some(g);
                }
            }
            let footer = egui::Rect::from_min_max(egui::pos2(full.min.x, area.max.y), full.max);
            self.footer(ui, footer);
            ui.allocate_rect(full, egui::Sense::hover());
            if let Some(g) = gesture {
                self.apply_gesture(g, image);
            }
        });
        self.textures.end_frame();
    }

    /// Draws pane `i` into `cell` and returns what the mouse did to it.
    fn draw_pane(
        &mut self,
        ui: &mut egui::Ui,
        i: usize,
        pane: Pane,
        cell: egui::Rect,
        image: egui::Vec2,
    ) -> Option<Gesture> {
        let ctx = ui.ctx().clone();
        let rect = snap(self.view.image_rect(cell, image), ctx.pixels_per_point());
        let resp = ui.interact(
            cell,
            ui.scope_id().with(("pane", i)),
            egui::Sense::click_and_drag(),
        );
        let painter = ui.painter_at(cell);
        painter.rect_filled(cell, 0.0, egui::Color32::from_gray(24));
        let content = self.display.content;
        let full_uv = egui::Rect::from_min_max(egui::Pos2::ZERO, egui::pos2(1.0, 1.0));
        let draw = |app: &mut ViewerApp, picture: Picture, clip: egui::Rect| {
            if let Some(tex) = app.texture(&ctx, picture) {
                ui.painter_at(clip)
                    .image(tex, rect, full_uv, egui::Color32::WHITE);
            }
        };
        let mut divider = None;
        match pane {
            Pane::Lane(k) => {
                let s = Source::Lane(k);
                let picture = Picture::of(s, content, self.difference_base(s));
                draw(self, picture, cell);
            }
            Pane::Reference => draw(self, Picture::Image(Source::Reference), cell),
            Pane::Wipe([a, b]) if content == Content::Difference => {
                draw(self, Picture::Difference(a, b), cell);
            }
            Pane::Wipe([a, b]) => {
                // The divider splits the image as seen: all of it at fit, the visible part
                // when zoomed in.
                let seen = rect.intersect(cell);
                let [left, right] = wipe::halves(seen, self.wipe_position);
                draw(self, Picture::of(a, content, None), left);
                draw(self, Picture::of(b, content, None), right);
                divider = Some(seen);
            }
        }
        self.outline_inspected(&painter, rect, image);
        self.pane_rects.push(rect);
        self.pane_cells.push(cell);
        if let Some(seen) = divider {
            self.divider(ui, seen);
        }
        if let Some(p) = resp.hover_pos()
            && let Some(px) = pixel_at(rect, image, p)
        {
            // Ctrl+click pins the pixel under the cursor, or releases the pin.
            if resp.clicked() && ui.input(|i| i.modifiers.command) {
                self.inspect_pinned = !(self.inspect_pinned && self.inspect == Some(px));
                self.inspect = Some(px);
                return None;
            }
            if !self.inspect_pinned {
                self.inspect = Some(px);
            }
        }
        gesture_of(ui, &resp, cell, rect, image)
    }

    /// The wipe's divider across `seen` (the visible image): a line with a handle; dragging it
    /// moves the split.
    fn divider(&mut self, ui: &mut egui::Ui, seen: egui::Rect) {
        let x = wipe::divider_x(seen, self.wipe_position);
        let grab = egui::Rect::from_min_max(
            egui::pos2(x - wipe::GRAB, seen.min.y),
            egui::pos2(x + wipe::GRAB, seen.max.y),
        );
        let resp = ui
            .interact(
                grab,
                ui.scope_id().with("wipe divider"),
                egui::Sense::drag(),
            )
            .on_hover_cursor(egui::CursorIcon::ResizeHorizontal);
        if resp.dragged()
            && let Some(p) = resp.interact_pointer_pos()
        {
            self.wipe_position = wipe::position_at(seen, p.x);
        }
        let painter = ui.painter_at(seen);
        let x = wipe::divider_x(seen, self.wipe_position);
        painter.vline(
            x,
            seen.y_range(),
            egui::Stroke::new(2.0, egui::Color32::from_gray(235)),
        );
        painter.circle_filled(
            egui::pos2(x, seen.center().y),
            wipe::GRAB,
            egui::Color32::from_gray(235),
        );
    }

    /// Outlines the inspected pixel when it is large enough to see.
    fn outline_inspected(&self, painter: &egui::Painter, rect: egui::Rect, image: egui::Vec2) {
        let Some((x, y)) = self.inspect.filter(|_| self.show_inspector) else {
            return;
        };
        let s = rect.width() / image.x;
        if s < 3.0 {
            return;
        }
        let px = egui::Rect::from_min_size(
            rect.min + egui::vec2(x as f32, y as f32) * s,
            egui::Vec2::splat(s),
        );
        painter.rect_stroke(
            px,
            0.0,
            egui::Stroke::new(1.5, egui::Color32::from_rgb(255, 64, 255)),
            egui::StrokeKind::Outside,
        );
    }

    /// The legend of a false-colour view and the key hints.
    fn footer(&self, ui: &mut egui::Ui, rect: egui::Rect) {
        let row = rect.height() / 2.0;
        let top = egui::Rect::from_min_size(rect.min, egui::vec2(rect.width(), row));
        let bottom = top.translate(egui::vec2(0.0, row));
        super::legend::legend(ui, top, self.display.content, self.reference.is_some());
        ui.put(
            bottom,
            egui::Label::new(
                "scroll zoom · middle/Alt-drag pan · F fit · 1 1:1 · +/− zoom · S one pane · \
                 , . next · I inspector · Ctrl+click pin pixel · C colours · drag orbit · \
                 right/Shift-drag move · Ctrl+scroll dolly",
            )
            .truncate(),
        );
    }
}
