//! The clearcoat lobe's microfacets: Burley's isotropic GTR1 ("generalised Trowbridge–Reitz",
//! γ = 1) distribution and the separable GGX masking Mitsuba 3.9.1's `principled` pairs with it
//! (`src/bsdfs/principledhelpers.h`: `GTR1Isotropic`, `clearcoat_G`, `smith_ggx1`). Its normals
//! are sampled from D·cosθ, not from the visible normals: the lobe is faint (Burley's
//! clearcoat has a quarter of the main lobe's energy), so Mitsuba did not bother.
//! WGSL twin: `materials/gtr1.wgsl`.

use crate::math::safe_sqrt;
use glam::{Vec2, Vec3};
use std::f32::consts::{PI, TAU};

/// D(m) = (α² − 1) / (π ln α² (1 + (α² − 1) cos²θ)), normalised so that ∫ D cosθ dω = 1; 0 where
/// D·cosθ ≤ 1e-20 (below the horizon, and Mitsuba's guard against underflow). α in (0, 1).
pub fn d(alpha: f32, m: Vec3) -> f32 {
    let a2 = alpha * alpha;
    let cos2 = m.z * m.z;
    let d = (a2 - 1.0) / (PI * a2.ln() * (1.0 + (a2 - 1.0) * cos2));
    if d * m.z > 1e-20 { d } else { 0.0 }
}

/// The density of [`sample`]: D(m)·cosθ on the upper hemisphere.
pub fn pdf(alpha: f32, m: Vec3) -> f32 {
    if m.z < 0.0 { 0.0 } else { m.z * d(alpha, m) }
}

/// A normal drawn ∝ D(m)·cosθ: cos²θ = (1 − α^(2(1 − u₁))) / (1 − α²), φ = 2π u₀.
pub fn sample(alpha: f32, u: Vec2) -> Vec3 {
    let a2 = alpha * alpha;
    let cos2 = (1.0 - a2.powf(1.0 - u.y)) / (1.0 - a2);
    let sin = safe_sqrt(1.0 - cos2);
    let cos = safe_sqrt(cos2);
    let phi = TAU * u.x;
    Vec3::new(phi.cos() * sin, phi.sin() * sin, cos)
}

/// The `u` that [`sample`] maps to `m` (m.z > 0): the inverse of both coordinates.
pub fn invert(alpha: f32, m: Vec3) -> Vec2 {
    let a2 = alpha * alpha;
    let cos2 = m.z * m.z;
    // α^(2(1 − u₁)) = 1 − cos²θ (1 − α²).
    let u1 = 1.0 - (1.0 - cos2 * (1.0 - a2)).ln() / a2.ln();
    let phi = m.y.atan2(m.x);
    let u0 = if phi < 0.0 {
        phi / TAU + 1.0
    } else {
        phi / TAU
    };
    Vec2::new(u0, u1)
}

/// Smith's GGX masking of one direction `v` against the microfacet `m` with roughness α:
/// 2 / (1 + √(1 + α² tan²θ)); 1 at normal incidence, 0 when `v` sees the microfacet from behind.
pub fn smith_ggx1(v: Vec3, m: Vec3, alpha: f32) -> f32 {
    if v.dot(m) * v.z <= 0.0 {
        return 0.0;
    }
    if v.z == 1.0 {
        return 1.0;
    }
    let cos2 = v.z * v.z;
    let tan2 = (1.0 - cos2) / cos2;
    2.0 / (1.0 + (1.0 + alpha * alpha * tan2).sqrt())
}

/// The clearcoat's separable masking-shadowing, always at α = 0.25 whatever its gloss (Burley
/// 2012; Mitsuba's `clearcoat_G` is called with 0.25).
pub fn clearcoat_g(wo: Vec3, wi: Vec3, m: Vec3) -> f32 {
    smith_ggx1(wo, m, 0.25) * smith_ggx1(wi, m, 0.25)
}

/// The clearcoat's α from its gloss: 0.1 at gloss 0, 0.001 at gloss 1 (Mitsuba's
/// `lerp(0.1, 0.001, gloss)`, in drjit's form b·t + (a − a·t), exact at both ends).
pub fn clearcoat_alpha(gloss: f32) -> f32 {
    0.001 * gloss + (0.1 - 0.1 * gloss)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    /// ∫ D(m) cosθ dω = 1, for the whole range of α: with y = cos²θ it is ½∫₀¹ D(y) dy, whose
    /// peak at y = 1 is α² wide, so the midpoint rule runs over ln(1 − y) (nodes from 1e-14 to 1;
    /// the rest of the interval holds < 1e-9).
    #[test]
    fn d_is_normalised() {
        for alpha in [0.001f32, 0.01, 0.05, 0.1, 0.3] {
            let n = 200_000;
            let (lo, hi) = ((1e-14f64).ln(), 0.0f64);
            let dz = (hi - lo) / n as f64;
            let mut sum = 0.0f64;
            for i in 0..n {
                let w = (lo + (i as f64 + 0.5) * dz).exp();
                let c = (1.0 - w).sqrt();
                let m = Vec3::new(w.sqrt() as f32, 0.0, c as f32);
                sum += d(alpha, m) as f64 * w * dz;
            }
            let integral = 0.5 * sum * std::f64::consts::TAU;
            assert!((integral - 1.0).abs() < 2e-3, "α {alpha}: {integral}");
        }
    }

    /// `invert` undoes `sample`, and the samples' cos θ follow the CDF of the density `pdf`
    /// (a Kolmogorov–Smirnov test at significance 1e-3, seed 4700; it detects a CDF off by
    /// 0.014 anywhere; the χ² of the whole principled sampler is in `stats`).
    #[test]
    fn sample_inverts_and_matches_its_pdf() {
        let mut rng = Rng::new(4700, 0, 0);
        for alpha in [0.001f32, 0.05, 0.1] {
            let n = 20_000;
            let mut cos: Vec<f32> = Vec::with_capacity(n);
            for _ in 0..n {
                let u = Vec2::new(rng.next_f32(), rng.next_f32());
                let m = sample(alpha, u);
                assert!((m.length() - 1.0).abs() < 1e-5 && m.z >= 0.0);
                let back = invert(alpha, m);
                // u₁ near 1 maps to cos near 1, where cos² loses digits: compare through `sample`.
                let again = sample(alpha, back);
                assert!(
                    (again - m).length() < 2e-3,
                    "α {alpha}: {u} → {m} → {back} → {again}"
                );
                cos.push(m.z);
            }
            cos.sort_by(f32::total_cmp);
            // CDF of cos θ under the density `d`·cos θ dω, integrated by hand (not through
            // `invert`): F(c) = 2π∫₀ᶜ D(x) x dx = ln(1 + (α² − 1)c²) / ln α².
            let a2 = alpha * alpha;
            let ks = cos
                .iter()
                .enumerate()
                .map(|(i, &c)| {
                    let f = (1.0 + (a2 - 1.0) * c * c).ln() / a2.ln();
                    ((i as f32 + 1.0) / n as f32 - f)
                        .abs()
                        .max((i as f32 / n as f32 - f).abs())
                })
                .fold(0.0f32, f32::max);
            // KS critical value at α = 1e-3 for n = 20 000: 1.95/√n = 0.0138.
            assert!(ks < 0.0138, "α {alpha}: KS {ks}");
        }
    }

    #[test]
    fn masking_is_one_at_the_pole_and_zero_from_behind() {
        let m = Vec3::Z;
        assert_eq!(smith_ggx1(Vec3::Z, m, 0.25), 1.0);
        let v = Vec3::new(0.6, 0.0, 0.8);
        let g = smith_ggx1(v, m, 0.25);
        let tan2 = (0.36f32) / 0.64;
        assert!((g - 2.0 / (1.0 + (1.0 + 0.0625 * tan2).sqrt())).abs() < 1e-7);
        assert_eq!(smith_ggx1(v, Vec3::new(-1.0, 0.0, 0.0), 0.25), 0.0);
        assert_eq!(clearcoat_alpha(0.0), 0.1);
        assert_eq!(clearcoat_alpha(1.0), 0.001);
    }
}
