//! The unidirectional path tracer. One function, one loop: it follows a camera path, gathers
//! emission seen along it, and estimates direct light at each vertex with the chosen [`Strategy`].
//!
//! Path length follows Mitsuba's `max_depth`: a path of `k` segments ends at its `k`-th vertex, so
//! `1` keeps only emission seen by the camera and `2` adds direct lighting.
//!
//! Transmission (dielectrics and thin sheets, [`crate::materials::Material::transmits`]): the
//! frame of a transmitting material is never flipped, so `wo` and `wi` may lie on either side;
//! next-event estimation at a rough dielectric samples lights on both sides; shadow rays are
//! blocked by dielectrics like by any surface (Mitsuba's `path`); Russian roulette sees the
//! throughput times η'² of every refraction (pbrt-v4's `etaScale`), so radiance's 1/η'² does not
//! kill paths inside glass. The loop is compiled twice, with and without this code
//! (`TRANSMISSION`); scenes without a transmitting material run the version without it, bit for
//! bit the renderer they ran before.
//!
//! Shading normals (meshes with vertex normals): the BSDF frame is the shading normal's, the
//! geometric normal decides sides and ray offsets, and a direction that the two normals put on
//! different sides does not count (`same_side`; docs/shading-normals.md says why).
//!
//! Emission is looked up through the scene ([`Scene::emitted`] at hits, [`Scene::sample_light`]
//! for light samples), which evaluates a textured emitter's texture at the point.
//! WGSL twin: `integrator/path.wgsl`.

use super::optimal::{OptimalSample, balance_ratios};
use super::technique::{Technique, TechniqueSplit};
use super::{Heuristic, Settings, Strategy};
use crate::geometry::SurfaceHit;
use crate::geometry::primitive::NONE;
use crate::geometry::ray::{Ray, spawn_ray, spawn_ray_to};
use crate::geometry::tangent;
use crate::materials::normal_map::{self, NormalMap, VertexBsdf};
use crate::materials::{bump_map, mix};
use crate::math::{Frame, max_component};
use crate::sampler::Sampler;
use crate::scene::Scene;
use glam::Vec3;

/// How emission found by the next BSDF-sampled ray is weighted.
#[derive(Clone, Copy, Debug)]
enum EmissionWeight {
    /// Full weight: camera rays, delta bounces, BSDF-only sampling.
    One,
    /// Zero: light sampling already accounted for this light.
    Zero,
    /// MIS weight of the BSDF sample with this pdf against light sampling.
    Mis { p_bsdf: f32, heuristic: Heuristic },
    /// One-sample mixture, BSDF branch: `p_bsdf / (w·p_light + (1−w)·p_bsdf)`.
    Mixture { p_bsdf: f32, light_weight: f32 },
    /// Already worked out (by `mis-optimal`'s first vertex, which needed the light pdf first).
    Fixed(f32),
}

/// How next-event estimation weighs its sample.
#[derive(Clone, Copy, Debug)]
enum NeeWeight {
    /// Light sampling alone.
    One,
    /// The light branch of the one-sample mixture with this light probability.
    Mixture(f32),
    /// Two-sample MIS with this heuristic.
    Mis(Heuristic),
}

/// Where a light sample ended, for `mis-optimal`'s control variate ([`super::optimal`]).
#[derive(Clone, Copy, Debug)]
enum NeeOutcome {
    /// Nothing BSDF sampling could also produce: a failure, a blocked shadow ray, a direction
    /// the shading-normal rule rejects.
    Pure,
    /// A visible point on an emitter, with the balance weights `(r_L, r_B)` there.
    Combined { rl: f32, rb: f32 },
    /// A delta light's sample, pure as well (BSDF sampling never finds a delta light), of
    /// contribution `h` (zero where blocked).
    Delta { h: Vec3 },
}

/// The BSDF sample of `mis-optimal`'s first vertex, whose control variate term waits for the
/// hit of its ray.
#[derive(Clone, Copy, Debug)]
struct PendingBsdf {
    /// Path throughput at the vertex.
    beta: Vec3,
    /// The sample's weight (f·cos/pdf, or the delta lobe's).
    weight: Vec3,
    /// Its pdf (non-delta samples).
    pdf: f32,
    /// Whether it came from a delta lobe.
    delta: bool,
}

/// Radiance arriving at the camera along `ray` (one sample of the estimator).
pub fn radiance(scene: &Scene, ray: Ray, sampler: &mut Sampler, settings: &Settings) -> Vec3 {
    if scene.has_transmission() {
        radiance_specialised::<true>(scene, ray, sampler, settings)
    } else {
        radiance_specialised::<false>(scene, ray, sampler, settings)
    }
}

/// [`radiance`] compiled for scenes with (`TRANSMISSION = true`) or without transmitting
/// materials; the caller hoists the choice out of its loops. `false` on a scene with a dielectric
/// is a logic error (caught in debug builds).
pub fn radiance_specialised<const TRANSMISSION: bool>(
    scene: &Scene,
    ray: Ray,
    sampler: &mut Sampler,
    settings: &Settings,
) -> Vec3 {
    trace::<TRANSMISSION>(scene, ray, sampler, settings, None, None)
}

/// [`radiance_specialised`] for [`Strategy::MisOptimal`] with the sample's α: adds the control
/// variate at the camera ray's first vertex and records the sample's moments in `optimal`
/// ([`super::optimal`]). Other strategies ignore `optimal`.
pub fn radiance_optimal<const TRANSMISSION: bool>(
    scene: &Scene,
    ray: Ray,
    sampler: &mut Sampler,
    settings: &Settings,
    optimal: &mut OptimalSample,
) -> Vec3 {
    trace::<TRANSMISSION>(scene, ray, sampler, settings, Some(optimal), None)
}

/// [`radiance_specialised`] with everything the engine may ask for besides the radiance:
/// `mis-optimal`'s α and moments (as [`radiance_optimal`]), and the sample's split by technique
/// ([`super::technique`]; the returned radiance is the same bit for bit with or without it).
pub fn radiance_recorded<const TRANSMISSION: bool>(
    scene: &Scene,
    ray: Ray,
    sampler: &mut Sampler,
    settings: &Settings,
    optimal: Option<&mut OptimalSample>,
    split: Option<&mut TechniqueSplit>,
) -> Vec3 {
    trace::<TRANSMISSION>(scene, ray, sampler, settings, optimal, split)
}

/// Adds `v` to the sample's radiance `l` and, when recorded, to the part of `technique`.
#[inline(always)]
fn add(l: &mut Vec3, split: &mut Option<&mut TechniqueSplit>, technique: Technique, v: Vec3) {
    *l += v;
    if let Some(s) = split {
        s.add(technique, v);
    }
}

/// Emission found at path depth `depth` was found by the camera ray (1) or by a BSDF sample.
#[inline(always)]
fn emission_technique(depth: i32) -> Technique {
    if depth == 1 {
        Technique::Camera
    } else {
        Technique::Bsdf
    }
}

/// The path tracer's loop; `optimal` carries `mis-optimal`'s α and moments when the engine
/// learns them; `split` records which technique contributed what.
fn trace<const TRANSMISSION: bool>(
    scene: &Scene,
    mut ray: Ray,
    sampler: &mut Sampler,
    settings: &Settings,
    mut optimal: Option<&mut OptimalSample>,
    mut split: Option<&mut TechniqueSplit>,
) -> Vec3 {
    debug_assert!(TRANSMISSION || !scene.has_transmission());
    let max_depth = settings.max_depth.unwrap_or(scene.max_depth);
    let mut l = Vec3::ZERO;
    let mut beta = Vec3::ONE;
    // Product of η'² over the refractions so far: Russian roulette sees beta·eta_scale.
    let mut eta_scale = 1.0f32;
    let mut weight_rule = EmissionWeight::One;
    let mut prev_p = ray.o;
    // The previous vertex's shading normal, for the cosine warp's pdf (zero at the camera).
    let mut prev_ns = Vec3::ZERO;
    // The normal that vertex gave the light sampler (`LightSampling::receiver_normal`), for the
    // light pdf (light selection sees `prev_ns`).
    let mut prev_light_ns = Vec3::ZERO;
    let mut depth: i32 = 0;
    // mis-optimal: the first vertex's BSDF sample awaiting its hit, and whether the path ends once
    // that is resolved (roulette or a zero throughput would have ended it before tracing).
    let mut pending: Option<PendingBsdf> = None;
    let mut stop = false;
    loop {
        depth += 1;
        // The sampler's bounce: 0 at the camera ray's hit.
        let bounce = (depth - 1) as u32;
        let hit = scene.intersect(&ray);
        if let (Some(p), Some(opt)) = (pending.take(), optimal.as_deref_mut()) {
            let (cv, w) = resolve_bsdf(
                scene,
                settings,
                &ray,
                hit.as_ref(),
                prev_p,
                [prev_ns, prev_light_ns],
                p,
                opt,
            );
            add(&mut l, &mut split, Technique::ControlVariate, cv);
            weight_rule = EmissionWeight::Fixed(w);
            if stop {
                break;
            }
        }
        // Mitsuba's hide_emitters: what the camera ray hits does not count its emission.
        let hidden = scene.hide_emitters && depth == 1;
        let Some(hit) = hit else {
            if let Some(bg) = scene.background_light.filter(|_| !hidden) {
                let light = &scene.lights[bg as usize];
                let w = emission_weight(scene, settings, weight_rule, bg, prev_p, prev_ns, || {
                    light.pdf(
                        prev_p,
                        prev_light_ns,
                        ray.d,
                        Vec3::ZERO,
                        Vec3::ZERO,
                        settings.light_sampling,
                    )
                });
                let le = light.radiance(Vec3::ZERO, ray.d);
                add(&mut l, &mut split, emission_technique(depth), beta * le * w);
            }
            break;
        };
        let prim = &scene.accel.primitives()[hit.prim as usize];
        if prim.light != NONE && !hidden {
            let light = &scene.lights[prim.light as usize];
            let le = scene.emitted(prim.light, &hit, ray.d);
            if le != Vec3::ZERO {
                let w = emission_weight(
                    scene,
                    settings,
                    weight_rule,
                    prim.light,
                    prev_p,
                    prev_ns,
                    || {
                        light.pdf(
                            prev_p,
                            prev_light_ns,
                            ray.d.normalize(),
                            hit.p,
                            hit.n,
                            settings.light_sampling,
                        )
                    },
                );
                add(&mut l, &mut split, emission_technique(depth), beta * le * w);
            }
        }
        if max_depth >= 0 && depth >= max_depth {
            break;
        }
        let wo_world = -ray.d.normalize();
        // `n`: the geometric normal, which decides sides and ray offsets; the BSDF lives in the
        // frame of the shading normal `ns` (the geometric one where the mesh has none).
        let mut n = hit.n;
        // A two-sided pair shows its back material to a path that arrives on its back.
        let arrives_back = n.dot(wo_world) < 0.0;
        let shaded = scene.shading_at(&hit, prim.material, arrives_back);
        let (material, detail_map, blend) = (&*shaded.material, shaded.detail_map, shaded.blend);
        let shading_normal = if scene.attributes.has_normals() {
            scene.attributes.shading_normal(prim.attr, hit.b, n)
        } else {
            None
        };
        let shading = shading_normal.is_some();
        let mut ns = shading_normal.unwrap_or(n);
        let transmits = TRANSMISSION && material.transmits();
        let back = arrives_back && !transmits;
        if back {
            if !scene.two_sided[prim.material as usize] {
                break;
            }
            n = -n;
            ns = -ns;
        }
        // An anisotropic lobe's α_u runs along the surface's ∂p/∂u; any frame about the normal
        // serves the others.
        let mut frame = if material.is_anisotropic() {
            let dp_du = tangent::dp_du(prim, &scene.attributes, &hit);
            tangent::tangent_frame(ns, dp_du)
        } else {
            Frame::from_normal(ns)
        };
        // A normal or bump map tilts the frame the material sees, about the frame of ∂p/∂u
        // (`materials/normal_map.rs`, `materials/bump_map.rs`).
        let mut perturbation = None;
        if let Some((map, at)) = detail_map {
            // A bump map's ∂p/∂u, kept for the base frame (`dp_duv`'s is `dp_du`'s, bit for bit).
            let mut bump_dp_du = None;
            let tilt = match map.height_scale {
                None => Some(NormalMap::decode(map.texture.eval(at))),
                // In the front's frame, which `seen_from` mirrors on the back as for a texel.
                Some(scale) => map.texture.eval_1_grad(at.uv).and_then(|g| {
                    let (dp_du, dp_dv) = tangent::dp_duv(prim, &scene.attributes, &hit)?;
                    bump_dp_du = Some(dp_du);
                    let ns_front = if back { -ns } else { ns };
                    let front = tangent::tangent_frame(ns_front, dp_du);
                    bump_map::local_normal(scale * g, dp_du, dp_dv, ns_front, hit.n, &front)
                }),
            };
            let base = || {
                let dp_du =
                    bump_dp_du.unwrap_or_else(|| tangent::dp_du(prim, &scene.attributes, &hit));
                normal_map::seen_from(tangent::tangent_frame(ns, dp_du), back)
            };
            if let Some((f, p)) = tilt.and_then(|n| map.perturb(n, base, wo_world)) {
                frame = f;
                perturbation = Some(p);
            }
        }
        let bsdf = VertexBsdf {
            material,
            perturbation,
        };
        let wo = frame.to_local(wo_world);
        // A reflecting surface is seen from its front only; a dielectric from either side.
        let wo_invalid = if transmits { wo.z == 0.0 } else { wo.z <= 0.0 };
        if wo_invalid || (shading && !same_side(wo_world, n, wo.z)) {
            break;
        }

        // Direct light by light sampling, and the rule for emission the BSDF sample will find.
        let smooth = material.has_smooth_part() && scene.light_sampler.is_some();
        // mis-optimal's first vertex: the balance heuristic, plus the control variate when the
        // engine supplies α.
        let optimal_vertex = depth == 1 && settings.strategy == Strategy::MisOptimal;
        let cv = smooth && optimal_vertex && optimal.is_some();
        let mut do_nee = false;
        let mut nee_weight = NeeWeight::One;
        weight_rule = if !smooth {
            EmissionWeight::One
        } else {
            match settings.strategy {
                Strategy::Light => {
                    do_nee = true;
                    EmissionWeight::Zero
                }
                Strategy::Bsdf => EmissionWeight::One,
                Strategy::Mis { heuristic } => {
                    do_nee = true;
                    nee_weight = NeeWeight::Mis(heuristic);
                    EmissionWeight::Mis {
                        p_bsdf: 0.0,
                        heuristic,
                    }
                }
                Strategy::MisOptimal => {
                    let heuristic = if optimal_vertex {
                        Heuristic::Balance
                    } else {
                        Heuristic::Power
                    };
                    do_nee = true;
                    nee_weight = NeeWeight::Mis(heuristic);
                    EmissionWeight::Mis {
                        p_bsdf: 0.0,
                        heuristic,
                    }
                }
                Strategy::Mixture { light_weight } => {
                    if sampler.mixture_1d(bounce) < light_weight {
                        do_nee = true;
                        nee_weight = NeeWeight::Mixture(light_weight);
                        EmissionWeight::Zero
                    } else {
                        EmissionWeight::Mixture {
                            p_bsdf: 0.0,
                            light_weight,
                        }
                    }
                }
            }
        };
        if do_nee {
            let u_light = sampler.light_select_1d(bounce);
            let u = sampler.light_2d(bounce);
            let (c, outcome) = direct_light::<TRANSMISSION>(
                scene, settings, &hit, n, &frame, wo, &bsdf, u_light, u, nee_weight, cv, transmits,
                shading,
            );
            add(&mut l, &mut split, Technique::Light, beta * c);
            if let (true, Some(opt)) = (cv, optimal.as_deref_mut()) {
                let term = match outcome {
                    NeeOutcome::Pure => opt.pure_light(),
                    NeeOutcome::Delta { h } => opt.delta_light(h),
                    NeeOutcome::Combined { rl, rb } => opt.combined(c, rl, rb),
                };
                let cv = beta * (opt.constant() + term);
                add(&mut l, &mut split, Technique::ControlVariate, cv);
            }
        }

        // Continue the path by BSDF sampling.
        let Some(mut bs) =
            bsdf.sample::<TRANSMISSION>(wo, sampler.bsdf_lobe_1d(bounce), sampler.bsdf_2d(bounce))
        else {
            if let (true, Some(opt)) = (cv, optimal.as_deref_mut()) {
                let cv = beta * opt.pure_bsdf(Vec3::ZERO);
                add(&mut l, &mut split, Technique::ControlVariate, cv);
            }
            break;
        };
        // Mitsuba's blend weighs a delta sample against the other part there (`materials/mix.rs`).
        if let (true, Some(b)) = (bs.delta, blend) {
            let partner = scene.material_at(&hit, b.partner, arrives_back);
            let (f, p) = (
                partner.eval_specialised::<TRANSMISSION>(wo, bs.wi),
                partner.pdf_specialised::<TRANSMISSION>(wo, bs.wi),
            );
            bs.weight = mix::blend_delta_weight(bs.weight, bs.pdf, b.weight, f, p);
        }
        let wi = frame.to_world(bs.wi);
        let wi_ok = !shading || same_side(wi, n, bs.wi.z);
        if cv {
            if wi_ok {
                pending = Some(PendingBsdf {
                    beta,
                    weight: bs.weight,
                    pdf: bs.pdf,
                    delta: bs.delta,
                });
            } else if let Some(opt) = optimal.as_deref_mut() {
                let cv = beta * opt.pure_bsdf(Vec3::ZERO);
                add(&mut l, &mut split, Technique::ControlVariate, cv);
            }
        }
        if bs.delta {
            weight_rule = EmissionWeight::One;
        } else {
            match &mut weight_rule {
                EmissionWeight::Mis { p_bsdf, .. } | EmissionWeight::Mixture { p_bsdf, .. } => {
                    *p_bsdf = bs.pdf
                }
                _ => {}
            }
        }
        beta *= bs.weight;
        if TRANSMISSION {
            eta_scale *= bs.eta * bs.eta;
        }
        if !wi_ok || (beta == Vec3::ZERO && pending.is_none()) {
            break;
        }
        prev_p = hit.p;
        prev_ns = frame.n;
        prev_light_ns = settings.light_sampling.receiver_normal(frame.n, transmits);
        ray = spawn_ray(hit.p, hit.p_error, n, wi);
        if beta == Vec3::ZERO {
            // Traced only for the pending control variate.
            stop = true;
            continue;
        }

        if depth as u32 >= settings.rr_depth {
            let rr_beta = if TRANSMISSION { beta * eta_scale } else { beta };
            let q = max_component(rr_beta).min(0.95);
            if sampler.rr_1d(bounce) >= q {
                if pending.is_none() {
                    break;
                }
                stop = true;
                continue;
            }
            beta /= q;
        }
    }
    l
}

/// The shading-normal rule: a direction counts only if the geometric normal `n` puts it on the
/// same side as the shading frame does (`local_z`, its cosine there), and not in the plane.
/// Directions between the two hemispheres would leak light through the surface or, for the
/// viewing direction, see a BSDF from a side the surface does not face (docs/shading-normals.md).
#[inline]
fn same_side(w: Vec3, n: Vec3, local_z: f32) -> bool {
    let d = w.dot(n);
    d != 0.0 && (d > 0.0) == (local_z > 0.0)
}

/// Weight of emission from light `light` found by a BSDF-sampled ray; `light_pdf` is the
/// solid-angle pdf with which light sampling at the previous vertex would have chosen the same
/// direction (light selection not included); `prev_p` and `prev_ns` are that vertex's point and
/// shading normal, which the selection probability depends on (with the light BVH).
#[inline]
#[allow(clippy::too_many_arguments)]
fn emission_weight(
    scene: &Scene,
    settings: &Settings,
    rule: EmissionWeight,
    light: u32,
    prev_p: Vec3,
    prev_ns: Vec3,
    light_pdf: impl FnOnce() -> f32,
) -> f32 {
    let pmf = || scene.light_pmf(settings.light_selection, prev_p, prev_ns, light as usize);
    match rule {
        EmissionWeight::One => 1.0,
        EmissionWeight::Zero => 0.0,
        EmissionWeight::Mis { p_bsdf, heuristic } => heuristic.weight(p_bsdf, pmf() * light_pdf()),
        EmissionWeight::Mixture {
            p_bsdf,
            light_weight,
        } => {
            let p_light = pmf() * light_pdf();
            let w = p_bsdf / (light_weight * p_light + (1.0 - light_weight) * p_bsdf);
            if w.is_finite() { w } else { 0.0 }
        }
        EmissionWeight::Fixed(w) => w,
    }
}

/// Resolves `mis-optimal`'s pending BSDF sample `p` once its `ray` (from the vertex at `prev_p`,
/// shading normal `prev_ns`, and the normal it gave the light sampler) found `hit`: records the sample in `optimal` and returns its control
/// variate term (times the vertex's throughput) and the weight of the emission it found.
///
/// Combined (both techniques could have produced the outcome) where the ray ends on an emitter
/// facing the vertex with non-zero radiance (or escapes into an environment light that is
/// non-zero there) and light sampling's pdf there is positive and finite: exactly the outcomes
/// where [`crate::scene::Scene::sample_light`] returns a sample. Pure otherwise, and for delta
/// samples.
#[allow(clippy::too_many_arguments)]
fn resolve_bsdf(
    scene: &Scene,
    settings: &Settings,
    ray: &Ray,
    hit: Option<&SurfaceHit>,
    prev_p: Vec3,
    [prev_ns, prev_light_ns]: [Vec3; 2],
    p: PendingBsdf,
    optimal: &mut OptimalSample,
) -> (Vec3, f32) {
    let method = settings.light_sampling;
    let pmf =
        |light: u32| scene.light_pmf(settings.light_selection, prev_p, prev_ns, light as usize);
    let (le, p_light) = match hit {
        None => match scene.background_light {
            Some(bg) => {
                let light = &scene.lights[bg as usize];
                let le = light.radiance(Vec3::ZERO, ray.d);
                let pdf =
                    || light.pdf(prev_p, prev_light_ns, ray.d, Vec3::ZERO, Vec3::ZERO, method);
                (le, if p.delta { 0.0 } else { pmf(bg) * pdf() })
            }
            None => (Vec3::ZERO, 0.0),
        },
        Some(hit) => {
            let prim = &scene.accel.primitives()[hit.prim as usize];
            if prim.light == NONE {
                (Vec3::ZERO, 0.0)
            } else {
                let light = &scene.lights[prim.light as usize];
                let le = scene.emitted(prim.light, hit, ray.d);
                let pdf = || {
                    let d = ray.d.normalize();
                    light.pdf(prev_p, prev_light_ns, d, hit.p, hit.n, method)
                };
                (
                    le,
                    if p.delta {
                        0.0
                    } else {
                        pmf(prim.light) * pdf()
                    },
                )
            }
        }
    };
    if p.delta {
        return (p.beta * optimal.pure_bsdf(p.weight * le), 1.0);
    }
    let emits = le.cmpgt(Vec3::ZERO).any();
    match balance_ratios(p_light, p.pdf) {
        Some((rl, rb)) if emits && p_light > 0.0 => {
            let c = p.weight * le * rb;
            (p.beta * optimal.combined(c, rl, rb), rb)
        }
        _ => {
            let w = Heuristic::Balance.weight(p.pdf, p_light);
            (p.beta * optimal.pure_bsdf(p.weight * le * w), w)
        }
    }
}

/// Next-event estimation: picks a light (by power or by the light BVH at the hit), samples it,
/// traces a shadow ray, and returns the contribution (without the path throughput) weighted by
/// `weight`, and where the sample ended. `transmits` lets the light lie below the surface.
///
/// `cv` (mis-optimal's control variate, with the balance heuristic): the outcome is needed, so a
/// sample where f is zero but the BSDF pdf is not still traces its shadow ray (visible, it is a
/// combined outcome of contribution 0; blocked, a pure one). Without `cv` the outcome is always
/// [`NeeOutcome::Pure`] and nothing extra is done.
#[allow(clippy::too_many_arguments)]
fn direct_light<const TRANSMISSION: bool>(
    scene: &Scene,
    settings: &Settings,
    hit: &crate::geometry::SurfaceHit,
    n: Vec3,
    frame: &Frame,
    wo: Vec3,
    bsdf: &VertexBsdf,
    u_light: f32,
    u: glam::Vec2,
    weight: NeeWeight,
    cv: bool,
    transmits: bool,
    shading: bool,
) -> (Vec3, NeeOutcome) {
    const PURE: (Vec3, NeeOutcome) = (Vec3::ZERO, NeeOutcome::Pure);
    let Some((index, pmf)) = scene.select_light(settings.light_selection, hit.p, frame.n, u_light)
    else {
        return PURE;
    };
    let transmits = TRANSMISSION && transmits;
    let ns = settings.light_sampling.receiver_normal(frame.n, transmits);
    let Some(ls) = scene.sample_light(index, hit.p, ns, u, settings.light_sampling) else {
        return PURE;
    };
    let wi = frame.to_local(ls.wi);
    let wi_invalid = if transmits { wi.z == 0.0 } else { wi.z <= 0.0 };
    if wi_invalid || (shading && !same_side(ls.wi, n, wi.z)) {
        return PURE;
    }
    let f = bsdf.eval::<TRANSMISSION>(wo, wi);
    if scene.lights[index].is_delta() {
        let h = delta_light(scene, hit, n, &ls, f, pmf, weight);
        return (h, NeeOutcome::Delta { h });
    }
    let p_bsdf_cv = if cv {
        bsdf.pdf::<TRANSMISSION>(wo, wi)
    } else {
        0.0
    };
    if f == Vec3::ZERO && p_bsdf_cv <= 0.0 {
        return PURE;
    }
    if scene.occluded(&shadow_ray(hit, n, &ls)) {
        if cv && crate::mutants::optimal_occluded_combined() {
            let p_bsdf = bsdf.pdf::<TRANSMISSION>(wo, wi);
            if let Some((rl, rb)) = balance_ratios(pmf * ls.pdf, p_bsdf) {
                return (Vec3::ZERO, NeeOutcome::Combined { rl, rb });
            }
        }
        return PURE;
    }
    let p_light = pmf * ls.pdf;
    let weight = match weight {
        NeeWeight::Mixture(w) => {
            // One-sample estimator: divide by the mixture pdf (selection probability included).
            let p_mix = w * p_light + (1.0 - w) * bsdf.pdf::<TRANSMISSION>(wo, wi);
            return (f * ls.le / p_mix, NeeOutcome::Pure);
        }
        NeeWeight::Mis(heuristic) if cv => heuristic.weight(p_light, p_bsdf_cv),
        NeeWeight::Mis(heuristic) => heuristic.weight(p_light, bsdf.pdf::<TRANSMISSION>(wo, wi)),
        NeeWeight::One => 1.0,
    };
    let contribution = f * ls.le * (weight / p_light);
    let outcome = match balance_ratios(p_light, p_bsdf_cv) {
        Some((rl, rb)) if cv => NeeOutcome::Combined { rl, rb },
        _ => NeeOutcome::Pure,
    };
    (contribution, outcome)
}

/// The shadow ray from `hit` (geometric normal `n`) to light sample `ls`: to infinity along its
/// direction for a light at infinity, else to its point (both ends offset off their surfaces).
#[inline(always)]
fn shadow_ray(hit: &SurfaceHit, n: Vec3, ls: &crate::lights::LightSample) -> Ray {
    if ls.infinite {
        spawn_ray(hit.p, hit.p_error, n, ls.wi)
    } else {
        spawn_ray_to(hit.p, hit.p_error, n, ls.p, ls.p_error, ls.n)
    }
}

/// Next-event estimation's contribution from a delta light's sample `ls` (the light selected with
/// probability `pmf`) at a vertex whose BSDF value (cosine included) towards it is `f`: no other
/// technique produces this sample, so its MIS weight is 1 in every strategy, and under the
/// one-sample mixture it is divided by the light branch's probability as well (the BSDF branch
/// never finds it). Zero where the shadow ray is blocked. Kept out of line, so that the loop of
/// scenes without delta lights, which never call it, stays as small as it was
/// (docs/performance.md, "Delta lights").
#[inline(never)]
fn delta_light(
    scene: &Scene,
    hit: &SurfaceHit,
    n: Vec3,
    ls: &crate::lights::LightSample,
    f: Vec3,
    pmf: f32,
    weight: NeeWeight,
) -> Vec3 {
    if f == Vec3::ZERO {
        return Vec3::ZERO;
    }
    if scene.occluded(&shadow_ray(hit, n, ls)) {
        return Vec3::ZERO;
    }
    let branch = match weight {
        NeeWeight::Mixture(w) => w,
        NeeWeight::One | NeeWeight::Mis(_) => 1.0,
    };
    f * ls.le / (pmf * branch)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::Heuristic;

    /// On scenes without a dielectric the transmission build of the loop gives the same radiance,
    /// bit for bit and with the same random numbers consumed, as the build without it: glass
    /// changes nothing for the scenes lumis rendered before it.
    #[test]
    fn transmission_code_leaves_other_scenes_bit_identical() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/data/scenes");
        for name in ["seed_cornell", "veach_mis"] {
            let scene = Scene::load(&dir.join(format!("{name}.json"))).unwrap();
            assert!(!scene.has_transmission());
            for strategy in [
                Strategy::Light,
                Strategy::Bsdf,
                Strategy::Mixture { light_weight: 0.5 },
                Strategy::Mis {
                    heuristic: Heuristic::Power,
                },
            ] {
                let settings = Settings {
                    strategy,
                    ..Settings::default()
                };
                let (w, h) = (scene.camera.width, scene.camera.height);
                for i in 0..4000u32 {
                    let (x, y) = ((i * 7919) % w, (i * 104_729) % h);
                    let mut rng_a = Sampler::from(crate::rng::Rng::new(3, i, 0));
                    let mut rng_b = rng_a.clone();
                    let ray = scene.camera.ray(x as f32 + 0.5, y as f32 + 0.5);
                    let a = radiance_specialised::<false>(&scene, ray, &mut rng_a, &settings);
                    let b = radiance_specialised::<true>(&scene, ray, &mut rng_b, &settings);
                    assert_eq!(
                        a.to_array().map(f32::to_bits),
                        b.to_array().map(f32::to_bits)
                    );
                    assert_eq!(rng_a.get_1d(0).to_bits(), rng_b.get_1d(0).to_bits());
                }
            }
        }
    }
}
