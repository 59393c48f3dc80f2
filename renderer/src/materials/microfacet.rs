//! A microfacet distribution as the rough materials use it: GGX or Beckmann, with roughness α_u
//! along the shading frame's first tangent and α_v along its second (equal: isotropic). The one
//! place that dispatches on the distribution; the formulas live in `ggx.rs` and `beckmann.rs`.
//! WGSL twin: `materials/microfacet.wgsl` (a `switch` on [`Distribution`]'s tags, same order).

use super::{beckmann, ggx};
use glam::{Vec2, Vec3};

/// The microfacet normal distributions, a closed set.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Distribution {
    /// GGX (Trowbridge–Reitz): long tails; lumis' default.
    #[default]
    Ggx,
    /// Beckmann (gaussian slopes): Mitsuba's default.
    Beckmann,
}

impl Distribution {
    /// Its name in the scene formats (lumis' and Mitsuba's spell it alike).
    pub fn name(self) -> &'static str {
        match self {
            Distribution::Ggx => "ggx",
            Distribution::Beckmann => "beckmann",
        }
    }

    /// The distribution named `name`, if any.
    pub fn from_name(name: &str) -> Option<Distribution> {
        [Distribution::Ggx, Distribution::Beckmann]
            .into_iter()
            .find(|d| d.name() == name)
    }
}

/// A distribution and its roughness; a perfect (delta) mirror or interface when both α are below
/// [`ggx::SMOOTH_ALPHA`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Microfacet {
    /// Which distribution.
    pub distribution: Distribution,
    /// α along the frame's first tangent (not squared).
    pub alpha_u: f32,
    /// α along the frame's second tangent.
    pub alpha_v: f32,
}

impl Microfacet {
    /// Isotropic GGX of roughness `alpha`.
    pub const fn ggx(alpha: f32) -> Microfacet {
        Microfacet {
            distribution: Distribution::Ggx,
            alpha_u: alpha,
            alpha_v: alpha,
        }
    }

    /// `distribution` with roughness (α_u, α_v). A rough lobe's narrower α is raised to
    /// [`ggx::SMOOTH_ALPHA`] (a lobe 0.06° wide, below any pixel's footprint): at α = 0 the
    /// distributions divide by zero.
    pub fn new(distribution: Distribution, alpha_u: f32, alpha_v: f32) -> Microfacet {
        let mut m = Microfacet {
            distribution,
            alpha_u,
            alpha_v,
        };
        if !m.is_smooth() {
            m.alpha_u = alpha_u.max(ggx::SMOOTH_ALPHA);
            m.alpha_v = alpha_v.max(ggx::SMOOTH_ALPHA);
        }
        m
    }

    /// The same distribution with isotropic roughness `alpha` (a textured α at a hit).
    pub fn with_alpha(self, alpha: f32) -> Microfacet {
        Microfacet::new(self.distribution, alpha, alpha)
    }

    /// True if handled as a delta mirror or interface.
    #[inline]
    pub fn is_smooth(&self) -> bool {
        ggx::is_smooth(self.alpha_u.max(self.alpha_v))
    }

    /// True if α_u ≠ α_v: the image depends on the shading frame's tangents.
    pub fn is_anisotropic(&self) -> bool {
        self.alpha_u != self.alpha_v
    }

    /// D(h), normalised so that ∫ D(h)·h.z dω = 1; 0 below the horizon.
    #[inline]
    pub fn d(&self, h: Vec3) -> f32 {
        let (u, v) = (self.alpha_u, self.alpha_v);
        match self.distribution {
            Distribution::Ggx => ggx::d_anisotropic(u, v, h),
            Distribution::Beckmann => beckmann::d(u, v, h),
        }
    }

    /// Smith masking G1(w), symmetric in w.z.
    #[inline]
    pub fn g1(&self, w: Vec3) -> f32 {
        let (u, v) = (self.alpha_u, self.alpha_v);
        match self.distribution {
            Distribution::Ggx => ggx::g1_anisotropic(u, v, w),
            Distribution::Beckmann => beckmann::g1(u, v, w),
        }
    }

    /// Separable masking-shadowing G1(wo)·G1(wi) (Mitsuba's `G`, the scene format's).
    #[inline]
    pub fn g2_separable(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.g1(wo) * self.g1(wi)
    }

    /// A normal drawn from the normals visible from `wo` (wo.z ≥ 0), density
    /// [`Microfacet::visible_normal_pdf`].
    #[inline]
    pub fn sample_visible_normal(&self, wo: Vec3, u: Vec2) -> Vec3 {
        let (a, b) = (self.alpha_u, self.alpha_v);
        match self.distribution {
            Distribution::Ggx => ggx::sample_visible_normal_anisotropic(a, b, wo, u),
            Distribution::Beckmann => beckmann::sample_visible_normal(a, b, wo, u),
        }
    }

    /// G1(wo)·max(0, wo·h)·D(h)/wo.z; 0 for wo.z ≤ 0.
    #[inline]
    pub fn visible_normal_pdf(&self, wo: Vec3, h: Vec3) -> f32 {
        if wo.z <= 0.0 {
            return 0.0;
        }
        self.g1(wo) * wo.dot(h).max(0.0) * self.d(h) / wo.z
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_unknown_is_none() {
        for d in [Distribution::Ggx, Distribution::Beckmann] {
            assert_eq!(Distribution::from_name(d.name()), Some(d));
        }
        assert_eq!(Distribution::from_name("phong"), None);
        assert_eq!(Distribution::default(), Distribution::Ggx);
    }

    #[test]
    fn isotropic_ggx_is_ggx_bit_for_bit() {
        // The anisotropic entry points must not move a single bit of the isotropic images.
        let m = Microfacet::ggx(0.3);
        let (wo, wi) = (
            Vec3::new(0.3, -0.2, 0.9).normalize(),
            Vec3::new(-0.5, 0.1, 0.7).normalize(),
        );
        let (h, _) = ggx::half_vector(wo, wi);
        assert_eq!(m.d(h), ggx::d(0.3, h));
        assert_eq!(m.g1(wo), ggx::g1(0.3, wo));
        let u = Vec2::new(0.37, 0.81);
        assert_eq!(
            m.sample_visible_normal(wo, u),
            ggx::sample_visible_normal(0.3, wo, u)
        );
        assert_eq!(
            m.visible_normal_pdf(wo, h),
            ggx::visible_normal_pdf(0.3, wo, h)
        );
    }

    #[test]
    fn smoothness_and_the_narrow_alpha_floor() {
        assert!(Microfacet::new(Distribution::Beckmann, 0.0, 0.0).is_smooth());
        assert!(Microfacet::new(Distribution::Ggx, 5e-4, 9e-4).is_smooth());
        let m = Microfacet::new(Distribution::Beckmann, 0.0, 0.3);
        assert!(!m.is_smooth() && m.alpha_u == ggx::SMOOTH_ALPHA && m.alpha_v == 0.3);
        assert!(m.is_anisotropic() && !Microfacet::ggx(0.2).is_anisotropic());
        let h = Vec3::new(1e-4, 0.2, 1.0).normalize();
        assert!(m.d(h).is_finite() && m.g1(h).is_finite());
    }
}
