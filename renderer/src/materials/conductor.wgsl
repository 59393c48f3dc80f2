// Microfacet conductor (or a perfect mirror below SMOOTH_ALPHA), the twin of
// `materials/conductor.rs`.

fn conductor_fresnel(m: Material, cos_h: f32) -> vec3f {
    switch m.h.z {
// #if HAS_COMPLEX_FRESNEL
        case FRESNEL_COMPLEX: {
            return fresnel_conductor(cos_h, m.a.xyz, m.b.xyz);
        }
        case FRESNEL_COMPLEX_TINTED: {
            let o = bitcast<u32>(m.b.w);
            let tint = vec3f(tables[o], tables[o + 1u], tables[o + 2u]);
            return fresnel_conductor(cos_h, m.a.xyz, m.b.xyz) * tint;
        }
// #endif
        case FRESNEL_TINT: {
            return m.a.xyz;
        }
        default: {
            return vec3f(unknown_tag());
        }
    }
}

fn conductor_is_delta(m: Material) -> bool {
    return microfacet_is_smooth(record_microfacet(m));
}

// The half vector and wo·h of a valid reflection pair; w < 0 for none.
fn conductor_half_vector(m: Material, wo: vec3f, wi: vec3f) -> vec4f {
    if conductor_is_delta(m) || wo.z <= 0.0 || wi.z <= 0.0 {
        return vec4f(0.0, 0.0, 0.0, -1.0);
    }
// #if HAS_GGX
    return ggx_half_vector(wo, wi);
// #else
    return vec4f(0.0, 0.0, 0.0, -1.0);
// #endif
}

fn conductor_eval(m: Material, wo: vec3f, wi: vec3f) -> vec3f {
// #if HAS_GGX
    let hv = conductor_half_vector(m, wo, wi);
    if hv.w < 0.0 {
        return vec3f(0.0);
    }
    let mf = record_microfacet(m);
    let s = microfacet_d(mf, hv.xyz) * microfacet_g2_separable(mf, wo, wi) / (4.0 * wo.z);
    return conductor_fresnel(m, hv.w) * s;
// #else
    return vec3f(0.0);
// #endif
}

fn conductor_pdf(m: Material, wo: vec3f, wi: vec3f) -> f32 {
// #if HAS_GGX
    let hv = conductor_half_vector(m, wo, wi);
    if hv.w < 0.0 {
        return 0.0;
    }
    let mf = record_microfacet(m);
    return microfacet_g1(mf, wo) * microfacet_d(mf, hv.xyz) / (4.0 * wo.z);
// #else
    return 0.0;
// #endif
}

fn conductor_sample(m: Material, wo: vec3f, u: vec2f) -> BsdfSample {
    if wo.z <= 0.0 {
        return no_bsdf_sample();
    }
    if conductor_is_delta(m) {
        let wi = vec3f(-wo.x, -wo.y, wo.z);
        return reflection_sample(wi, conductor_fresnel(m, wo.z), 1.0, true);
    }
// #if HAS_GGX
    let mf = record_microfacet(m);
    let h0 = microfacet_sample_visible_normal(mf, wo, u);
    let wi = normalize_glam(reflect_about(wo, h0));
    let hv = conductor_half_vector(m, wo, wi);
    if hv.w < 0.0 {
        return no_bsdf_sample();
    }
    let pdf = microfacet_g1(mf, wo) * microfacet_d(mf, hv.xyz) / (4.0 * wo.z);
    let weight = conductor_fresnel(m, hv.w) * microfacet_g1(mf, wi);
    return reflection_sample(wi, weight, pdf, false);
// #else
    return no_bsdf_sample();
// #endif
}
