//! Linear and bilinear warps of `[0,1)ⁿ`: the building block of cosine-aware light sampling
//! (Hart et al. 2020, "Practical product sampling by fitting and composing warps", as pbrt-v4
//! uses it for spherical triangles and rectangles). A sample square is first warped towards the
//! corner weights — the receiver's |cos θ| at the light's corner directions — and then through
//! the spherical warp, so the composed density is close to proportional to cos θ dω.
//!
//! Conventions: a bilinear weight array `w` holds the corners `(0,0), (1,0), (0,1), (1,1)` in that
//! order; the density on the square is `4·B(p) / Σw` with `B` the bilinear interpolant, so
//! `∫ pdf = 1`. All-zero weights mean the uniform density (there is nothing to prefer), and every
//! function accepts non-negative weights only.
//! WGSL twin: `sampling/bilinear.wgsl`.

use super::ONE_MINUS_EPSILON;
use glam::{Vec2, Vec3};

/// Smallest corner weight of the cosine warp: where the receiver's horizon cuts a light, corners
/// at or below it would otherwise weigh 0 and starve the part of the light above it that lies
/// near them (pbrt-v4 uses the same floor). Any positive weights keep the estimator unbiased.
pub const MIN_COSINE_WEIGHT: f32 = 0.01;

/// The bilinear weights `max(MIN_COSINE_WEIGHT, |ns·ŵ|)` of a cosine warp for a receiver with
/// unit shading normal `ns` and the vectors `to_corners` from it to the four points the corners
/// of the sample square map to (order in the module doc). `|cos|` rather than `cos`, so that a
/// transmitting receiver, lit from below, gets the same warp.
pub fn cosine_corner_weights(ns: Vec3, to_corners: [Vec3; 4]) -> [f32; 4] {
    to_corners.map(|d| ns.dot(d.normalize_or_zero()).abs().max(MIN_COSINE_WEIGHT))
}

/// The density on `[0,1]` proportional to the line from `a` at 0 to `b` at 1 (`a, b ≥ 0`; both 0
/// is the uniform density); 0 outside `[0,1]`.
pub fn linear_pdf(x: f32, a: f32, b: f32) -> f32 {
    if !(0.0..=1.0).contains(&x) {
        return 0.0;
    }
    if a + b == 0.0 {
        return 1.0;
    }
    2.0 * ((1.0 - x) * a + x * b) / (a + b)
}

/// Samples [`linear_pdf`] by inverting its CDF, `x((2 − x)a + xb)/(a + b) = u`, in the form
/// `u(a + b)/(a + √((1−u)a² + ub²))`, which has no cancellation when `a ≈ b`. At `u = 0` with
/// `a = 0` that form is 0/0; the answer is 0. Both weights 0: uniform, `u` itself (a bilinear
/// conditional at an edge whose two corners weigh 0).
pub fn sample_linear(u: f32, a: f32, b: f32) -> f32 {
    if a + b == 0.0 {
        return u;
    }
    if u == 0.0 && a == 0.0 {
        return 0.0;
    }
    let x = u * (a + b) / (a + ((1.0 - u) * a * a + u * b * b).sqrt());
    x.min(ONE_MINUS_EPSILON)
}

/// The CDF of [`linear_pdf`] at `x`: the inverse of [`sample_linear`].
pub fn invert_linear_sample(x: f32, a: f32, b: f32) -> f32 {
    if a + b == 0.0 {
        return x;
    }
    x * (a * (2.0 - x) + b * x) / (a + b)
}

/// The bilinear density at `p` for corner weights `w` (order in the module doc); uniform (1) when
/// every weight is 0.
pub fn bilinear_pdf(p: Vec2, w: [f32; 4]) -> f32 {
    if !(0.0..=1.0).contains(&p.x) || !(0.0..=1.0).contains(&p.y) {
        return 0.0;
    }
    let sum = w[0] + w[1] + w[2] + w[3];
    if sum == 0.0 {
        return 1.0;
    }
    4.0 * ((1.0 - p.x) * (1.0 - p.y) * w[0]
        + p.x * (1.0 - p.y) * w[1]
        + (1.0 - p.x) * p.y * w[2]
        + p.x * p.y * w[3])
        / sum
}

/// Samples [`bilinear_pdf`]: `y` from its marginal (linear between the bottom and top edges'
/// sums), then `x` from the conditional at that `y` (linear between the left and right edges'
/// values there).
pub fn sample_bilinear(u: Vec2, w: [f32; 4]) -> Vec2 {
    if w == [0.0; 4] {
        return u;
    }
    let y = sample_linear(u.y, w[0] + w[1], w[2] + w[3]);
    let x = sample_linear(u.x, lerp(y, w[0], w[2]), lerp(y, w[1], w[3]));
    Vec2::new(x, y)
}

/// The inverse of [`sample_bilinear`]: the `u` that maps to `p`.
pub fn invert_bilinear_sample(p: Vec2, w: [f32; 4]) -> Vec2 {
    if w == [0.0; 4] {
        return p;
    }
    Vec2::new(
        invert_linear_sample(p.x, lerp(p.y, w[0], w[2]), lerp(p.y, w[1], w[3])),
        invert_linear_sample(p.y, w[0] + w[1], w[2] + w[3]),
    )
}

fn lerp(t: f32, a: f32, b: f32) -> f32 {
    (1.0 - t) * a + t * b
}

#[cfg(test)]
#[path = "bilinear_tests.rs"]
mod tests;
