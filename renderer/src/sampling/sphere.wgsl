// The sphere warps of `sampling/sphere.rs`: the forward map and its constant pdf.

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
