// Mitsuba 3's plastic and roughplastic coupling of a plastic (MATERIAL_PLASTIC_MITSUBA): the twin
// of `materials/plastic_mitsuba.rs`, which states the model. Record (gpu/scene/materials.rs):
// a.xyz albedo, b.xyz tint, b.w η, c the microfacet slot; at h.z in `tables` the rough
// transmittance table (TRANSMITTANCE_SIZE entries at μ = i/63), then R, w and nonlinear.

fn plastic_mitsuba_is_smooth(m: Material) -> bool {
    return max(m.c.x, m.c.y) < SMOOTH_ALPHA;
}

// `MitsubaCoat::transmittance`: 1 − F(μ) for a smooth coat, else the table at x = 63μ.
fn plastic_mitsuba_transmittance(m: Material, mu: f32) -> f32 {
    if plastic_mitsuba_is_smooth(m) {
        return 1.0 - fresnel_dielectric(mu, m.b.w);
    }
    let x = clamp(mu, 0.0, 1.0) * f32(TRANSMITTANCE_SIZE - 1u);
    let i = min(u32(x), TRANSMITTANCE_SIZE - 2u);
    let a = tables[m.h.z + i];
    let b = tables[m.h.z + i + 1u];
    return a + (x - f32(i)) * (b - a);
}

// `MitsubaCoat::base`: the albedo after the internal bounces.
fn plastic_mitsuba_base(m: Material) -> vec3f {
    let r = tables[m.h.z + TRANSMITTANCE_SIZE];
    if tables[m.h.z + TRANSMITTANCE_SIZE + 2u] != 0.0 {
        return m.a.xyz / (vec3f(1.0) - m.a.xyz * r);
    }
    return m.a.xyz / (1.0 - r);
}

fn plastic_mitsuba_specular_probability(m: Material, t_o: f32) -> f32 {
    let w = tables[m.h.z + TRANSMITTANCE_SIZE + 1u];
    let s = (1.0 - t_o) * w;
    let d = t_o * (1.0 - w);
    if d <= 0.0 {
        return 1.0;
    } else if s <= 0.0 {
        return 0.0;
    }
    return s / (s + d);
}

// #if HAS_TEXTURES
// `Plastic::has_smooth_part`: a rough coat, or a base that receives light.
fn plastic_mitsuba_has_smooth_part(m: Material) -> bool {
    return !plastic_mitsuba_is_smooth(m) || max_component(m.a.xyz) > 0.0;
}
// #endif

// f·cosθi (xyz) and pdf (w) of the non-delta lobes.
fn plastic_mitsuba_eval_pdf(m: Material, wo: vec3f, wi: vec3f) -> vec4f {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return vec4f(0.0);
    }
    let t_o = plastic_mitsuba_transmittance(m, wo.z);
    let t_i = plastic_mitsuba_transmittance(m, wi.z);
    let p_coat = plastic_mitsuba_specular_probability(m, t_o);
    let eta = m.b.w;
    var f = plastic_mitsuba_base(m) * (INV_PI * t_o * t_i * (1.0 / (eta * eta)) * wi.z);
    var pdf = (1.0 - p_coat) * INV_PI * wi.z;
// #if HAS_GGX
    if !plastic_mitsuba_is_smooth(m) {
        let mf = record_microfacet(m);
        let hv = ggx_half_vector(wo, wi);
        let d_g1o = microfacet_d(mf, hv.xyz) * microfacet_g1(mf, wo) / (4.0 * wo.z);
        let fr = fresnel_dielectric(hv.w, eta);
        f += m.b.xyz * (fr * d_g1o * microfacet_g1(mf, wi));
        pdf += p_coat * d_g1o;
    }
// #endif
// #if MUTANTS
    return vec4f(f * MUTANT_PLASTIC_EVAL, pdf);
// #else
    return vec4f(f, pdf);
// #endif
}

fn plastic_mitsuba_sample(m: Material, wo: vec3f, u_lobe: f32, u: vec2f) -> BsdfSample {
    if wo.z <= 0.0 {
        return no_bsdf_sample();
    }
    let p_coat = plastic_mitsuba_specular_probability(m, plastic_mitsuba_transmittance(m, wo.z));
    var wi: vec3f;
    if u_lobe < p_coat {
        if plastic_mitsuba_is_smooth(m) {
            let f = fresnel_dielectric(wo.z, m.b.w);
            return reflection_sample(vec3f(-wo.x, -wo.y, wo.z), m.b.xyz * (f / p_coat), p_coat, true);
        }
// #if HAS_GGX
        let h = microfacet_sample_visible_normal(record_microfacet(m), wo, u);
        wi = normalize_glam(reflect_about(wo, h));
// #else
        return no_bsdf_sample();
// #endif
    } else {
        wi = sample_cosine_hemisphere(u);
    }
    let fp = plastic_mitsuba_eval_pdf(m, wo, wi);
    if !(fp.w > 0.0) {
        return no_bsdf_sample();
    }
    return reflection_sample(wi, fp.xyz / fp.w, fp.w, false);
}
