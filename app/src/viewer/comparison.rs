//! The image area: one pane per lane (the single view, or 2–3 strategies side by side, each its
//! own accumulation), with the mouse camera (drag to orbit, right/middle or shift-drag to pan,
//! scroll to zoom) and click-to-select.

use super::app::ViewerApp;
use super::camera;

/// Height of a pane's caption.
const CAPTION: f32 = 18.0;
/// Gap between panes.
const GAP: f32 = 6.0;

/// What the mouse did to a pane this frame.
enum Gesture {
    Select(f32, f32),
    Orbit(egui::Vec2),
    Pan(egui::Vec2, f32),
    Zoom(f32),
}

impl ViewerApp {
    pub(crate) fn central(&mut self, ui: &mut egui::Ui) {
        egui::CentralPanel::default().show(ui, |ui| {
            let Some(cam) = self.desc.as_ref().map(|d| &d.camera) else {
                ui.label("Open a scene: type its path above, or drop a .json file here.");
                return;
            };
            let (fw, fh) = (cam.width as f32, cam.height as f32);
            if let Some(e) = &self.output.error {
                ui.colored_label(ui.visuals().error_fg_color, format!("cannot render: {e}"));
                return;
            }
            let textures = self.textures(ui.ctx());
            let n = textures.len().max(1) as f32;
            let avail = ui.available_size();
            // Largest scale at which all panes fit side by side.
            let scale = ((avail.x - GAP * (n - 1.0)) / (n * fw))
                .min((avail.y - CAPTION) / fh)
                .max(0.05);
            let size = egui::vec2(fw * scale, fh * scale);
            let mut gesture = None;
            let mut rects = Vec::new();
            ui.horizontal_top(|ui| {
                ui.spacing_mut().item_spacing.x = GAP;
                for (lane, tex) in self.output.lanes.iter().zip(&textures) {
                    ui.vertical(|ui| {
                        ui.label(caption(lane));
                        let (rect, resp) =
                            ui.allocate_exact_size(size, egui::Sense::click_and_drag());
                        ui.painter().image(
                            *tex,
                            rect,
                            egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0)),
                            egui::Color32::WHITE,
                        );
                        rects.push(rect);
                        if let Some(g) = gesture_of(ui, &resp, rect, fw, fh) {
                            gesture = Some(g);
                        }
                    });
                }
            });
            self.pane_rects = rects;
            if let Some(g) = gesture {
                self.apply_gesture(g);
            }
        });
    }

    fn apply_gesture(&mut self, g: Gesture) {
        if let Gesture::Select(x, y) = g {
            self.select_at(x, y);
            return;
        }
        let Some(desc) = &mut self.desc else { return };
        match g {
            Gesture::Orbit(d) => camera::orbit(&mut desc.camera, d.x, d.y),
            Gesture::Pan(d, h) => camera::pan(&mut desc.camera, d.x, d.y, h),
            Gesture::Zoom(s) => camera::zoom(&mut desc.camera, s),
            Gesture::Select(..) => unreachable!(),
        }
        self.scene_changed();
    }
}

fn caption(lane: &super::worker::LaneView) -> String {
    if lane.preview {
        format!("{}: preview", lane.label)
    } else {
        format!("{}: {} spp", lane.label, lane.spp)
    }
}

fn gesture_of(
    ui: &egui::Ui,
    resp: &egui::Response,
    rect: egui::Rect,
    fw: f32,
    fh: f32,
) -> Option<Gesture> {
    if resp.clicked()
        && let Some(p) = resp.interact_pointer_pos()
    {
        let x = (p.x - rect.min.x) / rect.width() * fw;
        let y = (p.y - rect.min.y) / rect.height() * fh;
        return Some(Gesture::Select(x, y));
    }
    let d = resp.drag_delta();
    if d != egui::Vec2::ZERO {
        let shift = ui.input(|i| i.modifiers.shift);
        if resp.dragged_by(egui::PointerButton::Secondary)
            || resp.dragged_by(egui::PointerButton::Middle)
            || (shift && resp.dragged_by(egui::PointerButton::Primary))
        {
            return Some(Gesture::Pan(d, rect.height()));
        }
        if resp.dragged_by(egui::PointerButton::Primary) {
            return Some(Gesture::Orbit(d));
        }
    }
    if resp.hovered() {
        let scroll = ui.input(|i| i.smooth_scroll_delta.y);
        if scroll != 0.0 {
            return Some(Gesture::Zoom(scroll / 50.0));
        }
    }
    None
}
