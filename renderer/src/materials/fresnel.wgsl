// Fresnel reflectance, the twin of `materials/fresnel.rs`: exact conductor Fresnel for a complex
// IOR (pbrt-v4 `FrComplex`, complex numbers as vec2 (re, im)), exact dielectric Fresnel (pbrt-v4
// `FrDielectric`, and its form for a refraction whose two cosines are known) and Schlick's
// approximation.

fn c_mul(a: vec2f, b: vec2f) -> vec2f {
    return vec2f(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x);
}

fn c_norm(a: vec2f) -> f32 {
    return a.x * a.x + a.y * a.y;
}

fn c_div(a: vec2f, b: vec2f) -> vec2f {
    let s = 1.0 / c_norm(b);
    return vec2f((a.x * b.x + a.y * b.y) * s, (a.y * b.x - a.x * b.y) * s);
}

// Principal square root, stable for either sign of the real part.
fn c_sqrt(z: vec2f) -> vec2f {
    let n = sqrt(c_norm(z));
    if n == 0.0 {
        return vec2f(0.0);
    }
    let t1 = sqrt(0.5 * (n + abs(z.x)));
    let t2 = 0.5 * z.y / t1;
    if z.x >= 0.0 {
        return vec2f(t1, t2);
    }
    return vec2f(abs(t2), copysign(t1, z.y));
}

fn fresnel_complex(cos_theta_i: f32, eta_re: f32, k: f32) -> f32 {
    let cos_i = clamp(cos_theta_i, 0.0, 1.0);
    let eta = vec2f(eta_re, k);
    if c_norm(eta) == 0.0 {
        return 1.0;
    }
    let sin2_i = 1.0 - cos_i * cos_i;
    let sin2_t = c_div(vec2f(sin2_i, 0.0), c_mul(eta, eta));
    let cos_t = c_sqrt(vec2f(1.0, 0.0) - sin2_t);
    let ci = vec2f(cos_i, 0.0);
    let r_parl = c_div(eta * cos_i - cos_t, eta * cos_i + cos_t);
    let r_perp = c_div(ci - c_mul(eta, cos_t), ci + c_mul(eta, cos_t));
    return clamp(0.5 * (c_norm(r_parl) + c_norm(r_perp)), 0.0, 1.0);
}

fn fresnel_conductor(cos_theta_i: f32, eta: vec3f, k: vec3f) -> vec3f {
    return vec3f(
        fresnel_complex(cos_theta_i, eta.x, k.x),
        fresnel_complex(cos_theta_i, eta.y, k.y),
        fresnel_complex(cos_theta_i, eta.z, k.z),
    );
}

// #if HAS_DIELECTRIC_FRESNEL
// `cos_theta_i` against the normal of the side of index 1, `eta` = η_inside/η_outside; a negative
// cosine is seen from inside, with 1/η. Total internal reflection gives 1.
fn fresnel_dielectric(cos_theta_i: f32, eta_in: f32) -> f32 {
    var cos_i = clamp(cos_theta_i, -1.0, 1.0);
    var eta = eta_in;
    if cos_i < 0.0 {
        eta = 1.0 / eta;
        cos_i = -cos_i;
    }
    let sin2_i = 1.0 - cos_i * cos_i;
    let sin2_t = sin2_i / (eta * eta);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = safe_sqrt(1.0 - sin2_t);
    let r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    let r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return clamp(0.5 * (r_parl * r_parl + r_perp * r_perp), 0.0, 1.0);
}
// #endif

// #if HAS_REFRACTION

// `fresnel_dielectric` of a refraction from both of its cosines (outside, inside; both ≥ 0):
// symmetric in the pair, where recomputing one from the other would cancel near the critical angle.
fn fresnel_dielectric_pair(cos_out: f32, cos_in: f32, eta: f32) -> f32 {
    let r_parl = (eta * cos_out - cos_in) / (eta * cos_out + cos_in);
    let r_perp = (cos_out - eta * cos_in) / (cos_out + eta * cos_in);
    let f = 0.5 * (r_parl * r_parl + r_perp * r_perp);
    if is_finite_f(f) {
        return clamp(f, 0.0, 1.0);
    }
    return 1.0;
}
// #endif

fn fresnel_schlick(f0: f32, cos_theta: f32) -> f32 {
    let m = 1.0 - clamp(cos_theta, 0.0, 1.0);
    let m2 = m * m;
    return f0 + (1.0 - f0) * (m2 * m2 * m);
}

fn schlick_f0_from_ior(ior: f32) -> f32 {
    let r = (ior - 1.0) / (ior + 1.0);
    return r * r;
}
