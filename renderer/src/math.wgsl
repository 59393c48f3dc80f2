// Shared math, the twin of `math.rs` (frames, safe functions, luminance) plus the f32 helpers WGSL
// lacks (infinity, finiteness tests, copysign, ulp steps, glam's normalisations).

// PI, INV_PI, TAU, FRAC_PI_2, FRAC_PI_4, NONE ("no light" / "no material", u32::MAX) and
// ONE_MINUS_EPSILON (the largest f32 below 1) come from the prelude (`gpu/prelude.rs`).

// WGSL rejects infinite constant expressions, so infinity comes from a private variable's bits,
// which the front end cannot fold.
var<private> INF_BITS: u32 = 0x7f800000u;

fn inf() -> f32 {
    return bitcast<f32>(INF_BITS);
}

// Bit tests, because WGSL has no isnan/isinf and drivers may fold `x != x`.
fn is_finite_f(x: f32) -> bool {
    return (bitcast<u32>(x) & 0x7f800000u) != 0x7f800000u;
}

fn is_finite3(v: vec3f) -> bool {
    return is_finite_f(v.x) && is_finite_f(v.y) && is_finite_f(v.z);
}

fn is_nan_f(x: f32) -> bool {
    let b = bitcast<u32>(x);
    return (b & 0x7f800000u) == 0x7f800000u && (b & 0x007fffffu) != 0u;
}

fn is_sign_negative(x: f32) -> bool {
    return (bitcast<u32>(x) & 0x80000000u) != 0u;
}

// Rust's `f32::copysign`: the magnitude of `mag` with the sign bit of `s` (also for ±0).
fn copysign(mag: f32, s: f32) -> f32 {
    return bitcast<f32>((bitcast<u32>(mag) & 0x7fffffffu) | (bitcast<u32>(s) & 0x80000000u));
}

fn safe_sqrt(x: f32) -> f32 {
    return sqrt(max(x, 0.0));
}

fn luminance(c: vec3f) -> f32 {
    return dot(c, vec3f(0.2126, 0.7152, 0.0722));
}

// `textures::luminance`: Mitsuba's coefficients, a grey value returned exactly (scalar texture
// slots and the principled's tints).
fn mitsuba_luminance(c: vec3f) -> f32 {
    if c.x == c.y && c.y == c.z {
        return c.x;
    }
    return c.x * LUMINANCE_R + c.y * LUMINANCE_G + c.z * LUMINANCE_B;
}

fn max_component(c: vec3f) -> f32 {
    return max(max(c.x, c.y), c.z);
}

// Mirror reflection of `w` about `n` (`math::reflect`).
fn reflect_about(w: vec3f, n: vec3f) -> vec3f {
    return 2.0 * dot(w, n) * n - w;
}

// #if HAS_REFRACTION
// Refraction of `w` through the interface with normal `n` and relative IOR `eta` (`math::refract`;
// from the other side of `n` it is seen with 1/η): the transmitted direction (xyz) and the
// relative IOR η_t/η_i used (w), or w = 0 under total internal reflection.
fn refract_through(w: vec3f, n_in: vec3f, eta_in: f32) -> vec4f {
    var cos_i = dot(n_in, w);
    var eta = eta_in;
    var n = n_in;
    if cos_i < 0.0 {
        eta = 1.0 / eta;
        cos_i = -cos_i;
        n = -n;
    }
    let sin2_i = max(1.0 - cos_i * cos_i, 0.0);
    let sin2_t = sin2_i / (eta * eta);
    if sin2_t >= 1.0 {
        return vec4f(0.0);
    }
    let cos_t = safe_sqrt(1.0 - sin2_t);
    return vec4f(-w / eta + (cos_i / eta - cos_t) * n, eta);
}
// #endif

// `geometry::ray::gamma`: n·ε/(1 − n·ε), ε = 2⁻²⁴.
fn gamma(n: f32) -> f32 {
    let e = 5.9604645e-8;
    return (n * e) / (1.0 - n * e);
}

// glam's `normalize`: multiply by the reciprocal length (not inverseSqrt), so results round like
// the CPU's.
fn normalize_glam(v: vec3f) -> vec3f {
    return v * (1.0 / length(v));
}

// glam's `normalize_or`: `fallback` when the reciprocal length is not finite and positive.
fn normalize_or(v: vec3f, fallback: vec3f) -> vec3f {
    let rcp = 1.0 / length(v);
    if is_finite_f(rcp) && rcp > 0.0 {
        return v * rcp;
    }
    return fallback;
}

fn normalize_or_zero(v: vec3f) -> vec3f {
    return normalize_or(v, vec3f(0.0));
}

// a = hi + lo exactly, each with at most 12 significant bits, so products of halves are exact
// in f32. The split masks the low 12 bits of the significand instead of Dekker's
// `c − (c − a)` with c = 4097·a, which Mesa's optimiser may fold (measured: inside the path
// tracer it returned hi = a, lo = 0).
fn split_f32(a: f32) -> vec2f {
    let hi = bitcast<f32>(bitcast<u32>(a) & 0xfffff000u);
    return vec2f(hi, a - hi);
}

// a·b = p + e exactly (Dekker's TwoProduct). Written without `fma`: Mesa's lavapipe evaluates
// `fma` unfused (measured: fma(a, b, −a·b) = 0), which would silently drop `e`; the split form
// is exact whether or not a driver fuses its products.
fn two_prod(a: f32, b: f32) -> vec2f {
    let p = a * b;
    let sa = split_f32(a);
    let sb = split_f32(b);
    let e = ((sa.x * sb.x - p) + sa.x * sb.y + sa.y * sb.x) + sa.y * sb.y;
    return vec2f(p, e);
}

// `a·b − c·d` to about an ulp (the CPU rounds the exact f64 result once): both products exactly,
// then the difference of their heads plus that of their tails.
fn difference_of_products(a: f32, b: f32, c: f32, d: f32) -> f32 {
    let ab = two_prod(a, b);
    let cd = two_prod(c, d);
    return (ab.x - cd.x) + (ab.y - cd.y);
}

// An orthonormal basis with `n` as z (`math::Frame`, Duff et al. 2017).
struct Frame {
    s: vec3f,
    t: vec3f,
    n: vec3f,
}

fn frame_from_normal(n: vec3f) -> Frame {
    let sign = copysign(1.0, n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    let s = vec3f(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    let t = vec3f(b, sign + n.y * n.y * a, -n.y);
    return Frame(s, t, n);
}

fn to_local(f: Frame, v: vec3f) -> vec3f {
    return vec3f(dot(v, f.s), dot(v, f.t), dot(v, f.n));
}

fn to_world(f: Frame, v: vec3f) -> vec3f {
    return f.s * v.x + f.t * v.y + f.n * v.z;
}

// atan on [0, ∞) to about 2 ulp (Cephes `atanf`: reduction by tan(π/8) and tan(3π/8), then a
// degree-9 odd polynomial). Vulkan allows the built-in atan/atan2 an error of 4096 ulp, and Mesa's
// lavapipe uses about that much (2e-5 relative, measured), which the solid-angle pdfs would
// inherit.
fn atan_pos(x_in: f32) -> f32 {
    var x = x_in;
    var y0 = 0.0;
    if x > 2.414213562373095 {
        y0 = FRAC_PI_2;
        x = -1.0 / x;
    } else if x > 0.4142135623730950 {
        y0 = FRAC_PI_4;
        x = (x - 1.0) / (x + 1.0);
    }
    let z = x * x;
    let p = (((8.05374449538e-2 * z - 1.38776856032e-1) * z + 1.99777106478e-1) * z - 3.33329491539e-1) * z;
    return y0 + (p * x + x);
}

// atan2 with the quadrants and signed zeros of Rust's `f32::atan2`, accurate like `atan_pos`.
fn atan2_precise(y: f32, x: f32) -> f32 {
    let ax = abs(x);
    let ay = abs(y);
    var t: f32;
    if ax == 0.0 && ay == 0.0 {
        t = 0.0;
    } else if ay <= ax {
        t = atan_pos(ay / ax);
    } else {
        t = FRAC_PI_2 - atan_pos(ax / ay);
    }
    if is_sign_negative(x) {
        t = PI - t;
    }
    return copysign(t, y);
}

// acos to a few ulp through `atan2_precise` (the built-in may be as loose as atan's 4096 ulp).
// 1 − x and 1 + x are exact where they matter (near ±1, Sterbenz), so the poles stay accurate.
fn acos_precise(x: f32) -> f32 {
    return atan2_precise(safe_sqrt((1.0 - x) * (1.0 + x)), x);
}
