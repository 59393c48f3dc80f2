// Anisotropic Beckmann with the exact Smith masking and Mitsuba's visible-normal sampler, the
// twin of `materials/beckmann.rs` (same steps, same constants: BECKMANN_SAMPLE_TOLERANCE and
// BECKMANN_SAMPLE_MAX_STEPS from the Rust ones through the prelude).

const INV_SQRT_PI: f32 = 0.5641896f;

fn beckmann_d(alpha_u: f32, alpha_v: f32, h: vec3f) -> f32 {
    if h.z <= 0.0 {
        return 0.0;
    }
    let x = h.x / alpha_u;
    let y = h.y / alpha_v;
    let z2 = h.z * h.z;
    let r = exp(-(x * x + y * y) / z2) / (PI * alpha_u * alpha_v * z2 * z2);
    return select(0.0, r, is_finite_f(r));
}

fn beckmann_lambda(alpha_u: f32, alpha_v: f32, w: vec3f) -> f32 {
    let x = alpha_u * w.x;
    let y = alpha_v * w.y;
    let a = abs(w.z) / sqrt(x * x + y * y);
    if !is_finite_f(a) {
        return 0.0;
    }
    return max(0.5 * (exp(-a * a) * INV_SQRT_PI / a - erfc(a)), 0.0);
}

fn beckmann_g1(alpha_u: f32, alpha_v: f32, w: vec3f) -> f32 {
    return 1.0 / (1.0 + beckmann_lambda(alpha_u, alpha_v, w));
}

// Unit-roughness visible slopes seen from (sin, 0, cos) (`sample_slopes`).
fn beckmann_sample_slopes(cos_t: f32, sin_t: f32, u: vec2f) -> vec2f {
    let tan_t = sin_t / cos_t;
    let cot_t = cos_t / sin_t;
    let theta = acos(cos_t);
    let ux = clamp(u.x, 1e-6, 1.0 - 1e-6);
    let max_t = erf(cot_t);
    let norm = 1.0 / (1.0 + max_t + INV_SQRT_PI * tan_t * exp(-cot_t * cot_t));
    var lo = -1.0;
    var hi = max_t;
    let guess_exp = 1.0 + theta * (-0.876 + theta * (0.4265 - 0.0594 * theta));
    var t = max_t - (max_t + 1.0) * pow(1.0 - ux, guess_exp);
    for (var i = 0u; i < BECKMANN_SAMPLE_MAX_STEPS; i++) {
        if !(t >= lo && t <= hi) {
            t = 0.5 * (lo + hi);
        }
        let e = erfinv(t);
        let value = norm * (1.0 + t + INV_SQRT_PI * tan_t * exp(-e * e)) - ux;
        if abs(value) < BECKMANN_SAMPLE_TOLERANCE {
            break;
        }
        if value > 0.0 {
            hi = t;
        } else {
            lo = t;
        }
        let derivative = norm * (1.0 - e * tan_t);
        t -= value / derivative;
    }
    let uy = clamp(u.y, 1e-6, 1.0 - 1e-6);
    return vec2f(erfinv(t), erfinv(2.0 * uy - 1.0));
}

fn beckmann_sample_visible_normal(alpha_u: f32, alpha_v: f32, wo: vec3f, u: vec2f) -> vec3f {
    let w = normalize_or(vec3f(alpha_u * wo.x, alpha_v * wo.y, wo.z), vec3f(0.0, 0.0, 1.0));
    let sin_t = length(w.xy);
    var cos_phi = 1.0;
    var sin_phi = 0.0;
    if sin_t > 0.0 {
        cos_phi = w.x / sin_t;
        sin_phi = w.y / sin_t;
    }
    let s = beckmann_sample_slopes(max(w.z, 1e-7), sin_t, u);
    let sx = alpha_u * (cos_phi * s.x - sin_phi * s.y);
    let sy = alpha_v * (sin_phi * s.x + cos_phi * s.y);
    return normalize_glam(vec3f(-sx, -sy, 1.0));
}
