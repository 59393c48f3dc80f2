//! The surface tangent ∂p/∂u at a hit, and the shading frame it orients for an anisotropic BSDF
//! (α_u runs along it), as Mitsuba 3.9.1 computes them (`src/render/mesh.cpp`,
//! `SurfaceInteraction::initialize_sh_frame`):
//!
//! - a mesh triangle with texture coordinates: ∂p/∂u of its UV map, from its edges and their UV
//!   differences (a degenerate map, determinant 0: the first axis of the frame of the geometric
//!   normal); without them, its first edge p1 − p0 (the barycentric parameterisation);
//! - a sphere: the azimuthal direction about its frame's pole through its centre (`(−y, x, 0)`
//!   about +z for a sphere its `to_world` does not turn);
//! - a disk: the radial direction from its centre;
//! - a cylinder: the direction of growing φ about its axis (`Cylinder::dp_du`).
//!
//! The frame is the shading normal with ∂p/∂u made orthogonal to it (Gram–Schmidt), the frame of
//! the normal alone where that leaves nothing (∂p/∂u zero or along the normal). Only
//! anisotropic materials use it: an isotropic BSDF is the same in any frame about the normal,
//! and those keep `Frame::from_normal` (and their images, bit for bit). Which way the second
//! tangent points does not matter either: both distributions are even in each tangent axis.
//! WGSL twin: `geometry/tangent.wgsl`.

use super::SurfaceHit;
use super::mesh_attributes::MeshAttributes;
use super::primitive::{Primitive, Shape};
use crate::math::Frame;
use glam::Vec3;

/// ∂p/∂u of `hit` on `prim` (not normalised; zero at a sphere's poles and a disk's centre).
pub fn dp_du(prim: &Primitive, attributes: &MeshAttributes, hit: &SurfaceHit) -> Vec3 {
    match &prim.shape {
        Shape::Triangle { v, .. } => {
            let (dp0, dp1) = (v[1] - v[0], v[2] - v[0]);
            let Some([t0, t1, t2]) = attributes.triangle_uvs(prim.attr) else {
                return dp0;
            };
            let (duv0, duv1) = (t1 - t0, t2 - t0);
            let det = duv0.x * duv1.y - duv0.y * duv1.x;
            if det == 0.0 {
                return Frame::from_normal(hit.n).s;
            }
            (duv1.y * dp0 - duv0.y * dp1) / det
        }
        Shape::Sphere(s) => s.pole.cross(hit.p - s.center),
        Shape::Disk(d) => hit.p - d.center,
        Shape::Cylinder(c) => c.dp_du(hit.p),
    }
}

/// Both partials (∂p/∂u, ∂p/∂v) of a mesh triangle's parameterisation, Mitsuba's
/// (`Mesh::compute_surface_interaction`): of its UV map, from its edges and their UV differences
/// (a degenerate map: the two tangent axes of the geometric normal's frame), or without texture
/// coordinates the edges p1 − p0 and p2 − p0; `None` for the analytic shapes, whose ∂p/∂v
/// lumis does not give (a bump map needs both). ∂p/∂u is [`dp_du`]'s, bit for bit.
pub fn dp_duv(
    prim: &Primitive,
    attributes: &MeshAttributes,
    hit: &SurfaceHit,
) -> Option<(Vec3, Vec3)> {
    let Shape::Triangle { v, .. } = &prim.shape else {
        return None;
    };
    let (dp0, dp1) = (v[1] - v[0], v[2] - v[0]);
    let Some([t0, t1, t2]) = attributes.triangle_uvs(prim.attr) else {
        return Some((dp0, dp1));
    };
    let (duv0, duv1) = (t1 - t0, t2 - t0);
    let det = duv0.x * duv1.y - duv0.y * duv1.x;
    if det == 0.0 {
        let f = Frame::from_normal(hit.n);
        return Some((f.s, f.t));
    }
    Some((
        (duv1.y * dp0 - duv0.y * dp1) / det,
        (duv0.x * dp1 - duv1.x * dp0) / det,
    ))
}

/// The frame of unit normal `n` whose first axis is `dp_du` made orthogonal to `n`.
pub fn tangent_frame(n: Vec3, dp_du: Vec3) -> Frame {
    let s = dp_du - n * n.dot(dp_du);
    let len = s.length();
    if !(len > 0.0 && len.is_finite()) {
        return Frame::from_normal(n);
    }
    let s = s / len;
    Frame {
        s,
        t: n.cross(s),
        n,
    }
}

#[cfg(test)]
#[path = "tangent_tests.rs"]
mod tests;
