//! The Panes section of the side panel: single view, side-by-side comparison (2 or 3 strategies,
//! optionally one alone) or wipe (two sides, each a strategy on a backend or the reference), and
//! how lanes share time: equal samples, equal time, or each until the same error. Choices of
//! what renders restart accumulation; which pane is shown alone and the divider do not.

use super::app::ViewerApp;
use super::controls::combo;
use super::menus;
use super::params::{Pacing, StrategyKind, ViewMode, light_sampling_short_name};
use super::wipe::WipeSide;
use lumis::lights::LightSampling;

/// Range of the target relMSE slider (logarithmic).
const TARGET_RANGE: std::ops::RangeInclusive<f64> = 1e-5..=1.0;

impl ViewerApp {
    pub(crate) fn panes_controls(&mut self, ui: &mut egui::Ui) {
        let p = &mut self.params;
        let mut changed = false;
        ui.horizontal(|ui| {
            for (mode, name) in [
                (ViewMode::Single, "Single"),
                (ViewMode::Compare, "Side by side"),
                (ViewMode::Wipe, "Wipe"),
            ] {
                changed |= ui.radio_value(&mut p.view, mode, name).changed();
            }
        });
        match p.view {
            ViewMode::Single => {}
            ViewMode::Compare => {
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
                p.compare_light_sampling.resize(panes, None);
                // Each pane's light sampling: the Render menu's, or a method of its own.
                let methods: Vec<Option<LightSampling>> = std::iter::once(None)
                    .chain(menus::LIGHT_SAMPLING.iter().map(|(m, _)| Some(*m)))
                    .collect();
                for i in 0..p.compare_strategies.len() {
                    changed |= combo(
                        ui,
                        &format!("Pane {}", i + 1),
                        &mut p.compare_strategies[i],
                        &StrategyKind::ALL,
                        |s| s.name().into(),
                    );
                    changed |= combo(
                        ui,
                        &format!("Pane {} light sampling", i + 1),
                        &mut p.compare_light_sampling[i],
                        &methods,
                        |m| {
                            m.map_or("as in Render".into(), |m| {
                                light_sampling_short_name(m).into()
                            })
                        },
                    );
                }
                let n = p.compare_strategies.len();
                let options: Vec<Option<usize>> =
                    std::iter::once(None).chain((0..n).map(Some)).collect();
                // Display only: which pane fills the area alone.
                combo(ui, "Show (S)", &mut self.solo, &options, |s| {
                    s.map_or("all panes".into(), |k| format!("pane {} alone", k + 1))
                });
            }
            ViewMode::Wipe => {
                let sides = WipeSide::menu();
                for (i, name) in ["Wipe A (left)", "Wipe B (right)"].into_iter().enumerate() {
                    changed |= combo(ui, name, &mut p.wipe[i], &sides, |s| s.name());
                }
                ui.add(egui::Slider::new(&mut self.wipe_position, 0.0..=1.0).text("Divider"));
            }
        }
        ui.horizontal(|ui| {
            for pacing in Pacing::ALL {
                changed |= ui
                    .radio_value(&mut p.pacing, pacing, pacing.label())
                    .changed();
            }
        });
        // The target is display only (the predictions) unless lanes stop at it.
        let target = ui
            .add(
                egui::Slider::new(&mut p.target_relmse, TARGET_RANGE)
                    .logarithmic(true)
                    .text("Target relMSE"),
            )
            .on_hover_text(
                "the error the convergence panel predicts the time to; equal error stops \
                 each pane there",
            );
        changed |= target.changed() && p.pacing == Pacing::EqualError;
        if changed {
            self.restart();
        }
    }
}
