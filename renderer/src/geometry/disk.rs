//! Disks: a circle of radius `r` around `center` in the plane with unit normal `n`.
//! WGSL twin: `geometry/disk.wgsl`.

use super::ray::{Ray, crosses_plane_ahead, gamma};
use crate::math::Frame;
use glam::Vec3;

/// A disk.
#[derive(Clone, Copy, Debug)]
pub struct Disk {
    /// Centre.
    pub center: Vec3,
    /// Unit normal (the emitting side for lights).
    pub n: Vec3,
    /// Radius.
    pub radius: f32,
    /// Its object x axis, as Mitsuba's `to_world` turns it (unit, in its plane): texture
    /// coordinates `(r/radius, φ/2π)` with φ from it towards `n × u_axis` (`scene/surface.rs`).
    /// `None`: the tangents of `Frame::from_normal(n)`.
    pub u_axis: Option<Vec3>,
}

impl Disk {
    /// A disk with the default axes.
    pub fn new(center: Vec3, n: Vec3, radius: f32) -> Disk {
        Disk {
            center,
            n,
            radius,
            u_axis: None,
        }
    }

    /// The x and y axes of its texture coordinates.
    pub fn uv_axes(&self) -> [Vec3; 2] {
        match self.u_axis {
            Some(u) => [u, self.n.cross(u)],
            None => {
                let f = Frame::from_normal(self.n);
                [f.s, f.t]
            }
        }
    }

    /// Surface area.
    pub fn area(&self) -> f32 {
        std::f32::consts::PI * self.radius * self.radius
    }

    /// Ray parameter of the hit, or `None`.
    pub fn intersect(&self, ray: &Ray) -> Option<f32> {
        let denom = ray.d.dot(self.n);
        if denom == 0.0 {
            return None;
        }
        let t = (self.center - ray.o).dot(self.n) / denom;
        if !(t > 0.0 && t < ray.t_max) {
            return None;
        }
        let p = ray.at(t);
        if (p - self.center).length_squared() > self.radius * self.radius {
            return None;
        }
        // Reject hits that may lie behind the origin once t's error is accounted for.
        let t_err = gamma(7) * ((self.center - ray.o).abs().dot(self.n.abs()) / denom.abs());
        (t > t_err || crosses_plane_ahead(ray.o, ray.d, self.center.as_dvec3(), self.n.as_dvec3()))
            .then_some(t)
    }

    /// Hit point projected back onto the disk's plane, with its error bound.
    pub fn surface_point(&self, ray: &Ray, t: f32) -> (Vec3, Vec3) {
        let p = ray.at(t);
        let p = p - self.n * (p - self.center).dot(self.n);
        (p, gamma(6) * (self.center.abs() + (p - self.center).abs()))
    }

    /// Axis-aligned bounds (tight: the disk's extent along each axis is `r·sqrt(1 − n_i²)`).
    pub fn bounds(&self) -> (Vec3, Vec3) {
        let e = self.radius * (Vec3::ONE - self.n * self.n).max(Vec3::ZERO).powf(0.5);
        (self.center - e, self.center + e)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hit_and_miss() {
        let d = Disk::new(Vec3::new(0.0, 2.0, 0.0), -Vec3::Y, 1.0);
        let t = d
            .intersect(&Ray::new(Vec3::new(0.5, 0.0, 0.5), Vec3::Y))
            .unwrap();
        assert!((t - 2.0).abs() < 1e-6);
        assert!(
            d.intersect(&Ray::new(Vec3::new(0.8, 0.0, 0.8), Vec3::Y))
                .is_none()
        );
        let (lo, hi) = d.bounds();
        assert!((hi.x - 1.0).abs() < 1e-6 && hi.y - lo.y < 1e-6);
    }
}
