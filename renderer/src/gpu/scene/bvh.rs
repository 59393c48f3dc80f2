//! The BVH as the GPU traverses it: the obvhs CWBVH goes up as it is (its depth checked against
//! the traversal stack), the optional BVH2 is built here and packed into rows.
//! WGSL twin: `gpu/bvh2.wgsl` (the BVH2 rows; `geometry/bvh.wgsl` reads obvhs's own node layout).

use crate::geometry::primitive::Primitive;
use crate::gpu::GpuError;
use obvhs::cwbvh::CwBvh;

/// Entries of the CWBVH traversal stack (`BVH_STACK_SIZE` in `geometry/bvh.wgsl`), one node group per
/// level: obvhs's own `TRAVERSAL_STACK_SIZE`, which its builder keeps every tree's depth under.
pub const CWBVH_STACK_SIZE: usize = 32;

/// Entries of the BVH2 traversal stack (`BVH2_STACK_SIZE` in `gpu/bvh2.wgsl`), the deepest BVH2 the
/// upload accepts: near-first traversal defers at most one node per level.
pub const BVH2_STACK_SIZE: usize = 64;

/// Levels below the CWBVH's root (0 for a lone root), as obvhs's validation counts them.
fn cwbvh_depth(bvh: &CwBvh) -> usize {
    let mut depth = 0;
    let mut todo = vec![(0usize, 0usize)];
    while let Some((i, d)) = todo.pop() {
        depth = depth.max(d);
        let Some(node) = bvh.nodes.get(i) else {
            continue;
        };
        for ch in 0..8 {
            if !node.is_child_empty(ch) && !node.is_leaf(ch) {
                todo.push((node.child_node_index(ch) as usize, d + 1));
            }
        }
    }
    depth
}

/// Fails if the CWBVH is too deep for the GPU's traversal stack (obvhs never builds one; the
/// traversal would otherwise drop nodes silently).
pub(super) fn check_cwbvh(bvh: &CwBvh) -> Result<(), GpuError> {
    let depth = cwbvh_depth(bvh);
    if depth >= CWBVH_STACK_SIZE {
        return Err(GpuError::TooLarge(format!(
            "the CWBVH is {depth} levels deep, its GPU traversal holds {CWBVH_STACK_SIZE}"
        )));
    }
    Ok(())
}

/// Builds an obvhs BVH2 over `prims` (the CWBVH's leaf order) and packs it as `gpu/bvh2.wgsl` reads
/// it: node i as two `vec4<u32>` (min.xyz, prim_count) and (max.xyz, first), then the leaves'
/// primitive ids, four per row. A leaf's `first` becomes the word index of its ids, so the shader
/// needs no offset uniform (and the bind group layout stays the CWBVH's).
pub(super) fn bvh2_rows(prims: &[Primitive]) -> Result<Vec<[u32; 4]>, GpuError> {
    use obvhs::{BvhBuildParams, bvh2::builder::build_bvh2};
    let bvh = build_bvh2(
        prims,
        BvhBuildParams::medium_build(),
        &mut std::time::Duration::default(),
    );
    // Depth of the tree, iteratively (it may be deep enough to matter).
    let mut depth = 0;
    let mut todo = vec![(0usize, 1usize)];
    while let Some((i, d)) = todo.pop() {
        depth = depth.max(d);
        let n = &bvh.nodes[i];
        if n.prim_count == 0 {
            todo.push((n.first_index as usize, d + 1));
            todo.push((n.first_index as usize + 1, d + 1));
        }
    }
    if depth > BVH2_STACK_SIZE {
        return Err(GpuError::TooLarge(format!(
            "the BVH2 is {depth} levels deep, its GPU traversal holds {BVH2_STACK_SIZE}"
        )));
    }
    let ids_word = 8 * bvh.nodes.len() as u32;
    let mut rows = Vec::with_capacity(2 * bvh.nodes.len() + bvh.primitive_indices.len() / 4 + 1);
    for n in &bvh.nodes {
        let first = if n.prim_count == 0 {
            n.first_index
        } else {
            ids_word + n.first_index
        };
        let (lo, hi) = (n.aabb.min, n.aabb.max);
        rows.push([lo.x.to_bits(), lo.y.to_bits(), lo.z.to_bits(), n.prim_count]);
        rows.push([hi.x.to_bits(), hi.y.to_bits(), hi.z.to_bits(), first]);
    }
    for ids in bvh.primitive_indices.chunks(4) {
        let mut row = [0u32; 4];
        row[..ids.len()].copy_from_slice(ids);
        rows.push(row);
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Accel, Shape};

    #[test]
    fn cwbvh_depth_grows_with_the_scene_and_fits_the_stack() {
        // A grid of triangles: enough for several levels.
        let tri = |x: f32, y: f32| Primitive {
            shape: Shape::Triangle {
                v: [
                    glam::Vec3::new(x, y, 0.0),
                    glam::Vec3::new(x + 1.0, y, 0.0),
                    glam::Vec3::new(x, y + 1.0, 0.0),
                ],
                n: glam::Vec3::Z,
            },
            material: 0,
            light: crate::geometry::primitive::NONE,
            attr: crate::geometry::primitive::NONE,
        };
        let depth_of = |n: usize| {
            let prims = (0..n * n)
                .map(|i| tri((i % n) as f32, (i / n) as f32))
                .collect();
            let accel = Accel::new(prims);
            let bvh = accel.cwbvh().expect("a BVH");
            check_cwbvh(bvh).unwrap();
            // Counted as obvhs's own validation counts it.
            let obvhs_depth = bvh.validate(accel.primitives(), true).max_depth as usize;
            assert_eq!(cwbvh_depth(bvh), obvhs_depth, "{n}²");
            obvhs_depth
        };
        let (small, large) = (depth_of(3), depth_of(64));
        assert!(large > small, "{small} {large}");
    }
}
