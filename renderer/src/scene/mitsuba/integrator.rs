//! `<integrator>`: which of Mitsuba's integrators render the image lumis' path tracer renders,
//! and with which path settings. Every unbiased integrator converges to the same image, so
//! `path`, `prb`, `prb_basic` and `prb_projective` map to lumis' path tracer (their gradient-only
//! parameters are ignored), `direct` and `direct_projective` to it at max_depth 2 (emission seen
//! directly plus direct lighting), `moment` to the one integrator it nests, and `ptracer` to it
//! unless the scene has a delta BSDF: a particle tracer cannot reach the camera through one, so
//! Mitsuba's image lacks what is seen through glass and mirrors ([`check_ptracer`]). Defaults
//! are Mitsuba 3.9.1's: `max_depth` −1 for `path` and `ptracer`, 6 for the `prb` family
//! (`python/ad/integrators/common.py`).

use super::plugin::Plugin;
use super::{Ctx, target};
use crate::scene::desc::{MaterialDesc, SceneDesc};
use crate::scene::error::SceneError;

/// What the integrator makes of the path tracer.
#[derive(Clone, Debug, PartialEq)]
pub struct Mapped {
    /// lumis' `max_depth` (−1 unlimited).
    pub max_depth: i64,
    /// Russian roulette from this path length, where the integrator sets one.
    pub rr_depth: Option<u32>,
    /// Mitsuba's `hide_emitters`.
    pub hide_emitters: bool,
    /// Whether it is `ptracer`, whose image lacks paths through delta BSDFs.
    pub ptracer: bool,
}

/// Parameters of the differentiable integrators that change gradients, not the image.
const GRADIENT_ONLY: [&str; 7] = [
    "sppc",
    "sppp",
    "sppi",
    "guiding",
    "guiding_proj",
    "guiding_rounds",
    "project_seed",
];

/// The mapping of `<integrator>` `it`.
pub fn integrator(ctx: &mut Ctx, it: &Plugin) -> Result<Mapped, SceneError> {
    if it.ty == "moment" {
        // Its image is the nested integrator's; the second moment goes to AOVs lumis has not.
        let nested = it.objects("integrator");
        it.finish("one nested <integrator>")?;
        return match nested.as_slice() {
            [one] => {
                let inner = ctx.plugin(target(one))?;
                integrator(ctx, &inner)
            }
            [] => Err(it.error("a `moment` integrator needs a nested <integrator>")),
            [_, second, ..] => Err(second.el.pos.error(format!(
                "a `moment` integrator with {} nested integrators renders {} images; lumis \
                 renders one (nest one integrator)",
                nested.len(),
                nested.len()
            ))),
        };
    }
    let hide_emitters = it.bool("hide_emitters", false)?;
    let mapped = match it.ty {
        "path" | "ptracer" | "prb" | "prb_basic" | "prb_projective" => {
            let default_depth = if matches!(it.ty, "path" | "ptracer") {
                -1
            } else {
                6
            };
            let depth = it.int("max_depth", default_depth)?;
            if depth < -1 {
                return Err(it.get("max_depth").map_or_else(
                    || it.error("max_depth"),
                    |p| p.error("max_depth must be -1 or at least 0"),
                ));
            }
            let rr = it.int("rr_depth", 5)?;
            let rr = u32::try_from(rr).ok().filter(|&r| r >= 1).ok_or_else(|| {
                it.get("rr_depth").map_or_else(
                    || it.error("rr_depth"),
                    |p| p.error("rr_depth must be at least 1"),
                )
            })?;
            if let Some(p) = it.get("max_depth") {
                ctx.origin("max_depth", p.pos());
            }
            it.ignore(&GRADIENT_ONLY);
            // Particles per pass change the noise, not the image.
            it.ignore(&["samples_per_pass"]);
            Mapped {
                max_depth: depth,
                rr_depth: Some(rr),
                hide_emitters,
                ptracer: it.ty == "ptracer",
            }
        }
        "direct" | "direct_projective" => {
            // Sample counts per pixel sample change noise, not the image; direct_projective
            // fixes its depths at 2 whatever is given.
            it.ignore(&["emitter_samples", "bsdf_samples", "shading_samples"]);
            if it.ty == "direct_projective" {
                it.ignore(&GRADIENT_ONLY);
                it.ignore(&["max_depth", "rr_depth"]);
            }
            ctx.origin("max_depth", it.pos());
            Mapped {
                max_depth: 2,
                rr_depth: None,
                hide_emitters,
                ptracer: false,
            }
        }
        other => {
            return Err(it.error(format!(
                "integrator `{other}` is not supported (lumis maps path, prb, prb_basic, \
                 prb_projective, ptracer, direct, direct_projective and moment)"
            )));
        }
    };
    it.finish(
        "max_depth, rr_depth, hide_emitters; sample counts and gradient-only parameters are \
         ignored",
    )?;
    Ok(mapped)
}

/// `ptracer` is refused where the scene has a delta BSDF: Mitsuba's particle tracer connects
/// each vertex to the camera, which a smooth mirror, glass or coating cannot reflect or refract
/// into, so its image lacks those paths; lumis would render them.
pub fn check_ptracer(desc: &SceneDesc) -> Result<(), String> {
    let delta = desc.materials.iter().find(|m| match m.material {
        MaterialDesc::Conductor { alpha, .. }
        | MaterialDesc::Plastic { alpha, .. }
        | MaterialDesc::Dielectric { alpha, .. } => alpha == 0.0,
        MaterialDesc::ThinDielectric { .. } => true,
        _ => false,
    });
    if let Some(m) = delta {
        return Err(format!(
            "the `ptracer` integrator with a smooth (delta) BSDF (`{}`): a particle tracer \
             cannot reach the camera through it, so Mitsuba's image lacks what lumis' path \
             tracer shows there; use `path`",
            m.name
        ));
    }
    // Mitsuba's connections to the camera stop at a mask as its shadow rays do.
    match desc.materials.iter().find(|m| m.opacity.is_some()) {
        None => Ok(()),
        Some(m) => Err(format!(
            "the `ptracer` integrator with a mask (`{}`): a particle tracer's connections to \
             the camera stop at the mask, so Mitsuba's image lacks what lumis shows through it; \
             use `path`",
            m.name
        )),
    }
}
