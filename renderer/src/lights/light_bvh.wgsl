// Light selection by importance at the receiver, the twin of `lights/light_bvh.rs` (sampling and
// pmf by bit trail), `lights/light_bounds.rs` (the importance) and `lights/light_selection.rs`
// (`light_select`, `light_select_pmf`: the switch over LIGHT_SELECTION_* in the variant order of
// `LightSelection`). The tree lives in `tables` at `params.light_bvh` as `LightBvh::append_tables`
// writes it: a header [n_nodes, n_infinite, nodes offset, trails offset] (bit-cast u32), the
// infinite lights' indices, 16 words per node, 3 per scene light.

struct LightBoundsRec {
    lo: vec3f,
    phi: f32,
    hi: vec3f,
    cos_theta_o: f32,
    w: vec3f,
    cos_theta_e: f32,
    two_sided: bool,
}

fn light_bvh_word(i: u32) -> u32 {
    return bitcast<u32>(tables[i]);
}

fn light_bvh_vec3(i: u32) -> vec3f {
    return vec3f(tables[i], tables[i + 1u], tables[i + 2u]);
}

// Node k's bounds.
fn light_bvh_bounds(k: u32) -> LightBoundsRec {
    let at = light_bvh_word(params.light_bvh + 2u) + 16u * k;
    let two_sided = (light_bvh_word(at + 13u) & 2u) != 0u;
    return LightBoundsRec(
        light_bvh_vec3(at), tables[at + 3u],
        light_bvh_vec3(at + 4u), tables[at + 7u],
        light_bvh_vec3(at + 8u), tables[at + 11u],
        two_sided,
    );
}

fn light_bvh_child_or_light(k: u32) -> u32 {
    return light_bvh_word(light_bvh_word(params.light_bvh + 2u) + 16u * k + 12u);
}

fn light_bvh_is_leaf(k: u32) -> bool {
    return (light_bvh_word(light_bvh_word(params.light_bvh + 2u) + 16u * k + 13u) & 1u) != 0u;
}

// (cos, sin) of max(0, a − b) (`angle_sub`).
fn light_angle_sub(cos_a: f32, sin_a: f32, cos_b: f32, sin_b: f32) -> vec2f {
    if cos_a > cos_b {
        return vec2f(1.0, 0.0);
    }
    return vec2f(cos_a * cos_b + sin_a * sin_b, sin_a * cos_b - cos_a * sin_b);
}

// `LightBounds::importance`.
fn light_bounds_importance(b: LightBoundsRec, p: vec3f, n: vec3f) -> f32 {
    let pc = 0.5 * (b.lo + b.hi);
    let diag = b.hi - b.lo;
    let r2 = 0.25 * dot(diag, diag);
    let d = p - pc;
    let d2 = dot(d, d);
    if d2 <= r2 {
        return b.phi / max(r2, d2);
    }
    let wi = d / sqrt(d2);
    var cos_w = dot(b.w, wi);
    if b.two_sided {
        cos_w = abs(cos_w);
    }
    let sin_w = safe_sqrt(1.0 - cos_w * cos_w);
    let cos_b = safe_sqrt(1.0 - r2 / d2);
    let sin_b = safe_sqrt(r2 / d2);
    let sin_o = safe_sqrt(1.0 - b.cos_theta_o * b.cos_theta_o);
    let x = light_angle_sub(cos_w, sin_w, b.cos_theta_o, sin_o);
    let cos_p = light_angle_sub(x.x, x.y, cos_b, sin_b).x;
    if cos_p <= b.cos_theta_e {
        return 0.0;
    }
    var importance = b.phi * cos_p / d2;
    if any(n != vec3f(0.0)) {
        let cos_i = abs(dot(n, wi));
        let sin_i = safe_sqrt(1.0 - cos_i * cos_i);
        importance *= light_angle_sub(cos_i, sin_i, cos_b, sin_b).x;
    }
    return max(importance, 0.0);
}

fn light_bvh_p_infinite() -> f32 {
    let n_nodes = light_bvh_word(params.light_bvh);
    let n = f32(light_bvh_word(params.light_bvh + 1u));
    return n / (n + select(1.0, 0.0, n_nodes == 0u));
}

// `LightBvh::sample`: pmf 0 where no light can reach p.
// `LightBvh::children`: interior node `index`'s children and the probability of descending into
// each from (p, n); one function for sample and pmf, so the two multiply the same numbers.
struct LightBvhChildren {
    c0: u32,
    c1: u32,
    p0: f32,
    p1: f32,
    // False where neither child can reach p.
    reach: bool,
}

fn light_bvh_children(index: u32, p: vec3f, n: vec3f) -> LightBvhChildren {
    let c0 = index + 1u;
    let c1 = light_bvh_child_or_light(index);
    let w0 = light_bounds_importance(light_bvh_bounds(c0), p, n);
    let w1 = light_bounds_importance(light_bvh_bounds(c1), p, n);
    return LightBvhChildren(c0, c1, w0 / (w0 + w1), w1 / (w0 + w1), w0 + w1 > 0.0);
}

fn light_bvh_sample(p: vec3f, n: vec3f, u_in: f32) -> LightChoice {
    let base = params.light_bvh;
    let n_nodes = light_bvh_word(base);
    let n_inf = light_bvh_word(base + 1u);
    let p_inf = light_bvh_p_infinite();
    if u_in < p_inf {
        let k = min(u32(u_in / p_inf * f32(n_inf)), n_inf - 1u);
        return LightChoice(light_bvh_word(base + 4u + k), p_inf / f32(n_inf));
    }
    if n_nodes == 0u {
        return LightChoice(0u, 0.0);
    }
    var u = min((u_in - p_inf) / (1.0 - p_inf), ONE_MINUS_EPSILON);
    var pmf = 1.0 - p_inf;
    var index = 0u;
    while !light_bvh_is_leaf(index) {
        let c = light_bvh_children(index, p, n);
        if !c.reach {
            return LightChoice(0u, 0.0);
        }
        if u < c.p0 {
            u = min(u / c.p0, ONE_MINUS_EPSILON);
            pmf *= c.p0;
            index = c.c0;
        } else {
            u = min((u - c.p0) / (1.0 - c.p0), ONE_MINUS_EPSILON);
            pmf *= c.p1;
            index = c.c1;
        }
    }
    if index == 0u && !(light_bounds_importance(light_bvh_bounds(0u), p, n) > 0.0) {
        return LightChoice(0u, 0.0);
    }
    return LightChoice(light_bvh_child_or_light(index), pmf);
}

// `LightBvh::pmf`: re-descends light i's bit trail.
fn light_bvh_pmf(p: vec3f, n: vec3f, i: u32) -> f32 {
    let base = params.light_bvh;
    let n_nodes = light_bvh_word(base);
    let n_inf = light_bvh_word(base + 1u);
    for (var k = 0u; k < n_inf; k++) {
        if light_bvh_word(base + 4u + k) == i {
            return light_bvh_p_infinite() / f32(n_inf);
        }
    }
    let t = light_bvh_word(base + 3u) + 3u * i;
    if n_nodes == 0u || light_bvh_word(t + 2u) == 0u {
        return 0.0;
    }
    // The 64-bit trail as two halves; depth k reads bit k.
    var lo = light_bvh_word(t);
    var hi = light_bvh_word(t + 1u);
    var pmf = 1.0 - light_bvh_p_infinite();
    var index = 0u;
    while !light_bvh_is_leaf(index) {
        let c = light_bvh_children(index, p, n);
        if !c.reach {
            return 0.0;
        }
        if (lo & 1u) == 0u {
            pmf *= c.p0;
            index = c.c0;
        } else {
            pmf *= c.p1;
            index = c.c1;
        }
        lo = (lo >> 1u) | (hi << 31u);
        hi = hi >> 1u;
    }
    if index == 0u && !(light_bounds_importance(light_bvh_bounds(0u), p, n) > 0.0) {
        return 0.0;
    }
    return pmf;
}

// `Scene::select_light`: pmf 0 where nothing is chosen.
fn light_select(p: vec3f, n: vec3f, u: f32) -> LightChoice {
    switch params.light_selection {
        case LIGHT_SELECTION_POWER: {
            return light_sampler_sample(params.light_cdf, params.light_pmf, params.n_lights, u);
        }
        case LIGHT_SELECTION_BVH: {
            return light_bvh_sample(p, n, u);
        }
        default: {
            return LightChoice(0u, unknown_tag());
        }
    }
}

// `Scene::light_pmf`.
fn light_select_pmf(p: vec3f, n: vec3f, i: u32) -> f32 {
    switch params.light_selection {
        case LIGHT_SELECTION_POWER: {
            return light_sampler_pmf(params.light_pmf, i);
        }
        case LIGHT_SELECTION_BVH: {
            return light_bvh_pmf(p, n, i);
        }
        default: {
            return unknown_tag();
        }
    }
}
