// Emitting disks, the twin of `lights/disk.rs`: uniform by area through the concentric map (no
// closed-form solid-angle warp exists, so both methods sample by area).

fn disk_light_area(l: Light) -> f32 {
    return PI * l.a.w * l.a.w;
}

fn disk_light_sample(l: Light, p: vec3f, u: vec2f) -> LightSample {
    let center = l.a.xyz;
    let n = l.d.xyz;
    if dot(p - center, n) <= 0.0 {
        return no_light_sample();
    }
    let frame = frame_from_normal(n);
    let d = sample_uniform_disk_concentric(u) * l.a.w;
    let y = center + frame.s * d.x + frame.t * d.y;
    return area_sample(p, y, n, 1.0 / disk_light_area(l), l.le.xyz);
}
