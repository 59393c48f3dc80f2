//! The statistics panel: per lane spp, samples/s, render time, discarded non-finite samples and
//! the current error; the time and spp each lane needs to reach the target relMSE, predicted
//! from its curve's fitted 1/t line (or, with equal-error pacing, measured); and a live log-log
//! plot against render time of every lane's relMSE (with the fitted lines and the target) or of
//! its efficiency 1/(relMSE · t), flat for an unbiased estimator, higher is better.

use super::app::ViewerApp;
use super::params::Pacing;
use super::prediction::{InverseFit, describe};
use super::worker::LaneView;
use egui_plot::{GridMark, HLine, HoverPosition, Legend, Line, LineStyle, Plot};

/// Lane colours, shared by the plot and the captions' order.
pub const LANE_COLOURS: [egui::Color32; 3] = [
    egui::Color32::from_rgb(230, 120, 40),
    egui::Color32::from_rgb(60, 150, 230),
    egui::Color32::from_rgb(90, 190, 90),
];

/// A lane's statistics; `excluded`: its image lacks the scene's delta lights (said after the spp).
fn stats_line(l: &LaneView, excluded: bool) -> String {
    let error = match l.error {
        Some((e, source)) => format!("relMSE {e:.3e} ({})", source.label()),
        None => "relMSE –".into(),
    };
    format!(
        "{}: {} spp{} · {:.3e} samples/s · {:.1} s · {} non-finite discarded · {}{}",
        l.label,
        l.spp,
        if excluded {
            format!(" · {}", crate::delta_lights::CAPTION)
        } else {
            String::new()
        },
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
                let target = self.params.target_relmse;
                for l in &self.output.lanes {
                    ui.label(format!(
                        "{} · {}",
                        stats_line(l, self.misses_delta_lights(l)),
                        describe(&l.curve, target)
                    ));
                }
                if self.params.pacing == Pacing::EqualError {
                    ui.label(format!("equal error (relMSE {target:.0e}):"));
                    for line in super::equal_error::report(&self.output.lanes, target) {
                        ui.label(line);
                    }
                }
                let efficiency = self.plot_efficiency;
                ui.horizontal(|ui| {
                    ui.label("Plot");
                    ui.radio_value(&mut self.plot_efficiency, false, "relMSE");
                    ui.radio_value(&mut self.plot_efficiency, true, "efficiency 1/(relMSE·t)");
                });
                let y_name = if efficiency { "efficiency" } else { "relMSE" };
                Plot::new("convergence")
                    .legend(Legend::default())
                    .x_axis_label("render time (s)")
                    .y_axis_label(if efficiency {
                        "1/(relMSE · s)"
                    } else {
                        "relMSE"
                    })
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
                            "{name}\n{:.3} s\n{y_name} {:.3e}",
                            10f64.powf(p.x),
                            10f64.powf(p.y)
                        ))
                    })
                    .show(ui, |plot| {
                        for (i, l) in self.output.lanes.iter().enumerate() {
                            // Log-log: an unbiased estimator's error falls as 1/t, a straight
                            // line of slope −1, so strategies compare by their offsets.
                            // Efficiency 1/(relMSE·t) is flat for such an estimator.
                            let y = |e: f64, t: f64| if efficiency { 1.0 / (e * t) } else { e };
                            let colour = LANE_COLOURS[i % LANE_COLOURS.len()];
                            let points: Vec<[f64; 2]> = l
                                .curve
                                .iter()
                                .filter(|p| p.seconds > 0.0 && p.relmse > 0.0)
                                .map(|p| [p.seconds.log10(), y(p.relmse, p.seconds).log10()])
                                .collect();
                            plot.line(Line::new(l.label.clone(), points).color(colour));
                            // The fitted 1/t line, from the first point out to the target.
                            if let Some(fit) = InverseFit::fit(&l.curve) {
                                let t0 = l.curve[0].seconds.max(1e-3);
                                let t1 = fit.seconds_to(target).max(l.render_seconds);
                                let line: Vec<[f64; 2]> = [t0, t1]
                                    .iter()
                                    .map(|&t| [t.log10(), y(fit.per_second / t, t).log10()])
                                    .collect();
                                plot.line(
                                    Line::new(format!("{} 1/t fit", l.label), line)
                                        .color(colour.gamma_multiply(0.6))
                                        .style(LineStyle::dashed_dense()),
                                );
                            }
                        }
                        if !efficiency {
                            plot.hline(
                                HLine::new("target", target.log10())
                                    .color(egui::Color32::GRAY)
                                    .style(LineStyle::dotted_loose()),
                            );
                        }
                    });
            });
    }
}
