// Multiple-importance heuristics, the twin of `integrator/mis.rs`. `heuristic`: HEURISTIC_BALANCE
// or HEURISTIC_POWER.

fn mis_weight(heuristic: u32, pa: f32, pb: f32) -> f32 {
    // Bit tests: comparisons with NaN or infinity are not reliable in WGSL.
    if bitcast<u32>(pa) == 0x7f800000u {
        return 1.0;
    }
    if is_nan_f(pa) || !is_finite_f(pb) || !(pa > 0.0) {
        return 0.0;
    }
    // Scale so the larger pdf is in [2, 4) (see `pow2_normalizer`): the squares and the
    // division stay in the normal range, where WGSL bounds the division's error.
    let s = pow2_normalizer(max(pa, pb));
    var a = pa * s;
    var b = max(pb, 0.0) * s;
    if heuristic == HEURISTIC_POWER {
        a = a * a;
        b = b * b;
    }
    return a / (a + b);
}

// The twin of `integrator::mis::pow2_normalizer`: the power of two that brings a finite positive
// `m` into [2, 4), built from its exponent bits (always a normal f32).
fn pow2_normalizer(m: f32) -> f32 {
    let biased_exponent = max((bitcast<u32>(m) >> 23u) & 0xffu, 1u);
    return bitcast<f32>((255u - biased_exponent) << 23u);
}
