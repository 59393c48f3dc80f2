//! A mix of two materials, pbrt-v4's `MixMaterial`: at each shading point exactly one of the two
//! is chosen, the second with probability `weight`, by a deterministic hash of the point, so that
//! everything the integrator asks of the BSDF there (eval, sample, pdf) sees one material. Over
//! the many hits a pixel averages, the choice is a convex combination of the two BSDFs: the mix
//! conserves energy when both do, and its expected image is `(1 − w)·A + w·B`.
//!
//! pbrt-v4 hashes the hit point and `wo`; [`crate::scene::Scene::material_at`] sees the hit but
//! not the ray, so lumis hashes the point and the hit's ray distance `t` (which, with the point,
//! stands for where the ray came from), salted with the mix's own index so that nested mixes
//! choose independently. The choice is `u < w` with `u` on a grid of 2^-24 in [0, 1): the
//! probability of the second material is `w` to within 2^-24, exactly 0 at `w ≤ 0` and 1 at
//! `w ≥ 1`. A mix is resolved before textures, so it holds material indices, not materials.
//!
//! WGSL twin: `materials/mix.wgsl` (the hash bit for bit and the resolve loop of `Scene::resolve`),
//! `gpu/u64.wgsl` (the u64 arithmetic, emulated in u32 pairs).

use crate::sampler::owen;
use crate::textures::{TexPoint, Texture};
use glam::Vec3;

/// A mix of two materials of a scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Mix {
    /// The two materials (indices into the scene's materials); the second is chosen with
    /// probability `weight`.
    pub materials: [u32; 2],
    /// The weight, a scalar in [0, 1] ([`Texture::eval_scalar`]; a constant is grey).
    pub weight: Texture,
}

impl Mix {
    /// The material chosen at a hit: `p` and `t` are the hit's point and ray distance, `salt`
    /// the mix's own index, `at` gives where textures are looked up (called only for a
    /// textured weight).
    #[inline]
    pub fn choose<'a>(&self, p: Vec3, t: f32, salt: u32, at: impl FnOnce() -> TexPoint<'a>) -> u32 {
        let w = match &self.weight {
            Texture::Constant(c) => c.x,
            tex => tex.eval_scalar(at()),
        };
        self.materials[choice(w, hash_unit(p, t, salt))]
    }
}

/// 0 or 1: the second material when `u < w` (so with probability `w` for `u` uniform in
/// [0, 1)); exactly 0 for `w ≤ 0` (or NaN) and 1 for `w ≥ 1`.
#[inline]
pub fn choice(w: f32, u: f32) -> usize {
    usize::from(u < w)
}

/// The golden-ratio constant of SplitMix64: the hash's seed and [`splitmix64`]'s increment
/// (public for the GPU's twin, `materials/mix.wgsl`, whose prelude holds its halves).
pub const GOLDEN: u64 = 0x9e37_79b9_7f4a_7c15;

/// A value in [0, 1) on a grid of 2^-24, a hash of the bits of `p`, `t` and `salt`.
/// WGSL twin: `mix_hash_unit` in `materials/mix.wgsl` (u64 emulated in u32 pairs).
#[inline]
pub fn hash_unit(p: Vec3, t: f32, salt: u32) -> f32 {
    let mut h = GOLDEN ^ salt as u64;
    for word in [p.x.to_bits(), p.y.to_bits(), p.z.to_bits(), t.to_bits()] {
        h = splitmix64(h ^ word as u64);
    }
    (h >> 40) as f32 * (1.0 / (1u32 << 24) as f32)
}

/// One SplitMix64 step: the golden increment, then the 64-bit finaliser (Stafford's "Mix13",
/// the sampler's [`owen::mix64`]): every input bit flips each output bit with probability about
/// ½, so neighbouring floats hash to unrelated values.
#[inline]
fn splitmix64(z: u64) -> u64 {
    owen::mix64(z.wrapping_add(GOLDEN))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    /// How often the second material is chosen at `n` points from `points`, against the
    /// binomial: |k − n·w| ≤ 5.3 standard deviations (two-sided p ≈ 1e-7 per comparison, so a
    /// correct hash fails one of the comparisons below with probability < 1e-5).
    fn check_frequency(what: &str, w: f32, points: impl Iterator<Item = (Vec3, f32)>) {
        let (mut n, mut k) = (0u64, 0u64);
        for (p, t) in points {
            n += 1;
            k += choice(w, hash_unit(p, t, 7)) as u64;
        }
        let (nf, wf) = (n as f64, w as f64);
        let sd = (nf * wf * (1.0 - wf)).sqrt();
        let z = (k as f64 - nf * wf) / sd;
        assert!(
            z.abs() <= 5.3,
            "{what}: w = {w}: {k} of {n} chose the second (expected {:.0} ± {sd:.0}, z = {z:.2})",
            nf * wf
        );
    }

    /// The frequency converges to the weight, at random points (seed 17) and at neighbouring
    /// floats along a line and in `t` alone. Catches a hash that ignores low mantissa bits (every
    /// neighbour would choose alike: k would be 0 or n), a biased comparison (`u ≤ w` on a coarse
    /// grid, a swapped pair: k ≈ n·(1 − w)) and a poor mixer.
    #[test]
    fn choice_frequency_converges_to_the_weight() {
        let n = 200_000;
        for w in [0.1f32, 0.5, 0.73] {
            let mut rng = Rng::new(17, 3, 0);
            let random = (0..n).map(move |_| {
                let p = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 20.0 - 10.0;
                (p, 1.0 + 5.0 * rng.next_f32())
            });
            check_frequency("random points", w, random);
            let base = Vec3::new(0.3, 1.7, -2.25);
            let along_x = (0..n).map(move |i| {
                let x = f32::from_bits(base.x.to_bits() + i);
                (Vec3::new(x, base.y, base.z), 2.0)
            });
            check_frequency("neighbouring floats in x", w, along_x);
            let along_t = (0..n).map(move |i| (base, f32::from_bits(2f32.to_bits() + i)));
            check_frequency("neighbouring t", w, along_t);
        }
    }

    #[test]
    fn the_choice_is_deterministic_exact_at_the_ends_and_salted() {
        let (p, t) = (Vec3::new(0.25, -3.0, 8.5), 4.0);
        let u = hash_unit(p, t, 3);
        assert_eq!(u, hash_unit(p, t, 3), "the same point hashes the same");
        assert!((0.0..1.0).contains(&u));
        let mut rng = Rng::new(5, 1, 0);
        let mut same_salted = 0;
        for _ in 0..10_000 {
            let p = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
            let u = hash_unit(p, 1.0, 0);
            assert_eq!(choice(0.0, u), 0);
            assert_eq!(choice(1.0, u), 1);
            assert_eq!(choice(f32::NAN, u), 0);
            same_salted += (choice(0.5, u) == choice(0.5, hash_unit(p, 1.0, 1))) as u32;
        }
        // Independent salts agree half the time (binomial sd 50; 5 sd).
        assert!((same_salted as i32 - 5000).abs() < 250, "{same_salted}");
        let mix = Mix {
            materials: [4, 9],
            weight: Texture::Constant(Vec3::splat(0.5)),
        };
        let chosen = mix.choose(p, t, 3, || unreachable!("a constant weight needs no uv"));
        assert_eq!(chosen, [4, 9][choice(0.5, u)]);
        assert_eq!(chosen, mix.choose(p, t, 3, || glam::Vec2::ZERO.into()));
    }
}
