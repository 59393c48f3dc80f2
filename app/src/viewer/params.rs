//! The estimator parameters the controls edit, and the lanes (independent accumulations) they
//! describe: one in the single view, two or three in the comparison view, two in the wipe (or
//! one and the reference).

use super::wipe::WipeSide;
use super::worker::LaneSpec;
use lumis::engine::Backend;
use lumis::integrator::{Heuristic, Settings, Strategy};
use lumis::lights::{LightSampling, LightSelection};
use lumis::sampler::SamplerKind;

/// A direct-lighting strategy without its parameters (for menus).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StrategyKind {
    /// Light sampling only.
    Light,
    /// BSDF sampling only.
    Bsdf,
    /// One-sample mixture with weight w.
    Mixture,
    /// Two-sample MIS.
    Mis,
    /// Two-sample MIS with optimal weights learnt per pixel.
    MisOptimal,
}

impl StrategyKind {
    /// Every strategy, in menu order.
    pub const ALL: [StrategyKind; 5] = [
        StrategyKind::Light,
        StrategyKind::Bsdf,
        StrategyKind::Mixture,
        StrategyKind::Mis,
        StrategyKind::MisOptimal,
    ];

    /// The name the CLI uses.
    pub fn name(self) -> &'static str {
        match self {
            StrategyKind::Light => "light",
            StrategyKind::Bsdf => "bsdf",
            StrategyKind::Mixture => "mixture",
            StrategyKind::Mis => "mis",
            StrategyKind::MisOptimal => "mis-optimal",
        }
    }
}

/// How the image area is arranged.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ViewMode {
    /// One strategy.
    Single,
    /// Two or three strategies side by side (or one of them alone, see `PaneView`).
    Compare,
    /// Two renders (or a render and the reference) in one image, split by a divider.
    Wipe,
}

/// How render time is shared out between lanes, and when they stop.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pacing {
    /// Every lane gets the same samples per pixel.
    EqualSamples,
    /// Every lane gets the same render time.
    EqualTime,
    /// Lanes take turns by render time, and each stops when its relMSE reaches
    /// `RenderParams::target_relmse`: the times to equal error are the comparison.
    EqualError,
}

impl Pacing {
    /// Every pacing, in menu order.
    pub const ALL: [Pacing; 3] = [Pacing::EqualSamples, Pacing::EqualTime, Pacing::EqualError];

    /// The label of its radio button.
    pub fn label(self) -> &'static str {
        match self {
            Pacing::EqualSamples => "Equal samples",
            Pacing::EqualTime => "Equal time",
            Pacing::EqualError => "Equal error",
        }
    }
}

/// Everything about how the lanes render.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderParams {
    /// Where to render.
    pub backend: Backend,
    /// Strategy of the single view.
    pub strategy: StrategyKind,
    /// Probability of light sampling in the mixture, in [0, 1].
    pub mix_weight: f32,
    /// MIS heuristic.
    pub heuristic: Heuristic,
    /// How points on lights are chosen.
    pub light_sampling: LightSampling,
    /// How next-event estimation chooses a light.
    pub light_selection: LightSelection,
    /// Overrides the scene's maximum path depth.
    pub max_depth: Option<i32>,
    /// Where the random numbers come from (`--sampler`).
    pub sampler: SamplerKind,
    /// Stop at this many samples per pixel (0: never).
    pub spp_limit: u32,
    /// Single view, side-by-side comparison or wipe.
    pub view: ViewMode,
    /// Strategies of the comparison panes (two or three).
    pub compare_strategies: Vec<StrategyKind>,
    /// Per comparison pane, a light-sampling method of its own (`None`, or no entry: the Render
    /// menu's), so that panes can compare methods (e.g. solid angle against projected solid
    /// angle) as well as strategies.
    pub compare_light_sampling: Vec<Option<LightSampling>>,
    /// The wipe's left (A) and right (B) sides.
    pub wipe: [WipeSide; 2],
    /// How lanes share render time (equal samples, equal time, or until equal error).
    pub pacing: Pacing,
    /// The relMSE the convergence panel predicts the time to, and at which equal-error pacing
    /// stops each lane.
    pub target_relmse: f64,
}

impl Default for RenderParams {
    fn default() -> RenderParams {
        RenderParams {
            backend: Backend::Cpu,
            strategy: StrategyKind::Mis,
            mix_weight: 0.5,
            heuristic: Heuristic::Power,
            light_sampling: LightSampling::SolidAngle,
            light_selection: LightSelection::Power,
            max_depth: None,
            // The CLI's default too (docs/performance.md, "Sobol sampler").
            sampler: SamplerKind::Sobol,
            spp_limit: 0,
            view: ViewMode::Single,
            compare_strategies: vec![StrategyKind::Light, StrategyKind::Bsdf, StrategyKind::Mis],
            compare_light_sampling: Vec::new(),
            wipe: [
                WipeSide::Render(StrategyKind::Light, None),
                WipeSide::Render(StrategyKind::Mis, None),
            ],
            pacing: Pacing::EqualSamples,
            target_relmse: 1e-2,
        }
    }
}

impl RenderParams {
    /// The renderer settings of `kind` with these parameters.
    pub fn settings(&self, kind: StrategyKind) -> Settings {
        let strategy = match kind {
            StrategyKind::Light => Strategy::Light,
            StrategyKind::Bsdf => Strategy::Bsdf,
            StrategyKind::Mixture => Strategy::Mixture {
                light_weight: self.mix_weight.clamp(0.0, 1.0),
            },
            StrategyKind::Mis => Strategy::Mis {
                heuristic: self.heuristic,
            },
            StrategyKind::MisOptimal => Strategy::MisOptimal,
        };
        Settings {
            strategy,
            light_sampling: self.light_sampling,
            light_selection: self.light_selection,
            max_depth: self.max_depth,
            sampler: self.sampler,
            ..Settings::default()
        }
    }

    /// The lanes rendered: the single strategy, the comparison's, or the wipe's renders (a
    /// reference side has no lane). A lane without a backend of its own uses `backend`.
    pub fn lanes(&self) -> Vec<LaneSpec> {
        let lane_with = |k: StrategyKind, backend: Option<Backend>, ls: Option<LightSampling>| {
            let backend = backend.unwrap_or(self.backend);
            let mut label = lane_label(k, self);
            let mut settings = self.settings(k);
            if let Some(ls) = ls {
                label += &format!(" · {}", light_sampling_short_name(ls));
                settings.light_sampling = ls;
            }
            if backend != self.backend {
                label += match backend {
                    Backend::Cpu => " (CPU)",
                    Backend::Gpu => " (GPU)",
                };
            }
            LaneSpec {
                label,
                settings,
                backend,
            }
        };
        let lane = |k: StrategyKind, backend: Option<Backend>| lane_with(k, backend, None);
        match self.view {
            ViewMode::Single => vec![lane(self.strategy, None)],
            ViewMode::Compare => (self.compare_strategies.iter().enumerate())
                .map(|(i, &k)| {
                    let ls = self.compare_light_sampling.get(i).copied().flatten();
                    lane_with(k, None, ls)
                })
                .collect(),
            ViewMode::Wipe => {
                let mut lanes: Vec<LaneSpec> = (self.wipe.iter())
                    .filter_map(|s| match *s {
                        WipeSide::Render(k, b) => Some(lane(k, b)),
                        WipeSide::Reference => None,
                    })
                    .collect();
                // The same strategy on the same backend twice (two equal lanes) still gets two
                // names, so that the panes and the plot tell them apart.
                if lanes.len() == 2 && lanes[0].label == lanes[1].label {
                    lanes[0].label += " A";
                    lanes[1].label += " B";
                }
                lanes
            }
        }
    }
}

/// A light-sampling method as the CLI names it (short enough for a pane's caption).
pub fn light_sampling_short_name(ls: LightSampling) -> &'static str {
    match ls {
        LightSampling::Area => "area",
        LightSampling::SolidAngle => "solid-angle",
        LightSampling::SolidAngleCosine => "solid-angle-cosine",
        LightSampling::Adaptive => "adaptive",
        LightSampling::ProjectedSolidAngle => "projected-solid-angle",
    }
}

fn lane_label(kind: StrategyKind, p: &RenderParams) -> String {
    match kind {
        StrategyKind::Mixture => format!("mixture w={:.2}", p.mix_weight),
        StrategyKind::Mis => format!(
            "mis {}",
            match p.heuristic {
                Heuristic::Balance => "balance",
                Heuristic::Power => "power",
            }
        ),
        k => k.name().to_string(),
    }
}
