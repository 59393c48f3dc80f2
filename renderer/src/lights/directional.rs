//! Directional lights, Mitsuba 3.9.1's `directional`: irradiance `E` arriving from one direction
//! everywhere (the sun as a delta in direction). Next-event estimation is the only technique
//! that finds it: the sample is the direction towards the light, "pdf" 1, radiance `E` (the
//! receiver's cosine makes the irradiance), its shadow ray running to infinity. It sits with the
//! lights at infinity (the light BVH samples it apart).
//! WGSL twin: `lights/directional.wgsl`.

use super::LightSample;
use glam::{Vec2, Vec3};

/// A directional light.
#[derive(Clone, Debug)]
pub struct DirectionalLight {
    /// The unit direction the light travels in (Mitsuba's `direction`, `to_world`'s +z).
    pub direction: Vec3,
    /// Irradiance on a surface facing the light, per channel (≥ 0).
    pub irradiance: Vec3,
    /// Radius of a sphere bounding the scene (for its power).
    pub scene_radius: f32,
}

impl DirectionalLight {
    /// The direction towards the light.
    pub fn sample(&self) -> Option<LightSample> {
        let wi = -self.direction;
        Some(LightSample {
            p: wi,
            p_error: Vec3::ZERO,
            n: self.direction,
            wi,
            pdf: 1.0,
            le: self.irradiance,
            infinite: true,
            b: Vec2::ZERO,
        })
    }

    /// Power through a disk of the scene's radius (pbrt-v4's `Phi`; luminance).
    pub fn power(&self) -> f32 {
        std::f32::consts::PI
            * self.scene_radius
            * self.scene_radius
            * crate::math::luminance(self.irradiance)
    }
}
