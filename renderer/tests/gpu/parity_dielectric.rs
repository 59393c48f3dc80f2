//! Parity of the dielectric's WGSL twin (`materials/dielectric.wgsl`) with `materials/dielectric.rs`:
//! Fresnel and refraction, eval, pdf and sampling of smooth and rough glass at several indices,
//! with the conditioning of each comparison stated where a tolerance depends on it.

use crate::gpu_common;
use glam::{Vec2, Vec3};
use gpu_common::parity::*;
use gpu_common::*;
use lumis::gpu::GpuScene;
use lumis::materials::{Dielectric, Material, Microfacet, ThinDielectric, fresnel};
use lumis::math::{reflect, refract};
use lumis::rng::Rng;
use serde_json::json;

/// The dielectrics of the parity tests: smooth (a delta BSDF) and rough at α 0.01, 0.3 and 1, each
/// at a low, a typical and a high index.
const DIELECTRIC_IORS: [f32; 3] = [1.1, 1.5, 2.4];
const DIELECTRIC_ALPHAS: [f32; 4] = [0.0, 0.01, 0.3, 1.0];

/// f32's unit roundoff, 2⁻²⁴.
const U: f32 = f32::EPSILON / 2.0;

/// Relative tolerance of the dielectric's arithmetic downstream of its half vector and Fresnel
/// inputs: about 30 f32 operations on each side (D, G1 twice, Fresnel, the Jacobian, the pdf),
/// each within 2.5 ulp on a Vulkan device (division; the others 1), ≤ 75u ≈ 4.5e-6, doubled.
/// Everything ill-conditioned (the half-vector sum, the Fresnel term near the critical angle,
/// the refracted direction near grazing) is not in it but in each value's conditioning term.
const DIELECTRIC_RTOL: f32 = 1e-5;

/// The relative perturbation of the IOR that covers the GPU's rounding of 1/η and x/η² (Vulkan
/// divides to 2.5 ulp): with it, the CPU's expressions at η(1 ± 4u) bracket the GPU's at η.
const IOR_BACKWARD: f32 = 4.0 * U;

/// The VNDF normal's agreement (`ggx_matches`): 1e-5 for all but a few ill-conditioned inputs,
/// which stay within 2e-4.
const VNDF_AGREEMENT: f32 = 1e-5;
const VNDF_CAP: f32 = 2e-4;

/// Every dielectric of [`DIELECTRIC_IORS`] × [`DIELECTRIC_ALPHAS`] in a scene (the GPU gets them
/// as records), with each one's record index.
fn dielectric_scene() -> Option<(Vec<(Dielectric, usize)>, GpuScene)> {
    let ctx = context()?;
    let mut materials = serde_json::Map::new();
    let mut list = Vec::new();
    for ior in DIELECTRIC_IORS {
        for alpha in DIELECTRIC_ALPHAS {
            let name = format!("glass{}", list.len());
            materials.insert(
                name,
                json!({"type": "dielectric", "ior": ior, "alpha": alpha}),
            );
            list.push(Dielectric {
                ior,
                microfacet: Microfacet::ggx(alpha),
            });
        }
    }
    let desc = json!({
        "camera": {"from": [0, 0, -3], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40, "width": 4, "height": 4},
        "materials": materials,
        "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "glass0"}]
    });
    let scene = build(&desc.to_string());
    let list = list
        .into_iter()
        .enumerate()
        .map(|(i, d)| {
            let name = format!("glass{i}");
            let index = scene
                .material_names
                .iter()
                .position(|n| *n == name)
                .unwrap();
            assert_eq!(scene.materials[index], Material::Dielectric(d));
            (d, index)
        })
        .collect();
    let gpu = GpuScene::new(ctx, scene).expect("upload");
    Some((list, gpu))
}

/// A direction `theta` from the normal, inside (−z) or outside, at a random azimuth.
fn at_theta(theta: f32, inside: bool, r: &mut Rng) -> Vec3 {
    let phi = std::f32::consts::TAU * r.next_f32();
    let (s, c) = theta.sin_cos();
    Vec3::new(s * phi.cos(), s * phi.sin(), if inside { -c } else { c })
}

/// Item `k`'s viewing direction at a dielectric of index `ior`: uniform over the sphere, grazing
/// (89° to 90°) from either side, inside beyond the critical angle (total internal reflection),
/// inside where the refraction leaves at 89° to 90° (grazing refraction), near the normal from
/// either side (near straight-through refraction, where the half-vector sum cancels), and in the
/// tangent plane.
fn dielectric_wo(k: usize, ior: f32, r: &mut Rng) -> Vec3 {
    let deg = |d: f32| d.to_radians();
    let crit = (1.0 / ior).asin();
    let inside = r.next_f32() < 0.5;
    match k % 16 {
        0..=4 => unit(r),
        5 | 6 => at_theta(deg(89.0 + r.next_f32()), false, r),
        7 | 8 => at_theta(deg(89.0 + r.next_f32()), true, r),
        9 | 10 => at_theta(crit + (deg(90.0) - crit) * r.next_f32(), true, r),
        11 | 12 => at_theta((deg(89.0 + r.next_f32()).sin() / ior).asin(), true, r),
        13 | 14 => at_theta(deg(5.0) * r.next_f32(), inside, r),
        _ => Vec3::new(r.next_f32() - 0.5, r.next_f32() - 0.5, 0.0).normalize(),
    }
}

/// Item `k`'s light direction for eval and pdf: a sample of the CPU material itself (so that the
/// narrow lobes are compared where they are not 0, reflection and refraction), its exact
/// straight-through partner −wo, a uniform direction, or one in the tangent plane.
fn dielectric_wi(k: usize, m: &Material, wo: Vec3, r: &mut Rng) -> Vec3 {
    let (u_lobe, u) = (r.next_f32(), r.next_2d());
    match k % 8 {
        0..=3 => m.sample(wo, u_lobe, u).map_or_else(|| unit(r), |s| s.wi),
        4 => -wo,
        5 | 6 => unit(r),
        _ => Vec3::new(r.next_f32() - 0.5, r.next_f32() - 0.5, 0.0).normalize(),
    }
}

/// Σ over `n` perturbations of the larger one-sided change of each component of `f`: the
/// first-order bound on how far `f` moves when each perturbed input moves within its bound, i.e.
/// the forward error of a computation whose backward error those bounds are. `f(p, ±1)` is `f`
/// with perturbation `p` applied with either sign; `None` (the perturbed input is invalid) counts
/// as an infinite change.
fn spread<const K: usize>(
    base: [f32; K],
    n: usize,
    f: impl Fn(usize, f32) -> Option<[f32; K]>,
) -> [f32; K] {
    let mut out = [0.0; K];
    for p in 0..n {
        for k in 0..K {
            let change = |s: f32| {
                f(p, s).map_or(f32::INFINITY, |v| {
                    let d = (v[k] - base[k]).abs();
                    if d.is_nan() { f32::INFINITY } else { d }
                })
            };
            out[k] += change(1.0).max(change(-1.0));
        }
    }
    out
}

/// `d` with its IOR scaled by 1 + s·[`IOR_BACKWARD`].
fn ior_moved(d: Dielectric, s: f32) -> Dielectric {
    Dielectric {
        ior: d.ior * (1.0 + s * IOR_BACKWARD),
        ..d
    }
}

/// The conditioning of the CPU's (f·|cos|, pdf) of `d` at (wo, wi) under the GPU's f32 rounding,
/// as a backward error. The CPU forms the half-vector sum η_i·wi + η_o·wo in f64, the GPU in f32:
/// its products, sum and normalisation round each component c by at most
/// u(η_i|wi_c| + η_o|wo_c| + 2|sum_c|), which is the exact sum of a wi moved by that over η_i
/// (doubled here for device arithmetic; never across the tangent plane, which is an input).
/// The Fresnel term's divisions are covered by moving the IOR ([`IOR_BACKWARD`]). Near-
/// cancelling sums (an IOR near 1, straight through) and the critical angle get a large term,
/// everything else one far below [`DIELECTRIC_RTOL`].
fn eval_spread(d: Dielectric, wo: Vec3, wi: Vec3) -> [f32; 2] {
    let (f, p) = d.eval_pdf(wo, wi);
    let side = |w: Vec3| if w.z > 0.0 { 1.0 } else { d.ior };
    let (eta_o, eta_i) = if wo.z * wi.z > 0.0 {
        (1.0, 1.0)
    } else {
        (side(wo), side(wi))
    };
    let sum = wi * eta_i + wo * eta_o;
    let e = (wi.abs() * eta_i + wo.abs() * eta_o + 2.0 * sum.abs()) * (2.0 * U / eta_i);
    let e = Vec3::new(e.x, e.y, e.z.min(0.5 * wi.z.abs()));
    spread([f, p], 4, |k, s| {
        let (a, b) = if k == 3 {
            ior_moved(d, s).eval_pdf(wo, wi)
        } else {
            let mut w = wi;
            w[k] += s * e[k];
            d.eval_pdf(wo, w)
        };
        Some([a, b])
    })
}

/// The dielectric's Fresnel term and refraction themselves, on cosines over [−1, 1] (both sides),
/// near the critical angle from inside, at normal and grazing incidence, for the suite's IORs,
/// their inverses and random ones; the pair form on Snell-consistent and on arbitrary cosines.
/// Relative [`DIELECTRIC_RTOL`] plus the conditioning under [`IOR_BACKWARD`]: near the critical
/// angle cos θt = √(1 − sin²θt) cancels, which the moved IOR brackets.
#[test]
fn dielectric_fresnel_and_refraction_match() {
    let Some((_, gpu)) = parity_scene() else {
        return;
    };
    let mut r = Rng::new(16, 0, 0);
    let mut inputs = Vec::new();
    for k in 0..N {
        let eta = match k % 5 {
            0..=2 => DIELECTRIC_IORS[k % 3],
            3 => 1.0 / DIELECTRIC_IORS[(k / 5) % 3],
            _ => 1.01 + 2.0 * r.next_f32(),
        };
        let crit_cos = (1.0 - 1.0 / (eta * eta)).max(0.0).sqrt();
        let c = match (k / 5) % 6 {
            0 | 1 => 2.0 * r.next_f32() - 1.0,
            // Within ±1% of the critical cosine, from inside.
            2 => -crit_cos * (0.99 + 0.02 * r.next_f32()),
            3 => [0.0, 1.0, -1.0, 1e-6, -1e-6][(k / 30) % 5],
            _ => 1e-3 * (2.0 * r.next_f32() - 1.0),
        };
        let c_out = r.next_f32();
        let snell = (1.0 - (1.0 - c_out * c_out) / (eta * eta)).max(0.0).sqrt();
        let c_in = if k % 2 == 0 { snell } else { r.next_f32() };
        let n = if k % 3 == 0 { Vec3::Z } else { unit(&mut r) };
        inputs.push([c, eta, c_out, c_in]);
        inputs.push(f4(unit(&mut r), 0.0));
        inputs.push(f4(n, 0.0));
    }
    let out = run(
        &gpu,
        "let v = inp(0u); let w = inp(1u).xyz; let n = inp(2u).xyz;
         outp(0u, vec4f(fresnel_dielectric(v.x, v.y), fresnel_dielectric_pair(v.z, v.w, v.y), 0.0, 0.0));
         outp(1u, refract_through(w, n, v.y));",
        &inputs,
        3,
        2,
    );
    let mut fr = Compare::new("dielectric fresnel", DIELECTRIC_RTOL, 0.0);
    let mut rf = Compare::new("refraction", DIELECTRIC_RTOL, 1e-7);
    let mut tir = 0;
    for (i, o) in inputs.chunks(3).zip(out.chunks(2)) {
        let [c, eta, c_out, c_in] = i[0];
        let w = Vec3::from_slice(&i[1][..3]);
        let n = Vec3::from_slice(&i[2][..3]);
        let moved = |s: f32| eta * (1.0 + s * IOR_BACKWARD);
        let f = fresnel::fresnel_dielectric(c, eta);
        let [fs] = spread([f], 1, |_, s| {
            Some([fresnel::fresnel_dielectric(c, moved(s))])
        });
        fr.scalar_conditioned(o[0][0], f, fs, "fresnel_dielectric");
        let p = fresnel::fresnel_dielectric_pair(c_out, c_in, eta);
        let [ps] = spread([p], 1, |_, s| {
            Some([fresnel::fresnel_dielectric_pair(c_out, c_in, moved(s))])
        });
        fr.scalar_conditioned(o[0][1], p, ps, "fresnel_dielectric_pair");
        // Within the IOR's backward error of total internal reflection either answer is right.
        let boundary = refract(w, n, moved(1.0)).is_some() != refract(w, n, moved(-1.0)).is_some();
        if boundary {
            continue;
        }
        match refract(w, n, eta) {
            Some((wt, e)) => {
                let ws = spread(wt.to_array(), 1, |_, s| {
                    refract(w, n, moved(s)).map(|t| t.0.to_array())
                });
                for (k, what) in ["x", "y", "z"].iter().enumerate() {
                    rf.scalar_conditioned(o[1][k], wt[k], ws[k], &format!("refract {what}"));
                }
                rf.scalar(o[1][3], e, "refract eta");
            }
            None => {
                tir += 1;
                rf.scalar(o[1][3], 0.0, "total internal reflection");
            }
        }
    }
    assert!(tir > N / 20, "{tir} total internal reflections");
    fr.finish(0);
    rf.finish(0);
}

/// How the CPU's lobe choice and sampled direction of `d` at (wo, u_lobe, u) move under the GPU's
/// errors in their inputs: the microfacet normal per component by [`VNDF_AGREEMENT`] (or, for
/// the cap and the ambiguity, [`VNDF_CAP`]; a smooth interface's normal is exactly +z) and the
/// IOR by [`IOR_BACKWARD`].
struct SampleConditioning {
    /// The lobe choice or the sample's validity changes within those errors: either answer is
    /// right.
    ambiguous: bool,
    /// The direction's spread per component ([`spread`]) at the tolerance's and at the cap's
    /// VNDF error.
    dir: [f32; 3],
    dir_cap: [f32; 3],
}

/// [`SampleConditioning`] of `d`, mirroring `Dielectric::sample` from its building blocks (and
/// checking that the mirror gives the CPU's sample `cpu`).
fn sample_conditioning(
    d: Dielectric,
    wo: Vec3,
    u_lobe: f32,
    u: Vec2,
    cpu: Option<Vec3>,
) -> SampleConditioning {
    let flip = if wo.z < 0.0 { -1.0 } else { 1.0 };
    let wm0 = if d.is_delta() {
        Vec3::Z
    } else {
        d.microfacet.sample_visible_normal(wo * flip, u)
    };
    let fresnel_at = |wm: Vec3, ior: f32| {
        let c = if d.is_delta() { wo.z } else { wo.dot(wm) };
        fresnel::fresnel_dielectric(c, ior)
    };
    let reflection = u_lobe < fresnel_at(wm0, d.ior);
    // The sampled direction from a microfacet normal, or None if the sample is invalid.
    let wi_of = |wm: Vec3, ior: f32| -> Option<Vec3> {
        let wi = if reflection {
            if d.is_delta() {
                Vec3::new(-wo.x, -wo.y, wo.z)
            } else {
                reflect(wo, wm).normalize()
            }
        } else {
            let (t, _) = refract(wo, wm, ior)?;
            if d.is_delta() { t } else { t.normalize() }
        };
        let same_side = wi.z * wo.z > 0.0;
        let valid = wi.z != 0.0
            && (d.is_delta()
                || (Dielectric { ior, ..d }.eval_pdf(wo, wi).1 > 0.0 && same_side == reflection));
        valid.then_some(wi)
    };
    let base = wi_of(wm0, d.ior);
    assert_eq!(
        base, cpu,
        "the mirror of Dielectric::sample disagrees with it: {d:?} wo {wo}"
    );
    // Perturbations 0..3 move the normal along x, y, z (rough only), 3 the IOR.
    let moved = |delta: f32| {
        move |p: usize, s: f32| -> (Vec3, f32) {
            if p == 3 {
                (wm0, d.ior * (1.0 + s * IOR_BACKWARD))
            } else {
                let mut wm = wm0;
                wm[p] += s * delta;
                (wm.normalize(), d.ior)
            }
        }
    };
    let n = if d.is_delta() { 1 } else { 4 };
    let first = if d.is_delta() { 3 } else { 0 };
    let cap = moved(VNDF_CAP);
    let mut ambiguous = false;
    for p in first..first + n {
        for s in [-1.0, 1.0] {
            let (wm, ior) = cap(p, s);
            // The lobe choice within the Fresnel term's own rounding.
            let r = fresnel_at(wm, ior);
            let near = (u_lobe - r).abs() <= DIELECTRIC_RTOL * r + 1e-7;
            ambiguous |=
                near || (u_lobe < r) != reflection || wi_of(wm, ior).is_some() != base.is_some();
        }
    }
    let dirs = |delta: f32| match base {
        Some(w) => {
            let m = moved(delta);
            spread(w.to_array(), n, |p, s| {
                let (wm, ior) = m(p + first, s);
                wi_of(wm, ior).map(|v| v.to_array())
            })
        }
        None => [0.0; 3],
    };
    SampleConditioning {
        ambiguous,
        dir: dirs(VNDF_AGREEMENT),
        dir_cap: dirs(VNDF_CAP),
    }
}

/// The dielectrics' eval, pdf and sample on both sides: every [`DIELECTRIC_IORS`] ×
/// [`DIELECTRIC_ALPHAS`] from the viewing directions of [`dielectric_wo`] (uniform, grazing
/// from either side, total internal reflection, grazing refraction, near straight-through) to the
/// light directions of [`dielectric_wi`] (in the lobes, straight through, uniform, tangent).
///
/// Tolerance: relative [`DIELECTRIC_RTOL`] plus each value's conditioning, the first-order change
/// of the CPU's result under the GPU's rounding of the inputs that are ill-conditioned
/// ([`eval_spread`]: the half-vector sum, which the CPU forms in f64 and the GPU in f32, and the
/// IOR in the Fresnel term; [`sample_conditioning`]: the VNDF normal and the IOR). A smooth
/// interface's eval and pdf are exactly 0 on both sides, as are the rough one's at wi.z = 0 or
/// wo.z = 0. A sample's pdf and weight are compared with the CPU's eval and pdf at the GPU's
/// direction (so the direction's own conditioning does not enter them twice); samples whose lobe
/// choice or validity is within the errors of its inputs (u_lobe at the Fresnel term, a
/// refraction at the critical angle) are only counted.
#[test]
fn dielectric_matches() {
    let Some((list, gpu)) = dielectric_scene() else {
        return;
    };
    let mut r = Rng::new(17, 0, 0);
    let items = 8 * N;
    let mut inputs = Vec::with_capacity(3 * items);
    for k in 0..items {
        let (d, index) = list[k % list.len()];
        let j = k / list.len();
        let wo = dielectric_wo(j, d.ior, &mut r);
        let wi = dielectric_wi(j / 16, &Material::Dielectric(d), wo, &mut r);
        inputs.push(f4(wo, index as f32));
        inputs.push(f4(wi, r.next_f32()));
        inputs.push([r.next_f32(), r.next_f32(), k as f32, 0.0]);
    }
    let out = run(
        &gpu,
        "let m = materials[u32(inp(0u).w)]; let wo = inp(0u).xyz; let wi = inp(1u).xyz;
         let u_lobe = inp(1u).w; let u = inp(2u).xy;
         let e = material_eval(m, wo, wi);
         outp(0u, vec4f(e.x, material_pdf(m, wo, wi), e.y, e.z));
         let s = material_sample(m, wo, u_lobe, u);
         outp(1u, vec4f(s.wi, select(-1.0, s.pdf, s.ok)));
         outp(2u, vec4f(s.weight, select(0.0, 1.0, s.delta)));
         outp(3u, vec4f(s.eta, 0.0, 0.0, 0.0));",
        &inputs,
        3,
        4,
    );
    let mut ev = Compare::new("dielectric eval/pdf", DIELECTRIC_RTOL, 0.0);
    let mut zero = Compare::new("dielectric eval/pdf that must be 0", 0.0, 0.0);
    // The sampled direction: the rare VNDF outliers of `ggx_matches` (below) carry their cap.
    let mut dir = Compare::new("dielectric sample direction", DIELECTRIC_RTOL, 1e-7)
        .outliers_within(DIELECTRIC_RTOL, 1e-7);
    let mut sv = Compare::new("dielectric sample values", 2.0 * DIELECTRIC_RTOL, 0.0);
    let (mut ambiguous, mut samples, mut ill, mut nonzero) = (0, 0, 0, 0);
    let mut kinds = [0usize; 4]; // reflections, refractions, total internal reflections, none
    for (i, o) in inputs.chunks(3).zip(out.chunks(4)) {
        let k = i[2][2] as usize;
        let (d, _) = list[k % list.len()];
        let m = Material::Dielectric(d);
        let wo = Vec3::from_slice(&i[0][..3]);
        let wi = Vec3::from_slice(&i[1][..3]);
        let (u_lobe, u) = (i[1][3], Vec2::new(i[2][0], i[2][1]));
        let what = format!("{d:?} wo {wo} wi {wi}");

        // eval and pdf.
        let (f, p) = d.eval_pdf(wo, wi);
        assert_eq!((m.eval(wo, wi).x, m.pdf(wo, wi)), (f, p));
        assert!(o[0][0] == o[0][2] && o[0][0] == o[0][3], "grey: {:?}", o[0]);
        if d.is_delta() || wo.z == 0.0 || wi.z == 0.0 {
            zero.scalar(o[0][0], 0.0, &format!("eval, {what}"));
            zero.scalar(o[0][1], 0.0, &format!("pdf, {what}"));
            zero.scalar(f, 0.0, &format!("cpu eval, {what}"));
            zero.scalar(p, 0.0, &format!("cpu pdf, {what}"));
        } else {
            let [fs, ps] = eval_spread(d, wo, wi);
            nonzero += (p > 0.0) as usize;
            ill += (fs > 1e-2 * f || ps > 1e-2 * p) as usize;
            ev.scalar_conditioned(o[0][0], f, fs, &format!("eval, {what}"));
            ev.scalar_conditioned(o[0][1], p, ps, &format!("pdf, {what}"));
        }

        // sample.
        let cpu = m.sample(wo, u_lobe, u);
        let c = sample_conditioning(d, wo, u_lobe, u, cpu.map(|s| s.wi));
        let gpu_ok = o[1][3] >= 0.0;
        if c.ambiguous {
            ambiguous += 1;
            continue;
        }
        let what = format!("sample of {d:?} wo {wo} u_lobe {u_lobe} u {u}");
        let Some(s) = cpu else {
            let tir = d.is_delta() && wo.z < 0.0 && fresnel::fresnel_dielectric(wo.z, d.ior) == 1.0;
            kinds[if tir { 2 } else { 3 }] += 1;
            sv.scalar(o[1][3], -1.0, &format!("none, {what}"));
            continue;
        };
        kinds[if s.wi.z * wo.z > 0.0 { 0 } else { 1 }] += 1;
        if d.is_delta() && wo.z < 0.0 && fresnel::fresnel_dielectric(wo.z, d.ior) == 1.0 {
            kinds[2] += 1;
        }
        samples += 1;
        if !gpu_ok {
            sv.scalar(o[1][3], s.pdf, &format!("pdf, {what}"));
            continue;
        }
        for (k, g) in o[1][..3].iter().enumerate() {
            let what = format!("wi, {what}");
            dir.scalar_conditioned_capped(*g, s.wi[k], c.dir[k], c.dir_cap[k], &what);
        }
        sv.scalar(o[2][3], s.delta as u32 as f32, &format!("delta, {what}"));
        sv.scalar(o[3][0], s.eta, &format!("eta, {what}"));
        let gw = Vec3::from_slice(&o[1][..3]);
        if s.delta {
            let ps = spread([s.pdf, s.weight.x], 1, |_, sg| {
                let t = Material::Dielectric(ior_moved(d, sg)).sample(wo, u_lobe, u)?;
                Some([t.pdf, t.weight.x])
            });
            sv.scalar_conditioned(o[1][3], s.pdf, ps[0], &format!("pdf, {what}"));
            sv.scalar_conditioned(o[2][0], s.weight.x, ps[1], &format!("weight, {what}"));
        } else {
            // The CPU's value at the GPU's direction.
            let (f, p) = d.eval_pdf(wo, gw);
            let [fs, ps] = eval_spread(d, wo, gw);
            let weight = f / p;
            sv.scalar_conditioned(o[1][3], p, ps, &format!("pdf, {what}"));
            let ws = weight * (fs / f + ps / p);
            sv.scalar_conditioned(o[2][0], weight, ws, &format!("weight, {what}"));
        }
        assert!(
            o[2][0] == o[2][1] && o[2][0] == o[2][2],
            "grey weight: {:?}",
            o[2]
        );
    }
    eprintln!(
        "dielectric: {nonzero} pairs with pdf > 0, {ill} of them ill-conditioned (spread > 1e-2); \
         {samples} samples: {} reflections, {} refractions, {} total internal reflections, {} none; \
         {ambiguous} within their inputs' error of a lobe or validity boundary",
        kinds[0], kinds[1], kinds[2], kinds[3]
    );
    // The comparison must be of something: most pairs in the lobes, ill-conditioned ones rare.
    ev.finish(0);
    zero.finish(0);
    // As in `materials_match`: a few in 10⁴ VNDF normals are ill-conditioned (0.05%).
    let allowed = c_allowance(&dir, 2000);
    dir.finish(allowed);
    sv.finish(0);
    // The conditioning is far below the values: at α = 0.01 D moves by (2/α)·(the half vector's
    // angle, ~1e-6) ≈ 2e-4 per component, elsewhere less; beyond 1e-2 only rare pairs (0.1%).
    assert!(
        nonzero > items / 4 && ill * 1000 < nonzero,
        "{nonzero} {ill}"
    );
    assert!(kinds.iter().all(|&n| n > items / 200), "{kinds:?}");
    assert!(ambiguous * 100 < items, "{ambiguous} ambiguous samples");
}

/// Parity of the thin dielectric's twin (`materials/thin_dielectric.wgsl`) with
/// `materials/thin_dielectric.rs`: eval and pdf exactly 0, and a sample's lobe, direction, pdf,
/// weight and η' at sheets of index below 1 (total reflection beyond the critical angle), 1
/// (everything passes), water, 1.9 and diamond, from both sides and down to grazing. Both
/// directions are exact operations (a mirror and a negation): compared bit for bit. R = 2r/(1+r)
/// to [`DIELECTRIC_RTOL`] (the Fresnel term's ~20 operations, each within 2.5 ulp); a sample whose
/// u_lobe lies within that tolerance of R may pick either lobe and is only counted, as are those
/// within 1e-3 of a sheet's critical angle, where r's slope is unbounded.
#[test]
fn thin_dielectric_matches() {
    let Some(ctx) = context() else {
        return;
    };
    let iors = [0.7f32, 1.0, 1.33, 1.9, 2.42];
    let mut materials = serde_json::Map::new();
    for (i, ior) in iors.iter().enumerate() {
        materials.insert(
            format!("sheet{i}"),
            json!({"type": "thin_dielectric", "ior": ior}),
        );
    }
    let desc = json!({
        "camera": {"from": [0, 0, -3], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40, "width": 4, "height": 4},
        "materials": materials,
        "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "sheet0"}]
    });
    let scene = build(&desc.to_string());
    let list: Vec<(ThinDielectric, usize)> = iors
        .iter()
        .enumerate()
        .map(|(i, &ior)| {
            let name = format!("sheet{i}");
            let index = scene
                .material_names
                .iter()
                .position(|n| *n == name)
                .unwrap();
            let t = ThinDielectric { ior };
            assert_eq!(scene.materials[index], Material::ThinDielectric(t));
            (t, index)
        })
        .collect();
    let gpu = GpuScene::new(ctx, scene).expect("upload");
    let mut r = Rng::new(18, 0, 0);
    let items = 2 * N;
    let mut inputs = Vec::with_capacity(2 * items);
    for k in 0..items {
        let index = list[k % list.len()].1;
        // A quarter within 1° of grazing, from either side.
        let j = k / list.len();
        let theta = if j.is_multiple_of(4) {
            (90.0 - r.next_f32()).to_radians()
        } else {
            r.next_f32() * std::f32::consts::FRAC_PI_2
        };
        let wo = at_theta(theta, j % 2 == 1, &mut r);
        inputs.push(f4(wo, index as f32));
        inputs.push([r.next_f32(), k as f32, 0.0, 0.0]);
    }
    let out = run(
        &gpu,
        "let m = materials[u32(inp(0u).w)]; let wo = inp(0u).xyz; let wi = vec3f(wo.x, -wo.y, wo.z);
         let e = material_eval(m, wo, wi) + material_eval(m, wo, -wo);
         outp(0u, vec4f(e.x + e.y + e.z, material_pdf(m, wo, wi), material_pdf(m, wo, -wo), 0.0));
         let s = material_sample(m, wo, inp(1u).x, vec2f(0.5));
         outp(1u, vec4f(s.wi, select(-1.0, s.pdf, s.ok)));
         outp(2u, vec4f(s.weight, select(0.0, 1.0, s.delta)));
         outp(3u, vec4f(s.eta, 0.0, 0.0, 0.0));",
        &inputs,
        2,
        4,
    );
    let mut zero = Compare::new("thin dielectric eval/pdf", 0.0, 0.0);
    let mut exact = Compare::new("thin dielectric direction, weight, delta, η'", 0.0, 0.0);
    let mut pdf = Compare::new("thin dielectric pdf", DIELECTRIC_RTOL, 0.0);
    let (mut ambiguous, mut kinds) = (0, [0usize; 2]);
    for (i, o) in inputs.chunks(2).zip(out.chunks(4)) {
        let k = i[1][1] as usize;
        let (t, _) = list[k % list.len()];
        let m = Material::ThinDielectric(t);
        let wo = Vec3::from_slice(&i[0][..3]);
        let u_lobe = i[1][0];
        let what = format!("{t:?} wo {wo} u_lobe {u_lobe}");
        for v in o[0][..3].iter() {
            zero.scalar(*v, 0.0, &format!("eval/pdf, {what}"));
        }
        let big_r = t.reflectance(wo.z);
        let critical = t.ior < 1.0 && (wo.z.abs() - (1.0 - t.ior * t.ior).sqrt()).abs() < 1e-3;
        if critical || (u_lobe - big_r).abs() <= DIELECTRIC_RTOL * big_r.max(1e-30) * 4.0 {
            ambiguous += 1;
            continue;
        }
        let s = m
            .sample(wo, u_lobe, Vec2::splat(0.5))
            .expect("a sheet always samples");
        kinds[(s.wi.z * wo.z < 0.0) as usize] += 1;
        for (c, (g_wi, g_weight)) in o[1][..3].iter().zip(&o[2][..3]).enumerate() {
            exact.scalar(*g_wi, s.wi[c], &format!("wi, {what}"));
            exact.scalar(*g_weight, s.weight[c], &format!("weight, {what}"));
        }
        exact.scalar(o[2][3], 1.0, &format!("delta, {what}"));
        exact.scalar(o[3][0], s.eta, &format!("eta, {what}"));
        pdf.scalar(o[1][3], s.pdf, &format!("pdf, {what}"));
    }
    eprintln!(
        "thin dielectric: {} reflections, {} transmissions, {ambiguous} within the pdf's \
         tolerance of the lobe boundary or near a critical angle",
        kinds[0], kinds[1]
    );
    // Both lobes seen many times, and few samples left out.
    assert!(kinds[0] > 500 && kinds[1] > 5000, "{kinds:?}");
    assert!(ambiguous < items / 100, "{ambiguous} of {items}");
    zero.finish(0);
    exact.finish(0);
    pdf.finish(0);
}
