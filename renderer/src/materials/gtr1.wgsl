// The clearcoat lobe's microfacets, the twin of `materials/gtr1.rs`: Burley's isotropic GTR1
// distribution (sampled ∝ D·cosθ) and the separable GGX masking Mitsuba's principled pairs with
// it.

fn gtr1_d(alpha: f32, m: vec3f) -> f32 {
    let a2 = alpha * alpha;
    let cos2 = m.z * m.z;
    let d = (a2 - 1.0) / (PI * log(a2) * (1.0 + (a2 - 1.0) * cos2));
    return select(0.0, d, d * m.z > 1e-20);
}

fn gtr1_pdf(alpha: f32, m: vec3f) -> f32 {
    return select(m.z * gtr1_d(alpha, m), 0.0, m.z < 0.0);
}

fn gtr1_sample(alpha: f32, u: vec2f) -> vec3f {
    let a2 = alpha * alpha;
    let cos2 = (1.0 - pow(a2, 1.0 - u.y)) / (1.0 - a2);
    let s = safe_sqrt(1.0 - cos2);
    let c = safe_sqrt(cos2);
    let phi = TAU * u.x;
    return vec3f(cos(phi) * s, sin(phi) * s, c);
}

fn gtr1_smith_ggx1(v: vec3f, m: vec3f, alpha: f32) -> f32 {
    if dot(v, m) * v.z <= 0.0 {
        return 0.0;
    }
    if v.z == 1.0 {
        return 1.0;
    }
    let cos2 = v.z * v.z;
    let tan2 = (1.0 - cos2) / cos2;
    return 2.0 / (1.0 + sqrt(1.0 + alpha * alpha * tan2));
}

fn gtr1_clearcoat_g(wo: vec3f, wi: vec3f, m: vec3f) -> f32 {
    return gtr1_smith_ggx1(wo, m, 0.25) * gtr1_smith_ggx1(wi, m, 0.25);
}

fn gtr1_clearcoat_alpha(gloss: f32) -> f32 {
    return 0.001 * gloss + (0.1 - 0.1 * gloss);
}
