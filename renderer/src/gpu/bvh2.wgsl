// The BVH2 alternative to `geometry/bvh.wgsl`'s CWBVH (`USE_BVH2`, chosen by `Features::bvh2`), kept so
// both can be measured with the real path tracer. Same queries, same names, same guarantee: the
// node test keeps the ray's true interval (0, t_max) and the true reciprocal (`NodeRay`, shared
// with the CWBVH), and widens every slab by a bound on its rounding error, so no box the ray
// touches is culled.
//
// `nodes` (binding 1) is an array of vec4<u32> written by `gpu/scene/bvh.rs`: node i is rows
// 2i = (min.xyz bits, prim_count) and 2i + 1 = (max.xyz bits, first). An inner node
// (prim_count 0) has its children at `first` and `first + 1`; a leaf's `first` is the word index,
// in the same buffer, of its prim_count primitive ids (indices into `prims`, the CWBVH's order, so
// a hit's primitive means the same whichever BVH found it). The root is node 0.

// Near-child-first traversal pushes at most one node per level, so BVH2_STACK_SIZE (the prelude)
// is the depth the upload accepts.

// Entry distance of the ray into node `i`'s box within (0, t_max), or −1 when it misses.
fn bvh2_box(i: u32, ray: NodeRay, t_max: f32) -> f32 {
    let lo = bitcast<vec3f>(nodes[2u * i].xyz);
    let hi = bitcast<vec3f>(nodes[2u * i + 1u].xyz);
    let t0 = (select(lo, hi, ray.negative) - ray.o) * ray.inv;
    let t1 = (select(hi, lo, ray.negative) - ray.o) * ray.inv;
    // Each slab parameter is off by at most three roundings (the reciprocal, the difference, the
    // product), a relative error; scaling by 1 ∓ gamma(5) covers them and the scaling's own
    // rounding. The sign of a slab parameter is exact, so a negative far plane stays behind.
    let t_near = max(max(max(t0.x, t0.y), t0.z) * (1.0 - gamma(5.0)), 0.0);
    let t_far = min(min(min(t1.x, t1.y), t1.z) * (1.0 + gamma(5.0)), t_max);
    return select(-1.0, t_near, t_near <= t_far);
}

// The k-th word of `nodes` (a leaf's primitive ids).
fn bvh2_word(k: u32) -> u32 {
    return nodes[k >> 2u][k & 3u];
}

// Closest hit along `ray` in (0, ray.t_max); prim = NONE for none.
fn scene_intersect_t(ray: Ray) -> HitT {
    var best_t = ray.t_max;
    var best = NONE;
    let tri = triangle_ray_new(ray);
    let nray = node_ray_new(ray.o, ray.d);
    if bvh2_box(0u, nray, best_t) < 0.0 {
        return HitT(best_t, best);
    }
    // Deferred far children with their entry distances, skipped once a closer hit is known.
    var stack: array<vec2<u32>, BVH2_STACK_SIZE>;
    var sp = 0u;
    var node = 0u;
    loop {
        let count = nodes[2u * node].w;
        let first = nodes[2u * node + 1u].w;
        if count == 0u {
            let t0 = bvh2_box(first, nray, best_t);
            let t1 = bvh2_box(first + 1u, nray, best_t);
            if t0 >= 0.0 && t1 >= 0.0 {
                let near_is_1 = t1 < t0;
                if sp < BVH2_STACK_SIZE {
                    stack[sp] = vec2<u32>(
                        select(first + 1u, first, near_is_1),
                        bitcast<u32>(select(t1, t0, near_is_1)),
                    );
                    sp += 1u;
                }
                node = select(first, first + 1u, near_is_1);
                continue;
            }
            if t0 >= 0.0 {
                node = first;
                continue;
            }
            if t1 >= 0.0 {
                node = first + 1u;
                continue;
            }
        } else {
            for (var k = 0u; k < count; k++) {
                let id = bvh2_word(first + k);
                let t = prim_hit_t(id, Ray(ray.o, ray.d, best_t), tri);
                if t >= 0.0 {
                    best_t = t;
                    best = id;
                }
            }
        }
        // Pop the nearest deferred node that can still hold a closer hit.
        var found = false;
        while sp > 0u {
            sp -= 1u;
            let e = stack[sp];
            if bitcast<f32>(e.y) <= best_t {
                node = e.x;
                found = true;
                break;
            }
        }
        if !found {
            break;
        }
    }
    return HitT(best_t, best);
}

// Whether anything blocks `ray` in (0, ray.t_max); stops at the first blocker.
fn scene_occluded(ray: Ray) -> bool {
    let tri = triangle_ray_new(ray);
    let nray = node_ray_new(ray.o, ray.d);
    if bvh2_box(0u, nray, ray.t_max) < 0.0 {
        return false;
    }
    var stack: array<u32, BVH2_STACK_SIZE>;
    var sp = 0u;
    var node = 0u;
    loop {
        let count = nodes[2u * node].w;
        let first = nodes[2u * node + 1u].w;
        if count == 0u {
            let t0 = bvh2_box(first, nray, ray.t_max);
            let t1 = bvh2_box(first + 1u, nray, ray.t_max);
            if t0 >= 0.0 && t1 >= 0.0 {
                // Near first here too: a nearby blocker ends the query sooner on average.
                let near_is_1 = t1 < t0;
                if sp < BVH2_STACK_SIZE {
                    stack[sp] = select(first + 1u, first, near_is_1);
                    sp += 1u;
                }
                node = select(first, first + 1u, near_is_1);
                continue;
            }
            if t0 >= 0.0 {
                node = first;
                continue;
            }
            if t1 >= 0.0 {
                node = first + 1u;
                continue;
            }
        } else {
            for (var k = 0u; k < count; k++) {
                if prim_hit_t(bvh2_word(first + k), ray, tri) >= 0.0 {
                    return true;
                }
            }
        }
        if sp == 0u {
            break;
        }
        sp -= 1u;
        node = stack[sp];
    }
    return false;
}
