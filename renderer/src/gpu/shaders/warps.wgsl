// The planar warps of `sampling/` (`sampling/disk.rs`, `sampling/hemisphere.rs`,
// `sampling/sphere.rs`, `sampling/triangle.rs`): the forward maps the renderer uses. Their pdfs
// are constants the callers inline, as on the CPU.

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

// `sample_cosine_hemisphere` (Malley): pdf cosθ/π; cos θ from the radius, as on the CPU.
fn sample_cosine_hemisphere(u: vec2f) -> vec3f {
    let rt = concentric_polar(u);
    let r = abs(rt.x);
    let z = safe_sqrt((1.0 - r) * (1.0 + r));
    return vec3f(rt.x * cos(rt.y), rt.x * sin(rt.y), z);
}

// `sample_uniform_sphere`: pdf 1/4π.
fn sample_uniform_sphere(u: vec2f) -> vec3f {
    let z = 1.0 - 2.0 * u.x;
    let r = 2.0 * safe_sqrt(u.x * (1.0 - u.x));
    let phi = TAU * u.y;
    return vec3f(r * cos(phi), r * sin(phi), z);
}

fn uniform_sphere_pdf() -> f32 {
    return 1.0 / (4.0 * PI);
}

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
