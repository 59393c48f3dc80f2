// Emitting disks, the twin of `lights/disk.rs`: uniformly by solid angle through the spherical
// ellipse (`sampling/spherical_ellipse.wgsl`) where the method asks for it and the ellipse suits the warp,
// uniformly by area through the concentric map otherwise.

fn disk_light_area(l: Light) -> f32 {
    return PI * l.a.w * l.a.w;
}

// `DiskLight::ellipse`: the spherical ellipse seen from p, ok = false where sampled by area.
fn disk_light_ellipse(l: Light, p: vec3f, method: u32) -> SphericalEllipse {
    let center = l.a.xyz;
    let n = l.d.xyz;
    if !light_sampling_spherical_for(method, p, center, n, disk_light_area(l)) {
        var none: SphericalEllipse;
        none.ok = false;
        return none;
    }
    return sph_ellipse_new(p, center, n, l.a.w);
}

fn disk_light_sample(l: Light, p: vec3f, u: vec2f, method: u32) -> LightSample {
    let center = l.a.xyz;
    let n = l.d.xyz;
    let height = dot(p - center, n);
    if height <= 0.0 {
        return no_light_sample();
    }
    let e = disk_light_ellipse(l, p, method);
    if e.ok {
        let wi = sph_ellipse_sample(e, u);
        let cos_y = -dot(wi, n);
        if !(cos_y > 0.0) {
            return no_light_sample();
        }
        let y = disk_surface_point(center, n, Ray(p, wi, inf()), height / cos_y);
        return LightSample(y[0], y[1], n, wi, sph_ellipse_pdf(e), l.le.xyz, false, true, vec2f(0.0));
    }
    let frame = frame_from_normal(n);
    let d = sample_uniform_disk_concentric(u) * l.a.w;
    let y = center + frame.s * d.x + frame.t * d.y;
    return area_sample(p, y, n, 1.0 / disk_light_area(l), l.le.xyz);
}

// `DiskLight::pdf`: solid-angle pdf of hitting y (normal ny) from p.
fn disk_light_pdf(l: Light, p: vec3f, y: vec3f, ny: vec3f, method: u32) -> f32 {
    let e = disk_light_ellipse(l, p, method);
    if e.ok {
        return sph_ellipse_pdf(e);
    }
    return area_to_solid_angle(1.0 / disk_light_area(l), p, y, ny);
}
