//! The unidirectional path tracer. One function, one loop: it follows a camera path, gathers
//! emission seen along it, and estimates direct light at each vertex with the chosen [`Strategy`].
//!
//! Path length follows Mitsuba's `max_depth`: a path of `k` segments ends at its `k`-th vertex, so
//! `1` keeps only emission seen by the camera and `2` adds direct lighting.
//!
//! Transmission (dielectrics): the frame of a transmitting material is never flipped, so `wo` and
//! `wi` may lie on either side; next-event estimation at a rough dielectric samples lights on both
//! sides; shadow rays are blocked by dielectrics like by any surface (Mitsuba's `path`); Russian
//! roulette sees the throughput times η'² of every refraction (pbrt-v4's `etaScale`), so radiance's
//! 1/η'² does not kill paths inside glass. The loop is compiled twice, with and without this code
//! (`TRANSMISSION`); scenes without a dielectric run the version without it, bit for bit the
//! renderer they ran before.
//!
//! Shading normals (meshes with vertex normals): the BSDF frame is the shading normal's, the
//! geometric normal decides sides and ray offsets, and a direction that the two normals put on
//! different sides does not count (`same_side`; docs/shading-normals.md says why).
//!
//! Emission is looked up through the scene ([`Scene::emitted`] at hits, [`Scene::sample_light`]
//! for light samples), which evaluates a textured emitter's texture at the point.
//! WGSL twin: `path.wgsl`.

use super::{Heuristic, Settings, Strategy};
use crate::geometry::primitive::NONE;
use crate::geometry::ray::{Ray, spawn_ray, spawn_ray_to};
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
    mut ray: Ray,
    sampler: &mut Sampler,
    settings: &Settings,
) -> Vec3 {
    debug_assert!(TRANSMISSION || !scene.has_transmission());
    let max_depth = settings.max_depth.unwrap_or(scene.max_depth);
    let mut l = Vec3::ZERO;
    let mut beta = Vec3::ONE;
    // Product of η'² over the refractions so far: Russian roulette sees beta·eta_scale.
    let mut eta_scale = 1.0f32;
    let mut weight_rule = EmissionWeight::One;
    let mut prev_p = ray.o;
    // The previous vertex's shading normal, for light selection (zero at the camera), and the
    // one it gave the light sampler (`LightSampling::receiver_normal`), for the light pdf.
    let mut prev_ns = Vec3::ZERO;
    let mut prev_light_ns = Vec3::ZERO;
    let mut depth: i32 = 0;
    loop {
        depth += 1;
        // The sampler's bounce: 0 at the camera ray's hit.
        let bounce = (depth - 1) as u32;
        let Some(hit) = scene.accel.intersect(&ray) else {
            if let Some(bg) = scene.background_light {
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
                l += beta * light.radiance(Vec3::ZERO, ray.d) * w;
            }
            break;
        };
        let prim = &scene.accel.primitives()[hit.prim as usize];
        if prim.light != NONE {
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
                l += beta * le * w;
            }
        }
        if max_depth >= 0 && depth >= max_depth {
            break;
        }
        let material = &*scene.material_at(&hit, prim.material);
        let wo_world = -ray.d.normalize();
        // `n`: the geometric normal, which decides sides and ray offsets; the BSDF lives in the
        // frame of the shading normal `ns` (the geometric one where the mesh has none).
        let mut n = hit.n;
        let shading_normal = if scene.attributes.has_normals() {
            scene.attributes.shading_normal(prim.attr, hit.b, n)
        } else {
            None
        };
        let shading = shading_normal.is_some();
        let mut ns = shading_normal.unwrap_or(n);
        let transmits = TRANSMISSION && material.transmits();
        if n.dot(wo_world) < 0.0 && !transmits {
            if !scene.two_sided[prim.material as usize] {
                break;
            }
            n = -n;
            ns = -ns;
        }
        let frame = Frame::from_normal(ns);
        let wo = frame.to_local(wo_world);
        // A reflecting surface is seen from its front only; a dielectric from either side.
        let wo_invalid = if transmits { wo.z == 0.0 } else { wo.z <= 0.0 };
        if wo_invalid || (shading && !same_side(wo_world, n, wo.z)) {
            break;
        }

        // Direct light by light sampling, and the rule for emission the BSDF sample will find.
        let smooth = material.has_smooth_part() && scene.light_sampler.is_some();
        let mut do_nee = false;
        let mut nee_mixture_weight = None;
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
                    EmissionWeight::Mis {
                        p_bsdf: 0.0,
                        heuristic,
                    }
                }
                Strategy::Mixture { light_weight } => {
                    if sampler.mixture_1d(bounce) < light_weight {
                        do_nee = true;
                        nee_mixture_weight = Some(light_weight);
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
            l += beta
                * direct_light::<TRANSMISSION>(
                    scene,
                    settings,
                    &hit,
                    n,
                    &frame,
                    wo,
                    material,
                    u_light,
                    u,
                    nee_mixture_weight,
                    transmits,
                    shading,
                );
        }

        // Continue the path by BSDF sampling.
        let Some(bs) = material.sample_specialised::<TRANSMISSION>(
            wo,
            sampler.bsdf_lobe_1d(bounce),
            sampler.bsdf_2d(bounce),
        ) else {
            break;
        };
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
        if beta == Vec3::ZERO {
            break;
        }
        let wi = frame.to_world(bs.wi);
        if shading && !same_side(wi, n, bs.wi.z) {
            break;
        }
        prev_p = hit.p;
        prev_ns = ns;
        prev_light_ns = settings.light_sampling.receiver_normal(ns, transmits);
        ray = spawn_ray(hit.p, hit.p_error, n, wi);

        if depth as u32 >= settings.rr_depth {
            let rr_beta = if TRANSMISSION { beta * eta_scale } else { beta };
            let q = max_component(rr_beta).min(0.95);
            if sampler.rr_1d(bounce) >= q {
                break;
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
    }
}

/// Next-event estimation: picks a light (by power or by the light BVH at the hit), samples it, traces a shadow ray, and returns the
/// contribution (without the path throughput). `mixture` holds the mixture's light probability
/// when this is the light branch of the one-sample mixture; `transmits` lets the light lie below
/// the surface.
#[allow(clippy::too_many_arguments)]
fn direct_light<const TRANSMISSION: bool>(
    scene: &Scene,
    settings: &Settings,
    hit: &crate::geometry::SurfaceHit,
    n: Vec3,
    frame: &Frame,
    wo: Vec3,
    material: &crate::materials::Material,
    u_light: f32,
    u: glam::Vec2,
    mixture: Option<f32>,
    transmits: bool,
    shading: bool,
) -> Vec3 {
    let Some((index, pmf)) = scene.select_light(settings.light_selection, hit.p, frame.n, u_light)
    else {
        return Vec3::ZERO;
    };
    let transmits = TRANSMISSION && transmits;
    let ns = settings.light_sampling.receiver_normal(frame.n, transmits);
    let Some(ls) = scene.sample_light(index, hit.p, ns, u, settings.light_sampling) else {
        return Vec3::ZERO;
    };
    let wi = frame.to_local(ls.wi);
    let wi_invalid = if transmits { wi.z == 0.0 } else { wi.z <= 0.0 };
    if wi_invalid || (shading && !same_side(ls.wi, n, wi.z)) {
        return Vec3::ZERO;
    }
    let f = material.eval_specialised::<TRANSMISSION>(wo, wi);
    if f == Vec3::ZERO {
        return Vec3::ZERO;
    }
    let shadow = if ls.infinite {
        spawn_ray(hit.p, hit.p_error, n, ls.wi)
    } else {
        spawn_ray_to(hit.p, hit.p_error, n, ls.p, ls.p_error, ls.n)
    };
    if scene.accel.occluded(&shadow) {
        return Vec3::ZERO;
    }
    let p_light = pmf * ls.pdf;
    let weight = match (settings.strategy, mixture) {
        (_, Some(w)) => {
            // One-sample estimator: divide by the mixture pdf (selection probability included).
            let p_mix = w * p_light + (1.0 - w) * material.pdf_specialised::<TRANSMISSION>(wo, wi);
            return f * ls.le / p_mix;
        }
        (Strategy::Mis { heuristic }, None) => {
            heuristic.weight(p_light, material.pdf_specialised::<TRANSMISSION>(wo, wi))
        }
        _ => 1.0,
    };
    f * ls.le * (weight / p_light)
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
