// Mitsuba's thin principled BSDF, the twin of `materials/principled_thin.rs`, which states the
// model; it shares the principled's helpers (`materials/principled.wgsl`).
// Record (gpu/scene/materials.rs): a.xyz base colour; b = (roughness, anisotropic, spec_trans,
// spec_tint); c.xyz = (sheen, sheen_tint, flatness); d.xy = (diff_trans, η); at h.z in `tables`
// the sampling rates (specular reflection, specular transmission, diffuse reflection, diffuse
// transmission), then the ids of the textures of its scalars in `ThinParam::ALL`'s order (NONE:
// constant), which `material_at` reads.

// `PrincipledThin::microfacet` and `transmission_microfacet`.
fn principled_thin_microfacet(m: Material, roughness: f32) -> Microfacet {
    let r2 = roughness * roughness;
    let aspect = sqrt(1.0 - 0.9 * m.b.y);
    return Microfacet(vec2f(max(r2 / aspect, 0.001), max(r2 * aspect, 0.001)), DISTRIBUTION_GGX);
}

fn principled_thin_reflection_mf(m: Material) -> Microfacet {
    return principled_thin_microfacet(m, m.b.x);
}

fn principled_thin_transmission_mf(m: Material) -> Microfacet {
    return principled_thin_microfacet(m, (0.65 * m.d.y - 0.35) * m.b.x);
}

// `LobeProbabilities`: (specular reflection, specular transmission, diffuse reflection, diffuse
// transmission), normalised.
fn principled_thin_probabilities(m: Material) -> vec4f {
    let st = m.b.z;
    let dt = 0.5 * m.d.x;
    let o = m.h.z;
    let p = vec4f(
        st * tables[o] * 0.5,
        st * tables[o + 1u] * 0.5,
        tables[o + 2u] * (1.0 - st) * (1.0 - dt),
        tables[o + 3u] * (1.0 - st) * dt,
    );
    return p * (1.0 / (p.x + p.y + p.z + p.w));
}

// `Pair`: wo and wi turned to wo's side, the half vector of wo and wi mirrored there, and its
// flags.
struct ThinPair {
    wo: vec3f,
    wi: vec3f,
    wh: vec3f,
    cos_oh: f32,
    reflect_ok: bool,
    across_ok: bool,
    ok: bool,
}

fn principled_thin_pair(wo_in: vec3f, wi_in: vec3f) -> ThinPair {
    let flip = select(-1.0, 1.0, wo_in.z >= 0.0);
    let wo = wo_in * flip;
    let wi = wi_in * flip;
    var p = ThinPair(wo, wi, vec3f(0.0), 0.0, false, false, false);
    let sum = wo + vec3f(wi.xy, abs(wi.z));
    let len = length(sum);
    let wh = sum * (1.0 / len);
    if !is_finite3(wh) {
        return p;
    }
    p.wh = wh;
    p.cos_oh = 0.5 * len;
    let o = dot(wo, wh);
    let i = dot(wi, wh);
    p.reflect_ok = o > 0.0 && i > 0.0;
    p.across_ok = o > 0.0 && i < 0.0;
    p.ok = true;
    return p;
}

fn principled_thin_eval(m: Material, wo_in: vec3f, wi_in: vec3f) -> vec3f {
    if wo_in.z == 0.0 {
        return vec3f(0.0);
    }
    let p = principled_thin_pair(wo_in, wi_in);
    if !p.ok {
        return vec3f(0.0);
    }
    let base = m.a.xyz;
    let st = m.b.z;
    let dt = 0.5 * m.d.x;
    let eta = m.d.y;
    let cos_o = p.wo.z;
    let cos_i = abs(p.wi.z);
    let reflect = p.wi.z > 0.0;
    let across = p.wi.z < 0.0;
    var value = vec3f(0.0);
    if st > 0.0 && ((reflect && p.reflect_ok) || (across && p.across_ok)) {
        let f = fresnel_dielectric(p.cos_oh, eta);
        if reflect {
            let mf = principled_thin_reflection_mf(m);
            let dg = microfacet_d(mf, p.wh) * microfacet_g2_separable(mf, p.wo, p.wi);
            var fresnel = vec3f(f);
            if m.b.w != 0.0 {
                let f0 = principled_tint(base) * schlick_f0_from_ior(eta);
                let schlick = principled_calc_schlick(f0, p.cos_oh, eta);
                fresnel += (schlick - fresnel) * m.b.w;
            }
            value += fresnel * (st * dg / (4.0 * cos_o));
        } else {
            let mf = principled_thin_transmission_mf(m);
            let dg = microfacet_d(mf, p.wh) * microfacet_g2_separable(mf, p.wo, p.wi);
            value += base * (st * (1.0 - f) * dg / (4.0 * cos_o));
        }
    }
    if reflect && st < 1.0 && dt < 1.0 {
        let f_o = principled_schlick_weight(cos_i);
        let f_i = principled_schlick_weight(cos_o);
        let f_diff = (1.0 - 0.5 * f_i) * (1.0 - 0.5 * f_o);
        let cos_d = dot(p.wh, p.wi);
        let rr = 2.0 * m.b.x * cos_d * cos_d;
        let f_retro = rr * (f_o + f_i + f_o * f_i * (rr - 1.0));
        var lobe = f_diff + f_retro;
        if m.c.z != 0.0 {
            let fss90 = 0.5 * rr;
            let fss = (1.0 + (fss90 - 1.0) * f_o) * (1.0 + (fss90 - 1.0) * f_i);
            let f_ss = 1.25 * (fss * (1.0 / (cos_i + cos_o) - 0.5) + 0.5);
            lobe += (f_ss - lobe) * m.c.z;
        }
        value += base * ((1.0 - st) * cos_i * INV_PI * (1.0 - dt) * lobe);
        if m.c.x > 0.0 {
            let fd = principled_schlick_weight(abs(cos_d));
            var c_sheen = vec3f(1.0);
            if m.c.y != 0.0 {
                c_sheen = vec3f(1.0) + (principled_tint(base) - vec3f(1.0)) * m.c.y;
            }
            value += c_sheen * (m.c.x * (1.0 - st) * fd * (1.0 - dt) * cos_i);
        }
    }
    if across && st < 1.0 && dt > 0.0 {
        value += base * ((1.0 - st) * dt * INV_PI * cos_i);
    }
    return value;
}

fn principled_thin_pdf(m: Material, wo_in: vec3f, wi_in: vec3f) -> f32 {
    if wo_in.z == 0.0 {
        return 0.0;
    }
    let p = principled_thin_pair(wo_in, wi_in);
    if !p.ok {
        return 0.0;
    }
    let prob = principled_thin_probabilities(m);
    let dwh_dwi = abs(1.0 / (4.0 * p.cos_oh));
    var pdf = 0.0;
    if p.wi.z > 0.0 {
        if p.reflect_ok {
            let vnd = microfacet_visible_normal_pdf(principled_thin_reflection_mf(m), p.wo, p.wh);
            pdf += prob.x * vnd * dwh_dwi;
        }
        pdf += prob.z * p.wi.z * INV_PI;
    }
    if p.wi.z < 0.0 {
        if p.across_ok {
            let vnd = microfacet_visible_normal_pdf(principled_thin_transmission_mf(m), p.wo, p.wh);
            pdf += prob.y * vnd * dwh_dwi;
        }
        pdf += prob.w * -p.wi.z * INV_PI;
    }
    return pdf;
}

fn principled_thin_sample(m: Material, wo: vec3f, u_lobe: f32, u: vec2f) -> BsdfSample {
    if wo.z == 0.0 {
        return no_bsdf_sample();
    }
    let flip = select(-1.0, 1.0, wo.z > 0.0);
    let w = wo * flip;
    let prob = principled_thin_probabilities(m);
    var wi: vec3f;
    if u_lobe < prob.x {
        let mh = microfacet_sample_visible_normal(principled_thin_reflection_mf(m), w, u);
        wi = reflect_about(w, mh);
        if !(dot(w, mh) > 0.0 && dot(wi, mh) > 0.0 && wi.z > 0.0) {
            return no_bsdf_sample();
        }
    } else if u_lobe < prob.x + prob.y {
        let mh = microfacet_sample_visible_normal(principled_thin_transmission_mf(m), w, u);
        let r = reflect_about(w, mh);
        wi = vec3f(r.xy, -r.z);
        if !(dot(w, mh) > 0.0 && dot(wi, mh) < 0.0 && wi.z < 0.0) {
            return no_bsdf_sample();
        }
    } else if u_lobe < prob.x + prob.y + prob.z {
        wi = sample_cosine_hemisphere(u);
    } else {
        wi = -sample_cosine_hemisphere(u);
    }
    wi *= flip;
    if wi.z == 0.0 {
        return no_bsdf_sample();
    }
    let pdf = principled_thin_pdf(m, wo, wi);
    if !(pdf > 0.0) {
        return no_bsdf_sample();
    }
    let weight = principled_thin_eval(m, wo, wi) / pdf;
    // Only programs with a transmitting material have this one.
    return BsdfSample(wi, weight, pdf, false, 1.0, true);
}

// #if HAS_TEXTURES
// `MaterialTextures::at` for a thin principled: its scalar textures (ids in `tables`) into the
// record, in `ThinParam::ALL`'s order: b.xyzw, c.xyz, d.xy.
fn principled_thin_at(m_in: Material, at: TexPoint) -> Material {
    var m = m_in;
    for (var k = 0u; k < 9u; k++) {
        let id = bitcast<u32>(tables[m.h.z + 4u + k]);
        if id == NONE {
            continue;
        }
        let v = texture_eval_scalar(id, at);
        switch k {
            case 0u: { m.b.x = v; }
            case 1u: { m.b.y = v; }
            case 2u: { m.b.z = v; }
            case 3u: { m.b.w = v; }
            case 4u: { m.c.x = v; }
            case 5u: { m.c.y = v; }
            case 6u: { m.c.z = v; }
            case 7u: { m.d.x = v; }
            case 8u: { m.d.y = v; }
            default: { m.a = vec4f(unknown_tag()); }
        }
    }
    return m;
}
// #endif
