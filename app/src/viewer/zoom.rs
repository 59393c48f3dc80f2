//! The zoom and pan every pane shares: panes show the same image point at the same place in
//! their cells, so zooming or panning one moves all of them (down to single pixels, drawn
//! nearest-neighbour when magnified). Display only: never restarts accumulation.

/// Largest magnification: a pixel 64 points wide.
pub const MAX_SCALE: f32 = 64.0;
/// Smallest zoom, as a fraction of the fit scale.
pub const MIN_OF_FIT: f32 = 0.25;

/// How large the image is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Zoom {
    /// The largest scale at which the whole image fits its cell.
    Fit,
    /// This many points per image pixel, with `ImageView::centre` at the cell's centre.
    Scale(f32),
}

/// The shared view of the panes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageView {
    /// Fit or a fixed scale.
    pub zoom: Zoom,
    /// The image point (pixels, from the top-left corner) at the centre of each cell, when
    /// zoomed (`Zoom::Scale`); fit always centres the image.
    pub centre: egui::Vec2,
    /// Fit snaps down to a whole number of points per pixel when it is at least 1, so that
    /// every image pixel covers the same number of screen pixels.
    pub integer: bool,
}

impl Default for ImageView {
    fn default() -> ImageView {
        ImageView {
            zoom: Zoom::Fit,
            centre: egui::Vec2::ZERO,
            integer: false,
        }
    }
}

/// The largest scale (points per pixel) at which an `image`-sized image fits in `cell`.
pub fn fit_scale(cell: egui::Vec2, image: egui::Vec2) -> f32 {
    (cell.x / image.x).min(cell.y / image.y).max(1e-3)
}

impl ImageView {
    /// Points per image pixel in a cell whose fit scale is `fit`.
    pub fn scale(&self, fit: f32) -> f32 {
        match self.zoom {
            Zoom::Fit if self.integer && fit >= 1.0 => fit.floor(),
            Zoom::Fit => fit,
            Zoom::Scale(s) => s,
        }
    }

    /// Where the whole `image` is drawn for `cell` (clip the drawing to the cell).
    pub fn image_rect(&self, cell: egui::Rect, image: egui::Vec2) -> egui::Rect {
        let s = self.scale(fit_scale(cell.size(), image));
        let centre = match self.zoom {
            Zoom::Fit => image * 0.5,
            Zoom::Scale(_) => self.centre,
        };
        egui::Rect::from_min_size(cell.center() - centre * s, image * s)
    }

    /// Multiplies the scale by `factor`, keeping the image point under `at` (a screen point) in
    /// place.
    pub fn zoom_at(&mut self, factor: f32, at: egui::Pos2, cell: egui::Rect, image: egui::Vec2) {
        let fit = fit_scale(cell.size(), image);
        let rect = self.image_rect(cell, image);
        let s = self.scale(fit);
        let under = (at - rect.min) / s;
        let new = (s * factor).clamp(fit * MIN_OF_FIT, MAX_SCALE.max(fit));
        self.zoom = Zoom::Scale(new);
        self.centre = under - (at - cell.center()) / new;
        self.clamp_centre(image);
    }

    /// Fixes the scale at `scale` about the current centre (the `1` key: 1:1).
    pub fn set_scale(&mut self, scale: f32, image: egui::Vec2) {
        if self.zoom == Zoom::Fit {
            self.centre = image * 0.5;
        }
        self.zoom = Zoom::Scale(scale.clamp(1e-3, MAX_SCALE));
    }

    /// Moves the image by `delta` screen points (a drag).
    pub fn pan(&mut self, delta: egui::Vec2, cell: egui::Rect, image: egui::Vec2) {
        let s = self.scale(fit_scale(cell.size(), image));
        if self.zoom == Zoom::Fit {
            self.centre = image * 0.5;
            self.zoom = Zoom::Scale(s);
        }
        self.centre -= delta / s;
        self.clamp_centre(image);
    }

    /// Keeps the centre on the image, so the image can never be panned out of sight.
    fn clamp_centre(&mut self, image: egui::Vec2) {
        self.centre = self.centre.clamp(egui::Vec2::ZERO, image);
    }
}

/// `rect` moved so that its corner is on a physical pixel (`ppp`: pixels per point), so that
/// magnified pixels are drawn evenly.
pub fn snap(rect: egui::Rect, ppp: f32) -> egui::Rect {
    let min = egui::pos2(
        (rect.min.x * ppp).round() / ppp,
        (rect.min.y * ppp).round() / ppp,
    );
    egui::Rect::from_min_size(min, rect.size())
}

/// The image pixel under screen point `p` for an image drawn at `rect`, if any.
pub fn pixel_at(rect: egui::Rect, image: egui::Vec2, p: egui::Pos2) -> Option<(u32, u32)> {
    let u = (p - rect.min) / rect.size() * image;
    (u.x >= 0.0 && u.y >= 0.0 && u.x < image.x && u.y < image.y).then_some((u.x as u32, u.y as u32))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cell() -> egui::Rect {
        egui::Rect::from_min_size(egui::pos2(100.0, 50.0), egui::vec2(400.0, 300.0))
    }
    const IMAGE: egui::Vec2 = egui::vec2(320.0, 180.0);

    #[test]
    fn fit_fills_the_cell_and_integer_fit_snaps_down() {
        let mut v = ImageView::default();
        let r = v.image_rect(cell(), IMAGE);
        assert_eq!(r.width(), 400.0);
        assert_eq!(r.center(), cell().center());
        v.integer = true;
        assert_eq!(v.image_rect(cell(), IMAGE).width(), 320.0);
        // Below 1 there is no whole number to snap to: fractional fit.
        let small = egui::Rect::from_min_size(egui::Pos2::ZERO, egui::vec2(160.0, 90.0));
        assert_eq!(v.image_rect(small, IMAGE).width(), 160.0);
    }

    /// Zooming keeps the image point under the cursor under it, and the zoom is one scale for
    /// every cell (the panes stay in step).
    #[test]
    fn zoom_keeps_the_point_under_the_cursor() {
        let mut v = ImageView::default();
        let at = egui::pos2(180.0, 120.0);
        let before = pixel_f(v.image_rect(cell(), IMAGE), at);
        v.zoom_at(4.0, at, cell(), IMAGE);
        let after = pixel_f(v.image_rect(cell(), IMAGE), at);
        assert!((before - after).length() < 1e-3, "{before:?} {after:?}");
        assert_eq!(v.zoom, Zoom::Scale(4.0 * 400.0 / 320.0));
        // Another cell of the same size shows the same point at the same offset.
        let other = cell().translate(egui::vec2(500.0, 0.0));
        let there = pixel_f(v.image_rect(other, IMAGE), at + egui::vec2(500.0, 0.0));
        assert!((there - after).length() < 1e-3);
        // Limits.
        v.zoom_at(1e6, at, cell(), IMAGE);
        assert_eq!(v.zoom, Zoom::Scale(MAX_SCALE));
        v.zoom_at(1e-6, at, cell(), IMAGE);
        assert_eq!(v.zoom, Zoom::Scale(1.25 * MIN_OF_FIT));
    }

    #[test]
    fn pan_moves_the_image_with_the_drag_and_stays_on_it() {
        let mut v = ImageView::default();
        v.set_scale(2.0, IMAGE);
        let r0 = v.image_rect(cell(), IMAGE);
        v.pan(egui::vec2(10.0, -4.0), cell(), IMAGE);
        let r1 = v.image_rect(cell(), IMAGE);
        assert_eq!(r1.min - r0.min, egui::vec2(10.0, -4.0));
        v.pan(egui::vec2(1e6, 1e6), cell(), IMAGE);
        assert_eq!(v.centre, egui::Vec2::ZERO);
    }

    #[test]
    fn pixel_lookup() {
        let r = egui::Rect::from_min_size(egui::pos2(10.0, 10.0), egui::vec2(640.0, 360.0));
        assert_eq!(pixel_at(r, IMAGE, egui::pos2(10.0, 10.0)), Some((0, 0)));
        assert_eq!(
            pixel_at(r, IMAGE, egui::pos2(649.9, 369.9)),
            Some((319, 179))
        );
        assert_eq!(pixel_at(r, IMAGE, egui::pos2(650.0, 20.0)), None);
    }

    fn pixel_f(rect: egui::Rect, p: egui::Pos2) -> egui::Vec2 {
        (p - rect.min) / rect.size() * IMAGE
    }
}
