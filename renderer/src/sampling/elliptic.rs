//! Carlson's symmetric elliptic integrals `R_F` and `R_J` in f32, by his duplication algorithm
//! (B. C. Carlson 1995, "Numerical computation of real or complex elliptic integrals", Numerical
//! Algorithms 10; DLMF §19.36(i)), for the solid angle and the sampling CDF of spherical ellipses
//! ([`super::spherical_ellipse`]).
//!
//! Why Carlson's forms: Legendre's incomplete integrals of the third kind `Π(n; φ, k)` need
//! special cases by the sign and size of `n` and lose digits near `k → 1`, which is where a disk
//! seen nearly edge-on puts them; `R_F` and `R_J` are symmetric in their arguments, defined for
//! any non-negative ones, and one algorithm computes them to full precision everywhere: each
//! duplication step replaces the arguments by `(x + λ)/4` (`λ = √x√y + √x√z + √y√z`), which
//! leaves the integral unchanged and shrinks the arguments' relative spread 4-fold, until a
//! fifth-order Taylor series about their mean is exact to the requested tolerance. All terms
//! are positive sums, so nothing cancels.
//!
//! The step count is bounded ([`MAX_CARLSON_STEPS`]) so that GPU lanes cannot diverge without
//! bound; the spherical ellipse's arguments take at most 6 (measured in its tests), Carlson's test
//! values with spreads up to 1e8 at most 10.
//! WGSL twin: `sampling/elliptic.wgsl`.

use crate::math::atan2;

/// Relative truncation tolerance `r` of the final series (Carlson's stopping rule: the series'
/// neglected terms are `O(r)` once the arguments' spread is below `(3r)^{1/6}` for `R_F` and
/// `(r/4)^{1/6}` for `R_J`): f32's half ulp, so the series is as exact as the arithmetic.
pub const TOLERANCE: f32 = f32::EPSILON / 2.0;

/// At most this many duplication steps. Each step shrinks the spread 4-fold once the arguments
/// are within a factor of a few of each other, and squares the ratio of the extreme ones towards
/// 1 before that, so 16 steps reach the tolerance from any spread f32 can hold; the spherical
/// ellipse needs at most 10.
pub const MAX_CARLSON_STEPS: usize = 16;

/// `(3r)^{-1/6}` of Carlson's stopping rule for `R_F`, with `r` = [`TOLERANCE`] (checked below).
pub const RF_Q: f32 = 13.322_93;

/// `(r/4)^{-1/6}` of Carlson's stopping rule for `R_J` (checked below).
pub const RJ_Q: f32 = 20.158_737;

/// `R_F(x, y, z) = ½ ∫₀^∞ dt / √((t + x)(t + y)(t + z))` and
/// `R_J(x, y, z, p) = 3/2 ∫₀^∞ dt / ((t + p) √((t + x)(t + y)(t + z)))` for `x, y, z ≥ 0` (at
/// most one zero) and `p > 0`, by one duplication loop, and the number of steps it took.
///
/// The two share their `x, y, z` iterates and `λ` (`R_J` only adds `p` and a sum of `R_C`
/// terms), so the spherical ellipse, which needs both at the same arguments, pays for one loop:
/// four square roots a step instead of seven. The loop runs until both of Carlson's stopping
/// rules hold (`R_J`'s, stricter and including `p`, decides in practice; `R_F` only gains
/// digits from it).
pub fn carlson_rf_rj_steps(x: f32, y: f32, z: f32, p: f32) -> (f32, f32, usize) {
    let af0 = (x + y + z) / 3.0;
    let aj0 = (x + y + z + 2.0 * p) / 5.0;
    let qf = RF_Q * (af0 - x).abs().max((af0 - y).abs()).max((af0 - z).abs());
    let qj = RJ_Q
        * (aj0 - x)
            .abs()
            .max((aj0 - y).abs())
            .max((aj0 - z).abs())
            .max((aj0 - p).abs());
    let delta = (p - x) * (p - y) * (p - z);
    let (mut xm, mut ym, mut zm, mut pm) = (x, y, z, p);
    let (mut af, mut aj) = (af0, aj0);
    // 4^{-m}, exact in f32.
    let mut scale = 1.0f32;
    // Σ 4^{-m} R_C(1, 1 + e_m) / d_m.
    let mut sum = 0.0f32;
    let mut steps = 0;
    while steps < MAX_CARLSON_STEPS && (scale * qf >= af.abs() || scale * qj >= aj.abs()) {
        let (sx, sy, sz, sp) = (xm.sqrt(), ym.sqrt(), zm.sqrt(), pm.sqrt());
        let lambda = sx * (sy + sz) + sy * sz;
        // One division a step: the loop's critical path runs through it.
        let inv_d = 1.0 / ((sp + sx) * (sp + sy) * (sp + sz));
        let e = scale * scale * scale * delta * inv_d * inv_d;
        sum += scale * carlson_rc1(e) * inv_d;
        xm = 0.25 * (xm + lambda);
        ym = 0.25 * (ym + lambda);
        zm = 0.25 * (zm + lambda);
        pm = 0.25 * (pm + lambda);
        af = 0.25 * (af + lambda);
        aj = 0.25 * (aj + lambda);
        scale *= 0.25;
        steps += 1;
    }
    // R_F: deviations from the mean, from the initial ones (exact: A_m − x_m = 4^{-m}(A₀ − x₀)).
    let k = scale / af;
    let (dx, dy) = ((af0 - x) * k, (af0 - y) * k);
    let dz = -(dx + dy);
    let e2 = dx * dy - dz * dz;
    let e3 = dx * dy * dz;
    let rf = (1.0 - e2 * (1.0 / 10.0) + e3 * (1.0 / 14.0) + e2 * e2 * (1.0 / 24.0)
        - e2 * e3 * (3.0 / 44.0))
        / af.sqrt();
    // R_J.
    let k = scale / aj;
    let (dx, dy, dz) = ((aj0 - x) * k, (aj0 - y) * k, (aj0 - z) * k);
    let dp = -0.5 * (dx + dy + dz);
    let xyz = dx * dy * dz;
    let e2 = dx * dy + dx * dz + dy * dz - 3.0 * dp * dp;
    let e3 = xyz + 2.0 * e2 * dp + 4.0 * dp * dp * dp;
    let e4 = (2.0 * xyz + e2 * dp + 3.0 * dp * dp * dp) * dp;
    let e5 = xyz * dp * dp;
    let series = 1.0 - e2 * (3.0 / 14.0) + e3 * (1.0 / 6.0) + e2 * e2 * (9.0 / 88.0)
        - e4 * (3.0 / 22.0)
        - e2 * e3 * (9.0 / 52.0)
        + e5 * (3.0 / 26.0);
    let rj = scale * series / (aj * aj.sqrt()) + 6.0 * sum;
    (rf, rj, steps)
}

/// `(R_F(x, y, z), R_J(x, y, z, p))`: [`carlson_rf_rj_steps`] without the step count.
#[inline]
pub fn carlson_rf_rj(x: f32, y: f32, z: f32, p: f32) -> (f32, f32) {
    let (rf, rj, _) = carlson_rf_rj_steps(x, y, z, p);
    (rf, rj)
}

/// `R_C(1, 1 + e) = ∫₀^∞ dt / (2 (t + 1)^{1/2} (t + 1 + e))` for `e > −1`: `atan(√e)/√e` above
/// zero, `atanh(√−e)/√−e` below, and the series `1 − e/3 + e²/5 − e³/7 + e⁴/9` near it (its
/// neglected term `e⁵/11` is below 3e-8 relative for `|e| < 0.05`), where both closed forms
/// divide rounding by a small `√|e|`.
pub fn carlson_rc1(e: f32) -> f32 {
    if e.abs() < 0.05 {
        1.0 + e * (-1.0 / 3.0 + e * (1.0 / 5.0 + e * (-1.0 / 7.0 + e * (1.0 / 9.0))))
    } else if e > 0.0 {
        let s = e.sqrt();
        atan2(s, 1.0) / s
    } else {
        // atanh s = ½ ln((1 + s)/(1 − s)), s ≥ 0.22 here: the ratio is ≥ 1.5, no cancellation.
        let s = (-e).sqrt();
        0.5 * ((1.0 + s) / (1.0 - s)).ln() / s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Relative error of `got` against `want`.
    fn rel(got: f32, want: f64) -> f64 {
        (got as f64 / want - 1.0).abs()
    }

    /// `R_F` alone: its value does not depend on `p` beyond the extra steps `R_J`'s rule may take.
    fn rf(x: f32, y: f32, z: f32) -> (f32, usize) {
        let (rf, _, steps) = carlson_rf_rj_steps(x, y, z, 1.0);
        (rf, steps)
    }

    #[test]
    fn stopping_constants_match_their_formulas() {
        let r = TOLERANCE as f64;
        assert!(rel(RF_Q, (3.0 * r).powf(-1.0 / 6.0)) < 1e-6);
        assert!(rel(RJ_Q, (0.25 * r).powf(-1.0 / 6.0)) < 1e-6);
    }

    /// Carlson's own test values (Carlson 1995, §3; also DLMF 19.36), to 13 digits, and values
    /// from mpmath 1.3 (`elliprf`, `elliprj` at 30 digits) with the extreme spreads the
    /// spherical ellipse produces: all within 5e-7 relative (a few ulp), in at most 10 steps.
    #[test]
    fn known_values() {
        let rf_values = [
            ((1.0, 2.0, 0.0), 1.311_028_777_146_1),
            ((2.0, 3.0, 4.0), 0.584_082_841_677_15),
            ((0.0, 1e-6, 1.0), 8.294_051_463_615_44),
            ((0.5, 1.0, 1e3), 0.136_192_629_971_424),
        ];
        for ((x, y, z), want) in rf_values {
            let (got, steps) = rf(x, y, z);
            assert!(
                rel(got, want) < 5e-7,
                "R_F({x}, {y}, {z}) = {got} vs {want}"
            );
            assert!(steps <= 10, "{steps} steps");
        }
        let rj_values = [
            ((0.0, 1.0, 2.0, 3.0), 0.776_886_237_785_823),
            ((2.0, 3.0, 4.0, 5.0), 0.142_975_796_671_568),
            ((0.0, 1e-4, 1.0, 1e-6), 443_403.282_939_243_8),
            ((0.0, 1.0, 1.5, 1e-8), 38_472.991_682_912_5),
            ((0.0, 4.0, 3.0, 1e-4), 135.305_167_505_249_8),
            ((1e-3, 2.0, 3.0, 7.0), 0.264_076_926_673_043),
        ];
        for ((x, y, z, p), want) in rj_values {
            let (_, got, steps) = carlson_rf_rj_steps(x, y, z, p);
            assert!(
                rel(got, want) < 5e-7,
                "R_J({x}, {y}, {z}, {p}) = {got} vs {want}"
            );
            assert!(steps <= 10, "{steps} steps");
        }
    }

    /// Closed forms: `R_F(0, y, y) = π/(2√y)`, `R_J(0, y, y, y) = 3π/(4 y^{3/2})`,
    /// `R_F(x, y, y) = R_C(x, y) = atan(√((y − x)/x))/√(y − x)`; homogeneity `R_F(λ·) =
    /// λ^{-1/2} R_F`, `R_J(λ·) = λ^{-3/2} R_J` over 1e-12…1e12.
    #[test]
    fn closed_forms_and_homogeneity() {
        use std::f64::consts::PI;
        for y in [1e-8f32, 0.3, 1.0, 7.0, 1e8] {
            let yd = y as f64;
            let (rf0, rj0) = carlson_rf_rj(0.0, y, y, y);
            assert!(rel(rf0, PI / (2.0 * yd.sqrt())) < 3e-7, "{y}");
            assert!(rel(rj0, 3.0 * PI / (4.0 * yd * yd.sqrt())) < 3e-7, "{y}");
            let x = 0.25 * yd;
            let rc = ((yd - x) / x).sqrt().atan() / (yd - x).sqrt();
            assert!(rel(rf(x as f32, y, y).0, rc) < 3e-7, "{y}");
        }
        let (rf1, rj1) = carlson_rf_rj(0.0, 1.0, 2.0, 3.0);
        for lambda in [1e-12f32, 1e-6, 1e6, 1e12] {
            let l = lambda as f64;
            let (rf, rj) = carlson_rf_rj(0.0, lambda, 2.0 * lambda, 3.0 * lambda);
            assert!(
                (rf as f64 * l.sqrt() / rf1 as f64 - 1.0).abs() < 3e-7,
                "{lambda}"
            );
            assert!(
                (rj as f64 * l * l.sqrt() / rj1 as f64 - 1.0).abs() < 3e-7,
                "{lambda}"
            );
        }
    }

    /// `R_C(1, 1 + e)` is continuous across the series' boundaries and matches its closed forms.
    #[test]
    fn rc_branches_agree() {
        for e in [
            -0.5f64, -0.05, -0.049_999, -1e-4, 0.0, 1e-4, 0.049_999, 0.05, 3.0, 1e6,
        ] {
            let want = if e > 0.0 {
                e.sqrt().atan() / e.sqrt()
            } else if e < 0.0 {
                (-e).sqrt().atanh() / (-e).sqrt()
            } else {
                1.0
            };
            let got = carlson_rc1(e as f32);
            assert!(rel(got, want) < 4e-7, "{e}: {got}");
        }
    }
}
