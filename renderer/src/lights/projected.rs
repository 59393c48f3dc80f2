//! What the planar lights share for [`super::LightSampling::ProjectedSolidAngle`]: a light's
//! convex pieces (the triangle, the parallelogram, each triangle of a polygon's triangulation) as
//! seen from the receiver in its shading frame, clipped to its horizon
//! ([`ProjectedPolygon`]), the decision between sampling them and falling back to solid angle,
//! and the density `cos θ / Ω⊥`. `sample` and `pdf` build the same pieces from the same
//! arguments, so they decide alike.
//! WGSL twin: `lights/projected.wgsl`.

use crate::math::Frame;
use crate::sampling::ProjectedPolygon;
use crate::sampling::projected_solid_angle::conditioned;
use glam::Vec3;

/// How a planar light is sampled from a receiver under projected-solid-angle sampling.
#[derive(Clone, Copy, Debug)]
pub enum Projection<T> {
    /// No part of the light is above the receiver's horizon: it contributes nothing there (the
    /// receiver reflects only: [`super::LightSampling::receiver_normal`]), no sample, pdf 0.
    Below,
    /// Too small or too close to the horizon to sample accurately: by solid angle instead.
    Fallback,
    /// By projected solid angle, with what the light needs for it (the clipped polygon, or a
    /// polygon light's total Ω⊥).
    Sample(T),
}

/// The receiver's shading frame (normal `ns`, unit).
#[inline]
pub fn frame(ns: Vec3) -> Frame {
    Frame::from_normal(ns)
}

/// The convex polygon with world vertices `vertices` (at most four) seen from `p` in `frame`,
/// clipped to the horizon; `None` where none of it is above.
#[inline]
pub fn piece(p: Vec3, frame: &Frame, vertices: &[Vec3]) -> Option<ProjectedPolygon> {
    let mut w = [Vec3::ZERO; 4];
    for (l, &v) in w.iter_mut().zip(vertices) {
        *l = frame.to_local(v - p);
    }
    ProjectedPolygon::new(&w[..vertices.len()])
}

/// A convex light's [`Projection`] from `p` (frame `frame`).
#[inline]
pub fn convex(p: Vec3, frame: &Frame, vertices: &[Vec3]) -> Projection<ProjectedPolygon> {
    match piece(p, frame, vertices) {
        None => Projection::Below,
        Some(poly) if poly.well_conditioned() => Projection::Sample(poly),
        Some(_) => Projection::Fallback,
    }
}

/// The [`Projection`] of a light made of the convex `pieces` (disjoint as seen from `p`): each
/// piece's Ω⊥ goes to `weight(i, Ω⊥)` (0 for one wholly below the horizon), and the light is
/// sampled with the total Ω⊥ where the totals are well conditioned.
#[inline]
pub fn pieces<'a>(
    p: Vec3,
    frame: &Frame,
    pieces: impl Iterator<Item = &'a [Vec3; 3]>,
    mut weight: impl FnMut(usize, f32),
) -> Projection<f32> {
    let (mut total, mut abs_sum, mut any) = (0.0f32, 0.0f32, false);
    for (i, t) in pieces.enumerate() {
        let area = match piece(p, frame, t) {
            Some(poly) => {
                any = true;
                abs_sum += poly.abs_sum();
                poly.area()
            }
            None => 0.0,
        };
        total += area;
        weight(i, area);
    }
    if !any {
        Projection::Below
    } else if conditioned(total, abs_sum) {
        Projection::Sample(total)
    } else {
        Projection::Fallback
    }
}

/// The density `cos θ / Ω⊥` of direction `wi` from a receiver with normal `ns` (0 below its
/// horizon).
#[inline]
pub fn pdf(ns: Vec3, wi: Vec3, area: f32) -> f32 {
    ns.dot(wi).max(0.0) / area
}
