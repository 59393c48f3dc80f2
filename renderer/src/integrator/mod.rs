//! Integrators: the unidirectional path tracer and the five ways it can estimate direct light.

pub mod mis;
pub mod optimal;
pub mod path;
pub mod technique;

pub use mis::Heuristic;
pub use optimal::OptimalSample;
pub use path::{radiance, radiance_optimal, radiance_recorded, radiance_specialised};
pub use technique::{Technique, TechniqueSplit, TechniqueSums};

use crate::lights::{LightSampling, LightSelection};
use crate::sampler::SamplerKind;

/// How each path vertex estimates the light arriving directly from emitters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Strategy {
    /// Next-event estimation only: BSDF-sampled rays that hit an emitter add nothing, except after
    /// a delta bounce and for the camera ray.
    Light,
    /// BSDF sampling only: emission counts when a BSDF-sampled ray hits it.
    Bsdf,
    /// Veach's one-sample model: at each vertex the direct-light direction is drawn from the mixture
    /// `w·p_light + (1−w)·p_bsdf` (light sampling with probability `w`, else the BSDF sample) and
    /// divided by that mixture pdf. The path always continues by BSDF sampling, so indirect light
    /// stays unbiased for every `w` in `[0, 1]`; `w = 0` equals `Bsdf` and `w = 1` equals `Light`.
    /// (The original program continued the path along the mixture direction, which loses all
    /// indirect light at `w = 1`.)
    Mixture {
        /// Probability `w` of light sampling.
        light_weight: f32,
    },
    /// Next-event estimation plus BSDF sampling, weighted by a multiple-importance heuristic.
    Mis {
        /// Balance or power heuristic.
        heuristic: Heuristic,
    },
    /// Next-event estimation plus BSDF sampling with optimal MIS weights (Kondapaneni et al.
    /// 2019) at the camera ray's first vertex: the balance heuristic plus a control variate whose
    /// per-pixel coefficients α the engine learns from each pixel's earlier samples
    /// ([`optimal`]); the power heuristic at deeper vertices. Rendered through
    /// [`radiance`] without the engine's α, it is α = 0 (the balance heuristic there).
    MisOptimal,
}

impl Strategy {
    /// The strategy's name as the CLI spells it.
    pub fn name(&self) -> &'static str {
        match self {
            Strategy::Light => "light",
            Strategy::Bsdf => "bsdf",
            Strategy::Mixture { .. } => "mixture",
            Strategy::Mis { .. } => "mis",
            Strategy::MisOptimal => "mis-optimal",
        }
    }
}

/// Everything that controls the estimator besides the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Direct-lighting strategy.
    pub strategy: Strategy,
    /// How lights are sampled.
    pub light_sampling: LightSampling,
    /// How next-event estimation chooses the light to sample (power, or a light BVH that
    /// weighs the receiver's position and normal).
    pub light_selection: LightSelection,
    /// Overrides the scene's `max_depth` (`-1` = unlimited) when set.
    pub max_depth: Option<i32>,
    /// Path length (in segments) from which Russian roulette may end paths.
    pub rr_depth: u32,
    /// Where the random numbers come from (either backend has every sampler).
    pub sampler: SamplerKind,
}

impl Default for Settings {
    fn default() -> Settings {
        Settings {
            strategy: Strategy::Mis {
                heuristic: Heuristic::Power,
            },
            light_sampling: LightSampling::SolidAngle,
            light_selection: LightSelection::Power,
            max_depth: None,
            rr_depth: 5,
            sampler: SamplerKind::Independent,
        }
    }
}
