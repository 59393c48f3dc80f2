//! Counter-based random numbers: every (seed, pixel, sample) triple starts its own stream, so an
//! image is identical for any thread count and any order of work. 32-bit state, so the GPU
//! backend can reproduce it bit for bit.
//! WGSL twin: `rng.wgsl`.

/// PCG hash (Jarzynski & Olano 2020, "Hash Functions for GPU Rendering"): a good 32→32 bit mix.
#[inline]
pub fn pcg_hash(x: u32) -> u32 {
    let state = x.wrapping_mul(747796405).wrapping_add(2891336453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277803737);
    (word >> 22) ^ word
}

/// The uniform [`Rng::next_f32`] makes of 32 random bits: the top 24 as k/2^24, so every uniform
/// the renderer draws is one of the 2^24 values k/2^24, k < 2^24 (exact in f32, never 1.0). Tests
/// that enumerate what a sampler can reach go through this function.
#[inline]
pub fn unit_f32(bits: u32) -> f32 {
    (bits >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// A random stream for one sample of one pixel: a PCG32 (RXS-M-XS) generator whose start state is a
/// hash of (seed, pixel index, sample index).
#[derive(Clone, Debug)]
pub struct Rng {
    state: u32,
}

impl Rng {
    /// The stream of sample `sample` of pixel `pixel` for the given seed.
    pub fn new(seed: u32, pixel: u32, sample: u32) -> Rng {
        let h = pcg_hash(seed ^ pcg_hash(pixel ^ pcg_hash(sample.wrapping_add(0x9e37_79b9))));
        Rng { state: h }
    }

    /// Next 32 random bits.
    #[inline]
    pub fn next_u32(&mut self) -> u32 {
        self.state = self.state.wrapping_mul(747796405).wrapping_add(2891336453);
        let s = self.state;
        let word = ((s >> ((s >> 28) + 4)) ^ s).wrapping_mul(277803737);
        (word >> 22) ^ word
    }

    /// Uniform in [0, 1): 24 random mantissa bits, never 1.0 (see [`unit_f32`]).
    #[inline]
    pub fn next_f32(&mut self) -> f32 {
        unit_f32(self.next_u32())
    }

    /// Two uniforms in [0, 1).
    #[inline]
    pub fn next_2d(&mut self) -> glam::Vec2 {
        let x = self.next_f32();
        glam::Vec2::new(x, self.next_f32())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_mean_and_range() {
        let mut r = Rng::new(7, 11, 13);
        let n = 200_000;
        let mut sum = 0.0f64;
        for _ in 0..n {
            let x = r.next_f32();
            assert!((0.0..1.0).contains(&x));
            sum += x as f64;
        }
        // mean of U(0,1) has std 1/sqrt(12 n) ≈ 6.5e-4; 5 sigma.
        assert!((sum / n as f64 - 0.5).abs() < 3.3e-3);
    }

    #[test]
    fn streams_differ_and_repeat() {
        let a: Vec<u32> = (0..4)
            .map(|_| 0)
            .scan(Rng::new(1, 2, 3), |r, _| Some(r.next_u32()))
            .collect();
        let b: Vec<u32> = (0..4)
            .map(|_| 0)
            .scan(Rng::new(1, 2, 3), |r, _| Some(r.next_u32()))
            .collect();
        let c: Vec<u32> = (0..4)
            .map(|_| 0)
            .scan(Rng::new(1, 2, 4), |r, _| Some(r.next_u32()))
            .collect();
        let d: Vec<u32> = (0..4)
            .map(|_| 0)
            .scan(Rng::new(1, 3, 3), |r, _| Some(r.next_u32()))
            .collect();
        assert_eq!(a, b);
        assert_ne!(a, c);
        assert_ne!(a, d);
    }
}
