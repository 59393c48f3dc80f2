// Projected-solid-angle sampling of the planar lights (LIGHT_SAMPLING_PROJECTED_SOLID_ANGLE), the
// twin of `lights/projected.rs`: a light's convex pieces seen from p in the receiver's frame,
// clipped to its horizon (`psa_polygon`), the decision between them and solid angle, and the
// density cos θ / Ω⊥. A piece with n < 3 is wholly below the horizon.

// `projected::frame`: the receiver's shading frame.
fn psa_frame(normal: vec3f) -> Frame {
    return frame_from_normal(normal);
}

// `projected::piece`: the convex polygon with `count` (3 or 4) world vertices a, b, c, d seen from
// p in frame f, clipped to the horizon.
fn psa_piece(p: vec3f, f: Frame, a: vec3f, b: vec3f, c: vec3f, d: vec3f, count: u32) -> PsaPolygon {
    var w: array<vec3f, 4>;
    w[0] = to_local(f, a - p);
    w[1] = to_local(f, b - p);
    w[2] = to_local(f, c - p);
    w[3] = to_local(f, d - p);
    return psa_polygon(w, count);
}

// `projected::pdf`: cos θ / Ω⊥, 0 below the horizon.
fn psa_light_pdf(ns: vec3f, wi: vec3f, area: f32) -> f32 {
    return max(dot(ns, wi), 0.0) / area;
}
