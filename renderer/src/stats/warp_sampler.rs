//! Adapter: the plain warps of [`crate::sampling`] as direction samplers.

use super::domain::Domain;
use super::sampler::{DirectionSample, DirectionalSampler};
use crate::sampling::{
    cosine_hemisphere_pdf, sample_cosine_hemisphere, sample_uniform_cone, sample_uniform_sphere,
    uniform_cone_pdf, uniform_sphere_pdf,
};
use glam::{Vec2, Vec3};

/// A warp from the unit square to directions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Warp {
    /// [`sample_cosine_hemisphere`].
    CosineHemisphere,
    /// [`sample_uniform_sphere`].
    UniformSphere,
    /// [`sample_uniform_cone`] with this `cos θmax`.
    Cone(f32),
}

impl DirectionalSampler for Warp {
    fn sample(&self, _u1: f32, u: Vec2) -> Option<DirectionSample> {
        let (w, pdf) = match *self {
            Warp::CosineHemisphere => {
                let w = sample_cosine_hemisphere(u);
                (w, cosine_hemisphere_pdf(w.z))
            }
            Warp::UniformSphere => (sample_uniform_sphere(u), uniform_sphere_pdf()),
            Warp::Cone(c) => (sample_uniform_cone(u, c), uniform_cone_pdf(c)),
        };
        Some(DirectionSample {
            w,
            pdf,
            delta: false,
        })
    }

    fn pdf(&self, w: Vec3) -> f32 {
        match *self {
            Warp::CosineHemisphere => cosine_hemisphere_pdf(w.z),
            Warp::UniformSphere => uniform_sphere_pdf(),
            // Inside test by 1 − cos θ from x² + y², exact for narrow cones.
            Warp::Cone(c) => {
                let t = if w.z > 0.0 {
                    (w.x * w.x + w.y * w.y) / (1.0 + w.z)
                } else {
                    1.0 - w.z
                };
                if t <= 1.0 - c {
                    uniform_cone_pdf(c)
                } else {
                    0.0
                }
            }
        }
    }

    fn domain(&self) -> Domain {
        match *self {
            // Zoom on the cone, a little wider so its rim falls inside the cap's cells.
            Warp::Cone(c) => Domain::cap(Vec3::Z, 1.1 * (c as f64).clamp(-1.0, 1.0).acos()),
            _ => Domain::sphere(),
        }
    }
}
