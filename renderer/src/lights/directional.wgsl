// Directional lights, the twin of `lights/directional.rs`: the direction towards the light,
// radiance = its irradiance, "pdf" 1, a shadow ray to infinity. Record: a.xyz = the direction
// the light travels in, le.xyz = irradiance.

fn directional_light_sample(l: Light) -> LightSample {
    let wi = -l.a.xyz;
    return LightSample(wi, vec3f(0.0), l.a.xyz, wi, 1.0, l.le.xyz, true, true, vec2f(0.0));
}
