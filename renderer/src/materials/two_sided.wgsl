// Two-sided pairs, the twin of `materials/two_sided.rs`: a front and a back material, the back
// one seen by paths that arrive on the back of the surface (then, as for any two-sided material,
// through flipped normals). Compiled with `materials/mix.wgsl`, whose resolve loop calls it.
//
// A pair's record lives in `materials` at the pair's own index (`gpu/scene/materials.rs`):
//   h = (MATERIAL_TWO_SIDED, front material, back material, NONE); a.w, c.w = bits of NONE (no
//   texture slots). No BSDF function takes MATERIAL_TWO_SIDED (their `switch`es flag it), so a
//   pair left unresolved is loud.

// `TwoSided::choose`: the material that a path arriving on the back (`back`) or front sees.
fn two_sided_choose(m: Material, back: bool) -> u32 {
    return select(m.h.y, m.h.z, back);
}
