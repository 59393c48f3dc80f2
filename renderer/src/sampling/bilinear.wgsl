// Linear and bilinear warps for cosine-aware light samples, the twin of `sampling/bilinear.rs`
// (the inverses are not needed on the GPU: its MIS pdfs invert the spherical warps only). A
// bilinear weight vector holds the corners (0,0), (1,0), (0,1), (1,1) in x, y, z, w.

fn linear_pdf(x: f32, a: f32, b: f32) -> f32 {
    if !(x >= 0.0 && x <= 1.0) {
        return 0.0;
    }
    if a + b == 0.0 {
        return 1.0;
    }
    return 2.0 * ((1.0 - x) * a + x * b) / (a + b);
}

fn sample_linear(u: f32, a: f32, b: f32) -> f32 {
    if a + b == 0.0 {
        return u;
    }
    if u == 0.0 && a == 0.0 {
        return 0.0;
    }
    let x = u * (a + b) / (a + sqrt((1.0 - u) * a * a + u * b * b));
    return min(x, ONE_MINUS_EPSILON);
}

fn bilinear_lerp(t: f32, a: f32, b: f32) -> f32 {
    return (1.0 - t) * a + t * b;
}

fn bilinear_pdf(p: vec2f, w: vec4f) -> f32 {
    if !(p.x >= 0.0 && p.x <= 1.0 && p.y >= 0.0 && p.y <= 1.0) {
        return 0.0;
    }
    let sum = w.x + w.y + w.z + w.w;
    if sum == 0.0 {
        return 1.0;
    }
    return 4.0 * ((1.0 - p.x) * (1.0 - p.y) * w.x + p.x * (1.0 - p.y) * w.y + (1.0 - p.x) * p.y * w.z
        + p.x * p.y * w.w) / sum;
}

fn sample_bilinear(u: vec2f, w: vec4f) -> vec2f {
    if all(w == vec4f(0.0)) {
        return u;
    }
    let y = sample_linear(u.y, w.x + w.y, w.z + w.w);
    let x = sample_linear(u.x, bilinear_lerp(y, w.x, w.z), bilinear_lerp(y, w.y, w.w));
    return vec2f(x, y);
}

// `cosine_corner_weights`: max(MIN_COSINE_WEIGHT, |ns·normalize(d)|) for the vectors d to the
// four corner points.
fn cosine_corner_weights(ns: vec3f, d00: vec3f, d10: vec3f, d01: vec3f, d11: vec3f) -> vec4f {
    return max(
        vec4f(MIN_COSINE_WEIGHT),
        abs(vec4f(
            dot(ns, normalize_or_zero(d00)),
            dot(ns, normalize_or_zero(d10)),
            dot(ns, normalize_or_zero(d01)),
            dot(ns, normalize_or_zero(d11)),
        )),
    );
}
