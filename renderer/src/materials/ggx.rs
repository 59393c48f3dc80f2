//! GGX (Trowbridge–Reitz) microfacet distribution with Smith masking, isotropic (`alpha`) and
//! anisotropic (`alpha_u` along the frame's x, `alpha_v` along y; the `_anisotropic` functions,
//! which are the isotropic ones bit for bit where the two are equal).
//!
//! `alpha` is the GGX α itself (used as is, never squared again by a caller). Directions are in the
//! local shading frame (normal = +z) and unit length. Visible normals are sampled with Dupuy &
//! Benyoub 2023, "Sampling Visible GGX Normals with Spherical Caps": it draws exactly Heitz 2018's
//! VNDF (same pdf, `G1(wo)·max(0, wo·h)·D(h)/wo.z`) but needs no orthonormal basis around `wo` and
//! no branches, so it is cheaper and mirrors one-to-one in WGSL. Eto & Tokuyoshi 2023's bounded
//! VNDF samples a *different*, more complex pdf, which every caller would then have to match.
//! WGSL twin: `materials/ggx.wgsl`.

use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// Below this α a microfacet lobe is treated as a perfect (delta) mirror; α = 0 always is.
///
/// Same value as pbrt-v4's `EffectivelySmooth`. At α = 1e-3 the lobe is ~0.1° wide, narrower than
/// any pixel footprint we render, so a mirror looks identical while avoiding D peaks of 1/(πα²)
/// that make light sampling useless; yet f32 still resolves it (half-vector tangents ~α ≫ ε).
pub const SMOOTH_ALPHA: f32 = 1e-3;

/// True if a lobe of roughness `alpha` is handled as a delta mirror.
#[inline]
pub fn is_smooth(alpha: f32) -> bool {
    alpha < SMOOTH_ALPHA
}

/// Normal distribution D(h), normalised so that ∫ D(h)·h.z dω = 1; 0 below the horizon.
#[inline]
pub fn d(alpha: f32, h: Vec3) -> f32 {
    if h.z <= 0.0 {
        return 0.0;
    }
    // Use x²+y² for sin²θ instead of 1−cos²θ: the latter cancels catastrophically near the
    // peak when α is small.
    let a2 = alpha * alpha;
    let t = (h.x * h.x + h.y * h.y) / a2 + h.z * h.z;
    1.0 / (PI * a2 * t * t)
}

/// [`d`] for roughness `alpha_u` along x and `alpha_v` along y:
/// 1/(π α_u α_v (h_x²/α_u² + h_y²/α_v² + h_z²)²).
#[inline]
pub fn d_anisotropic(alpha_u: f32, alpha_v: f32, h: Vec3) -> f32 {
    if alpha_u == alpha_v {
        return d(alpha_u, h);
    }
    if h.z <= 0.0 {
        return 0.0;
    }
    let (x, y) = (h.x / alpha_u, h.y / alpha_v);
    let t = x * x + y * y + h.z * h.z;
    1.0 / (PI * alpha_u * alpha_v * t * t)
}

/// Smith Λ(w) = (√(1 + α² tan²θ) − 1)/2; symmetric in w.z (callers check hemispheres), +∞ at
/// the horizon.
#[inline]
pub fn lambda(alpha: f32, w: Vec3) -> f32 {
    let a = alpha * alpha * (w.x * w.x + w.y * w.y) / (w.z * w.z);
    if !a.is_finite() {
        return f32::INFINITY;
    }
    // a/(2(1+√(1+a))) equals the textbook form without its cancellation for small α tanθ.
    0.5 * a / (1.0 + (1.0 + a).sqrt())
}

/// Smith masking G1(w) = 1/(1 + Λ(w)), in the form 2|z|/(|z| + √(z² + α²(x²+y²))) that needs
/// no tanθ and so is exact down to the horizon (where it is 0).
#[inline]
pub fn g1(alpha: f32, w: Vec3) -> f32 {
    let z = w.z.abs();
    let r = (z * z + alpha * alpha * (w.x * w.x + w.y * w.y)).sqrt();
    if r <= 0.0 { 0.0 } else { 2.0 * z / (z + r) }
}

/// [`g1`] for roughness `alpha_u` along x and `alpha_v` along y (α² tan²θ becomes
/// (α_u² w_x² + α_v² w_y²)/w_z²).
#[inline]
pub fn g1_anisotropic(alpha_u: f32, alpha_v: f32, w: Vec3) -> f32 {
    if alpha_u == alpha_v {
        return g1(alpha_u, w);
    }
    let z = w.z.abs();
    let (x, y) = (alpha_u * w.x, alpha_v * w.y);
    let r = (z * z + x * x + y * y).sqrt();
    if r <= 0.0 { 0.0 } else { 2.0 * z / (z + r) }
}

/// Separable Smith masking-shadowing G1(wo)·G1(wi) (the scene format specifies it, not the
/// height-correlated form).
#[inline]
pub fn g2_separable(alpha: f32, wo: Vec3, wi: Vec3) -> f32 {
    g1(alpha, wo) * g1(alpha, wi)
}

/// Half vector h of the unit directions `wo`, `wi` and the cosine wo·h = wi·h = |wo + wi|/2.
/// That cosine is exactly symmetric in (wo, wi) and free of the cancellation of dotting with a
/// rounded h when the two directions are nearly opposite (which breaks reciprocity by ~1e-4).
#[inline]
pub fn half_vector(wo: Vec3, wi: Vec3) -> (Vec3, f32) {
    let s = wo + wi;
    let len = s.length();
    (s / len, 0.5 * len)
}

/// Samples a microfacet normal from the distribution of normals visible from `wo` (wo.z ≥ 0),
/// with pdf [`visible_normal_pdf`]. Dupuy & Benyoub 2023: in the α-stretched (hemisphere)
/// configuration the visible normals are `c + wo` for `c` uniform on the spherical cap
/// z ∈ (−wo.z, 1]; unstretching maps them back. The lobe's tail is set by 1 − u.y (exact in f32)
/// through h_std.z = (1 − u.y)(1 + wo_std.z): the RNG's 24-bit uniforms reach the whole lobe in
/// f32 down to grazing `wo` (measured by `ggx/reachability.rs`).
#[inline]
pub fn sample_visible_normal(alpha: f32, wo: Vec3, u: Vec2) -> Vec3 {
    sample_visible_normal_anisotropic(alpha, alpha, wo, u)
}

/// [`sample_visible_normal`] for roughness `alpha_u` along x and `alpha_v` along y: the stretch
/// to the hemisphere configuration scales x by α_u and y by α_v (Dupuy & Benyoub's section 4).
#[inline]
pub fn sample_visible_normal_anisotropic(alpha_u: f32, alpha_v: f32, wo: Vec3, u: Vec2) -> Vec3 {
    let wo_std = Vec3::new(wo.x * alpha_u, wo.y * alpha_v, wo.z).normalize_or(Vec3::Z);
    let phi = 2.0 * PI * u.x;
    let z = (1.0 - u.y).mul_add(1.0 + wo_std.z, -wo_std.z);
    let sin_theta = crate::math::safe_sqrt(1.0 - z * z);
    let (s, c) = phi.sin_cos();
    let h_std = Vec3::new(sin_theta * c, sin_theta * s, z) + wo_std;
    // The fallback only triggers for the measure-zero c = −wo; it keeps the result finite.
    Vec3::new(h_std.x * alpha_u, h_std.y * alpha_v, h_std.z.max(0.0)).normalize_or(Vec3::Z)
}

/// Solid-angle pdf of [`sample_visible_normal`]: G1(wo)·max(0, wo·h)·D(h)/wo.z.
#[inline]
pub fn visible_normal_pdf(alpha: f32, wo: Vec3, h: Vec3) -> f32 {
    if wo.z <= 0.0 {
        return 0.0;
    }
    g1(alpha, wo) * wo.dot(h).max(0.0) * d(alpha, h) / wo.z
}

#[cfg(test)]
mod reachability;

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::rng::Rng;

    /// Midpoint quadrature of `g` over the hemisphere (f64 sums). θ = (π/2)t² concentrates nodes
    /// near the pole, where the narrow GGX peaks are.
    pub(crate) fn hemisphere_quadrature(n_t: usize, n_phi: usize, g: impl Fn(Vec3) -> f64) -> f64 {
        let mut sum = 0.0f64;
        for i in 0..n_t {
            let t = (i as f64 + 0.5) / n_t as f64;
            let theta = std::f64::consts::FRAC_PI_2 * t * t;
            let dtheta = std::f64::consts::PI * t / n_t as f64;
            let mut ring = 0.0;
            for j in 0..n_phi {
                let phi = 2.0 * std::f64::consts::PI * (j as f64 + 0.5) / n_phi as f64;
                let w = Vec3::new(
                    (theta.sin() * phi.cos()) as f32,
                    (theta.sin() * phi.sin()) as f32,
                    theta.cos() as f32,
                );
                ring += g(w);
            }
            sum += ring * theta.sin() * dtheta * 2.0 * std::f64::consts::PI / n_phi as f64;
        }
        sum
    }

    fn dir(theta_deg: f32) -> Vec3 {
        let t = theta_deg.to_radians();
        Vec3::new(t.sin(), 0.0, t.cos())
    }

    #[test]
    fn d_projected_area_is_one() {
        for alpha in [0.01, 0.1, 0.5, 1.0] {
            let i = hemisphere_quadrature(4000, 16, |h| d(alpha, h) as f64 * h.z as f64);
            // Quadrature error is ~1e-6 here; 1e-3 leaves room for f32 evaluation of D.
            assert!((i - 1.0).abs() < 1e-3, "alpha {alpha}: {i}");
        }
    }

    #[test]
    fn vndf_pdf_integrates_to_one() {
        for alpha in [0.01, 0.1, 0.5, 1.0] {
            for th in [0.0, 45.0, 80.0, 89.9] {
                let wo = dir(th);
                let i =
                    hemisphere_quadrature(2000, 256, |h| visible_normal_pdf(alpha, wo, h) as f64);
                // The φ dependence (through wo·h) is smooth, so 256 nodes suffice; 2e-3 covers it.
                assert!((i - 1.0).abs() < 2e-3, "alpha {alpha} theta {th}: {i}");
            }
        }
    }

    /// Sample means of a few test functions of `n` normals drawn by `sample` against their
    /// quadrature under `pdf` (`n_phi` azimuth nodes): within 5σ of the Monte Carlo mean plus the
    /// quadrature's own error (2e-3). `what` names the case in the message.
    pub(crate) fn assert_moments_match(
        mut sample: impl FnMut() -> Vec3,
        pdf: impl Fn(Vec3) -> f32,
        n: usize,
        n_phi: usize,
        what: &str,
    ) {
        let tests: [fn(Vec3) -> f64; 4] = [
            |h| h.x as f64,
            |h| h.y as f64,
            |h| (h.z * h.z) as f64,
            |h| (h.x * h.z + 0.5 * h.y * h.y) as f64,
        ];
        let hs: Vec<Vec3> = (0..n).map(|_| sample()).collect();
        for g in tests {
            let vals: Vec<f64> = hs.iter().map(|&h| g(h)).collect();
            let mean = vals.iter().sum::<f64>() / n as f64;
            let var = vals.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n as f64;
            let quad = hemisphere_quadrature(800, n_phi, |h| g(h) * pdf(h) as f64);
            let tol = 5.0 * (var / n as f64).sqrt() + 2e-3;
            assert!((mean - quad).abs() < tol, "{what}: {mean} vs {quad}");
        }
    }

    #[test]
    fn vndf_samples_follow_the_pdf() {
        for (k, alpha) in [0.05f32, 0.3, 1.0].into_iter().enumerate() {
            for (l, th) in [0.0f32, 50.0, 85.0].into_iter().enumerate() {
                let wo = dir(th);
                let mut rng = Rng::new(11, k as u32, l as u32);
                assert_moments_match(
                    || sample_visible_normal(alpha, wo, rng.next_2d()),
                    |h| visible_normal_pdf(alpha, wo, h),
                    200_000,
                    128,
                    &format!("a {alpha} th {th}"),
                );
            }
        }
    }

    #[test]
    fn lambda_and_g1_match_closed_forms() {
        // Λ(α=1, 60°) = (√4 − 1)/2 = 0.5; Λ(α=0.5, 60°) = (√1.75 − 1)/2.
        assert!((lambda(1.0, dir(60.0)) - 0.5).abs() < 1e-5);
        assert!((lambda(0.5, dir(60.0)) - (1.75f32.sqrt() - 1.0) / 2.0).abs() < 1e-5);
        assert_eq!(lambda(0.3, Vec3::Z), 0.0);
        for alpha in [SMOOTH_ALPHA, 0.1, 0.5, 1.0] {
            for th in [0.0, 20.0, 60.0, 85.0, 89.9] {
                let w = dir(th);
                let c = w.z;
                // Textbook G1 = 2cos/(cos + √(α² + (1−α²)cos²)).
                let closed = 2.0 * c / (c + (alpha * alpha + (1.0 - alpha * alpha) * c * c).sqrt());
                assert!((g1(alpha, w) - closed).abs() < 1e-5, "{alpha} {th}");
                assert!((g1(alpha, w) - 1.0 / (1.0 + lambda(alpha, w))).abs() < 1e-5);
            }
        }
        assert_eq!(g1(0.5, Vec3::X), 0.0);
        let (wo, wi) = (dir(30.0), dir(-70.0));
        assert_eq!(g2_separable(0.4, wo, wi), g1(0.4, wo) * g1(0.4, wi));
        let (h, c) = half_vector(wo, wi);
        assert!((h - dir(-20.0)).length() < 1e-6 && (c - 50f32.to_radians().cos()).abs() < 1e-6);
    }

    #[test]
    fn finite_at_grazing_and_extreme_alpha() {
        let wo = Vec3::new(crate::math::safe_sqrt(1.0 - 1e-12), 0.0, 1e-6);
        let mut rng = Rng::new(5, 0, 0);
        for alpha in [SMOOTH_ALPHA, 0.01, 1.0] {
            assert!(lambda(alpha, wo).is_finite() && g1(alpha, wo) > 0.0);
            for _ in 0..10_000 {
                let h = sample_visible_normal(alpha, wo, rng.next_2d());
                assert!(
                    h.is_finite() && (h.length() - 1.0).abs() < 1e-4 && h.z >= 0.0,
                    "{h}"
                );
                let p = visible_normal_pdf(alpha, wo, h);
                assert!(p.is_finite() && p >= 0.0 && d(alpha, h).is_finite());
            }
        }
        // Corners of the unit square.
        for u in [
            Vec2::ZERO,
            Vec2::new(0.0, 0.99999994),
            Vec2::new(0.99999994, 0.0),
        ] {
            for w in [wo, Vec3::Z] {
                assert!(sample_visible_normal(SMOOTH_ALPHA, w, u).is_finite());
            }
        }
    }
}
