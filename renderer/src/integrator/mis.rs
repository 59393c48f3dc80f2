//! Multiple-importance-sampling heuristics (Veach 1997).

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
    /// An infinite `pa` takes all the weight; two zero pdfs give 0.
    #[inline]
    pub fn weight(self, pa: f32, pb: f32) -> f32 {
        if pa.is_infinite() {
            return 1.0;
        }
        let (a, b) = match self {
            Heuristic::Balance => (pa, pb),
            Heuristic::Power => (pa * pa, pb * pb),
        };
        let w = a / (a + b);
        if w.is_finite() {
            w
        } else if pb.is_infinite() {
            0.0
        } else {
            // Both squared pdfs overflowed or underflowed: fall back to the balance form.
            let w = pa / (pa + pb);
            if w.is_finite() { w } else { 0.0 }
        }
    }
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
}
