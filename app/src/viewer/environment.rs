//! The background's controls: an environment map's scale and rotation about +y, or a constant
//! background's radiance. Edits go into the scene description, which is then rebuilt.

use super::app::ViewerApp;
use lumis::scene::BackgroundDesc;

/// Range of the environment map's scale slider (logarithmic).
const SCALE_RANGE: std::ops::RangeInclusive<f64> = 1e-3..=1e3;

impl ViewerApp {
    pub(crate) fn environment_controls(&mut self, ui: &mut egui::Ui) {
        self.studio_toggle(ui);
        let Some(desc) = &mut self.desc else { return };
        let mut changed = false;
        match &mut desc.background {
            BackgroundDesc::Envmap(e) => {
                ui.label(format!(
                    "environment map {}",
                    e.file.file_name().unwrap_or_default().to_string_lossy()
                ));
                changed |= ui
                    .add(
                        egui::Slider::new(&mut e.scale, SCALE_RANGE)
                            .logarithmic(true)
                            .text("Environment scale"),
                    )
                    .changed();
                changed |= ui
                    .add(
                        egui::Slider::new(&mut e.rotate_y_deg, -180.0..=180.0)
                            .text("Environment rotation (°)"),
                    )
                    .changed();
            }
            BackgroundDesc::Constant(c) => {
                ui.horizontal(|ui| {
                    for (v, name) in [(&mut c.x, "red"), (&mut c.y, "green"), (&mut c.z, "blue")] {
                        changed |= ui
                            .add(
                                egui::DragValue::new(v)
                                    .range(0.0..=1e5)
                                    .speed(0.01)
                                    .prefix(format!("{name} ")),
                            )
                            .changed();
                    }
                    ui.label("Background radiance");
                });
            }
        }
        if changed {
            self.scene_changed();
        }
    }

    /// For a model file opened on its own: the studio (ground and studio lights) on or off,
    /// which reloads the model (`--no-studio` starts with it off).
    fn studio_toggle(&mut self, ui: &mut egui::Ui) {
        let Some(path) = self.scene_path.clone() else {
            return;
        };
        if !lumis::scene::model::is_model_file(&path) {
            return;
        }
        let mut on = crate::scene_file::studio();
        if ui
            .checkbox(&mut on, "Studio")
            .on_hover_text("The model on a grey ground under studio lights; off: a white sky")
            .changed()
        {
            crate::scene_file::set_studio(on);
            self.load_scene(&path);
        }
    }
}
