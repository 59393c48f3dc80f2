// Closest-hit and any-hit queries, the twin of `geometry/bvh.rs` (the CPU traverses the same tree
// with decoded nodes, `geometry/wide_bvh.rs`; `gpu/scene/bvh.rs` checks it fits the stack):
// obvhs's CWBVH (nodes uploaded as they are, 80 bytes = 5 × vec4<u32>) traversed as obvhs's
// `traverse!` does (child order by ray octant, a stack of node groups), with the CPU's robust
// child test: the ray's true interval (0, t_max), the true reciprocal, and each slab widened by a
// bound on its rounding error, so no box the ray touches is culled. Scenes of at most 4
// primitives are scanned linearly (no BVH code at all, see `USE_BVH`). With `USE_BVH2` the
// traversal functions come from `gpu/bvh2.wgsl` instead (a BVH2 measured against this one); the node
// ray below is shared.
//
// Node words: d0 = (p.xyz bits, e0 | e1 << 8 | e2 << 16 | imask << 24),
// d1 = (child_base_idx, primitive_base_idx, child_meta[0..4], child_meta[4..8]),
// d2 = (min_x[0..4], min_x[4..8], max_x[0..4], max_x[4..8]), d3 = y planes, d4 = z planes.

// #if USE_CWBVH
struct BvhNode {
    d0: vec4<u32>,
    d1: vec4<u32>,
    d2: vec4<u32>,
    d3: vec4<u32>,
    d4: vec4<u32>,
}
// #endif

// #if USE_BVH
// The per-ray part of the node test (`NodeRay`).
struct NodeRay {
    o: vec3f,
    inv: vec3f,
    negative: vec3<bool>,
    oct_inv4: u32,
}

fn node_inv(x: f32) -> f32 {
    if x == 0.0 {
        return copysign(MAX_INV, x);
    }
    let r = 1.0 / x;
    if abs(r) > MAX_INV {
        return copysign(MAX_INV, r);
    }
    return r;
}

fn node_ray_new(o: vec3f, d: vec3f) -> NodeRay {
    var oct = 0u;
    if !(d.x < 0.0) {
        oct |= 0x04040404u;
    }
    if !(d.y < 0.0) {
        oct |= 0x02020202u;
    }
    if !(d.z < 0.0) {
        oct |= 0x01010101u;
    }
    return NodeRay(
        o,
        vec3f(node_inv(d.x), node_inv(d.y), node_inv(d.z)),
        vec3<bool>(is_sign_negative(d.x), is_sign_negative(d.y), is_sign_negative(d.z)),
        oct,
    );
}
// #endif

// #if USE_CWBVH
fn byte_of(w: u32, j: u32) -> u32 {
    return (w >> (8u * j)) & 0xffu;
}

// The quantised plane of child `c` (0..8) from a pair of words holding 8 bytes.
fn plane_q(lo_word: u32, hi_word: u32, c: u32) -> f32 {
    let w = select(lo_word, hi_word, c >= 4u);
    return f32(byte_of(w, c & 3u));
}

// Hit mask of the node's children for the traversal (`intersect_node`).
fn intersect_node(node: BvhNode, ray: NodeRay, t_max: f32) -> u32 {
    let p = bitcast<vec3f>(node.d0.xyz);
    let e = node.d0.w;
    let extent = vec3f(
        bitcast<f32>((e & 0xffu) << 23u),
        bitcast<f32>(((e >> 8u) & 0xffu) << 23u),
        bitcast<f32>(((e >> 16u) & 0xffu) << 23u),
    );
    let a = extent * ray.inv;
    let b = (p - ray.o) * ray.inv;
    let err = gamma(5.0) * (255.0 * abs(a) + abs(b));
    var hit_mask = 0u;
    for (var half = 0u; half < 2u; half++) {
        let meta4 = select(node.d1.z, node.d1.w, half == 1u);
        let is_inner4 = (meta4 & (meta4 << 1u)) & 0x10101010u;
        let inner_mask4 = (is_inner4 >> 4u) * 0xffu;
        let bit_index4 = (meta4 ^ (ray.oct_inv4 & inner_mask4)) & 0x1f1f1f1fu;
        let child_bits4 = (meta4 >> 5u) & 0x07070707u;
        for (var j = 0u; j < 4u; j++) {
            let c = 4u * half + j;
            var lo = vec3f(plane_q(node.d2.x, node.d2.y, c), plane_q(node.d3.x, node.d3.y, c), plane_q(node.d4.x, node.d4.y, c));
            var hi = vec3f(plane_q(node.d2.z, node.d2.w, c), plane_q(node.d3.z, node.d3.w, c), plane_q(node.d4.z, node.d4.w, c));
            let near_q = select(lo, hi, ray.negative);
            let far_q = select(hi, lo, ray.negative);
            let t0 = near_q * a + (b - err);
            let t1 = far_q * a + (b + err);
            let t_near = max(max(max(t0.x, t0.y), t0.z), 0.0);
            let t_far = min(min(min(t1.x, t1.y), t1.z), t_max);
            if t_near <= t_far {
                hit_mask |= byte_of(child_bits4, j) << byte_of(bit_index4, j);
            }
        }
    }
    return hit_mask;
}
// #endif

struct HitT {
    t: f32,
    prim: u32,
}

// The hit of primitive `id` on `ray` that the traversals consider (its distance, negative for
// none): with HAS_MASKS a hit that a mask lets the ray pass is none (`materials/mask.wgsl`).
fn prim_hit_t(id: u32, ray: Ray, tri: TriangleRay) -> f32 {
// #if HAS_MASKS
    var t = shape_intersect_t(prims[id], ray, tri);
    // A passed sphere or cylinder may still be met on its far side (at most two hits).
    for (var k = 0u; k < 2u && t >= 0.0; k++) {
        if mask_meets(id, ray, t) {
            return t;
        }
        t = shape_intersect_t_beyond(prims[id], ray, t);
    }
    return -1.0;
// #else
    return shape_intersect_t(prims[id], ray, tri);
// #endif
}

// #if !USE_BVH2
// Closest hit along `ray` in (0, ray.t_max); prim = NONE for none.
fn scene_intersect_t(ray: Ray) -> HitT {
    var best_t = ray.t_max;
    var best = NONE;
    let tri = triangle_ray_new(ray);
// #if USE_CWBVH
    let nray = node_ray_new(ray.o, ray.d);
    var stack: array<vec2<u32>, BVH_STACK_SIZE>;
    var sp = 0u;
    var current = vec2<u32>(0u, 0x80000000u);
    var prims_group = vec2<u32>(0u, 0u);
    loop {
        while prims_group.y != 0u {
            let local = firstLeadingBit(prims_group.y);
            prims_group.y &= ~(1u << local);
            let id = prims_group.x + local;
            let t = prim_hit_t(id, Ray(ray.o, ray.d, best_t), tri);
            if t >= 0.0 {
                best_t = t;
                best = id;
            }
        }
        if (current.y & 0xff000000u) != 0u {
            let hits_imask = current.y;
            let child_index_offset = firstLeadingBit(hits_imask);
            let child_index_base = current.x;
            current.y &= ~(1u << child_index_offset);
            if (current.y & 0xff000000u) != 0u && sp < BVH_STACK_SIZE {
                stack[sp] = current;
                sp += 1u;
            }
            let slot_index = (child_index_offset - 24u) ^ (nray.oct_inv4 & 0xffu);
            let relative_index = countOneBits(hits_imask & ~(0xffffffffu << slot_index));
            let node = nodes[child_index_base + relative_index];
            let hitmask = intersect_node(node, nray, best_t);
            current = vec2<u32>(node.d1.x, (hitmask & 0xff000000u) | (node.d0.w >> 24u));
            prims_group = vec2<u32>(node.d1.y, hitmask & 0x00ffffffu);
        } else {
            current = vec2<u32>(0u, 0u);
        }
        if prims_group.y == 0u && (current.y & 0xff000000u) == 0u {
            if sp == 0u {
                break;
            }
            sp -= 1u;
            current = stack[sp];
        }
    }
// #else
    let n = arrayLength(&prims);
    for (var id = 0u; id < n; id++) {
        let t = prim_hit_t(id, Ray(ray.o, ray.d, best_t), tri);
        if t >= 0.0 {
            best_t = t;
            best = id;
        }
    }
// #endif
    return HitT(best_t, best);
}

// Whether anything blocks `ray` in (0, ray.t_max); stops at the first blocker.
fn scene_occluded(ray: Ray) -> bool {
    let tri = triangle_ray_new(ray);
// #if USE_CWBVH
    let nray = node_ray_new(ray.o, ray.d);
    var stack: array<vec2<u32>, BVH_STACK_SIZE>;
    var sp = 0u;
    var current = vec2<u32>(0u, 0x80000000u);
    var prims_group = vec2<u32>(0u, 0u);
    loop {
        while prims_group.y != 0u {
            let local = firstLeadingBit(prims_group.y);
            prims_group.y &= ~(1u << local);
            if prim_hit_t(prims_group.x + local, ray, tri) >= 0.0 {
                return true;
            }
        }
        if (current.y & 0xff000000u) != 0u {
            let hits_imask = current.y;
            let child_index_offset = firstLeadingBit(hits_imask);
            let child_index_base = current.x;
            current.y &= ~(1u << child_index_offset);
            if (current.y & 0xff000000u) != 0u && sp < BVH_STACK_SIZE {
                stack[sp] = current;
                sp += 1u;
            }
            let slot_index = (child_index_offset - 24u) ^ (nray.oct_inv4 & 0xffu);
            let relative_index = countOneBits(hits_imask & ~(0xffffffffu << slot_index));
            let node = nodes[child_index_base + relative_index];
            let hitmask = intersect_node(node, nray, ray.t_max);
            current = vec2<u32>(node.d1.x, (hitmask & 0xff000000u) | (node.d0.w >> 24u));
            prims_group = vec2<u32>(node.d1.y, hitmask & 0x00ffffffu);
        } else {
            current = vec2<u32>(0u, 0u);
        }
        if prims_group.y == 0u && (current.y & 0xff000000u) == 0u {
            if sp == 0u {
                break;
            }
            sp -= 1u;
            current = stack[sp];
        }
    }
    return false;
// #else
    let n = arrayLength(&prims);
    for (var id = 0u; id < n; id++) {
        if prim_hit_t(id, ray, tri) >= 0.0 {
            return true;
        }
    }
    return false;
// #endif
}
// #endif

// Closest hit with its full record; prim = NONE for a miss.
fn scene_intersect(ray: Ray) -> SurfaceHit {
    let h = scene_intersect_t(ray);
    if h.prim == NONE {
        return SurfaceHit(0.0, vec3f(0.0), vec3f(0.0), vec3f(0.0), NONE, vec2f(0.0));
    }
    return shape_surface_hit(prims[h.prim], ray, h.t, h.prim);
}
