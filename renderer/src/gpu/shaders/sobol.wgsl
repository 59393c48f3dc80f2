// The first two Sobol dimensions, the twin of `sampler/sobol.rs`, 32-bit fixed point. Dimension
// 1's generator matrix is the prelude's SOBOL_1_COLUMNS, written from the Rust table.

// `sobol_0`: van der Corput, the index's bits reversed.
fn sobol_0(index: u32) -> u32 {
    return reverseBits(index);
}

// `sobol_1`: the XOR of the columns of the index's set bits.
fn sobol_1(index: u32) -> u32 {
    var v = 0u;
    var a = index;
    var i = 0u;
    while a != 0u {
        if (a & 1u) != 0u {
            v ^= SOBOL_1_COLUMNS[i];
        }
        a >>= 1u;
        i += 1u;
    }
    return v;
}
