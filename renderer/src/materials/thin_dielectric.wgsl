// A thin dielectric sheet, the twin of `materials/thin_dielectric.rs` (Mitsuba 3's
// `thindielectric`): mirror reflection with probability R = 2r/(1+r), r the Fresnel reflectance
// of one face at |cosθ|, else straight through (wi = −wo, η' = 1); both lobes delta, weight 1.
// Record: a.x ior.

fn thin_dielectric_reflectance(m: Material, cos_theta: f32) -> f32 {
    let r = fresnel_dielectric(abs(cos_theta), m.a.x);
    return 2.0 * r / (1.0 + r);
}

fn thin_dielectric_sample(m: Material, wo: vec3f, u_lobe: f32) -> BsdfSample {
    if wo.z == 0.0 {
        return no_bsdf_sample();
    }
    let r = thin_dielectric_reflectance(m, wo.z);
    if u_lobe < r {
        return reflection_sample(vec3f(-wo.x, -wo.y, wo.z), vec3f(1.0), r, true);
    }
    // A crossing without refraction: η' = 1 (`reflection_sample`'s), on the far side.
    return reflection_sample(-wo, vec3f(1.0), 1.0 - r, true);
}
