//! Adapter: a material's `sample`/`pdf` for a fixed outgoing direction, in its local frame.
//!
//! Histogram domains: reflection-only lobes at most `NARROW_ALPHA` rough by half vector, zoomed
//! on the normal; other reflection-only materials by direction. A transmitting material (a
//! dielectric, seen from outside or inside) always by generalised half vector over the whole
//! sphere ([`Domain::generalised_half_vector`]), zoomed on the normal in both halves (by 10α when
//! narrow, 45° otherwise: see `WIDE_CAP`); a thin principled by direction over the whole sphere. In directions, its refraction lobe is far narrower
//! than α when η is near 1 (dωi/dωh ≈ (η − 1)²/η² at normal incidence): at η 1.1, α = 0.3 would
//! cover about two cells of a direction histogram.

use super::domain::Domain;
use super::sampler::{DirectionSample, DirectionalSampler};
use crate::materials::Material;
use glam::{Vec2, Vec3};

/// Lobes at most this rough are histogrammed by half vector, zoomed on the normal.
const NARROW_ALPHA: f32 = 0.1;
/// The zoomed cap's half-angle in units of α: GGX puts `1/(1 + 10²) ≈ 1%` of its half vectors
/// outside, which the outer rows still resolve.
const CAP_IN_ALPHAS: f64 = 10.0;
/// The cap's half-angle for wider lobes of a transmitting material. The quadrature works in the
/// versine, which squashes the pole: at θo = 89° the reflections that would go below the horizon
/// cut the lobe 0.5° from h = +z, a sliver of 1/800 of the first equal-area row that no rule
/// resolves (its samples then land in cells of expected count 0), but 1/30 of the first of 16
/// uniform-θ rows over 45°.
const WIDE_CAP: f64 = std::f64::consts::FRAC_PI_4;

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

    /// Sampling `material` from inside, `wo` at `theta_o_deg` from the inward normal −z, in the
    /// xz plane (a transmitting material: the viewer is on the `ior` side).
    pub fn inside_at_angle(material: Material, theta_o_deg: f32) -> BsdfSampler {
        let t = theta_o_deg.to_radians();
        BsdfSampler {
            material,
            wo: Vec3::new(t.sin(), 0.0, -t.cos()),
        }
    }

    /// Roughness of the material's glossy lobe, if it has one: the larger α of an anisotropic
    /// one (the lobe's widest extent sets the zoom; a Beckmann lobe is narrower than GGX's of
    /// the same α, so a cap sized for GGX holds it).
    fn alpha(&self) -> Option<f32> {
        let widest = |m: &crate::materials::Microfacet| m.alpha_u.max(m.alpha_v);
        match &self.material {
            // A thin sheet is delta: χ² has nothing to see.
            Material::Diffuse(_) | Material::ThinDielectric(_) => None,
            Material::Conductor(c) => Some(widest(&c.microfacet)),
            Material::Plastic(p) => Some(p.alpha()),
            Material::Dielectric(d) => Some(widest(&d.microfacet)),
            // Its main lobes' α (the clearcoat's is at most 0.1 too, beside it).
            Material::Principled(p) => Some(widest(&p.microfacet())),
            // The wider of its reflection's and its (η-scaled) transmission's.
            Material::PrincipledThin(p) => {
                Some(widest(&p.microfacet()).max(widest(&p.transmission_microfacet())))
            }
            Material::GltfPbr(p) => Some(p.alpha()),
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
    /// incidence. Others: directions over the whole sphere. Transmission: generalised half
    /// vectors, zoomed on the normal in both halves (see the module doc).
    fn domain(&self) -> Domain {
        let ior = match &self.material {
            Material::Dielectric(d) => Some(d.ior),
            Material::Principled(p) if p.transmission => Some(p.eta),
            _ => None,
        };
        // A thin principled's transmission mirrors its reflection, which a sphere of directions
        // resolves for the wide lobes its cases use (α > NARROW_ALPHA).
        if let Material::PrincipledThin(_) = self.material {
            return Domain::sphere();
        }
        if let Some(ior) = ior {
            let alpha = self.alpha().unwrap_or(0.0);
            let a = alpha as f64;
            let cap = if alpha <= NARROW_ALPHA {
                CAP_IN_ALPHAS * a
            } else {
                WIDE_CAP
            };
            return Domain::generalised_half_vector(self.wo, ior, Some(cap));
        }
        match self.alpha() {
            Some(a) if a <= NARROW_ALPHA => {
                Domain::half_vector(self.wo, Some(CAP_IN_ALPHAS * a as f64))
            }
            _ => Domain::sphere(),
        }
    }
}
