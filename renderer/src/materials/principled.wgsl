// Mitsuba's principled BSDF, the twin of `materials/principled.rs`, which states the model.
// Record (gpu/scene/materials.rs): a.xyz base colour; b = (roughness, anisotropic, metallic,
// spec_trans); c.xyz = (spec_tint, sheen, sheen_tint); d = (flatness, clearcoat,
// clearcoat_gloss, η); at h.z in `tables` the sampling rates (specular, clearcoat, diffuse),
// then `transmission` (0 or 1), then the ids of the textures of its scalars in
// `PrincipledParam::ALL`'s order (NONE: constant), which `material_at` reads.

// `Principled::transmission`.
fn principled_transmission(m: Material) -> bool {
    return tables[m.h.z + 3u] != 0.0;
}

// `Principled::brdf_bsdf`.
fn principled_brdf_bsdf(m: Material) -> vec2f {
    let dielectric = 1.0 - m.b.z;
    return vec2f(dielectric * (1.0 - m.b.w), dielectric * m.b.w);
}

// `Principled::microfacet`: GGX, α = max(0.001, roughness²) stretched by √(1 − 0.9·anisotropic).
fn principled_microfacet(m: Material) -> Microfacet {
    let r2 = m.b.x * m.b.x;
    let aspect = sqrt(1.0 - 0.9 * m.b.y);
    return Microfacet(vec2f(max(r2 / aspect, 0.001), max(r2 * aspect, 0.001)), DISTRIBUTION_GGX);
}

fn principled_schlick_weight(cos: f32) -> f32 {
    let x = clamp(1.0 - cos, 0.0, 1.0);
    let x2 = x * x;
    return x2 * x2 * x;
}

// Mitsuba's `calc_schlick`.
fn principled_calc_schlick(r0: vec3f, cos_i: f32, eta: f32) -> vec3f {
    let eta_it = select(1.0 / eta, eta, cos_i >= 0.0);
    let eta_ti = 1.0 / eta_it;
    let cos_t = safe_sqrt(1.0 - (1.0 - cos_i * cos_i) * eta_ti * eta_ti);
    let w = select(principled_schlick_weight(cos_t), principled_schlick_weight(abs(cos_i)), eta_it > 1.0);
    return r0 + (vec3f(1.0) - r0) * w;
}

fn principled_tint(base: vec3f) -> vec3f {
    let lum = mitsuba_luminance(base);
    return select(vec3f(1.0), base / lum, lum > 0.0);
}

// `LobeProbabilities`: (diffuse, clearcoat, transmission, reflection), normalised.
fn principled_probabilities(m: Material, front: bool, f: f32) -> vec4f {
    let wb = principled_brdf_bsdf(m);
    let transmission = principled_transmission(m);
    let bsdf = select(0.0, wb.y, transmission);
    let rates = vec3f(tables[m.h.z], tables[m.h.z + 1u], tables[m.h.z + 2u]);
    var p: vec4f;
    if front {
        p = vec4f(wb.x * rates.z, 0.25 * m.d.y * rates.y, rates.x * bsdf * (1.0 - f), rates.x * (1.0 - bsdf * (1.0 - f)));
    } else {
        p = vec4f(0.0, 0.0, select(0.0, 1.0 - f, transmission), f);
    }
    let norm = 1.0 / (p.w + p.z + p.y + p.x);
    return p * norm;
}

// `Pair`: the half vector (facing +z) and its flags; `across` (a pair on both sides) and
// `across_ok` exist only in programs that refract.
struct PrincipledPair {
    wh: vec3f,
    reflect: bool,
// #if HAS_REFRACTION
    across: bool,
    across_ok: bool,
// #endif
    cos_oh: f32,
    f: f32,
    reflect_ok: bool,
    eta_path: f32,
    ok: bool,
}

fn principled_pair(m: Material, wo: vec3f, wi: vec3f) -> PrincipledPair {
    let eta = m.d.w;
    let front = wo.z > 0.0;
    let reflect = wo.z * wi.z > 0.0;
// #if HAS_REFRACTION
    var p = PrincipledPair(vec3f(0.0), reflect, wo.z * wi.z < 0.0, false, 0.0, 0.0, false, select(1.0 / eta, eta, front), false);
    // η(wo side)·wo + η(wi side)·wi (the CPU sums it in f64).
    let side_o = select(eta, 1.0, reflect || wo.z > 0.0);
    let side_i = select(eta, 1.0, reflect || wi.z > 0.0);
    let sum = wo * side_o + wi * side_i;
// #else
    var p = PrincipledPair(vec3f(0.0), reflect, 0.0, 0.0, false, 1.0, false);
    if !reflect {
        return p;
    }
    let sum = wo + wi;
// #endif
    let len = length(sum);
    var wh = sum * (1.0 / len);
    if !is_finite3(wh) {
        return p;
    }
    wh = select(wh, -wh, wh.z < 0.0);
    p.wh = wh;
    let ms = select(-wh, wh, front);
    let o = dot(wo, ms);
    let i = dot(wi, ms);
    p.reflect_ok = o > 0.0 && i > 0.0;
    if reflect {
        // |wo + wi|/2 = wo·wh = wi·wh: the pair's two directions see one Fresnel term.
        p.cos_oh = select(-0.5 * len, 0.5 * len, wo.z >= 0.0);
        p.f = fresnel_dielectric(p.cos_oh, eta);
    }
// #if HAS_REFRACTION
    else {
        p.cos_oh = dot(wo, wh);
        let c = select(vec2f(dot(wi, wh), dot(wo, wh)), vec2f(dot(wo, wh), dot(wi, wh)), front);
        p.f = fresnel_dielectric_pair(abs(c.x), abs(c.y), eta);
    }
    p.across_ok = o > 0.0 && i < 0.0;
// #endif
    p.ok = true;
    return p;
}

// `Principled::fresnel`.
fn principled_fresnel(m: Material, f_dielectric: f32, cos: f32, front: bool) -> vec3f {
    let wb = principled_brdf_bsdf(m);
    if !front {
        return vec3f(wb.y * f_dielectric);
    }
    let eta = m.d.w;
    let metallic = m.b.z;
    let spec_tint = m.c.x;
    var schlick = vec3f(0.0);
    if metallic != 0.0 {
        schlick += metallic * principled_calc_schlick(m.a.xyz, cos, eta);
    }
    if spec_tint != 0.0 {
        let eta_it = select(1.0 / eta, eta, cos >= 0.0);
        let f0 = principled_tint(m.a.xyz) * schlick_f0_from_ior(eta_it);
        schlick += (1.0 - metallic) * spec_tint * principled_calc_schlick(f0, cos, eta);
    }
    return vec3f((1.0 - metallic) * (1.0 - spec_tint) * f_dielectric) + schlick;
}

fn principled_eval(m: Material, wo: vec3f, wi: vec3f) -> vec3f {
    if wo.z == 0.0 {
        return vec3f(0.0);
    }
    let p = principled_pair(m, wo, wi);
    if !p.ok {
        return vec3f(0.0);
    }
    let front = wo.z > 0.0;
    let wb = principled_brdf_bsdf(m);
    let mf = principled_microfacet(m);
    let d = microfacet_d(mf, p.wh);
    let g = microfacet_g2_separable(mf, wo, wi);
    var value = vec3f(0.0);
    if p.reflect && p.reflect_ok && p.f > 0.0 {
        let f = principled_fresnel(m, p.f, p.cos_oh, front);
        value += f * (d * g / (4.0 * abs(wo.z)));
    }
// #if HAS_REFRACTION
    if wb.y > 0.0 && p.across && p.across_ok && p.f < 1.0 && principled_transmission(m) {
        let scale = 1.0 / (p.eta_path * p.eta_path);
        let oh = dot(wo, p.wh);
        let ih = dot(wi, p.wh);
        let denom = oh + p.eta_path * ih;
        let t = abs(scale * (1.0 - p.f) * d * g * p.eta_path * p.eta_path * oh * ih / (wo.z * denom * denom));
        value += sqrt(m.a.xyz) * (wb.y * t);
    }
// #endif
    if !(front && p.reflect) {
        return value;
    }
    let cos_i = abs(wi.z);
    let cos_o = abs(wo.z);
    if m.d.y > 0.0 && p.reflect_ok {
        let fcc = principled_calc_schlick(vec3f(0.04), p.cos_oh, m.d.w).x;
        let dcc = gtr1_d(gtr1_clearcoat_alpha(m.d.z), p.wh);
        let gcc = gtr1_clearcoat_g(wo, wi, p.wh);
        value += vec3f(m.d.y * 0.25 * fcc * dcc * gcc * cos_i);
    }
    let f_i = principled_schlick_weight(cos_i);
    let f_o = principled_schlick_weight(cos_o);
    let cos_d = dot(p.wh, wi);
    if wb.x > 0.0 {
        let f_diff = (1.0 - 0.5 * f_o) * (1.0 - 0.5 * f_i);
        let rr = 2.0 * m.b.x * cos_d * cos_d;
        let f_retro = rr * (f_i + f_o + f_i * f_o * (rr - 1.0));
        var lobe = f_diff + f_retro;
        if m.d.x != 0.0 {
            let fss90 = 0.5 * rr;
            let fss = (1.0 + (fss90 - 1.0) * f_i) * (1.0 + (fss90 - 1.0) * f_o);
            let f_ss = 1.25 * (fss * (1.0 / (cos_i + cos_o) - 0.5) + 0.5);
            lobe += (f_ss - lobe) * m.d.x;
        }
        value += m.a.xyz * (wb.x * cos_i * INV_PI * lobe);
    }
    let metallic = m.b.z;
    if m.c.y > 0.0 && 1.0 - metallic > 0.0 {
        let fd = principled_schlick_weight(abs(cos_d));
        var c_sheen = vec3f(1.0);
        if m.c.z != 0.0 {
            c_sheen = vec3f(1.0) + (principled_tint(m.a.xyz) - vec3f(1.0)) * m.c.z;
        }
        value += c_sheen * (m.c.y * (1.0 - metallic) * fd * cos_i);
    }
    return value;
}

fn principled_pdf(m: Material, wo: vec3f, wi: vec3f) -> f32 {
    if wo.z == 0.0 {
        return 0.0;
    }
    let p = principled_pair(m, wo, wi);
    if !p.ok {
        return 0.0;
    }
    let front = wo.z > 0.0;
    let prob = principled_probabilities(m, front, p.f);
    let ih = dot(wi, p.wh);
    var dwh_dwi = abs(1.0 / (4.0 * ih));
// #if HAS_REFRACTION
    let crossing = principled_transmission(m) && !p.reflect;
    if crossing {
        let denom = dot(wo, p.wh) + p.eta_path * ih;
        dwh_dwi = abs(p.eta_path * p.eta_path * ih / (denom * denom));
    }
// #endif
    let mf = principled_microfacet(m);
    let wo_up = wo * select(-1.0, 1.0, wo.z >= 0.0);
    var pdf = 0.0;
    if p.reflect && p.reflect_ok {
        pdf += prob.w * microfacet_visible_normal_pdf(mf, wo_up, p.wh) * dwh_dwi;
    }
    if p.reflect {
        pdf += prob.x * max(wi.z, 0.0) * INV_PI;
    }
// #if HAS_REFRACTION
    if crossing && p.across && p.across_ok {
        pdf += prob.z * microfacet_visible_normal_pdf(mf, wo_up, p.wh) * dwh_dwi;
    }
// #endif
    if p.reflect && p.reflect_ok && prob.y > 0.0 {
        pdf += prob.y * gtr1_pdf(gtr1_clearcoat_alpha(m.d.z), p.wh) * dwh_dwi;
    }
    return pdf;
}

// Whether `wi`, from microfacet `mh` (facing +z), is a direction its lobe can give: wo and wi
// see `mh` from the sides a reflection (`across` false) or refraction needs.
fn principled_sees(wo: vec3f, mh: vec3f, wi: vec3f, across: bool) -> bool {
    let ms = mh * select(-1.0, 1.0, wo.z >= 0.0);
    let i = select(dot(wi, ms), -dot(wi, ms), across);
    return dot(wo, ms) > 0.0 && i > 0.0 && ((wi.z * wo.z < 0.0) == across);
}

fn principled_sample(m: Material, wo: vec3f, u_lobe: f32, u: vec2f) -> BsdfSample {
    if wo.z == 0.0 {
        return no_bsdf_sample();
    }
    let front = wo.z > 0.0;
    let wb = principled_brdf_bsdf(m);
    if !front && !(principled_transmission(m) && wb.y > 0.0) {
        return no_bsdf_sample();
    }
    let mf = principled_microfacet(m);
    let flip = select(-1.0, 1.0, wo.z >= 0.0);
    let mh = microfacet_sample_visible_normal(mf, wo * flip, u);
    let f = fresnel_dielectric(dot(wo, mh), m.d.w);
    let prob = principled_probabilities(m, front, f);
    var wi: vec3f;
    var eta = 1.0;
    if u_lobe < prob.x {
        wi = sample_cosine_hemisphere(u);
    } else if u_lobe < prob.x + prob.y {
        let mc = gtr1_sample(gtr1_clearcoat_alpha(m.d.z), u);
        wi = reflect_about(wo, mc);
        if !principled_sees(wo, mc, wi, false) {
            return no_bsdf_sample();
        }
    } else if u_lobe < prob.x + prob.y + prob.z {
// #if HAS_REFRACTION
        let t = refract_through(wo, mh, m.d.w);
        if t.w == 0.0 {
            return no_bsdf_sample();
        }
        wi = t.xyz;
        eta = t.w;
        if !principled_sees(wo, mh, wi, true) {
            return no_bsdf_sample();
        }
// #else
        return no_bsdf_sample();
// #endif
    } else {
        wi = reflect_about(wo, mh);
        if !principled_sees(wo, mh, wi, false) {
            return no_bsdf_sample();
        }
    }
    if wi.z * wo.z == 0.0 {
        return no_bsdf_sample();
    }
    let pdf = principled_pdf(m, wo, wi);
    if !(pdf > 0.0) {
        return no_bsdf_sample();
    }
    let weight = principled_eval(m, wo, wi) / pdf;
// #if HAS_TRANSMISSION
    return BsdfSample(wi, weight, pdf, false, eta, true);
// #else
    return reflection_sample(wi, weight, pdf, false);
// #endif
}

// #if HAS_TEXTURES
// `MaterialTextures::at` for a principled: its scalar textures (ids in `tables`) into the record.
fn principled_at(m_in: Material, at: TexPoint) -> Material {
    var m = m_in;
    for (var k = 0u; k < 10u; k++) {
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
            case 9u: { m.d.z = v; }
            default: { m.a = vec4f(unknown_tag()); }
        }
    }
    return m;
}
// #endif
