//! The image keys (display only, never a restart): F fit, 1 one image pixel per screen pixel,
//! +/− zoom by 2 about the panes' centre, arrows pan, S one pane alone at full size, comma and
//! period the previous and next pane, I the pixel inspector, C the next display content.
//! Ignored while a text field has the keyboard.

use super::app::ViewerApp;
use super::tonemap::Content;
use super::zoom::Zoom;
use egui::{Key, Modifiers};

/// Points an arrow key pans by.
const PAN_STEP: f32 = 40.0;

impl ViewerApp {
    pub(crate) fn view_keys(&mut self, ctx: &egui::Context) {
        if ctx.egui_wants_keyboard_input() {
            return;
        }
        let pressed = |k: Key| ctx.input_mut(|i| i.consume_key(Modifiers::NONE, k));
        let image = self.desc.as_ref().map_or(egui::vec2(1.0, 1.0), |d| {
            egui::vec2(d.camera.width as f32, d.camera.height as f32)
        });
        let cell = self.pane_cells.first().copied();
        if pressed(Key::F) {
            self.view.zoom = Zoom::Fit;
        }
        if pressed(Key::Num1) {
            self.view.set_scale(1.0 / ctx.pixels_per_point(), image);
        }
        if let Some(cell) = cell {
            let shift = ctx.input(|i| i.modifiers.shift);
            let plus = ctx.input_mut(|i| {
                i.consume_key(Modifiers::NONE, Key::Plus)
                    || i.consume_key(Modifiers::NONE, Key::Equals)
                    || (shift && i.consume_key(Modifiers::SHIFT, Key::Equals))
            });
            if plus {
                self.view.zoom_at(2.0, cell.center(), cell, image);
            }
            if pressed(Key::Minus) {
                self.view.zoom_at(0.5, cell.center(), cell, image);
            }
            for (k, d) in [
                (Key::ArrowLeft, egui::vec2(PAN_STEP, 0.0)),
                (Key::ArrowRight, egui::vec2(-PAN_STEP, 0.0)),
                (Key::ArrowUp, egui::vec2(0.0, PAN_STEP)),
                (Key::ArrowDown, egui::vec2(0.0, -PAN_STEP)),
            ] {
                if pressed(k) {
                    self.view.pan(d, cell, image);
                }
            }
        }
        let n = self.output.lanes.len().max(1);
        if pressed(Key::S) {
            self.solo = match self.solo {
                Some(_) => None,
                None => Some(self.hovered_pane(ctx).unwrap_or(0)),
            };
        }
        if pressed(Key::Period) {
            self.solo = Some(self.solo.map_or(0, |k| (k + 1) % n));
        }
        if pressed(Key::Comma) {
            self.solo = Some(self.solo.map_or(n - 1, |k| (k + n - 1) % n));
        }
        if pressed(Key::I) {
            self.show_inspector = !self.show_inspector;
        }
        if pressed(Key::C) {
            let all = Content::ALL;
            let at = all.iter().position(|&c| c == self.display.content);
            self.display.content = all[at.map_or(0, |i| (i + 1) % all.len())];
        }
    }

    /// The lane of the pane under the pointer, if any.
    fn hovered_pane(&self, ctx: &egui::Context) -> Option<usize> {
        let pos = ctx.input(|i| i.pointer.hover_pos())?;
        let i = self.pane_cells.iter().position(|c| c.contains(pos))?;
        match self.panes().get(i)? {
            super::image_area::Pane::Lane(k) => Some(*k),
            super::image_area::Pane::Wipe(_) | super::image_area::Pane::Reference => None,
        }
    }
}
