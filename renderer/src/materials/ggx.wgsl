// GGX with separable Smith masking, isotropic and anisotropic, the twin of `materials/ggx.rs`,
// including the spherical-cap visible-normal sampler (Dupuy & Benyoub 2023).

fn ggx_is_smooth(alpha: f32) -> bool {
    return alpha < SMOOTH_ALPHA;
}

fn ggx_d(alpha: f32, h: vec3f) -> f32 {
    if h.z <= 0.0 {
        return 0.0;
    }
    let a2 = alpha * alpha;
    let t = (h.x * h.x + h.y * h.y) / a2 + h.z * h.z;
    return 1.0 / (PI * a2 * t * t);
}

fn ggx_lambda(alpha: f32, w: vec3f) -> f32 {
    let a = alpha * alpha * (w.x * w.x + w.y * w.y) / (w.z * w.z);
    if !is_finite_f(a) {
        return inf();
    }
    return 0.5 * a / (1.0 + sqrt(1.0 + a));
}

fn ggx_g1(alpha: f32, w: vec3f) -> f32 {
    let z = abs(w.z);
    let r = sqrt(z * z + alpha * alpha * (w.x * w.x + w.y * w.y));
    if r <= 0.0 {
        return 0.0;
    }
    return 2.0 * z / (z + r);
}

fn ggx_g2_separable(alpha: f32, wo: vec3f, wi: vec3f) -> f32 {
    return ggx_g1(alpha, wo) * ggx_g1(alpha, wi);
}

// The half vector (xyz) and wo·h = |wo + wi|/2 (w).
fn ggx_half_vector(wo: vec3f, wi: vec3f) -> vec4f {
    let s = wo + wi;
    let len = length(s);
    return vec4f(s / len, 0.5 * len);
}

fn ggx_sample_visible_normal(alpha: f32, wo: vec3f, u: vec2f) -> vec3f {
    return ggx_sample_visible_normal_anisotropic(alpha, alpha, wo, u);
}

fn ggx_visible_normal_pdf(alpha: f32, wo: vec3f, h: vec3f) -> f32 {
    if wo.z <= 0.0 {
        return 0.0;
    }
    return ggx_g1(alpha, wo) * max(dot(wo, h), 0.0) * ggx_d(alpha, h) / wo.z;
}

// The anisotropic forms (roughness αu along x, αv along y), the isotropic ones where αu = αv.
fn ggx_d_anisotropic(alpha_u: f32, alpha_v: f32, h: vec3f) -> f32 {
    if alpha_u == alpha_v {
        return ggx_d(alpha_u, h);
    }
    if h.z <= 0.0 {
        return 0.0;
    }
    let x = h.x / alpha_u;
    let y = h.y / alpha_v;
    let t = x * x + y * y + h.z * h.z;
    return 1.0 / (PI * alpha_u * alpha_v * t * t);
}

fn ggx_g1_anisotropic(alpha_u: f32, alpha_v: f32, w: vec3f) -> f32 {
    if alpha_u == alpha_v {
        return ggx_g1(alpha_u, w);
    }
    let z = abs(w.z);
    let x = alpha_u * w.x;
    let y = alpha_v * w.y;
    let r = sqrt(z * z + x * x + y * y);
    if r <= 0.0 {
        return 0.0;
    }
    return 2.0 * z / (z + r);
}

fn ggx_sample_visible_normal_anisotropic(alpha_u: f32, alpha_v: f32, wo: vec3f, u: vec2f) -> vec3f {
    let wo_std = normalize_or(vec3f(wo.x * alpha_u, wo.y * alpha_v, wo.z), vec3f(0.0, 0.0, 1.0));
    let phi = TAU * u.x;
    let z = fma(1.0 - u.y, 1.0 + wo_std.z, -wo_std.z);
    let sin_theta = safe_sqrt(1.0 - z * z);
    let h_std = vec3f(sin_theta * cos(phi), sin_theta * sin(phi), z) + wo_std;
    return normalize_or(vec3f(h_std.x * alpha_u, h_std.y * alpha_v, max(h_std.z, 0.0)), vec3f(0.0, 0.0, 1.0));
}
