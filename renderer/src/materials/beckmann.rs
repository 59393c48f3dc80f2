//! Anisotropic Beckmann microfacet distribution with Smith masking, as Mitsuba 3 defines it
//! (`include/mitsuba/render/microfacet.h`), but with the exact masking function.
//!
//! α_u, α_v are the RMS slopes along the frame's x and y (used as is). Directions are in the
//! local shading frame (normal = +z) and unit length.
//!
//! Masking: Mitsuba's `smith_g1` for Beckmann is Walter 2007's rational fit of
//! 1/(1 + Λ), within ~0.35% of it, while its visible-normal sampler draws from the *exact* Λ; its
//! pdf therefore disagrees with its sampler by up to that much. lumis evaluates the exact
//! Λ(a) = (erf(a) − 1)/2 + exp(−a²)/(2a√π), a = 1/(α tanθ), so that the pdf is the sampler's
//! density (the χ² test holds it to that); the image differs from Mitsuba's by under 0.35% where
//! masking matters (grazing angles), the bound measured in `tests::mitsuba_rational_g1_is_close`.
//!
//! Sampling: Mitsuba's visible-normal sampler (Jakob 2014, "An improved visible normal sampling
//! routine for the Beckmann distribution"): stretch `wo` to unit roughness, draw the visible slope
//! along it by Newton steps inside a bisection bracket on its CDF (in the erf domain), the other
//! slope from the gaussian, rotate and unstretch. Mitsuba's shortcut near normal incidence
//! (cosθ > 0.99999: the slope drawn as if `wo` were the normal) is left out: the general path is
//! exact there too, and the shortcut is a (tiny) different density.
//! WGSL twin: `materials/beckmann.wgsl`.

use crate::erf::{erf, erfc, erfinv};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// 1/√π.
const INV_SQRT_PI: f32 = 0.564_189_6;

/// Newton/bisection stops when the slope CDF is this close to its target (Mitsuba's value).
pub const SAMPLE_TOLERANCE: f32 = 1e-5;

/// At most this many Newton/bisection steps; bisection alone would reach the f32 resolution
/// of the bracket in about 24.
pub const SAMPLE_MAX_STEPS: u32 = 64;

/// D(h) = exp(−(h_x²/α_u² + h_y²/α_v²)/h_z²)/(π α_u α_v h_z⁴), normalised so that
/// ∫ D(h)·h.z dω = 1; 0 below the horizon.
#[inline]
pub fn d(alpha_u: f32, alpha_v: f32, h: Vec3) -> f32 {
    if h.z <= 0.0 {
        return 0.0;
    }
    let (x, y) = (h.x / alpha_u, h.y / alpha_v);
    let z2 = h.z * h.z;
    let r = (-(x * x + y * y) / z2).exp() / (PI * alpha_u * alpha_v * z2 * z2);
    // exp underflows to 0 long before z2² does, except at x = y = 0 with z = 1.
    if r.is_finite() { r } else { 0.0 }
}

/// a = 1/(α(w) tanθ) = |w.z|/√(α_u² w_x² + α_v² w_y²): +∞ at the normal, 0 at the horizon.
#[inline]
fn a(alpha_u: f32, alpha_v: f32, w: Vec3) -> f32 {
    let (x, y) = (alpha_u * w.x, alpha_v * w.y);
    w.z.abs() / (x * x + y * y).sqrt()
}

/// Smith Λ(w) = (erf(a) − 1)/2 + exp(−a²)/(2a√π), exact (see the module doc); symmetric in w.z,
/// +∞ at the horizon, 0 at the normal.
#[inline]
pub fn lambda(alpha_u: f32, alpha_v: f32, w: Vec3) -> f32 {
    let a = a(alpha_u, alpha_v, w);
    if a.is_infinite() {
        return 0.0;
    }
    // (exp(−a²)/(a√π) − erfc(a))/2: both terms positive, no erf(a) − 1 to cancel. Past a ≈ 4
    // the difference is below f32's resolution of 1 + Λ anyway.
    (0.5 * ((-a * a).exp() * INV_SQRT_PI / a - erfc(a))).max(0.0)
}

/// Smith masking G1(w) = 1/(1 + Λ(w)); 0 at the horizon.
#[inline]
pub fn g1(alpha_u: f32, alpha_v: f32, w: Vec3) -> f32 {
    1.0 / (1.0 + lambda(alpha_u, alpha_v, w))
}

/// The slopes of visible normals for unit roughness, seen from a direction at cosθ = `cos`,
/// sinθ = `sin` in the xz-plane (towards +x). The first slope has density
/// ∝ (1 − x̃ tanθ)·exp(−x̃²) on x̃ < cotθ; in the erf domain t = erf(x̃) its CDF is
/// (1 + t + tanθ·exp(−erfinv(t)²)/√π)/(1 + erf(cotθ) + tanθ·exp(−cot²θ)/√π), inverted by Newton
/// steps in a bisection bracket from Mitsuba's initial guess. The second slope is gaussian.
fn sample_slopes(cos: f32, sin: f32, u: Vec2) -> Vec2 {
    let tan = sin / cos;
    let cot = cos / sin;
    let theta = cos.acos();
    // Keep the targets off 0 and 1, where erfinv is infinite (Mitsuba clamps likewise; the
    // mass cut away, 2e-6, is far below anything a render resolves).
    let ux = u.x.clamp(1e-6, 1.0 - 1e-6);
    let max_t = erf(cot);
    let norm = 1.0 / (1.0 + max_t + INV_SQRT_PI * tan * (-cot * cot).exp());
    let (mut lo, mut hi) = (-1.0f32, max_t);
    let guess_exp = 1.0 + theta * (-0.876 + theta * (0.4265 - 0.0594 * theta));
    let mut t = max_t - (max_t + 1.0) * (1.0 - ux).powf(guess_exp);
    for _ in 0..SAMPLE_MAX_STEPS {
        // Written so that a NaN step also falls back to bisection.
        if !(t >= lo && t <= hi) {
            t = 0.5 * (lo + hi);
        }
        let e = erfinv(t);
        let value = norm * (1.0 + t + INV_SQRT_PI * tan * (-e * e).exp()) - ux;
        if value.abs() < SAMPLE_TOLERANCE {
            break;
        }
        if value > 0.0 {
            hi = t;
        } else {
            lo = t;
        }
        let derivative = norm * (1.0 - e * tan);
        t -= value / derivative;
    }
    let uy = u.y.clamp(1e-6, 1.0 - 1e-6);
    Vec2::new(erfinv(t), erfinv(2.0 * uy - 1.0))
}

/// Samples a microfacet normal from the distribution of normals visible from `wo` (wo.z > 0),
/// with pdf G1(wo)·max(0, wo·h)·D(h)/wo.z ([`super::Microfacet::visible_normal_pdf`]).
pub fn sample_visible_normal(alpha_u: f32, alpha_v: f32, wo: Vec3, u: Vec2) -> Vec3 {
    // Stretch to unit roughness; the visible slopes there are the unit-roughness ones.
    let w = Vec3::new(alpha_u * wo.x, alpha_v * wo.y, wo.z).normalize_or(Vec3::Z);
    let sin = w.x.hypot(w.y);
    let (cos_phi, sin_phi) = if sin > 0.0 {
        (w.x / sin, w.y / sin)
    } else {
        (1.0, 0.0)
    };
    let s = sample_slopes(w.z.max(1e-7), sin, u);
    // Rotate back to wo's azimuth, unstretch; the normal of slope (sx, sy) is (−sx, −sy, 1).
    let sx = alpha_u * (cos_phi * s.x - sin_phi * s.y);
    let sy = alpha_v * (sin_phi * s.x + cos_phi * s.y);
    Vec3::new(-sx, -sy, 1.0).normalize()
}

#[cfg(test)]
#[path = "beckmann_tests.rs"]
mod tests;
