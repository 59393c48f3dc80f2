//! The pinhole camera of the scene format (Mitsuba `look_at` convention: image left→right along
//! `cross(forward, up)`, top→bottom along the projection of `-up`).
//!
//! WGSL twin: `camera.wgsl` (the primary ray).

pub mod filter;

use crate::geometry::Ray;
pub use filter::PixelFilter;
use glam::{Vec2, Vec3};

/// A pinhole camera with a vertical field of view.
#[derive(Clone, Copy, Debug)]
pub struct Camera {
    /// Eye position.
    pub origin: Vec3,
    forward: Vec3,
    right: Vec3,
    up: Vec3,
    tan_x: f32,
    tan_y: f32,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// The pixel filter that places camera samples on the film.
    pub filter: PixelFilter,
}

impl Camera {
    /// Camera at `from` looking at `to`. The scene parser has already rejected `from == to` and an
    /// `up` parallel to the view direction.
    pub fn new(from: Vec3, to: Vec3, up: Vec3, vfov_deg: f32, width: u32, height: u32) -> Camera {
        let forward = (to - from).normalize();
        let right = forward.cross(up).normalize();
        let up = right.cross(forward);
        let tan_y = (vfov_deg.to_radians() * 0.5).tan();
        let tan_x = tan_y * width as f32 / height as f32;
        Camera {
            origin: from,
            forward,
            right,
            up,
            tan_x,
            tan_y,
            width,
            height,
            filter: PixelFilter::Box,
        }
    }

    /// This camera with pixel filter `filter` (a new camera has the box filter).
    pub fn with_filter(mut self, filter: PixelFilter) -> Camera {
        self.filter = filter;
        self
    }

    /// The film position of a camera sample of pixel `(px, py)` from the uniforms `u`
    /// ([`PixelFilter::film_position`]): for the box filter `(px + u.x, py + u.y)`.
    #[inline]
    pub fn film_position(&self, u: Vec2, px: u32, py: u32) -> Vec2 {
        self.filter
            .film_position(u, px, py, self.width, self.height)
    }

    /// The view basis as plain data: `(forward, right, up, tan_x, tan_y)`, the unit axes and the
    /// half-extents of the image plane at distance 1 that [`Camera::ray`] combines (for the GPU).
    pub fn basis(&self) -> (Vec3, Vec3, Vec3, f32, f32) {
        (self.forward, self.right, self.up, self.tan_x, self.tan_y)
    }

    /// The ray through continuous film position `(x, y)` in pixels (0..width, 0..height, y down).
    #[inline]
    pub fn ray(&self, x: f32, y: f32) -> Ray {
        let sx = 2.0 * x / self.width as f32 - 1.0;
        let sy = 1.0 - 2.0 * y / self.height as f32;
        let d = self.forward + (sx * self.tan_x) * self.right + (sy * self.tan_y) * self.up;
        Ray::new(self.origin, d.normalize())
    }

    /// Film position (pixels) that world point `p` projects to, or `None` if it is behind the eye.
    pub fn project(&self, p: Vec3) -> Option<(f32, f32)> {
        let v = p - self.origin;
        let z = v.dot(self.forward);
        if z <= 0.0 {
            return None;
        }
        let sx = v.dot(self.right) / (z * self.tan_x);
        let sy = v.dot(self.up) / (z * self.tan_y);
        Some((
            (sx + 1.0) * 0.5 * self.width as f32,
            (1.0 - sy) * 0.5 * self.height as f32,
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orientation_and_projection_round_trip() {
        let c = Camera::new(
            Vec3::new(0.0, 1.0, -4.5),
            Vec3::new(0.0, 0.35, 0.0),
            Vec3::Y,
            50.0,
            256,
            128,
        );
        // the centre pixel looks at `to`
        let r = c.ray(128.0, 64.0);
        assert!((r.d - (Vec3::new(0.0, 0.35, 0.0) - c.origin).normalize()).length() < 1e-6);
        // left edge of the image is to the left: cross(forward, up) with forward≈+z, up=+y is -x
        let left = c.ray(0.0, 64.0);
        assert!(
            left.d.x > 0.0,
            "Mitsuba look_at: image x runs along cross(forward, up) = -x here"
        );
        // top row looks up
        assert!(c.ray(128.0, 0.0).d.y > r.d.y);
        let p = c.origin + c.ray(37.25, 101.5).d * 3.0;
        let (x, y) = c.project(p).unwrap();
        assert!((x - 37.25).abs() < 1e-3 && (y - 101.5).abs() < 1e-3);
    }
}
