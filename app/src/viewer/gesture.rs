//! What the mouse does over a pane: the scene camera (drag to orbit, right or shift drag to move
//! it, Ctrl+scroll to dolly; these restart accumulation) or the image (scroll to zoom about the
//! cursor, middle or Alt drag to pan; display only), and click to select.

use super::app::ViewerApp;
use super::camera;

/// What the mouse did to a pane this frame.
pub enum Gesture {
    /// A click at this film position (pixels, fractional).
    Select(f32, f32),
    /// Orbit the camera by a drag of this many points.
    Orbit(egui::Vec2),
    /// Move the camera by a drag of this many points in a pane this tall.
    CameraPan(egui::Vec2, f32),
    /// Dolly the camera (steps; positive is closer).
    Dolly(f32),
    /// Pan the image by this many points, in a cell.
    ImagePan(egui::Vec2, egui::Rect),
    /// Zoom the image by this factor about this point, in a cell.
    ImageZoom(f32, egui::Pos2, egui::Rect),
}

/// The gesture of `resp`, a pane's `cell` showing an `image`-sized image at `rect`.
pub fn gesture_of(
    ui: &egui::Ui,
    resp: &egui::Response,
    cell: egui::Rect,
    rect: egui::Rect,
    image: egui::Vec2,
) -> Option<Gesture> {
    let (shift, alt) = ui.input(|i| (i.modifiers.shift, i.modifiers.alt));
    if resp.clicked()
        && !alt
        && let Some(p) = resp.interact_pointer_pos()
    {
        let u = (p - rect.min) / rect.size() * image;
        return Some(Gesture::Select(u.x, u.y));
    }
    let d = resp.drag_delta();
    if d != egui::Vec2::ZERO {
        let primary = resp.dragged_by(egui::PointerButton::Primary);
        if resp.dragged_by(egui::PointerButton::Middle) || (alt && primary) {
            return Some(Gesture::ImagePan(d, cell));
        }
        if resp.dragged_by(egui::PointerButton::Secondary) || (shift && primary) {
            return Some(Gesture::CameraPan(d, rect.height()));
        }
        if primary {
            return Some(Gesture::Orbit(d));
        }
    }
    if resp.hovered() {
        let (scroll, zoom, at) = ui.input(|i| {
            (
                i.smooth_scroll_delta.y,
                i.zoom_delta(),
                i.pointer.hover_pos(),
            )
        });
        // egui turns Ctrl+scroll (and pinches) into zoom_delta = exp(scroll / 200).
        if zoom != 1.0 {
            return Some(Gesture::Dolly(4.0 * zoom.ln()));
        }
        if scroll != 0.0
            && let Some(at) = at
        {
            return Some(Gesture::ImageZoom((scroll / 200.0).exp(), at, cell));
        }
    }
    None
}

impl ViewerApp {
    /// Applies `g`: image gestures change the shared view, camera gestures the scene.
    pub(crate) fn apply_gesture(&mut self, g: Gesture, image: egui::Vec2) {
        let Some(desc) = &mut self.desc else { return };
        match g {
            Gesture::Select(x, y) => return self.select_at(x, y),
            Gesture::ImagePan(d, cell) => return self.view.pan(d, cell, image),
            Gesture::ImageZoom(f, at, cell) => return self.view.zoom_at(f, at, cell, image),
            Gesture::Orbit(d) => camera::orbit(&mut desc.camera, d.x, d.y),
            Gesture::CameraPan(d, h) => camera::pan(&mut desc.camera, d.x, d.y, h),
            Gesture::Dolly(s) => camera::zoom(&mut desc.camera, s),
        }
        self.scene_changed();
    }
}
