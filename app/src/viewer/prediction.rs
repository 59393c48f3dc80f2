//! How long until a pane reaches a target error: an unbiased estimator's relMSE falls as `c/t`
//! (variance over samples, samples in proportion to time), a line of slope −1 on the log-log
//! plot. Fitting that line's offset to the later part of a pane's curve predicts the time and the
//! spp to any target; `1/c`, the inverse of relMSE × time, is the estimator's efficiency, the
//! number that ranks strategies independently of how long they ran.

use super::convergence::CurvePoint;

/// Fewest curve points a fit uses.
pub const MIN_POINTS: usize = 3;
/// Points below this spp are left out: a half-buffer estimate from 2 or 3 samples is itself
/// too noisy, and the first passes carry start-up costs.
pub const MIN_SPP: u32 = 4;

/// `relMSE ≈ c_t / t` and `relMSE ≈ c_spp / spp`, fitted by least squares in log space with the
/// slope fixed at −1 (the mean of `log(relMSE · t)`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InverseFit {
    /// relMSE × seconds.
    pub per_second: f64,
    /// relMSE × spp.
    pub per_spp: f64,
    /// How many curve points went into the fit.
    pub points: usize,
}

impl InverseFit {
    /// Fits the later part of `curve`: the points past an eighth of its render time, from
    /// [`MIN_SPP`] on. `None` with fewer than [`MIN_POINTS`] such points.
    pub fn fit(curve: &[CurvePoint]) -> Option<InverseFit> {
        let end = curve.last()?.seconds;
        let used: Vec<&CurvePoint> = curve
            .iter()
            .filter(|p| {
                p.spp >= MIN_SPP && p.seconds >= end / 8.0 && p.seconds > 0.0 && p.relmse > 0.0
            })
            .collect();
        if used.len() < MIN_POINTS {
            return None;
        }
        let mean_log = |f: &dyn Fn(&CurvePoint) -> f64| {
            used.iter().map(|p| (p.relmse * f(p)).ln()).sum::<f64>() / used.len() as f64
        };
        Some(InverseFit {
            per_second: mean_log(&|p| p.seconds).exp(),
            per_spp: mean_log(&|p| p.spp as f64).exp(),
            points: used.len(),
        })
    }

    /// Predicted render time (s) to reach relMSE `target`.
    pub fn seconds_to(&self, target: f64) -> f64 {
        self.per_second / target
    }

    /// Predicted samples per pixel to reach relMSE `target`.
    pub fn spp_to(&self, target: f64) -> f64 {
        self.per_spp / target
    }

    /// Efficiency, `1/(relMSE · t)` in 1/s.
    pub fn efficiency(&self) -> f64 {
        1.0 / self.per_second
    }
}

/// The first curve point at or below `target`, as measured: `(seconds, spp)`.
pub fn measured_crossing(curve: &[CurvePoint], target: f64) -> Option<(f64, u32)> {
    curve
        .iter()
        .find(|p| p.spp >= MIN_SPP && p.relmse <= target)
        .map(|p| (p.seconds, p.spp))
}

/// One line of the convergence panel for a pane's `curve` and `target`.
pub fn describe(curve: &[CurvePoint], target: f64) -> String {
    if let Some((t, spp)) = measured_crossing(curve, target) {
        return format!("reached relMSE {target:.0e} at {t:.2} s, {spp} spp");
    }
    match InverseFit::fit(curve) {
        Some(f) => format!(
            "relMSE {target:.0e} predicted at {:.3} s, {:.0} spp · efficiency {:.3e}/s",
            f.seconds_to(target),
            f.spp_to(target).ceil(),
            f.efficiency()
        ),
        None => format!("relMSE {target:.0e}: too few points to predict yet"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn curve(c: f64, noise: impl Fn(usize) -> f64) -> Vec<CurvePoint> {
        (1..=40)
            .map(|i| {
                let seconds = 0.1 * i as f64;
                CurvePoint {
                    seconds,
                    spp: 8 * i as u32,
                    relmse: c / seconds * noise(i),
                }
            })
            .collect()
    }

    /// An exact 1/t curve gives back its constant; relMSE × spp too.
    #[test]
    fn exact_inverse_time_is_recovered() {
        let f = InverseFit::fit(&curve(0.5, |_| 1.0)).unwrap();
        assert!((f.per_second - 0.5).abs() < 1e-12, "{f:?}");
        assert!((f.per_spp - 0.5 * 80.0).abs() < 1e-9, "{f:?}");
        assert!((f.seconds_to(1e-3) - 500.0).abs() < 1e-9);
        assert!((f.efficiency() - 2.0).abs() < 1e-12);
        // Points before an eighth of the run (0.5 s of 4 s) are left out.
        assert_eq!(f.points, 36);
    }

    /// Multiplicative noise of ±20 % alternating: the geometric mean cancels it.
    #[test]
    fn symmetric_noise_in_log_space_cancels() {
        let f = InverseFit::fit(&curve(2.0, |i| if i % 2 == 0 { 1.2 } else { 1.0 / 1.2 })).unwrap();
        assert!((f.per_second / 2.0 - 1.0).abs() < 1e-9, "{f:?}");
    }

    #[test]
    fn too_few_points_give_no_fit_and_a_measured_crossing_wins() {
        assert_eq!(InverseFit::fit(&curve(1.0, |_| 1.0)[..2]), None);
        let c = curve(0.5, |_| 1.0);
        // relMSE 0.5/t ≤ 0.25 from t = 2 s (point 20, 160 spp).
        assert_eq!(measured_crossing(&c, 0.25), Some((2.0, 160)));
        assert!(describe(&c, 0.25).starts_with("reached"));
        assert!(describe(&c, 1e-3).contains("predicted at 500.000 s"));
    }
}
