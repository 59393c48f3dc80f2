//! Rays, surface hits and robust ray spawning.
//!
//! Every intersection routine returns a conservative bound on the floating-point error of the hit
//! point (pbrt-v4's `pError`). New rays start just outside that error box, so self-intersection is
//! avoided at every scene scale without a fixed epsilon.
//! WGSL twin: `geometry/ray.wgsl`.

use glam::{DVec3, Vec3};

/// `n·ε / (1 − n·ε)` with ε = 2⁻²⁴: the bound on the relative error of n chained f32 operations.
#[inline]
pub const fn gamma(n: i32) -> f32 {
    let e = f32::EPSILON * 0.5;
    (n as f32 * e) / (1.0 - n as f32 * e)
}

/// A ray `o + t·d` for `t` in `(0, t_max)`. `d` is unit length except for rays made by
/// [`spawn_ray_to`], where `t_max` is then in units of `d`.
#[derive(Clone, Copy, Debug)]
pub struct Ray {
    /// Origin.
    pub o: Vec3,
    /// Direction.
    pub d: Vec3,
    /// Largest parameter that counts as a hit.
    pub t_max: f32,
}

impl Ray {
    /// A ray of unbounded length.
    pub fn new(o: Vec3, d: Vec3) -> Ray {
        Ray {
            o,
            d,
            t_max: f32::INFINITY,
        }
    }

    /// The point at parameter `t`.
    #[inline]
    pub fn at(&self, t: f32) -> Vec3 {
        self.o + t * self.d
    }
}

/// Where a ray hit a surface.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceHit {
    /// Ray parameter of the hit.
    pub t: f32,
    /// Hit point.
    pub p: Vec3,
    /// Conservative absolute error bound of `p`, per axis.
    pub p_error: Vec3,
    /// Unit geometric normal, on the shape's "outside" (the side that emits, for lights).
    pub n: Vec3,
    /// Index of the primitive in the scene's primitive list.
    pub prim: u32,
    /// Barycentrics `(b1, b2)` of a triangle hit (`p = (1−b1−b2)·v0 + b1·v1 + b2·v2`), for
    /// interpolating vertex attributes; zero on disks and spheres.
    pub b: glam::Vec2,
}

/// The next representable f32 above `v`.
#[inline]
pub fn next_float_up(v: f32) -> f32 {
    if v.is_infinite() && v > 0.0 {
        return v;
    }
    let v = if v == -0.0 { 0.0 } else { v };
    let bits = v.to_bits();
    f32::from_bits(if v >= 0.0 { bits + 1 } else { bits - 1 })
}

/// The next representable f32 below `v`.
#[inline]
pub fn next_float_down(v: f32) -> f32 {
    if v.is_infinite() && v < 0.0 {
        return v;
    }
    let v = if v == 0.0 { -0.0 } else { v };
    let bits = v.to_bits();
    f32::from_bits(if v > 0.0 { bits - 1 } else { bits + 1 })
}

/// Whether the ray `o + t·d` crosses the plane through `p0` with normal `n` at some `t > 0`, decided
/// in f64 (exact up to ~1e-16) and only when the origin is clearly off the plane: the origin on
/// one side, the ray heading to the other.
///
/// Intersection routines reject hits closer than their `t` error bound, since such a hit might be
/// the surface the ray just left. This test settles those: rays leaving a surface start on the side
/// they head to ([`offset_ray_origin`]), so it never accepts the surface a ray left, yet it keeps
/// the wall next to a floor's edge, which the error bound alone would lose (a path would escape a
/// closed room through its corners).
pub fn crosses_plane_ahead(o: Vec3, d: Vec3, p0: DVec3, n: DVec3) -> bool {
    let rel = o.as_dvec3() - p0;
    let d = d.as_dvec3();
    let side = rel.dot(n);
    let heading = d.dot(n);
    // Generous bounds on the f64 rounding of both dot products.
    const TOL: f64 = 1e-13;
    let off_plane = side.abs() > TOL * rel.length() * n.length();
    let not_parallel = heading.abs() > TOL * d.length() * n.length();
    off_plane && not_parallel && (side < 0.0) != (heading < 0.0)
}

/// Moves `p` (with error bound `p_error`) along the normal `n` to the side `w` points to, far enough
/// that a ray leaving from the result cannot re-hit the surface `p` lies on (pbrt-v4 `OffsetRayOrigin`).
#[inline(always)]
pub fn offset_ray_origin(p: Vec3, p_error: Vec3, n: Vec3, w: Vec3) -> Vec3 {
    let d = n.abs().dot(p_error);
    let mut offset = d * n;
    if w.dot(n) < 0.0 {
        offset = -offset;
    }
    let po = p + offset;
    // Round away from p so that the offset survives the addition's rounding.
    Vec3::new(
        step_towards(po.x, offset.x),
        step_towards(po.y, offset.y),
        step_towards(po.z, offset.z),
    )
}

/// `v` moved one ulp up when `dir > 0`, down when `dir < 0`, kept when `dir` is ±0:
/// [`next_float_up`] / [`next_float_down`] without their branches on the sign, which are taken at
/// random along a path (the sign follows the surface normal) and mispredict.
#[inline]
fn step_towards(v: f32, dir: f32) -> f32 {
    if v == 0.0 || !v.is_finite() {
        return step_towards_rare(v, dir);
    }
    // For v ≠ 0 the magnitude, hence the bit pattern, grows by one when v and dir share a sign.
    let opposite = (v.to_bits() ^ dir.to_bits()) >> 31;
    let stepped = f32::from_bits(v.to_bits().wrapping_add(1).wrapping_sub(2 * opposite));
    if dir == 0.0 { v } else { stepped }
}

#[cold]
fn step_towards_rare(v: f32, dir: f32) -> f32 {
    if dir > 0.0 {
        next_float_up(v)
    } else if dir < 0.0 {
        next_float_down(v)
    } else {
        v
    }
}

/// A ray leaving surface point `p` in direction `d` (unit).
#[inline]
pub fn spawn_ray(p: Vec3, p_error: Vec3, n: Vec3, d: Vec3) -> Ray {
    Ray::new(offset_ray_origin(p, p_error, n, d), d)
}

/// Relative slack kept at the far end of a shadow ray, in units of its length (pbrt-v4's
/// `ShadowEpsilon`). Both ends are already offset off their surfaces; this only absorbs the rounding
/// of the direction, so it is relative, not a distance.
pub const SHADOW_EPSILON: f32 = 1e-4;

/// A shadow ray from surface point `p_from` to surface point `p_to`, both offset off their surfaces.
/// `t_max` is in units of the (unnormalised) direction, just short of 1.
#[inline]
pub fn spawn_ray_to(
    p_from: Vec3,
    err_from: Vec3,
    n_from: Vec3,
    p_to: Vec3,
    err_to: Vec3,
    n_to: Vec3,
) -> Ray {
    let pf = offset_ray_origin(p_from, err_from, n_from, p_to - p_from);
    let pt = offset_ray_origin(p_to, err_to, n_to, pf - p_to);
    Ray {
        o: pf,
        d: pt - pf,
        t_max: 1.0 - SHADOW_EPSILON,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn next_float_steps_one_ulp() {
        for v in [0.0f32, -0.0, 1.0, -1.0, 1e-30, -1e30, 12345.678] {
            let up = next_float_up(v);
            let down = next_float_down(v);
            assert!(up > v && down < v, "{v}");
            assert!(next_float_down(up) == v || v == 0.0);
        }
    }

    /// The branchless step agrees bit for bit with the branchy one for every sign of both
    /// arguments, zeros, subnormals, the largest finite values and infinities.
    #[test]
    fn step_towards_matches_next_float() {
        let mut values = vec![
            0.0f32,
            -0.0,
            f32::MAX,
            -f32::MAX,
            f32::INFINITY,
            -f32::INFINITY,
        ];
        values.extend([1e-45f32, -1e-45, 1.0, -1.0, 3.5e-39, 7e22, -0.1]);
        let mut rng = crate::rng::Rng::new(5, 0, 0);
        for _ in 0..10_000 {
            values.push(f32::from_bits(rng.next_u32()));
        }
        for &v in values.iter().filter(|v| !v.is_nan()) {
            for dir in [1.0f32, -1.0, 0.0, -0.0, 1e-40, -3e30] {
                let expected = if dir > 0.0 {
                    next_float_up(v)
                } else if dir < 0.0 {
                    next_float_down(v)
                } else {
                    v
                };
                assert_eq!(
                    step_towards(v, dir).to_bits(),
                    expected.to_bits(),
                    "{v:e} {dir:e}"
                );
            }
        }
    }

    #[test]
    fn offset_moves_to_the_side_of_w() {
        let p = Vec3::new(1e5, -3.0, 7e-4);
        let err = Vec3::splat(1e-2);
        let n = Vec3::new(0.0, 1.0, 0.0);
        let up = offset_ray_origin(p, err, n, Vec3::new(0.3, 0.5, 0.0));
        let down = offset_ray_origin(p, err, n, Vec3::new(0.3, -0.5, 0.0));
        assert!(up.y > p.y + 1e-2 * 0.99 && down.y < p.y - 1e-2 * 0.99);
        assert_eq!(up.x, p.x);
    }
}
