//! Spheres, with the numerically careful ray intersection of Haines et al., "Precision Improvements
//! for Ray/Sphere Intersection" (Ray Tracing Gems, ch. 7).
//! WGSL twin: `geometry/sphere.wgsl`.

use super::ray::{Ray, gamma};
use crate::math::Frame;
use glam::Vec3;

/// A sphere; its normal points outwards.
#[derive(Clone, Copy, Debug)]
pub struct Sphere {
    /// Centre.
    pub center: Vec3,
    /// Radius.
    pub radius: f32,
    /// Its object frame's z axis, as Mitsuba's `to_world` turns it (unit): texture coordinates
    /// `v = θ/π` from it (`scene/surface.rs`), ∂p/∂u about it. +z unless the scene turns it.
    pub pole: Vec3,
    /// Its object frame's x axis (unit, ⟂ `pole`): `u = φ/2π` from it towards
    /// `pole × u_axis`. +x unless the scene turns it. (Two vectors, not a frame: a `Primitive`
    /// stays 64 bytes.)
    pub u_axis: Vec3,
}

impl Sphere {
    /// A sphere in the world's axes.
    pub fn new(center: Vec3, radius: f32) -> Sphere {
        Sphere {
            center,
            radius,
            pole: Vec3::Z,
            u_axis: Vec3::X,
        }
    }

    /// The object frame (`s` = `u_axis`, `n` = `pole`); the world's axes exactly by default.
    pub fn frame(&self) -> Frame {
        Frame {
            s: self.u_axis,
            t: self.pole.cross(self.u_axis),
            n: self.pole,
        }
    }

    /// Surface area.
    pub fn area(&self) -> f32 {
        4.0 * std::f32::consts::PI * self.radius * self.radius
    }

    /// Nearest ray parameter in `(0, t_max)`, or `None`.
    pub fn intersect(&self, ray: &Ray) -> Option<f32> {
        let (t0, t1, slack) = self.roots(ray)?;
        if t0 > slack && t0 < ray.t_max {
            Some(t0)
        } else if t1 > slack && t1 < ray.t_max {
            Some(t1)
        } else {
            None
        }
    }

    /// Nearest ray parameter in `(after, t_max)` (`after` ≥ 0), or `None`: the far side of the
    /// sphere where a mask let the ray pass its near side ([`crate::materials::mask`]).
    pub fn intersect_beyond(&self, ray: &Ray, after: f32) -> Option<f32> {
        let (t0, t1, slack) = self.roots(ray)?;
        [t0, t1]
            .into_iter()
            .find(|&t| t > slack && t > after && t < ray.t_max)
    }

    /// The two roots along `ray`, in order, and the distance uncertainty of a hit in the ray's
    /// parameter; `None` where the line misses.
    #[inline(always)]
    fn roots(&self, ray: &Ray) -> Option<(f32, f32, f32)> {
        let inv_len = 1.0 / ray.d.length();
        let d = ray.d * inv_len;
        let f = ray.o - self.center;
        let b = -f.dot(d);
        // Distance² from the centre to the line, computed without cancellation.
        let l = f + b * d;
        let (t0, t1) = careful_roots(
            b,
            l.length_squared(),
            f.length_squared(),
            self.radius,
            inv_len,
        )?;
        // Distance uncertainty of a hit, scaled to the ray's parameter.
        let slack = gamma(8) * (f.length() + self.radius) * inv_len;
        Some((t0, t1, slack))
    }

    /// Hit point reprojected onto the sphere, its error bound and outward normal.
    pub fn surface_point(&self, ray: &Ray, t: f32) -> (Vec3, Vec3, Vec3) {
        let local = ray.at(t) - self.center;
        let n = local.normalize_or(Vec3::Z);
        let p = self.center + n * self.radius;
        (
            p,
            gamma(5) * (n * self.radius).abs() + gamma(2) * p.abs(),
            n,
        )
    }
}

/// The roots, in order, of `|f + s·u|² = r²` along a unit direction `u`, given `b = −f·u`, the
/// squared distance `l2 = |f + b·u|²` from the centre to the line (computed so, without
/// cancellation: Haines et al.) and `f2 = |f|²`, each times `inv_len` (a ray parameter whose
/// direction is `u / inv_len`); `None` where the line misses. The sphere's intersection, and the
/// cylinder's in the plane across its axis.
pub(super) fn careful_roots(b: f32, l2: f32, f2: f32, r: f32, inv_len: f32) -> Option<(f32, f32)> {
    let disc = r * r - l2;
    if disc < 0.0 {
        return None;
    }
    let c = f2 - r * r;
    let q = b + b.signum() * disc.sqrt();
    let (mut t0, mut t1) = if q == 0.0 { (0.0, 0.0) } else { (c / q, q) };
    if t0 > t1 {
        std::mem::swap(&mut t0, &mut t1);
    }
    Some((t0 * inv_len, t1 * inv_len))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hits_from_outside_and_inside() {
        let s = Sphere::new(Vec3::new(1.0, 2.0, 3.0), 0.5);
        let t = s
            .intersect(&Ray::new(Vec3::new(1.0, 2.0, 0.0), Vec3::Z))
            .unwrap();
        assert!((t - 2.5).abs() < 1e-5);
        let t = s.intersect(&Ray::new(s.center, Vec3::X)).unwrap();
        assert!((t - 0.5).abs() < 1e-6);
        assert!(
            s.intersect(&Ray::new(Vec3::new(1.6, 2.0, 0.0), Vec3::Z))
                .is_none()
        );
        // far away, tiny sphere: the careful form keeps precision
        let s = Sphere::new(Vec3::new(0.0, 0.0, 1e4), 1e-2);
        let t = s.intersect(&Ray::new(Vec3::ZERO, Vec3::Z)).unwrap();
        assert!((t - (1e4 - 1e-2)).abs() < 2e-3);
    }
}
