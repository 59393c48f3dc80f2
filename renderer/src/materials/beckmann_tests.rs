//! Tests of `beckmann.rs`: normalisation of D and of the visible-normal pdf, the sampler against
//! the pdf (moments), the exact Λ against an f64 evaluation, Mitsuba's rational G1 within its
//! stated 0.35%, and finiteness at grazing angles and extreme α.

use super::*;
use crate::materials::ggx::tests::{assert_moments_match, hemisphere_quadrature};
use crate::rng::Rng;

/// The visible-normal pdf of Beckmann (α_u, α_v), through the one definition of it.
fn visible_normal_pdf(alpha_u: f32, alpha_v: f32, wo: Vec3, h: Vec3) -> f32 {
    crate::materials::Microfacet {
        distribution: crate::materials::Distribution::Beckmann,
        alpha_u,
        alpha_v,
    }
    .visible_normal_pdf(wo, h)
}

fn dir(theta_deg: f32, phi_deg: f32) -> Vec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
}

/// (α_u, α_v) pairs: isotropic narrow to wide, and anisotropic both ways.
const ALPHAS: [(f32, f32); 5] = [
    (0.05, 0.05),
    (0.3, 0.3),
    (1.0, 1.0),
    (0.1, 1.0),
    (0.8, 0.08),
];

#[test]
fn d_projected_area_is_one() {
    for (au, av) in ALPHAS {
        let i = hemisphere_quadrature(4000, 512, |h| d(au, av, h) as f64 * h.z as f64);
        // Quadrature error is ~1e-5 for the narrowest lobe here; 1e-3 leaves room for f32.
        assert!((i - 1.0).abs() < 1e-3, "alpha ({au}, {av}): {i}");
    }
}

#[test]
fn vndf_pdf_integrates_to_one() {
    // With the exact Λ, ∫ G1(wo)·max(0, wo·h)·D(h) dω = wo.z exactly: this is what fails for
    // Mitsuba's rational G1 (by up to its 0.35%).
    for (au, av) in ALPHAS {
        for (th, ph) in [(0.0, 0.0), (45.0, 30.0), (80.0, 90.0), (89.0, 200.0)] {
            let wo = dir(th, ph);
            let i = hemisphere_quadrature(2000, 512, |h| visible_normal_pdf(au, av, wo, h) as f64);
            assert!(
                (i - 1.0).abs() < 2e-3,
                "alpha ({au}, {av}) at {th}/{ph}: {i}"
            );
        }
    }
}

#[test]
fn lambda_is_the_exact_smith_function() {
    // Λ(a) = (erf(a) − 1)/2 + exp(−a²)/(2a√π) in f64 (libm), a = 1/(α tanθ).
    for (au, av) in ALPHAS {
        for th in [1.0f32, 20.0, 45.0, 70.0, 85.0, 89.5] {
            for ph in [0.0f32, 60.0, 90.0] {
                let w = dir(th, ph);
                let (x, y) = ((au * w.x) as f64, (av * w.y) as f64);
                let a = w.z as f64 / (x * x + y * y).sqrt();
                let want = (libm::erf(a) - 1.0) / 2.0
                    + (-a * a).exp() / (2.0 * a * std::f64::consts::PI.sqrt());
                let got = lambda(au, av, w) as f64;
                // 3e-7 relative to 1 + Λ: what G1 = 1/(1 + Λ) sees.
                assert!(
                    (got - want).abs() < 3e-7 * (1.0 + want),
                    "alpha ({au}, {av}) {th}/{ph}: {got} vs {want}"
                );
            }
        }
    }
    assert_eq!(lambda(0.3, 0.3, Vec3::Z), 0.0);
    assert_eq!(g1(0.3, 0.3, Vec3::X), 0.0);
}

/// Mitsuba's (and Walter 2007's) rational approximation of the Beckmann G1.
fn mitsuba_g1(a: f64) -> f64 {
    if a >= 1.6 {
        1.0
    } else {
        (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a)
    }
}

#[test]
fn mitsuba_rational_g1_is_close() {
    // The image difference that lumis' exact G1 makes against Mitsuba's is bounded by the
    // largest ratio of the two masking terms, per factor of G1 in f (two per bounce).
    let mut worst = 0.0f64;
    for i in 1..4000 {
        let a = i as f64 * 1e-3;
        let w = Vec3::new(1.0, 0.0, a as f32).normalize();
        let exact = g1(1.0, 1.0, w) as f64;
        let rel = (mitsuba_g1(a) / exact - 1.0).abs();
        worst = worst.max(rel);
    }
    eprintln!("largest |G1_mitsuba / G1_exact − 1| = {worst:.5}");
    assert!(worst < 0.0035, "{worst}");
}

#[test]
fn vndf_samples_follow_the_pdf() {
    for (k, (au, av)) in ALPHAS.into_iter().enumerate() {
        for (l, (th, ph)) in [(0.0f32, 0.0f32), (50.0, 30.0), (85.0, 120.0)]
            .into_iter()
            .enumerate()
        {
            let wo = dir(th, ph);
            let mut rng = Rng::new(13, k as u32, l as u32);
            assert_moments_match(
                || sample_visible_normal(au, av, wo, rng.next_2d()),
                |h| visible_normal_pdf(au, av, wo, h),
                200_000,
                256,
                &format!("alpha ({au}, {av}) at {th}/{ph}"),
            );
        }
    }
}

#[test]
fn finite_at_grazing_normal_incidence_and_extreme_alpha() {
    let grazing = Vec3::new(crate::math::safe_sqrt(1.0 - 1e-12), 0.0, 1e-6);
    let mut rng = Rng::new(5, 1, 0);
    for (au, av) in [(1e-3, 1e-3), (0.01, 1.0), (1.0, 1.0), (2.0, 0.5)] {
        for wo in [grazing, Vec3::Z, dir(30.0, 45.0)] {
            assert!(lambda(au, av, wo).is_finite() && g1(au, av, wo) > 0.0);
            for _ in 0..5_000 {
                let h = sample_visible_normal(au, av, wo, rng.next_2d());
                assert!(
                    h.is_finite() && (h.length() - 1.0).abs() < 1e-4 && h.z > 0.0,
                    "{h}"
                );
                let p = visible_normal_pdf(au, av, wo, h);
                assert!(p.is_finite() && p >= 0.0 && d(au, av, h).is_finite());
            }
            for u in [
                Vec2::ZERO,
                Vec2::new(0.0, 0.99999994),
                Vec2::new(0.99999994, 0.0),
                Vec2::splat(0.99999994),
            ] {
                assert!(sample_visible_normal(au, av, wo, u).is_finite());
            }
        }
    }
}
