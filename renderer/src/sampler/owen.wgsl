// Owen scrambling and the hashes that seed it, bit for bit the twin of `sampler/owen.rs` (u64
// emulated on vec2<u32>(lo, hi) by `gpu/u64.wgsl`). `mix64` is also the finaliser of `materials/mix.wgsl`'s
// SplitMix64 step, as on the CPU. The inverse (`owen_unscramble`) has no twin: only the CPU's
// tests need it.

// `mix64`: SplitMix64's finaliser (Stafford's "Mix13"), multipliers from the prelude.
fn mix64(v: vec2<u32>) -> vec2<u32> {
    var z = u64_mul(v ^ u64_shr(v, 30u), vec2<u32>(MIX64_M1_LO, MIX64_M1_HI));
    z = u64_mul(z ^ u64_shr(z, 27u), vec2<u32>(MIX64_M2_LO, MIX64_M2_HI));
    return z ^ u64_shr(z, 31u);
}

// `hash3`: the top half of mix64(mix64(a << 32 | b) ^ c).
fn hash3(a: u32, b: u32, c: vec2<u32>) -> u32 {
    return mix64(mix64(vec2<u32>(b, a)) ^ c).y;
}

// `hash32`: Wellons' lowbias32, multipliers from the prelude.
fn hash32(v: u32) -> u32 {
    var x = v ^ (v >> 16u);
    x *= HASH32_M1;
    x ^= x >> 15u;
    x *= HASH32_M2;
    return x ^ (x >> 16u);
}

// `owen_scramble`: the nested uniform scramble of the 32-bit fixed-point value v (Laine–Karras
// style: reverse, a permutation whose carries only flow upwards, reverse back).
fn owen_scramble(v: u32, seed: u32) -> u32 {
    var x = reverseBits(v);
    x ^= x * OWEN_LK_MUL_A;
    x += seed;
    x *= (seed >> 16u) | 1u;
    x ^= x * OWEN_LK_MUL_B;
    x ^= x * OWEN_LK_MUL_C;
    return reverseBits(x);
}
