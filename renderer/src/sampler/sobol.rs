//! The first two dimensions of the Sobol sequence, all the ZSobol sampler needs: dimension 0 is
//! the van der Corput sequence (the index's bits reversed) and dimension 1 the generator matrix
//! of the primitive polynomial `x + 1` (Pascal's triangle mod 2). Together they form a
//! (0, 2)-sequence: every aligned block of `2^m` consecutive indices puts exactly one point in
//! each elementary interval of area `2^-m`. Values are 32-bit fixed point in `[0, 1)`.
//! WGSL twin: `sampler/sobol.wgsl`.

/// Columns of dimension 1's generator matrix: column `i` is the value of index bit `i`
/// (`v₀ = ½`, `vᵢ = vᵢ₋₁ ⊕ (vᵢ₋₁ >> 1)`, Sobol's direction numbers 1, 3, 5, 15, 17, 51, …).
/// The definition [`sobol_1`] computes faster (its test compares the two).
pub const SOBOL_1_COLUMNS: [u32; 32] = {
    let mut c = [0u32; 32];
    c[0] = 1 << 31;
    let mut i = 1;
    while i < 32 {
        c[i] = c[i - 1] ^ (c[i - 1] >> 1);
        i += 1;
    }
    c
};

/// Sobol dimension 0 (van der Corput) of `index`, 32-bit fixed point.
#[inline]
pub fn sobol_0(index: u32) -> u32 {
    index.reverse_bits()
}

/// Sobol dimension 1 of `index`, 32-bit fixed point: the XOR of the [`SOBOL_1_COLUMNS`] of the
/// index's set bits, in five steps instead of a loop over the bits. Column `j` has value bit
/// `31 − i` set iff `C(j, i)` is odd, i.e. (Lucas) iff the bits of `i` are a subset of those of
/// `j`; so output bit `i` is the XOR of the index bits `j ⊇ i`, the superset (zeta) transform
/// over GF(2), one shift-mask-XOR per bit of the bit position, then reversed into place. The
/// bit loop was a third of the Sobol sampler's time (its branch on each bit is unpredictable).
#[inline]
pub fn sobol_1(index: u32) -> u32 {
    let mut z = index;
    z ^= (z >> 1) & 0x5555_5555;
    z ^= (z >> 2) & 0x3333_3333;
    z ^= (z >> 4) & 0x0f0f_0f0f;
    z ^= (z >> 8) & 0x00ff_00ff;
    z ^= (z >> 16) & 0x0000_ffff;
    z.reverse_bits()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The (0, m, 2)-net property of the unscrambled points: every aligned block of `2^m`
    /// indices (m ≤ 10, three blocks each) has one point in every elementary interval
    /// `2^-a × 2^-(m−a)`. Catches a wrong direction number (tried: `c[i-1] >> 2` fails the direction-number check).
    /// The five-step [`sobol_1`] equals the XOR of the generator matrix's columns (the
    /// definition) on every index with one or two bits set and on a spread of others.
    #[test]
    fn sobol_1_is_the_xor_of_its_columns() {
        let by_columns = |index: u32| {
            (0..32)
                .filter(|&i| index >> i & 1 != 0)
                .fold(0, |v, i| v ^ SOBOL_1_COLUMNS[i])
        };
        let mut indices: Vec<u32> = (0..32)
            .flat_map(|i| (0..32).map(move |j| 1 << i | 1 << j))
            .collect();
        indices.extend((0..1u32 << 16).map(|i| i.wrapping_mul(0x9e37_79b9)));
        indices.extend([0, u32::MAX]);
        for i in indices {
            assert_eq!(sobol_1(i), by_columns(i), "index {i:#x}");
        }
    }

    #[test]
    fn first_two_dimensions_are_a_0_2_sequence() {
        let top: Vec<u32> = SOBOL_1_COLUMNS[..6].iter().map(|c| c >> 26).collect();
        assert_eq!(top, [32, 48, 40, 60, 34, 51]);
        for m in 0..=10u32 {
            for block in [0u32, 1, 37] {
                for a in 0..=m {
                    let mut seen = vec![false; 1 << m];
                    for i in (block << m)..((block + 1) << m) {
                        let (x, y) = (sobol_0(i), sobol_1(i));
                        let cell = if m == 0 {
                            0
                        } else {
                            let cx = if a == 0 { 0 } else { x >> (32 - a) };
                            let cy = if a == m { 0 } else { y >> (32 - (m - a)) };
                            (cx << (m - a)) | cy
                        };
                        assert!(!seen[cell as usize], "m {m} a {a} block {block}");
                        seen[cell as usize] = true;
                    }
                }
            }
        }
    }
}
