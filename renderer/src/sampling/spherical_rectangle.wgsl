// Uniform solid-angle sampling of a rectangle (Ureña, Fajardo & King 2013), the twin of
// `sampling/spherical_rectangle.rs`: closed-form abscissa polished by safeguarded Newton steps,
// cancellation-free forms of 1 ± h.

struct SphericalRectangle {
    corner: vec3f,
    edge_u: vec3f,
    edge_v: vec3f,
    exl: f32,
    eyl: f32,
    x0: f32,
    y0: f32,
    y1: f32,
    z0: f32,
    b0: f32,
    b1: f32,
    one_minus_b0sq: f32,
    sin_k: f32,
    cos_k: f32,
    solid_angle: f32,
    ok: bool,
}

fn sph_rect_partial_solid_angle(r: SphericalRectangle, width: f32) -> f32 {
    let x0 = r.x0;
    let x1 = r.x0 + width;
    let v00 = vec3f(x0, r.y0, r.z0);
    let v01 = vec3f(x0, r.y1, r.z0);
    let v10 = vec3f(x1, r.y0, r.z0);
    let v11 = vec3f(x1, r.y1, r.z0);
    let triple = -r.z0 * width * r.eyl;
    return solid_angle_from_vectors(triple, v00, v10, v11) + solid_angle_from_vectors(triple, v00, v11, v01);
}

fn normalize2(v: vec2f) -> vec2f {
    return v * (1.0 / length(v));
}

fn sph_rect_new(p: vec3f, corner: vec3f, edge_u: vec3f, edge_v: vec3f) -> SphericalRectangle {
    var r: SphericalRectangle;
    r.ok = false;
    let exl = length(edge_u);
    let eyl = length(edge_v);
    if !(exl > 0.0 && eyl > 0.0 && is_finite_f(exl) && is_finite_f(eyl)) {
        return r;
    }
    let x = edge_u / exl;
    let y0v = edge_v / eyl;
    if abs(dot(x, y0v)) > MAX_EDGE_COS {
        return r;
    }
    let y = normalize_glam(y0v - dot(x, y0v) * x);
    let d = corner - p;
    let z0 = -abs(dot(d, cross(x, y)));
    if z0 >= -1e-6 * length(d) || is_nan_f(z0) {
        return r;
    }
    let x0 = dot(d, x);
    let y0 = dot(d, y);
    let y1 = y0 + eyl;
    let z2 = z0 * z0;
    let g2 = normalize2(vec2f(x0 * y1, -z0 * sqrt(x0 * x0 + y1 * y1 + z2)));
    let g3 = normalize2(vec2f(-x0 * y0, -z0 * sqrt(x0 * x0 + y0 * y0 + z2)));
    r.corner = corner;
    r.edge_u = edge_u;
    r.edge_v = edge_v;
    r.exl = exl;
    r.eyl = eyl;
    r.x0 = x0;
    r.y0 = y0;
    r.y1 = y1;
    r.z0 = z0;
    r.b0 = -y0 / sqrt(z2 + y0 * y0);
    r.b1 = y1 / sqrt(z2 + y1 * y1);
    r.one_minus_b0sq = z2 / (z2 + y0 * y0);
    r.cos_k = g2.x * g3.x - g2.y * g3.y;
    r.sin_k = -(g2.y * g3.x + g2.x * g3.y);
    r.solid_angle = sph_rect_partial_solid_angle(r, exl);
    r.ok = r.solid_angle > 0.0 && is_finite_f(r.solid_angle);
    return r;
}

// h(yb) − h(ya) without cancellation.
fn sph_rect_h_diff(ya: f32, yb: f32, dd2: f32) -> f32 {
    let ra = sqrt(dd2 + ya * ya);
    let rb = sqrt(dd2 + yb * yb);
    if ya * yb > 0.0 {
        return dd2 * (yb - ya) * (yb + ya) / (ra * rb * (yb * ra + ya * rb));
    }
    return yb / rb - ya / ra;
}

// (h, 1 − h, 1 + h) without cancellation.
fn sph_rect_h_terms(y: f32, dd2: f32) -> vec3f {
    let r = sqrt(dd2 + y * y);
    if y > 0.0 {
        return vec3f(y / r, dd2 / (r * (r + y)), (r + y) / r);
    }
    return vec3f(y / r, (r - y) / r, dd2 / (r * (r - y)));
}

fn sph_rect_solve_width(r: SphericalRectangle, goal: f32, guess: f32) -> f32 {
    var lo = 0.0;
    var hi = r.exl;
    var w: f32;
    if is_nan_f(guess) {
        w = 0.5 * r.exl;
    } else {
        w = clamp(guess, lo, hi);
    }
    for (var i = 0u; i < MAX_NEWTON_STEPS; i++) {
        let f = sph_rect_partial_solid_angle(r, w) - goal;
        if f == 0.0 {
            break;
        } else if f > 0.0 {
            hi = w;
        } else {
            lo = w;
        }
        let x = r.x0 + w;
        let dd2 = x * x + r.z0 * r.z0;
        let newton = w - f * dd2 / (-r.z0 * sph_rect_h_diff(r.y0, r.y1, dd2));
        if newton > lo && newton < hi {
            let step = newton - w;
            w = newton;
            if abs(step) <= 1e-4 * sqrt(dd2) {
                break;
            }
        } else {
            w = 0.5 * (lo + hi);
            if hi - lo <= 4.0 * 1.1920929e-7 * r.exl {
                break;
            }
        }
    }
    return w;
}

fn sph_rect_sample(r: SphericalRectangle, u: vec2f) -> vec3f {
    let sd = sin(u.x * r.solid_angle);
    let cd = cos(u.x * r.solid_angle);
    let sin_au = r.sin_k * cd + r.cos_k * sd;
    let cos_au = r.cos_k * cd - r.sin_k * sd;
    let fu = fma(r.b0, cos_au, -r.b1) / sin_au;
    let xu0 = copysign(-r.z0 / safe_sqrt(fma(fu, fu, -r.one_minus_b0sq)), fu);
    let width = sph_rect_solve_width(r, u.x * r.solid_angle, xu0 - r.x0);
    let xu = r.x0 + width;

    let dd2 = xu * xu + r.z0 * r.z0;
    let t0 = sph_rect_h_terms(r.y0, dd2);
    let t1 = sph_rect_h_terms(r.y1, dd2);
    let hv = t0.x + u.y * sph_rect_h_diff(r.y0, r.y1, dd2);
    let one_minus = (1.0 - u.y) * t0.y + u.y * t1.y;
    let one_plus = (1.0 - u.y) * t0.z + u.y * t1.z;
    var yv = hv * sqrt(dd2) / sqrt(one_minus * one_plus);
    if is_nan_f(yv) {
        yv = r.y0 + u.y * r.eyl;
    }
    yv = clamp(yv, r.y0, r.y1);
    let s = width / r.exl;
    let t = clamp((yv - r.y0) / r.eyl, 0.0, 1.0);
    return r.corner + s * r.edge_u + t * r.edge_v;
}

// `SphericalRectangle::invert`: the u that samples `point` (on the rectangle).
fn sph_rect_invert(r: SphericalRectangle, point: vec3f) -> vec2f {
    // Parallelogram coordinates (s, t) by the 2×2 normal equations.
    let d = point - r.corner;
    let uu = dot(r.edge_u, r.edge_u);
    let uv = dot(r.edge_u, r.edge_v);
    let vv = dot(r.edge_v, r.edge_v);
    let ru = dot(d, r.edge_u);
    let rv = dot(d, r.edge_v);
    let det = uu * vv - uv * uv;
    let s = clamp((ru * vv - rv * uv) / det, 0.0, 1.0);
    let t = clamp((rv * uu - ru * uv) / det, 0.0, 1.0);
    let u0 = sph_rect_partial_solid_angle(r, s * r.exl) / r.solid_angle;
    let xu = r.x0 + s * r.exl;
    let yv = r.y0 + t * r.eyl;
    let dd2 = xu * xu + r.z0 * r.z0;
    let u1 = sph_rect_h_diff(r.y0, yv, dd2) / sph_rect_h_diff(r.y0, r.y1, dd2);
    return clamp(vec2f(u0, u1), vec2f(0.0), vec2f(1.0));
}
