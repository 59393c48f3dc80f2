//! Shared statistical checks run on every material configuration by the per-material tests.

use super::Material;
use crate::math::reflect;
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
    /// ∫ pdf(wo, wi) dωi by quadrature (non-delta lobes only).
    pub pdf_integral: f64,
    /// Directional albedo: mean of sample weights (all lobes).
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

/// Quadrature of `g(wi)` over the upper hemisphere, done in half-vector space: wi = reflect(wo, h),
/// dωi = 4(wo·h) dωh. Narrow lobes are round bumps around h = +z there (in wi space they become
/// slivers at grazing wo), so θh = (π/2)t² nodes crowded at the pole resolve them.
fn half_vector_quadrature(wo: Vec3, mut g: impl FnMut(Vec3) -> (f64, DVec3)) -> (f64, DVec3) {
    let (n_t, n_phi) = (768, 192);
    let (mut s, mut v) = (0.0, DVec3::ZERO);
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
            let wi = reflect(wo, h);
            if cos_h <= 0.0 || wi.z <= 0.0 {
                continue;
            }
            let (a, b) = g(wi.normalize());
            let w = w_ring * 4.0 * cos_h as f64;
            s += a * w;
            v += b * w;
        }
    }
    (s, v)
}

/// Runs the generic BSDF checks at every angle of [`THETAS_DEG`], asserting what holds for every
/// material, and returns the measurements for material-specific assertions:
/// * every sample is finite with pdf > 0; non-delta samples satisfy weight = eval/pdf and
///   pdf = `pdf(wo, wi)` (relative 1e-4: both sides are computed from the same f32 half vector,
///   so only a few ulps of rounding separate them); delta samples are mirror directions;
/// * reciprocity eval(wo,wi)/cosθi = eval(wi,wo)/cosθo on the sampled pairs (relative 1e-4);
/// * ∫pdf ≤ 1 and equals the fraction of non-delta samples (the sampler's mass matches pdf);
/// * the fraction of delta samples equals their reported selection probability;
/// * directional albedo ≤ 1, and the mean sample weight agrees with quadrature of `eval` and
///   with uniform-hemisphere sampling of `eval` (the sampler is unbiased w.r.t. eval).
pub(crate) fn check_material(m: &Material, seed: u32) -> Vec<Report> {
    check_grazing(m, seed);
    let mut out = Vec::new();
    for (k, &th) in THETAS_DEG.iter().enumerate() {
        let t = th.to_radians();
        let wo = Vec3::new(t.sin(), 0.0, t.cos());
        let mut rng = Rng::new(seed, k as u32, 0);
        let (mut sum, mut sum2) = (DVec3::ZERO, DVec3::ZERO);
        let (mut sum_nd, mut sum_nd2) = (DVec3::ZERO, DVec3::ZERO);
        let (mut n_nondelta, mut n_delta) = (0usize, 0usize);
        let mut delta: Option<(Vec3, f32)> = None; // (weight, selection probability)
        for _ in 0..N_SAMPLES {
            let Some(s) = m.sample(wo, rng.next_f32(), rng.next_2d()) else {
                continue;
            };
            assert!(
                s.weight.is_finite() && s.pdf.is_finite() && s.pdf > 0.0,
                "{m:?} {th} {s:?}"
            );
            assert!(
                (s.wi.length() - 1.0).abs() < 1e-4 && s.wi.z > 0.0,
                "{m:?} {th} {s:?}"
            );
            let w = s.weight.as_dvec3();
            sum += w;
            sum2 += w * w;
            if s.delta {
                assert!(s.pdf <= 1.0 && (s.wi - reflect(wo, Vec3::Z)).length() < 1e-5);
                assert!(
                    delta.is_none_or(|d| d == (s.weight, s.pdf)),
                    "delta lobe depends on wo only"
                );
                delta = Some((s.weight, s.pdf));
                n_delta += 1;
                continue;
            }
            assert!(!m.is_delta(), "{m:?}");
            n_nondelta += 1;
            sum_nd += w;
            sum_nd2 += w * w;
            let (f, p) = (m.eval(wo, s.wi), m.pdf(wo, s.wi));
            assert!(close(p, s.pdf, 1e-4), "{m:?} {th}: pdf {} vs {p}", s.pdf);
            assert!(
                close3(s.weight, f / p, 1e-4),
                "{m:?} {th}: {} vs {}",
                s.weight,
                f / p
            );
            let back = m.eval(s.wi, wo) / wo.z;
            assert!(
                close3(f / s.wi.z, back, 1e-4),
                "{m:?} reciprocity {th}: {} {back}",
                f / s.wi.z
            );
        }
        let n = N_SAMPLES as f64;
        let albedo_mc = sum / n;
        let albedo_sigma = ((sum2 / n - albedo_mc * albedo_mc).max(DVec3::ZERO) / n).powf(0.5);

        let (pdf_integral, eval_integral) =
            half_vector_quadrature(wo, |wi| (m.pdf(wo, wi) as f64, m.eval(wo, wi).as_dvec3()));
        let delta_mass = delta.map_or(DVec3::ZERO, |(w, p)| w.as_dvec3() * p as f64);
        let albedo_quad = eval_integral + delta_mass;
        let frac = n_nondelta as f64 / n;
        // Binomial 5σ; 2e-3 absorbs the quadrature's error at the horizon, where the pdf jumps.
        let tol = 5.0 * (frac * (1.0 - frac) / n).sqrt() + 2e-3;
        assert!(
            pdf_integral <= 1.0 + 2e-3,
            "{m:?} {th}: ∫pdf = {pdf_integral}"
        );
        assert!(
            (pdf_integral - frac).abs() < tol,
            "{m:?} {th}: ∫pdf {pdf_integral} vs {frac}"
        );
        if let Some((_, p)) = delta {
            let fd = n_delta as f64 / n;
            let tol = 5.0 * (fd * (1.0 - fd) / n).sqrt() + 1e-6;
            assert!((fd - p as f64).abs() < tol, "{m:?} {th}: delta {fd} vs {p}");
        }
        assert_eq!(
            m.is_delta(),
            n_nondelta == 0 && !m.has_smooth_part(),
            "{m:?}"
        );

        // The sampler's estimate vs quadrature of eval: 5σ of MC + 2e-3 of quadrature error.
        let diff = (albedo_mc - albedo_quad).abs();
        let ok = diff.cmple(albedo_sigma * 5.0 + 2e-3).all();
        assert!(ok, "{m:?} {th}: {albedo_mc} vs {albedo_quad}");
        // Energy conservation: quadrature within its error, the MC estimate within 5σ.
        assert!(
            albedo_quad.max_element() <= 1.0 + 2e-3,
            "{m:?} {th}: {albedo_quad}"
        );
        let lo = albedo_mc - albedo_sigma * 5.0;
        assert!(lo.max_element() <= 1.0, "{m:?} {th}: {albedo_mc}");

        // Uniform-hemisphere estimate of the non-delta albedo ∫eval, independent of sample().
        let (mut su, mut su2) = (DVec3::ZERO, DVec3::ZERO);
        let mut urng = Rng::new(seed, k as u32, 1);
        for _ in 0..N_SAMPLES {
            let u: Vec2 = urng.next_2d();
            let z = 1.0 - u.x; // (0, 1]
            let r = crate::math::safe_sqrt(1.0 - z * z);
            let (s, c) = (2.0 * std::f32::consts::PI * u.y).sin_cos();
            let wi = Vec3::new(r * c, r * s, z);
            let f = m.eval(wo, wi);
            let back = m.eval(wi, wo) / wo.z;
            assert!(
                close3(f / wi.z, back, 1e-4),
                "{m:?} reciprocity {th}: {} {back}",
                f / wi.z
            );
            let e = f.as_dvec3() * (2.0 * PI);
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
            assert!(ok, "{m:?} {th}: uniform {mu} vs sampled {nd}");
        }
        out.push(Report {
            theta_deg: th,
            pdf_integral,
            albedo_mc,
            albedo_sigma,
            albedo_quad,
        });
    }
    out
}

/// At wo.z = 1e-6 (and exactly at normal incidence) everything stays finite, and samples keep
/// weight = eval/pdf.
fn check_grazing(m: &Material, seed: u32) {
    let mut rng = Rng::new(seed, 99, 0);
    for wo in [
        Vec3::new(crate::math::safe_sqrt(1.0 - 1e-12), 0.0, 1e-6),
        Vec3::Z,
    ] {
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
