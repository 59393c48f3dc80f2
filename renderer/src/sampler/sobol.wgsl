// The first two Sobol dimensions, the twin of `sampler/sobol.rs`, 32-bit fixed point.

// `sobol_0`: van der Corput, the index's bits reversed.
fn sobol_0(index: u32) -> u32 {
    return reverseBits(index);
}

// `sobol_1`: the XOR of the generator matrix's columns of the index's set bits, as the superset
// transform of the index's bits over GF(2), reversed.
fn sobol_1(index: u32) -> u32 {
    var z = index;
    z ^= (z >> 1u) & 0x55555555u;
    z ^= (z >> 2u) & 0x33333333u;
    z ^= (z >> 4u) & 0x0f0f0f0fu;
    z ^= (z >> 8u) & 0x00ff00ffu;
    z ^= (z >> 16u) & 0x0000ffffu;
    return reverseBits(z);
}
