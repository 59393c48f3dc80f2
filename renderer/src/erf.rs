//! The error function's complement and the inverse error function in f32, shared by the gaussian
//! pixel filter (`camera/filter.rs`) and the Beckmann microfacet distribution
//! (`materials/beckmann.rs`); the GPU's have the same coefficients and evaluation order.
//! WGSL twin: `erf.wgsl`.

/// `erfc(x)` to a fractional error below 1.2e-7 (Numerical Recipes' Chebyshev fit `erfcc`).
pub fn erfc(x: f32) -> f32 {
    let z = x.abs();
    let t = 1.0 / (1.0 + 0.5 * z);
    let p = -1.265_512_2
        + t * (1.000_023_7
            + t * (0.374_091_96
                + t * (0.096_784_18
                    + t * (-0.186_288_06
                        + t * (0.278_868_07
                            + t * (-1.135_204
                                + t * (1.488_515_9 + t * (-0.822_152_23 + t * 0.170_872_77))))))));
    let r = t * (-z * z + p).exp();
    if x >= 0.0 { r } else { 2.0 - r }
}

/// `erf(x)` as 1 − erfc(x): absolute error below 2.5e-7, which is all its callers need (they
/// use it where it is a probability, never as a small relative quantity).
#[inline]
pub fn erf(x: f32) -> f32 {
    1.0 - erfc(x)
}

/// The inverse error function on (−1, 1) (Giles 2010, "Approximating the erfinv function", the
/// single-precision fit; relative error a few ulps on top of its 3e-7 fit; ±∞ at ±1). Mitsuba's
/// Beckmann sampler inverts the same way.
pub fn erfinv(x: f32) -> f32 {
    let w = -((1.0 - x) * (1.0 + x)).ln();
    let p = if w < 5.0 {
        let w = w - 2.5;
        let mut p = 2.810_226_4e-8;
        p = 3.432_739_4e-7 + p * w;
        p = -3.523_387_7e-6 + p * w;
        p = -4.391_506_5e-6 + p * w;
        p = 0.000_218_580_87 + p * w;
        p = -0.001_253_725 + p * w;
        p = -0.004_177_681_6 + p * w;
        p = 0.246_640_73 + p * w;
        1.501_409_4 + p * w
    } else {
        let w = w.sqrt() - 3.0;
        let mut p = -0.000_200_214_26;
        p = 0.000_100_950_56 + p * w;
        p = 0.001_349_343_2 + p * w;
        p = -0.003_673_428_4 + p * w;
        p = 0.005_739_507_7 + p * w;
        p = -0.007_622_461_3 + p * w;
        p = 0.009_438_870_5 + p * w;
        p = 1.001_674 + p * w;
        2.832_976_8 + p * w
    };
    p * x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn erfc_matches_known_values() {
        // erfc to 9 digits (Abramowitz & Stegun table 7.1).
        for (x, want) in [
            (0.0f32, 1.0f64),
            (0.5, 0.479_500_122),
            (1.0, 0.157_299_207),
            (2.0, 0.004_677_735),
            (-1.0, 1.842_700_793),
            (3.0, 2.209_049_7e-5),
        ] {
            let got = erfc(x) as f64;
            assert!(
                (got - want).abs() <= 3e-7 * want,
                "erfc({x}) = {got}, want {want}"
            );
        }
    }

    #[test]
    fn erfinv_inverts_erf() {
        // Against libm's f64 erf: |erf(erfinv(x)) − x| in units of the slope, i.e. the error in
        // erfinv itself, relative. 2e-6 leaves room for f32's ln near ±1 (w = −ln(1 − x²) loses
        // digits where 1 − x is a few ulps), where x = 1 − 2⁻²³ still inverts to 1e-6.
        let mut worst = 0.0f64;
        for i in 1..20_000 {
            let x = -1.0 + 2.0 * i as f32 / 20_000.0;
            let y = erfinv(x) as f64;
            let back = libm::erf(y);
            let slope = 2.0 / std::f64::consts::PI.sqrt() * (-y * y).exp();
            let rel = ((back - x as f64) / slope).abs() / y.abs().max(1e-3);
            worst = worst.max(rel);
        }
        assert!(worst < 2e-6, "erfinv's worst relative error {worst}");
        let edge = 1.0 - f32::EPSILON;
        let y = erfinv(edge) as f64;
        assert!((libm::erf(y) - edge as f64).abs() < 1e-7 && y > 3.5, "{y}");
        assert_eq!(erfinv(0.0), 0.0);
        assert_eq!(erfinv(-0.3), -erfinv(0.3));
    }
}
