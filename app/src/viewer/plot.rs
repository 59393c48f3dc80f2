//! The statistics panel: per lane spp, samples/s, render time, discarded non-finite samples and
//! the current error, and a live log-log plot of error against render time for every lane.

use super::app::ViewerApp;
use super::worker::LaneView;
use egui_plot::{GridMark, HoverPosition, Legend, Line, Plot};

/// Lane colours, shared by the plot and the captions' order.
pub const LANE_COLOURS: [egui::Color32; 3] = [
    egui::Color32::from_rgb(230, 120, 40),
    egui::Color32::from_rgb(60, 150, 230),
    egui::Color32::from_rgb(90, 190, 90),
];

fn stats_line(l: &LaneView) -> String {
    let error = match l.error {
        Some((e, source)) => format!("relMSE {e:.3e} ({})", source.label()),
        None => "relMSE –".into(),
    };
    format!(
        "{}: {} spp · {:.3e} samples/s · {:.1} s · {} non-finite discarded · {}{}",
        l.label,
        l.spp,
        l.samples_per_second,
        l.render_seconds,
        l.nonfinite,
        error,
        if l.done { " · done" } else { "" }
    )
}

/// `10^v` as a short label for log axes.
fn pow10_label(mark: GridMark, unit: &str) -> String {
    let v = 10f64.powf(mark.value);
    if (0.01..1000.0).contains(&v) {
        format!("{}{unit}", (v * 1000.0).round() / 1000.0)
    } else {
        format!("{v:.0e}{unit}")
    }
}

impl ViewerApp {
    pub(crate) fn stats_panel(&mut self, ui: &mut egui::Ui) {
        egui::Panel::bottom("stats")
            .default_size(230.0)
            .resizable(true)
            .show(ui, |ui| {
                let latency = self
                    .last_latency
                    .map_or("–".into(), |t| format!("{:.0} ms", t.as_secs_f64() * 1e3));
                ui.label(format!(
                    "first image after the last change: {latency} · restarts: {}",
                    self.restarts
                ));
                for l in &self.output.lanes {
                    ui.label(stats_line(l));
                }
                Plot::new("convergence")
                    .legend(Legend::default())
                    .x_axis_label("render time (s)")
                    .y_axis_label("relMSE")
                    .x_axis_formatter(|m, _| pow10_label(m, ""))
                    .y_axis_formatter(|m, _| pow10_label(m, ""))
                    .label_formatter(|hover| {
                        let (name, p) = match hover {
                            HoverPosition::NearDataPoint {
                                plot_name,
                                position,
                                ..
                            } => (*plot_name, position),
                            HoverPosition::Elsewhere { position } => ("", position),
                        };
                        Some(format!(
                            "{name}\n{:.3} s\nrelMSE {:.3e}",
                            10f64.powf(p.x),
                            10f64.powf(p.y)
                        ))
                    })
                    .show(ui, |plot| {
                        for (i, l) in self.output.lanes.iter().enumerate() {
                            // Log-log: an unbiased estimator's error falls as 1/t, a straight
                            // line of slope −1, so strategies compare by their offsets.
                            let points: Vec<[f64; 2]> = l
                                .curve
                                .iter()
                                .filter(|p| p.seconds > 0.0 && p.relmse > 0.0)
                                .map(|p| [p.seconds.log10(), p.relmse.log10()])
                                .collect();
                            plot.line(
                                Line::new(l.label.clone(), points)
                                    .color(LANE_COLOURS[i % LANE_COLOURS.len()]),
                            );
                        }
                    });
            });
    }
}
