//! Shared statistical checks run on every material configuration by the per-material tests.

use super::Material;
use crate::math::{reflect, refract};
use crate::rng::Rng;
use glam::{DVec3, Vec2, Vec3};
use std::f64::consts::PI;

/// Viewing angles every material is checked at, down to 0.5° above the horizon.
pub(crate) const THETAS_DEG: [f32; 5] = [0.0, 30.0, 60.0, 85.0, 89.5];
/// Samples per viewing angle for the consistency and albedo estimates.
pub(crate) const N_SAMPLES: usize = 100_000;

/// What [`check_material`] measured at one viewing angle.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Report {
    pub theta_deg: f32,
    /// True if `wo` was inside (below the surface of a transmitting material).
    pub inside: bool,
    /// ∫ pdf(wo, wi) dωi by quadrature (non-delta lobes only).
    pub pdf_integral: f64,
    /// Directional albedo (energy): mean of sample weights (all lobes), with a refraction's
    /// radiance scaling 1/η'² taken out.
    pub albedo_mc: DVec3,
    /// Standard error of `albedo_mc`.
    pub albedo_sigma: DVec3,
    /// Directional albedo from quadrature of `eval` plus the delta lobe's exact weight·probability.
    pub albedo_quad: DVec3,
}

/// Relative comparison with a tiny absolute floor (values are O(1e-30..1e9) and f32).
fn close(a: f32, b: f32, rel: f32) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs()) + 1e-30
}

fn close3(a: Vec3, b: Vec3, rel: f32) -> bool {
    close(a.x, b.x, rel) && close(a.y, b.y, rel) && close(a.z, b.z, rel)
}

/// η of the medium on the side of `w` (1 outside; a dielectric's `ior` below its surface).
pub(crate) fn side_ior(m: &Material, w: Vec3) -> f32 {
    match m {
        Material::Dielectric(d) if w.z < 0.0 => d.ior,
        Material::Principled(p) if p.transmission && w.z < 0.0 => p.eta,
        _ => 1.0,
    }
}

/// Quadrature of `g(wi)` over the sphere, done in half-vector space: reflected directions
/// wi = reflect(wo, h) with dωi = 4|wo·h| dωh (for a thin principled also those mirrored to the
/// other side, with the same Jacobian), and for a refracting material refracted ones,
/// wi = refract(wo, h) with dωi = (η_o wo·h + η_i wi·h)²/(η_i²|wi·h|) dωh. Narrow lobes are round
/// bumps around h = +z there (in wi space they become slivers at grazing wo), so θh = (π/2)t²
/// nodes crowded at the pole resolve them. Microfacet normals face +z; from inside (wo.z < 0)
/// the visible ones have wo·h < 0.
fn half_vector_quadrature(
    m: &Material,
    wo: Vec3,
    mut g: impl FnMut(Vec3) -> (f64, DVec3),
) -> (f64, DVec3) {
    let (n_t, n_phi) = (768, 192);
    let (mut s, mut v) = (0.0, DVec3::ZERO);
    let eta_o = side_ior(m, wo) as f64;
    for i in 0..n_t {
        let t = (i as f64 + 0.5) / n_t as f64;
        let theta = 0.5 * PI * t * t;
        let w_ring = theta.sin() * PI * t / n_t as f64 * 2.0 * PI / n_phi as f64;
        for j in 0..n_phi {
            let phi = 2.0 * PI * (j as f64 + 0.5) / n_phi as f64;
            let h = Vec3::new(
                (theta.sin() * phi.cos()) as f32,
                (theta.sin() * phi.sin()) as f32,
                theta.cos() as f32,
            );
            let cos_h = wo.dot(h);
            if cos_h * wo.z <= 0.0 {
                continue;
            }
            let wi = reflect(wo, h);
            if wi.z * wo.z > 0.0 {
                let wi = wi.normalize();
                let w = w_ring * 4.0 * cos_h.abs() as f64;
                let (a, b) = g(wi);
                s += a * w;
                v += b * w;
                if let Material::PrincipledThin(_) = m {
                    let (a, b) = g(Vec3::new(wi.x, wi.y, -wi.z));
                    s += a * w;
                    v += b * w;
                }
            }
            let ior = match m {
                Material::Dielectric(d) => d.ior,
                Material::Principled(p) if p.transmission => p.eta,
                _ => continue,
            };
            let Some((wt, _)) = refract(wo, h, ior) else {
                continue;
            };
            let wt = wt.normalize();
            if wt.z * wo.z >= 0.0 {
                continue;
            }
            let eta_i = side_ior(m, wt) as f64;
            let (ci, co) = (wt.dot(h) as f64, cos_h as f64);
            let jac = (eta_o * co + eta_i * ci).powi(2) / (eta_i * eta_i * ci.abs());
            let (a, b) = g(wt);
            s += a * w_ring * jac;
            v += b * w_ring * jac;
        }
    }
    (s, v)
}

/// Runs the generic BSDF checks at every angle of [`THETAS_DEG`] (and, for a transmitting
/// material, at the same angles from inside), asserting what holds for every material, and
/// returns the measurements for material-specific assertions:
/// * every sample is finite with pdf > 0; non-delta samples satisfy weight = eval/pdf and
///   pdf = `pdf(wo, wi)` (relative 1e-4: both sides are computed from the same f32 half vector,
///   so only a few ulps of rounding separate them); delta samples are mirror or Snell directions;
/// * generalised reciprocity f(wo,wi)/η(wo)² = f(wi,wo)/η(wi)² on the sampled pairs and on
///   uniform ones (relative 1e-4; η = 1 on both sides of a reflection-only material);
/// * ∫pdf ≤ 1 and equals the fraction of non-delta samples (the sampler's mass matches pdf);
/// * the fraction of each delta lobe's samples equals its reported selection probability;
/// * energy ≤ 1, and the mean sample energy agrees with quadrature of `eval` and with uniform
///   sampling of `eval` (the sampler is unbiased w.r.t. eval). Energy is the weight with the
///   radiance scaling of a refraction taken out (weight·η'²): radiance itself may grow by η².
pub(crate) fn check_material(m: &Material, seed: u32) -> Vec<Report> {
    check_material_with_energy(m, seed, 1.0)
}

/// [`check_material`] with energy bounded by `max_energy` instead of 1: for models that are not
/// energy conserving by design (Burley's principled BSDF), the bound their test states.
pub(crate) fn check_material_with_energy(m: &Material, seed: u32, max_energy: f64) -> Vec<Report> {
    check_grazing(m, seed);
    let sides: &[f32] = if m.transmits() { &[1.0, -1.0] } else { &[1.0] };
    let mut out = Vec::new();
    for (side_index, &side) in sides.iter().enumerate() {
        for (k, &th) in THETAS_DEG.iter().enumerate() {
            let t = th.to_radians();
            let wo = Vec3::new(t.sin(), 0.0, side * t.cos());
            let stream = (side_index * THETAS_DEG.len() + k) as u32;
            out.push(check_at(m, seed, stream, th, wo, max_energy));
        }
    }
    out
}

/// The checks of [`check_material`] at one `wo`.
fn check_at(m: &Material, seed: u32, stream: u32, th: f32, wo: Vec3, max_energy: f64) -> Report {
    let eta_o = side_ior(m, wo);
    let mut rng = Rng::new(seed, stream, 0);
    let (mut sum, mut sum2) = (DVec3::ZERO, DVec3::ZERO);
    let (mut sum_nd, mut sum_nd2) = (DVec3::ZERO, DVec3::ZERO);
    let mut n_nondelta = 0usize;
    // Per delta lobe (reflection, refraction): (weight, selection probability, η', count).
    let mut delta: [Option<(Vec3, f32, f32, usize)>; 2] = [None, None];
    for _ in 0..N_SAMPLES {
        let Some(s) = m.sample(wo, rng.next_f32(), rng.next_2d()) else {
            continue;
        };
        assert!(
            s.weight.is_finite() && s.pdf.is_finite() && s.pdf > 0.0,
            "{m:?} {wo} {s:?}"
        );
        let side_ok = if m.transmits() {
            s.wi.z != 0.0
        } else {
            s.wi.z > 0.0
        };
        assert!(
            (s.wi.length() - 1.0).abs() < 1e-4 && side_ok,
            "{m:?} {wo} {s:?}"
        );
        // Crossing the surface is a refraction with η' = η(wi side)/η(wo side): 1 through a
        // thin sheet, whose two sides have the same index.
        let refracted = s.wi.z * wo.z < 0.0;
        let eta = if refracted {
            side_ior(m, s.wi) / eta_o
        } else {
            1.0
        };
        assert!((s.eta - eta).abs() < 1e-6, "{m:?} {wo} {s:?}");
        let energy = s.weight.as_dvec3() * (s.eta as f64).powi(2);
        sum += energy;
        sum2 += energy * energy;
        if s.delta {
            let expect = if refracted {
                refract(wo, Vec3::Z * wo.z.signum(), s.eta).map(|(w, _)| w)
            } else {
                Some(reflect(wo, Vec3::Z))
            };
            assert!(
                s.pdf <= 1.0 && expect.is_some_and(|e| (s.wi - e).length() < 1e-5),
                "{m:?} {wo} {s:?}"
            );
            let lobe = &mut delta[refracted as usize];
            let (w, p, e, n) = lobe.get_or_insert((s.weight, s.pdf, s.eta, 0));
            assert!(
                (*w, *p, *e) == (s.weight, s.pdf, s.eta),
                "a delta lobe depends on wo only"
            );
            *n += 1;
            continue;
        }
        assert!(!m.is_delta(), "{m:?}");
        n_nondelta += 1;
        sum_nd += energy;
        sum_nd2 += energy * energy;
        let (f, p) = (m.eval(wo, s.wi), m.pdf(wo, s.wi));
        assert!(close(p, s.pdf, 1e-4), "{m:?} {wo}: pdf {} vs {p}", s.pdf);
        assert!(
            close3(s.weight, f / p, 1e-4),
            "{m:?} {wo}: {} vs {}",
            s.weight,
            f / p
        );
        check_reciprocity(m, wo, s.wi);
    }
    let n = N_SAMPLES as f64;
    let albedo_mc = sum / n;
    let albedo_sigma = ((sum2 / n - albedo_mc * albedo_mc).max(DVec3::ZERO) / n).powf(0.5);

    let (pdf_integral, eval_integral) = half_vector_quadrature(m, wo, |wi| {
        let eta2 = (side_ior(m, wi) / eta_o).powi(2) as f64;
        (m.pdf(wo, wi) as f64, m.eval(wo, wi).as_dvec3() * eta2)
    });
    let delta_mass = delta
        .iter()
        .flatten()
        .fold(DVec3::ZERO, |acc, &(w, p, e, _)| {
            acc + w.as_dvec3() * (p as f64 * (e as f64).powi(2))
        });
    let albedo_quad = eval_integral + delta_mass;
    let frac = n_nondelta as f64 / n;
    // Binomial 5σ; 2e-3 absorbs the quadrature's error at the horizon, where the pdf jumps.
    let tol = 5.0 * (frac * (1.0 - frac) / n).sqrt() + 2e-3;
    assert!(
        pdf_integral <= 1.0 + 2e-3,
        "{m:?} {wo}: ∫pdf = {pdf_integral}"
    );
    assert!(
        (pdf_integral - frac).abs() < tol,
        "{m:?} {wo}: ∫pdf {pdf_integral} vs {frac}"
    );
    for (w, p, _, count) in delta.iter().flatten() {
        let fd = *count as f64 / n;
        let tol = 5.0 * (fd * (1.0 - fd) / n).sqrt() + 1e-6;
        assert!(
            (fd - *p as f64).abs() < tol,
            "{m:?} {wo}: delta {w} {fd} vs {p}"
        );
    }
    assert_eq!(
        m.is_delta(),
        n_nondelta == 0 && !m.has_smooth_part(),
        "{m:?}"
    );

    // The sampler's estimate vs quadrature of eval: 5σ of MC + 2e-3 of quadrature error.
    let diff = (albedo_mc - albedo_quad).abs();
    let ok = diff.cmple(albedo_sigma * 5.0 + 2e-3).all();
    assert!(ok, "{m:?} {wo}: {albedo_mc} vs {albedo_quad}");
    // Energy conservation: quadrature within its error, the MC estimate within 5σ.
    assert!(
        albedo_quad.max_element() <= max_energy + 2e-3,
        "{m:?} {wo}: {albedo_quad}"
    );
    // 1e-6: a smooth refraction's 1/η'²·η'² is 1 only to f32 rounding.
    let lo = albedo_mc - albedo_sigma * 5.0;
    assert!(
        lo.max_element() <= max_energy + 1e-6,
        "{m:?} {wo}: {albedo_mc}"
    );

    // Uniform estimate of the non-delta energy ∫eval·η'², independent of sample(): over the
    // hemisphere of wo, or the whole sphere for a transmitting material.
    let (mut su, mut su2) = (DVec3::ZERO, DVec3::ZERO);
    let mut urng = Rng::new(seed, stream, 1);
    let (z_range, solid_angle) = if m.transmits() {
        (2.0, 4.0 * PI)
    } else {
        (1.0, 2.0 * PI)
    };
    for _ in 0..N_SAMPLES {
        let u: Vec2 = urng.next_2d();
        let z = (1.0 - z_range * u.x) * wo.z.signum(); // (0, 1] on wo's side, first
        if z == 0.0 {
            continue;
        }
        let r = crate::math::safe_sqrt(1.0 - z * z);
        let (sn, c) = (2.0 * std::f32::consts::PI * u.y).sin_cos();
        let wi = Vec3::new(r * c, r * sn, z);
        check_reciprocity(m, wo, wi);
        let eta2 = ((side_ior(m, wi) / eta_o) as f64).powi(2);
        let e = m.eval(wo, wi).as_dvec3() * (solid_angle * eta2);
        su += e;
        su2 += e * e;
    }
    let mu = su / n;
    let var_u = (su2 / n - mu * mu).max(DVec3::ZERO) / n;
    let nd = sum_nd / n;
    let var_nd = (sum_nd2 / n - nd * nd).max(DVec3::ZERO) / n;
    // The σ of a uniform estimate is only trustworthy once it has seen the lobe many times:
    // require an effective sample size (Σe)²/Σe² ≥ 100 (or eval ≡ 0, as for mirrors). Lobes
    // with α ≲ 0.01 (tens of hits in 1e5) fail that; the quadrature comparison covers them.
    let ess = su.element_sum().powi(2) / (su2.element_sum() + 1e-300);
    if ess >= 100.0 || su2.element_sum() == 0.0 {
        let tol = (var_u + var_nd).powf(0.5) * 5.0 + 1e-4;
        let ok = (mu - nd).abs().cmple(tol).all();
        assert!(ok, "{m:?} {wo}: uniform {mu} vs sampled {nd}");
    }
    Report {
        theta_deg: th,
        inside: wo.z < 0.0,
        pdf_integral,
        albedo_mc,
        albedo_sigma,
        albedo_quad,
    }
}

/// Generalised reciprocity f(wo,wi)/η(wo)² = f(wi,wo)/η(wi)², with f = eval/|cosθi| (relative
/// 1e-4); for a thin principled's transmission only where its lobe is valid both ways or
/// neither (Mitsuba's model is not reciprocal otherwise, `materials/principled_thin.rs`).
fn check_reciprocity(m: &Material, wo: Vec3, wi: Vec3) {
    if let Material::PrincipledThin(p) = m
        && !p.transmission_is_reciprocal(wo, wi)
    {
        return;
    }
    let (eo, ei) = (side_ior(m, wo), side_ior(m, wi));
    let there = m.eval(wo, wi) / wi.z.abs() / (eo * eo);
    let back = m.eval(wi, wo) / wo.z.abs() / (ei * ei);
    assert!(
        close3(there, back, 1e-4),
        "{m:?} reciprocity {wo} {wi}: {there} {back}"
    );
}

/// At wo.z = 1e-6 (and exactly at normal incidence) everything stays finite, and samples keep
/// weight = eval/pdf.
fn check_grazing(m: &Material, seed: u32) {
    let mut rng = Rng::new(seed, 99, 0);
    let grazing = Vec3::new(crate::math::safe_sqrt(1.0 - 1e-12), 0.0, 1e-6);
    let below = |w: Vec3| Vec3::new(w.x, w.y, -w.z);
    let mut wos = vec![grazing, Vec3::Z];
    if m.transmits() {
        wos.extend([below(grazing), -Vec3::Z]);
    }
    for wo in wos {
        for _ in 0..20_000 {
            let Some(s) = m.sample(wo, rng.next_f32(), rng.next_2d()) else {
                continue;
            };
            assert!(
                s.weight.is_finite() && s.pdf.is_finite() && s.pdf > 0.0,
                "{m:?} {s:?}"
            );
            let (f, p) = (m.eval(wo, s.wi), m.pdf(wo, s.wi));
            assert!(f.is_finite() && p.is_finite(), "{m:?} {s:?}");
            assert!(s.delta || close3(s.weight, f / p, 1e-4), "{m:?} {s:?}");
        }
    }
}

/// A unit vector from a JSON array of three numbers (the Mitsuba values files).
pub(crate) fn json_vec3(v: &serde_json::Value) -> Vec3 {
    let c = |i: usize| v[i].as_f64().expect("a number") as f32;
    Vec3::new(c(0), c(1), c(2))
}

/// lumis' eval and pdf against Mitsuba's own at every direction pair of
/// `tests/data/refs/{file}` (written by a `tools/mitsuba_*_values.py`), the material of each case
/// built by `material_of` from the case's Mitsuba parameters. Relative tolerance `tol` on eval
/// (per channel) and pdf, with an absolute floor of 1e-4 of the case's largest value (values run
/// down to 1e-9 at grazing angles, where f32 rounding of the half vector alone moves them by more
/// than any relative tolerance). Panics with the failing pairs, or if there are not `min_pairs`;
/// prints the largest differences.
pub(crate) fn assert_matches_mitsuba_values(
    file: &str,
    min_pairs: usize,
    tol: f32,
    material_of: impl Fn(&serde_json::Value) -> Material,
) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../tests/data/refs")
        .join(file);
    let data: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let relative = |a: f32, b: f32, scale: f32| {
        (a - b).abs() / a.abs().max(b.abs()).max(1e-4 * scale).max(1e-30)
    };
    let (mut worst_eval, mut worst_pdf, mut pairs) = (0.0f32, 0.0f32, 0);
    let mut failures = Vec::new();
    for case in data["cases"].as_array().unwrap() {
        let bsdf = &case["bsdf"];
        let m = material_of(bsdf);
        let values = case["values"].as_array().unwrap();
        let all_pairs = || values.iter().flat_map(|e| e["pairs"].as_array().unwrap());
        let eval_scale = all_pairs()
            .map(|p| json_vec3(&p["eval"]).max_element())
            .fold(0.0, f32::max);
        let pdf_scale = all_pairs()
            .map(|p| p["pdf"].as_f64().unwrap() as f32)
            .fold(0.0, f32::max);
        for entry in values {
            let wo = json_vec3(&entry["wo"]);
            for pair in entry["pairs"].as_array().unwrap() {
                let wi = json_vec3(&pair["wi"]);
                let (f, pdf) = (m.eval(wo, wi), m.pdf(wo, wi));
                let f_mi = json_vec3(&pair["eval"]);
                let pdf_mi = pair["pdf"].as_f64().unwrap() as f32;
                let d_eval = (0..3)
                    .map(|c| relative(f[c], f_mi[c], eval_scale))
                    .fold(0.0, f32::max);
                let d_pdf = relative(pdf, pdf_mi, pdf_scale);
                worst_eval = worst_eval.max(d_eval);
                worst_pdf = worst_pdf.max(d_pdf);
                pairs += 1;
                if d_eval >= tol || d_pdf >= tol {
                    failures.push(format!(
                        "{bsdf} wo {wo} wi {wi}: lumis {f} pdf {pdf}, Mitsuba {f_mi} pdf {pdf_mi}"
                    ));
                }
            }
        }
    }
    eprintln!(
        "{pairs} pairs; largest relative differences from Mitsuba: eval {worst_eval:.2e}, pdf \
         {worst_pdf:.2e}"
    );
    assert!(pairs >= min_pairs, "{pairs} pairs");
    assert!(
        failures.is_empty(),
        "{} of {pairs} pairs differ:\n{}",
        failures.len(),
        failures[..failures.len().min(30)].join("\n")
    );
}
