//! The top bar (scene file, camera, screenshot, messages) and the render, display and reference
//! controls of the side panel. Every estimator control restarts accumulation; display controls
//! (exposure, content, zoom, inspector) never do.

use super::app::ViewerApp;
use super::menus::{self, menu};
use super::params::StrategyKind;
use super::tonemap::Content;
use super::zoom::Zoom;
use std::path::PathBuf;

/// Width of the side panel's combo boxes (points).
const COMBO_WIDTH: f32 = 150.0;

/// Largest spp limit the slider offers (0 = no limit).
const MAX_SPP_LIMIT: u32 = 1 << 16;

/// A combo box over `options`; true when the user picked another value.
pub(crate) fn combo<T: PartialEq + Copy>(
    ui: &mut egui::Ui,
    label: &str,
    value: &mut T,
    options: &[T],
    name: impl Fn(T) -> String,
) -> bool {
    let before = *value;
    // A fixed width, long names truncated (shown whole in the list), so that the side panel
    // keeps its width and leaves the room to the image.
    egui::ComboBox::from_label(label)
        .width(COMBO_WIDTH)
        .truncate()
        .selected_text(name(*value))
        .show_ui(ui, |ui| {
            for &o in options {
                ui.selectable_value(value, o, name(o));
            }
        });
    *value != before
}

impl ViewerApp {
    pub(crate) fn top_bar(&mut self, ui: &mut egui::Ui) {
        egui::Panel::top("top").show(ui, |ui| {
            ui.horizontal(|ui| {
                ui.label("Scene");
                let field = ui.add(
                    egui::TextEdit::singleline(&mut self.path_field)
                        .desired_width(280.0)
                        .hint_text("scene.json (or drop a file on the window)"),
                );
                let enter = field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
                if ui.button("Open").clicked() || enter {
                    self.load_scene(&PathBuf::from(self.path_field.trim()));
                }
                if ui.button("Reset camera").clicked() {
                    self.reset_camera();
                }
                if ui.button("Save camera").clicked() {
                    self.save_camera();
                }
                if ui.button("Screenshot (Ctrl+S)").clicked() {
                    let ctx = ui.ctx().clone();
                    self.save_screenshot(&ctx);
                }
            });
            if let Some(e) = &self.error {
                ui.colored_label(ui.visuals().error_fg_color, e);
            } else if let Some(s) = &self.status {
                ui.label(s);
            }
        });
    }

    pub(crate) fn controls_panel(&mut self, ui: &mut egui::Ui) {
        // At most this wide unless dragged wider: the image gets the room.
        egui::Panel::left("controls")
            .default_size(300.0)
            .max_size(320.0)
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| {
                    ui.heading("Render");
                    self.render_controls(ui);
                    ui.separator();
                    ui.heading("Display");
                    self.display_controls(ui);
                    ui.separator();
                    ui.heading("Panes");
                    self.panes_controls(ui);
                    ui.separator();
                    ui.heading("Reference");
                    self.reference_controls(ui);
                    ui.separator();
                    self.selection_controls(ui);
                    self.delta_light_controls(ui);
                    ui.separator();
                    ui.heading("Camera");
                    self.camera_controls(ui);
                    ui.separator();
                    ui.heading("Background");
                    self.environment_controls(ui);
                });
            });
    }

    fn render_controls(&mut self, ui: &mut egui::Ui) {
        let p = &mut self.params;
        let mut changed = false;
        // A backend that cannot run here (no adapter) says why in the image area.
        changed |= menu(ui, "Backend", &mut p.backend, menus::BACKENDS);
        changed |= combo(ui, "Strategy", &mut p.strategy, &StrategyKind::ALL, |s| {
            s.name().into()
        });
        changed |= ui
            .add(egui::Slider::new(&mut p.mix_weight, 0.0..=1.0).text("Mixture weight w"))
            .on_hover_text(
                "probability of light sampling in the mixture: 0 = BSDF only, 1 = light only",
            )
            .changed();
        changed |= menu(ui, "Heuristic", &mut p.heuristic, menus::HEURISTICS);
        changed |= menu(
            ui,
            "Light sampling",
            &mut p.light_sampling,
            menus::LIGHT_SAMPLING,
        );
        changed |= menu(
            ui,
            "Light selection",
            &mut p.light_selection,
            menus::LIGHT_SELECTION,
        );
        changed |= menu(ui, "Sampler", &mut p.sampler, menus::SAMPLERS);
        let mut depth = p.max_depth.unwrap_or(0);
        let scene_depth = self.desc.as_ref().map_or(0, |d| d.max_depth);
        if ui
            .add(
                egui::Slider::new(&mut depth, 0..=64)
                    .text("Max depth")
                    .custom_formatter(move |v, _| {
                        if v == 0.0 {
                            format!("scene ({scene_depth})")
                        } else {
                            format!("{v}")
                        }
                    }),
            )
            .changed()
        {
            p.max_depth = (depth > 0).then_some(depth);
            changed = true;
        }
        changed |= ui
            .add(
                egui::Slider::new(&mut p.spp_limit, 0..=MAX_SPP_LIMIT)
                    .logarithmic(true)
                    .text("Spp limit")
                    .custom_formatter(|v, _| {
                        if v == 0.0 {
                            "none".into()
                        } else {
                            format!("{v}")
                        }
                    }),
            )
            .changed();
        if changed {
            self.restart();
        }
    }

    fn display_controls(&mut self, ui: &mut egui::Ui) {
        ui.add(egui::Slider::new(&mut self.display.exposure, -10.0..=10.0).text("Exposure (EV)"));
        combo(
            ui,
            "Show (C)",
            &mut self.display.content,
            &Content::ALL,
            |c| c.label().into(),
        );
        ui.horizontal(|ui| {
            if ui.button("Fit (F)").clicked() {
                self.view.zoom = Zoom::Fit;
            }
            if ui.button("1:1 (1)").clicked() {
                let image = self.desc.as_ref().map_or(egui::vec2(1.0, 1.0), |d| {
                    egui::vec2(d.camera.width as f32, d.camera.height as f32)
                });
                self.view
                    .set_scale(1.0 / ui.ctx().pixels_per_point(), image);
            }
            ui.label(match self.view.zoom {
                Zoom::Fit => "fit".to_string(),
                Zoom::Scale(s) => format!("{:.0} %", 100.0 * s * ui.ctx().pixels_per_point()),
            });
        });
        ui.checkbox(&mut self.view.integer, "Fit at whole pixels");
        ui.checkbox(&mut self.show_inspector, "Pixel inspector (I)");
    }

    fn reference_controls(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            ui.add(
                egui::TextEdit::singleline(&mut self.reference_field)
                    .desired_width(170.0)
                    .hint_text("reference.exr"),
            );
            if ui.button("Load").clicked() {
                let path = PathBuf::from(self.reference_field.trim());
                self.load_reference(&path);
            }
            if self.reference.is_some() && ui.button("Clear").clicked() {
                self.clear_reference();
            }
        });
        ui.label(match &self.reference {
            Some((p, _)) => format!("error: relMSE against {}", p.display()),
            None => "error: half-buffer estimate (no reference)".into(),
        });
    }
}
