//! Primitive records (`Prim` in `geometry/primitive.wgsl`), one per BVH primitive in the BVH's leaf order, and
//! the shapes' kind tags.
//! WGSL twin: `geometry/primitive.wgsl` (the record layout and the `switch` on [`ShapeTag`]).

use super::{bits, v4};
use crate::geometry::Shape;
use crate::gpu::prelude::gpu_tags;
use crate::scene::Scene;
use bytemuck::{Pod, Zeroable};

/// A primitive record (`Prim` in `geometry/primitive.wgsl`): a.w, b.w, c.w hold the bits of (kind, material,
/// light); the rest is the shape (see the top of `geometry/primitive.wgsl`), and a triangle's d.w (a free slot)
/// the bits of its attribute index ([`crate::geometry::Primitive::attr`]; the analytic shapes,
/// which have none, use d.w for their radius).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuPrim {
    pub(crate) a: [f32; 4],
    pub(crate) b: [f32; 4],
    pub(crate) c: [f32; 4],
    pub(crate) d: [f32; 4],
}

gpu_tags! {
    /// A primitive record's kind (the bits of `a.w`), in the variant order of [`Shape`].
    pub enum ShapeTag {
        /// [`Shape::Triangle`].
        Triangle => "SHAPE_TRIANGLE",
        /// [`Shape::Disk`].
        Disk => "SHAPE_DISK",
        /// [`Shape::Sphere`].
        Sphere => "SHAPE_SPHERE",
        /// [`Shape::Cylinder`].
        Cylinder => "SHAPE_CYLINDER",
    }
}

impl ShapeTag {
    /// The tag of `s`.
    pub fn of(s: &Shape) -> ShapeTag {
        match s {
            Shape::Triangle { .. } => ShapeTag::Triangle,
            Shape::Disk(_) => ShapeTag::Disk,
            Shape::Sphere(_) => ShapeTag::Sphere,
            Shape::Cylinder(_) => ShapeTag::Cylinder,
        }
    }
}

/// The records of `scene`'s primitives, in the order of [`crate::geometry::Accel::primitives`]
/// (the BVH's leaf order, so a hit's primitive index means the same on both sides).
pub(super) fn encode(scene: &Scene) -> Vec<GpuPrim> {
    scene
        .accel
        .primitives()
        .iter()
        .map(|p| {
            let (a, b, c, d) = match p.shape {
                Shape::Triangle { v, n } => (v[0], v[1], v[2], v4(n, bits(p.attr))),
                Shape::Disk(k) => {
                    let [x, y] = k.uv_axes();
                    (k.center, x, y, v4(k.n, k.radius))
                }
                Shape::Sphere(s) => {
                    let f = s.frame();
                    (s.center, f.s, f.t, v4(f.n, s.radius))
                }
                // The flip as the radius' sign.
                Shape::Cylinder(c) => (
                    c.p0,
                    c.axis,
                    c.u_axis,
                    [0.0, 0.0, 0.0, if c.flip { -c.radius } else { c.radius }],
                ),
            };
            GpuPrim {
                a: v4(a, bits(ShapeTag::of(&p.shape).gpu_tag())),
                b: v4(b, bits(p.material)),
                c: v4(c, bits(p.light)),
                d,
            }
        })
        .collect()
}
