//! The camera of the scene format (Mitsuba `look_at` convention: image left→right along
//! `cross(forward, up)`, top→bottom along the projection of `-up`), in Mitsuba's three
//! projections: the pinhole (`perspective`), the thin lens (`thinlens`: depth of field) and the
//! parallel `orthographic` view.
//!
//! **Thin lens** (Mitsuba's `thinlens.cpp`): the film point fixes a point on the plane of focus,
//! at perpendicular distance `focus_distance` along the chief ray (the pinhole's ray through the
//! lens centre); the ray starts at a point uniform on the lens disk of radius `aperture_radius`
//! (concentric mapping) and passes through that focus point. Points on the plane of focus are
//! sharp, others blur into a disk ∝ the aperture. A uniform lens sample keeps every sample's
//! weight 1: the image is the average over the lens of pinhole images aimed at the same focus
//! points, which is Mitsuba's estimator (its importance is constant over the lens too).
//!
//! **Orthographic** (Mitsuba's `orthographic.cpp`): parallel rays along `forward` from the plane
//! through `origin`, the film spanning `2·half_x × 2·half_y` world units.
//!
//! The lens's 2-D sample is the sampler's [`Sampler::lens_2d`], drawn only by the thin lens, so
//! that pinhole and orthographic renders draw exactly what they drew before lenses existed.
//!
//! WGSL twin: `camera.wgsl` (the primary ray).

pub mod filter;

use crate::geometry::Ray;
use crate::sampler::Sampler;
use crate::sampling::disk::sample_uniform_disk_concentric;
pub use filter::PixelFilter;
use glam::{Vec2, Vec3};

/// How film positions become rays.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// A pinhole at `origin` (Mitsuba `perspective`).
    Perspective,
    /// A thin lens centred on `origin` (Mitsuba `thinlens`).
    ThinLens {
        /// Radius of the lens disk in world units (≥ 0; 0 is the pinhole).
        aperture_radius: f32,
        /// Distance from the lens to the plane in focus, along `forward` (> 0).
        focus_distance: f32,
    },
    /// Parallel rays along `forward` (Mitsuba `orthographic`).
    Orthographic,
}

/// A camera: a view frame, a projection and a film.
#[derive(Clone, Copy, Debug)]
pub struct Camera {
    /// Eye position (the lens centre; the centre of an orthographic camera's film plane).
    pub origin: Vec3,
    forward: Vec3,
    right: Vec3,
    up: Vec3,
    /// Half-extents of the film: on the image plane at distance 1 (the tangents of the half
    /// fields of view) for a perspective or thin-lens camera, in world units for an orthographic.
    half_x: f32,
    half_y: f32,
    /// How film positions become rays.
    pub projection: Projection,
    /// Mitsuba's principal point offset in pixels: the film position `(x, y)` is projected as
    /// `(x + shift.x, y + shift.y)` of the centred camera (0 by default).
    shift: Vec2,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// The pixel filter that places camera samples on the film.
    pub filter: PixelFilter,
}

impl Camera {
    /// Pinhole camera at `from` looking at `to`. The scene parser has already rejected
    /// `from == to` and an `up` parallel to the view direction.
    pub fn new(from: Vec3, to: Vec3, up: Vec3, vfov_deg: f32, width: u32, height: u32) -> Camera {
        let tan_y = (vfov_deg.to_radians() * 0.5).tan();
        let tan_x = tan_y * width as f32 / height as f32;
        Camera::framed(from, to, up, tan_x, tan_y, width, height)
    }

    /// Orthographic camera whose film at `from`, facing `to`, spans `view_width × view_height`
    /// world units.
    pub fn orthographic(
        from: Vec3,
        to: Vec3,
        up: Vec3,
        view_width: f32,
        view_height: f32,
        width: u32,
        height: u32,
    ) -> Camera {
        let (hx, hy) = (0.5 * view_width, 0.5 * view_height);
        Camera {
            projection: Projection::Orthographic,
            ..Camera::framed(from, to, up, hx, hy, width, height)
        }
    }

    fn framed(
        from: Vec3,
        to: Vec3,
        up: Vec3,
        half_x: f32,
        half_y: f32,
        width: u32,
        height: u32,
    ) -> Camera {
        let forward = (to - from).normalize();
        let right = forward.cross(up).normalize();
        let up = right.cross(forward);
        Camera {
            origin: from,
            forward,
            right,
            up,
            half_x,
            half_y,
            projection: Projection::Perspective,
            shift: Vec2::ZERO,
            width,
            height,
            filter: PixelFilter::Box,
        }
    }

    /// This camera with its principal point moved by `(ox, oy)` film widths and heights
    /// (Mitsuba's `principal_point_offset_x/y`: the film position `(x, y)` sees what the centred
    /// camera sees at `(x + ox·width, y + oy·height)`).
    pub fn with_principal_point_offset(mut self, ox: f32, oy: f32) -> Camera {
        self.shift = Vec2::new(ox * self.width as f32, oy * self.height as f32);
        self
    }

    /// The principal point offset in pixels (for the GPU).
    pub fn shift(&self) -> Vec2 {
        self.shift
    }

    /// This perspective camera as a thin lens of radius `aperture_radius` focused at
    /// `focus_distance` (the parser checked `aperture_radius ≥ 0`, `focus_distance > 0`).
    pub fn with_thin_lens(mut self, aperture_radius: f32, focus_distance: f32) -> Camera {
        debug_assert!(self.projection != Projection::Orthographic);
        self.projection = Projection::ThinLens {
            aperture_radius,
            focus_distance,
        };
        self
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

    /// [`Camera::film_position`] and the sample's filter weight (1 but for a filter with negative
    /// lobes, [`PixelFilter::film_sample`]).
    #[inline]
    pub fn film_sample(&self, u: Vec2, px: u32, py: u32) -> (Vec2, f32) {
        self.filter.film_sample(u, px, py, self.width, self.height)
    }

    /// The view basis as plain data: `(forward, right, up, half_x, half_y)`, the unit axes and
    /// the film's half-extents that [`Camera::ray`] combines (for the GPU).
    pub fn basis(&self) -> (Vec3, Vec3, Vec3, f32, f32) {
        (self.forward, self.right, self.up, self.half_x, self.half_y)
    }

    /// The camera ray of one sample of pixel `(px, py)` and the weight its radiance takes (the
    /// filter's, [`Camera::film_sample`]): the film position from the sampler's camera
    /// dimensions, and for a thin lens the lens point from its lens dimensions.
    #[inline]
    pub fn sample_ray(&self, sampler: &mut Sampler, px: u32, py: u32) -> (Ray, f32) {
        let (p, weight) = self.film_sample(sampler.camera_2d(), px, py);
        let ray = match self.projection {
            Projection::ThinLens { .. } => self.lens_ray(p.x, p.y, sampler.lens_2d()),
            Projection::Perspective | Projection::Orthographic => self.ray(p.x, p.y),
        };
        (ray, weight)
    }

    /// Film coordinates `(x, y)` in pixels (0..width, 0..height, y down) as the signed image
    /// plane coordinates in [−1, 1] (+y up).
    #[inline]
    fn screen(&self, x: f32, y: f32) -> (f32, f32) {
        // Adding a zero shift is exact: a centred camera's rays keep their bits.
        let (x, y) = (x + self.shift.x, y + self.shift.y);
        (
            2.0 * x / self.width as f32 - 1.0,
            1.0 - 2.0 * y / self.height as f32,
        )
    }

    /// The ray through continuous film position `(x, y)` in pixels (0..width, 0..height, y
    /// down); for a thin lens the chief ray (through the lens centre).
    #[inline]
    pub fn ray(&self, x: f32, y: f32) -> Ray {
        let (sx, sy) = self.screen(x, y);
        let (along_x, along_y) = (
            (sx * self.half_x) * self.right,
            (sy * self.half_y) * self.up,
        );
        // Summed in this order (the pinhole's since the first release) so images keep their bits.
        match self.projection {
            Projection::Orthographic => Ray::new(self.origin + along_x + along_y, self.forward),
            Projection::Perspective | Projection::ThinLens { .. } => {
                Ray::new(self.origin, (self.forward + along_x + along_y).normalize())
            }
        }
    }

    /// The thin lens's ray through film position `(x, y)` from the lens point of the uniforms
    /// `u` (the pinhole's ray for any other projection).
    pub fn lens_ray(&self, x: f32, y: f32, u: Vec2) -> Ray {
        let Projection::ThinLens {
            aperture_radius,
            focus_distance,
        } = self.projection
        else {
            return self.ray(x, y);
        };
        let (sx, sy) = self.screen(x, y);
        let chief = self.forward + (sx * self.half_x) * self.right + (sy * self.half_y) * self.up;
        // `chief` has unit length along `forward`: this point is on the plane of focus.
        let focus = chief * focus_distance;
        let l = aperture_radius * sample_uniform_disk_concentric(u);
        let on_lens = l.x * self.right + l.y * self.up;
        Ray::new(self.origin + on_lens, (focus - on_lens).normalize())
    }

    /// Film position (pixels) that world point `p` projects to (through the lens centre), or
    /// `None` if it is behind the eye (the film plane, for an orthographic camera).
    pub fn project(&self, p: Vec3) -> Option<(f32, f32)> {
        let v = p - self.origin;
        let z = v.dot(self.forward);
        let depth = match self.projection {
            Projection::Orthographic if z >= 0.0 => 1.0,
            Projection::Perspective | Projection::ThinLens { .. } if z > 0.0 => z,
            _ => return None,
        };
        let sx = v.dot(self.right) / (depth * self.half_x);
        let sy = v.dot(self.up) / (depth * self.half_y);
        Some((
            (sx + 1.0) * 0.5 * self.width as f32 - self.shift.x,
            (1.0 - sy) * 0.5 * self.height as f32 - self.shift.y,
        ))
    }
}

#[cfg(test)]
#[path = "camera_tests.rs"]
mod tests;
