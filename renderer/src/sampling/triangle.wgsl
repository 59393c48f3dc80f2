// The triangle warp of `sampling/triangle.rs`: the forward map the renderer uses (its pdf is a
// constant the callers inline, as on the CPU).

// `sample_uniform_triangle` (Heitz 2019): barycentrics (b0, b1, b2).
fn sample_uniform_triangle(u: vec2f) -> vec3f {
    var b0: f32;
    var b1: f32;
    if u.x < u.y {
        b0 = 0.5 * u.x;
        b1 = u.y - b0;
    } else {
        b1 = 0.5 * u.y;
        b0 = u.x - b1;
    }
    return vec3f(b0, b1, 1.0 - b0 - b1);
}
