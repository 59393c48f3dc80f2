//! Gauss–Legendre quadrature: the nodes and weights that integrate polynomials of degree up to
//! 2n − 1 over [−1, 1] exactly. Mitsuba 3 tabulates its rough coats' transmittance with these
//! (`quad::gauss_legendre`), and so does lumis' Mitsuba plastic (`materials/plastic_mitsuba.rs`),
//! to give the same table.

/// The `n` nodes of the n-point Gauss–Legendre rule on [−1, 1], ascending, with their weights.
/// Newton's method on the Legendre polynomial Pₙ from Tricomi's estimate of each root, in f64
/// (converged to a few ulp for any n used here).
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        // The i-th largest root lies near cos(π(i + 3/4)/(n + 1/2)).
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        for _ in 0..100 {
            let (p, d) = legendre(n, x);
            let step = p / d;
            x -= step;
            if step.abs() < 1e-16 {
                break;
            }
        }
        let (_, d) = legendre(n, x);
        out.push((-x, 2.0 / ((1.0 - x * x) * d * d)));
    }
    out
}

/// Pₙ(x) and Pₙ'(x), by the three-term recurrence.
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    if n == 0 {
        return (1.0, 0.0);
    }
    for k in 2..=n {
        let k = k as f64;
        let p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
    }
    let n = n as f64;
    (p1, n * (x * p1 - p0) / (x * x - 1.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Exact for every monomial up to degree 2n − 1 (∫x^k = 2/(k+1) for even k, 0 for odd), not
    /// for degree 2n (small n); weights sum to 2; nodes ascending inside (−1, 1).
    #[test]
    fn integrates_polynomials_of_degree_below_2n_exactly() {
        for n in [1, 2, 5, 32, 128] {
            let rule = gauss_legendre(n);
            assert_eq!(rule.len(), n);
            assert!(rule.windows(2).all(|w| w[0].0 < w[1].0));
            assert!(rule.iter().all(|&(x, w)| x > -1.0 && x < 1.0 && w > 0.0));
            let integral = |k: i32| rule.iter().map(|&(x, w)| w * x.powi(k)).sum::<f64>();
            for k in 0..2 * n as i32 {
                let exact = if k % 2 == 0 {
                    2.0 / (k + 1) as f64
                } else {
                    0.0
                };
                assert!(
                    (integral(k) - exact).abs() < 1e-12,
                    "n {n} x^{k}: {}",
                    integral(k)
                );
            }
            // The error at degree 2n shrinks like 4⁻ⁿ: visible for small n only.
            let k = 2 * n as i32;
            if n <= 5 {
                let error = (integral(k) - 2.0 / (k + 1) as f64).abs();
                assert!(error > 1e-6, "n {n}: degree 2n exact too ({error})");
            }
        }
    }
}
