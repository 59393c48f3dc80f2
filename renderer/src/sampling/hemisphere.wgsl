// The hemisphere warps of `sampling/hemisphere.rs`: the forward maps the renderer uses (their
// pdfs are constants the callers inline, as on the CPU).

// `sample_cosine_hemisphere` (Malley): pdf cosθ/π; cos θ from the radius, as on the CPU.
fn sample_cosine_hemisphere(u: vec2f) -> vec3f {
    let rt = concentric_polar(u);
    let r = abs(rt.x);
    let z = safe_sqrt((1.0 - r) * (1.0 + r));
    return vec3f(rt.x * cos(rt.y), rt.x * sin(rt.y), z);
}
