// Projected-solid-angle sampling of a convex spherical polygon clipped to the upper hemisphere
// (Peters 2021), the twin of `sampling/projected_solid_angle.rs`, whose module doc explains the
// geometry: wedges between the origin's radial lines through the vertices, each bounded by an
// outer and an inner elliptic arc (the origin when the zenith is inside), the azimuth by a
// bracketed Newton iteration (at most PSA_NEWTON_STEPS), r² uniform between the arcs. Sampling
// only: the GPU's pdf is cos θ / Ω⊥ and needs no inverse.

// `ProjectedPolygon`; n < 3 stands for `None`. start = NONE when the zenith is inside.
struct PsaPolygon {
    v: array<vec3f, PSA_MAX_VERTICES>,
    n: u32,
    area: f32,
    abs_sum: f32,
    start: u32,
    end: u32,
}

// `sector`: signed area of the elliptic sector along the arc a → b.
fn psa_sector(a: vec3f, b: vec3f) -> f32 {
    let c = cross(a, b - a);
    let len = length(c);
    if len > 0.0 {
        return 0.5 * atan2_precise(len, dot(a, b)) * (c.z / len);
    }
    return 0.0;
}

fn psa_angle(a: vec3f, b: vec3f) -> f32 {
    return atan2_precise(length(cross(a, b - a)), dot(a, b));
}

fn psa_arc_normal(a: vec3f, b: vec3f) -> vec3f {
    return normalize_or_zero(cross(a, b - a));
}

// `arc_point_unnormalised`: (|m_z| h, −sign(m_z) m·h).
fn psa_arc_point(m: vec3f, h: vec3f) -> vec3f {
    let mh = m.x * h.x + m.y * h.y;
    let mz = abs(m.z);
    return vec3f(mz * h.x, mz * h.y, select(-mh, mh, m.z < 0.0));
}

// `arc_r2_z2`: (r², z²) of the arc's point at azimuth h.
fn psa_arc_r2_z2(m: vec3f, h: vec3f) -> vec2f {
    let mh = m.x * h.x + m.y * h.y;
    let a = m.z * m.z;
    let b = mh * mh;
    let d = a + b;
    if d > 0.0 {
        return vec2f(a / d, b / d);
    }
    return vec2f(0.0, 1.0);
}

fn psa_rotate(h: vec3f, phi: f32) -> vec3f {
    let s = sin(phi);
    let c = cos(phi);
    return vec3f(c * h.x - s * h.y, s * h.x + c * h.y, 0.0);
}

// `azimuth_from`, in [−π/2, 3π/2).
fn psa_azimuth_from(h: vec3f, v: vec3f) -> f32 {
    let a = atan2_precise(h.x * v.y - h.y * v.x, h.x * v.x + h.y * v.y);
    if a < -FRAC_PI_2 {
        return a + 2.0 * PI;
    }
    return a;
}

// `ProjectedPolygon::new` for the `count` vectors of w (local frame, any length).
fn psa_polygon(w: array<vec3f, 4>, count: u32) -> PsaPolygon {
    var out: PsaPolygon;
    out.n = 0u;
    out.start = NONE;
    out.end = NONE;
    var clipped: array<vec3f, PSA_MAX_VERTICES>;
    var k = 0u;
    for (var i = 0u; i < count; i++) {
        let a = w[i];
        let b = w[(i + 1u) % count];
        if a.z >= 0.0 && k < PSA_MAX_VERTICES {
            clipped[k] = a;
            k++;
        }
        if ((a.z > 0.0 && b.z < 0.0) || (a.z < 0.0 && b.z > 0.0)) && k < PSA_MAX_VERTICES {
            let t = a.z / (a.z - b.z);
            let x = a + t * (b - a);
            clipped[k] = vec3f(x.x, x.y, 0.0);
            k++;
        }
    }
    var n = 0u;
    for (var i = 0u; i < k; i++) {
        let d = normalize_or_zero(clipped[i]);
        if any(d != vec3f(0.0)) && (n == 0u || any(d != out.v[n - 1u])) {
            out.v[n] = d;
            n++;
        }
    }
    if n > 1u && all(out.v[n - 1u] == out.v[0]) {
        n--;
    }
    if n < 3u {
        return out;
    }
    var area = 0.0;
    var abs_sum = 0.0;
    for (var i = 0u; i < n; i++) {
        let s = psa_sector(out.v[i], out.v[(i + 1u) % n]);
        area += s;
        abs_sum += abs(s);
    }
    if area < 0.0 {
        for (var i = 0u; i < n / 2u; i++) {
            let t = out.v[i];
            out.v[i] = out.v[n - 1u - i];
            out.v[n - 1u - i] = t;
        }
        area = -area;
    }
    out.n = n;
    out.area = area;
    out.abs_sum = abs_sum;
    // Outer edges (positive sectors) run counter-clockwise; the chains' ends, as on the CPU.
    var all_outer_or_flat = true;
    for (var i = 0u; i < n; i++) {
        if psa_sector(out.v[i], out.v[(i + 1u) % n]) < 0.0 {
            all_outer_or_flat = false;
        }
    }
    if !all_outer_or_flat {
        var start = NONE;
        var end = NONE;
        for (var i = 0u; i < n; i++) {
            let here = psa_sector(out.v[i], out.v[(i + 1u) % n]) > 0.0;
            let before = psa_sector(out.v[(i + n - 1u) % n], out.v[i]) > 0.0;
            if here && !before && start == NONE {
                start = i;
            }
            if !here && before && end == NONE {
                end = i;
            }
        }
        if start != NONE && end != NONE {
            out.start = start;
            out.end = end;
        }
    }
    return out;
}

// `conditioned`: positive, and Σ|S_e| ≤ PSA_MAX_CONDITION · Ω⊥.
fn psa_conditioned(area: f32, abs_sum: f32) -> bool {
    return area > 0.0 && abs_sum <= PSA_MAX_CONDITION * area;
}

// `Wedge`.
struct PsaWedge {
    h: vec3f,
    phi0: f32,
    phi1: f32,
    mo: vec3f,
    o0: vec3f,
    mi: vec3f,
    i0: vec3f,
}

fn psa_wedge_cdf(w: PsaWedge, hp: vec3f) -> f32 {
    let o = normalize_or_zero(psa_arc_point(w.mo, hp));
    let i = normalize_or_zero(psa_arc_point(w.mi, hp));
    return 0.5 * (abs(w.mo.z) * psa_angle(w.o0, o) - abs(w.mi.z) * psa_angle(w.i0, i));
}

fn psa_wedge_density(w: PsaWedge, hp: vec3f) -> f32 {
    let o = psa_arc_r2_z2(w.mo, hp);
    let i = psa_arc_r2_z2(w.mi, hp);
    if o.x < 0.5 {
        return 0.5 * (o.x - i.x);
    }
    return 0.5 * (i.y - o.y);
}

// `Wedge::solve`: the azimuth where the wedge's CDF reaches goal.
fn psa_wedge_solve(w: PsaWedge, goal: f32, area: f32) -> f32 {
    let width = w.phi1 - w.phi0;
    let f0 = max(psa_wedge_density(w, psa_rotate(w.h, w.phi0)), 0.0);
    let f1 = max(psa_wedge_density(w, psa_rotate(w.h, w.phi1)), 0.0);
    var t = 0.5;
    if area > 0.0 {
        t = clamp(goal / area, 0.0, 1.0);
    }
    let den = f0 + safe_sqrt((1.0 - t) * f0 * f0 + t * f1 * f1);
    var x = t;
    if den > 0.0 {
        x = t * (f0 + f1) / den;
    }
    var lo = w.phi0;
    var hi = w.phi1;
    var phi = w.phi0 + clamp(x, 0.0, 1.0) * width;
    for (var k = 0u; k < PSA_NEWTON_STEPS; k++) {
        let hp = psa_rotate(w.h, phi);
        let f = psa_wedge_cdf(w, hp) - goal;
        if f > 0.0 {
            hi = phi;
        } else {
            lo = phi;
        }
        let newton = phi - f / psa_wedge_density(w, hp);
        if abs(newton - phi) <= PSA_NEWTON_TOLERANCE * width {
            return clamp(newton, lo, hi);
        }
        if hi - lo <= PSA_NEWTON_TOLERANCE * width {
            return 0.5 * (lo + hi);
        }
        if newton > lo && newton < hi {
            phi = newton;
        } else {
            phi = 0.5 * (lo + hi);
        }
    }
    return phi;
}

// `Wedge::lift`.
fn psa_wedge_lift(w: PsaWedge, phi: f32, uy: f32) -> vec3f {
    let hp = psa_rotate(w.h, phi);
    let o = psa_arc_r2_z2(w.mo, hp);
    let i = psa_arc_r2_z2(w.mi, hp);
    let r = safe_sqrt(i.x + uy * (o.x - i.x));
    let z = safe_sqrt(i.y + uy * (o.y - i.y));
    return vec3f(r * hp.x, r * hp.y, z);
}

// `ProjectedPolygon::sample_around_zenith`.
fn psa_sample_around_zenith(poly: PsaPolygon, goal: f32, uy: f32) -> vec3f {
    let n = poly.n;
    var acc = 0.0;
    var found = false;
    var a = vec3f(0.0);
    var b = vec3f(0.0);
    var f = 0.0;
    for (var i = 0u; i < n; i++) {
        let ai = poly.v[i];
        let bi = poly.v[(i + 1u) % n];
        let s = psa_sector(ai, bi);
        if s <= 0.0 {
            continue;
        }
        found = true;
        a = ai;
        b = bi;
        f = clamp((goal - acc) / s, 0.0, 1.0);
        if goal < acc + s {
            break;
        }
        acc += s;
    }
    if !found {
        return vec3f(0.0, 0.0, 1.0);
    }
    let ang = f * psa_angle(a, b);
    let e = b - a;
    let t = normalize_or_zero(e - dot(e, a) * a);
    let x = cos(ang) * a + sin(ang) * t;
    let s = sqrt(uy);
    return vec3f(s * x.x, s * x.y, safe_sqrt((1.0 - uy) + uy * x.z * x.z));
}

// `ProjectedPolygon::sample`: the local direction for u, density cos θ / Ω⊥ (walks the wedges
// of `ProjectedPolygon::wedges` in order until the one holding u.x · Ω⊥).
fn psa_sample(poly: PsaPolygon, u: vec2f) -> vec3f {
    let goal = u.x * poly.area;
    if poly.start == NONE {
        return psa_sample_around_zenith(poly, goal, u.y);
    }
    let n = poly.n;
    let start = poly.start;
    let end = poly.end;
    let s = poly.v[start];
    let h = normalize_or_zero(vec3f(s.x, s.y, 0.0));
    var io = start;
    var ii = start;
    var o0 = s;
    var i0 = s;
    var phi0 = 0.0;
    let phi_end = psa_azimuth_from(h, poly.v[end]);
    var acc = 0.0;
    var have_last = false;
    var last: PsaWedge;
    var last_area = 0.0;
    for (var step = 0u; step < n; step++) {
        if io == end && ii == end {
            break;
        }
        let no = (io + 1u) % n;
        let ni = (ii + n - 1u) % n;
        var phi_o = inf();
        if io != end {
            phi_o = select(psa_azimuth_from(h, poly.v[no]), phi_end, no == end);
        }
        var phi_i = inf();
        if ii != end {
            phi_i = select(psa_azimuth_from(h, poly.v[ni]), phi_end, ni == end);
        }
        let mo = psa_arc_normal(poly.v[io], poly.v[no]);
        let mi = psa_arc_normal(poly.v[ii], poly.v[ni]);
        let phi1 = max(min(phi_o, phi_i), phi0);
        let h1 = psa_rotate(h, phi1);
        var o1 = o0;
        if io != end {
            o1 = select(normalize_or_zero(psa_arc_point(mo, h1)), poly.v[no], phi_o <= phi_i);
        }
        var i1 = i0;
        if ii != end {
            i1 = select(normalize_or_zero(psa_arc_point(mi, h1)), poly.v[ni], phi_i <= phi_o);
        }
        let w = PsaWedge(h, phi0, phi1, mo, o0, mi, i0);
        let area = 0.5 * (abs(mo.z) * psa_angle(o0, o1) - abs(mi.z) * psa_angle(i0, i1));
        if area > 0.0 {
            have_last = true;
            last = w;
            last_area = area;
            if goal < acc + area {
                return psa_wedge_lift(w, psa_wedge_solve(w, goal - acc, area), u.y);
            }
            acc += area;
        }
        if phi_o <= phi_i {
            io = no;
        }
        if phi_i <= phi_o {
            ii = ni;
        }
        o0 = o1;
        i0 = i1;
        phi0 = phi1;
    }
    if have_last {
        return psa_wedge_lift(last, psa_wedge_solve(last, last_area, last_area), u.y);
    }
    return poly.v[start];
}
