// A rough material's microfacet distribution, the twin of `materials/microfacet.rs`: a `switch`
// on DISTRIBUTION_* (the variant order of `Distribution`); an unknown tag is flagged.

struct Microfacet {
    alpha: vec2f,
    distribution: u32,
}

// The microfacet slot `c` of a conductor's or dielectric's record (gpu/scene/materials.rs).
fn record_microfacet(m: Material) -> Microfacet {
    return Microfacet(m.c.xy, bitcast<u32>(m.c.z));
}

fn microfacet_is_smooth(mf: Microfacet) -> bool {
    return max(mf.alpha.x, mf.alpha.y) < SMOOTH_ALPHA;
}

// `Material::is_anisotropic`: a rough conductor, dielectric or principled (thin or not) with
// α_u ≠ α_v.
fn material_anisotropic(m: Material) -> bool {
// #if HAS_PRINCIPLED
    if m.h.x == MATERIAL_PRINCIPLED {
        let mf = principled_microfacet(m);
        return mf.alpha.x != mf.alpha.y;
    }
// #endif
// #if HAS_PRINCIPLED_THIN
    if m.h.x == MATERIAL_PRINCIPLED_THIN {
        let r = principled_thin_reflection_mf(m);
        let t = principled_thin_transmission_mf(m);
        return r.alpha.x != r.alpha.y || t.alpha.x != t.alpha.y;
    }
// #endif
    if m.h.x != MATERIAL_CONDUCTOR && m.h.x != MATERIAL_DIELECTRIC {
        return false;
    }
    let mf = record_microfacet(m);
    return mf.alpha.x != mf.alpha.y && !microfacet_is_smooth(mf);
}

// #if HAS_GGX
fn microfacet_d(mf: Microfacet, h: vec3f) -> f32 {
    switch mf.distribution {
        case DISTRIBUTION_GGX: {
            return ggx_d_anisotropic(mf.alpha.x, mf.alpha.y, h);
        }
// #if HAS_BECKMANN
        case DISTRIBUTION_BECKMANN: {
            return beckmann_d(mf.alpha.x, mf.alpha.y, h);
        }
// #endif
        default: {
            return unknown_tag();
        }
    }
}

fn microfacet_g1(mf: Microfacet, w: vec3f) -> f32 {
    switch mf.distribution {
        case DISTRIBUTION_GGX: {
            return ggx_g1_anisotropic(mf.alpha.x, mf.alpha.y, w);
        }
// #if HAS_BECKMANN
        case DISTRIBUTION_BECKMANN: {
            return beckmann_g1(mf.alpha.x, mf.alpha.y, w);
        }
// #endif
        default: {
            return unknown_tag();
        }
    }
}

fn microfacet_g2_separable(mf: Microfacet, wo: vec3f, wi: vec3f) -> f32 {
    return microfacet_g1(mf, wo) * microfacet_g1(mf, wi);
}

fn microfacet_sample_visible_normal(mf: Microfacet, wo: vec3f, u: vec2f) -> vec3f {
    switch mf.distribution {
        case DISTRIBUTION_GGX: {
            return ggx_sample_visible_normal_anisotropic(mf.alpha.x, mf.alpha.y, wo, u);
        }
// #if HAS_BECKMANN
        case DISTRIBUTION_BECKMANN: {
            return beckmann_sample_visible_normal(mf.alpha.x, mf.alpha.y, wo, u);
        }
// #endif
        default: {
            return vec3f(unknown_tag());
        }
    }
}

fn microfacet_visible_normal_pdf(mf: Microfacet, wo: vec3f, h: vec3f) -> f32 {
    if wo.z <= 0.0 {
        return 0.0;
    }
    return microfacet_g1(mf, wo) * max(dot(wo, h), 0.0) * microfacet_d(mf, h) / wo.z;
}
// #endif
