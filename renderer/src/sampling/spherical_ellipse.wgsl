// Uniform solid-angle sampling of a disk through its spherical ellipse (Guillén et al. 2017, the
// polar parameterisation), the twin of `sampling/spherical_ellipse.rs`: the elliptic cone's frame
// and tangent-plane semi-axes in closed form, the quadrant's area by Carlson's R_F and R_J
// (`sampling/elliptic.wgsl`), the azimuth by at most MAX_ELLIPSE_NEWTON_STEPS safeguarded Newton steps.

struct SphericalEllipse {
    // s = minor axis, t = major axis, n = the cone's axis.
    frame: Frame,
    a: f32,
    b: f32,
    g_scale: f32,
    seed_ratio: f32,
    quarter: f32,
    ok: bool,
}

// G(ψ) for (s, c) = (sin ψ, cos ψ): the quadrant's sector [0, ψ] has area ψ − G(ψ).
fn sph_ellipse_g(e: SphericalEllipse, s: f32, c: f32) -> f32 {
    if s == 0.0 {
        return 0.0;
    }
    let a2 = e.a * e.a;
    let b2 = e.b * e.b;
    let diff = b2 - a2;
    let x = a2 * c * c;
    let y = x + b2 * s * s;
    let z = a2 + diff * s * s / (1.0 + b2);
    let r = carlson_rf_rj(x, y, z, a2);
    return e.g_scale * s * (r.x + diff / 3.0 * s * s * r.y);
}

// 1 − cos θ_max(ψ), without cancellation.
fn sph_ellipse_versine_max(e: SphericalEllipse, s: f32, c: f32) -> f32 {
    let a2 = e.a * e.a;
    let b2 = e.b * e.b;
    let d = a2 * c * c + b2 * s * s;
    let ab2 = a2 * b2;
    let outer = sqrt(d + ab2);
    return ab2 / (outer * (outer + sqrt(d)));
}

// (2 sin(α/2))² for tan α = t, without cancellation: the Lambert equal-area semi-axis.
fn sph_ellipse_lambert2(t: f32) -> f32 {
    let r = sqrt(1.0 + t * t);
    return 2.0 * t * t / (r * (r + 1.0));
}

// `SphericalEllipse::new`; ok = false where the caller samples by area.
fn sph_ellipse_new(p: vec3f, center: vec3f, n: vec3f, radius: f32) -> SphericalEllipse {
    var e: SphericalEllipse;
    e.ok = false;
    let v = center - p;
    let h = -dot(v, n);
    if !(h > 0.0) {
        return e;
    }
    let w = v + h * n;
    let cx = length(w);
    let d = sqrt(h * h + cx * cx);
    let hn = h / d;
    let cn = cx / d;
    let rn = radius / d;
    if !(rn > 0.0 && rn < MAX_ELLIPSE_RELATIVE_RADIUS && hn > 0.0) {
        return e;
    }
    let t = (1.0 - rn) * (1.0 + rn);
    let hr = hn * rn;
    let s = sqrt(t * t + 4.0 * hr * hr);
    var lambda: f32;
    if t >= 0.0 {
        lambda = 0.5 * (t + s);
    } else {
        lambda = 2.0 * hr * hr / (s - t);
    }
    let a = hr / lambda;
    let b = rn / sqrt(lambda);
    if !(PI * a * b >= MIN_ELLIPSE_SOLID_ANGLE && b <= MAX_ELLIPSE_TAN) {
        return e;
    }
    let zl = -n;
    let xl = normalize_or(w - n * dot(w, n), frame_from_normal(n).s);
    let axis_v = vec2f(cn, hn * (1.0 + rn * rn / lambda));
    let axis = axis_v * (1.0 / length(axis_v));
    e.frame = Frame(axis.y * xl - axis.x * zl, cross(zl, xl), axis.x * xl + axis.y * zl);
    e.a = a;
    e.b = b;
    e.g_scale = a / sqrt(1.0 + b * b);
    e.seed_ratio = sqrt(sph_ellipse_lambert2(a) / sph_ellipse_lambert2(b));
    e.quarter = FRAC_PI_2 - sph_ellipse_g(e, 1.0, 0.0);
    let omega = 4.0 * e.quarter;
    e.ok = omega >= MIN_ELLIPSE_SOLID_ANGLE && omega <= MAX_ELLIPSE_SOLID_ANGLE;
    return e;
}

fn sph_ellipse_solid_angle(e: SphericalEllipse) -> f32 {
    return 4.0 * e.quarter;
}

fn sph_ellipse_pdf(e: SphericalEllipse) -> f32 {
    return 0.25 / e.quarter;
}

// `SphericalEllipse::solve_azimuth`: (sin ψ, cos ψ) of the azimuth from the major axis whose
// sector holds the fraction t of the quadrant.
fn sph_ellipse_solve_azimuth(e: SphericalEllipse, t: f32) -> vec2f {
    let goal = t * e.quarter;
    var psi = atan2_precise(e.seed_ratio * sin(FRAC_PI_2 * t), cos(FRAC_PI_2 * t));
    var lo = 0.0;
    var hi = FRAC_PI_2;
    for (var i = 0u; i < MAX_ELLIPSE_NEWTON_STEPS; i++) {
        let s = sin(psi);
        let c = cos(psi);
        psi = atan2_precise(s, c);
        let f = psi - sph_ellipse_g(e, s, c) - goal;
        if f == 0.0 {
            break;
        } else if f > 0.0 {
            hi = psi;
        } else {
            lo = psi;
        }
        let newton = psi - f / sph_ellipse_versine_max(e, s, c);
        if newton > lo && newton < hi {
            let step = newton - psi;
            psi = newton;
            if abs(step) <= ELLIPSE_NEWTON_TOLERANCE {
                break;
            }
        } else {
            psi = 0.5 * (lo + hi);
            if hi - lo <= ELLIPSE_NEWTON_TOLERANCE {
                break;
            }
        }
    }
    return vec2f(sin(psi), cos(psi));
}

// `SphericalEllipse::sample`: a direction uniform in solid angle over the ellipse.
fn sph_ellipse_sample(e: SphericalEllipse, u: vec2f) -> vec3f {
    let q = min(u32(4.0 * u.x), 3u);
    let f = 4.0 * u.x - f32(q);
    var t = f;
    if q % 2u == 1u {
        t = 1.0 - f;
    }
    let sc = sph_ellipse_solve_azimuth(e, clamp(t, 0.0, 1.0));
    var sx = sc.x;
    var sy = sc.y;
    if q == 1u || q == 2u {
        sy = -sy;
    }
    if q >= 2u {
        sx = -sx;
    }
    let h = u.y * sph_ellipse_versine_max(e, sc.x, sc.y);
    let sin_theta = safe_sqrt(h * (2.0 - h));
    return to_world(e.frame, vec3f(sin_theta * sx, sin_theta * sy, 1.0 - h));
}
