//! The top bar (scene file, camera, screenshot, messages) and the render, display, comparison
//! and reference controls of the side panel. Every estimator control restarts accumulation.

use super::app::ViewerApp;
use super::params::StrategyKind;
use lumis::engine::Backend;
use lumis::integrator::Heuristic;
use lumis::lights::{LightSampling, LightSelection};
use std::path::PathBuf;

/// Largest spp limit the slider offers (0 = no limit).
const MAX_SPP_LIMIT: u32 = 1 << 16;

fn heuristic_name(h: Heuristic) -> &'static str {
    match h {
        Heuristic::Balance => "balance",
        Heuristic::Power => "power",
    }
}

fn backend_name(b: Backend) -> &'static str {
    match b {
        Backend::Cpu => "CPU",
        Backend::Gpu => "GPU (wgpu)",
    }
}

fn sampling_name(s: LightSampling) -> &'static str {
    match s {
        LightSampling::Area => "area (env. map: uniform)",
        LightSampling::SolidAngle => "solid angle (env. map: importance)",
        LightSampling::SolidAngleCosine => "solid angle × cos warp (Hart 2020)",
        LightSampling::Adaptive => "adaptive: area where small, else solid angle",
        LightSampling::ProjectedSolidAngle => "projected solid angle ∝ cos (Peters 2021)",
    }
}

/// A combo box over `options`; true when the user picked another value.
pub(crate) fn combo<T: PartialEq + Copy>(
    ui: &mut egui::Ui,
    label: &str,
    value: &mut T,
    options: &[T],
    name: impl Fn(T) -> String,
) -> bool {
    let before = *value;
    egui::ComboBox::from_label(label)
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
        egui::Panel::left("controls")
            .default_size(300.0)
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| {
                    ui.heading("Render");
                    self.render_controls(ui);
                    ui.separator();
                    ui.heading("Display");
                    ui.add(
                        egui::Slider::new(&mut self.display.exposure, -10.0..=10.0)
                            .text("Exposure (EV)"),
                    );
                    ui.checkbox(
                        &mut self.display.false_colour,
                        "False colour: relative error",
                    );
                    ui.separator();
                    ui.heading("Comparison");
                    self.comparison_controls(ui);
                    ui.separator();
                    ui.heading("Reference");
                    self.reference_controls(ui);
                    ui.separator();
                    self.selection_controls(ui);
                });
            });
    }

    fn render_controls(&mut self, ui: &mut egui::Ui) {
        let p = &mut self.params;
        let mut changed = false;
        // A backend that cannot run here (no adapter) says why in the image area.
        changed |= combo(
            ui,
            "Backend",
            &mut p.backend,
            &[Backend::Cpu, Backend::Gpu],
            |b| backend_name(b).into(),
        );
        changed |= combo(ui, "Strategy", &mut p.strategy, &StrategyKind::ALL, |s| {
            s.name().into()
        });
        changed |= ui
            .add(egui::Slider::new(&mut p.mix_weight, 0.0..=1.0).text("Mixture weight w"))
            .on_hover_text(
                "probability of light sampling in the mixture: 0 = BSDF only, 1 = light only",
            )
            .changed();
        changed |= combo(
            ui,
            "Heuristic",
            &mut p.heuristic,
            &[Heuristic::Balance, Heuristic::Power],
            |h| heuristic_name(h).into(),
        );
        changed |= combo(
            ui,
            "Light sampling",
            &mut p.light_sampling,
            &[
                LightSampling::Area,
                LightSampling::SolidAngle,
                LightSampling::SolidAngleCosine,
                LightSampling::Adaptive,
                LightSampling::ProjectedSolidAngle,
            ],
            |s| sampling_name(s).into(),
        );
        changed |= combo(
            ui,
            "Light selection",
            &mut p.light_selection,
            &[LightSelection::Power, LightSelection::Bvh],
            |s| s.name().into(),
        );
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

    fn comparison_controls(&mut self, ui: &mut egui::Ui) {
        let p = &mut self.params;
        let mut changed = ui.checkbox(&mut p.compare, "Compare strategies").changed();
        ui.add_enabled_ui(p.compare, |ui| {
            let mut panes = p.compare_strategies.len();
            ui.horizontal(|ui| {
                ui.label("Panes");
                ui.radio_value(&mut panes, 2, "2");
                ui.radio_value(&mut panes, 3, "3");
            });
            if panes != p.compare_strategies.len() {
                p.compare_strategies.resize(panes, StrategyKind::Mis);
                changed = true;
            }
            for i in 0..p.compare_strategies.len() {
                changed |= combo(
                    ui,
                    &format!("Pane {}", i + 1),
                    &mut p.compare_strategies[i],
                    &StrategyKind::ALL,
                    |s| s.name().into(),
                );
            }
            ui.horizontal(|ui| {
                changed |= ui
                    .radio_value(&mut p.equal_time, false, "Equal samples")
                    .changed();
                changed |= ui
                    .radio_value(&mut p.equal_time, true, "Equal time")
                    .changed();
            });
        });
        if changed {
            self.restart();
        }
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
