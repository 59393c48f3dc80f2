// The pixel filter, the twin of `camera/filter.rs`: camera samples are placed on the film with
// density ∝ the filter (filter importance sampling, every sample weight 1). The box filter is the
// original jitter over the pixel, bit for bit; the gaussian (Mitsuba's windowed one) and the tent
// (Mitsuba's) draw each
// axis's offset from the filter restricted to the film, by inverting its CDF with Newton steps
// inside a bisection bracket: at most FILTER_MAX_STEPS, stopping at FILTER_TOLERANCE (the Rust
// constants, through the prelude). The render kernel reads the filter from `Params`
// (`params_filter`; tags FILTER_*, written by the uniform's encoder, gpu/scene/params.rs).

// `PixelFilter`: its tag (FILTER_*) and the gaussian's σ and the gaussian's or tent's radius in
// pixels (the box ignores them, the tent σ).
struct PixelFilter {
    tag: u32,
    stddev: f32,
    radius: f32,
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
        default: {
            return unknown_tag();
        }
    }
}

// ∫_{−r}^{x} eval, for x in [−r, r] (`integral`).
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
    let base = filter_integral(f, c.x);
    return clamp((filter_integral(f, xc) - base) / (filter_integral(f, c.y) - base), 0.0, 1.0);
}

// An offset in [lo, hi] ∩ [−r, r] with density ∝ the filter there, from a uniform u
// (`sample_1d`, the same loop step for step).
fn filter_sample_1d(f: PixelFilter, u: f32, lo_in: f32, hi_in: f32) -> f32 {
    let c = filter_clip(f, lo_in, hi_in);
    let lo = c.x;
    let hi = c.y;
    if f.tag == FILTER_BOX {
        return clamp(lo + u * (hi - lo), lo, hi);
    }
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
    return clamp(x, lo, hi);
}

// One axis of a gaussian's film position: the pixel centre plus an offset on the film [0, n].
fn filter_film_axis(f: PixelFilter, u: f32, p: u32, n: u32) -> f32 {
    let c = f32(p) + 0.5;
    return c + filter_sample_1d(f, u, -c, f32(n) - c);
}

// The film position (pixels) of a camera sample of pixel (px, py) of a width × height film from
// the uniforms u (`film_position`); the box gives (px + u.x, py + u.y) exactly. The gaussian and
// the tent have a case each here and in `filter_radius` rather than one shared case: shared,
// lavapipe compiled the gaussian's path differently, and the GPU images of a gaussian-filtered
// scene (xml_meshes.xml) changed in their last bits.
fn film_position(f: PixelFilter, u: vec2f, px: u32, py: u32, width: u32, height: u32) -> vec2f {
    switch f.tag {
        case FILTER_BOX: {
            return vec2f(f32(px) + u.x, f32(py) + u.y);
        }
        case FILTER_GAUSSIAN: {
            return vec2f(filter_film_axis(f, u.x, px, width), filter_film_axis(f, u.y, py, height));
        }
        case FILTER_TENT: {
            return vec2f(filter_film_axis(f, u.x, px, width), filter_film_axis(f, u.y, py, height));
        }
        default: {
            return vec2f(unknown_tag());
        }
    }
}
