// The closed set of materials, the twin of `materials/mod.rs`: one record per material, a `switch`
// on the same variant order as `Material` (Diffuse, Conductor, Plastic, Dielectric,
// ThinDielectric, Principled, PrincipledThin, GltfPbr); and, under
// HAS_TEXTURES, `material_at`, the twin of `materials/textured.rs`, which evaluates a material's
// textures at a hit.
//
// Record layout (see `gpu/scene/materials.rs`):
//   h = (kind, two_sided, aux, has_smooth_part); kind = MATERIAL_*; aux = Fresnel kind for
//       conductors (FRESNEL_COMPLEX or FRESNEL_TINT) and the coat table's offset in `tables` for plastic.
//   Diffuse:    a.xyz albedo.
//   Conductor:  a.xyz η (or the tint), b.xyz k, c.xyz = (α_u, α_v, DISTRIBUTION_* bits), the
//               microfacet slot (`record_microfacet`, `materials/microfacet.wgsl`).
//   Plastic:    a.xyz albedo, b.xyz coat tint, c = (α, F0, 1/(1 − E_avg) or 0, _); with a textured
//               α, aux is its coat grid's offset and `material_at` makes it the hit's lower node
//               table, b.w the blend weight of the next (`materials/plastic.wgsl`); b.w = 0 otherwise.
//   Plastic with Mitsuba's coupling (MATERIAL_PLASTIC_MITSUBA): a.xyz albedo, b.xyz tint, b.w η,
//               c the microfacet slot; aux its tables' offset (`materials/plastic_mitsuba.wgsl`).
//   Mix:        (MATERIAL_MIX) resolved by `materials/mix.wgsl` before anything here sees the material.
//   Two-sided pair: (MATERIAL_TWO_SIDED) likewise resolved there (`materials/two_sided.wgsl`).
//   Dielectric: a.x ior, c.xyz the microfacet slot as a conductor's; never two-sided (its two
//               sides are its two media).
//   ThinDielectric: a.x ior; never two-sided (it is the same from both sides).
//   Principled: a.xyz base colour, b, c.xyz and d its scalars, h.z its rates, transmission flag
//               and scalar texture ids in `tables` (`materials/principled.wgsl`); c.w is not
//               NONE where a scalar is textured.
//   PrincipledThin: a.xyz base colour, b, c.xyz and d.xy its scalars, h.z its rates and scalar
//               texture ids in `tables` (`materials/principled_thin.wgsl`); c.w as a
//               principled's; the same from both sides, never two-sided.
//   GltfPbr:    a.xyz base colour, b = (roughness, metallic, ior, specular), c.xyz the specular
//               colour; c.w the ids of its roughness (low 16 bits) and metallic (high 16)
//               textures (`materials/gltf_pbr.wgsl`).
//   Only the principled kinds fill d.
//   Every kind: a.w, c.w = bits of the ids of its colour texture (a diffuse's or plastic's albedo,
//       a conductor's reflectance: replaces a.xyz) and its roughness textures (α, or α_u in the
//       low 16 bits and α_v in the high 16, 0xFFFF for none: replace a conductor's or
//       dielectric's c.xy), NONE where constant (`textures/mod.wgsl`,
//       `gpu/scene/materials.rs` `roughness_slot`).

struct Material {
    h: vec4<u32>,
    a: vec4f,
    b: vec4f,
    c: vec4f,
    d: vec4f,
}

// `BsdfSample`; `ok` = false stands for `None`. `eta` (η' of a refraction, 1 for a reflection)
// exists only in programs with a transmitting material, so the others are the reflection-only
// program.
struct BsdfSample {
    wi: vec3f,
    weight: vec3f,
    pdf: f32,
    delta: bool,
// #if HAS_TRANSMISSION
    eta: f32,
// #endif
    ok: bool,
}

// A valid sample of a reflection (η' = 1).
fn reflection_sample(wi: vec3f, weight: vec3f, pdf: f32, delta: bool) -> BsdfSample {
// #if HAS_TRANSMISSION
    return BsdfSample(wi, weight, pdf, delta, 1.0, true);
// #else
    return BsdfSample(wi, weight, pdf, delta, true);
// #endif
}

fn no_bsdf_sample() -> BsdfSample {
    var s = reflection_sample(vec3f(0.0), vec3f(0.0), 0.0, false);
    s.ok = false;
    return s;
}

// #if HAS_TRANSMISSION
// `Material::transmits`: wo and wi may lie on either side, the frame is never flipped.
fn material_transmits(m: Material) -> bool {
    if m.h.x == MATERIAL_DIELECTRIC || m.h.x == MATERIAL_THIN_DIELECTRIC {
        return true;
    }
// #if HAS_PRINCIPLED
    if m.h.x == MATERIAL_PRINCIPLED {
        return principled_transmission(m);
    }
// #endif
    return m.h.x == MATERIAL_PRINCIPLED_THIN;
}
// #endif

fn material_eval(m: Material, wo: vec3f, wi: vec3f) -> vec3f {
    switch m.h.x {
        case MATERIAL_DIFFUSE: {
            return diffuse_eval(m, wo, wi);
        }
// #if HAS_CONDUCTOR
        case MATERIAL_CONDUCTOR: {
            return conductor_eval(m, wo, wi);
        }
// #endif
// #if HAS_PLASTIC
        case MATERIAL_PLASTIC: {
            return plastic_eval_pdf(m, wo, wi).xyz;
        }
// #endif
// #if HAS_MITSUBA_PLASTIC
        case MATERIAL_PLASTIC_MITSUBA: {
            return plastic_mitsuba_eval_pdf(m, wo, wi).xyz;
        }
// #endif
// #if HAS_DIELECTRIC
        case MATERIAL_DIELECTRIC: {
            return vec3f(dielectric_eval_pdf(m, wo, wi).x);
        }
// #endif
// #if HAS_THIN_DIELECTRIC
        // Both lobes delta.
        case MATERIAL_THIN_DIELECTRIC: {
            return vec3f(0.0);
        }
// #endif
// #if HAS_PRINCIPLED
        case MATERIAL_PRINCIPLED: {
            return principled_eval(m, wo, wi);
        }
// #endif
// #if HAS_PRINCIPLED_THIN
        case MATERIAL_PRINCIPLED_THIN: {
            return principled_thin_eval(m, wo, wi);
        }
// #endif
// #if HAS_GLTF_PBR
        case MATERIAL_GLTF_PBR: {
            return gltf_pbr_eval(m, wo, wi);
        }
// #endif
        default: {
            return vec3f(unknown_tag());
        }
    }
}

fn material_pdf(m: Material, wo: vec3f, wi: vec3f) -> f32 {
// #if MUTANTS
    let pdf = material_pdf_unmutated(m, wo, wi);
    return select(pdf, pdf * MUTANT_FACTOR, m.h.x == MUTANT_BSDF_PDF_TAG);
}

fn material_pdf_unmutated(m: Material, wo: vec3f, wi: vec3f) -> f32 {
// #endif
    switch m.h.x {
        case MATERIAL_DIFFUSE: {
            return diffuse_pdf(wo, wi);
        }
// #if HAS_CONDUCTOR
        case MATERIAL_CONDUCTOR: {
            return conductor_pdf(m, wo, wi);
        }
// #endif
// #if HAS_PLASTIC
        case MATERIAL_PLASTIC: {
            return plastic_eval_pdf(m, wo, wi).w;
        }
// #endif
// #if HAS_MITSUBA_PLASTIC
        case MATERIAL_PLASTIC_MITSUBA: {
            return plastic_mitsuba_eval_pdf(m, wo, wi).w;
        }
// #endif
// #if HAS_DIELECTRIC
        case MATERIAL_DIELECTRIC: {
            return dielectric_eval_pdf(m, wo, wi).y;
        }
// #endif
// #if HAS_THIN_DIELECTRIC
        case MATERIAL_THIN_DIELECTRIC: {
            return 0.0;
        }
// #endif
// #if HAS_PRINCIPLED
        case MATERIAL_PRINCIPLED: {
            return principled_pdf(m, wo, wi);
        }
// #endif
// #if HAS_PRINCIPLED_THIN
        case MATERIAL_PRINCIPLED_THIN: {
            return principled_thin_pdf(m, wo, wi);
        }
// #endif
// #if HAS_GLTF_PBR
        case MATERIAL_GLTF_PBR: {
            return gltf_pbr_pdf(m, wo, wi);
        }
// #endif
        default: {
            return unknown_tag();
        }
    }
}

// `Material::sample` including `BsdfSample::checked`.
fn material_sample(m: Material, wo: vec3f, u_lobe: f32, u: vec2f) -> BsdfSample {
    var s = no_bsdf_sample();
    switch m.h.x {
        case MATERIAL_DIFFUSE: {
            s = diffuse_sample(m, wo, u);
        }
// #if HAS_CONDUCTOR
        case MATERIAL_CONDUCTOR: {
            s = conductor_sample(m, wo, u);
        }
// #endif
// #if HAS_PLASTIC
        case MATERIAL_PLASTIC: {
            s = plastic_sample(m, wo, u_lobe, u);
        }
// #endif
// #if HAS_MITSUBA_PLASTIC
        case MATERIAL_PLASTIC_MITSUBA: {
            s = plastic_mitsuba_sample(m, wo, u_lobe, u);
        }
// #endif
// #if HAS_DIELECTRIC
        case MATERIAL_DIELECTRIC: {
            s = dielectric_sample(m, wo, u_lobe, u);
        }
// #endif
// #if HAS_THIN_DIELECTRIC
        case MATERIAL_THIN_DIELECTRIC: {
            s = thin_dielectric_sample(m, wo, u_lobe);
        }
// #endif
// #if HAS_PRINCIPLED
        case MATERIAL_PRINCIPLED: {
            s = principled_sample(m, wo, u_lobe, u);
        }
// #endif
// #if HAS_PRINCIPLED_THIN
        case MATERIAL_PRINCIPLED_THIN: {
            s = principled_thin_sample(m, wo, u_lobe, u);
        }
// #endif
// #if HAS_GLTF_PBR
        case MATERIAL_GLTF_PBR: {
            s = gltf_pbr_sample(m, wo, u_lobe, u);
        }
// #endif
        default: {
            s.pdf = unknown_tag();
        }
    }
// #if MUTANTS
    if !s.delta && m.h.x == MUTANT_BSDF_PDF_TAG {
        s.pdf *= MUTANT_FACTOR;
        s.weight /= MUTANT_FACTOR;
    }
// #endif
// #if HAS_TRANSMISSION
    // A transmitting material may send wi below the surface (never into the tangent plane).
    let side_ok = select(s.wi.z > 0.0, s.wi.z != 0.0, material_transmits(m));
    let ok = s.ok && s.pdf > 0.0 && is_finite_f(s.pdf) && is_finite3(s.weight) && is_finite_f(s.eta) && side_ok;
// #else
    let ok = s.ok && s.pdf > 0.0 && is_finite_f(s.pdf) && is_finite3(s.weight) && s.wi.z > 0.0;
// #endif
    if !ok {
        return no_bsdf_sample();
    }
    return s;
}

fn material_has_smooth_part(m: Material) -> bool {
    return m.h.w != 0u;
}

// #if HAS_TEXTURES
// Whether `m` has a texture (`Scene::material_at` borrows the others as they are).
fn material_textured(m: Material) -> bool {
    return bitcast<u32>(m.a.w) != NONE || bitcast<u32>(m.c.w) != NONE;
}

// `MaterialTextures::at`: `m` with its textures evaluated at `at`, and its has-a-smooth-part flag
// recomputed for the values found (`Material::has_smooth_part`). The one place a material's
// parameters come from textures: further texturable kinds plug in here.
fn material_at(m_in: Material, at: TexPoint) -> Material {
    var m = m_in;
    let colour = bitcast<u32>(m.a.w);
    let slot = bitcast<u32>(m.c.w);
    let alpha = select(slot & 0xFFFFu, NONE, slot == NONE);
    let alpha_v = select(slot >> 16u, NONE, slot == NONE || (slot >> 16u) == 0xFFFFu);
    switch m.h.x {
        case MATERIAL_DIFFUSE, MATERIAL_PLASTIC, MATERIAL_PLASTIC_MITSUBA: {
            // `Plastic::set_albedo` sets the albedo only: the coat's table and norm stay.
            if colour != NONE {
                m.a = vec4f(texture_eval(colour, at), m.a.w);
            }
// #if HAS_PLASTIC
            // A plastic's α: its coat from the grid (`Plastic::set_alpha_from_grid`).
            if m.h.x == MATERIAL_PLASTIC && alpha != NONE {
                m = plastic_alpha_from_grid(m, texture_eval_scalar(alpha, at));
            }
// #endif
        }
        // A textured α alone is isotropic: (α_u, α_v) = (α, α) (`Microfacet::with_alpha`).
        case MATERIAL_CONDUCTOR: {
            // A textured reflectance is a tint, whatever the constant's Fresnel.
            if colour != NONE {
                m.a = vec4f(texture_eval(colour, at), m.a.w);
                m.h.z = FRESNEL_TINT;
            }
            if alpha != NONE {
                m.c = vec4f(textured_alphas(alpha, alpha_v, at), m.c.zw);
            }
        }
        case MATERIAL_DIELECTRIC: {
            if alpha != NONE {
                m.c = vec4f(textured_alphas(alpha, alpha_v, at), m.c.zw);
            }
        }
        // Nothing of it is texturable (`MaterialTextures::check`).
        case MATERIAL_THIN_DIELECTRIC: {}
// #if HAS_PRINCIPLED
        // Its base colour in the colour slot, its scalars by the ids in `tables`.
        case MATERIAL_PRINCIPLED: {
            if colour != NONE {
                m.a = vec4f(texture_eval(colour, at), m.a.w);
            }
            if slot != NONE {
                m = principled_at(m, at);
            }
        }
// #endif
// #if HAS_PRINCIPLED_THIN
        case MATERIAL_PRINCIPLED_THIN: {
            if colour != NONE {
                m.a = vec4f(texture_eval(colour, at), m.a.w);
            }
            if slot != NONE {
                m = principled_thin_at(m, at);
            }
        }
// #endif
// #if HAS_GLTF_PBR
        // Its base colour in the colour slot, roughness and metallic by the ids in c.w.
        case MATERIAL_GLTF_PBR: {
            if colour != NONE {
                m.a = vec4f(texture_eval(colour, at), m.a.w);
            }
            if slot != NONE {
                m = gltf_pbr_at(m, at);
            }
        }
// #endif
        default: {
            m.a = vec4f(unknown_tag());
        }
    }
    m.h.w = select(0u, 1u, material_smooth_part(m));
    return m;
}

// `MaterialTextures::microfacet_at`: (α_u, α_v) from the α texture and, if any, the α_v one; the
// narrower raised to SMOOTH_ALPHA where the lobe is rough (`Microfacet::new`).
fn textured_alphas(alpha: u32, alpha_v: u32, at: TexPoint) -> vec2f {
    let u = texture_eval_scalar(alpha, at);
    if alpha_v == NONE {
        return vec2f(u);
    }
    var a = vec2f(u, texture_eval_scalar(alpha_v, at));
    if !(max(a.x, a.y) < SMOOTH_ALPHA) {
        a = max(a, vec2f(SMOOTH_ALPHA));
    }
    return a;
}

// `Material::has_smooth_part` of a record's current parameters.
fn material_smooth_part(m: Material) -> bool {
    switch m.h.x {
        case MATERIAL_DIFFUSE: {
            return true;
        }
// #if HAS_CONDUCTOR
        case MATERIAL_CONDUCTOR: {
            return !conductor_is_delta(m);
        }
// #endif
// #if HAS_PLASTIC
        case MATERIAL_PLASTIC: {
            return plastic_has_smooth_part(m);
        }
// #endif
// #if HAS_MITSUBA_PLASTIC
        case MATERIAL_PLASTIC_MITSUBA: {
            return plastic_mitsuba_has_smooth_part(m);
        }
// #endif
// #if HAS_DIELECTRIC
        case MATERIAL_DIELECTRIC: {
            return !dielectric_is_delta(m);
        }
// #endif
// #if HAS_THIN_DIELECTRIC
        case MATERIAL_THIN_DIELECTRIC: {
            return false;
        }
// #endif
// #if HAS_PRINCIPLED
        case MATERIAL_PRINCIPLED: {
            return true;
        }
// #endif
// #if HAS_PRINCIPLED_THIN
        case MATERIAL_PRINCIPLED_THIN: {
            return true;
        }
// #endif
// #if HAS_GLTF_PBR
        // Always rough (α ≥ SMOOTH_ALPHA).
        case MATERIAL_GLTF_PBR: {
            return true;
        }
// #endif
        default: {
            _ = unknown_tag();
            return false;
        }
    }
}
// #endif
