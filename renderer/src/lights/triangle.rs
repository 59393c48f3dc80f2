//! Emitting triangles: area sampling (uniform barycentrics) or solid-angle sampling of the
//! spherical triangle (Arvo 1995), optionally through the cosine warp
//! ([`LightSampling::SolidAngleCosine`]), or the one that pays from the shading point
//! ([`LightSampling::Adaptive`]), or in proportion to the receiver's cos θ
//! ([`LightSampling::ProjectedSolidAngle`]).
//! WGSL twin: `lights/triangle.wgsl`.

use super::projected::{self, Projection};
use super::{LightSample, LightSampling, area_sample, area_to_solid_angle, triangle_sample};
use crate::sampling::{
    MAX_SPHERICAL_SAMPLE_AREA, MIN_SPHERICAL_SAMPLE_AREA, barycentrics_along,
    invert_spherical_triangle, sample_spherical_triangle, sample_uniform_triangle,
    spherical_triangle_area, spherical_triangle_corners,
};
use glam::{Vec2, Vec3};

/// A one-sided emitting triangle.
#[derive(Clone, Debug)]
pub struct TriangleLight {
    /// Vertices.
    pub v: [Vec3; 3],
    /// Unit normal (right-hand rule); emits on this side.
    pub n: Vec3,
    /// Area.
    pub area: f32,
    /// Emitted radiance (a textured light's selection radiance: see the module doc of
    /// [`super`]).
    pub le: Vec3,
    /// Index of its primitive's vertex attributes in
    /// [`crate::geometry::mesh_attributes::MeshAttributes::triangles`] ([`crate::geometry::primitive::NONE`]:
    /// none), whose texture coordinates a textured light's samples look up.
    pub attr: u32,
    /// Emission texture ([`super::Light::texture`]).
    pub texture: u32,
}

/// Solid angle of triangle `v` seen from `p`.
pub(crate) fn triangle_solid_angle(v: &[Vec3; 3], p: Vec3) -> f32 {
    let a = (v[0] - p).normalize_or_zero();
    let b = (v[1] - p).normalize_or_zero();
    let c = (v[2] - p).normalize_or_zero();
    spherical_triangle_area(a, b, c)
}

/// Whether the spherical warp is accurate for this solid angle (pbrt-v4's limits).
#[inline]
pub(crate) fn spherical_ok(omega: f32) -> bool {
    (MIN_SPHERICAL_SAMPLE_AREA..=MAX_SPHERICAL_SAMPLE_AREA).contains(&omega)
}

impl TriangleLight {
    /// `p` is strictly on the emitting side of the plane.
    #[inline]
    fn faces(&self, p: Vec3) -> bool {
        (p - self.v[0]).dot(self.n) > 0.0
    }

    /// Whether `method` samples this triangle from `p` by its spherical warp
    /// ([`LightSampling::spherical_for`]).
    #[inline]
    fn spherical(&self, p: Vec3, method: LightSampling) -> bool {
        let centroid = (self.v[0] + self.v[1] + self.v[2]) / 3.0;
        method.spherical_for(p, centroid, self.n, self.area)
    }

    /// Samples a point as seen from `p` (shading normal `ns`: [`super::Light::sample`]).
    pub fn sample(&self, p: Vec3, ns: Vec3, u: Vec2, method: LightSampling) -> Option<LightSample> {
        if !self.faces(p) {
            return None;
        }
        if method.projects(ns) {
            let frame = projected::frame(ns);
            match projected::convex(p, &frame, &self.v) {
                Projection::Below => return None,
                Projection::Sample(poly) => {
                    let wi = frame.to_world(poly.sample(u)).normalize();
                    return Some(self.sample_along(p, wi, projected::pdf(ns, wi, poly.area())));
                }
                Projection::Fallback => {}
            }
        }
        if self.spherical(p, method) && spherical_ok(triangle_solid_angle(&self.v, p)) {
            let (u, warp_pdf) = method.warp(p, ns, spherical_triangle_corners(&self.v), u);
            let s = sample_spherical_triangle(&self.v, p, u)?;
            let pdf = s.pdf * warp_pdf;
            return Some(triangle_sample(
                &self.v,
                s.barycentrics,
                self.n,
                self.le,
                s.dir,
                pdf,
            ));
        }
        let b = sample_uniform_triangle(u);
        let y = b[0] * self.v[0] + b[1] * self.v[1] + b[2] * self.v[2];
        let s = area_sample(p, y, self.n, 1.0 / self.area, self.le)?;
        Some(LightSample {
            b: Vec2::new(b[1], b[2]),
            ..s
        })
    }

    /// The sample along direction `wi` from `p` (within the triangle's solid angle), with
    /// solid-angle density `pdf`: the point where it meets the triangle.
    fn sample_along(&self, p: Vec3, wi: Vec3, pdf: f32) -> LightSample {
        let b = barycentrics_along(&self.v, p, wi);
        triangle_sample(&self.v, b, self.n, self.le, wi, pdf)
    }

    /// Solid-angle pdf of hitting `y` (normal `ny`) from `p` (shading normal `ns`) along `wi`.
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
            match projected::convex(p, &frame, &self.v) {
                Projection::Below => return 0.0,
                Projection::Sample(poly) => return projected::pdf(ns, wi, poly.area()),
                Projection::Fallback => {}
            }
        }
        if self.spherical(p, method) {
            let omega = triangle_solid_angle(&self.v, p);
            if spherical_ok(omega) {
                let corners = spherical_triangle_corners(&self.v);
                return method
                    .warp_pdf(p, ns, corners, || invert_spherical_triangle(&self.v, p, wi))
                    / omega;
            }
        }
        area_to_solid_angle(1.0 / self.area, p, y, ny)
    }
}
