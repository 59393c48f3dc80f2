//! Emitting planar polygons (any simple polygon, convex or concave), held as their triangulation.
//!
//! Area sampling picks a triangle in proportion to its area. Solid-angle sampling picks a triangle in
//! proportion to the solid angle it subtends from the shading point, then samples that spherical
//! triangle uniformly: from a point off the plane, the triangles of a planar simple polygon project to
//! disjoint spherical triangles, so the result is uniform over the polygon's solid angle with
//! pdf `1 / Σ Ω_i`. With the cosine warp ([`LightSampling::SolidAngleCosine`]) the chosen
//! spherical triangle is sampled through its own bilinear warp, so the pdf is
//! `B_i(u) / Σ Ω_i` with `B_i` the warp's density in triangle `i` (the one holding the point).
//!
//! [`LightSampling::Adaptive`] samples by area where the polygon looks small, and elsewhere picks
//! triangle `i` with probability `q_i = e_i / Σ e_j` by the cheap estimate `e_i` of its solid angle
//! ([`super::planar_solid_angle_estimate`]) and samples its spherical triangle: pdf `q_i / Ω_i`,
//! one exact solid angle per sample or pdf instead of one per triangle (or, where that triangle's
//! solid angle does not suit the warp, by area within it: `q_i d² / (A_i |cos θ_y|)`).
//!
//! [`LightSampling::ProjectedSolidAngle`] picks triangle `i` with probability `Ω⊥_i / Σ Ω⊥_j`
//! (`Ω⊥_i` its projected solid angle clipped to the receiver's horizon) and samples it in
//! proportion to cos θ ([`super::projected`]): since the triangles' directions are disjoint, the
//! density is `cos θ / Σ Ω⊥_j` over the whole polygon, concave or not. The triangulation serves
//! as the convex decomposition the method needs; it exists already, is what the other methods
//! use, and costs one clipped triangle per piece (a triangle gains at most one vertex).
//! WGSL twin: `lights/polygon.wgsl`.

use super::projected::{self, Projection};
use super::triangle::spherical_ok;
use super::{LightSample, LightSampling, area_sample, area_to_solid_angle, triangle_sample};
use crate::sampling::{
    DiscreteDistribution, barycentrics_along, invert_spherical_triangle,
    sample_spherical_triangle_from_dirs, sample_uniform_triangle, spherical_triangle_area,
    spherical_triangle_corners,
};
use glam::{Vec2, Vec3};

/// A one-sided emitting polygon.
#[derive(Clone, Debug)]
pub struct PolygonLight {
    /// The polygon's vertices.
    pub vertices: Vec<Vec3>,
    /// Its triangulation (indices into `vertices`), wound like the polygon.
    pub indices: Vec<[u32; 3]>,
    /// The same triangles as vertex positions.
    pub triangles: Vec<[Vec3; 3]>,
    /// Unit normal (Newell); emits on this side.
    pub n: Vec3,
    /// A point of the polygon's plane.
    pub origin: Vec3,
    /// Total area.
    pub area: f32,
    /// Area-weighted centroid ([`LightSampling::spherical_for`]).
    pub centroid: Vec3,
    /// Each triangle's area.
    pub triangle_areas: Vec<f32>,
    /// Emitted radiance (a textured light's selection radiance: see the module doc of
    /// [`super`]).
    pub le: Vec3,
    /// Emission texture ([`super::Light::texture`]); its texture coordinates are each
    /// triangle's barycentrics, as the polygon's primitives have no vertex attributes.
    pub texture: u32,
    by_area: DiscreteDistribution,
}

/// Most triangles for which solid-angle sampling is tried; beyond it, computing every triangle's
/// solid angle per sample costs more than the variance it saves.
pub(crate) const MAX_SOLID_ANGLE_TRIANGLES: usize = 64;

/// Polygons of up to this many triangles (10 vertices) keep their per-sample arrays small.
const FEW_TRIANGLES: usize = 8;

impl PolygonLight {
    /// A polygon light from its vertices and triangulation; `None` if it has no area.
    pub fn new(
        vertices: Vec<Vec3>,
        indices: Vec<[u32; 3]>,
        n: Vec3,
        le: Vec3,
    ) -> Option<PolygonLight> {
        let triangles: Vec<[Vec3; 3]> = indices
            .iter()
            .map(|t| t.map(|i| vertices[i as usize]))
            .collect();
        let areas: Vec<f32> = triangles
            .iter()
            .map(crate::geometry::triangle::triangle_area)
            .collect();
        let by_area = DiscreteDistribution::new(&areas)?;
        let area: f32 = areas.iter().sum();
        let origin = triangles.first()?[0];
        let centroid = triangles
            .iter()
            .zip(&areas)
            .map(|(t, &a)| a * (t[0] + t[1] + t[2]))
            .sum::<Vec3>()
            / (3.0 * area);
        Some(PolygonLight {
            vertices,
            indices,
            triangles,
            n,
            origin,
            area,
            centroid,
            triangle_areas: areas,
            le,
            texture: crate::geometry::primitive::NONE,
            by_area,
        })
    }

    #[inline]
    fn faces(&self, p: Vec3) -> bool {
        (p - self.origin).dot(self.n) > 0.0
    }

    /// Calls `f` with the unit directions from `p` to the vertices, the solid angle of each
    /// triangle and their sum, if solid-angle sampling applies. The arrays are on the stack (no
    /// allocation per sample), sized for the polygon, and each vertex's direction is normalised
    /// once for all the triangles that use it.
    fn with_solid_angles<R>(
        &self,
        p: Vec3,
        f: impl FnOnce(&[Vec3], &[f32], f32) -> R,
    ) -> Option<R> {
        match self.triangles.len() {
            n if n <= FEW_TRIANGLES => {
                self.solid_angles_in::<FEW_TRIANGLES, { FEW_TRIANGLES + 2 }, R>(p, f)
            }
            n if n <= MAX_SOLID_ANGLE_TRIANGLES => self
                .solid_angles_in::<MAX_SOLID_ANGLE_TRIANGLES, { MAX_SOLID_ANGLE_TRIANGLES + 2 }, R>(
                    p, f,
                ),
            _ => None,
        }
    }

    /// [`PolygonLight::with_solid_angles`] with room for `T` triangles and `V = T + 2` vertices.
    fn solid_angles_in<const T: usize, const V: usize, R>(
        &self,
        p: Vec3,
        f: impl FnOnce(&[Vec3], &[f32], f32) -> R,
    ) -> Option<R> {
        let mut dirs = [Vec3::ZERO; V];
        for (d, v) in dirs.iter_mut().zip(&self.vertices) {
            *d = (*v - p).normalize_or_zero();
        }
        let mut omegas = [0.0f32; T];
        let mut total = 0.0;
        for (o, t) in omegas.iter_mut().zip(&self.indices) {
            *o = spherical_triangle_area(
                dirs[t[0] as usize],
                dirs[t[1] as usize],
                dirs[t[2] as usize],
            );
            total += *o;
        }
        spherical_ok(total).then(|| {
            f(
                &dirs[..self.vertices.len()],
                &omegas[..self.triangles.len()],
                total,
            )
        })
    }

    /// The triangle of the triangulation that holds `y` (a point of the polygon): the one whose
    /// smallest barycentric coordinate of `y` is largest, so a point on a shared edge, or just
    /// off the polygon by rounding, still gets one.
    fn triangle_holding(&self, y: Vec3) -> usize {
        let mut best = (0, f32::NEG_INFINITY);
        for (i, [a, b, c]) in self.triangles.iter().enumerate() {
            let (a, b, c) = (*a - y, *b - y, *c - y);
            let area = self.n.dot((b - a).cross(c - a));
            let smallest = self
                .n
                .dot(b.cross(c))
                .min(self.n.dot(c.cross(a)))
                .min(self.n.dot(a.cross(b)))
                / area;
            if smallest > best.1 {
                best = (i, smallest);
            }
        }
        best.0
    }

    /// Samples a point as seen from `p` (shading normal `ns`: [`super::Light::sample`]).
    pub fn sample(&self, p: Vec3, ns: Vec3, u: Vec2, method: LightSampling) -> Option<LightSample> {
        if !self.faces(p) {
            return None;
        }
        if method == LightSampling::Adaptive {
            return self.sample_adaptive(p, u);
        }
        if method.projects(ns) && self.triangles.len() <= MAX_SOLID_ANGLE_TRIANGLES {
            let frame = projected::frame(ns);
            let mut weights = [0.0f32; MAX_SOLID_ANGLE_TRIANGLES];
            match projected::pieces(p, &frame, self.triangles.iter(), |i, a| weights[i] = a) {
                Projection::Below => return None,
                Projection::Sample(total) => {
                    let (i, ux) = pick(&weights[..self.triangles.len()], total, u.x)?;
                    let poly = projected::piece(p, &frame, &self.triangles[i])?;
                    let wi = frame.to_world(poly.sample(Vec2::new(ux, u.y))).normalize();
                    return Some(self.sample_along(i, p, wi, projected::pdf(ns, wi, total)));
                }
                Projection::Fallback => {}
            }
        }
        let picked = if method.solid_angle() {
            self.with_solid_angles(p, |dirs, omegas, total| {
                let (i, ux) = pick(omegas, total, u.x)?;
                let corners = self.indices[i].map(|k| dirs[k as usize]);
                let v = &self.triangles[i];
                let warp_corners = spherical_triangle_corners(v);
                let (u, warp_pdf) = method.warp(p, ns, warp_corners, Vec2::new(ux, u.y));
                let s = sample_spherical_triangle_from_dirs(v, p, corners, omegas[i], u)?;
                Some((i, s, warp_pdf / total))
            })
        } else {
            None
        };
        if let Some(picked) = picked {
            let (i, s, pdf) = picked?;
            let v = &self.triangles[i];
            return Some(triangle_sample(
                v,
                s.barycentrics,
                self.n,
                self.le,
                s.dir,
                pdf,
            ));
        }
        self.sample_by_area(p, u)
    }

    /// The sample along direction `wi` from `p` (within triangle `i`'s solid angle), with
    /// solid-angle density `pdf`: the point where it meets that triangle.
    fn sample_along(&self, i: usize, p: Vec3, wi: Vec3, pdf: f32) -> LightSample {
        let v = &self.triangles[i];
        triangle_sample(v, barycentrics_along(v, p, wi), self.n, self.le, wi, pdf)
    }

    /// Area sampling: a triangle by area, then uniform in it.
    fn sample_by_area(&self, p: Vec3, u: Vec2) -> Option<LightSample> {
        let (i, _, ux) = self.by_area.sample(u.x);
        self.sample_in_triangle(p, i, Vec2::new(ux, u.y), 1.0 / self.area)
    }

    /// A uniform point of triangle `i` for `u`, with area density `pdf_area`.
    fn sample_in_triangle(&self, p: Vec3, i: usize, u: Vec2, pdf_area: f32) -> Option<LightSample> {
        let v = &self.triangles[i];
        let b = sample_uniform_triangle(u);
        let y = b[0] * v[0] + b[1] * v[1] + b[2] * v[2];
        let s = area_sample(p, y, self.n, pdf_area, self.le)?;
        Some(LightSample {
            b: Vec2::new(b[1], b[2]),
            ..s
        })
    }

    /// The estimated solid angle `e_i` of triangle `i` from `p` ([`LightSampling::Adaptive`]).
    #[inline]
    fn triangle_estimate(&self, i: usize, p: Vec3) -> f32 {
        let [a, b, c] = self.triangles[i];
        super::planar_solid_angle_estimate(p, (a + b + c) / 3.0, self.n, self.triangle_areas[i])
    }

    /// `Σ e_i` from `p` where [`LightSampling::Adaptive`] samples by triangle estimates there, `None`
    /// where it samples the whole polygon by area (the polygon looks small, or an estimate is not
    /// finite because `p` is almost on the plane).
    fn adaptive_total(&self, p: Vec3) -> Option<f32> {
        if !LightSampling::Adaptive.spherical_for(p, self.centroid, self.n, self.area) {
            return None;
        }
        let total: f32 = (0..self.triangles.len())
            .map(|i| self.triangle_estimate(i, p))
            .sum();
        (total > 0.0 && total.is_finite()).then_some(total)
    }

    /// [`LightSampling::Adaptive`]'s sample (see the module doc).
    fn sample_adaptive(&self, p: Vec3, u: Vec2) -> Option<LightSample> {
        let Some(total) = self.adaptive_total(p) else {
            return self.sample_by_area(p, u);
        };
        // `pick` without an array: the estimates are cheap to compute again.
        let goal = u.x * total;
        let mut acc = 0.0;
        let mut chosen = None;
        for i in 0..self.triangles.len() {
            let e = self.triangle_estimate(i, p);
            if e <= 0.0 {
                continue;
            }
            let ux = ((goal - acc) / e).clamp(0.0, crate::sampling::ONE_MINUS_EPSILON);
            chosen = Some((i, e, ux));
            if goal < acc + e {
                break;
            }
            acc += e;
        }
        // Rounding past the last positive entry keeps that entry, at the top of its interval.
        let (i, e, ux) = chosen?;
        let q = e / total;
        let v = &self.triangles[i];
        let omega = super::triangle::triangle_solid_angle(v, p);
        if !spherical_ok(omega) {
            return self.sample_in_triangle(p, i, Vec2::new(ux, u.y), q / self.triangle_areas[i]);
        }
        let s = crate::sampling::sample_spherical_triangle(v, p, Vec2::new(ux, u.y))?;
        Some(triangle_sample(
            v,
            s.barycentrics,
            self.n,
            self.le,
            s.dir,
            q / omega,
        ))
    }

    /// [`LightSampling::Adaptive`]'s pdf of hitting `y` (normal `ny`) from `p`.
    fn pdf_adaptive(&self, p: Vec3, y: Vec3, ny: Vec3) -> f32 {
        let Some(total) = self.adaptive_total(p) else {
            return area_to_solid_angle(1.0 / self.area, p, y, ny);
        };
        let i = self.triangle_holding(y);
        let q = self.triangle_estimate(i, p) / total;
        let omega = super::triangle::triangle_solid_angle(&self.triangles[i], p);
        if !spherical_ok(omega) {
            return area_to_solid_angle(q / self.triangle_areas[i], p, y, ny);
        }
        q / omega
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
        if method == LightSampling::Adaptive {
            return self.pdf_adaptive(p, y, ny);
        }
        if method.projects(ns) && self.triangles.len() <= MAX_SOLID_ANGLE_TRIANGLES {
            let frame = projected::frame(ns);
            match projected::pieces(p, &frame, self.triangles.iter(), |_, _| {}) {
                Projection::Below => return 0.0,
                Projection::Sample(total) => return projected::pdf(ns, wi, total),
                Projection::Fallback => {}
            }
        }
        if method.solid_angle()
            && let Some(total) = self.with_solid_angles(p, |_, _, total| total)
        {
            if !method.warps(ns) {
                return 1.0 / total;
            }
            let v = &self.triangles[self.triangle_holding(y)];
            let corners = spherical_triangle_corners(v);
            return method.warp_pdf(p, ns, corners, || invert_spherical_triangle(v, p, wi)) / total;
        }
        area_to_solid_angle(1.0 / self.area, p, y, ny)
    }
}

/// Picks an entry in proportion to `weights` (summing to `total`) and remaps `u` to `[0, 1)` within
/// it; never an entry of zero weight.
fn pick(weights: &[f32], total: f32, u: f32) -> Option<(usize, f32)> {
    let target = u * total;
    let mut acc = 0.0;
    let mut last = None;
    for (i, &w) in weights.iter().enumerate() {
        if w <= 0.0 {
            continue;
        }
        if target < acc + w {
            return Some((
                i,
                ((target - acc) / w).clamp(0.0, crate::sampling::ONE_MINUS_EPSILON),
            ));
        }
        acc += w;
        last = Some(i);
    }
    // Rounding left `target` past the last positive entry.
    last.map(|i| (i, crate::sampling::ONE_MINUS_EPSILON))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pick_follows_weights_and_skips_zeros() {
        let w = [0.0, 1.0, 0.0, 3.0];
        assert_eq!(pick(&w, 4.0, 0.0).unwrap().0, 1);
        assert_eq!(pick(&w, 4.0, 0.24).unwrap().0, 1);
        let (i, u) = pick(&w, 4.0, 0.5).unwrap();
        assert_eq!(i, 3);
        assert!((u - 1.0 / 3.0).abs() < 1e-6);
        assert_eq!(pick(&w, 4.0, 0.999_999_9).unwrap().0, 3);
        assert!(pick(&[0.0, 0.0], 0.0, 0.5).is_none());
    }
}
