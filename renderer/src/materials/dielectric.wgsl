// A dielectric interface (glass), the twin of `materials/dielectric.rs`: smooth (delta reflection
// and refraction chosen by the exact Fresnel term) or rough (Walter et al. 2007 with GGX or Beckmann,
// separable Smith masking and visible-normal sampling). The outside (index 1) is where +z points;
// wo and wi may lie on either side. Radiance through a refraction is scaled by 1/η'², with
// η' = η(wi side)/η(wo side), which the sample reports as `eta`.
//
// The CPU forms the generalised half vector η_i·wi + η_o·wo in f64; WGSL has no f64, so here it is
// f32 with the same formulas: the two agree to the sum's conditioning, (η_i + η_o)/|sum| ulps
// (tests/gpu_parity.rs).

fn dielectric_is_delta(m: Material) -> bool {
    return microfacet_is_smooth(record_microfacet(m));
}

// `a` and `b` nonzero with the same sign (the CPU's `a·b > 0` without its underflow to 0).
fn dielectric_same_side(a: f32, b: f32) -> bool {
    return (a > 0.0 && b > 0.0) || (a < 0.0 && b < 0.0);
}

// #if HAS_GGX
// The microfacet configuration of a direction pair (`Pair`); `ok` = false for none.
struct DielectricPair {
    // Generalised half vector, facing +z.
    wm: vec3f,
    cos_im: f32,
    cos_om: f32,
    // (wi·wm + wo·wm/η')², the refraction Jacobian's denominator.
    denom: f32,
    reflect: bool,
    // η(wi side)/η(wo side); 1 for a reflection.
    etap: f32,
    // Fresnel reflectance at the microfacet.
    f: f32,
    ok: bool,
}

fn dielectric_pair(m: Material, wo: vec3f, wi: vec3f) -> DielectricPair {
    var p = DielectricPair(vec3f(0.0), 0.0, 0.0, 0.0, false, 1.0, 0.0, false);
    if dielectric_is_delta(m) || wo.z == 0.0 || wi.z == 0.0 {
        return p;
    }
    let ior = m.a.x;
    p.reflect = dielectric_same_side(wo.z, wi.z);
    var eta_o = 1.0;
    var eta_i = 1.0;
    if !p.reflect {
        eta_o = select(ior, 1.0, wo.z > 0.0);
        eta_i = select(ior, 1.0, wi.z > 0.0);
    }
    let sum = wi * eta_i + wo * eta_o;
    let len = length(sum);
    if len == 0.0 || !is_finite_f(len) {
        return p;
    }
    var wm = sum / len;
    if wm.z < 0.0 {
        wm = -wm;
    }
    p.wm = wm;
    // A reflection's wo·wm = wi·wm = |wo + wi|/2, from the length (exactly symmetric).
    if p.reflect {
        let c = copysign(0.5 * len, wo.z);
        p.cos_im = c;
        p.cos_om = c;
    } else {
        p.cos_im = dot(wi, wm);
        p.cos_om = dot(wo, wm);
    }
    // Both directions must see the microfacet from their own side of the macro surface.
    if !dielectric_same_side(p.cos_im, wi.z) || !dielectric_same_side(p.cos_om, wo.z) {
        return p;
    }
    if p.reflect {
        p.etap = 1.0;
        p.f = fresnel_dielectric(p.cos_om, ior);
    } else {
        p.etap = select(1.0 / ior, ior, wo.z > 0.0);
        var c_out = p.cos_im;
        var c_in = p.cos_om;
        if wo.z > 0.0 {
            c_out = p.cos_om;
            c_in = p.cos_im;
        }
        p.f = fresnel_dielectric_pair(abs(c_out), abs(c_in), ior);
    }
    // wi·wm + wo·wm/η' = ±|η_i wi + η_o wo|/η_i.
    let l = len / eta_i;
    p.denom = l * l;
    p.ok = true;
    return p;
}
// #endif

// f·|cosθi| (x) and the pdf of `dielectric_sample` producing wi (y), from one evaluation of the pair.
fn dielectric_eval_pdf(m: Material, wo: vec3f, wi: vec3f) -> vec2f {
// #if HAS_GGX
    let p = dielectric_pair(m, wo, wi);
    if !p.ok {
        return vec2f(0.0);
    }
    let mf = record_microfacet(m);
    let d = microfacet_d(mf, p.wm);
    let g = microfacet_g2_separable(mf, wo, wi);
    let cos_o = abs(wo.z);
    // Visible-normal density of wm seen from wo: G1(wo)·|wo·wm|·D(wm)/|cosθo|.
    let vndf = microfacet_g1(mf, wo) * abs(p.cos_om) * d / cos_o;
    if p.reflect {
        let f = p.f * d * g / (4.0 * cos_o);
        let pdf = vndf / (4.0 * abs(p.cos_om)) * p.f;
        return vec2f(f, pdf);
    }
    let t = 1.0 - p.f;
    // Walter 2007 eq. 21 times |cosθi|, with the radiance-mode 1/η'².
    let f = t * d * g * abs(p.cos_im * p.cos_om / (cos_o * p.denom)) / (p.etap * p.etap);
    let pdf = vndf * abs(p.cos_im) / p.denom * t;
    return vec2f(f, pdf);
// #else
    return vec2f(0.0);
// #endif
}

// Reflection or refraction chosen by the Fresnel term (at the visible microfacet normal when rough).
fn dielectric_sample(m: Material, wo: vec3f, u_lobe: f32, u: vec2f) -> BsdfSample {
    if wo.z == 0.0 {
        return no_bsdf_sample();
    }
    let ior = m.a.x;
    if dielectric_is_delta(m) {
        let r = fresnel_dielectric(wo.z, ior);
        if u_lobe < r {
            return BsdfSample(vec3f(-wo.x, -wo.y, wo.z), vec3f(1.0), r, true, 1.0, true);
        }
        let t = refract_through(wo, vec3f(0.0, 0.0, 1.0), ior);
        if t.w == 0.0 {
            return no_bsdf_sample();
        }
        return BsdfSample(t.xyz, vec3f(1.0 / (t.w * t.w)), 1.0 - r, true, t.w, true);
    }
// #if HAS_GGX
    // Microfacet normals face +z; seen from inside, the visible ones are those visible from −wo
    // (D is even in the tangent plane), and Fresnel and Snell then see wo·wm < 0, i.e. the
    // index 1/ior.
    let flip = select(1.0, -1.0, wo.z < 0.0);
    let wm = microfacet_sample_visible_normal(record_microfacet(m), wo * flip, u);
    let r = fresnel_dielectric(dot(wo, wm), ior);
    let reflection = u_lobe < r;
    var wi: vec3f;
    var eta = 1.0;
    if reflection {
        wi = normalize_glam(reflect_about(wo, wm));
    } else {
        let t = refract_through(wo, wm, ior);
        if t.w == 0.0 {
            return no_bsdf_sample();
        }
        wi = normalize_glam(t.xyz);
        eta = t.w;
    }
    // pdf and weight from the pair (wo, wi) as `dielectric_eval_pdf` sees it; a refraction that
    // comes out on wo's side (or a reflection that does not) has no valid pair: no sample.
    let fp = dielectric_eval_pdf(m, wo, wi);
    if !(fp.y > 0.0) || dielectric_same_side(wi.z, wo.z) != reflection {
        return no_bsdf_sample();
    }
    return BsdfSample(wi, vec3f(fp.x / fp.y), fp.y, false, eta, true);
// #else
    return no_bsdf_sample();
// #endif
}
