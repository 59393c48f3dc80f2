//! Uniform sampling of the unit disk: Shirley–Chiu concentric and polar mappings.
//! WGSL twin: `sampling/disk.wgsl`.

use glam::Vec2;
use std::f32::consts::{FRAC_PI_2, FRAC_PI_4, PI, TAU};

/// Maps `u ∈ [0,1)²` to the unit disk uniformly (pdf `1/π`) with Shirley and Chiu's concentric
/// mapping: squares go to circles, so strata stay compact and the map is continuous.
pub fn sample_uniform_disk_concentric(u: Vec2) -> Vec2 {
    let (r, theta) = concentric_polar(u);
    r * Vec2::new(theta.cos(), theta.sin())
}

/// The polar form of [`sample_uniform_disk_concentric`]: the point is `r·(cos θ, sin θ)`, with a
/// signed `r` and `θ ∈ [-π/4, 3π/4]` (where GPU sin/cos are accurate), or `(0, 0)` at the centre.
/// Callers that need `1 − r²` get it from `r` exactly rather than from the rounded point.
pub fn concentric_polar(u: Vec2) -> (f32, f32) {
    let o = 2.0 * u - Vec2::ONE;
    if o == Vec2::ZERO {
        return (0.0, 0.0);
    }
    // Each quadrant-like wedge |x| > |y| or |y| >= |x| keeps its square "radius" as the disk radius.
    if o.x.abs() > o.y.abs() {
        (o.x, FRAC_PI_4 * (o.y / o.x))
    } else {
        (o.y, FRAC_PI_2 - FRAC_PI_4 * (o.x / o.y))
    }
}

/// Inverse of [`sample_uniform_disk_concentric`]: the `u` that maps to the disk point `p`.
pub fn invert_uniform_disk_concentric(p: Vec2) -> Vec2 {
    let r = p.length();
    let mut phi = p.y.atan2(p.x);
    if phi < -FRAC_PI_4 {
        phi += TAU;
    }
    // phi ∈ [-π/4, 7π/4): one branch per wedge of the forward map (r < 0 there means angle + π).
    let k = 4.0 / PI;
    let o = if phi < FRAC_PI_4 {
        Vec2::new(r, r * phi * k)
    } else if phi < 3.0 * FRAC_PI_4 {
        Vec2::new(r * (FRAC_PI_2 - phi) * k, r)
    } else if phi < 5.0 * FRAC_PI_4 {
        Vec2::new(-r, -r * (phi - PI) * k)
    } else {
        Vec2::new(-r * (3.0 * FRAC_PI_2 - phi) * k, -r)
    };
    ((o + Vec2::ONE) * 0.5).clamp(Vec2::ZERO, Vec2::ONE)
}

/// Maps `u` to the unit disk uniformly (pdf `1/π`) in polar form: `r = √u₀`, `φ = 2π u₁`.
/// Distorts strata more than the concentric map but is simpler to invert.
pub fn sample_uniform_disk_polar(u: Vec2) -> Vec2 {
    let r = u.x.sqrt();
    let theta = TAU * u.y;
    r * Vec2::new(theta.cos(), theta.sin())
}

/// Inverse of [`sample_uniform_disk_polar`].
pub fn invert_uniform_disk_polar(p: Vec2) -> Vec2 {
    let mut phi = p.y.atan2(p.x);
    if phi < 0.0 {
        phi += TAU;
    }
    Vec2::new(p.length_squared().min(1.0), (phi / TAU).min(1.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;
    use crate::sampling::testing::check_grid;

    /// Periodic distance for the angular coordinate of the polar map.
    fn wrap_dist(a: f32, b: f32) -> f32 {
        let d = (a - b).abs();
        d.min(1.0 - d)
    }

    /// A uniform point in the unit disk by rejection (independent of the code under test).
    fn random_disk_point(rng: &mut Rng) -> Vec2 {
        loop {
            let p = 2.0 * rng.next_2d() - Vec2::ONE;
            if p.length_squared() < 1.0 {
                return p;
            }
        }
    }

    /// (r², φ/2π) are independent uniforms exactly when the samples are uniform on the disk.
    fn check_uniform(sample: fn(Vec2) -> Vec2, seed: u32) {
        check_grid(200_000, seed, |u| {
            let p = sample(u);
            assert!(p.length_squared() <= 1.0 + 1e-6, "{p} outside the disk");
            Vec2::new(p.length_squared(), p.y.atan2(p.x).rem_euclid(TAU) / TAU)
        });
    }

    #[test]
    fn concentric_is_uniform_on_disk() {
        check_uniform(sample_uniform_disk_concentric, 1);
    }

    #[test]
    fn polar_is_uniform_on_disk() {
        check_uniform(sample_uniform_disk_polar, 2);
    }

    #[test]
    fn concentric_round_trips() {
        let mut rng = Rng::new(3, 0, 0);
        for i in 0..100_000 {
            let u = if i < 5 {
                [
                    Vec2::splat(0.5),
                    Vec2::ZERO,
                    Vec2::new(0.75, 0.75),
                    Vec2::new(0.0, 0.5),
                    Vec2::X,
                ][i]
            } else {
                rng.next_2d()
            };
            // Only f32 rounding in sin/cos/atan2 (a few ulps of 1).
            let back = invert_uniform_disk_concentric(sample_uniform_disk_concentric(u));
            assert!((back - u).abs().max_element() < 2e-6, "{u} -> {back}");
            let p = random_disk_point(&mut rng);
            let q = sample_uniform_disk_concentric(invert_uniform_disk_concentric(p));
            assert!((q - p).length() < 2e-6, "{p} -> {q}");
        }
    }

    #[test]
    fn polar_round_trips() {
        let mut rng = Rng::new(4, 0, 0);
        for _ in 0..100_000 {
            let u = rng.next_2d();
            let back = invert_uniform_disk_polar(sample_uniform_disk_polar(u));
            assert!((back.x - u.x).abs() < 2e-6, "{u} -> {back}");
            // The angle is only defined up to ~ulp/r, so skip it at the very center.
            if u.x > 1e-6 {
                assert!(wrap_dist(back.y, u.y) < 2e-6 / u.x.sqrt(), "{u} -> {back}");
            }
            let p = random_disk_point(&mut rng);
            let q = sample_uniform_disk_polar(invert_uniform_disk_polar(p));
            assert!((q - p).length() < 2e-6, "{p} -> {q}");
        }
    }
}
