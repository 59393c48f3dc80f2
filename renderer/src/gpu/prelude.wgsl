// Unknown kind tags, the twin of `gpu/prelude.rs` (which generates the tags themselves: MATERIAL_*,
// FRESNEL_*, LIGHT_*, SHAPE_*, STRATEGY_*, HEURISTIC_*, LIGHT_SAMPLING_*, FILTER_*, …). A `switch` over a tag
// whose cases miss the value (a record or parameter the encoders never write) calls
// `unknown_tag()` instead of quietly returning 0: the sample is then NaN, which the render kernel
// counts as non-finite (`integrator/path.wgsl`), and eval and pdf return NaN to their callers.

var<private> unknown_tag_seen: bool = false;
// NaN's bits in a private variable: WGSL rejects NaN constant expressions.
var<private> NAN_BITS: u32 = 0x7fc00000u;

// Flags the invocation and returns NaN.
fn unknown_tag() -> f32 {
    unknown_tag_seen = true;
    return bitcast<f32>(NAN_BITS);
}
