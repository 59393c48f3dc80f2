// Lambert base under a GGX dielectric coat, coupled through the coat's tabulated directional
// albedo: the twin of `materials/plastic.rs`, `materials/coat_albedo.rs` and
// `materials/plastic_textured.rs`. The table (E_TABLE_SIZE = 64 nodes at μ = (i/63)³) lives in
// `tables` at the material's offset; a textured α blends two tables of its coat grid.

fn coat_node_mu(i: u32) -> f32 {
    let t = f32(i) / f32(E_TABLE_SIZE - 1u);
    return t * t * t;
}

// E(μ): Schlick for a smooth coat, else the table interpolated linearly in μ.
fn coat_albedo_eval(m: Material, mu_in: f32) -> f32 {
    let mu = clamp(mu_in, 0.0, 1.0);
    let alpha = m.c.x;
    if alpha < SMOOTH_ALPHA {
        return fresnel_schlick(m.c.y, mu);
    }
    // pow(μ, 1/3) for cbrt; its rounding can pick a neighbouring node, so step to the node
    // interval that really holds μ (the interpolant is continuous across nodes).
    var i = min(u32(pow(mu, 1.0 / 3.0) * f32(E_TABLE_SIZE - 1u)), E_TABLE_SIZE - 2u);
    if i + 2u < E_TABLE_SIZE && mu >= coat_node_mu(i + 1u) {
        i += 1u;
    }
    if i > 0u && mu < coat_node_mu(i) {
        i -= 1u;
    }
    let ma = coat_node_mu(i);
    let mb = coat_node_mu(i + 1u);
    let t = clamp((mu - ma) / (mb - ma), 0.0, 1.0);
    let off = m.h.z;
    var ea = tables[off + i];
    var eb = tables[off + i + 1u];
    let s = m.b.w;
    if s != 0.0 {
        // `CoatAlbedo::blend` of this node table and the next, entry by entry (textured α).
        let next = off + E_TABLE_SIZE;
        ea = ea + s * (tables[next + i] - ea);
        eb = eb + s * (tables[next + i + 1u] - eb);
    }
    return ea + t * (eb - ea);
}

// #if HAS_TEXTURES
// `Plastic::set_alpha_from_grid` with `CoatGrid::coat` (`materials/plastic_textured.rs`): `m`
// (whose aux is its coat grid's offset) with roughness `alpha_in` clamped to [0, 1]. A smooth
// coat is Schlick's with E_avg = F0 + (1 − F0)/21; a rough one sits between grid nodes i and
// i + 1, located linearly in ln α by the CPU's expression, and its E_avg is their blend; the
// tables are blended where they are read (`coat_albedo_eval`). Grid layout in
// `gpu/scene/materials.rs`: GRID_SIZE tables of E_TABLE_SIZE entries, then the GRID_SIZE E_avg.
fn plastic_alpha_from_grid(m_in: Material, alpha_in: f32) -> Material {
    var m = m_in;
    let alpha = clamp(alpha_in, 0.0, 1.0);
    m.c.x = alpha;
    var e_avg: f32;
    if alpha < SMOOTH_ALPHA {
        e_avg = m.c.y + (1.0 - m.c.y) / 21.0;
        m.b.w = 0.0;
    } else {
        let x = (log(alpha) - COAT_GRID_LN_FIRST) / -COAT_GRID_LN_FIRST * f32(COAT_GRID_SIZE - 1u);
        let i = min(u32(max(x, 0.0)), COAT_GRID_SIZE - 2u);
        let t = clamp(x - f32(i), 0.0, 1.0);
        let grid = m.h.z;
        let averages = grid + COAT_GRID_SIZE * E_TABLE_SIZE;
        let ea = tables[averages + i];
        let eb = tables[averages + i + 1u];
        e_avg = ea + t * (eb - ea);
        m.h.z = grid + i * E_TABLE_SIZE;
        m.b.w = t;
    }
    // As `Plastic::new`: no light reaches the base of a coat that reflects all.
    m.c.z = select(0.0, 1.0 / (1.0 - e_avg), 1.0 - e_avg > 1e-6);
    return m;
}
// #endif

// #if HAS_TEXTURES
// `Plastic::has_smooth_part`: a rough coat, or a base that receives light (the encoder's flag;
// `material_at` asks again for a textured albedo's value at a hit).
fn plastic_has_smooth_part(m: Material) -> bool {
    return !(m.c.x < SMOOTH_ALPHA) || (max_component(m.a.xyz) > 0.0 && m.c.z > 0.0);
}
// #endif

fn plastic_coat_probability(m: Material, e_o: f32) -> f32 {
    let s = max(luminance(m.b.xyz) * e_o, 0.0);
    var d = 0.0;
    if m.c.z > 0.0 {
        d = max(luminance(m.a.xyz) * (1.0 - e_o), 0.0);
    }
    if d <= 0.0 {
        return 1.0;
    } else if s <= 0.0 {
        return 0.0;
    }
    return clamp(s / (s + d), 0.05, 0.95);
}

// f·cosθi (xyz) and pdf (w) of the non-delta lobes, together so they agree.
fn plastic_eval_pdf(m: Material, wo: vec3f, wi: vec3f) -> vec4f {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return vec4f(0.0);
    }
    let e_o = coat_albedo_eval(m, wo.z);
    let e_i = coat_albedo_eval(m, wi.z);
    let p_coat = plastic_coat_probability(m, e_o);
    let k = INV_PI * (1.0 - e_o) * (1.0 - e_i) * m.c.z * wi.z;
    var f = m.a.xyz * k;
    var pdf = (1.0 - p_coat) * INV_PI * wi.z;
// #if HAS_GGX
    let a = m.c.x;
    if !(a < SMOOTH_ALPHA) {
        let hv = ggx_half_vector(wo, wi);
        let d_g1o = ggx_d(a, hv.xyz) * ggx_g1(a, wo) / (4.0 * wo.z);
        let fr = fresnel_schlick(m.c.y, hv.w);
        f += m.b.xyz * (fr * d_g1o * ggx_g1(a, wi));
        pdf += p_coat * d_g1o;
    }
// #endif
// #if MUTANTS
    return vec4f(f * MUTANT_PLASTIC_EVAL, pdf);
// #else
    return vec4f(f, pdf);
// #endif
}

fn plastic_sample(m: Material, wo: vec3f, u_lobe: f32, u: vec2f) -> BsdfSample {
    if wo.z <= 0.0 {
        return no_bsdf_sample();
    }
    let p_coat = plastic_coat_probability(m, coat_albedo_eval(m, wo.z));
    var wi: vec3f;
    if u_lobe < p_coat {
        if m.c.x < SMOOTH_ALPHA {
            let wm = vec3f(-wo.x, -wo.y, wo.z);
            let weight = m.b.xyz * (fresnel_schlick(m.c.y, wo.z) / p_coat);
            return reflection_sample(wm, weight, p_coat, true);
        }
// #if HAS_GGX
        wi = normalize_glam(reflect_about(wo, ggx_sample_visible_normal(m.c.x, wo, u)));
// #else
        return no_bsdf_sample();
// #endif
    } else {
        wi = sample_cosine_hemisphere(u);
    }
    let fp = plastic_eval_pdf(m, wo, wi);
    if !(fp.w > 0.0) {
        return no_bsdf_sample();
    }
    return reflection_sample(wi, fp.xyz / fp.w, fp.w, false);
}
