// The planar disk warps of `sampling/disk.rs`: the forward maps the renderer uses.

// `sample_uniform_disk_concentric` (Shirley–Chiu).
fn sample_uniform_disk_concentric(u: vec2f) -> vec2f {
    let rt = concentric_polar(u);
    return rt.x * vec2f(cos(rt.y), sin(rt.y));
}

// `concentric_polar`: (signed r, θ ∈ [-π/4, 3π/4]) of the concentric disk point.
fn concentric_polar(u: vec2f) -> vec2f {
    let o = 2.0 * u - vec2f(1.0);
    if o.x == 0.0 && o.y == 0.0 {
        return vec2f(0.0);
    }
    if abs(o.x) > abs(o.y) {
        return vec2f(o.x, FRAC_PI_4 * (o.y / o.x));
    }
    return vec2f(o.y, FRAC_PI_2 - FRAC_PI_4 * (o.x / o.y));
}
