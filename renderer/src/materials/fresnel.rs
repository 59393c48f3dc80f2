//! Fresnel reflectance: exact dielectric and conductor Fresnel (real and complex index of
//! refraction) and Schlick's approximation.
//! WGSL twin: `materials/fresnel.wgsl`.

use glam::Vec3;

/// A minimal complex number, just enough for the conductor Fresnel equations.
#[derive(Clone, Copy, Debug)]
struct Complex {
    re: f32,
    im: f32,
}

impl Complex {
    fn new(re: f32, im: f32) -> Complex {
        Complex { re, im }
    }
    fn add(self, o: Complex) -> Complex {
        Complex::new(self.re + o.re, self.im + o.im)
    }
    fn sub(self, o: Complex) -> Complex {
        Complex::new(self.re - o.re, self.im - o.im)
    }
    fn mul(self, o: Complex) -> Complex {
        Complex::new(
            self.re * o.re - self.im * o.im,
            self.re * o.im + self.im * o.re,
        )
    }
    fn scale(self, s: f32) -> Complex {
        Complex::new(self.re * s, self.im * s)
    }
    /// |z|².
    fn norm(self) -> f32 {
        self.re * self.re + self.im * self.im
    }
    fn div(self, o: Complex) -> Complex {
        let s = 1.0 / o.norm();
        Complex::new(
            (self.re * o.re + self.im * o.im) * s,
            (self.im * o.re - self.re * o.im) * s,
        )
    }
    /// Principal square root (pbrt-v4's `pstd::sqrt`, stable for either sign of the real part).
    fn sqrt(self) -> Complex {
        let n = self.norm().sqrt();
        if n == 0.0 {
            return Complex::new(0.0, 0.0);
        }
        let t1 = (0.5 * (n + self.re.abs())).sqrt();
        let t2 = 0.5 * self.im / t1;
        if self.re >= 0.0 {
            Complex::new(t1, t2)
        } else {
            Complex::new(t2.abs(), t1.copysign(self.im))
        }
    }
}

/// Bound on the magnitude of a complex IOR in [`fresnel_complex`], so that |η|² and the Fresnel
/// quotients stay inside f32's range (the WGSL twin cannot fall back to f64).
pub const IOR_LIMIT: f32 = 1e6;

/// Unpolarised Fresnel reflectance of a conductor with complex IOR η + ik, one wavelength
/// (pbrt-v4 `FrComplex`).
///
/// Valid for any η > 0, k ≥ 0 a scene may hold: |η + ik| beyond [`IOR_LIMIT`] is clamped there
/// (the reflectance is then 1 to within ~4/(limit·cosθ), negligible in a render, while |η|²
/// and the quotients below stay finite), and |η + ik| below 1/[`IOR_LIMIT`] reflects fully.
pub fn fresnel_complex(cos_theta_i: f32, eta: f32, k: f32) -> f32 {
    let cos_i = cos_theta_i.clamp(0.0, 1.0);
    let eta = Complex::new(eta.min(IOR_LIMIT), k.min(IOR_LIMIT));
    if eta.norm() < 1.0 / (IOR_LIMIT * IOR_LIMIT) {
        return 1.0; // η → 0: a perfect reflector; avoids dividing by (almost) zero below
    }
    if cos_i == 0.0 {
        return 1.0; // the grazing limit for every η ≠ 1; η = 1, k = 0 would give 0/0
    }
    let sin2_i = 1.0 - cos_i * cos_i;
    let sin2_t = Complex::new(sin2_i, 0.0).div(eta.mul(eta));
    let cos_t = Complex::new(1.0, 0.0).sub(sin2_t).sqrt();
    let ci = Complex::new(cos_i, 0.0);
    let r_parl = eta.scale(cos_i).sub(cos_t).div(eta.scale(cos_i).add(cos_t));
    let r_perp = ci.sub(eta.mul(cos_t)).div(ci.add(eta.mul(cos_t)));
    (0.5 * (r_parl.norm() + r_perp.norm())).clamp(0.0, 1.0)
}

/// Per-channel [`fresnel_complex`] for RGB η and k.
pub fn fresnel_conductor(cos_theta_i: f32, eta: Vec3, k: Vec3) -> Vec3 {
    Vec3::new(
        fresnel_complex(cos_theta_i, eta.x, k.x),
        fresnel_complex(cos_theta_i, eta.y, k.y),
        fresnel_complex(cos_theta_i, eta.z, k.z),
    )
}

/// Unpolarised Fresnel reflectance of a dielectric interface (pbrt-v4 `FrDielectric`).
///
/// `cos_theta_i` is the cosine of the incident direction with the normal of the side of index 1;
/// `eta` is the relative IOR η_inside/η_outside. A negative cosine means the direction is inside:
/// then the interface is seen with 1/η. Total internal reflection gives 1.
#[inline]
pub fn fresnel_dielectric(cos_theta_i: f32, eta: f32) -> f32 {
    let mut cos_i = cos_theta_i.clamp(-1.0, 1.0);
    let mut eta = eta;
    if cos_i < 0.0 {
        eta = 1.0 / eta;
        cos_i = -cos_i;
    }
    let sin2_i = 1.0 - cos_i * cos_i;
    let sin2_t = sin2_i / (eta * eta);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = crate::math::safe_sqrt(1.0 - sin2_t);
    let r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    let r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    (0.5 * (r_parl * r_parl + r_perp * r_perp)).clamp(0.0, 1.0)
}

/// [`fresnel_dielectric`] of a refraction whose two cosines are both known: `cos_out` of the
/// direction outside (index 1) and `cos_in` of the one inside (index `eta`), both ≥ 0.
///
/// The same value as `fresnel_dielectric(cos_out, eta)` when `cos_in` is the Snell cosine, but
/// symmetric in the pair: near the critical angle, recomputing one cosine from the other as
/// √(1 − sin²) cancels, and the two directions of a refraction would see different Fresnel terms.
#[inline]
pub fn fresnel_dielectric_pair(cos_out: f32, cos_in: f32, eta: f32) -> f32 {
    let r_parl = (eta * cos_out - cos_in) / (eta * cos_out + cos_in);
    let r_perp = (cos_out - eta * cos_in) / (cos_out + eta * cos_in);
    let f = 0.5 * (r_parl * r_parl + r_perp * r_perp);
    if f.is_finite() {
        f.clamp(0.0, 1.0)
    } else {
        1.0
    }
}

/// Schlick's approximation F0 + (1 − F0)(1 − cosθ)⁵, scalar F0.
#[inline]
pub fn fresnel_schlick(f0: f32, cos_theta: f32) -> f32 {
    let m = 1.0 - cos_theta.clamp(0.0, 1.0);
    let m2 = m * m;
    f0 + (1.0 - f0) * (m2 * m2 * m)
}

/// Schlick's approximation with an RGB F0.
#[inline]
pub fn fresnel_schlick_rgb(f0: Vec3, cos_theta: f32) -> Vec3 {
    let m = 1.0 - cos_theta.clamp(0.0, 1.0);
    let m2 = m * m;
    f0 + (Vec3::ONE - f0) * (m2 * m2 * m)
}

/// Normal-incidence reflectance of a dielectric interface with relative IOR `ior`:
/// ((ior − 1)/(ior + 1))².
#[inline]
pub fn schlick_f0_from_ior(ior: f32) -> f32 {
    let r = (ior - 1.0) / (ior + 1.0);
    r * r
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every η > 0, k ≥ 0 an f32 scene can hold gives a reflectance in [0, 1], and huge or tiny
    /// |η + ik| reflect (almost) fully away from grazing. Found by the scene-mutation property test: η = 2e19
    /// overflowed |η|² and gave NaN.
    #[test]
    fn complex_fresnel_is_finite_for_extreme_iors() {
        let values = [
            0.0,
            1e-45,
            1e-30,
            1e-20,
            1e-7,
            1e-3,
            0.2,
            1.0,
            1.5,
            3.9,
            1e3,
            1e6,
            1e7,
            2e19,
            1e30,
            f32::MAX,
        ];
        for &eta in &values[1..] {
            for &k in &values {
                for c in [0.0, 1e-6, 0.1, 0.5, 0.9, 1.0] {
                    let f = fresnel_complex(c, eta, k);
                    assert!((0.0..=1.0).contains(&f), "F({c}, {eta}, {k}) = {f}");
                    if c >= 0.1 && (eta.max(k) >= 1e7 || eta.max(k) <= 1e-20) {
                        assert!(f > 0.999, "F({c}, {eta}, {k}) = {f}");
                    }
                }
            }
        }
    }

    /// pbrt-v3's real-arithmetic `FrConductor` in f64: an independent reference.
    fn reference(cos_i: f64, eta: f64, k: f64) -> f64 {
        let c2 = cos_i * cos_i;
        let s2 = 1.0 - c2;
        let (e2, k2) = (eta * eta, k * k);
        let t0 = e2 - k2 - s2;
        let a2b2 = (t0 * t0 + 4.0 * e2 * k2).sqrt();
        let t1 = a2b2 + c2;
        let a = (0.5 * (a2b2 + t0)).sqrt();
        let t2 = 2.0 * cos_i * a;
        let rs = (t1 - t2) / (t1 + t2);
        let t3 = c2 * a2b2 + s2 * s2;
        let t4 = t2 * s2;
        let rp = rs * (t3 - t4) / (t3 + t4);
        0.5 * (rp + rs)
    }

    // (η, k) of gold, copper, aluminium (RGB-ish) and two dielectric-like cases.
    const CASES: [(f32, f32); 6] = [
        (0.143, 3.98),
        (0.2, 2.58),
        (1.3, 7.5),
        (1.5, 0.0),
        (0.05, 0.0),
        (2.5, 0.3),
    ];

    #[test]
    fn conductor_normal_incidence() {
        for (eta, k) in CASES {
            let expect = ((eta - 1.0).powi(2) + k * k) / ((eta + 1.0).powi(2) + k * k);
            let f = fresnel_complex(1.0, eta, k);
            assert!((f - expect).abs() < 1e-5, "{eta} {k}: {f} vs {expect}");
        }
        let v = fresnel_conductor(1.0, Vec3::new(0.2, 0.9, 1.1), Vec3::new(3.9, 2.4, 2.2));
        assert!((v.y - fresnel_complex(1.0, 0.9, 2.4)).abs() < 1e-7);
    }

    #[test]
    fn conductor_matches_reference_and_reaches_one_at_grazing() {
        for (eta, k) in CASES {
            for i in 0..=100 {
                let c = i as f32 / 100.0;
                let f = fresnel_complex(c, eta, k);
                let r = reference(c as f64, eta as f64, k as f64);
                // f32 complex arithmetic vs f64: 1e-4 absolute is ample.
                assert!((f as f64 - r).abs() < 1e-4, "{eta} {k} cos {c}: {f} vs {r}");
            }
            assert!((fresnel_complex(0.0, eta, k) - 1.0).abs() < 1e-6);
            assert!(fresnel_complex(1e-4, eta, k) > 0.99);
        }
        assert_eq!(fresnel_complex(0.5, 0.0, 0.0), 1.0);
    }

    #[test]
    fn schlick_basics() {
        let f0 = schlick_f0_from_ior(1.5);
        assert!((f0 - 0.04).abs() < 1e-7);
        assert_eq!(schlick_f0_from_ior(1.0), 0.0);
        assert_eq!(fresnel_schlick(f0, 1.0), f0);
        assert_eq!(fresnel_schlick(f0, 0.0), 1.0);
        assert_eq!(fresnel_schlick(f0, -0.3), 1.0);
        let mut prev = 1.0;
        for i in 1..=50 {
            let f = fresnel_schlick(f0, i as f32 / 50.0);
            assert!(f <= prev && f >= f0);
            prev = f;
        }
        let rgb = fresnel_schlick_rgb(Vec3::new(0.04, 0.5, 1.0), 0.3);
        assert!((rgb.x - fresnel_schlick(0.04, 0.3)).abs() < 1e-7 && rgb.z == 1.0);
    }

    /// Closed forms: normal incidence ((η−1)/(η+1))², Brewster's angle (p-polarised part 0, so
    /// F = r_s²/2), total internal reflection beyond the critical angle, and the inside view
    /// equals the outside view with 1/η.
    #[test]
    fn dielectric_fresnel_closed_forms() {
        for eta in [1.1f32, 1.5, 2.4, 0.7] {
            let f0 = ((eta - 1.0) / (eta + 1.0)).powi(2);
            assert!((fresnel_dielectric(1.0, eta) - f0).abs() < 1e-6, "{eta}");
            assert!((fresnel_dielectric(-1.0, eta) - f0).abs() < 1e-6, "{eta}");
            let tb = eta.atan();
            let (ci, si) = (tb.cos(), tb.sin());
            let ct = (1.0 - si * si / (eta * eta)).sqrt();
            let rs = (ci - eta * ct) / (ci + eta * ct);
            assert!(
                (fresnel_dielectric(ci, eta) - 0.5 * rs * rs).abs() < 1e-6,
                "{eta}"
            );
            for c in [0.05f32, 0.3, 0.7, 0.99] {
                assert_eq!(
                    fresnel_dielectric(-c, eta),
                    fresnel_dielectric(c, 1.0 / eta)
                );
            }
        }
        // With the Snell cosine, the pair form is the same function, from either side (away from
        // the critical angle, where recomputing the outside cosine from the inside one cancels).
        for c in [0.01f32, 0.3, 0.7, 1.0] {
            let cos_in = (1.0 - (1.0 - c * c) / 2.25).sqrt();
            let (a, b) = (
                fresnel_dielectric(c, 1.5),
                fresnel_dielectric_pair(c, cos_in, 1.5),
            );
            assert!((a - b).abs() < 1e-6, "{c}: {a} {b}");
            if c >= 0.3 {
                assert!((fresnel_dielectric(-cos_in, 1.5) - b).abs() < 1e-5, "{c}");
            }
        }
        // Inside glass of η = 1.5 the critical angle is asin(1/1.5) ≈ 41.8°.
        let crit = (1.0f32 / 1.5).asin();
        assert_eq!(fresnel_dielectric(-(crit + 1e-3).cos(), 1.5), 1.0);
        assert!(fresnel_dielectric(-(crit - 1e-2).cos(), 1.5) < 1.0);
        assert_eq!(fresnel_dielectric(0.0, 1.5), 1.0);
        // Reflectance rises monotonically to 1 at grazing from outside.
        let mut prev = 0.0;
        for i in (0..=100).rev() {
            let f = fresnel_dielectric(i as f32 / 100.0, 1.5);
            assert!(f >= prev - 1e-7, "{i}");
            prev = f;
        }
    }
}
