//! Multiple-importance-sampling heuristics (Veach 1997).
//! WGSL twin: `integrator/mis.wgsl`.

/// Weighting heuristic for two-sample MIS.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Heuristic {
    /// `p_a / (p_a + p_b)`.
    Balance,
    /// `p_a² / (p_a² + p_b²)` (exponent 2).
    #[default]
    Power,
}

impl Heuristic {
    /// Weight of the strategy with pdf `pa` when the other one has pdf `pb`, one sample each.
    /// An infinite `pa` takes all the weight; a zero, negative or NaN `pa`, an infinite or NaN
    /// `pb` give 0.
    ///
    /// Both pdfs are first scaled by the power of two that brings the larger into [2, 4): exact,
    /// and it keeps the squares and the quotient in f32's normal range whatever the pdfs' scale
    /// (solid-angle pdfs reach 1e30). The GPU twin needs this: WGSL bounds `x / y` only for
    /// |y| in [2⁻¹²⁶, 2¹²⁶], and NVIDIA's division returns 0 above it; relying on overflow to
    /// infinity gave weights of 0 instead of 1 there. As a bonus the weight is exactly
    /// invariant under scaling both pdfs by a power of two.
    #[inline]
    pub fn weight(self, pa: f32, pb: f32) -> f32 {
        if pa == f32::INFINITY {
            return 1.0;
        }
        if pa.is_nan() || pa <= 0.0 || pb.is_nan() || pb == f32::INFINITY {
            return 0.0;
        }
        let s = pow2_normalizer(pa.max(pb));
        let (a, b) = (pa * s, pb.max(0.0) * s);
        let (a, b) = match self {
            Heuristic::Balance => (a, b),
            Heuristic::Power => (a * a, b * b),
        };
        a / (a + b)
    }
}

/// The power of two `s` with `m·s` in [2, 4) for a finite positive normal `m` (subnormal `m`
/// are treated as the smallest normal, giving `m·s` < 2). Always a normal f32, so the products
/// by it are exact unless they underflow, which only the smaller pdf can, negligibly.
#[inline]
pub fn pow2_normalizer(m: f32) -> f32 {
    let biased_exponent = ((m.to_bits() >> 23) & 0xff).max(1);
    f32::from_bits((255 - biased_exponent) << 23)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_sum_to_one() {
        for h in [Heuristic::Balance, Heuristic::Power] {
            for (a, b) in [
                (1.0, 1.0),
                (0.1, 30.0),
                (1e30, 1e-30),
                (1e20, 3e20),
                (0.0, 2.0),
            ] {
                let s = h.weight(a, b) + h.weight(b, a);
                assert!((s - 1.0).abs() < 1e-6, "{h:?} {a} {b} -> {s}");
            }
        }
        assert_eq!(Heuristic::Power.weight(f32::INFINITY, 3.0), 1.0);
        assert_eq!(Heuristic::Power.weight(3.0, f32::INFINITY), 0.0);
        assert_eq!(Heuristic::Balance.weight(0.0, 0.0), 0.0);
        assert!((Heuristic::Power.weight(1.0, 2.0) - 0.2).abs() < 1e-7);
    }

    /// Against f64 over pdfs from the smallest normal to f32::MAX, where the squares overflow
    /// and underflow: within 4 ulp of the exact weight, and exactly invariant under scaling both
    /// pdfs by a power of two (what the GPU twin relies on).
    #[test]
    fn weights_are_accurate_at_every_scale() {
        let mut rng = crate::rng::Rng::new(3, 0, 0);
        for _ in 0..100_000 {
            let pa = f32::MIN_POSITIVE * 2f32.powf(253.9 * rng.next_f32());
            let pb = pa * 2f32.powf(60.0 * rng.next_f32() - 30.0);
            if !pb.is_finite() || pb < f32::MIN_POSITIVE {
                continue;
            }
            for (h, k) in [(Heuristic::Balance, 1), (Heuristic::Power, 2)] {
                let w = h.weight(pa, pb);
                let exact = 1.0 / (1.0 + (pb as f64 / pa as f64).powi(k));
                assert!(
                    (w as f64 - exact).abs() <= 4.0 * f32::EPSILON as f64 * exact.max(1e-30),
                    "{h:?} {pa:e} {pb:e}: {w:e} vs {exact:e}"
                );
                for shift in [-20i32, 7] {
                    let f = 2f32.powi(shift);
                    let (sa, sb) = (pa * f, pb * f);
                    if sa.is_finite() && sb.is_finite() && sa.min(sb) >= f32::MIN_POSITIVE {
                        assert_eq!(
                            h.weight(sa, sb).to_bits(),
                            w.to_bits(),
                            "{h:?} {pa:e} {pb:e}"
                        );
                    }
                }
            }
        }
        for m in [f32::MIN_POSITIVE, 1e-30, 0.75, 3.0, 1e30, f32::MAX] {
            let v = m * pow2_normalizer(m);
            assert!((2.0..4.0).contains(&v), "{m:e} -> {v}");
        }
        assert_eq!(Heuristic::Power.weight(f32::MAX, 1.0), 1.0);
        assert_eq!(Heuristic::Power.weight(1.0, f32::MAX), 0.0);
        assert_eq!(Heuristic::Power.weight(f32::NAN, 1.0), 0.0);
        assert_eq!(Heuristic::Power.weight(1.0, f32::NAN), 0.0);
    }
}
