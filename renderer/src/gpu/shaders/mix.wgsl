// Mixes of two materials, the twin of `materials/mix.rs` and of `Scene::resolve_mix`: at a hit a
// mix chooses one of its two materials by a hash of the bits of the hit point, the hit's ray
// distance and the mix's own material index (the salt), bit for bit as the CPU does, so that both
// sides choose alike at the same hit. Compiled only under HAS_MIXES.
//
// A mix's record lives in `materials` at the mix's own index (`gpu/scene/materials.rs`):
//   h = (MATERIAL_MIX, first material, second material, id of the weight's texture or NONE);
//   a.x = the constant weight (when h.w is NONE); a.w, c.w = bits of NONE (no texture slots).
// No BSDF function takes MATERIAL_MIX (their `switch`es flag it), so a mix left unresolved is loud.
//
// u64 arithmetic is emulated on vec2<u32>(lo, hi): WGSL has no 64-bit integers.

// a + b mod 2^64.
fn u64_add(a: vec2<u32>, b: vec2<u32>) -> vec2<u32> {
    let lo = a.x + b.x;
    return vec2<u32>(lo, a.y + b.y + select(0u, 1u, lo < a.x));
}

// The full 64-bit product of two u32, from 16-bit halves (no partial sum overflows).
fn u32_mul_wide(a: u32, b: u32) -> vec2<u32> {
    let a0 = a & 0xffffu;
    let a1 = a >> 16u;
    let b0 = b & 0xffffu;
    let b1 = b >> 16u;
    let p00 = a0 * b0;
    let p01 = a0 * b1;
    let p10 = a1 * b0;
    let p11 = a1 * b1;
    let mid = (p00 >> 16u) + (p01 & 0xffffu) + (p10 & 0xffffu);
    let lo = (p00 & 0xffffu) | (mid << 16u);
    let hi = p11 + (p01 >> 16u) + (p10 >> 16u) + (mid >> 16u);
    return vec2<u32>(lo, hi);
}

// a · b mod 2^64 (`u64::wrapping_mul`).
fn u64_mul(a: vec2<u32>, b: vec2<u32>) -> vec2<u32> {
    let w = u32_mul_wide(a.x, b.x);
    return vec2<u32>(w.x, w.y + a.x * b.y + a.y * b.x);
}

// a >> n for 0 < n < 32.
fn u64_shr(a: vec2<u32>, n: u32) -> vec2<u32> {
    return vec2<u32>((a.x >> n) | (a.y << (32u - n)), a.y >> n);
}

// `mix64`: SplitMix64's finaliser.
fn mix64(z_in: vec2<u32>) -> vec2<u32> {
    var z = u64_add(z_in, vec2<u32>(MIX_GOLDEN_LO, MIX_GOLDEN_HI));
    z = u64_mul(z ^ u64_shr(z, 30u), vec2<u32>(MIX64_M1_LO, MIX64_M1_HI));
    z = u64_mul(z ^ u64_shr(z, 27u), vec2<u32>(MIX64_M2_LO, MIX64_M2_HI));
    return z ^ u64_shr(z, 31u);
}

// `hash_unit`: a value in [0, 1) on a grid of 2^-24 from the bits of p, t and salt.
fn mix_hash_unit(p: vec3f, t: f32, salt: u32) -> f32 {
    var h = vec2<u32>(MIX_GOLDEN_LO ^ salt, MIX_GOLDEN_HI);
    let words = array<u32, 4>(bitcast<u32>(p.x), bitcast<u32>(p.y), bitcast<u32>(p.z), bitcast<u32>(t));
    for (var k = 0u; k < 4u; k++) {
        h = mix64(vec2<u32>(h.x ^ words[k], h.y));
    }
    // (h >> 40) as f32 / 2^24: exact.
    return f32(h.y >> 8u) * (1.0 / 16777216.0);
}

// `choice`: the second material (1) when u < w; 0 for w ≤ 0 or NaN.
fn mix_choice(w: f32, u: f32) -> u32 {
    return select(0u, 1u, u < w);
}

// `Scene::resolve_mix`: the material that material `mi` resolves to at `hit` on `prim` (`mi`
// itself when it is no mix), through nested mixes, each salted with its own index. The texture
// coordinates are computed only for a textured weight, as on the CPU.
fn mix_resolve(mi_in: u32, prim: Prim, hit: SurfaceHit) -> u32 {
    var mi = mi_in;
    // The builder checked that every chain of mixes ends within the number of materials; the
    // bound only keeps a corrupt record from hanging the device.
    let n = arrayLength(&materials);
    for (var k = 0u; k <= n; k++) {
        let m = materials[mi];
        if m.h.x != MATERIAL_MIX {
            return mi;
        }
        var w = m.a.x;
// #if HAS_TEXTURES
        if m.h.w != NONE {
            w = texture_eval_scalar(m.h.w, surface_uv(prim, hit));
        }
// #endif
        let pick = mix_choice(w, mix_hash_unit(hit.p, hit.t, mi));
        mi = select(m.h.y, m.h.z, pick == 1u);
    }
    _ = unknown_tag();
    return mi;
}
