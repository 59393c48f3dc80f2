// Rays and robust spawning, the twin of `geometry/ray.rs`: hit points carry error bounds, new rays
// start just outside them (pbrt-v4), no fixed epsilon. `crosses_plane_ahead` is decided in f64 on
// the CPU; WGSL has no f64, so it runs in double-f32 arithmetic (≈ 48 significant bits, built on
// exact two-sum and Dekker's two-product), which its 1e-13 tolerances still dominate.

struct Ray {
    o: vec3f,
    d: vec3f,
    t_max: f32,
}

fn ray_at(r: Ray, t: f32) -> vec3f {
    return r.o + t * r.d;
}

// One ulp up/down, by the bits (zeros of either sign step to the smallest subnormal, as on the
// CPU, where −0 is first turned into +0 or the reverse).
fn next_float_up(v: f32) -> f32 {
    let bits = bitcast<u32>(v);
    if bits == 0x7f800000u {
        return v;
    }
    if (bits & 0x7fffffffu) == 0u {
        return bitcast<f32>(1u);
    }
    if (bits & 0x80000000u) == 0u {
        return bitcast<f32>(bits + 1u);
    }
    return bitcast<f32>(bits - 1u);
}

fn next_float_down(v: f32) -> f32 {
    let bits = bitcast<u32>(v);
    if bits == 0xff800000u {
        return v;
    }
    if (bits & 0x7fffffffu) == 0u {
        return bitcast<f32>(0x80000001u);
    }
    if (bits & 0x80000000u) == 0u {
        return bitcast<f32>(bits - 1u);
    }
    return bitcast<f32>(bits + 1u);
}

// --- double-f32 ("df") arithmetic: value = x + y, |y| ≤ ulp(x)/2 ---

fn df_two_sum(a: f32, b: f32) -> vec2f {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    return vec2f(s, e);
}

fn df_quick_two_sum(a: f32, b: f32) -> vec2f {
    let s = a + b;
    return vec2f(s, b - (s - a));
}

fn df_from_diff(a: f32, b: f32) -> vec2f {
    return df_two_sum(a, -b);
}

fn df_add(a: vec2f, b: vec2f) -> vec2f {
    let s = df_two_sum(a.x, b.x);
    return df_quick_two_sum(s.x, s.y + (a.y + b.y));
}

fn df_mul(a: vec2f, b: vec2f) -> vec2f {
    let p = two_prod(a.x, b.x);
    return df_quick_two_sum(p.x, p.y + (a.x * b.y + a.y * b.x));
}

// Whether o + t·d crosses the plane through p0 with normal n at some t > 0, p0 and n given as
// df vectors (x, y, z each a vec2): the origin clearly off the plane, on the side away from the
// heading.
fn crosses_plane_ahead_df(o: vec3f, d: vec3f, p0x: vec2f, p0y: vec2f, p0z: vec2f,
                          nx: vec2f, ny: vec2f, nz: vec2f) -> bool {
    let rx = df_add(vec2f(o.x, 0.0), -p0x);
    let ry = df_add(vec2f(o.y, 0.0), -p0y);
    let rz = df_add(vec2f(o.z, 0.0), -p0z);
    let side = df_add(df_add(df_mul(rx, nx), df_mul(ry, ny)), df_mul(rz, nz));
    let heading = df_add(df_add(df_mul(vec2f(d.x, 0.0), nx), df_mul(vec2f(d.y, 0.0), ny)), df_mul(vec2f(d.z, 0.0), nz));
    let rel_len = length(vec3f(rx.x, ry.x, rz.x));
    let n_len = length(vec3f(nx.x, ny.x, nz.x));
    let tol = 1e-13;
    let off_plane = abs(side.x) > tol * rel_len * n_len;
    let not_parallel = abs(heading.x) > tol * length(d) * n_len;
    return off_plane && not_parallel && ((side.x < 0.0) != (heading.x < 0.0));
}

// `crosses_plane_ahead` for an f32 plane point and normal.
fn crosses_plane_ahead(o: vec3f, d: vec3f, p0: vec3f, n: vec3f) -> bool {
    return crosses_plane_ahead_df(o, d, vec2f(p0.x, 0.0), vec2f(p0.y, 0.0), vec2f(p0.z, 0.0),
                                  vec2f(n.x, 0.0), vec2f(n.y, 0.0), vec2f(n.z, 0.0));
}

// `offset_ray_origin` (pbrt-v4 OffsetRayOrigin): p moved along n to the side w points to, past
// its error bound, rounded away from p.
fn offset_ray_origin(p: vec3f, p_error: vec3f, n: vec3f, w: vec3f) -> vec3f {
    let d = dot(abs(n), p_error);
    var offset = d * n;
    if dot(w, n) < 0.0 {
        offset = -offset;
    }
    var po = p + offset;
    for (var i = 0; i < 3; i++) {
        if offset[i] > 0.0 {
            po[i] = next_float_up(po[i]);
        } else if offset[i] < 0.0 {
            po[i] = next_float_down(po[i]);
        }
    }
    return po;
}

fn spawn_ray(p: vec3f, p_error: vec3f, n: vec3f, d: vec3f) -> Ray {
    return Ray(offset_ray_origin(p, p_error, n, d), d, inf());
}

fn spawn_ray_to(p_from: vec3f, err_from: vec3f, n_from: vec3f, p_to: vec3f, err_to: vec3f, n_to: vec3f) -> Ray {
    let pf = offset_ray_origin(p_from, err_from, n_from, p_to - p_from);
    let pt = offset_ray_origin(p_to, err_to, n_to, pf - p_to);
    return Ray(pf, pt - pf, 1.0 - SHADOW_EPSILON);
}
