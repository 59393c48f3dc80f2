//! Adapter: a material's `sample`/`pdf` for a fixed outgoing direction, in its local frame.

use super::domain::Domain;
use super::sampler::{DirectionSample, DirectionalSampler};
use crate::materials::Material;
use glam::{Vec2, Vec3};

/// Lobes at most this rough are histogrammed by half vector, zoomed on the normal.
const NARROW_ALPHA: f32 = 0.1;
/// The zoomed cap's half-angle in units of α: GGX puts `1/(1 + 10²) ≈ 1%` of its half vectors
/// outside, which the outer rows still resolve.
const CAP_IN_ALPHAS: f64 = 10.0;

/// BSDF sampling of `material` seen from `wo` (local frame, normal +z).
#[derive(Clone, Debug)]
pub struct BsdfSampler {
    /// The material.
    pub material: Material,
    /// The outgoing direction.
    pub wo: Vec3,
}

impl BsdfSampler {
    /// Sampling `material` from `wo` at `theta_o_deg` from the normal, in the xz plane.
    pub fn at_angle(material: Material, theta_o_deg: f32) -> BsdfSampler {
        let t = theta_o_deg.to_radians();
        BsdfSampler {
            material,
            wo: Vec3::new(t.sin(), 0.0, t.cos()),
        }
    }

    /// GGX roughness of the material's glossy lobe, if it has one.
    fn alpha(&self) -> Option<f32> {
        match &self.material {
            Material::Diffuse(_) => None,
            Material::Conductor(c) => Some(c.alpha),
            Material::Plastic(p) => Some(p.alpha()),
        }
    }
}

impl DirectionalSampler for BsdfSampler {
    fn sample(&self, u1: f32, u2: Vec2) -> Option<DirectionSample> {
        let s = self.material.sample(self.wo, u1, u2)?;
        Some(DirectionSample {
            w: s.wi,
            pdf: s.pdf,
            delta: s.delta,
        })
    }

    fn pdf(&self, w: Vec3) -> f32 {
        self.material.pdf(self.wo, w)
    }

    /// Narrow lobes: half vectors zoomed on the normal, where a GGX lobe is round at any
    /// incidence. Others: directions over the whole sphere.
    fn domain(&self) -> Domain {
        match self.alpha() {
            Some(a) if a <= NARROW_ALPHA => {
                Domain::half_vector(self.wo, Some(CAP_IN_ALPHAS * a as f64))
            }
            _ => Domain::sphere(),
        }
    }
}
