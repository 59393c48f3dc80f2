//! Emitting planar polygons (any simple polygon, convex or concave), held as their triangulation.
//!
//! Area sampling picks a triangle in proportion to its area. Solid-angle sampling picks a triangle in
//! proportion to the solid angle it subtends from the shading point, then samples that spherical
//! triangle uniformly: from a point off the plane, the triangles of a planar simple polygon project to
//! disjoint spherical triangles, so the result is uniform over the polygon's solid angle with
//! pdf `1 / Σ Ω_i`.

use super::triangle::{spherical_ok, triangle_solid_angle};
use super::{LightSample, LightSampling, area_sample, area_to_solid_angle};
use crate::geometry::ray::gamma;
use crate::sampling::{DiscreteDistribution, sample_spherical_triangle, sample_uniform_triangle};
use glam::{Vec2, Vec3};

/// A one-sided emitting polygon.
#[derive(Clone, Debug)]
pub struct PolygonLight {
    /// Triangles of the polygon's triangulation, wound like the polygon.
    pub triangles: Vec<[Vec3; 3]>,
    /// Unit normal (Newell); emits on this side.
    pub n: Vec3,
    /// A point of the polygon's plane.
    pub origin: Vec3,
    /// Total area.
    pub area: f32,
    /// Emitted radiance.
    pub le: Vec3,
    by_area: DiscreteDistribution,
}

/// Most triangles for which solid-angle sampling is tried; beyond it, computing every triangle's
/// solid angle per sample costs more than the variance it saves.
const MAX_SOLID_ANGLE_TRIANGLES: usize = 64;

impl PolygonLight {
    /// A polygon light from its triangulation; `None` if it has no area.
    pub fn new(triangles: Vec<[Vec3; 3]>, n: Vec3, le: Vec3) -> Option<PolygonLight> {
        let areas: Vec<f32> = triangles.iter().map(crate::geometry::triangle::triangle_area).collect();
        let by_area = DiscreteDistribution::new(&areas)?;
        let area = areas.iter().sum();
        let origin = triangles.first()?[0];
        Some(PolygonLight { triangles, n, origin, area, le, by_area })
    }

    #[inline]
    fn faces(&self, p: Vec3) -> bool {
        (p - self.origin).dot(self.n) > 0.0
    }

    /// Solid angles of the triangles from `p` and their sum, if solid-angle sampling applies.
    fn solid_angles(&self, p: Vec3) -> Option<(Vec<f32>, f32)> {
        if self.triangles.len() > MAX_SOLID_ANGLE_TRIANGLES {
            return None;
        }
        let omegas: Vec<f32> = self.triangles.iter().map(|t| triangle_solid_angle(t, p)).collect();
        let total: f32 = omegas.iter().sum();
        spherical_ok(total).then_some((omegas, total))
    }

    /// Samples a point as seen from `p`.
    pub fn sample(&self, p: Vec3, u: Vec2, method: LightSampling) -> Option<LightSample> {
        if !self.faces(p) {
            return None;
        }
        if method == LightSampling::SolidAngle
            && let Some((omegas, total)) = self.solid_angles(p)
        {
            let dist = DiscreteDistribution::new(&omegas)?;
            let (i, _, ux) = dist.sample(u.x);
            let v = &self.triangles[i];
            let s = sample_spherical_triangle(v, p, Vec2::new(ux, u.y))?;
            let b = s.barycentrics;
            let y = b[0] * v[0] + b[1] * v[1] + b[2] * v[2];
            let err = gamma(6) * ((b[0] * v[0]).abs() + (b[1] * v[1]).abs() + (b[2] * v[2]).abs());
            return Some(LightSample { p: y, p_error: err, n: self.n, wi: s.dir, pdf: 1.0 / total, le: self.le, infinite: false });
        }
        let (i, _, ux) = self.by_area.sample(u.x);
        let v = &self.triangles[i];
        let b = sample_uniform_triangle(Vec2::new(ux, u.y));
        let y = b[0] * v[0] + b[1] * v[1] + b[2] * v[2];
        area_sample(p, y, self.n, 1.0 / self.area, self.le)
    }

    /// Solid-angle pdf of hitting `y` (normal `ny`) from `p`.
    pub fn pdf(&self, p: Vec3, _wi: Vec3, y: Vec3, ny: Vec3, method: LightSampling) -> f32 {
        if !self.faces(p) {
            return 0.0;
        }
        if method == LightSampling::SolidAngle
            && let Some((_, total)) = self.solid_angles(p)
        {
            return 1.0 / total;
        }
        area_to_solid_angle(1.0 / self.area, p, y, ny)
    }
}
