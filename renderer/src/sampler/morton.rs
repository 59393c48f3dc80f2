//! Morton (Z-order) codes of 2-D pixel coordinates: the bits of `x` and `y` interleaved, so that
//! pixels close in the image get close codes. The ZSobol sampler ([`super::zsobol`]) gives
//! consecutive blocks of Sobol indices to consecutive Morton codes.
//! WGSL twin: `sampler/morton.wgsl` (the encoding only).

/// Spreads the low 16 bits of `v` to the even bit positions (bit `i` goes to bit `2i`).
#[inline]
pub fn spread_bits(v: u32) -> u32 {
    let mut v = v & 0x0000_ffff;
    v = (v | (v << 8)) & 0x00ff_00ff;
    v = (v | (v << 4)) & 0x0f0f_0f0f;
    v = (v | (v << 2)) & 0x3333_3333;
    (v | (v << 1)) & 0x5555_5555
}

/// Inverse of [`spread_bits`]: gathers the even bits of `v` into its low 16 bits.
#[inline]
pub fn compact_bits(v: u32) -> u32 {
    let mut v = v & 0x5555_5555;
    v = (v | (v >> 1)) & 0x3333_3333;
    v = (v | (v >> 2)) & 0x0f0f_0f0f;
    v = (v | (v >> 4)) & 0x00ff_00ff;
    (v | (v >> 8)) & 0x0000_ffff
}

/// The Morton code of `(x, y)`, `x` in the even bits and `y` in the odd ones; only the low 16
/// bits of each count.
#[inline]
pub fn morton_encode(x: u32, y: u32) -> u32 {
    spread_bits(x) | (spread_bits(y) << 1)
}

/// Inverse of [`morton_encode`]: `(x, y)`.
#[inline]
pub fn morton_decode(code: u32) -> (u32, u32) {
    (compact_bits(code), compact_bits(code >> 1))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Round trip on every 8-bit pair and a spread of 16-bit ones, and the code's bit layout on a
    /// hand-checked value. Catches a wrong mask or shift in either direction (tried: `<< 2` as the
    /// last spread step fails the round trip).
    #[test]
    fn morton_round_trip() {
        for y in 0..256u32 {
            for x in 0..256u32 {
                assert_eq!(morton_decode(morton_encode(x, y)), (x, y));
            }
        }
        for i in 0..10_000u32 {
            let (x, y) = (
                i.wrapping_mul(40_503) & 0xffff,
                i.wrapping_mul(65_521) >> 3 & 0xffff,
            );
            assert_eq!(morton_decode(morton_encode(x, y)), (x, y));
            assert_eq!(
                morton_encode(morton_decode(i * 429_497).0, morton_decode(i * 429_497).1),
                i * 429_497
            );
        }
        // x = 0b11, y = 0b01: bits x0 y0 x1 y1 = 1 1 1 0 → 0b0111.
        assert_eq!(morton_encode(3, 1), 0b0111);
        // Neighbours in a 2×2 block get consecutive codes.
        assert_eq!(
            [(0, 0), (1, 0), (0, 1), (1, 1)].map(|(x, y)| morton_encode(x, y)),
            [0, 1, 2, 3]
        );
    }
}
