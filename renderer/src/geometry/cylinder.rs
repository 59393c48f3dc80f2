//! Cylinders as Mitsuba 3.9.1's `cylinder` (`src/shapes/cylinder.cpp`): the open tube of radius
//! `r` around the segment `p0 → p0 + axis`, without end caps, its normal pointing away from the
//! axis (towards it when flipped). Its texture coordinates are Mitsuba's, `u = φ/2π` measured
//! from `u_axis` towards `axis × u_axis`, `v` the fraction of the way from `p0` along the axis.
//! WGSL twin: `geometry/cylinder.wgsl`.

use super::ray::{Ray, gamma};
use super::sphere::careful_roots;
use glam::{Vec2, Vec3};
use std::f32::consts::TAU;

/// A cylinder.
#[derive(Clone, Copy, Debug)]
pub struct Cylinder {
    /// Centre of the base circle (`v = 0`).
    pub p0: Vec3,
    /// From the base centre to the top centre (`v = 1`); its length is the height.
    pub axis: Vec3,
    /// Unit vector perpendicular to `axis` where `u = 0`.
    pub u_axis: Vec3,
    /// Radius, > 0.
    pub radius: f32,
    /// Whether the normal points towards the axis (Mitsuba's `flip_normals`).
    pub flip: bool,
}

impl Cylinder {
    /// Surface area (no caps).
    pub fn area(&self) -> f32 {
        TAU * self.radius * self.axis.length()
    }

    /// The unit axis and the frame's second tangent `axis × u_axis`.
    fn frame(&self) -> (Vec3, Vec3) {
        let z = self.axis.normalize();
        (z, z.cross(self.u_axis))
    }

    /// Nearest ray parameter in `(0, t_max)` whose point lies between the end circles, or
    /// `None`. A ray that meets the tube beyond an end first may still hit its inside.
    pub fn intersect(&self, ray: &Ray) -> Option<f32> {
        self.intersect_beyond(ray, 0.0)
    }

    /// [`Cylinder::intersect`] in `(after, t_max)` (`after` ≥ 0): the far wall where a mask let
    /// the ray pass the near one ([`crate::materials::mask`]).
    #[inline]
    pub fn intersect_beyond(&self, ray: &Ray, after: f32) -> Option<f32> {
        let (z, y) = self.frame();
        let f = ray.o - self.p0;
        // The problem in the plane perpendicular to the axis, solved as the sphere's (Haines
        // et al.): along the unit direction of the projected ray, without cancellation.
        let o2 = Vec2::new(f.dot(self.u_axis), f.dot(y));
        let d2 = Vec2::new(ray.d.dot(self.u_axis), ray.d.dot(y));
        let len2 = d2.length();
        if len2 == 0.0 {
            // Parallel to the axis: inside or outside the tube, never on it.
            return None;
        }
        let inv_len = 1.0 / len2;
        let u = d2 * inv_len;
        let b = -o2.dot(u);
        let l = o2 + b * u;
        let (t0, t1) = careful_roots(
            b,
            l.length_squared(),
            o2.length_squared(),
            self.radius,
            inv_len,
        )?;
        // Distance uncertainty of a hit (the projection's rounding included), in the ray's
        // parameter.
        let slack = gamma(8) * (f.length() + self.radius) * inv_len;
        let (oz, dz, h) = (f.dot(z), ray.d.dot(z), self.axis.length());
        let on_tube = |t: f32| {
            let zt = oz + t * dz;
            t > slack && t > after && t < ray.t_max && (0.0..=h).contains(&zt)
        };
        if on_tube(t0) {
            Some(t0)
        } else if on_tube(t1) {
            Some(t1)
        } else {
            None
        }
    }

    /// Hit point reprojected onto the tube, its error bound and its normal (outward unless
    /// flipped).
    pub fn surface_point(&self, ray: &Ray, t: f32) -> (Vec3, Vec3, Vec3) {
        let (z, _) = self.frame();
        let rel = ray.at(t) - self.p0;
        let along = z * rel.dot(z);
        let out = (rel - along).normalize_or(self.u_axis);
        let p = self.p0 + along + out * self.radius;
        let p_error = gamma(6) * (self.p0.abs() + along.abs() + (out * self.radius).abs());
        (p, p_error, if self.flip { -out } else { out })
    }

    /// Mitsuba's texture coordinates of the point `p` on the tube.
    pub fn uv(&self, p: Vec3) -> Vec2 {
        let (z, y) = self.frame();
        let rel = p - self.p0;
        let phi = crate::math::atan2(rel.dot(y), rel.dot(self.u_axis));
        let u = if phi < 0.0 { phi + TAU } else { phi } / TAU;
        Vec2::new(u, rel.dot(z) / self.axis.length())
    }

    /// ∂p/∂u at `p` (not normalised): the direction of growing φ, whatever the flip (Mitsuba
    /// flips the normal only).
    pub fn dp_du(&self, p: Vec3) -> Vec3 {
        self.axis.cross(p - self.p0)
    }

    /// Axis-aligned bounds: the end circles' (each extends `r·sqrt(1 − ẑ_i²)` along axis `i`).
    pub fn bounds(&self) -> (Vec3, Vec3) {
        let z = self.axis.normalize();
        let e = self.radius * (Vec3::ONE - z * z).max(Vec3::ZERO).powf(0.5);
        let p1 = self.p0 + self.axis;
        (self.p0.min(p1) - e, self.p0.max(p1) + e)
    }
}

#[cfg(test)]
#[path = "cylinder_tests.rs"]
mod tests;
