// Emitting polygons (triangulated), the twin of `lights/polygon.rs`: by area (a triangle picked by
// area, then uniform), or by solid angle (a triangle picked by its solid angle, then Arvo), which
// is uniform over the whole polygon's solid angle. The per-triangle solid angles are summed twice
// (total, then the pick) instead of being kept in an array: private arrays are costly on GPUs.

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

fn polygon_light_sample(l: Light, p: vec3f, u: vec2f, method: u32) -> LightSample {
    if !polygon_light_faces(l, p) {
        return no_light_sample();
    }
    let first = l.h.y;
    let count = l.h.z;
    if method == LIGHT_SAMPLING_SOLID_ANGLE {
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
            let s = sample_spherical_triangle(v0, v1, v2, p, vec2f(ux, u.y));
            if !s.ok {
                return no_light_sample();
            }
            let b = s.barycentrics;
            let y = b.x * v0 + b.y * v1 + b.z * v2;
            let err = gamma(6.0) * (abs(b.x * v0) + abs(b.y * v1) + abs(b.z * v2));
            return LightSample(y, err, l.d.xyz, s.dir, 1.0 / total, l.le.xyz, false, true, b.yz);
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

fn polygon_light_pdf(l: Light, p: vec3f, y: vec3f, ny: vec3f, method: u32) -> f32 {
    if !polygon_light_faces(l, p) {
        return 0.0;
    }
    if method == LIGHT_SAMPLING_SOLID_ANGLE {
        let total = polygon_total_solid_angle(l, p);
        if total > 0.0 {
            return 1.0 / total;
        }
    }
    return area_to_solid_angle(1.0 / l.le.w, p, y, ny);
}
