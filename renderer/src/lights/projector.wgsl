// Projectors, the twin of `lights/projector.rs`: Mitsuba's perspective projection of the image,
// radiance π·scale·irradiance / (z² cos θ), the texture applied by `light_sample_textured` at
// the sample's b. Record: a = (position, tan(fov_x/2)), b = (local x, tan(fov_y/2)),
// c.xyz = local y, d.xyz = axis, le.xyz = π·scale·irradiance (π·scale where textured),
// h.w = texture.

fn projector_light_sample(l: Light, p: vec3f) -> LightSample {
    let q = p - l.a.xyz;
    let local = vec3f(dot(q, l.b.xyz), dot(q, l.c.xyz), dot(q, l.d.xyz));
    let u = 0.5 - 0.5 * local.x / (local.z * l.a.w);
    let v = 0.5 - 0.5 * local.y / (local.z * l.b.w);
    if !(local.z > 0.0 && u >= 0.0 && u <= 1.0 && v >= 0.0 && v <= 1.0) {
        return no_light_sample();
    }
    let d = l.a.xyz - p;
    let wi = d / length(d);
    let cos_theta = -dot(l.d.xyz, wi);
    let le = l.le.xyz / (local.z * local.z * cos_theta);
    var uv = vec2f(0.0);
    if l.h.w != NONE {
        uv = vec2f(u, v);
    }
    return delta_sample(l.a.xyz, wi, le, uv);
}
