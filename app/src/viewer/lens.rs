//! The camera's controls: its projection (pinhole, thin lens, orthographic), a thin lens's
//! aperture and focus distance, the field of view or an orthographic film's size. Edits go into
//! the scene description, which is then rebuilt (as the background's controls do).

use super::app::ViewerApp;
use super::controls::combo;
use lumis::scene::{CameraDesc, ProjectionDesc};

/// The projections the menu offers, in the scene format's order.
const KINDS: [&str; 3] = ["perspective", "thinlens", "orthographic"];

fn kind(p: &ProjectionDesc) -> &'static str {
    match p {
        ProjectionDesc::Perspective { .. } => KINDS[0],
        ProjectionDesc::ThinLens { .. } => KINDS[1],
        ProjectionDesc::Orthographic { .. } => KINDS[2],
    }
}

/// `cam` with projection `to`, keeping what the image shows at the look-at point: a thin lens
/// starts closed (the pinhole's image) and focused on the look-at point; an orthographic film is
/// the perspective view's extent at that distance, and back.
pub fn switch_projection(cam: &mut CameraDesc, to: &str) {
    let dist = (cam.to - cam.from).length();
    let aspect = cam.width as f64 / cam.height as f64;
    let vfov = match cam.projection {
        ProjectionDesc::Perspective { vfov_deg } | ProjectionDesc::ThinLens { vfov_deg, .. } => {
            vfov_deg
        }
        ProjectionDesc::Orthographic { view_size } => {
            2.0 * (0.5 * view_size[1] / dist).atan().to_degrees()
        }
    };
    cam.projection = match to {
        "thinlens" => ProjectionDesc::ThinLens {
            vfov_deg: vfov,
            aperture_radius: 0.0,
            focus_distance: dist,
        },
        "orthographic" => {
            let h = 2.0 * dist * (0.5 * vfov.to_radians()).tan();
            ProjectionDesc::Orthographic {
                view_size: [h * aspect, h],
            }
        }
        _ => ProjectionDesc::Perspective { vfov_deg: vfov },
    };
}

impl ViewerApp {
    pub(crate) fn camera_controls(&mut self, ui: &mut egui::Ui) {
        let Some(desc) = &mut self.desc else { return };
        let cam = &mut desc.camera;
        let dist = (cam.to - cam.from).length();
        let mut chosen = kind(&cam.projection);
        let mut changed = combo(ui, "Projection", &mut chosen, &KINDS, |k| k.into());
        if changed {
            switch_projection(cam, chosen);
        }
        match &mut cam.projection {
            ProjectionDesc::Perspective { vfov_deg } => {
                changed |= fov_slider(ui, vfov_deg);
            }
            ProjectionDesc::ThinLens {
                vfov_deg,
                aperture_radius,
                focus_distance,
            } => {
                changed |= fov_slider(ui, vfov_deg);
                // Up to a quarter of the distance to the look-at point: a strong blur already.
                let max_aperture = (0.25 * dist).max(*aperture_radius);
                changed |= ui
                    .add(
                        egui::Slider::new(aperture_radius, 0.0..=max_aperture)
                            .text("Aperture radius"),
                    )
                    .on_hover_text("the lens's radius in scene units: 0 is the pinhole")
                    .changed();
                let range =
                    (0.01 * dist).min(*focus_distance)..=(100.0 * dist).max(*focus_distance);
                changed |= ui
                    .add(
                        egui::Slider::new(focus_distance, range)
                            .logarithmic(true)
                            .text("Focus distance"),
                    )
                    .on_hover_text("distance of the sharp plane along the view direction")
                    .changed();
                if ui.button("Focus on the look-at point").clicked() {
                    *focus_distance = dist;
                    changed = true;
                }
            }
            ProjectionDesc::Orthographic { view_size } => {
                let aspect = view_size[0] / view_size[1];
                let mut h = view_size[1];
                if ui
                    .add(
                        egui::Slider::new(&mut h, 1e-3 * dist.max(1e-3)..=1e3 * dist.max(1e-3))
                            .logarithmic(true)
                            .text("Film height"),
                    )
                    .on_hover_text("the orthographic film's height in scene units")
                    .changed()
                {
                    *view_size = [h * aspect, h];
                    changed = true;
                }
            }
        }
        if changed {
            self.scene_changed();
        }
    }
}

fn fov_slider(ui: &mut egui::Ui, vfov_deg: &mut f64) -> bool {
    ui.add(egui::Slider::new(vfov_deg, 1.0..=150.0).text("Field of view (°)"))
        .on_hover_text("the vertical field of view")
        .changed()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// Switching keeps the view at the look-at point: perspective → orthographic gives the film
    /// the perspective image's extent there, and back gives the same field of view; a new thin
    /// lens is closed and focused on the look-at point.
    #[test]
    fn switching_projection_keeps_the_view_at_the_look_at_point() {
        let mut cam = CameraDesc {
            from: DVec3::new(0.0, 0.0, -4.0),
            to: DVec3::ZERO,
            up: DVec3::Y,
            projection: ProjectionDesc::Perspective { vfov_deg: 45.0 },
            principal_point_offset: [0.0; 2],
            width: 200,
            height: 100,
            filter: Default::default(),
        };
        switch_projection(&mut cam, "orthographic");
        let ProjectionDesc::Orthographic { view_size } = cam.projection else {
            panic!()
        };
        let h = 8.0 * (22.5f64).to_radians().tan();
        assert!((view_size[1] - h).abs() < 1e-12 && (view_size[0] - 2.0 * h).abs() < 1e-12);
        switch_projection(&mut cam, "perspective");
        assert!((cam.vfov_deg().unwrap() - 45.0).abs() < 1e-9);
        switch_projection(&mut cam, "thinlens");
        assert_eq!(
            cam.projection,
            ProjectionDesc::ThinLens {
                vfov_deg: cam.vfov_deg().unwrap(),
                aperture_radius: 0.0,
                focus_distance: 4.0
            }
        );
    }
}
