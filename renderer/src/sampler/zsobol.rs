//! The ZSobol sampler (after the design of pbrt-v4's `ZSobolSampler`, Ahmed & Wonka's "Screen-space
//! blue-noise diffusion of Monte Carlo sampling error via hierarchical ordering of pixels"): the
//! pixels of a tile, in Morton order, take consecutive blocks of one Owen-scrambled Sobol
//! sequence, so each pixel's samples are a scrambled (0, 2)-sequence and neighbouring pixels'
//! together form a larger net. Each sampler dimension permutes the sample's Sobol index by its own
//! hashed base-4 digit permutation ([`permute_index`], which keeps every aligned block of
//! `4^k` indices a block) and scrambles the values with its own seed, so the first two Sobol
//! dimensions serve every dimension without correlating them.
//!
//! Index layout (24 bits: [`crate::rng::unit_f32`] keeps the top 24 bits of a value, and index
//! bit `i` of Sobol dimensions 0 and 1 reaches only value bits `31 − i` and below):
//!
//! | bits | what |
//! |---|---|
//! | 23…12 | Morton code of the pixel within its 64×64 tile ([`TILE_LOG2`]) |
//! | 11…0 | sample index within its epoch of 4096 ([`EPOCH_LOG2`]) |
//!
//! Everything else — the seed, the tile's position and the epoch (`sample >> 12`) — goes into the
//! hash that seeds the permutations and scrambles, so tiles and epochs are independent
//! randomisations of the same construction.
//!
//! WGSL twin: `sampler/zsobol.wgsl` (its layout constants and [`PERMUTATION_WORDS`] reach it through the
//! prelude).

use super::morton::morton_encode;
use super::owen::{hash3, hash32, mix64, owen_scramble};
use super::sobol::{sobol_0, sobol_1};
use crate::rng::unit_f32;
use glam::Vec2;

/// log2 of the samples in one epoch: the first 4096 samples of a pixel are one (0, 12, 2)-net
/// per 2-D dimension pair; later epochs are fresh, independently scrambled nets.
pub const EPOCH_LOG2: u32 = 12;
/// log2 of a tile's side in pixels.
pub const TILE_LOG2: u32 = 6;
/// Base-4 digits of the Sobol index.
pub const INDEX_DIGITS: u32 = (EPOCH_LOG2 + 2 * TILE_LOG2) / 2;

/// The 24 permutations of the digits {0, 1, 2, 3}, in lexicographic order.
const PERMUTATIONS: [[u8; 4]; 24] = {
    let mut table = [[0u8; 4]; 24];
    let mut n = 0;
    let mut a = 0;
    while a < 4 {
        let mut b = 0;
        while b < 4 {
            let mut c = 0;
            while c < 4 {
                if a != b && b != c && a != c {
                    table[n] = [a, b, c, 6 - a - b - c];
                    n += 1;
                }
                c += 1;
            }
            b += 1;
        }
        a += 1;
    }
    table
};

/// [`PERMUTATIONS`] for the GPU's twin: permutation `k` as one word, digit `d` mapping to bits
/// `2d` and `2d + 1` (WGSL has no u8 arrays; `sampler/zsobol.wgsl` unpacks the digit it needs).
pub const PERMUTATION_WORDS: [u32; 24] = {
    let mut words = [0u32; 24];
    let mut k = 0;
    while k < 24 {
        let mut d = 0;
        while d < 4 {
            words[k] |= (PERMUTATIONS[k][d] as u32) << (2 * d);
            d += 1;
        }
        k += 1;
    }
    words
};

/// Which of [`PERMUTATIONS`] digit `position` uses, given the digits above it (`higher`, at
/// most 22 bits) and the dimension's `key`: [`hash32`] of the two packed together, xor the key,
/// so each (higher digits, position) pair of a dimension has its own hash input.
#[inline]
fn digit_permutation(higher: u32, position: u32, key: u32) -> &'static [u8; 4] {
    let h = hash32(((higher << 4) | position) ^ key);
    // 24 does not divide 2^32: the bias of `% 24` is below 2^-27, far under any test's reach.
    &PERMUTATIONS[(h % 24) as usize]
}

/// Permutes the low `2·digits` bits of `index` base-4 digit by digit, each digit by a permutation
/// chosen by hashing `key`, its position and the (original) digits above it: a nested random
/// permutation, so indices sharing their top digits still share them (permuted) and an aligned
/// block of `4^k` indices maps onto an aligned block.
#[inline]
pub fn permute_index(index: u32, digits: u32, key: u32) -> u32 {
    let mut out = 0;
    for position in (0..digits).rev() {
        let shift = 2 * position;
        let digit = (index >> shift) & 3;
        let higher = index >> (shift + 2);
        out |= (digit_permutation(higher, position, key)[digit as usize] as u32) << shift;
    }
    out
}

/// Inverse of [`permute_index`]: recovers the digits from the top down, each permutation being
/// chosen by the digits already recovered.
pub fn unpermute_index(permuted: u32, digits: u32, key: u32) -> u32 {
    let mut index = 0;
    for position in (0..digits).rev() {
        let shift = 2 * position;
        let digit = (permuted >> shift) & 3;
        let higher = index >> (shift + 2);
        let perm = digit_permutation(higher, position, key);
        let original = perm.iter().position(|&d| d as u32 == digit).unwrap_or(0) as u32;
        index |= original << shift;
    }
    index
}

/// One sample of one pixel of the ZSobol sampler.
#[derive(Clone, Debug)]
pub struct ZSobolSampler {
    /// Hash of (seed, tile, epoch).
    key: u64,
    /// The unpermuted Sobol index: the pixel's Morton code in its tile, then the sample.
    index: u32,
}

impl ZSobolSampler {
    /// Sample `sample` of pixel `(x, y)` for `seed`.
    pub fn new(seed: u32, x: u32, y: u32, sample: u32) -> ZSobolSampler {
        let mask = (1 << TILE_LOG2) - 1;
        let key = mix64(
            ((seed as u64) << 32 | (sample >> EPOCH_LOG2) as u64)
                ^ mix64(((x >> TILE_LOG2) as u64) << 32 | (y >> TILE_LOG2) as u64),
        );
        let index =
            (morton_encode(x & mask, y & mask) << EPOCH_LOG2) | (sample & ((1 << EPOCH_LOG2) - 1));
        ZSobolSampler { key, index }
    }

    /// The Sobol index dimension `dim` uses: the permutation key is the sample's key xor the
    /// dimension's hash, folded to 32 bits.
    #[inline]
    fn index_for(&self, dim: u32) -> u32 {
        let k = self.key ^ mix64(dim as u64);
        permute_index(self.index, INDEX_DIGITS, (k ^ (k >> 32)) as u32)
    }

    /// The scramble seed of component `component` (0 or 1) of dimension `dim`.
    #[inline]
    fn seed_for(&self, dim: u32, component: u32) -> u32 {
        hash3(dim, component, self.key)
    }

    /// The 1-D sample of dimension `dim`.
    #[inline]
    pub fn get_1d(&self, dim: u32) -> f32 {
        let i = self.index_for(dim);
        unit_f32(owen_scramble(sobol_0(i), self.seed_for(dim, 0)))
    }

    /// The 2-D sample of dimension `dim` (one permuted index, Sobol dimensions 0 and 1).
    #[inline]
    pub fn get_2d(&self, dim: u32) -> Vec2 {
        let i = self.index_for(dim);
        Vec2::new(
            unit_f32(owen_scramble(sobol_0(i), self.seed_for(dim, 0))),
            unit_f32(owen_scramble(sobol_1(i), self.seed_for(dim, 1))),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn permutation_table_is_complete() {
        let mut all: Vec<[u8; 4]> = PERMUTATIONS.to_vec();
        all.sort();
        all.dedup();
        assert_eq!(all.len(), 24);
        assert!(all.iter().all(|p| {
            let mut q = *p;
            q.sort();
            q == [0, 1, 2, 3]
        }));
    }

    /// The GPU's packed table unpacks to the Rust one (so `sampler/zsobol.wgsl`'s digit lookup reads the
    /// same permutations).
    #[test]
    fn packed_permutations_unpack_to_the_table() {
        for (k, p) in PERMUTATIONS.iter().enumerate() {
            for (d, &v) in p.iter().enumerate() {
                assert_eq!((PERMUTATION_WORDS[k] >> (2 * d)) & 3, v as u32, "{k} {d}");
            }
        }
    }

    /// `unpermute_index` undoes `permute_index` on every 12-bit index and a spread of 24-bit
    /// ones, several keys; and the permutation is nested (indices that share their top digits
    /// share them after permuting). Catches twins that disagree on which digits choose a
    /// permutation (tried: `permute_index` choosing by the low digits: the round trip fails).
    #[test]
    fn index_permutation_round_trip_and_nesting() {
        for key in [0u32, 1, 0xdead_beef] {
            for i in 0..1u32 << 12 {
                assert_eq!(unpermute_index(permute_index(i, 6, key), 6, key), i);
            }
            for i in (0..1u32 << 24).step_by(4099) {
                let p = permute_index(i, INDEX_DIGITS, key);
                assert!(p < 1 << 24);
                assert_eq!(unpermute_index(p, INDEX_DIGITS, key), i);
                // Same top 16 bits → same permuted top 16 bits.
                assert_eq!(permute_index(i | 0xff, INDEX_DIGITS, key) >> 8, p >> 8);
            }
        }
    }
}
