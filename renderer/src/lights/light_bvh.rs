//! Light selection that knows the receiving point: a BVH over the emitters' [`LightBounds`]
//! (after pbrt-v4's `BVHLightSampler`). Sampling descends from the root, choosing each child in
//! proportion to its importance at the receiver `(p, n)` and re-using one uniform number by
//! rescaling it; the probability of a given light (for MIS) re-descends along its bit trail, the
//! path from the root, computing the same importances in the same order, so [`LightBvh::sample`]
//! and [`LightBvh::pmf`] agree bit for bit.
//!
//! The lights at infinity have no bounds: one of them is chosen uniformly with probability
//! `n_inf / (n_inf + 1)` (`n_inf / n_inf` where there are no finite lights), the tree otherwise.
//! Lights without positive power are left out (pmf 0), as power selection leaves them.
//! WGSL twin: `lights/light_bvh.wgsl` (its node and trail records: [`LightBvh::append_tables`]).

use super::Light;
use super::light_bounds::{LightBounds, split_cost};
use glam::Vec3;

/// Buckets per axis of the split search.
const BUCKETS: usize = 12;
/// Depth from which nodes are split at the median instead of by cost: the median halves the
/// count, so every trail fits in [`MAX_DEPTH`] bits for up to 2³² lights.
const COST_DEPTH: u32 = 32;
/// Bits of a bit trail.
const MAX_DEPTH: u32 = 64;

/// One node: its bounds, and its second child (the first follows it) or its light.
#[derive(Clone, Copy, Debug)]
pub struct LightBvhNode {
    /// Bounds of the lights below.
    pub bounds: LightBounds,
    /// Index of the second child (interior) or of the light in the scene's list (leaf).
    pub child_or_light: u32,
    /// Whether this is a leaf (one light).
    pub leaf: bool,
}

/// The light BVH of a scene.
#[derive(Clone, Debug, Default)]
pub struct LightBvh {
    /// Nodes, the root first, each interior node followed by its first child.
    nodes: Vec<LightBvhNode>,
    /// Indices of the lights at infinity with power.
    infinite: Vec<u32>,
    /// Per light of the scene: the path from the root to its leaf, bit k the branch taken at
    /// depth k (1: second child); `None` for lights not in the tree.
    trails: Vec<Option<u64>>,
}

impl LightBvh {
    /// Builds the tree over `lights`; `None` if nothing has power (the power sampler's rule).
    pub fn new(lights: &[Light]) -> Option<LightBvh> {
        let mut items: Vec<(u32, LightBounds)> = Vec::new();
        let mut infinite = Vec::new();
        for (i, l) in lights.iter().enumerate() {
            if l.is_infinite() {
                let phi = l.power();
                if phi > 0.0 && phi.is_finite() {
                    infinite.push(i as u32);
                }
            } else if let Some(b) = LightBounds::of(l) {
                items.push((i as u32, b));
            }
        }
        if items.is_empty() && infinite.is_empty() {
            return None;
        }
        let mut bvh = LightBvh {
            nodes: Vec::with_capacity(2 * items.len()),
            infinite,
            trails: vec![None; lights.len()],
        };
        if !items.is_empty() {
            bvh.build(&mut items, 0, 0);
        }
        Some(bvh)
    }

    /// The nodes (root first).
    pub fn nodes(&self) -> &[LightBvhNode] {
        &self.nodes
    }

    /// The lights at infinity that are sampled apart.
    pub fn infinite(&self) -> &[u32] {
        &self.infinite
    }

    /// Light `i`'s bit trail, `None` if the tree does not hold it.
    pub fn trail(&self, i: usize) -> Option<u64> {
        self.trails.get(i).copied().flatten()
    }

    /// Builds the subtree of `items` at depth `depth` whose trail so far is `trail`; returns its
    /// node index.
    fn build(&mut self, items: &mut [(u32, LightBounds)], depth: u32, trail: u64) -> usize {
        let index = self.nodes.len();
        if let [(light, bounds)] = items {
            self.trails[*light as usize] = Some(trail);
            self.nodes.push(LightBvhNode {
                bounds: *bounds,
                child_or_light: *light,
                leaf: true,
            });
            return index;
        }
        let bounds = items[1..].iter().fold(items[0].1, |a, (_, b)| a.union(b));
        let mid = split(items, &bounds, depth);
        // A placeholder until the children are built.
        self.nodes.push(LightBvhNode {
            bounds,
            child_or_light: 0,
            leaf: false,
        });
        let (a, b) = items.split_at_mut(mid);
        self.build(a, depth + 1, trail);
        let second = self.build(b, depth + 1, trail | (1u64 << depth));
        self.nodes[index].child_or_light = second as u32;
        index
    }

    /// Probability of choosing the lights at infinity as a whole.
    #[inline]
    fn p_infinite(&self) -> f32 {
        let n = self.infinite.len() as f32;
        n / (n + if self.nodes.is_empty() { 0.0 } else { 1.0 })
    }

    /// The children of the interior node `node` (at `index`) and the probability of descending
    /// into each from a receiver at `(p, n)`; `None` where neither can reach `p`. One function
    /// for [`LightBvh::sample`] and [`LightBvh::pmf`], so that the two multiply the same numbers.
    #[inline]
    fn children(
        &self,
        index: usize,
        node: &LightBvhNode,
        p: Vec3,
        n: Vec3,
    ) -> Option<[(usize, f32); 2]> {
        let (c0, c1) = (index + 1, node.child_or_light as usize);
        let w0 = self.nodes[c0].bounds.importance(p, n);
        let w1 = self.nodes[c1].bounds.importance(p, n);
        if !positive(w0 + w1) {
            return None;
        }
        Some([(c0, w0 / (w0 + w1)), (c1, w1 / (w0 + w1))])
    }

    /// Chooses a light for a receiver at `p` with normal `n` (zero: none) from `u ∈ [0, 1)`:
    /// `(index, probability)`, `None` where no light can reach `p`.
    pub fn sample(&self, p: Vec3, n: Vec3, u: f32) -> Option<(usize, f32)> {
        let p_inf = self.p_infinite();
        if u < p_inf {
            let k =
                ((u / p_inf * self.infinite.len() as f32) as usize).min(self.infinite.len() - 1);
            return Some((
                self.infinite[k] as usize,
                p_inf / self.infinite.len() as f32,
            ));
        }
        let root = self.nodes.first()?;
        let mut u = ((u - p_inf) / (1.0 - p_inf)).min(crate::sampling::ONE_MINUS_EPSILON);
        let mut pmf = 1.0 - p_inf;
        let mut node = root;
        let mut index = 0;
        while !node.leaf {
            let [(c0, p0), (c1, p1)] = self.children(index, node, p, n)?;
            if u < p0 {
                u = (u / p0).min(crate::sampling::ONE_MINUS_EPSILON);
                pmf *= p0;
                index = c0;
            } else {
                u = ((u - p0) / (1.0 - p0)).min(crate::sampling::ONE_MINUS_EPSILON);
                pmf *= p1;
                index = c1;
            }
            node = &self.nodes[index];
        }
        // A lone light is chosen only where it can reach p (inside the tree the importances did).
        if index == 0 && !positive(root.bounds.importance(p, n)) {
            return None;
        }
        Some((node.child_or_light as usize, pmf))
    }

    /// Probability that [`LightBvh::sample`] at `(p, n)` chooses light `i`.
    pub fn pmf(&self, p: Vec3, n: Vec3, i: usize) -> f32 {
        if self.infinite.contains(&(i as u32)) {
            return self.p_infinite() / self.infinite.len() as f32;
        }
        let (Some(mut trail), Some(root)) = (self.trail(i), self.nodes.first()) else {
            return 0.0;
        };
        let mut pmf = 1.0 - self.p_infinite();
        let mut node = root;
        let mut index = 0;
        while !node.leaf {
            let Some([(c0, p0), (c1, p1)]) = self.children(index, node, p, n) else {
                return 0.0;
            };
            (pmf, index) = if trail & 1 == 0 {
                (pmf * p0, c0)
            } else {
                (pmf * p1, c1)
            };
            trail >>= 1;
            node = &self.nodes[index];
        }
        if index == 0 && !positive(root.bounds.importance(p, n)) {
            return 0.0;
        }
        pmf
    }

    /// Appends the GPU's copy to `tables` (f32 words, integers bit-cast) and returns its offset.
    /// Layout: a header `[n_nodes, n_infinite, nodes offset, trails offset]`, the indices of the
    /// infinite lights, then 16 words per node (`lo, φ`, `hi, cos θo`, `w, cos θe`,
    /// `child_or_light, flags (1 leaf, 2 two-sided), 0, 0`), then 3 words per scene light (the
    /// trail's low and high halves, and 1 where the tree holds the light). `lights/light_bvh.wgsl`
    /// reads it.
    pub fn append_tables(&self, tables: &mut Vec<f32>) -> u32 {
        let base = tables.len() as u32;
        let bits = f32::from_bits;
        let nodes_at = base + 4 + self.infinite.len() as u32;
        let trails_at = nodes_at + 16 * self.nodes.len() as u32;
        tables.extend([
            bits(self.nodes.len() as u32),
            bits(self.infinite.len() as u32),
            bits(nodes_at),
            bits(trails_at),
        ]);
        tables.extend(self.infinite.iter().map(|&i| bits(i)));
        for node in &self.nodes {
            let b = &node.bounds;
            let flags = u32::from(node.leaf) | (u32::from(b.two_sided) << 1);
            tables.extend([b.lo.x, b.lo.y, b.lo.z, b.phi]);
            tables.extend([b.hi.x, b.hi.y, b.hi.z, b.cos_theta_o]);
            tables.extend([b.w.x, b.w.y, b.w.z, b.cos_theta_e]);
            tables.extend([bits(node.child_or_light), bits(flags), 0.0, 0.0]);
        }
        for t in &self.trails {
            let v = t.unwrap_or(0);
            tables.extend([
                bits(v as u32),
                bits((v >> 32) as u32),
                bits(u32::from(t.is_some())),
            ]);
        }
        base
    }
}

/// Orders `items` (two or more, bounded by `bounds`) so that `items[..mid]` and `items[mid..]`
/// are the children and returns `mid` (0 < mid < len): the cheapest bucket boundary by
/// [`split_cost`] over the three axes, or the middle where no cut separates anything or from
/// depth [`COST_DEPTH`] on.
fn split(items: &mut [(u32, LightBounds)], bounds: &LightBounds, depth: u32) -> usize {
    let n = items.len();
    let (clo, chi) = items
        .iter()
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), (_, b)| {
            (lo.min(b.centroid()), hi.max(b.centroid()))
        });
    let extent = chi - clo;
    let diag = bounds.hi - bounds.lo;
    let bucket = |c: Vec3, axis: usize| {
        let t = (c[axis] - clo[axis]) / extent[axis];
        ((t * BUCKETS as f32) as usize).min(BUCKETS - 1)
    };
    let mut best: Option<(f32, usize, usize)> = None;
    // Two lights split one way whatever the cost says.
    if depth < COST_DEPTH && n > 2 {
        for axis in 0..3 {
            if !positive(extent[axis]) {
                continue;
            }
            let mut buckets: [Option<LightBounds>; BUCKETS] = [None; BUCKETS];
            for (_, b) in items.iter() {
                let k = bucket(b.centroid(), axis);
                buckets[k] = Some(buckets[k].map_or(*b, |a| a.union(b)));
            }
            // Unions of the buckets below and above each cut, by two sweeps.
            let join = |a: Option<LightBounds>, b: &Option<LightBounds>| match (a, b) {
                (Some(a), Some(b)) => Some(a.union(b)),
                (a, b) => a.or(*b),
            };
            let mut below = [None; BUCKETS];
            let mut above = [None; BUCKETS];
            let mut acc = None;
            for (slot, b) in below.iter_mut().zip(&buckets) {
                acc = join(acc, b);
                *slot = acc;
            }
            acc = None;
            for (slot, b) in above.iter_mut().zip(&buckets).rev() {
                acc = join(acc, b);
                *slot = acc;
            }
            for cut in 1..BUCKETS {
                // A cut above an empty bucket splits as the one below it does.
                if buckets[cut - 1].is_none() {
                    continue;
                }
                let (Some(a), Some(b)) = (below[cut - 1], above[cut]) else {
                    continue;
                };
                let cost = split_cost(&a, diag, axis) + split_cost(&b, diag, axis);
                if cost.is_finite() && best.is_none_or(|(c, _, _)| cost < c) {
                    best = Some((cost, axis, cut));
                }
            }
        }
    }
    let mid = match best {
        Some((_, axis, cut)) => partition(items, |b| bucket(b.centroid(), axis) < cut),
        None => 0,
    };
    if mid > 0 && mid < n {
        return mid;
    }
    // The median along the widest centroid extent: halves the count whatever the geometry.
    let axis = extent.max_position();
    let mid = n / 2;
    items.select_nth_unstable_by(mid, |a, b| {
        a.1.centroid()[axis].total_cmp(&b.1.centroid()[axis])
    });
    mid
}

/// Moves the items for which `left` holds to the front; returns their number.
fn partition(items: &mut [(u32, LightBounds)], left: impl Fn(&LightBounds) -> bool) -> usize {
    let mut k = 0;
    for i in 0..items.len() {
        if left(&items[i].1) {
            items.swap(i, k);
            k += 1;
        }
    }
    k
}

/// Whether `x` is positive (NaN is not): where an importance can choose something.
#[inline(always)]
fn positive(x: f32) -> bool {
    x > 0.0
}

// The median split keeps depth below COST_DEPTH + 32 ≤ MAX_DEPTH.
const _: () = assert!(COST_DEPTH + 32 <= MAX_DEPTH);

#[cfg(test)]
#[path = "light_bvh_tests.rs"]
mod tests;
