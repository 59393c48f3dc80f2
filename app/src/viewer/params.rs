//! The estimator parameters the controls edit, and the lanes (independent accumulations) they
//! describe: one in the single view, two or three in the comparison view.

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
    /// Show the comparison view instead of the single view.
    pub compare: bool,
    /// Strategies of the comparison panes (two or three).
    pub compare_strategies: Vec<StrategyKind>,
    /// In the comparison view, give every pane the same render time (else the same samples).
    pub equal_time: bool,
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
            sampler: SamplerKind::Independent,
            spp_limit: 0,
            compare: false,
            compare_strategies: vec![StrategyKind::Light, StrategyKind::Bsdf, StrategyKind::Mis],
            equal_time: false,
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

    /// The lanes shown: the single strategy, or the comparison's.
    pub fn lanes(&self) -> Vec<LaneSpec> {
        let kinds: &[StrategyKind] = if self.compare {
            &self.compare_strategies
        } else {
            std::slice::from_ref(&self.strategy)
        };
        kinds
            .iter()
            .map(|&k| LaneSpec {
                label: lane_label(k, self),
                settings: self.settings(k),
            })
            .collect()
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
