//! The constant background: radiance arriving from every direction that hits nothing.
//! WGSL twin: `lights/background.wgsl`.

use super::LightSample;
use crate::sampling::{sample_uniform_sphere, uniform_sphere_pdf};
use glam::{Vec2, Vec3};

/// A constant environment light.
#[derive(Clone, Debug)]
pub struct BackgroundLight {
    /// Radiance.
    pub le: Vec3,
    /// Radius of a sphere bounding the scene (for its power).
    pub scene_radius: f32,
}

impl BackgroundLight {
    /// Samples a direction uniformly on the sphere.
    pub fn sample(&self, u: Vec2) -> Option<LightSample> {
        let wi = sample_uniform_sphere(u);
        Some(LightSample {
            p: wi,
            p_error: Vec3::ZERO,
            n: -wi,
            wi,
            pdf: uniform_sphere_pdf(),
            le: self.le,
            infinite: true,
            b: Vec2::ZERO,
        })
    }

    /// Power through a disk of the scene's radius, from all directions (pbrt-v4's `Phi`).
    pub fn power(&self) -> f32 {
        let pi = std::f32::consts::PI;
        4.0 * pi * pi * self.scene_radius * self.scene_radius * crate::math::luminance(self.le)
    }
}
