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
//! **Mitsuba's blend** (`"model": "mitsuba"`): Mitsuba 3.9.1's `blendbsdf` samples part i with
//! its probability w_i, as here, but weighs the sample by both parts: `(w_i·f_i + w_j·f_j) /
//! (w_i·p_i + w_j·p_j)`, the sampled part's value and pdf with the other's `eval` and `pdf` at
//! the sampled direction. For continuous lobes that is a one-sample mixture estimator with the
//! mix's expected image; for a delta lobe, whose "value" and "pdf" are a reflectance and a
//! discrete probability, it adds the partner's density to a discrete mass, and the image differs
//! (darker on a smooth conductor blended with a rough lobe, the gallery's `bsdf_blendbsdf.xml`).
//! lumis reproduces that expectation: a mix of model mitsuba chooses as any mix, and only a
//! delta sample of its chosen part is reweighted by [`blend_delta_weight`] with the partner
//! evaluated there; everything else is the mix's (both estimators are unbiased there).
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
    /// Mitsuba's blend (module doc): a delta sample is weighed against the other part.
    pub mitsuba: bool,
}

/// What a mix of model mitsuba chose at a hit: the other part and the chosen part's probability.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Blend {
    /// The material not chosen (a material of its own).
    pub partner: u32,
    /// The probability of the chosen part, w_i.
    pub weight: f32,
}

/// Mitsuba's `blendbsdf` weight of a delta sample of the chosen part (lumis' weight `weight`
/// and discrete probability `pdf`, so its value is `weight·pdf`), chosen with probability
/// `w_self`, with the partner's `eval` (f·cos) and `pdf` at the sampled direction:
/// `(w·weight·pdf + (1 − w)·f) / (w·pdf + (1 − w)·p)`; the sample's own weight where the
/// partner has no density there.
/// WGSL twin: `blend_delta_weight` in `materials/mix.wgsl`.
#[inline]
pub fn blend_delta_weight(weight: Vec3, pdf: f32, w_self: f32, f: Vec3, p: f32) -> Vec3 {
    let w_other = 1.0 - w_self;
    let denominator = w_self * pdf + w_other * p;
    if denominator.is_nan() || denominator <= 0.0 {
        return weight;
    }
    (w_self * weight * pdf + w_other * f) / denominator
}

impl Mix {
    /// The material chosen at a hit: `p` and `t` are the hit's point and ray distance, `salt`
    /// the mix's own index, `at` gives where textures are looked up (called only for a
    /// textured weight).
    #[inline]
    pub fn choose<'a>(&self, p: Vec3, t: f32, salt: u32, at: impl FnOnce() -> TexPoint<'a>) -> u32 {
        self.choose_blend(p, t, salt, at).0
    }

    /// [`Mix::choose`], and for Mitsuba's blend the [`Blend`] of the choice.
    #[inline]
    pub fn choose_blend<'a>(
        &self,
        p: Vec3,
        t: f32,
        salt: u32,
        at: impl FnOnce() -> TexPoint<'a>,
    ) -> (u32, Option<Blend>) {
        let w = match &self.weight {
            Texture::Constant(c) => c.x,
            tex => tex.eval_scalar(at()),
        };
        let k = choice(w, hash_unit(p, t, salt));
        let blend = self.mitsuba.then(|| Blend {
            partner: self.materials[1 - k],
            weight: if k == 1 { w } else { 1.0 - w },
        });
        (self.materials[k], blend)
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
            mitsuba: false,
        };
        let chosen = mix.choose(p, t, 3, || unreachable!("a constant weight needs no uv"));
        assert_eq!(chosen, [4, 9][choice(0.5, u)]);
        assert_eq!(chosen, mix.choose(p, t, 3, || glam::Vec2::ZERO.into()));
        assert_eq!(mix.choose_blend(p, t, 3, || unreachable!()).1, None);
        let blend = Mix {
            weight: Texture::Constant(Vec3::splat(0.3)),
            mitsuba: true,
            ..mix
        };
        let (chosen, b) = blend.choose_blend(p, t, 3, || unreachable!());
        let b = b.expect("a blend");
        assert_eq!(
            [chosen, b.partner],
            if chosen == 9 { [9, 4] } else { [4, 9] }
        );
        assert_eq!(b.weight, if chosen == 9 { 0.3 } else { 0.7 });
    }

    /// Mitsuba's blend weight of a delta sample: its own weight where the partner has no density
    /// there; with a partner, the one-sample mixture of value and density (a smooth conductor's
    /// reflectance 0.9 at probability 1, chosen at w = 0.5, beside a lobe of f·cos 2 and pdf 3:
    /// (0.45 + 1)/(0.5 + 1.5) = 0.725); and the expectation it gives, summed over both choices,
    /// is Mitsuba's: w_i·(w_i·V + w_j·f)/(w_i·P + w_j·p).
    #[test]
    fn blend_delta_weight_is_mitsubas_mixture() {
        let r = Vec3::new(0.9, 0.6, 0.3);
        assert_eq!(blend_delta_weight(r, 1.0, 0.5, Vec3::ZERO, 0.0), r);
        let got = blend_delta_weight(r, 1.0, 0.5, Vec3::splat(2.0), 3.0);
        assert!(
            (got - (0.5 * r + Vec3::splat(1.0)) / 2.0).length() < 1e-6,
            "{got}"
        );
        assert!((got.x - 0.725).abs() < 1e-6);
        // A plastic's specular lobe chosen with probability 0.25 (weight = value / 0.25).
        let v = Vec3::splat(0.04);
        let got = blend_delta_weight(v / 0.25, 0.25, 0.8, Vec3::splat(0.5), 2.0);
        let want = (0.8 * v + 0.2 * Vec3::splat(0.5)) / (0.8 * 0.25 + 0.2 * 2.0);
        assert!((got - want).length() < 1e-6, "{got} vs {want}");
        // A zero denominator (no discrete mass, no density) keeps the sample's weight.
        assert_eq!(blend_delta_weight(r, 0.0, 0.5, Vec3::ONE, 0.0), r);
    }
}
