//! A robust ray test against the eight quantized child boxes of an obvhs CWBVH node: the Rust
//! model of the GPU's node test (`shaders/bvh.wgsl`), which traverses the compressed nodes as
//! uploaded. The CPU decodes the nodes once instead ([`super::wide_bvh`]).
//!
//! obvhs's own node test ignores every box that ends before `t = 1e-4` (a fixed ray epsilon), so a
//! path leaving a floor a hair away from a wall escapes through the corner, and with it the light
//! of tiny scenes. It also clamps `1/d` to `1/ε` for near-axis directions, which can end a slab
//! too early. This test keeps the ray's real interval `(0, t_max)`, uses the true reciprocal, and
//! widens each slab by a bound on its rounding error, so it never culls a box the ray touches.

use super::ray::gamma;
use glam::{Vec3, Vec3A, Vec4};
use obvhs::cwbvh::node::{CwBvhNode, extract_byte64};

/// Reciprocals are clamped here: large enough that a clamped slab still spans any scene, small
/// enough that `255 · extent / d` cannot overflow.
const MAX_INV: f32 = 1e20;

/// The per-ray part of the node test.
#[derive(Clone, Copy, Debug)]
pub struct NodeRay {
    o: Vec3A,
    inv: Vec3A,
    negative: [bool; 3],
    /// Boxes entered beyond this are culled; closest-hit traversal lowers it as hits are found.
    pub t_max: f32,
}

impl NodeRay {
    /// Prepares the ray `o + t·d`, `0 < t < t_max`.
    pub fn new(o: Vec3, d: Vec3, t_max: f32) -> NodeRay {
        let inv = |x: f32| {
            let r = 1.0 / x;
            // ±0 gives ±∞; keep the sign of zero so the slab order below stays right.
            if r.abs() > MAX_INV {
                MAX_INV.copysign(r)
            } else {
                r
            }
        };
        NodeRay {
            o: o.into(),
            inv: Vec3A::new(inv(d.x), inv(d.y), inv(d.z)),
            negative: [
                d.x.is_sign_negative(),
                d.y.is_sign_negative(),
                d.z.is_sign_negative(),
            ],
            t_max,
        }
    }
}

/// The hit mask of `node`'s children for obvhs's `traverse!` macro (`oct_inv4` from its traversal
/// state): a child counts when the ray's interval overlaps its box, widened by rounding error.
#[inline(always)]
pub fn intersect_node(node: &CwBvhNode, ray: &NodeRay, oct_inv4: u32) -> u32 {
    // Child plane q (0..=255) lies at p + q·extent; its slab parameter is q·a + b.
    let a = node.compute_extent() * ray.inv;
    let b = (Vec3A::from(node.p) - ray.o) * ray.inv;
    // Four roundings in each of q·a + b (the reciprocal, p − o, the two products, the sum).
    let err = gamma(5) * (255.0 * a.abs() + b.abs());
    let (child_bits8, bit_index8) = node.get_child_and_index_bits(oct_inv4);
    let mut hit_mask = 0u32;
    for half in 0..2 {
        let q = |v: &[u8; 8]| {
            let i = 4 * half;
            Vec4::new(
                v[i] as f32,
                v[i + 1] as f32,
                v[i + 2] as f32,
                v[i + 3] as f32,
            )
        };
        let slab = |lo: &[u8; 8], hi: &[u8; 8], axis: usize| {
            let (near, far) = if ray.negative[axis] {
                (q(hi), q(lo))
            } else {
                (q(lo), q(hi))
            };
            (
                near * a[axis] + Vec4::splat(b[axis] - err[axis]),
                far * a[axis] + Vec4::splat(b[axis] + err[axis]),
            )
        };
        let (x0, x1) = slab(&node.child_min_x, &node.child_max_x, 0);
        let (y0, y1) = slab(&node.child_min_y, &node.child_max_y, 1);
        let (z0, z1) = slab(&node.child_min_z, &node.child_max_z, 2);
        let t_near = x0.max(y0).max(z0).max(Vec4::ZERO);
        let t_far = x1.min(y1).min(z1).min(Vec4::splat(ray.t_max));
        let mask = t_near.cmple(t_far).bitmask();
        for j in 0..4 {
            if mask & (1 << j) != 0 {
                let child = 4 * half + j;
                hit_mask |= extract_byte64(child_bits8, child) << extract_byte64(bit_index8, child);
            }
        }
    }
    hit_mask
}
