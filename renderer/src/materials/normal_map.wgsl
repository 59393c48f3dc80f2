// Normal and bump maps (Mitsuba's `normalmap` and `bumpmap`), the twin of
// `materials/normal_map.rs` and `materials/bump_map.rs`: the bumped normal (`bump_normal`), the
// perturbed frame (`normal_map_perturb`) and the BSDF of a path vertex under it (`VertexBsdf`: `vertex_eval`,
// `vertex_pdf`, `vertex_sample`). The current vertex's perturbation is a private variable that
// `path_trace` sets where it builds the frame, so that the BSDF calls keep the arguments they have
// (the CPU passes it in `VertexBsdf`); without HAS_NORMAL_MAPS the calls are the material's own.
//
// A material record's `h.y` (`gpu/scene/materials.rs` `sides_word`): bit 0 two-sided, bit 1
// `flip_invalid_normals`, bit 2 the shadowing term, bit 3 a bump map (the texture is heights,
// its record's c1.x the scale), bits 4… the map texture's id + 1 (0: none).

// #if HAS_NORMAL_MAPS
// `Perturbation`; `on` = false stands for `None`.
struct Perturbation {
    up: vec3f,
    alpha2: f32,
    on: bool,
}

var<private> vertex_perturbation: Perturbation;

// `NormalMap::perturb`'s result; `ok` = false stands for `None`.
struct Perturbed {
    ok: bool,
    frame: Frame,
    p: Perturbation,
}

fn no_perturbation() -> Perturbation {
    return Perturbation(vec3f(0.0, 0.0, 1.0), 0.0, false);
}

// The id + 1 of material `m`'s normal or bump map texture, 0 for none.
fn normal_map_texture(m: Material) -> u32 {
    return m.h.y >> 4u;
}

// Whether material `m`'s map is a bump map.
fn normal_map_is_bump(m: Material) -> bool {
    return (m.h.y & 8u) != 0u;
}

// `bump_map::local_normal`: the bumped normal in `front`'s coordinates (xyz), w = 0 for no tilt.
fn bump_normal(grad: vec2f, dp_du: vec3f, dp_dv: vec3f, ns: vec3f, ng: vec3f, front: Frame) -> vec4f {
    if grad.x == 0.0 && grad.y == 0.0 {
        return vec4f(0.0);
    }
    let du = dp_du + ns * (grad.x - dot(ns, dp_du));
    let dv = dp_dv + ns * (grad.y - dot(ns, dp_dv));
    let c = cross(du, dv);
    let len = length(c);
    if !(len > 0.0 && is_finite_f(len)) {
        return vec4f(0.0);
    }
    var n = c / len;
    if dot(ng, n) < 0.0 {
        n = -n;
    }
    return vec4f(to_local(front, n), 1.0);
}

fn nm_tan2(cos: f32) -> f32 {
    return max(1.0 - cos * cos, 0.0) / (cos * cos);
}

// `NormalMap::perturb`: the frame the material sees where material word `word` (its `h.y`) has a
// map giving the normal `n_in` (`NormalMap::decode` of a texel, or `bump_normal`) about the
// unperturbed frame `base` (first axis along ∂p/∂u), seen from `wo_world`.
fn normal_map_perturb(word: u32, n_in: vec3f, base: Frame, wo_world: vec3f) -> Perturbed {
    let none = Perturbed(false, base, no_perturbation());
    var n = n_in;
    if n.x == 0.0 && n.y == 0.0 && n.z > 0.0 {
        return none;
    }
    let len = length(n);
    if !(len > 0.0 && is_finite_f(len)) {
        return none;
    }
    if (word & 2u) != 0u {
        let wo = to_local(base, wo_world);
        if wo.z * dot(wo, n) <= 0.0 {
            n = vec3f(-n.x, -n.y, n.z);
        }
    }
    n = n / len;
    var s = vec3f(1.0, 0.0, 0.0) - n * n.x;
    let s_len = length(s);
    if s_len > 0.0 {
        s = s / s_len;
    } else {
        s = frame_from_normal(n).s;
    }
    let t = cross(n, s);
    let frame = Frame(to_world(base, s), to_world(base, t), to_world(base, n));
    let up = vec3f(s.z, t.z, n.z);
    var alpha2 = 0.0;
    if (word & 4u) != 0u {
        alpha2 = min(0.125 * nm_tan2(up.z), 1.0);
    }
    return Perturbed(true, frame, Perturbation(up, alpha2, true));
}

// `normal_map::seen_from`: the frame the map is read in; on the back of a two-sided material the
// turned frame's second axis turned back (the front's frame mirrored through the surface).
fn normal_map_seen_from(f: Frame, back: bool) -> Frame {
    if back {
        return Frame(f.s, -f.t, f.n);
    }
    return f;
}

// `Perturbation::factor`: 0 on the wrong side of the unperturbed frame, else the shadowing term.
fn perturbation_factor(p: Perturbation, wi: vec3f) -> f32 {
    let cos = dot(wi, p.up);
    if !(wi.z * cos > 0.0) {
        return 0.0;
    }
    if p.alpha2 == 0.0 {
        return 1.0;
    }
    return 2.0 / (1.0 + sqrt(1.0 + p.alpha2 * nm_tan2(cos)));
}
// #endif

// `VertexBsdf::eval`.
fn vertex_eval(m: Material, wo: vec3f, wi: vec3f) -> vec3f {
    let f = material_eval(m, wo, wi);
// #if HAS_NORMAL_MAPS
    if vertex_perturbation.on {
        let k = perturbation_factor(vertex_perturbation, wi);
        return select(f * k, vec3f(0.0), k == 0.0);
    }
// #endif
    return f;
}

// `VertexBsdf::pdf`.
fn vertex_pdf(m: Material, wo: vec3f, wi: vec3f) -> f32 {
// #if HAS_NORMAL_MAPS
    if vertex_perturbation.on && perturbation_factor(vertex_perturbation, wi) == 0.0 {
        return 0.0;
    }
// #endif
    return material_pdf(m, wo, wi);
}

// `VertexBsdf::sample`.
fn vertex_sample(m: Material, wo: vec3f, u_lobe: f32, u: vec2f) -> BsdfSample {
    var s = material_sample(m, wo, u_lobe, u);
// #if HAS_NORMAL_MAPS
    if vertex_perturbation.on && s.ok {
        let k = perturbation_factor(vertex_perturbation, s.wi);
        if k == 0.0 {
            return no_bsdf_sample();
        }
        s.weight *= k;
    }
// #endif
    return s;
}
