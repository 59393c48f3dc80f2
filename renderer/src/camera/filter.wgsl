// The pixel filter, the twin of `camera/filter.rs`: camera samples are placed on the film with
// density ∝ |filter| (filter importance sampling). The box filter is the original jitter over the
// pixel, bit for bit; the gaussian (Mitsuba's windowed one) and the tent (Mitsuba's) draw each
// axis's offset from the filter restricted to the film, by inverting its CDF with Newton steps
// inside a bisection bracket: at most FILTER_MAX_STEPS, stopping at FILTER_TOLERANCE (the Rust
// constants, through the prelude). Lanczos and Mitchell have negative lobes: they are integrated
// piece by piece (8-point Gauss–Legendre, FILTER_GL_*) and their samples carry the weight
// sign f · A / S per axis (the Rust module's docs say why); their code is only in programs for a
// scene with such a filter (HAS_SIGNED_FILTER; without it their tags fail as unknown ones). The
// render kernel reads the filter from `Params` (`params_filter`; tags FILTER_*, written by the
// uniform's encoder, gpu/scene/params.rs).

// `PixelFilter`: its tag (FILTER_*), the gaussian's σ, the radius in pixels (the box ignores it),
// a Mitchell filter's B and C and its piece ends on [0, 2] (`breaks`, 8 in two vec4s).
struct PixelFilter {
    tag: u32,
    stddev: f32,
    radius: f32,
    b: f32,
    c: f32,
    breaks_lo: vec4f,
    breaks_hi: vec4f,
}

// Half-width of the support in pixels (`radius`).
fn filter_radius(f: PixelFilter) -> f32 {
    switch f.tag {
        case FILTER_BOX: {
            return 0.5;
        }
        case FILTER_GAUSSIAN: {
            return f.radius;
        }
        case FILTER_TENT: {
            return f.radius;
        }
// #if HAS_SIGNED_FILTER
        case FILTER_LANCZOS: {
            return f.radius;
        }
        case FILTER_MITCHELL: {
            return f.radius;
        }
// #endif
        default: {
            return unknown_tag();
        }
    }
}

// The 1-D weight at offset `x` from the pixel centre, unnormalised (`eval`).
fn filter_eval(f: PixelFilter, x: f32) -> f32 {
    switch f.tag {
        case FILTER_BOX: {
            return select(0.0, 1.0, abs(x) <= 0.5);
        }
        case FILTER_GAUSSIAN: {
            let k = -0.5 / (f.stddev * f.stddev);
            return max(exp(k * x * x) - exp(k * f.radius * f.radius), 0.0);
        }
        case FILTER_TENT: {
            return max(1.0 - abs(x) / f.radius, 0.0);
        }
// #if HAS_SIGNED_FILTER
        case FILTER_LANCZOS: {
            let ax = abs(x);
            if ax < F32_EPSILON {
                return 1.0;
            }
            if ax > f.radius {
                return 0.0;
            }
            let x1 = PI * ax;
            let x2 = x1 / f.radius;
            return (sin(x1) * sin(x2)) / (x1 * x2);
        }
        case FILTER_MITCHELL: {
            let ax = abs(x);
            if ax >= 2.0 {
                return 0.0;
            }
            return mitchell_cubic(f.b, f.c, ax);
        }
// #endif
        default: {
            return unknown_tag();
        }
    }
}

// #if HAS_SIGNED_FILTER
// Mitchell–Netravali's cubic at x in [0, 2), as Mitsuba's `mitchell.cpp` writes it
// (`mitchell_cubic`).
fn mitchell_cubic(b: f32, c: f32, x: f32) -> f32 {
    let x2 = x * x;
    let x3 = x * x * x;
    var v: f32;
    if x < 1.0 {
        v = (12.0 - 9.0 * b - 6.0 * c) * x3 + (-18.0 + 12.0 * b + 6.0 * c) * x2 + (6.0 - 2.0 * b);
    } else {
        v = (-b - 6.0 * c) * x3 + (6.0 * b + 30.0 * c) * x2 + (-12.0 * b - 48.0 * c) * x
            + (8.0 * b + 24.0 * c);
    }
    return v / 6.0;
}
// #endif

// ∫_{−r}^{x} eval, for x in [−r, r] (`integral`; box, gaussian and tent only: a signed filter is
// integrated by pieces, and its tag reaching here fails like an unknown one).
fn filter_integral(f: PixelFilter, x: f32) -> f32 {
    switch f.tag {
        case FILTER_BOX: {
            return x + 0.5;
        }
        case FILTER_GAUSSIAN: {
            // ∫ exp(−t²/2σ²) = σ√(π/2)·erf(t/(σ√2)); erf(b) − erf(a) = erfc(a) − erfc(b).
            let s = FRAC_1_SQRT_2 / f.stddev;
            let scale = f.stddev * SQRT_FRAC_PI_2;
            let window = exp(-0.5 * f.radius * f.radius / (f.stddev * f.stddev));
            return scale * (erfc(-f.radius * s) - erfc(x * s)) - window * (x + f.radius);
        }
        case FILTER_TENT: {
            let r = f.radius;
            if x <= 0.0 {
                return (x + r) * (x + r) / (2.0 * r);
            }
            return r - (r - x) * (r - x) / (2.0 * r);
        }
        default: {
            return unknown_tag();
        }
    }
}

// [lo, hi] ∩ [−r, r] (`clip`).
fn filter_clip(f: PixelFilter, lo: f32, hi: f32) -> vec2f {
    let r = filter_radius(f);
    return vec2f(max(lo, -r), min(hi, r));
}

// The 1-D CDF on [lo, hi] at x (`cdf_1d`): the inverse of `filter_sample_1d`.
fn filter_cdf_1d(f: PixelFilter, x: f32, lo: f32, hi: f32) -> f32 {
    let c = filter_clip(f, lo, hi);
    let xc = clamp(x, c.x, c.y);
// #if HAS_SIGNED_FILTER
    if filter_is_signed(f) {
        return clamp(filter_masses(f, c.x, xc).x / filter_masses(f, c.x, c.y).x, 0.0, 1.0);
    }
// #endif
    let base = filter_integral(f, c.x);
    return clamp((filter_integral(f, xc) - base) / (filter_integral(f, c.y) - base), 0.0, 1.0);
}

// An offset in [lo, hi] ∩ [−r, r] with density ∝ |filter| there, from a uniform u, and its weight
// (1 but for a signed filter): `sample_1d`, the same loop step for step.
fn filter_sample_1d(f: PixelFilter, u: f32, lo_in: f32, hi_in: f32) -> vec2f {
    let c = filter_clip(f, lo_in, hi_in);
    let lo = c.x;
    let hi = c.y;
    if f.tag == FILTER_BOX {
        return vec2f(clamp(lo + u * (hi - lo), lo, hi), 1.0);
    }
// #if HAS_SIGNED_FILTER
    if filter_is_signed(f) {
        return filter_sample_signed(f, u, lo, hi);
    }
// #endif
    let base = filter_integral(f, lo);
    let goal = u * (filter_integral(f, hi) - base);
    // Newton on F(x) = goal inside a bracket [a, b] that always holds the root; a step leaving the
    // bracket (or a flat spot) bisects instead.
    var a = lo;
    var b = hi;
    var x = lo + u * (hi - lo);
    for (var i = 0u; i < FILTER_MAX_STEPS; i++) {
        let g = filter_integral(f, x) - base - goal;
        if g < 0.0 {
            a = x;
        } else {
            b = x;
        }
        let fx = filter_eval(f, x);
        var next = x - g / fx;
        if !(fx > 0.0 && next > a && next < b) {
            next = 0.5 * (a + b);
        }
        let done = abs(next - x) <= FILTER_TOLERANCE * (1.0 + abs(x)) || b - a <= FILTER_TOLERANCE;
        x = next;
        if done {
            break;
        }
    }
    return vec2f(clamp(x, lo, hi), 1.0);
}

// #if HAS_SIGNED_FILTER
// Whether the filter has negative lobes (`is_signed`).
fn filter_is_signed(f: PixelFilter) -> bool {
    return f.tag == FILTER_LANCZOS || f.tag == FILTER_MITCHELL;
}

// A signed filter's pieces on each side of 0 (`half_pieces`).
fn filter_half_pieces(f: PixelFilter) -> u32 {
    if f.tag == FILTER_LANCZOS {
        return u32(f.radius);
    }
    return FILTER_MITCHELL_BREAKS;
}

// The end of piece k (1-based) on the positive side, 0 for k = 0 (`piece_end`).
fn filter_piece_end(f: PixelFilter, k: u32) -> f32 {
    if k == 0u {
        return 0.0;
    }
    if f.tag == FILTER_MITCHELL {
        let v = select(f.breaks_hi, f.breaks_lo, k - 1u < 4u);
        return v[(k - 1u) & 3u];
    }
    return f32(k);
}

// Piece i of 2 · half_pieces on [−r, r], left to right, cut to [lo, hi] (`piece`).
fn filter_piece(f: PixelFilter, i: u32, lo: f32, hi: f32) -> vec2f {
    let n = filter_half_pieces(f);
    var ab: vec2f;
    if i < n {
        ab = vec2f(-filter_piece_end(f, n - i), -filter_piece_end(f, n - i - 1u));
    } else {
        ab = vec2f(filter_piece_end(f, i - n), filter_piece_end(f, i - n + 1u));
    }
    return vec2f(max(ab.x, lo), min(ab.y, hi));
}

// ∫_a^b f by 8-point Gauss–Legendre inside one piece (`quadrature`).
fn filter_quadrature(f: PixelFilter, a: f32, b: f32) -> f32 {
    let m = 0.5 * (a + b);
    let h = 0.5 * (b - a);
    var s = 0.0;
    s += FILTER_GL_W0 * (filter_eval(f, m - h * FILTER_GL_X0) + filter_eval(f, m + h * FILTER_GL_X0));
    s += FILTER_GL_W1 * (filter_eval(f, m - h * FILTER_GL_X1) + filter_eval(f, m + h * FILTER_GL_X1));
    s += FILTER_GL_W2 * (filter_eval(f, m - h * FILTER_GL_X2) + filter_eval(f, m + h * FILTER_GL_X2));
    s += FILTER_GL_W3 * (filter_eval(f, m - h * FILTER_GL_X3) + filter_eval(f, m + h * FILTER_GL_X3));
    return s * h;
}

// (∫|f|, ∫f) over [lo, hi] inside [−r, r], piece by piece (`masses`).
fn filter_masses(f: PixelFilter, lo: f32, hi: f32) -> vec2f {
    var total = 0.0;
    var signed = 0.0;
    for (var i = 0u; i < 2u * filter_half_pieces(f); i++) {
        let ab = filter_piece(f, i, lo, hi);
        if ab.x < ab.y {
            let v = filter_quadrature(f, ab.x, ab.y);
            total += abs(v);
            signed += v;
        }
    }
    return vec2f(total, signed);
}

// `sample_1d` of a signed filter on [lo, hi] (already clipped): the piece holding u's share of
// ∫|f|, then Newton inside it (`sample_signed`); (offset, weight).
fn filter_sample_signed(f: PixelFilter, u: f32, lo: f32, hi: f32) -> vec2f {
    let m = filter_masses(f, lo, hi);
    let goal = u * m.x;
    let pieces = 2u * filter_half_pieces(f);
    // The last non-empty piece takes what rounding leaves past the others.
    var last = 0u;
    for (var i = 0u; i < pieces; i++) {
        let ab = filter_piece(f, i, lo, hi);
        if ab.x < ab.y && filter_quadrature(f, ab.x, ab.y) != 0.0 {
            last = i;
        }
    }
    var below = 0.0;
    for (var i = 0u; i < pieces; i++) {
        let ab = filter_piece(f, i, lo, hi);
        if !(ab.x < ab.y) {
            continue;
        }
        let v = filter_quadrature(f, ab.x, ab.y);
        if v == 0.0 {
            continue;
        }
        if below + abs(v) >= goal || i == last {
            let s = sign(v);
            let t = clamp(goal - below, 0.0, abs(v));
            let start = ab.x + (t / abs(v)) * (ab.y - ab.x);
            return vec2f(filter_invert_piece(f, s, t, ab.x, ab.y, start), s * m.x / m.y);
        }
        below += abs(v);
    }
    return vec2f(0.5 * (lo + hi), 0.0);
}

// The x in the piece [lo, hi] (sign s) where s·∫_lo^x f reaches t, from `start`: `invert` with
// `sample_signed`'s g. The loop is `filter_sample_1d`'s (WGSL has no closures to share it, and the
// unsigned filters' loop stays as it was, so their images keep their bits).
fn filter_invert_piece(f: PixelFilter, s: f32, t: f32, lo: f32, hi: f32, start: f32) -> f32 {
    var a = lo;
    var b = hi;
    var x = start;
    for (var i = 0u; i < FILTER_MAX_STEPS; i++) {
        let g = s * filter_quadrature(f, lo, x) - t;
        if g < 0.0 {
            a = x;
        } else {
            b = x;
        }
        let fx = abs(filter_eval(f, x));
        var next = x - g / fx;
        if !(fx > 0.0 && next > a && next < b) {
            next = 0.5 * (a + b);
        }
        let done = abs(next - x) <= FILTER_TOLERANCE * (1.0 + abs(x)) || b - a <= FILTER_TOLERANCE;
        x = next;
        if done {
            break;
        }
    }
    return clamp(x, lo, hi);
}
// #endif

// One axis of a film position: the pixel centre plus an offset on the film [0, n], and its weight.
fn filter_film_axis(f: PixelFilter, u: f32, p: u32, n: u32) -> vec2f {
    let c = f32(p) + 0.5;
    let s = filter_sample_1d(f, u, -c, f32(n) - c);
    return vec2f(c + s.x, s.y);
}

// Both axes: (x, y, the sample's weight).
fn filter_film_both(f: PixelFilter, u: vec2f, px: u32, py: u32, width: u32, height: u32) -> vec3f {
    let x = filter_film_axis(f, u.x, px, width);
    let y = filter_film_axis(f, u.y, py, height);
    return vec3f(x.x, y.x, x.y * y.y);
}

// The film position (pixels) of a camera sample of pixel (px, py) of a width × height film from
// the uniforms u, and the sample's weight (`film_sample`); the box gives (px + u.x, py + u.y, 1)
// exactly. The gaussian and the tent have a case each here and in `filter_radius` rather than one
// shared case: shared, lavapipe compiled the gaussian's path differently, and the GPU images of a
// gaussian-filtered scene (xml_meshes.xml) changed in their last bits.
fn film_position(f: PixelFilter, u: vec2f, px: u32, py: u32, width: u32, height: u32) -> vec3f {
    switch f.tag {
        case FILTER_BOX: {
            return vec3f(f32(px) + u.x, f32(py) + u.y, 1.0);
        }
        case FILTER_GAUSSIAN: {
            return filter_film_both(f, u, px, py, width, height);
        }
        case FILTER_TENT: {
            return filter_film_both(f, u, px, py, width, height);
        }
// #if HAS_SIGNED_FILTER
        case FILTER_LANCZOS: {
            return filter_film_both(f, u, px, py, width, height);
        }
        case FILTER_MITCHELL: {
            return filter_film_both(f, u, px, py, width, height);
        }
// #endif
        default: {
            return vec3f(unknown_tag());
        }
    }
}
