// Emitting polygons (triangulated), the twin of `lights/polygon.rs`: by area (a triangle picked by
// area, then uniform), or by solid angle (a triangle picked by its solid angle, then Arvo), which
// is uniform over the whole polygon's solid angle. The per-triangle solid angles are summed twice
// (total, then the pick) instead of being kept in an array: private arrays are costly on GPUs.
// With the cosine warp, the chosen spherical triangle is sampled through its own bilinear warp.
// `Adaptive`: by area where the polygon looks small from p, else a triangle picked by its
// estimated solid angle, then Arvo in it. The record's b holds the centroid, each triangle's third
// vertex's w its area. Projected solid angle: a triangle picked by its clipped projected solid
// angle (summed twice, like the solid angles), then `psa_sample` in it.

fn polygon_light_faces(l: Light, p: vec3f) -> bool {
    return dot(p - l.a.xyz, l.d.xyz) > 0.0;
}

fn polygon_tri_solid_angle(i: u32, p: vec3f) -> f32 {
    let v0 = vertex_data[3u * i].xyz;
    let v1 = vertex_data[3u * i + 1u].xyz;
    let v2 = vertex_data[3u * i + 2u].xyz;
    return spherical_triangle_area(normalize_or_zero(v0 - p), normalize_or_zero(v1 - p), normalize_or_zero(v2 - p));
}

// Total solid angle if solid-angle sampling applies, else a negative value.
fn polygon_total_solid_angle(l: Light, p: vec3f) -> f32 {
    let count = l.h.z;
    if count > MAX_SOLID_ANGLE_TRIANGLES {
        return -1.0;
    }
    var total = 0.0;
    for (var i = 0u; i < count; i++) {
        total += polygon_tri_solid_angle(l.h.y + i, p);
    }
    if spherical_ok(total) {
        return total;
    }
    return -1.0;
}

// Triangle t (absolute index) seen from p in frame f, clipped to the horizon.
fn polygon_psa_piece(t: u32, p: vec3f, f: Frame) -> PsaPolygon {
    let v0 = vertex_data[3u * t].xyz;
    let v1 = vertex_data[3u * t + 1u].xyz;
    let v2 = vertex_data[3u * t + 2u].xyz;
    return psa_piece(p, f, v0, v1, v2, v2, 3u);
}

// `projected::pieces` over the triangles: (Σ Ω⊥, Σ|S_e|, 1 if any triangle is above the horizon).
fn polygon_psa_totals(l: Light, p: vec3f, f: Frame) -> vec3f {
    var out = vec3f(0.0);
    for (var i = 0u; i < l.h.z; i++) {
        let poly = polygon_psa_piece(l.h.y + i, p, f);
        if poly.n >= 3u {
            out += vec3f(poly.area, poly.abs_sum, 1.0);
        }
    }
    return vec3f(out.xy, min(out.z, 1.0));
}

// `PolygonLight::sample` by projected solid angle, given the totals (well conditioned).
fn polygon_light_sample_projected(l: Light, p: vec3f, ns: vec3f, f: Frame, u: vec2f, total: f32) -> LightSample {
    let goal = u.x * total;
    var acc = 0.0;
    var chosen = NONE;
    var ux = ONE_MINUS_EPSILON;
    for (var i = 0u; i < l.h.z; i++) {
        let poly = polygon_psa_piece(l.h.y + i, p, f);
        var w = 0.0;
        if poly.n >= 3u {
            w = poly.area;
        }
        if w <= 0.0 {
            continue;
        }
        chosen = i;
        if goal < acc + w {
            ux = clamp((goal - acc) / w, 0.0, ONE_MINUS_EPSILON);
            break;
        }
        acc += w;
    }
    if chosen == NONE {
        return no_light_sample();
    }
    let t = l.h.y + chosen;
    let poly = polygon_psa_piece(t, p, f);
    if poly.n < 3u {
        return no_light_sample();
    }
    let wi = normalize_glam(to_world(f, psa_sample(poly, vec2f(ux, u.y))));
    let v0 = vertex_data[3u * t].xyz;
    let v1 = vertex_data[3u * t + 1u].xyz;
    let v2 = vertex_data[3u * t + 2u].xyz;
    let b = barycentrics_along(v0, v1, v2, p, wi);
    return triangle_sample(v0, v1, v2, b, l.d.xyz, l.le.xyz, wi, psa_light_pdf(ns, wi, total));
}

// `PolygonLight::triangle_holding`: the triangle (index from `first`) whose smallest
// barycentric coordinate of y is largest.
fn polygon_triangle_holding(l: Light, y: vec3f) -> u32 {
    var best = 0u;
    var best_smallest = -3.4028235e38;
    for (var i = 0u; i < l.h.z; i++) {
        let t = l.h.y + i;
        let a = vertex_data[3u * t].xyz - y;
        let b = vertex_data[3u * t + 1u].xyz - y;
        let c = vertex_data[3u * t + 2u].xyz - y;
        let n = l.d.xyz;
        let area = dot(n, cross(b - a, c - a));
        let smallest = min(min(dot(n, cross(b, c)), dot(n, cross(c, a))), dot(n, cross(a, b))) / area;
        if smallest > best_smallest {
            best = i;
            best_smallest = smallest;
        }
    }
    return best;
}

// `PolygonLight::triangle_estimate`: the estimated solid angle of triangle t (absolute index).
fn polygon_tri_estimate(l: Light, t: u32, p: vec3f) -> f32 {
    let c = (vertex_data[3u * t].xyz + vertex_data[3u * t + 1u].xyz + vertex_data[3u * t + 2u].xyz) / 3.0;
    return planar_solid_angle_estimate(p, c, l.d.xyz, vertex_data[3u * t + 2u].w);
}

// `PolygonLight::adaptive_total`: Σ e_i where `Adaptive` picks by triangle estimates, else -1.
fn polygon_adaptive_total(l: Light, p: vec3f) -> f32 {
    if !light_sampling_spherical_for(LIGHT_SAMPLING_ADAPTIVE, p, l.b.xyz, l.d.xyz, l.le.w) {
        return -1.0;
    }
    var total = 0.0;
    for (var i = 0u; i < l.h.z; i++) {
        total += polygon_tri_estimate(l, l.h.y + i, p);
    }
    // Not NaN nor infinite (p almost on the plane).
    if total > 0.0 && total < 3.4028235e38 {
        return total;
    }
    return -1.0;
}

// A uniform point of triangle t (absolute index) for u, with area density pdf_area.
fn polygon_sample_in_triangle(l: Light, t: u32, p: vec3f, u: vec2f, pdf_area: f32) -> LightSample {
    let v0 = vertex_data[3u * t].xyz;
    let v1 = vertex_data[3u * t + 1u].xyz;
    let v2 = vertex_data[3u * t + 2u].xyz;
    let b = sample_uniform_triangle(u);
    let y = b.x * v0 + b.y * v1 + b.z * v2;
    var s = area_sample(p, y, l.d.xyz, pdf_area, l.le.xyz);
    s.b = b.yz;
    return s;
}

// `PolygonLight::sample_adaptive` where `polygon_adaptive_total` gave total > 0.
fn polygon_light_sample_adaptive(l: Light, p: vec3f, u: vec2f, total: f32) -> LightSample {
    let goal = u.x * total;
    var acc = 0.0;
    var chosen = NONE;
    var e_chosen = 0.0;
    var ux = ONE_MINUS_EPSILON;
    for (var i = 0u; i < l.h.z; i++) {
        let e = polygon_tri_estimate(l, l.h.y + i, p);
        if e <= 0.0 {
            continue;
        }
        chosen = i;
        e_chosen = e;
        ux = clamp((goal - acc) / e, 0.0, ONE_MINUS_EPSILON);
        if goal < acc + e {
            break;
        }
        acc += e;
    }
    if chosen == NONE {
        return no_light_sample();
    }
    let q = e_chosen / total;
    let t = l.h.y + chosen;
    let v0 = vertex_data[3u * t].xyz;
    let v1 = vertex_data[3u * t + 1u].xyz;
    let v2 = vertex_data[3u * t + 2u].xyz;
    let omega = polygon_tri_solid_angle(t, p);
    if !spherical_ok(omega) {
        return polygon_sample_in_triangle(l, t, p, vec2f(ux, u.y), q / vertex_data[3u * t + 2u].w);
    }
    let s = sample_spherical_triangle(v0, v1, v2, p, vec2f(ux, u.y));
    if !s.ok {
        return no_light_sample();
    }
    let b = s.barycentrics;
    return triangle_sample(v0, v1, v2, b, l.d.xyz, l.le.xyz, s.dir, q / omega);
}

// `PolygonLight::pdf_adaptive` where `polygon_adaptive_total` gave total > 0.
fn polygon_light_pdf_adaptive(l: Light, p: vec3f, y: vec3f, ny: vec3f, total: f32) -> f32 {
    let t = l.h.y + polygon_triangle_holding(l, y);
    let q = polygon_tri_estimate(l, t, p) / total;
    let omega = polygon_tri_solid_angle(t, p);
    if !spherical_ok(omega) {
        return area_to_solid_angle(q / vertex_data[3u * t + 2u].w, p, y, ny);
    }
    return q / omega;
}

fn polygon_light_sample(l: Light, p: vec3f, ns: vec3f, u: vec2f, method: u32) -> LightSample {
    if !polygon_light_faces(l, p) {
        return no_light_sample();
    }
    let first = l.h.y;
    let count = l.h.z;
    if method == LIGHT_SAMPLING_ADAPTIVE {
        let total = polygon_adaptive_total(l, p);
        if total > 0.0 {
            return polygon_light_sample_adaptive(l, p, u, total);
        }
    }
    if light_sampling_projects(method, ns) && count <= MAX_SOLID_ANGLE_TRIANGLES {
        let f = psa_frame(ns);
        let totals = polygon_psa_totals(l, p, f);
        if totals.z == 0.0 {
            return no_light_sample();
        }
        if psa_conditioned(totals.x, totals.y) {
            return polygon_light_sample_projected(l, p, ns, f, u, totals.x);
        }
    }
    if light_sampling_solid_angle(method) && method != LIGHT_SAMPLING_ADAPTIVE {
        let total = polygon_total_solid_angle(l, p);
        if total > 0.0 {
            // `pick`: an entry in proportion to its solid angle, u.x remapped within it.
            let goal = u.x * total;
            var acc = 0.0;
            var chosen = NONE;
            var ux = ONE_MINUS_EPSILON;
            for (var i = 0u; i < count; i++) {
                let w = polygon_tri_solid_angle(first + i, p);
                if w <= 0.0 {
                    continue;
                }
                chosen = i;
                if goal < acc + w {
                    ux = clamp((goal - acc) / w, 0.0, ONE_MINUS_EPSILON);
                    break;
                }
                acc += w;
            }
            if chosen == NONE {
                return no_light_sample();
            }
            let t = first + chosen;
            let v0 = vertex_data[3u * t].xyz;
            let v1 = vertex_data[3u * t + 1u].xyz;
            let v2 = vertex_data[3u * t + 2u].xyz;
            var uw = vec2f(ux, u.y);
            var warp_pdf = 1.0;
            if light_sampling_warps(method, ns) {
                let w = spherical_triangle_cosine_weights(v0, v1, v2, p, ns);
                uw = sample_bilinear(uw, w);
                warp_pdf = bilinear_pdf(uw, w);
            }
            let s = sample_spherical_triangle(v0, v1, v2, p, uw);
            if !s.ok {
                return no_light_sample();
            }
            let b = s.barycentrics;
            return triangle_sample(v0, v1, v2, b, l.d.xyz, l.le.xyz, s.dir, warp_pdf / total);
        }
    }
    // By area: the triangle whose CDF interval holds u.x, u.x remapped within it.
    var lo = 0u;
    var hi = count;
    while hi - lo > 1u {
        let mid = (lo + hi) / 2u;
        if vertex_data[3u * (first + mid)].w <= u.x {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let t = first + lo;
    let c0 = vertex_data[3u * t].w;
    let c1 = vertex_data[3u * t + 1u].w;
    let ux = min((u.x - c0) / (c1 - c0), ONE_MINUS_EPSILON);
    let v0 = vertex_data[3u * t].xyz;
    let v1 = vertex_data[3u * t + 1u].xyz;
    let v2 = vertex_data[3u * t + 2u].xyz;
    let b = sample_uniform_triangle(vec2f(ux, u.y));
    let y = b.x * v0 + b.y * v1 + b.z * v2;
    var s = area_sample(p, y, l.d.xyz, 1.0 / l.le.w, l.le.xyz);
    s.b = b.yz;
    return s;
}

fn polygon_light_pdf(l: Light, p: vec3f, ns: vec3f, wi: vec3f, y: vec3f, ny: vec3f, method: u32) -> f32 {
    if !polygon_light_faces(l, p) {
        return 0.0;
    }
    if method == LIGHT_SAMPLING_ADAPTIVE {
        let total = polygon_adaptive_total(l, p);
        if total > 0.0 {
            return polygon_light_pdf_adaptive(l, p, y, ny, total);
        }
        return area_to_solid_angle(1.0 / l.le.w, p, y, ny);
    }
    if light_sampling_projects(method, ns) && l.h.z <= MAX_SOLID_ANGLE_TRIANGLES {
        let totals = polygon_psa_totals(l, p, psa_frame(ns));
        if totals.z == 0.0 {
            return 0.0;
        }
        if psa_conditioned(totals.x, totals.y) {
            return psa_light_pdf(ns, wi, totals.x);
        }
    }
    if light_sampling_solid_angle(method) {
        let total = polygon_total_solid_angle(l, p);
        if total > 0.0 {
            if light_sampling_warps(method, ns) {
                let t = l.h.y + polygon_triangle_holding(l, y);
                let v0 = vertex_data[3u * t].xyz;
                let v1 = vertex_data[3u * t + 1u].xyz;
                let v2 = vertex_data[3u * t + 2u].xyz;
                let w = spherical_triangle_cosine_weights(v0, v1, v2, p, ns);
                return bilinear_pdf(invert_spherical_triangle(v0, v1, v2, p, wi), w) / total;
            }
            return 1.0 / total;
        }
    }
    return area_to_solid_angle(1.0 / l.le.w, p, y, ny);
}
