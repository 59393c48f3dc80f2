// Mixes of two materials, the twin of `materials/mix.rs` and of `Scene::resolve` (whose loop also
// resolves the pairs of `materials/two_sided.rs`): at a hit a mix chooses one of its two
// materials by a hash of the bits of the hit point, the hit's ray distance and the mix's own
// material index (the salt), bit for bit as the CPU does, so that both sides choose alike at the
// same hit. Compiled under HAS_MIXES (a scene with mixes or two-sided pairs) or HAS_MASKS (for
// the hash alone).
//
// A mix's record lives in `materials` at the mix's own index (`gpu/scene/materials.rs`):
//   h = (MATERIAL_MIX, first material, second material, id of the weight's texture or NONE);
//   a.x = the constant weight (when h.w is NONE); a.y = 1 for Mitsuba's blend (`Mix::mitsuba`);
//   a.w, c.w = bits of NONE (no texture slots).
// No BSDF function takes MATERIAL_MIX (their `switch`es flag it), so a mix left unresolved is loud.
//
// u64 arithmetic is emulated on vec2<u32>(lo, hi) (`gpu/u64.wgsl`): WGSL has no 64-bit integers.

// `splitmix64`: one SplitMix64 step, the golden increment then `sampler/owen.wgsl`'s finaliser `mix64`.
fn splitmix64(z: vec2<u32>) -> vec2<u32> {
    return mix64(u64_add(z, vec2<u32>(MIX_GOLDEN_LO, MIX_GOLDEN_HI)));
}

// `hash_unit`: a value in [0, 1) on a grid of 2^-24 from the bits of p, t and salt.
fn mix_hash_unit(p: vec3f, t: f32, salt: u32) -> f32 {
    var h = vec2<u32>(MIX_GOLDEN_LO ^ salt, MIX_GOLDEN_HI);
    let words = array<u32, 4>(bitcast<u32>(p.x), bitcast<u32>(p.y), bitcast<u32>(p.z), bitcast<u32>(t));
    for (var k = 0u; k < 4u; k++) {
        h = splitmix64(vec2<u32>(h.x ^ words[k], h.y));
    }
    // (h >> 40) as f32 / 2^24: exact.
    return f32(h.y >> 8u) * (1.0 / 16777216.0);
}

// `choice`: the second material (1) when u < w; 0 for w ≤ 0 or NaN.
fn mix_choice(w: f32, u: f32) -> u32 {
    return select(0u, 1u, u < w);
}

// A material resolved at a hit: its index, and whether a two-sided pair chose it on the way (then
// it is seen from either side, whatever its own record's two-sided bit says, as the CPU reads the
// bit of the hit primitive's own material).
// A mix of model mitsuba that chose it gives its `Blend`: the other part (else NONE) and the
// chosen part's probability.
struct ResolvedMaterial {
    index: u32,
    paired: bool,
    partner: u32,
    weight: f32,
}

// `blend_delta_weight`: Mitsuba's blend weight of a delta sample (weight, discrete pdf) of the
// part chosen with probability w_self, the partner's eval f and pdf p there.
fn blend_delta_weight(weight: vec3f, pdf: f32, w_self: f32, f: vec3f, p: f32) -> vec3f {
    let w_other = 1.0 - w_self;
    let denominator = w_self * pdf + w_other * p;
    if !(denominator > 0.0) {
        return weight;
    }
    return (w_self * weight * pdf + w_other * f) / denominator;
}

// `Scene::resolve`: the material that material `mi` is at `hit` on `prim` for a path arriving on
// the back (`back`) or front (`mi` itself when it is made of no others), through nested mixes,
// each salted with its own index, and two-sided pairs. The texture coordinates are computed only
// for a textured weight, as on the CPU.
fn material_resolve(mi_in: u32, prim: Prim, hit: SurfaceHit, back: bool) -> ResolvedMaterial {
    var mi = mi_in;
    var paired = false;
    var partner = NONE;
    var weight = 1.0;
    // The builder checked that every chain of mixes and pairs ends within the number of
    // materials; the bound only keeps a corrupt record from hanging the device.
    let n = arrayLength(&materials);
    for (var k = 0u; k <= n; k++) {
        let m = materials[mi];
        if m.h.x == MATERIAL_TWO_SIDED {
            mi = two_sided_choose(m, back);
            paired = true;
            continue;
        }
        if m.h.x != MATERIAL_MIX {
            return ResolvedMaterial(mi, paired, partner, weight);
        }
        var w = m.a.x;
// #if HAS_TEXTURES
        if m.h.w != NONE {
            w = texture_eval_scalar(m.h.w, surface_tex(prim, hit));
        }
// #endif
        let pick = mix_choice(w, mix_hash_unit(hit.p, hit.t, mi));
        partner = select(NONE, select(m.h.z, m.h.y, pick == 1u), m.a.y != 0.0);
        weight = select(1.0 - w, w, pick == 1u);
        mi = select(m.h.y, m.h.z, pick == 1u);
    }
    _ = unknown_tag();
    return ResolvedMaterial(mi, paired, partner, weight);
}
