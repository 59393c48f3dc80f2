//! Owen scrambling and the hashes that seed it.
//!
//! [`owen_scramble`] is a nested uniform scramble of 32-bit fixed-point values: whether bit `i`
//! (counted from the most significant) flips depends only on the seed and the bits above it, so
//! it maps every dyadic interval `[k/2^j, (k+1)/2^j)` onto another one of the same size and
//! keeps a (0, m, 2)-net a net. It follows the Laine–Karras construction: reverse the bits, apply
//! a permutation of `u32` in which each output bit depends only on the same and lower input bits
//! (additions and multiplications carry only upwards), reverse back. The mixing constants are
//! Nathan Vegdahl's ("Building a better LK hash", 2021), as pbrt-v4's `FastOwenScrambler` uses.
//! Every step is invertible; [`owen_unscramble`] undoes them in reverse order.
//!
//! [`mix64`] is also the finaliser of the material mixes' SplitMix64 hash
//! ([`crate::materials::mix`]), so the two share one definition on each side.
//! WGSL twin: `sampler/owen.wgsl`, `gpu/u64.wgsl` (the u64 arithmetic, emulated on u32 pairs).

/// [`mix64`]'s first multiplier (public for the GPU's twin, whose prelude holds its halves).
pub const MIX64_M1: u64 = 0xbf58_476d_1ce4_e5b9;
/// [`mix64`]'s second multiplier (public for the GPU's twin).
pub const MIX64_M2: u64 = 0x94d0_49bb_1331_11eb;

/// SplitMix64's finaliser (Stafford's "Mix13"): every input bit affects every
/// output bit, so the sampler's seeds of nearby pixels, samples and dimensions are unrelated.
#[inline]
pub fn mix64(mut v: u64) -> u64 {
    v = (v ^ (v >> 30)).wrapping_mul(MIX64_M1);
    v = (v ^ (v >> 27)).wrapping_mul(MIX64_M2);
    v ^ (v >> 31)
}

/// A 32-bit hash of two 32-bit words and a 64-bit one (the top half of [`mix64`] of them
/// chained).
#[inline]
pub fn hash3(a: u32, b: u32, c: u64) -> u32 {
    (mix64(mix64(((a as u64) << 32) | b as u64) ^ c) >> 32) as u32
}

/// [`hash32`]'s first multiplier (public for the GPU's twin, as the second).
pub const HASH32_M1: u32 = 0x7feb_352d;
/// [`hash32`]'s second multiplier.
pub const HASH32_M2: u32 = 0x846c_a68b;

/// A 32-bit integer hash (Chris Wellons' "lowbias32" from his hash prospector, 2020: two
/// multiplies, low avalanche bias). A bijection of `u32`. The ZSobol sampler's per-digit
/// permutation choice uses it, twelve times per dimension, where two [`mix64`] each (on the GPU,
/// 64-bit arithmetic emulated on `u32` pairs) made Sobol samples much dearer than independent
/// ones (`docs/performance.md`, "Sobol sampler cost").
#[inline]
pub fn hash32(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(HASH32_M1);
    x ^= x >> 15;
    x = x.wrapping_mul(HASH32_M2);
    x ^ (x >> 16)
}

/// First constant of the Laine–Karras-style permutation (even multipliers: `x ^ x·c` is
/// invertible); public, as the next two, for the GPU's twin.
pub const LK_MUL_A: u32 = 0x3d20_adea;
/// Second constant of the Laine–Karras-style permutation.
pub const LK_MUL_B: u32 = 0x0552_6c56;
/// Third constant of the Laine–Karras-style permutation.
pub const LK_MUL_C: u32 = 0x53a2_2864;

/// Nested uniform (Owen) scramble of the 32-bit fixed-point value `v` with `seed`.
#[inline]
pub fn owen_scramble(v: u32, seed: u32) -> u32 {
    let mut x = v.reverse_bits();
    x ^= x.wrapping_mul(LK_MUL_A);
    x = x.wrapping_add(seed);
    x = x.wrapping_mul((seed >> 16) | 1);
    x ^= x.wrapping_mul(LK_MUL_B);
    x ^= x.wrapping_mul(LK_MUL_C);
    x.reverse_bits()
}

/// Inverse of [`owen_scramble`] for the same seed.
pub fn owen_unscramble(v: u32, seed: u32) -> u32 {
    let mut x = v.reverse_bits();
    x = undo_xor_mul(x, LK_MUL_C);
    x = undo_xor_mul(x, LK_MUL_B);
    x = x.wrapping_mul(inverse_odd((seed >> 16) | 1));
    x = x.wrapping_sub(seed);
    x = undo_xor_mul(x, LK_MUL_A);
    x.reverse_bits()
}

/// Inverse of `x ↦ x ⊕ x·c` for even `c`: bit `i` of `x·c` depends only on bits below `i` of `x`,
/// so each round fixes at least one more low bit; 32 rounds recover all of them.
fn undo_xor_mul(y: u32, c: u32) -> u32 {
    debug_assert!(c.is_multiple_of(2));
    let mut x = y;
    for _ in 0..32 {
        x = y ^ x.wrapping_mul(c);
    }
    x
}

/// The inverse of odd `m` modulo 2^32 (Newton's iteration; each step doubles the correct bits).
fn inverse_odd(m: u32) -> u32 {
    let mut inv = m; // correct to 3 bits for odd m
    for _ in 0..5 {
        inv = inv.wrapping_mul(2u32.wrapping_sub(m.wrapping_mul(inv)));
    }
    inv
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Exhaustive on 16 bits: for several seeds, the top 16 bits of the scrambled value depend
    /// only on the top 16 bits of the input (nested: the low bits are zero here), and the 2^16
    /// prefixes map one to one. Catches a lossy step (tried: `x *= seed >> 16` without `| 1`: prefixes
    /// collide for seed 0, and the 32-bit round trip fails) and, by the nesting checks, a step
    /// whose carries would flow downwards in value.
    #[test]
    fn owen_scramble_is_a_nested_bijection_on_16_bits() {
        for seed in [0u32, 1, 0x2_0000, 0xdead_beef, 0x1234_5678] {
            let mut seen = vec![false; 1 << 16];
            for k in 0..1u32 << 16 {
                let s = owen_scramble(k << 16, seed);
                // The same prefix with different low bits maps to the same prefix.
                assert_eq!(owen_scramble((k << 16) | 0xffff, seed) >> 16, s >> 16);
                assert_eq!(owen_scramble((k << 16) | 0x1234, seed) >> 16, s >> 16);
                assert!(
                    !seen[(s >> 16) as usize],
                    "seed {seed:#x}: prefix {k} collides"
                );
                seen[(s >> 16) as usize] = true;
            }
        }
    }

    #[test]
    fn inverse_odd_inverts() {
        for m in [1u32, 3, 0xffff_ffff, 0x1234_5679] {
            assert_eq!(m.wrapping_mul(inverse_odd(m)), 1);
        }
    }

    proptest! {
        /// On 32 bits: the inverse twin undoes the scramble for any value and seed (so it is a
        /// bijection), and distinct values stay distinct.
        #[test]
        fn owen_scramble_is_a_bijection_on_32_bits(v: u32, w: u32, seed: u32) {
            prop_assert_eq!(owen_unscramble(owen_scramble(v, seed), seed), v);
            prop_assert_eq!(owen_scramble(owen_unscramble(v, seed), seed), v);
            if v != w {
                prop_assert_ne!(owen_scramble(v, seed), owen_scramble(w, seed));
            }
        }
    }
}
