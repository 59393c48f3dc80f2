// Alpha masks, the twin of `materials/mask.rs` and of `Scene::meets` (`scene/trace.rs`): a
// candidate hit on a primitive whose material has an opacity α is kept with probability α, by
// `materials/mix.wgsl`'s hash of the ray's origin, the hit's distance and the primitive, as the
// CPU decides. Compiled only under HAS_MASKS.
//
// The opacities lead `tables` (`Records::of`): tables[m] holds the bits of the id of material
// m's opacity texture record (a constant opacity is a constant record), or NONE for an opaque
// material.

// Whether `ray` meets primitive `id` at its candidate hit at distance `t`.
fn mask_meets(id: u32, ray: Ray, t: f32) -> bool {
    let p = prims[id];
    let record = bitcast<u32>(tables[prim_material(p)]);
    if record == NONE {
        return true;
    }
    let at = surface_tex(p, shape_surface_hit(p, ray, t, id));
    return mask_kept(texture_eval_scalar(record, at), ray.o, t, id);
}

// `kept`: with probability alpha.
fn mask_kept(alpha: f32, o: vec3f, t: f32, prim: u32) -> bool {
    return mix_hash_unit(o, t, prim) < alpha;
}
