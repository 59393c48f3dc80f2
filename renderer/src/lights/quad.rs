//! Emitting parallelograms: area sampling, or solid-angle sampling of the spherical rectangle
//! (Ureña, Fajardo & King 2013) when the quad is a rectangle, optionally through the cosine warp
//! ([`LightSampling::SolidAngleCosine`]), or the one that pays from the shading point
//! ([`LightSampling::Adaptive`]), or in proportion to the receiver's cos θ over the part above
//! its horizon ([`LightSampling::ProjectedSolidAngle`]).
//! WGSL twin: `lights/quad.wgsl`.

use super::projected::{self, Projection};
use super::triangle::spherical_ok;
use super::{LightSample, LightSampling, area_sample, area_to_solid_angle};
use crate::geometry::primitive::NONE;
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
    /// Emitted radiance (a textured light's selection radiance: see the module doc of
    /// [`super`]).
    pub le: Vec3,
    /// Index of the vertex attributes of its first triangle in
    /// [`crate::geometry::mesh_attributes::MeshAttributes::triangles`], the second's following
    /// it ([`NONE`]: none); see [`QuadLight::triangle_point`].
    pub attr: u32,
    /// Emission texture ([`super::Light::texture`]).
    pub texture: u32,
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
            attr: NONE,
            texture: NONE,
        })
    }

    /// Which of the quad's two triangles holds `y` (a point of the quad) and `y`'s barycentrics
    /// `(b1, b2)` there, for texture coordinates. The triangles are those the scene builds the
    /// quad's primitives from, `[corner, +edge_u, +edge_u+edge_v]` (0) and
    /// `[corner, +edge_u+edge_v, +edge_v]` (1): with `y = corner + s·edge_u + t·edge_v`, the first
    /// holds `t ≤ s` with `b = (s − t, t)`, the second `t > s` with `b = (s, t − s)`.
    pub fn triangle_point(&self, y: Vec3) -> (u32, Vec2) {
        let d = y - self.corner;
        let s = (d.cross(self.edge_v).dot(self.n) / self.area).clamp(0.0, 1.0);
        let t = (self.edge_u.cross(d).dot(self.n) / self.area).clamp(0.0, 1.0);
        if t <= s {
            (0, Vec2::new(s - t, t))
        } else {
            (1, Vec2::new(s, t - s))
        }
    }

    #[inline]
    fn faces(&self, p: Vec3) -> bool {
        (p - self.corner).dot(self.n) > 0.0
    }

    /// The spherical rectangle seen from `p`, where `method` samples by it
    /// ([`LightSampling::spherical_for`]) and it suits the warp.
    fn spherical(&self, p: Vec3, method: LightSampling) -> Option<SphericalRectangle> {
        let center = self.corner + 0.5 * (self.edge_u + self.edge_v);
        if !method.spherical_for(p, center, self.n, self.area) {
            return None;
        }
        SphericalRectangle::new(p, self.corner, self.edge_u, self.edge_v)
            .filter(|r| spherical_ok(r.solid_angle()))
    }

    /// The points the corners `(0,0), (1,0), (0,1), (1,1)` of the sample square go to under
    /// [`SphericalRectangle::sample`] (`u.x` along `edge_u`, `u.y` along `edge_v`): the cosine
    /// warp's corners.
    fn corners(&self) -> [Vec3; 4] {
        let c = self.corner;
        [
            c,
            c + self.edge_u,
            c + self.edge_v,
            c + self.edge_u + self.edge_v,
        ]
    }

    /// The corners in order around the quad (counter-clockwise about `n`).
    fn outline(&self) -> [Vec3; 4] {
        let c = self.corner;
        [
            c,
            c + self.edge_u,
            c + self.edge_u + self.edge_v,
            c + self.edge_v,
        ]
    }

    /// Where the ray from `p` along `wi` meets the quad's plane, clamped onto the quad.
    fn point_along(&self, p: Vec3, wi: Vec3) -> Vec3 {
        let t = self.n.dot(self.corner - p) / self.n.dot(wi);
        let d = p + t * wi - self.corner;
        let s = (d.cross(self.edge_v).dot(self.n) / self.area).clamp(0.0, 1.0);
        let t = (self.edge_u.cross(d).dot(self.n) / self.area).clamp(0.0, 1.0);
        self.corner + s * self.edge_u + t * self.edge_v
    }

    /// Samples a point as seen from `p` (shading normal `ns`: [`super::Light::sample`]).
    pub fn sample(&self, p: Vec3, ns: Vec3, u: Vec2, method: LightSampling) -> Option<LightSample> {
        if !self.faces(p) {
            return None;
        }
        if method.projects(ns) {
            let frame = projected::frame(ns);
            match projected::convex(p, &frame, &self.outline()) {
                Projection::Below => return None,
                Projection::Sample(poly) => {
                    let wi = frame.to_world(poly.sample(u)).normalize();
                    let y = self.point_along(p, wi);
                    let mut s = area_sample(p, y, self.n, 1.0 / self.area, self.le)?;
                    s.pdf = projected::pdf(ns, s.wi, poly.area());
                    return Some(s);
                }
                Projection::Fallback => {}
            }
        }
        if let Some(rect) = self.spherical(p, method) {
            let (u, warp_pdf) = method.warp(p, ns, self.corners(), u);
            let y = rect.sample(u);
            let mut s = area_sample(p, y, self.n, 1.0 / self.area, self.le)?;
            s.pdf = warp_pdf / rect.solid_angle();
            return Some(s);
        }
        let y = self.corner + u.x * self.edge_u + u.y * self.edge_v;
        area_sample(p, y, self.n, 1.0 / self.area, self.le)
    }

    /// Solid-angle pdf of hitting `y` (normal `ny`) from `p` (shading normal `ns`).
    pub fn pdf(
        &self,
        p: Vec3,
        ns: Vec3,
        wi: Vec3,
        y: Vec3,
        ny: Vec3,
        method: LightSampling,
    ) -> f32 {
        if !self.faces(p) {
            return 0.0;
        }
        if method.projects(ns) {
            let frame = projected::frame(ns);
            match projected::convex(p, &frame, &self.outline()) {
                Projection::Below => return 0.0,
                Projection::Sample(poly) => return projected::pdf(ns, wi, poly.area()),
                Projection::Fallback => {}
            }
        }
        if let Some(rect) = self.spherical(p, method) {
            return method.warp_pdf(p, ns, self.corners(), || rect.invert(y)) / rect.solid_angle();
        }
        area_to_solid_angle(1.0 / self.area, p, y, ny)
    }
}
