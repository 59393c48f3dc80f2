// The ZSobol sampler, bit for bit the twin of `sampler/zsobol.rs`: the sample's Sobol index is
// the pixel's Morton code within its 64×64 tile above the sample's index within its epoch of
// 4096; the seed, the tile and the epoch go into a 64-bit key (vec2<u32>(lo, hi), `gpu/u64.wgsl`)
// that seeds each dimension's base-4 index permutation (folded to 32 bits, its digits chosen by
// `hash32`) and Owen scrambles. The permutation table
// is the prelude's ZSOBOL_PERMUTATIONS (the Rust table, each permutation packed 2 bits a digit).
// The inverse (`unpermute_index`) has no twin: only the CPU's tests need it.

// One invocation draws one sample at a time, so the sample's state is private (`ZSobolSampler`).
var<private> zsobol_key: vec2<u32>;
var<private> zsobol_index: u32;

// `digit_permutation`, returned packed: digit d maps to bits 2d..2d+1.
fn zsobol_digit_permutation(higher: u32, position: u32, key: u32) -> u32 {
    return ZSOBOL_PERMUTATIONS[hash32(((higher << 4u) | position) ^ key) % 24u];
}

// `permute_index`: the low 2·digits bits of index permuted digit by digit, from the top, each
// digit's permutation chosen by key, its position and the original digits above it.
fn permute_index(index: u32, digits: u32, key: u32) -> u32 {
    var out = 0u;
    for (var position = digits; position > 0u; ) {
        position -= 1u;
        let shift = 2u * position;
        let digit = (index >> shift) & 3u;
        let higher = index >> (shift + 2u);
        let perm = zsobol_digit_permutation(higher, position, key);
        out |= ((perm >> (2u * digit)) & 3u) << shift;
    }
    return out;
}

// `ZSobolSampler::new`.
fn zsobol_init(seed: u32, x: u32, y: u32, sample: u32) {
    let mask = (1u << ZSOBOL_TILE_LOG2) - 1u;
    let tile = mix64(vec2<u32>(y >> ZSOBOL_TILE_LOG2, x >> ZSOBOL_TILE_LOG2));
    zsobol_key = mix64(vec2<u32>(sample >> ZSOBOL_EPOCH_LOG2, seed) ^ tile);
    zsobol_index = (morton_encode(x & mask, y & mask) << ZSOBOL_EPOCH_LOG2)
        | (sample & ((1u << ZSOBOL_EPOCH_LOG2) - 1u));
}

// `ZSobolSampler::index_for`.
fn zsobol_index_for(dim: u32) -> u32 {
    let k = zsobol_key ^ mix64(vec2<u32>(dim, 0u));
    return permute_index(zsobol_index, ZSOBOL_INDEX_DIGITS, k.x ^ k.y);
}

// `ZSobolSampler::seed_for`.
fn zsobol_seed_for(dim: u32, component: u32) -> u32 {
    return hash3(dim, component, zsobol_key);
}

// `ZSobolSampler::get_1d`.
fn zsobol_get_1d(dim: u32) -> f32 {
    let i = zsobol_index_for(dim);
    return unit_f32(owen_scramble(sobol_0(i), zsobol_seed_for(dim, 0u)));
}

// `ZSobolSampler::get_2d`: one permuted index, Sobol dimensions 0 and 1.
fn zsobol_get_2d(dim: u32) -> vec2f {
    let i = zsobol_index_for(dim);
    let x = unit_f32(owen_scramble(sobol_0(i), zsobol_seed_for(dim, 0u)));
    return vec2f(x, unit_f32(owen_scramble(sobol_1(i), zsobol_seed_for(dim, 1u))));
}
