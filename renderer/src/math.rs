//! Small shared math: orthonormal frames, safe functions, luminance.
//! WGSL twin: `math.wgsl`.

use glam::Vec3;

/// An orthonormal basis whose `z` axis is a given unit normal; converts between world and local
/// ("shading") coordinates, where BSDFs live with the normal along +z.
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    /// First tangent.
    pub s: Vec3,
    /// Second tangent.
    pub t: Vec3,
    /// The normal.
    pub n: Vec3,
}

impl Frame {
    /// The world axes.
    pub const IDENTITY: Frame = Frame {
        s: Vec3::X,
        t: Vec3::Y,
        n: Vec3::Z,
    };

    /// Builds a frame around the unit vector `n` (Duff et al. 2017, branchless and continuous
    /// except at one sign flip).
    pub fn from_normal(n: Vec3) -> Frame {
        let sign = 1.0f32.copysign(n.z);
        let a = -1.0 / (sign + n.z);
        let b = n.x * n.y * a;
        let s = Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
        let t = Vec3::new(b, sign + n.y * n.y * a, -n.y);
        Frame { s, t, n }
    }

    /// World → local.
    #[inline]
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.s), v.dot(self.t), v.dot(self.n))
    }

    /// Local → world.
    #[inline]
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        self.s * v.x + self.t * v.y + self.n * v.z
    }
}

/// `sqrt(max(x, 0))`: never NaN for slightly negative rounding results.
#[inline]
pub fn safe_sqrt(x: f32) -> f32 {
    x.max(0.0).sqrt()
}

/// `atan2(y, x)` for finite arguments, within 3 ulp of the exact angle (tested below): the
/// ratio of the smaller to the larger magnitude is reduced to `[0, tan(π/8)]` and fed to Cephes'
/// `atanf` polynomial. It has no calls and no unpredictable branches, and runs several times faster
/// than libm's `atan2f`, which matters in solid-angle light sampling (two per spherical triangle).
/// Like libm it returns `±0` or `±π` for `y = ±0` by the sign of `x`, and 0 for `(0, 0)`.
#[inline]
pub fn atan2(y: f32, x: f32) -> f32 {
    use std::f32::consts::{FRAC_PI_2, FRAC_PI_4, PI};
    let (ax, ay) = (x.abs(), y.abs());
    let steep = ay > ax;
    let (num, den) = if steep { (ax, ay) } else { (ay, ax) };
    let z = if den > 0.0 { num / den } else { 0.0 };
    // atan z = π/4 + atan((z − 1)/(z + 1)) above tan(π/8).
    let upper = z > 0.414_213_57;
    let w = if upper { (z - 1.0) / (z + 1.0) } else { z };
    let w2 = w * w;
    let poly = ((8.053_744_5e-2 * w2 - 1.387_768_6e-1) * w2 + 1.997_771_1e-1) * w2 - 3.333_295e-1;
    let mut a = poly * w2 * w + w;
    if upper {
        a += FRAC_PI_4;
    }
    if steep {
        a = FRAC_PI_2 - a;
    }
    if x.is_sign_negative() {
        a = PI - a;
    }
    a.copysign(y)
}

/// Rec. 709 luminance of a linear RGB value.
#[inline]
pub fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

/// Largest component.
#[inline]
pub fn max_component(c: Vec3) -> f32 {
    c.x.max(c.y).max(c.z)
}

/// Mirror reflection of `w` about `n` (both pointing away from the surface).
#[inline]
pub fn reflect(w: Vec3, n: Vec3) -> Vec3 {
    2.0 * w.dot(n) * n - w
}

/// Refraction of `w` (pointing away from the surface) through the interface with normal `n` and
/// relative IOR `eta` = η on the side `n` points away from / η on the side it points to (pbrt-v4
/// `Refract`). If `w` is on the other side of `n`, the interface is seen with 1/η. Returns the
/// transmitted direction (unit if `w` and `n` are) and the relative IOR η_t/η_i actually used, or
/// `None` under total internal reflection.
#[inline]
pub fn refract(w: Vec3, n: Vec3, eta: f32) -> Option<(Vec3, f32)> {
    let mut cos_i = n.dot(w);
    let (mut eta, mut n) = (eta, n);
    if cos_i < 0.0 {
        eta = 1.0 / eta;
        cos_i = -cos_i;
        n = -n;
    }
    let sin2_i = (1.0 - cos_i * cos_i).max(0.0);
    let sin2_t = sin2_i / (eta * eta);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = safe_sqrt(1.0 - sin2_t);
    Some((-w / eta + (cos_i / eta - cos_t) * n, eta))
}

/// `a * b - c * d` without catastrophic cancellation: the products of two f32 are exact in f64, so
/// this rounds once (Kahan's FMA trick gives the same accuracy but needs hardware FMA to be fast).
#[inline]
pub fn difference_of_products(a: f32, b: f32, c: f32, d: f32) -> f32 {
    (a as f64 * b as f64 - c as f64 * d as f64) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Snell's law η_i sinθ_i = η_t sinθ_t, the transmitted side, the reported η, the round trip
    /// back to `w`, and total internal reflection beyond the critical angle.
    #[test]
    fn refract_obeys_snell_and_inverts() {
        for eta in [1.1f32, 1.5, 2.4] {
            for deg in [0.0f32, 10.0, 45.0, 80.0, 89.0] {
                let t = deg.to_radians();
                let w = Vec3::new(t.sin(), 0.0, t.cos());
                let (wt, e) = refract(w, Vec3::Z, eta).unwrap();
                assert_eq!(e, eta);
                assert!(wt.z < 0.0 && (wt.length() - 1.0).abs() < 1e-6);
                let sin_t = (wt.x * wt.x + wt.y * wt.y).sqrt();
                assert!((t.sin() - eta * sin_t).abs() < 1e-6, "{eta} {deg}");
                assert!(wt.x <= 0.0, "the tangential part flips side");
                let (back, e2) = refract(wt, Vec3::Z, eta).unwrap();
                assert!((e2 - 1.0 / eta).abs() < 1e-7 && (back - w).length() < 1e-5);
            }
            let crit = (1.0 / eta).asin();
            let inside = |a: f32| Vec3::new(a.sin(), 0.0, -a.cos());
            assert!(refract(inside(crit + 1e-3), Vec3::Z, eta).is_none());
            assert!(refract(inside(crit - 1e-3), Vec3::Z, eta).is_some());
        }
    }

    #[test]
    fn frame_is_orthonormal_and_inverts() {
        let mut seed = 1u32;
        for i in 0..2000 {
            let mut r = || {
                seed = seed.wrapping_mul(747796405).wrapping_add(2891336453);
                (seed >> 8) as f32 / (1u32 << 24) as f32 * 2.0 - 1.0
            };
            let mut n = Vec3::new(r(), r(), r());
            if i < 4 {
                // exact poles and the sign-flip plane
                n = [Vec3::Z, -Vec3::Z, Vec3::new(1.0, 0.0, -1e-30), Vec3::X][i];
            }
            let n = n.normalize();
            let f = Frame::from_normal(n);
            assert!((f.s.length() - 1.0).abs() < 1e-5, "{n}");
            assert!((f.t.length() - 1.0).abs() < 1e-5);
            assert!(
                f.s.dot(f.t).abs() < 1e-5 && f.s.dot(n).abs() < 1e-5 && f.t.dot(n).abs() < 1e-5
            );
            assert!((f.s.cross(f.t) - n).length() < 1e-4, "right-handed");
            let v = Vec3::new(0.3, -0.5, 0.8);
            assert!((f.to_world(f.to_local(v)) - v).length() < 1e-5);
        }
    }

    /// [`atan2`] against f64 over every octant, ratios from 1e-30 to 1e30 and signed zeros: at
    /// most 3 ulp of the exact angle (the worst seen is 2.9).
    #[test]
    fn atan2_is_within_three_ulp() {
        let ulp = |v: f32| (f32::from_bits(v.abs().to_bits() + 1) - v.abs()) as f64;
        let mut worst = 0.0f64;
        let mut seed = 7u32;
        let mut rnd = || {
            seed = seed.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
            seed
        };
        for i in 0..400_000 {
            let (y, x) = if i < 200_000 {
                // Uniform angles around the circle.
                let t = (i as f64 / 200_000.0 - 0.5) * std::f64::consts::TAU;
                (t.sin() as f32, t.cos() as f32)
            } else {
                // Random magnitudes over 60 decades and random signs.
                let m = |r: u32| 10f32.powf((r % 60_000) as f32 / 1000.0 - 30.0);
                let s = |r: u32| if r & 1 == 0 { 1.0 } else { -1.0 };
                (s(rnd()) * m(rnd()), s(rnd()) * m(rnd()))
            };
            let exact = (y as f64).atan2(x as f64);
            let got = atan2(y, x);
            let err = (got as f64 - exact).abs() / ulp(exact as f32);
            worst = worst.max(err);
            assert!(
                err <= 3.0,
                "atan2({y:e}, {x:e}) = {got:e}, exact {exact:e}: {err} ulp"
            );
        }
        assert!(worst > 0.0);
        for (y, x) in [
            (0.0f32, 1.0f32),
            (-0.0, 1.0),
            (0.0, -1.0),
            (-0.0, -1.0),
            (0.0, 0.0),
            (1.0, 0.0),
            (-1.0, -0.0),
        ] {
            assert_eq!(
                atan2(y, x).to_bits(),
                y.atan2(x).to_bits(),
                "atan2({y}, {x})"
            );
        }
    }

    #[test]
    fn difference_of_products_is_accurate() {
        // 1e8 * 1e8 - (1e8+1)*(1e8-1) = 1 exactly; naive f32 gives 0.
        let a = 1.0e4f32;
        let r = difference_of_products(a, a, a + 1.0, a - 1.0);
        assert_eq!(r, 1.0);
    }
}
