//! Shared statistical checks for the sampling tests (seeded, deterministic).

use super::{sample_uniform_cone, sample_uniform_sphere, uniform_cone_pdf};
use crate::math::Frame;
use crate::rng::Rng;
use glam::{Vec2, Vec3};

/// Draws `n` samples, maps each to a point of `[0,1]²` with `to_unit` (a pair of analytic CDFs,
/// which are independent uniforms exactly when the sampler is right) and checks that every cell
/// of a 4×4 grid holds 1/16 of them within 5 binomial standard deviations.
pub(crate) fn check_grid(n: u32, seed: u32, mut to_unit: impl FnMut(Vec2) -> Vec2) {
    let mut rng = Rng::new(seed, 0, 0);
    let mut counts = [0u32; 16];
    for _ in 0..n {
        let c = (to_unit(rng.next_2d()) * 4.0)
            .as_uvec2()
            .min(glam::UVec2::splat(3));
        counts[(c.y * 4 + c.x) as usize] += 1;
    }
    check_fractions(&counts, &[1.0 / 16.0; 16]);
}

/// Checks observed counts against expected fractions, each within 5 binomial standard deviations
/// (plus 1e-4 for the rounding of expected values computed in f32).
pub(crate) fn check_fractions(counts: &[u32], expect: &[f32]) {
    let n = counts.iter().sum::<u32>() as f64;
    for (&c, &p) in counts.iter().zip(expect) {
        let p = p as f64;
        let sigma = (p * (1.0 - p) / n).sqrt();
        assert!(
            (c as f64 / n - p).abs() < 5.0 * sigma + 1e-4,
            "{counts:?} vs {expect:?}"
        );
    }
}

/// Brute-force solid angle of a convex planar shape seen from `p`: uniform directions in a cone
/// around its `corners` (the whole sphere when that cone is wider than ~84°), fraction for which
/// `hits(dir)` × the cone's solid angle. Returns (estimate, standard error).
pub(crate) fn brute_force_solid_angle(
    p: Vec3,
    corners: &[Vec3],
    n: u32,
    seed: u32,
    hits: impl Fn(Vec3) -> bool,
) -> (f64, f64) {
    let d: Vec<Vec3> = corners.iter().map(|&x| (x - p).normalize()).collect();
    let axis = d.iter().copied().sum::<Vec3>().normalize();
    // A cone under 90° is convex, so holding the corners it holds the whole shape.
    let cos_max = d.iter().map(|x| x.dot(axis)).fold(1.0f32, f32::min) - 1e-4;
    let frame = Frame::from_normal(axis);
    let wide = cos_max < 0.1;
    let omega = if wide {
        4.0 * std::f64::consts::PI
    } else {
        1.0 / uniform_cone_pdf(cos_max) as f64
    };
    let mut rng = Rng::new(seed, 0, 0);
    let count = (0..n)
        .filter(|_| {
            let u = rng.next_2d();
            hits(if wide {
                sample_uniform_sphere(u)
            } else {
                frame.to_world(sample_uniform_cone(u, cos_max))
            })
        })
        .count();
    let f = count as f64 / n as f64;
    (f * omega, omega * (f * (1.0 - f) / n as f64).sqrt())
}
