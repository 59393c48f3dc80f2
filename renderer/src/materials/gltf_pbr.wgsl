// glTF's metallic-roughness material, the twin of `materials/gltf_pbr.rs`, which states the model
// (the specification's Appendix B, separable Smith G) and its sampling.
// Record (gpu/scene/materials.rs): a.xyz base colour; b = (roughness, metallic, ior, specular);
// c.xyz the specular colour, c.w the ids of its roughness (low 16 bits) and metallic (high 16
// bits, 0xFFFF: none) textures, NONE where neither is textured; a.w its base colour texture's.

// `GltfPbr::alpha`: roughness², at least SMOOTH_ALPHA.
fn gltf_pbr_alpha(m: Material) -> f32 {
    return max(m.b.x * m.b.x, SMOOTH_ALPHA);
}

// `fresnel_schlick_rgb`.
fn gltf_pbr_schlick_rgb(f0: vec3f, cos_theta: f32) -> vec3f {
    let m = 1.0 - clamp(cos_theta, 0.0, 1.0);
    let m2 = m * m;
    return f0 + (vec3f(1.0) - f0) * (m2 * m2 * m);
}

// `GltfPbr::non_metal_fresnel`: specular·Schlick(min(f0·specular colour, 1), cos).
fn gltf_pbr_non_metal_fresnel(m: Material, cos: f32) -> vec3f {
    let f0 = min(schlick_f0_from_ior(m.b.z) * m.c.xyz, vec3f(1.0));
    return m.b.w * gltf_pbr_schlick_rgb(f0, cos);
}

fn gltf_pbr_max3(v: vec3f) -> f32 {
    return max(max(v.x, v.y), v.z);
}

// `GltfPbr::specular_probability`.
fn gltf_pbr_specular_probability(m: Material, wo: vec3f) -> f32 {
    let metallic = m.b.y;
    let f_d = gltf_pbr_non_metal_fresnel(m, wo.z);
    let f_m = gltf_pbr_schlick_rgb(m.a.xyz, wo.z);
    let w_d = (1.0 - metallic) * (1.0 - gltf_pbr_max3(f_d)) * luminance(m.a.xyz);
    if w_d <= 0.0 {
        return 1.0;
    }
    let w_s = (1.0 - metallic) * luminance(f_d) + metallic * luminance(f_m);
    return max(w_s / (w_s + w_d), GLTF_PBR_MIN_SPECULAR_RATE);
}

const GLTF_PBR_MIN_SPECULAR_RATE: f32 = 0.05;

fn gltf_pbr_eval(m: Material, wo: vec3f, wi: vec3f) -> vec3f {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return vec3f(0.0);
    }
    let hv = ggx_half_vector(wo, wi);
    let alpha = gltf_pbr_alpha(m);
    let s = ggx_d(alpha, hv.xyz) * ggx_g2_separable(alpha, wo, wi) / (4.0 * wo.z);
    let metallic = m.b.y;
    let f_d = gltf_pbr_non_metal_fresnel(m, hv.w);
    let f_m = gltf_pbr_schlick_rgb(m.a.xyz, hv.w);
    let non_metal = (1.0 - gltf_pbr_max3(f_d)) * INV_PI * wi.z * m.a.xyz + f_d * s;
    return (1.0 - metallic) * non_metal + metallic * s * f_m;
}

fn gltf_pbr_pdf(m: Material, wo: vec3f, wi: vec3f) -> f32 {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return 0.0;
    }
    let p_s = gltf_pbr_specular_probability(m, wo);
    let hv = ggx_half_vector(wo, wi);
    let alpha = gltf_pbr_alpha(m);
    let specular = ggx_g1(alpha, wo) * ggx_d(alpha, hv.xyz) / (4.0 * wo.z);
    return p_s * specular + (1.0 - p_s) * (INV_PI * wi.z);
}

fn gltf_pbr_sample(m: Material, wo: vec3f, u_lobe: f32, u: vec2f) -> BsdfSample {
    if wo.z <= 0.0 {
        return no_bsdf_sample();
    }
    var wi: vec3f;
    if u_lobe < gltf_pbr_specular_probability(m, wo) {
        let h = ggx_sample_visible_normal(gltf_pbr_alpha(m), wo, u);
        wi = normalize_glam(reflect_about(wo, h));
    } else {
        wi = sample_cosine_hemisphere(u);
    }
    if wi.z <= 0.0 {
        return no_bsdf_sample();
    }
    let pdf = gltf_pbr_pdf(m, wo, wi);
    return reflection_sample(wi, gltf_pbr_eval(m, wo, wi) / pdf, pdf, false);
}

// #if HAS_TEXTURES
// `MaterialTextures::at` for its scalars: roughness and metallic from the ids in c.w.
fn gltf_pbr_at(m_in: Material, at: TexPoint) -> Material {
    var m = m_in;
    let slot = bitcast<u32>(m.c.w);
    let roughness = slot & 0xFFFFu;
    let metallic = slot >> 16u;
    if roughness != 0xFFFFu {
        m.b.x = texture_eval_scalar(roughness, at);
    }
    if metallic != 0xFFFFu {
        m.b.y = texture_eval_scalar(metallic, at);
    }
    return m;
}
// #endif
