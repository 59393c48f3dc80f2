// Uniform solid-angle sampling of a spherical triangle (Arvo 1995), the twin of
// `sampling/spherical_triangle.rs`, with the same versine and half-angle forms.

// Van Oosterom–Strackee solid angle of the unit vectors a, b, c.
fn spherical_triangle_area(a: vec3f, b: vec3f, c: vec3f) -> f32 {
    let triple = dot(a, cross(b - a, c - a));
    return 2.0 * atan2_precise(abs(triple), 1.0 + dot(a, b) + dot(b, c) + dot(c, a));
}

// Van Oosterom–Strackee for vectors of any length, `triple_abs` = |a·(b×c)|.
fn solid_angle_from_vectors(triple_abs: f32, a: vec3f, b: vec3f, c: vec3f) -> f32 {
    let la = length(a);
    let lb = length(b);
    let lc = length(c);
    let den = la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb;
    return 2.0 * atan2_precise(triple_abs, den);
}

// `spherical_triangle_corners` + `cosine_corner_weights`: the weights of a cosine warp in front of
// `sample_spherical_triangle`, whose corners (0,0), (1,0), (0,1), (1,1) go to v1, v1, v0, v2.
fn spherical_triangle_cosine_weights(v0: vec3f, v1: vec3f, v2: vec3f, p: vec3f, ns: vec3f) -> vec4f {
    return cosine_corner_weights(ns, v1 - p, v1 - p, v0 - p, v2 - p);
}

// `invert_spherical_triangle`: the u that samples direction w_in from p (inside the spherical
// triangle); (0.5, 0.5) for degenerate inputs.
fn invert_spherical_triangle(v0: vec3f, v1: vec3f, v2: vec3f, p: vec3f, w_in: vec3f) -> vec2f {
    let a = normalize_or_zero(v0 - p);
    let b = normalize_or_zero(v1 - p);
    let c = normalize_or_zero(v2 - p);
    let triple = dot(a, cross(b - a, c - a));
    if triple == 0.0 {
        return vec2f(0.5);
    }
    let area = 2.0 * atan2_precise(abs(triple), 1.0 + dot(a, b) + dot(b, c) + dot(c, a));
    if !(area > 0.0 && is_finite_f(area)) {
        return vec2f(0.5);
    }
    let w = normalize_or_zero(w_in);
    // c' is where the great circle through b and w crosses the arc a→c.
    let n_bw = cross(b, w - b);
    let n_ca = cross(c, a - c);
    var cp = normalize_or_zero(cross(n_bw, n_ca));
    if all(cp == vec3f(0.0)) {
        return vec2f(0.5, 0.0);
    }
    if dot(cp, a + c) < 0.0 {
        cp = -cp;
    }
    let u0 = spherical_triangle_area(a, b, cp) / area;
    let bw = w - b;
    let bc = cp - b;
    let u1 = dot(bw, bw) / dot(bc, bc);
    return clamp(vec2f(u0, u1), vec2f(0.0), vec2f(1.0));
}

struct SphericalTriangleSample {
    dir: vec3f,
    barycentrics: vec3f,
    pdf: f32,
    ok: bool,
}

fn st_tangent(from_v: vec3f, e: vec3f) -> vec3f {
    return normalize_or_zero(e - dot(e, from_v) * from_v);
}

fn sample_spherical_triangle(v0: vec3f, v1: vec3f, v2: vec3f, p: vec3f, u: vec2f) -> SphericalTriangleSample {
    var out = SphericalTriangleSample(vec3f(0.0), vec3f(0.0), 0.0, false);
    // Arvo::new
    let a = normalize_or_zero(v0 - p);
    let b = normalize_or_zero(v1 - p);
    let c = normalize_or_zero(v2 - p);
    let triple = dot(a, cross(b - a, c - a));
    if triple == 0.0 {
        return out;
    }
    let area = 2.0 * atan2_precise(abs(triple), 1.0 + dot(a, b) + dot(b, c) + dot(c, a));
    if !(area > 0.0 && is_finite_f(area)) {
        return out;
    }
    let n_ab = normalize_or_zero(cross(a, b - a));
    let n_ac = normalize_or_zero(cross(a, c - a));
    let cos_alpha = clamp(dot(n_ab, n_ac), -1.0, 1.0);
    let sin_alpha = min(length(cross(n_ab, n_ac)), 1.0);
    let alpha = atan2_precise(sin_alpha, cos_alpha);

    let ap = u.x * area;
    let sin_ap = sin(ap);
    let cos_ap = cos(ap);
    let sin_half = sin(0.5 * ap);
    let vers_ap = 2.0 * sin_half * sin_half;
    let ab = a - b;
    let vers_c = 0.5 * dot(ab, ab);
    let uu = 2.0 * sin_half * sin(alpha - 0.5 * ap);
    let vv = sin_alpha * (vers_ap - vers_c) + cos_alpha * sin_ap;
    let sin_phi = difference_of_products(sin_ap, cos_alpha, cos_ap, sin_alpha);
    let cos_phi = difference_of_products(cos_ap, cos_alpha, -sin_ap, sin_alpha);
    let den = difference_of_products(vv, sin_phi, -uu, cos_phi) * sin_alpha;
    let num = difference_of_products(vv, vers_ap, -uu, sin_ap);
    var vers_l = clamp(num / den, 0.0, 2.0);
    if is_nan_f(num / den) {
        vers_l = 0.0;
    }
    let sin_l = safe_sqrt(vers_l * (2.0 - vers_l));
    let a_to_cp = sin_l * st_tangent(a, c - a) - vers_l * a;

    let b_to_cp = (a - b) + a_to_cp;
    let vt = u.y * 0.5 * dot(b_to_cp, b_to_cp);
    let sin_theta = safe_sqrt(vt * (2.0 - vt));
    let dir = normalize_or_zero(b + (sin_theta * st_tangent(b, b_to_cp) - vt * b));

    out.dir = dir;
    out.barycentrics = barycentrics_along(v0, v1, v2, p, dir);
    out.pdf = 1.0 / area;
    out.ok = true;
    return out;
}

// `barycentrics_along`: where the ray from p along dir meets the triangle's plane
// (Möller–Trumbore), clamped onto the triangle; a third each for a ray parallel to the plane.
fn barycentrics_along(v0: vec3f, v1: vec3f, v2: vec3f, p: vec3f, dir: vec3f) -> vec3f {
    let e1 = v1 - v0;
    let e2 = v2 - v0;
    let s1 = cross(dir, e2);
    let det = dot(s1, e1);
    if det == 0.0 {
        return vec3f(1.0 / 3.0);
    }
    let o = p - v0;
    var b1 = clamp(dot(o, s1) / det, 0.0, 1.0);
    var b2 = clamp(dot(dir, cross(o, e1)) / det, 0.0, 1.0);
    let sum = b1 + b2;
    if sum > 1.0 {
        b1 = b1 / sum;
        b2 = b2 / sum;
    }
    return vec3f(max(1.0 - b1 - b2, 0.0), b1, b2);
}
