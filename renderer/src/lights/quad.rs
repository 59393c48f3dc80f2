//! Emitting parallelograms: area sampling, or solid-angle sampling of the spherical rectangle
//! (Ureña, Fajardo & King 2013) when the quad is a rectangle.
//! WGSL twin: `quad_light.wgsl`.

use super::triangle::spherical_ok;
use super::{LightSample, LightSampling, area_sample, area_to_solid_angle};
use crate::sampling::SphericalRectangle;
use glam::{Vec2, Vec3};

/// A one-sided emitting parallelogram `corner + s·edge_u + t·edge_v`, `s, t ∈ [0, 1]`.
#[derive(Clone, Debug)]
pub struct QuadLight {
    /// Corner.
    pub corner: Vec3,
    /// First edge.
    pub edge_u: Vec3,
    /// Second edge.
    pub edge_v: Vec3,
    /// Unit normal `normalize(edge_u × edge_v)`; emits on this side.
    pub n: Vec3,
    /// Area.
    pub area: f32,
    /// Emitted radiance.
    pub le: Vec3,
}

impl QuadLight {
    /// A quad light; `None` if it has no area.
    pub fn new(corner: Vec3, edge_u: Vec3, edge_v: Vec3, le: Vec3) -> Option<QuadLight> {
        let c = edge_u.cross(edge_v);
        let area = c.length();
        (area > 0.0 && area.is_finite()).then(|| QuadLight {
            corner,
            edge_u,
            edge_v,
            n: c / area,
            area,
            le,
        })
    }

    #[inline]
    fn faces(&self, p: Vec3) -> bool {
        (p - self.corner).dot(self.n) > 0.0
    }

    fn spherical(&self, p: Vec3) -> Option<SphericalRectangle> {
        SphericalRectangle::new(p, self.corner, self.edge_u, self.edge_v)
            .filter(|r| spherical_ok(r.solid_angle()))
    }

    /// Samples a point as seen from `p`.
    pub fn sample(&self, p: Vec3, u: Vec2, method: LightSampling) -> Option<LightSample> {
        if !self.faces(p) {
            return None;
        }
        if method == LightSampling::SolidAngle
            && let Some(rect) = self.spherical(p)
        {
            let y = rect.sample(u);
            let mut s = area_sample(p, y, self.n, 1.0 / self.area, self.le)?;
            s.pdf = 1.0 / rect.solid_angle();
            return Some(s);
        }
        let y = self.corner + u.x * self.edge_u + u.y * self.edge_v;
        area_sample(p, y, self.n, 1.0 / self.area, self.le)
    }

    /// Solid-angle pdf of hitting `y` (normal `ny`) from `p`.
    pub fn pdf(&self, p: Vec3, _wi: Vec3, y: Vec3, ny: Vec3, method: LightSampling) -> f32 {
        if !self.faces(p) {
            return 0.0;
        }
        if method == LightSampling::SolidAngle
            && let Some(rect) = self.spherical(p)
        {
            return 1.0 / rect.solid_angle();
        }
        area_to_solid_angle(1.0 / self.area, p, y, ny)
    }
}
