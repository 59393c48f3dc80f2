// Spot lights, the twin of `lights/spot.rs`: a point light shaped by Mitsuba's falloff curve,
// optionally projecting a texture (applied by `light_sample_textured` at the sample's b).
// Record: a = (position, cutoff), b = (local x, cos cutoff), c = (local y, cos beam),
// d = (axis, 1 / (cutoff − beam)), le = (intensity, tan cutoff), h.w = texture.

// `SpotLight::falloff`.
fn spot_light_falloff(l: Light, local: vec3f) -> f32 {
    let cos_theta = normalize(local).z;
    if !(cos_theta > l.b.w) {
        return 0.0;
    }
    if cos_theta >= l.c.w {
        return 1.0;
    }
    // The built-in acos may be 4096 ulp off: the ramp would amplify it.
    return (l.a.w - acos_precise(cos_theta)) * l.d.w;
}

fn spot_light_sample(l: Light, p: vec3f) -> LightSample {
    let d = l.a.xyz - p;
    let dist2 = dot(d, d);
    let local = vec3f(dot(-d, l.b.xyz), dot(-d, l.c.xyz), dot(-d, l.d.xyz));
    let falloff = spot_light_falloff(l, local);
    if !(falloff > 0.0 && dist2 > 0.0) {
        return no_light_sample();
    }
    var uv = vec2f(0.0);
    if l.h.w != NONE {
        uv = vec2f(0.5 + 0.5 * local.x / (local.z * l.le.w), 0.5 + 0.5 * local.y / (local.z * l.le.w));
    }
    return delta_sample(l.a.xyz, d / sqrt(dist2), l.le.xyz * (falloff / dist2), uv);
}
