// Morton (Z-order) codes, the twin of `sampler/morton.rs`: the bits of x and y interleaved. Only
// the encoding: the GPU never decodes (`morton_decode` is the CPU tests' round trip).

// `spread_bits`: the low 16 bits of v to the even bit positions.
fn spread_bits(v_in: u32) -> u32 {
    var v = v_in & 0x0000ffffu;
    v = (v | (v << 8u)) & 0x00ff00ffu;
    v = (v | (v << 4u)) & 0x0f0f0f0fu;
    v = (v | (v << 2u)) & 0x33333333u;
    return (v | (v << 1u)) & 0x55555555u;
}

// `morton_encode`: x in the even bits, y in the odd ones (low 16 bits of each).
fn morton_encode(x: u32, y: u32) -> u32 {
    return spread_bits(x) | (spread_bits(y) << 1u);
}
