//! Projectors, Mitsuba 3.9.1's `projector`: a pinhole that projects an image (its `irradiance`,
//! a texture or a constant) into a rectangular frustum — a perspective camera run backwards.
//! The image's texture coordinates of a point are those of Mitsuba's `perspective_projection`
//! (horizontal field of view `fov_x`, the image's aspect), `u = ½ − ½ x / (z tan(fov_x/2))`,
//! `v = ½ − ½ y / (z tan(fov_y/2))` in the light's frame; a point outside `[0, 1]²` or behind the
//! projector gets nothing. Radiance arriving from the projector at a point at depth `z` along
//! its axis, seen at angle θ off the axis, is `π · scale · irradiance(uv) / (z² cos θ)`, so that
//! the irradiance on the plane z = 1 facing the projector is `π · scale · irradiance`
//! (Mitsuba's normalisation). A delta in position, sampled as [`super::point`] is.
//!
//! Frame and textures as [`super::spot`]: Mitsuba's `to_world` (`s` = local +x, `t` = +y, `n` the
//! axis); a textured projector's `le` leaves the texture out for
//! [`crate::scene::Scene::sample_light`] to apply at `LightSample::b`.
//! WGSL twin: `lights/projector.wgsl`.

use super::LightSample;
use super::point::delta_sample;
use crate::geometry::primitive::NONE;
use crate::math::Frame;
use glam::{Vec2, Vec3};

/// A projector.
#[derive(Clone, Debug)]
pub struct ProjectorLight {
    /// Its pinhole.
    pub position: Vec3,
    /// The light's frame (local x, y and the axis).
    pub frame: Frame,
    /// tan of half the horizontal and of half the vertical field of view.
    pub tan_half: Vec2,
    /// `π · scale · irradiance` for a constant irradiance, `π · scale` (grey) for a textured one.
    pub intensity: Vec3,
    /// The texture's selection radiance (one without a texture), for the light's power.
    pub selection: Vec3,
    /// Emission texture ([`super::Light::texture`]), [`NONE`] for none.
    pub texture: u32,
}

impl ProjectorLight {
    /// The texture coordinates of the point `local` (in the light's frame), and whether it is lit
    /// (in front, inside the image: Mitsuba's inclusive bounds).
    #[inline]
    pub fn uv(&self, local: Vec3) -> (Vec2, bool) {
        let u = 0.5 - 0.5 * local.x / (local.z * self.tan_half.x);
        let v = 0.5 - 0.5 * local.y / (local.z * self.tan_half.y);
        let lit = local.z > 0.0 && (0.0..=1.0).contains(&u) && (0.0..=1.0).contains(&v);
        (Vec2::new(u, v), lit)
    }

    /// The direction from `p` towards the pinhole with the radiance arriving along it (the
    /// texture not applied); `None` outside the frustum.
    pub fn sample(&self, p: Vec3) -> Option<LightSample> {
        let local = self.frame.to_local(p - self.position);
        let (uv, lit) = self.uv(local);
        if !lit {
            return None;
        }
        let d = self.position - p;
        let dist = d.length();
        let wi = d / dist;
        // cos θ between the axis and the direction from the pinhole to p.
        let cos_theta = -self.frame.n.dot(wi);
        let le = self.intensity / (local.z * local.z * cos_theta);
        let uv = if self.texture == NONE { Vec2::ZERO } else { uv };
        Some(delta_sample(self.position, wi, le, uv))
    }

    /// Emitted power: `π · scale · irradiance` over the image's rectangle on the plane z = 1,
    /// `2 tan(fov_x/2) · 2 tan(fov_y/2)` (Mitsuba's `sample_ray` weight; luminance).
    pub fn power(&self) -> f32 {
        let area = 4.0 * self.tan_half.x * self.tan_half.y;
        area * crate::math::luminance(self.intensity * self.selection)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn projector() -> ProjectorLight {
        ProjectorLight {
            position: Vec3::ZERO,
            frame: Frame {
                s: Vec3::X,
                t: Vec3::Y,
                n: Vec3::Z,
            },
            tan_half: Vec2::new(0.5, 0.25),
            intensity: Vec3::splat(std::f32::consts::PI * 2.0),
            selection: Vec3::ONE,
            texture: NONE,
        }
    }

    /// Mitsuba's perspective projection: the axis at the image's centre, local +x towards u = 0
    /// (Mitsuba's cameras look along +z with +x to the left), +y towards v = 0; the frustum's
    /// edges at 0 and 1; nothing behind.
    #[test]
    fn texture_coordinates_are_mitsubas_projection() {
        let l = projector();
        assert_eq!(l.uv(Vec3::new(0.0, 0.0, 3.0)), (Vec2::splat(0.5), true));
        assert_eq!(l.uv(Vec3::new(1.0, 0.0, 2.0)).0, Vec2::new(0.0, 0.5));
        assert_eq!(l.uv(Vec3::new(0.0, -0.5, 2.0)).0, Vec2::new(0.5, 1.0));
        assert!(!l.uv(Vec3::new(1.1, 0.0, 2.0)).1);
        assert!(!l.uv(Vec3::new(0.0, 0.0, -2.0)).1);
    }

    /// On a plane facing the projector at depth z, irradiance = le·cos θ = π·scale·E / z² times
    /// nothing else: uniform over the footprint, falling as 1/z², zero outside.
    #[test]
    fn irradiance_on_a_facing_plane_is_uniform() {
        let l = projector();
        for z in [1.0f32, 2.0, 5.0] {
            for (x, y) in [(0.0f32, 0.0f32), (0.4, 0.2), (-0.45, -0.2)] {
                let p = Vec3::new(x * z, y * z, z);
                let s = l.sample(p).unwrap();
                let e = s.le.x * s.wi.dot(-Vec3::Z);
                let want = 2.0 * std::f32::consts::PI / (z * z);
                assert!((e - want).abs() < 1e-5 * want, "{x} {y} {z}: {e} vs {want}");
            }
            assert!(l.sample(Vec3::new(0.6 * z, 0.0, z)).is_none());
        }
    }
}
