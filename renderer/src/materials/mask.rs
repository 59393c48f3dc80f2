//! Alpha masks (Mitsuba's `mask`): a material with an opacity α in [0, 1] (a constant or a
//! scalar texture) is there for a fraction α of the rays that reach it and absent for the rest.
//!
//! Mitsuba makes the mask a BSDF: α times the nested BSDF plus a null lobe of weight 1 − α that
//! continues the ray unchanged, which its path tracer samples like any other lobe (so it counts
//! as a bounce) while its shadow rays stop at the surface. lumis tests the mask where rays meet
//! surfaces instead, pbrt-v4's stochastic alpha test: a hit on a masked primitive is kept with
//! probability α, by a hash of the ray and the hit, in the closest-hit and the any-hit (shadow)
//! traversals alike. Both estimate the same light transport: a fraction 1 − α of the light passes
//! the surface unchanged, α meets its BSDF. They differ only where the path length is bounded
//! (Mitsuba spends a bounce on each pass), so the Mitsuba importer refuses a mask beside a finite
//! `max_depth`. lumis' shadow rays pass the mask too, so a masked leaf casts a leaf's shadow
//! under next-event estimation, not only under BSDF sampling.
//!
//! The decision is a deterministic function of the ray's origin, the hit's ray distance and the
//! primitive: the same candidate hit is judged alike however often the traversal meets it, and a
//! ray never sees a surface it skipped. Over the many rays a pixel averages, the decisions are
//! independent Bernoulli(α) draws, the hash being [`crate::materials::mix`]'s.
//!
//! WGSL twin: `materials/mask.wgsl` (the record in `tables`, the same hash and rule).

use super::mix::hash_unit;
use glam::Vec3;

/// Whether a hit at distance `t` on primitive `prim` along a ray from `o` meets a surface of
/// opacity `alpha`: with probability `alpha` (exactly never at α ≤ 0 and always at α ≥ 1, the
/// hash lying on a grid in [0, 1)).
#[inline]
pub fn kept(alpha: f32, o: Vec3, t: f32, prim: u32) -> bool {
    hash_unit(o, t, prim) < alpha
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    /// |z| of `k` successes in `n` Bernoulli(`p`) draws.
    fn z(k: u64, n: u64, p: f64) -> f64 {
        let n = n as f64;
        ((k as f64 - n * p) / (n * p * (1.0 - p)).sqrt()).abs()
    }

    /// Over rays with random origins and distances the fraction kept is α: |z| ≤ 5.3 (two-sided
    /// p ≈ 1e-7 per α; n = 200,000, seed 2700, fixed before the first run), which detects a
    /// bias of 0.6% absolute at α = ½ (a comparison the wrong way round, `1 − α`, fails by
    /// hundreds of σ); α = 0 and α = 1 are exact.
    #[test]
    fn kept_with_probability_alpha() {
        let mut rng = Rng::new(2700, 0, 0);
        let n = 200_000u64;
        for alpha in [0.0f32, 0.05, 0.5, 0.93, 1.0] {
            let mut k = 0u64;
            for i in 0..n {
                let o = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 10.0;
                let t = rng.next_f32() * 5.0;
                k += kept(alpha, o, t, (i % 7) as u32) as u64;
            }
            match alpha {
                0.0 => assert_eq!(k, 0),
                1.0 => assert_eq!(k, n),
                _ => assert!(z(k, n, alpha as f64) <= 5.3, "α {alpha}: kept {k} of {n}"),
            }
        }
    }

    /// The same candidate hit is judged alike every time; another primitive at the same place
    /// (two masked layers that touch), or the same one at another distance, is an independent
    /// draw: at α = ½ the two agree half the time (|z| ≤ 5.3, n = 100,000, seed 2701). A rule
    /// that ignored the primitive would make them agree always.
    #[test]
    fn one_decision_per_hit_independent_across_primitives() {
        let mut rng = Rng::new(2701, 0, 0);
        let n = 100_000u64;
        let (mut same_prim, mut same_t) = (0u64, 0u64);
        for _ in 0..n {
            let o = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
            let t = rng.next_f32() + 0.5;
            assert_eq!(kept(0.5, o, t, 3), kept(0.5, o, t, 3));
            same_prim += (kept(0.5, o, t, 3) == kept(0.5, o, t, 4)) as u64;
            same_t += (kept(0.5, o, t, 3) == kept(0.5, o, t * 1.001, 3)) as u64;
        }
        for (what, k) in [("primitives", same_prim), ("distances", same_t)] {
            assert!(z(k, n, 0.5) <= 5.3, "two {what} agree {k} of {n} times");
        }
    }
}
