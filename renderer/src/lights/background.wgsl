// The constant background, the twin of `lights/background.rs`: uniform directions on the sphere.

fn background_light_sample(l: Light, u: vec2f) -> LightSample {
    let wi = sample_uniform_sphere(u);
    return LightSample(wi, vec3f(0.0), -wi, wi, uniform_sphere_pdf(), l.le.xyz, true, true, vec2f(0.0));
}
