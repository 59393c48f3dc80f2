// Point lights, the twin of `lights/point.rs`: the direction to the light, radiance I / d²,
// "pdf" 1 (a delta in position). Record: a.xyz = position, le.xyz = intensity.
// Also the helpers every delta light shares (`delta_sample`, `light_is_delta`).

// `delta_sample`: the sample of a light at y seen along wi, radiance le arriving, texture
// coordinates uv (a textured spot's or projector's).
fn delta_sample(y: vec3f, wi: vec3f, le: vec3f, uv: vec2f) -> LightSample {
    return LightSample(y, vec3f(0.0), vec3f(0.0), wi, 1.0, le, false, true, uv);
}

// `Light::is_delta`.
fn light_is_delta(l: Light) -> bool {
    let k = l.h.x;
    return k == LIGHT_POINT || k == LIGHT_SPOT || k == LIGHT_DIRECTIONAL || k == LIGHT_PROJECTOR;
}

fn point_light_sample(l: Light, p: vec3f) -> LightSample {
    let d = l.a.xyz - p;
    let dist2 = dot(d, d);
    if !(dist2 > 0.0) {
        return no_light_sample();
    }
    return delta_sample(l.a.xyz, d / sqrt(dist2), l.le.xyz / dist2, vec2f(0.0));
}
