//! The CPU's traversal structure: the CWBVH's tree with each node's eight child boxes decoded once
//! into `f32` planes (rounded outwards) and laid out four children per `Vec4`, so that a node costs
//! two 4-wide slab tests (SSE through glam) instead of decoding 48 quantized bytes per visit.
//!
//! The tree, its leaves and the primitive order are exactly the CWBVH's ([`super::Accel`] keeps
//! that for the GPU, which traverses the compressed nodes); only the node format differs. Children
//! are visited nearest first, and a closest-hit traversal drops entries that start beyond the
//! closest hit found so far.
//! WGSL twin: `geometry/bvh.wgsl`.

use super::ray::{Ray, gamma};
use glam::Vec4;
use obvhs::cwbvh::CwBvh;
use std::ops::Range;

/// Reciprocal directions are clamped here, as in the GPU's node test (`geometry/bvh.wgsl`): a
/// clamped slab still spans any scene, and no product overflows to a NaN. Like that test, this one
/// keeps the ray's true interval `(0, t_max)`: obvhs's own culls boxes that end before a fixed
/// `1e-4`, which let paths escape closed rooms through their corners.
pub(crate) const MAX_INV: f32 = 1e20;

/// A slab parameter is `(plane − o) · (1/d)`: three roundings, each within `γ(3)` of exact.
/// Widening the far end by `1 + 2γ(3)` (pbrt-v4's `Bounds3::IntersectP`) keeps every box the ray
/// touches.
const FAR_SCALE: f32 = 1.0 + 2.0 * gamma(3);

/// Child reference: internal nodes are their index; leaves set this bit.
const LEAF: u32 = 1 << 31;
/// Leaves keep their primitive count in the low bits and the first primitive above them.
const COUNT_BITS: u32 = 3;
/// Largest primitive index a leaf reference can hold.
const MAX_FIRST: u32 = (LEAF >> COUNT_BITS) - 1;
/// An empty child slot (its box is also empty, so it is never entered).
const EMPTY: u32 = u32::MAX;

/// Traversal stacks hold this many entries when the tree needs no more (see
/// [`WideBvh::stack_need`]): a small scene's stack is cleared with a few stores, not a `memset`.
const SMALL_STACK: usize = 16;
/// The same for mid-sized trees.
const SHALLOW_STACK: usize = 64;
/// Capacity for deeper trees: obvhs keeps CWBVHs under 32 levels, each deferring at most 7 children.
const DEEP_STACK: usize = 32 * 7 + 1;

/// One node: `planes[k][h]` holds plane `k` (min x, min y, min z, max x, max y, max z) of children
/// `4h .. 4h + 4`.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
struct WideNode {
    planes: [[Vec4; 2]; 6],
    child: [u32; 8],
}

/// The per-ray part of the node test.
struct WideRay {
    o: [Vec4; 3],
    inv: [Vec4; 3],
    /// Plane index of each axis's entry and exit: min first for a positive direction.
    near: [usize; 3],
    far: [usize; 3],
}

impl WideRay {
    fn new(ray: &Ray) -> WideRay {
        let inv = |x: f32| {
            let r = 1.0 / x;
            if r.abs() > MAX_INV {
                MAX_INV.copysign(r)
            } else {
                r
            }
        };
        let d = ray.d.to_array();
        let o = ray.o.to_array();
        let negative = d.map(|x| x.is_sign_negative() as usize);
        WideRay {
            o: o.map(Vec4::splat),
            inv: d.map(|x| Vec4::splat(inv(x))),
            near: [3 * negative[0], 1 + 3 * negative[1], 2 + 3 * negative[2]],
            far: [
                3 - 3 * negative[0],
                4 - 3 * negative[1],
                5 - 3 * negative[2],
            ],
        }
    }
}

/// The CWBVH as `f32` nodes for 4-wide tests.
#[derive(Clone, Debug)]
pub struct WideBvh {
    nodes: Vec<WideNode>,
    /// Entries a traversal stack may need: over all root-to-leaf paths, the most children deferred.
    stack_need: usize,
}

/// Rounds `p + q·e` (exact in f64) down or up to an `f32`, so the decoded plane lies on the outer
/// side of the quantized one.
fn decode_plane(p: f32, q: u8, e: f32, down: bool) -> f32 {
    let exact = p as f64 + q as f64 * e as f64;
    let r = exact as f32;
    match (down, (r as f64).partial_cmp(&exact)) {
        (true, Some(std::cmp::Ordering::Greater)) => super::ray::next_float_down(r),
        (false, Some(std::cmp::Ordering::Less)) => super::ray::next_float_up(r),
        _ => r,
    }
}

impl WideBvh {
    /// Decodes `cw`, whose leaves index the primitives directly (as [`super::Accel`] orders them).
    pub fn from_cwbvh(cw: &CwBvh) -> WideBvh {
        let nodes: Vec<WideNode> = cw
            .nodes
            .iter()
            .map(|n| {
                let e = n.compute_extent();
                // Empty slots keep min = +∞, max = −∞: entered at +∞, left at −∞, never hit.
                let mut planes = [[Vec4::INFINITY; 2]; 6];
                for p in &mut planes[3..] {
                    *p = [Vec4::NEG_INFINITY; 2];
                }
                let mut child = [EMPTY; 8];
                for (i, slot) in child.iter_mut().enumerate() {
                    if n.is_child_empty(i) {
                        continue;
                    }
                    let (h, j) = (i / 4, i % 4);
                    let lo = [n.child_min_x[i], n.child_min_y[i], n.child_min_z[i]];
                    let hi = [n.child_max_x[i], n.child_max_y[i], n.child_max_z[i]];
                    for a in 0..3 {
                        planes[a][h][j] = decode_plane(n.p[a], lo[a], e[a], true);
                        planes[3 + a][h][j] = decode_plane(n.p[a], hi[a], e[a], false);
                    }
                    *slot = if n.is_leaf(i) {
                        let (first, count) = n.child_primitives(i);
                        assert!(first <= MAX_FIRST && count < 1 << COUNT_BITS);
                        LEAF | first << COUNT_BITS | count
                    } else {
                        n.child_node_index(i)
                    };
                }
                WideNode { planes, child }
            })
            .collect();
        // Deepest deferral, iteratively: (node, entries already deferred above it).
        let mut stack_need = 1;
        let mut todo = vec![(0usize, 0usize)];
        while let Some((i, above)) = todo.pop() {
            let children: Vec<u32> = nodes[i]
                .child
                .iter()
                .copied()
                .filter(|&c| c != EMPTY)
                .collect();
            let here = above + children.len().saturating_sub(1);
            stack_need = stack_need.max(here + 1);
            for c in children {
                if c & LEAF == 0 {
                    todo.push((c as usize, here));
                }
            }
        }
        assert!(
            stack_need <= DEEP_STACK,
            "the CWBVH is deeper than obvhs guarantees"
        );
        WideBvh { nodes, stack_need }
    }

    /// Children of `node` that the ray enters within `(0, t_max)`, as a bit mask, and where it
    /// enters each.
    #[inline(always)]
    fn enter(node: &WideNode, r: &WideRay, t_max: f32) -> (u32, [Vec4; 2]) {
        let mut mask = 0;
        let mut t_near = [Vec4::ZERO; 2];
        let t_max = Vec4::splat(t_max);
        for (h, entry) in t_near.iter_mut().enumerate() {
            let slab = |plane: usize, a: usize| (node.planes[plane][h] - r.o[a]) * r.inv[a];
            let near = slab(r.near[0], 0)
                .max(slab(r.near[1], 1))
                .max(slab(r.near[2], 2))
                .max(Vec4::ZERO);
            let far = slab(r.far[0], 0)
                .min(slab(r.far[1], 1))
                .min(slab(r.far[2], 2))
                .min(t_max)
                * FAR_SCALE;
            mask |= near.cmple(far).bitmask() << (4 * h);
            *entry = near;
        }
        (mask, t_near)
    }

    /// Closest-hit traversal: `test(leaf, t_max)` tests the primitives of a leaf against the ray
    /// within `(0, t_max)` and returns the parameter of a closer hit, if it found one.
    #[inline]
    pub fn closest(&self, ray: &Ray, test: impl FnMut(Range<usize>, f32) -> Option<f32>) {
        if self.stack_need <= SMALL_STACK {
            self.closest_with::<SMALL_STACK>(ray, test)
        } else if self.stack_need <= SHALLOW_STACK {
            self.closest_with::<SHALLOW_STACK>(ray, test)
        } else {
            self.closest_with::<DEEP_STACK>(ray, test)
        }
    }

    fn closest_with<const N: usize>(
        &self,
        ray: &Ray,
        mut test: impl FnMut(Range<usize>, f32) -> Option<f32>,
    ) {
        let r = WideRay::new(ray);
        let mut t_max = ray.t_max;
        // Entries are (entry t bits << 32 | child): t ≥ 0, so the integers sort as the t do.
        let mut stack = [0u64; N];
        let mut len = 0;
        let mut current = 0u32;
        loop {
            if current & LEAF != 0 {
                if let Some(t) = test(leaf_range(current), t_max) {
                    t_max = t;
                }
            } else {
                let node = &self.nodes[current as usize];
                let (mut mask, t_near) = Self::enter(node, &r, t_max);
                let base = len;
                while mask != 0 {
                    let i = mask.trailing_zeros() as usize;
                    mask &= mask - 1;
                    let entry =
                        (t_near[i / 4][i % 4].to_bits() as u64) << 32 | node.child[i] as u64;
                    // Insertion sort, farthest deepest, so the nearest child pops first.
                    let mut k = len;
                    while k > base && stack[k - 1] < entry {
                        stack[k] = stack[k - 1];
                        k -= 1;
                    }
                    stack[k] = entry;
                    len += 1;
                }
            }
            // Next entry that starts before the closest hit so far.
            loop {
                if len == 0 {
                    return;
                }
                len -= 1;
                let entry = stack[len];
                if f32::from_bits((entry >> 32) as u32) <= t_max * FAR_SCALE {
                    current = entry as u32;
                    break;
                }
            }
        }
    }

    /// Any-hit traversal: `test(leaf)` says whether a primitive of the leaf blocks the ray;
    /// returns at the first that does.
    #[inline]
    pub fn any(&self, ray: &Ray, test: impl FnMut(Range<usize>) -> bool) -> bool {
        if self.stack_need <= SMALL_STACK {
            self.any_with::<SMALL_STACK>(ray, test)
        } else if self.stack_need <= SHALLOW_STACK {
            self.any_with::<SHALLOW_STACK>(ray, test)
        } else {
            self.any_with::<DEEP_STACK>(ray, test)
        }
    }

    fn any_with<const N: usize>(
        &self,
        ray: &Ray,
        mut test: impl FnMut(Range<usize>) -> bool,
    ) -> bool {
        let r = WideRay::new(ray);
        let mut stack = [0u32; N];
        let mut len = 0;
        let mut current = 0u32;
        loop {
            if current & LEAF != 0 {
                if test(leaf_range(current)) {
                    return true;
                }
            } else {
                let node = &self.nodes[current as usize];
                let (mut mask, _) = Self::enter(node, &r, ray.t_max);
                while mask != 0 {
                    let i = mask.trailing_zeros() as usize;
                    mask &= mask - 1;
                    stack[len] = node.child[i];
                    len += 1;
                }
            }
            if len == 0 {
                return false;
            }
            len -= 1;
            current = stack[len];
        }
    }
}

/// The primitives of leaf reference `c`.
#[inline(always)]
fn leaf_range(c: u32) -> Range<usize> {
    let first = ((c & !LEAF) >> COUNT_BITS) as usize;
    first..first + (c & ((1 << COUNT_BITS) - 1)) as usize
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::primitive::{NONE, Primitive, Shape};
    use crate::geometry::sphere::Sphere;
    use crate::rng::Rng;
    use glam::Vec3;
    use obvhs::{BvhBuildParams, cwbvh::builder::build_cwbvh};

    fn random_scene(rng: &mut Rng, n: usize, scale: f32) -> Vec<Primitive> {
        let v = |rng: &mut Rng| Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
        (0..n)
            .filter_map(|i| {
                let c = v(rng) * 10.0 * scale;
                let shape = if i % 4 == 0 {
                    Shape::Sphere(Sphere::new(c, 0.2 * scale))
                } else {
                    Shape::triangle([c, c + (v(rng) - 0.5) * scale, c + (v(rng) - 0.5) * scale])?
                };
                Some(Primitive {
                    shape,
                    material: 0,
                    light: NONE,
                    attr: NONE,
                })
            })
            .collect()
    }

    /// (CWBVH, decoded copy, primitives in leaf order) for a random scene.
    fn build(rng: &mut Rng, n: usize, scale: f32) -> (CwBvh, WideBvh, Vec<Primitive>) {
        let prims = random_scene(rng, n, scale);
        let cw = build_cwbvh(
            &prims,
            BvhBuildParams::medium_build(),
            &mut std::time::Duration::default(),
        );
        let ordered = cw
            .primitive_indices
            .iter()
            .map(|&i| prims[i as usize])
            .collect();
        let wide = WideBvh::from_cwbvh(&cw);
        (cw, wide, ordered)
    }

    /// Box `c` of `node`, as (min, max).
    fn child_box(node: &WideNode, c: usize) -> (Vec3, Vec3) {
        let p = |k: usize| node.planes[k][c / 4][c % 4];
        (Vec3::new(p(0), p(1), p(2)), Vec3::new(p(3), p(4), p(5)))
    }

    /// Every decoded child box holds the quantized one it came from and every primitive below it.
    #[test]
    fn decoded_boxes_hold_their_subtrees() {
        let mut rng = Rng::new(21, 0, 0);
        for scale in [1e-3f32, 1.0, 1e3] {
            let (cw, wide, prims) = build(&mut rng, 2000, scale);
            assert_eq!(wide.nodes.len(), cw.nodes.len());
            let mut todo = vec![0usize];
            let mut leaves = 0;
            while let Some(i) = todo.pop() {
                let node = &wide.nodes[i];
                for c in 0..8 {
                    let r = node.child[c];
                    if r == EMPTY {
                        assert!(cw.nodes[i].is_child_empty(c));
                        continue;
                    }
                    let (lo, hi) = child_box(node, c);
                    let q = cw.nodes[i].child_aabb(c);
                    assert!(lo.cmple(Vec3::from(q.min)).all() && hi.cmpge(Vec3::from(q.max)).all());
                    // All primitives below this child.
                    let mut below = vec![r];
                    while let Some(r) = below.pop() {
                        if r & LEAF != 0 {
                            leaves += 1;
                            for p in &prims[leaf_range(r)] {
                                let (a, b) = p.shape.bounds();
                                assert!(
                                    lo.cmple(a).all() && hi.cmpge(b).all(),
                                    "{a} {b} outside {lo} {hi}"
                                );
                            }
                        } else {
                            below.extend(
                                wide.nodes[r as usize].child.iter().filter(|&&c| c != EMPTY),
                            );
                        }
                    }
                    if r & LEAF == 0 {
                        todo.push(r as usize);
                    }
                }
            }
            assert!(leaves > 500);
        }
    }

    /// Whether the ray meets the closed box within `[0, t_max]`, in f64 with the exact direction
    /// (the slab parameters are then exact to ~1e-16; a 1e-12 relative margin absorbs that).
    /// Axis-parallel rays on a box's plane are left out (`false`): their slab is 0/0.
    fn surely_enters(o: Vec3, d: Vec3, t_max: f32, lo: Vec3, hi: Vec3) -> bool {
        let (o, d, lo, hi) = (o.as_dvec3(), d.as_dvec3(), lo.as_dvec3(), hi.as_dvec3());
        let (mut near, mut far) = (0.0f64, t_max as f64);
        for a in 0..3 {
            if d[a] == 0.0 {
                if o[a] <= lo[a] || o[a] >= hi[a] {
                    return false;
                }
                continue;
            }
            let (t0, t1) = ((lo[a] - o[a]) / d[a], (hi[a] - o[a]) / d[a]);
            near = near.max(t0.min(t1));
            far = far.min(t0.max(t1));
        }
        near <= far - 1e-12 * far.abs()
    }

    /// The node test never drops a child the ray enters, even by a hair: random boxes, rays aimed
    /// at points on their edges and corners (where rounding decides), axis-parallel directions,
    /// origins on box faces, and short rays.
    #[test]
    fn node_test_keeps_every_entered_child() {
        let mut rng = Rng::new(4, 0, 0);
        let mut checked = 0;
        for _ in 0..60_000 {
            let mut node = WideNode {
                planes: [[Vec4::ZERO; 2]; 6],
                child: [0; 8],
            };
            let mut boxes = [(Vec3::ZERO, Vec3::ZERO); 8];
            for (c, b) in boxes.iter_mut().enumerate() {
                let a = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 4.0 - 2.0;
                let e = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 2.0;
                *b = (a, a + e);
                for k in 0..3 {
                    node.planes[k][c / 4][c % 4] = a[k];
                    node.planes[3 + k][c / 4][c % 4] = (a + e)[k];
                }
            }
            let mut d = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 2.0 - 1.0;
            match rng.next_u32() % 4 {
                0 => d[(rng.next_u32() % 3) as usize] = 0.0,
                1 => d[(rng.next_u32() % 3) as usize] = -1e-30,
                _ => {}
            }
            let mut o = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 6.0 - 3.0;
            if rng.next_u32().is_multiple_of(2) {
                // Aimed at a point of a random box, keeping the zeroed component.
                let (lo, hi) = boxes[(rng.next_u32() % 8) as usize];
                let mut aim =
                    lo + Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * (hi - lo);
                // Onto two or three of its planes: an edge or a corner.
                for k in 0..3 {
                    if k != (rng.next_u32() % 4) as usize {
                        aim[k] = if rng.next_u32().is_multiple_of(2) {
                            lo[k]
                        } else {
                            hi[k]
                        };
                    }
                }
                let aim = aim - o;
                d = Vec3::select(
                    d.cmpeq(Vec3::ZERO) | d.abs().cmplt(Vec3::splat(1e-20)),
                    d,
                    aim,
                );
            }
            let d = d.normalize();
            if rng.next_u32().is_multiple_of(2) {
                // On a face of box 0.
                let k = (rng.next_u32() % 3) as usize;
                o[k] = boxes[0].0[k];
            }
            let t_max = if rng.next_u32().is_multiple_of(2) {
                f32::INFINITY
            } else {
                3.0 * rng.next_f32()
            };
            let (mask, _) = WideBvh::enter(&node, &WideRay::new(&Ray { o, d, t_max }), t_max);
            for (c, (lo, hi)) in boxes.iter().enumerate() {
                if surely_enters(o, d, t_max, *lo, *hi) {
                    checked += 1;
                    assert!(
                        mask & 1 << c != 0,
                        "dropped box {c} {lo} {hi} for o {o} d {d} t_max {t_max}"
                    );
                }
            }
        }
        assert!(checked > 10_000, "{checked}");
    }

    /// Every stack size a tree may get gives the same closest hits and occlusion as the deepest:
    /// the 64-entry stack on a 3000-primitive tree, the 16-entry one on a 40-primitive tree.
    #[test]
    fn stack_sizes_agree() {
        let mut rng = Rng::new(8, 0, 0);
        for (n, capacity) in [(3000, SHALLOW_STACK), (40, SMALL_STACK)] {
            let (_, wide, prims) = build(&mut rng, n, 1.0);
            assert!(wide.stack_need <= capacity && wide.stack_need > 1);
            let hits = |ray: &Ray, stack: usize| {
                let tri = crate::geometry::triangle::TriangleRay::new(ray);
                let mut best = None;
                let test = |slots: Range<usize>, t_max: f32| {
                    let mut closer = None;
                    for id in slots {
                        if let Some(h) = prims[id].shape.intersect_t(&Ray { t_max, ..*ray }, &tri)
                            && h.t < closer.unwrap_or(t_max)
                        {
                            closer = Some(h.t);
                            best = Some((id, h.t));
                        }
                    }
                    closer
                };
                match stack {
                    SMALL_STACK => wide.closest_with::<SMALL_STACK>(ray, test),
                    SHALLOW_STACK => wide.closest_with::<SHALLOW_STACK>(ray, test),
                    _ => wide.closest_with::<DEEP_STACK>(ray, test),
                }
                let any = |slots: Range<usize>| {
                    prims[slots]
                        .iter()
                        .any(|p| p.shape.intersect_t(ray, &tri).is_some())
                };
                let blocked = match stack {
                    SMALL_STACK => wide.any_with::<SMALL_STACK>(ray, any),
                    SHALLOW_STACK => wide.any_with::<SHALLOW_STACK>(ray, any),
                    _ => wide.any_with::<DEEP_STACK>(ray, any),
                };
                (best, blocked)
            };
            let mut found = 0;
            for i in 0..3000 {
                // From anywhere, towards a random primitive.
                let o = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 12.0 - 1.0;
                let target = match prims[(rng.next_u32() as usize) % prims.len()].shape {
                    Shape::Triangle { v, .. } => (v[0] + v[1] + v[2]) / 3.0,
                    Shape::Sphere(s) => s.center,
                    Shape::Disk(d) => d.center,
                    Shape::Cylinder(c) => c.p0,
                };
                let d = (target - o).normalize();
                let t_max = if i % 2 == 0 { f32::INFINITY } else { 6.0 };
                let ray = Ray { o, d, t_max };
                let small = hits(&ray, capacity);
                assert_eq!(small, hits(&ray, DEEP_STACK));
                found += small.0.is_some() as usize;
            }
            assert!(found > 2000, "{n} primitives: {found} hits");
        }
    }
}
