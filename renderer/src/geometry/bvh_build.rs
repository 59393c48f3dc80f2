//! Building the CWBVH ([`super::Accel`]'s) and reordering the primitives in place into its leaf
//! order, within a memory bound for large meshes.
//!
//! obvhs's builder needs about 300 bytes of temporaries per primitive at its peak (a BVH2 of
//! 48-byte nodes, PLOC's two node buffers and Morton codes, then 56 bytes of bvh2→CWBVH
//! decisions per BVH2 node and a CWBVH node buffer sized by the primitive count), on top of the
//! 64-byte primitives the scene holds. From [`CHUNKED_FROM`] primitives on, the build is
//! therefore chunked: the primitives whose boxes are large against the scene's are set aside, the
//! rest sorted by the Morton code of their box centres and split into [`CHUNKS`] ranges of equal
//! count, and obvhs builds one CWBVH per range, one after the other, so its temporaries scale
//! with an eighth of the scene. A top tree, which obvhs builds over the ranges' roots' children
//! and the large primitives, joins them ([`join`]). Smaller scenes are built whole, exactly as
//! obvhs builds them.
//!
//! The price of the cuts between ranges: on the 1M-triangle sphere of `renderer/tests/mesh_scale.rs`
//! the chunked tree costs about 4% more BVH nodes per ray than a whole build (surface-area
//! estimate; callgrind: 4.3% more instructions per rendered sample), about the same with
//! 2 ranges as with 8 (the first cut costs it all), and neither deeper opening of the ranges'
//! roots nor more reinsertion won it back.

use super::primitive::Primitive;
use glam::Vec3A;
use obvhs::aabb::Aabb;
use obvhs::cwbvh::CwBvh;
use obvhs::cwbvh::builder::build_cwbvh;
use obvhs::cwbvh::node::CwBvhNode;
use obvhs::{Boundable, BvhBuildParams};
use std::ops::Range;
use std::time::Duration;

/// From this many primitives on the tree is built in [`CHUNKS`] ranges (below, obvhs's
/// temporaries are under 80 MB, and the tree stays exactly obvhs's).
pub const CHUNKED_FROM: usize = 1 << 18;

/// Ranges of a chunked build: the root node's eight children.
pub const CHUNKS: usize = 8;

/// Builds the CWBVH over `prims` and reorders them into its leaf order, so that its leaves index
/// `prims` directly; its `primitive_indices` give each slot's index in the original order.
pub fn build(prims: &mut [Primitive]) -> CwBvh {
    if prims.len() < CHUNKED_FROM {
        build_whole(prims)
    } else {
        build_chunked(prims)
    }
}

/// obvhs's build of the whole slice, its node buffer trimmed (obvhs reserves one node per
/// primitive, about eight times what the tree needs).
fn build_whole(prims: &mut [Primitive]) -> CwBvh {
    let mut bvh = build_cwbvh(
        prims,
        BvhBuildParams::medium_build(),
        &mut Duration::default(),
    );
    bvh.nodes.shrink_to_fit();
    gather(prims, &bvh.primitive_indices);
    bvh
}

/// The chunked build (see the module doc), for any size (the tests use it on small scenes).
pub(super) fn build_chunked(prims: &mut [Primitive]) -> CwBvh {
    let n = prims.len();
    let large = large_primitives(prims);
    let order = chunk_order(prims, &large);
    let small = n - large.iter().filter(|&&l| l).count();
    drop(large);
    gather(prims, &order);
    let ranges: Vec<Range<usize>> = (0..CHUNKS)
        .map(|c| c * small / CHUNKS..(c + 1) * small / CHUNKS)
        .filter(|r| !r.is_empty())
        .collect();
    let parts: Vec<CwBvh> = ranges
        .iter()
        .map(|r| build_whole(&mut prims[r.clone()]))
        .collect();
    join(prims, &order, &parts, &ranges, small..n)
}

/// Which primitives are large: boxes of more than [`LARGE_AREA`] of the scene box's surface
/// (at most `n / CHUNKS` of them, the largest). In a range of small ones, one of them would
/// stretch that range's box over much of the scene (a floor under a mesh: every ray aimed at the
/// floor would then enter that range's subtree), so they are leaves of the top tree instead,
/// near the root, where a whole build puts them too.
fn large_primitives(prims: &[Primitive]) -> Vec<bool> {
    let boxes = || prims.iter().map(|p| p.aabb());
    let scene = boxes().fold(Aabb::empty(), |a, b| a.union(&b));
    let areas: Vec<f32> = boxes().map(|b| b.half_area()).collect();
    let mut threshold = scene.half_area() * LARGE_AREA;
    let cap = prims.len() / CHUNKS;
    if areas.iter().filter(|&&a| a > threshold).count() > cap {
        // The cap-th largest area: strictly above it are fewer than `cap`.
        let mut sorted = areas.clone();
        let (_, nth, _) = sorted.select_nth_unstable_by(cap, |a, b| b.total_cmp(a));
        threshold = threshold.max(*nth);
    }
    areas.iter().map(|&a| a > threshold).collect()
}

/// A primitive whose box has more than this fraction of the scene box's surface area is large:
/// an eighth of the scene's extent in two dimensions, where a range's box spans about half.
const LARGE_AREA: f32 = 1.0 / 64.0;

/// The order of the chunked build: the small primitives by the Morton code of their box centres
/// (in the small ones' centre bounds; ties by index), then the large ones in their own order.
fn chunk_order(prims: &[Primitive], large: &[bool]) -> Vec<u32> {
    let centres = || prims.iter().map(|p| p.aabb().center());
    let (lo, hi) = centres().zip(large).filter(|(_, l)| !**l).fold(
        (Vec3A::splat(f32::INFINITY), Vec3A::splat(f32::NEG_INFINITY)),
        |(lo, hi), (c, _)| (lo.min(c), hi.max(c)),
    );
    // 21 bits per axis; a flat axis maps to 0.
    let scale = (hi - lo).to_array().map(|e| {
        if e > 0.0 {
            ((1u32 << 21) - 1) as f64 / e as f64
        } else {
            0.0
        }
    });
    let lo = lo.to_array();
    // The key: bit 63 set for large primitives, below it the 63-bit Morton code.
    let mut keyed: Vec<(u64, u32)> = centres()
        .zip(large)
        .enumerate()
        .map(|(i, (c, &l))| {
            if l {
                return (1 << 63, i as u32);
            }
            let c = c.to_array();
            let q = |a: usize| ((c[a] - lo[a]) as f64 * scale[a]).clamp(0.0, 2097151.0) as u32;
            (
                spread_bits(q(0)) << 2 | spread_bits(q(1)) << 1 | spread_bits(q(2)),
                i as u32,
            )
        })
        .collect();
    keyed.sort_unstable();
    keyed.into_iter().map(|(_, i)| i).collect()
}

/// The low 21 bits of `x`, two zero bits after each.
fn spread_bits(x: u32) -> u64 {
    let mut x = (x & 0x1f_ffff) as u64;
    x = (x | x << 32) & 0x001f_0000_0000_ffff;
    x = (x | x << 16) & 0x001f_0000_ff00_00ff;
    x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
    x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
    x = (x | x << 2) & 0x1249_2492_4924_9249;
    x
}

/// Reorders `prims` in place so that slot `i` holds what was at `from[i]` (`from` a permutation),
/// following its cycles: no second copy of the primitives.
fn gather(prims: &mut [Primitive], from: &[u32]) {
    debug_assert_eq!(prims.len(), from.len());
    let mut done = vec![false; prims.len()];
    for start in 0..prims.len() {
        if done[start] {
            continue;
        }
        let first = prims[start];
        let mut i = start;
        loop {
            done[i] = true;
            let next = from[i] as usize;
            if next == start {
                prims[i] = first;
                break;
            }
            prims[i] = prims[next];
            i = next;
        }
    }
}

/// A leaf of the top tree of a chunked build.
#[derive(Clone, Copy)]
enum Item {
    /// Node `local` of part `part`: the part's root, or a node below it whose ancestors in the
    /// part are dropped.
    Node { part: usize, local: usize },
    /// The large primitive at this offset in the large range.
    Large(usize),
}

/// Where a node of the joined tree comes from.
#[derive(Clone, Copy)]
enum Source {
    /// Node `t` of the top tree.
    Top(usize),
    /// A leaf of the top tree.
    Item(Item),
}

/// How many levels of each part's tree the top tree replaces: a part's node this close to its
/// root whose children are all internal is dropped, and its children become items of the top
/// tree instead (in which obvhs's surface-area costs place them). 2 and 3 were measured no better
/// on the 1M-triangle sphere.
const OPEN_LEVELS: usize = 1;

/// One tree over `parts` (part `c` built over the primitive slots `ranges[c]`) and the large
/// primitives in `prims[large]`. obvhs builds a top tree whose leaves (one item each) are the
/// parts' nodes [`OPEN_LEVELS`] below their roots (or above, where a node has leaf children),
/// and the large primitives: the parts' nodes above those are dropped, so the joined tree is no
/// deeper than a whole build, and the top tree's surface-area costs decide how the subtrees and
/// the large primitives share its nodes. Each subtree's leaf becomes an internal child holding
/// that subtree's root; the parts' other nodes follow, in their order, their indices moved. The
/// large primitives are reordered to the top tree's leaf order. `order[slot]` is the original
/// index of what `gather` moved into `slot` before the parts were built.
fn join(
    prims: &mut [Primitive],
    order: &[u32],
    parts: &[CwBvh],
    ranges: &[Range<usize>],
    large: Range<usize>,
) -> CwBvh {
    let mut items = Vec::new();
    let mut boxes = Vec::new();
    // Per part: for each node, whether it goes into the part's body (neither dropped nor an
    // item); a node's children are consecutive and all in the body or all not, so they stay
    // consecutive there.
    let mut in_body: Vec<Vec<bool>> = parts.iter().map(|p| vec![true; p.nodes.len()]).collect();
    for (c, part) in parts.iter().enumerate() {
        let mut todo = vec![(0usize, 0usize)];
        while let Some((local, depth)) = todo.pop() {
            in_body[c][local] = false;
            let node = &part.nodes[local];
            let children = (0..8).filter(|&s| !node.is_child_empty(s));
            if depth < OPEN_LEVELS && children.clone().all(|s| !node.is_leaf(s)) {
                todo.extend(children.map(|s| (node.child_node_index(s) as usize, depth + 1)));
            } else {
                items.push(Item::Node { part: c, local });
                boxes.push(subtree_box(part, local, &prims[ranges[c].clone()]));
            }
        }
    }
    for (i, p) in prims[large.clone()].iter().enumerate() {
        items.push(Item::Large(i));
        boxes.push(p.aabb());
    }
    let params = BvhBuildParams {
        max_prims_per_leaf: 1,
        ..BvhBuildParams::medium_build()
    };
    let top = build_cwbvh(&boxes, params, &mut Duration::default());
    drop(boxes);
    let node_count = top.nodes.len() + parts.iter().map(|p| p.nodes.len()).sum::<usize>();
    let mut nodes = Vec::with_capacity(node_count);
    nodes.push(CwBvhNode::default());
    // Per part, once its body is copied: each node's index there (for body nodes; one entry
    // more, for an index one past the end).
    let mut moved_to: Vec<Option<Vec<u32>>> = vec![None; parts.len()];
    // The large primitives (offsets in `large`) in the order the joined tree's leaves hold them.
    let mut large_order: Vec<u32> = Vec::with_capacity(large.len());
    let mut todo = vec![(0, Source::Top(0))];
    while let Some((at, source)) = todo.pop() {
        let (c, local) = match source {
            Source::Item(Item::Node { part, local }) => (part, local),
            Source::Item(Item::Large(_)) => unreachable!("large primitives are leaves"),
            Source::Top(t) => {
                let old = &top.nodes[t];
                let mut node = *old;
                node.primitive_base_idx = (large.start + large_order.len()) as u32;
                // Internal children in slot order, as their indices are consecutive.
                let mut internal = Vec::new();
                let mut leaves = 0;
                for s in 0..8 {
                    if old.is_child_empty(s) {
                        continue;
                    }
                    if !old.is_leaf(s) {
                        internal.push(Source::Top(old.child_node_index(s) as usize));
                        continue;
                    }
                    let item = top.primitive_indices[old.child_primitives(s).0 as usize];
                    match items[item as usize] {
                        Item::Large(i) => {
                            // A leaf of one primitive at offset `leaves` from the node's base.
                            node.child_meta[s] = 0b0010_0000 | leaves;
                            leaves += 1;
                            large_order.push(i as u32);
                        }
                        subtree => {
                            node.imask |= 1 << s;
                            node.child_meta[s] = (24 + s as u8) | 0b0010_0000;
                            internal.push(Source::Item(subtree));
                        }
                    }
                }
                let base = nodes.len();
                node.child_base_idx = base as u32;
                nodes[at] = node;
                nodes.resize(base + internal.len(), CwBvhNode::default());
                todo.extend(internal.into_iter().enumerate().map(|(k, s)| (base + k, s)));
                continue;
            }
        };
        // The body of part c is copied when the first of its items is placed.
        let part = &parts[c];
        let to = moved_to[c].get_or_insert_with(|| {
            let mut next = nodes.len() as u32;
            let to: Vec<u32> = in_body[c]
                .iter()
                .chain([&true])
                .map(|&b| {
                    next += b as u32;
                    next - b as u32
                })
                .collect();
            nodes.extend(
                (0..part.nodes.len())
                    .filter(|&l| in_body[c][l])
                    .map(|l| moved(part.nodes[l], &to, ranges[c].start)),
            );
            to
        });
        nodes[at] = moved(part.nodes[local], to, ranges[c].start);
    }
    gather(&mut prims[large.clone()], &large_order);
    let mut primitive_indices = Vec::with_capacity(prims.len());
    for (r, part) in ranges.iter().zip(parts) {
        primitive_indices.extend(
            part.primitive_indices
                .iter()
                .map(|&i| order[r.start + i as usize]),
        );
    }
    primitive_indices.extend(large_order.iter().map(|&i| order[large.start + i as usize]));
    CwBvh {
        nodes,
        primitive_indices,
        total_aabb: top.total_aabb,
        exact_node_aabbs: None,
        uses_spatial_splits: false,
    }
}

/// A part's node with its children's index moved as `to` says and its primitives' by `first`
/// (the part's first slot).
fn moved(mut node: CwBvhNode, to: &[u32], first: usize) -> CwBvhNode {
    // A node without internal children may hold any index up to one past the part's last.
    node.child_base_idx = to[node.child_base_idx as usize];
    node.primitive_base_idx += first as u32;
    node
}

/// The box of the primitives under node `local` of `part` (built over `prims`).
fn subtree_box(part: &CwBvh, local: usize, prims: &[Primitive]) -> Aabb {
    let mut total = Aabb::empty();
    let mut todo = vec![local];
    while let Some(i) = todo.pop() {
        let node = &part.nodes[i];
        for s in 0..8 {
            if node.is_child_empty(s) {
            } else if node.is_leaf(s) {
                let (first, count) = node.child_primitives(s);
                for p in &prims[first as usize..(first + count) as usize] {
                    total = total.union(&p.aabb());
                }
            } else {
                todo.push(node.child_node_index(s) as usize);
            }
        }
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::primitive::{NONE, Shape};
    use crate::rng::Rng;
    use glam::Vec3;

    #[test]
    fn spread_bits_interleaves() {
        assert_eq!(spread_bits(0b111), 0b1001001);
        assert_eq!(spread_bits(0x1f_ffff).count_ones(), 21);
        assert_eq!(spread_bits(1 << 20), 1 << 60);
    }

    #[test]
    fn gather_applies_the_permutation() {
        let mut rng = Rng::new(3, 0, 0);
        let prims: Vec<Primitive> = (0..100)
            .map(|i| Primitive {
                shape: Shape::Triangle {
                    v: [Vec3::splat(i as f32); 3],
                    n: Vec3::Z,
                },
                material: i,
                light: NONE,
                attr: NONE,
            })
            .collect();
        let mut from: Vec<u32> = (0..100).collect();
        for i in (1..100).rev() {
            from.swap(i, (rng.next_f32() * (i + 1) as f32) as usize % (i + 1));
        }
        let mut moved = prims.clone();
        gather(&mut moved, &from);
        for (p, &f) in moved.iter().zip(&from) {
            assert_eq!(p.material, prims[f as usize].material);
        }
    }
}
