// Lambertian reflection, the twin of `materials/diffuse.rs`.

fn diffuse_eval(m: Material, wo: vec3f, wi: vec3f) -> vec3f {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return vec3f(0.0);
    }
    return m.a.xyz * (INV_PI * wi.z);
}

fn diffuse_pdf(wo: vec3f, wi: vec3f) -> f32 {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return 0.0;
    }
    return max(wi.z, 0.0) * INV_PI;
}

fn diffuse_sample(m: Material, wo: vec3f, u: vec2f) -> BsdfSample {
    if wo.z <= 0.0 {
        return no_bsdf_sample();
    }
    let wi = sample_cosine_hemisphere(u);
    if wi.z <= 0.0 {
        return no_bsdf_sample();
    }
    return reflection_sample(wi, m.a.xyz, INV_PI * wi.z, false);
}
