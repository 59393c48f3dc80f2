//! Parity of `camera/filter.wgsl` with `camera/filter.rs` (issue 18): the WGSL `film_position`,
//! `filter_cdf_1d` and `erfc` against the CPU's on the same inputs, for several filters (Mitsuba's
//! default σ = 0.5, r = 2; a narrow one; a short window whose subtracted floor matters; radius 16
//! on films of 1–5 pixels, wider than the film; σ = r = 16, nearly flat) and pixels at every film
//! edge and corner, where the filter is cut at the border; and an unknown filter tag fails loudly.
//!
//! Runs on any wgpu adapter (lavapipe where there is no GPU); `LUMIS_SKIP_GPU_TESTS=1` skips.

use crate::gpu_common;
use gpu_common::parity::any_scene_gpu;
use gpu_common::*;
use lumis::camera::PixelFilter;
use lumis::camera::filter::TOLERANCE;
use lumis::erf::erfc;
use lumis::gpu::GpuScene;
use lumis::gpu::kernel::run_snippet;
use lumis::gpu::scene::FilterTag;
use lumis::integrator::Settings;
use lumis::rng::Rng;
use lumis::sampling::ONE_MINUS_EPSILON;

fn run(gpu: &GpuScene, body: &str, inputs: &[[f32; 4]], in_stride: usize) -> Vec<[f32; 4]> {
    run_snippet(gpu, &Settings::default(), body, inputs, in_stride, 1)
        .unwrap_or_else(|e| panic!("{e}"))
}

fn gaussian(stddev: f32, radius: f32) -> PixelFilter {
    PixelFilter::Gaussian { stddev, radius }
}

/// The filters compared, each with the films it is compared on.
fn cases() -> Vec<(PixelFilter, Vec<(u32, u32)>)> {
    let films = vec![(64, 48), (7, 5), (1, 1), (3, 2), (5, 1)];
    vec![
        (gaussian(0.5, 2.0), films.clone()),
        (gaussian(0.3, 1.2), films.clone()),
        (gaussian(1.0, 1.5), films.clone()),
        (gaussian(4.0, 16.0), films.clone()),
        (gaussian(16.0, 16.0), films.clone()),
        (PixelFilter::Tent { radius: 1.0 }, films.clone()),
        (PixelFilter::Tent { radius: 0.4 }, films.clone()),
        (PixelFilter::Tent { radius: 16.0 }, films),
        (PixelFilter::Box, vec![(64, 48), (1, 1)]),
    ]
}

/// The filter's WGSL value: its tag, σ and radius, as `GpuParams` carries them.
fn filter_vec(f: PixelFilter) -> [f32; 3] {
    let (tag, stddev, radius) = FilterTag::of(f);
    [f32::from_bits(tag.gpu_tag()), stddev, radius]
}

/// The pixels of a `w × h` film compared: every corner, the middle of every edge, and a few
/// inside (duplicates on tiny films are harmless).
fn pixels(w: u32, h: u32, r: &mut Rng) -> Vec<(u32, u32)> {
    let mut p = vec![
        (0, 0),
        (w - 1, 0),
        (0, h - 1),
        (w - 1, h - 1),
        (w / 2, 0),
        (w / 2, h - 1),
        (0, h / 2),
        (w - 1, h / 2),
        (1.min(w - 1), 1.min(h - 1)),
    ];
    for _ in 0..4 {
        p.push((
            (r.next_f32() * w as f32) as u32,
            (r.next_f32() * h as f32) as u32,
        ));
    }
    p
}

/// The uniforms: the extremes `rng_next_f32` gives (0 and 1 − 2⁻²⁴), ½, and random ones.
fn uniforms(r: &mut Rng) -> Vec<[f32; 2]> {
    let mut u = vec![
        [0.0, 0.0],
        [ONE_MINUS_EPSILON, ONE_MINUS_EPSILON],
        [0.0, ONE_MINUS_EPSILON],
        [0.5, 0.5],
    ];
    u.extend((0..60).map(|_| [r.next_f32(), r.next_f32()]));
    u
}

/// `M = 2σ√(π/2) + 2r·floor`, the largest magnitude of the terms of the filter's integral
/// (`floor = exp(−r²/2σ²)`, the window's subtracted value).
fn magnitude(f: PixelFilter) -> f32 {
    match f {
        PixelFilter::Box => 1.0,
        PixelFilter::Gaussian { stddev, radius } => {
            let floor = (-0.5 * radius * radius / (stddev * stddev)).exp();
            2.0 * stddev * std::f32::consts::FRAC_PI_2.sqrt() + 2.0 * radius * floor
        }
        // Its integral's terms reach the whole mass r.
        PixelFilter::Tent { radius } => radius,
        PixelFilter::Lanczos { .. } | PixelFilter::Mitchell { .. } => unreachable!("unsigned only"),
    }
}

/// The filter's mass on `[a, b] ⊂ [−r, r]`, unnormalised (as `integral(b) − integral(a)`).
fn mass(f: PixelFilter, a: f32, b: f32) -> f32 {
    match f {
        PixelFilter::Box => b - a,
        PixelFilter::Gaussian { stddev, radius } => {
            let s = std::f32::consts::FRAC_1_SQRT_2 / stddev;
            let scale = stddev * std::f32::consts::FRAC_PI_2.sqrt();
            let floor = (-0.5 * radius * radius / (stddev * stddev)).exp();
            scale * (erfc(a * s) - erfc(b * s)) - floor * (b - a)
        }
        PixelFilter::Tent { radius } => {
            let up = |x: f32| {
                if x <= 0.0 {
                    (x + radius) * (x + radius) / (2.0 * radius)
                } else {
                    radius - (radius - x) * (radius - x) / (2.0 * radius)
                }
            };
            up(b) - up(a)
        }
        PixelFilter::Lanczos { .. } | PixelFilter::Mitchell { .. } => unreachable!("unsigned only"),
    }
}

/// The tolerance of one film coordinate, per axis: `|gpu − cpu| ≤ 4 ulp of the position + 4 ×
/// TOLERANCE·(1 + |offset|) + 64 ε·M / f(offset)` (capped at the axis's interval). Why: both
/// sides run the same loop on the same CDF, but a GPU's `exp` and division are not correctly
/// rounded (Vulkan allows a few ulp), so F(x) differs by a few ulp of its terms' magnitude
/// `M = 2σ√(π/2) + 2r·floor`; the root then moves by that over the density f at the root (64 ε·M
/// / f bounds it with room for the ulp counts Vulkan allows), and each side stops within its
/// stopping tolerance of the root, possibly one step apart. The box filter's is exact (one
/// addition of the same floats): its position must be bit-identical.
fn position_tolerance(f: PixelFilter, offset: f32, lo: f32, hi: f32, p: f32) -> f32 {
    let radius = match f {
        PixelFilter::Gaussian { radius, .. } | PixelFilter::Tent { radius } => radius,
        PixelFilter::Box => return 0.0,
        PixelFilter::Lanczos { .. } | PixelFilter::Mitchell { .. } => unreachable!("unsigned only"),
    };
    let m = magnitude(f);
    let density = f.eval(offset).max(1e-30);
    let conditioned = (64.0 * f32::EPSILON * m / density).min(hi.min(radius) - lo.max(-radius));
    4.0 * f32::EPSILON * p.abs() + 4.0 * TOLERANCE * (1.0 + offset.abs()) + conditioned
}

/// `film_position` of many (u, pixel) pairs per filter and film, incl. every edge and corner
/// pixel. Catches any difference in the sampler beyond rounding: a wrong interval (the film's
/// truncation ignored: positions off the film at every edge pixel), a changed erfc coefficient,
/// window or stopping rule. Deliberate bug tried: `filter_film_axis` sampling `[−r, r]` instead
/// of the film's interval: failed at the first corner (pixel (0, 0) of 64×48, u = 0: x = −1.5,
/// off the film).
#[test]
fn film_positions_match_the_cpu_at_every_edge_and_corner() {
    let Some(gpu) = any_scene_gpu() else {
        return;
    };
    let mut r = Rng::new(18, 0, 0);
    let mut inputs = Vec::new();
    let mut want = Vec::new();
    for (f, films) in cases() {
        let [tag, stddev, radius] = filter_vec(f);
        for (w, h) in films {
            for (px, py) in pixels(w, h, &mut r) {
                for u in uniforms(&mut r) {
                    inputs.push([tag, stddev, radius, u[0]]);
                    let bits = |v: u32| f32::from_bits(v);
                    inputs.push([u[1], bits(px), bits(py), 0.0]);
                    inputs.push([bits(w), bits(h), 0.0, 0.0]);
                    want.push((f, u, px, py, w, h));
                }
            }
        }
    }
    let out = run(
        &gpu,
        "let a = inp(0u); let b = inp(1u); let c = bitcast<vec4<u32>>(inp(2u));
         let f = PixelFilter(bitcast<u32>(a.x), a.y, a.z, 0.0, 0.0, vec4f(0.0), vec4f(0.0));
         let p = film_position(f, vec2f(a.w, b.x), bitcast<u32>(b.y), bitcast<u32>(b.z), c.x, c.y);
         outp(0u, vec4f(p.xy, select(0.0, 1.0, unknown_tag_seen), p.z));",
        &inputs,
        3,
    );
    let mut c = Compare::new("film_position", 0.0, 0.0);
    let mut worst = 0.0f32;
    for (o, &(f, u, px, py, w, h)) in out.iter().zip(&want) {
        assert_eq!(o[2], 0.0, "{f:?}: unknown tag flagged");
        assert_eq!(o[3], 1.0, "{f:?}: an unsigned filter's sample weight");
        let p = f.film_position(glam::Vec2::from(u), px, py, w, h);
        for (axis, (got, want, q, n)) in [(o[0], p.x, px, w), (o[1], p.y, py, h)]
            .into_iter()
            .enumerate()
        {
            let centre = q as f32 + 0.5;
            let (lo, hi) = (-centre, n as f32 - centre);
            let tol = position_tolerance(f, want - centre, lo, hi, want);
            let what = format!("{f:?} film {w}x{h} pixel ({px},{py}) u {u:?} axis {axis}");
            c.scalar_conditioned(got, want, tol, &what);
            worst = worst.max((got - want).abs() / tol.max(f32::MIN_POSITIVE));
            // On the film, whatever the rounding.
            assert!(
                (0.0..=n as f32).contains(&got),
                "{what}: {got} off the film"
            );
        }
    }
    eprintln!("film_position: worst |gpu − cpu| / tolerance {worst:.3e}");
    c.finish(0);
}

/// `filter_cdf_1d` at random x on the intervals of edge pixels, and `erfc` on [−6, 6]. Their
/// tolerances: the CDF is a ratio of differences of erfc values of magnitude ≤ M (see
/// [`position_tolerance`]), so 64 ε·M over the interval's mass; erfc's is 64 ε relative plus
/// 1e-9 absolute (GPU `exp` far in its tail, erfc(6) ≈ 2e-17). Catches a changed coefficient or
/// window (`erfc_matches_known_values` and the CPU's own tests then tell which side is wrong).
/// Deliberate bug tried: the WGSL erfc's coefficient 0.27886807 as 0.2789: 889 of 6000 CDF
/// values failed (worst 1.6e-3 for σ = r = 16).
#[test]
fn cdf_and_erfc_match_the_cpu() {
    let Some(gpu) = any_scene_gpu() else {
        return;
    };
    let mut r = Rng::new(18, 1, 0);
    let mut inputs = Vec::new();
    let mut want = Vec::new();
    for (f, _) in cases() {
        let [tag, stddev, radius] = filter_vec(f);
        let rad = f.radius();
        for (lo, hi) in [
            (-rad, rad),
            (-0.5, 100.0),
            (-1.5, rad),
            (-0.5, 0.5),
            (-3.5, 1.5),
        ] {
            for _ in 0..200 {
                let x = lo.max(-rad) + r.next_f32() * (hi.min(rad) - lo.max(-rad));
                let e = 12.0 * r.next_f32() - 6.0;
                inputs.push([tag, stddev, radius, x]);
                inputs.push([lo, hi, e, 0.0]);
                want.push((f, x, lo, hi, e));
            }
        }
    }
    let out = run(
        &gpu,
        "let a = inp(0u); let b = inp(1u);
         let f = PixelFilter(bitcast<u32>(a.x), a.y, a.z, 0.0, 0.0, vec4f(0.0), vec4f(0.0));
         outp(0u, vec4f(filter_cdf_1d(f, a.w, b.x, b.y), erfc(b.z), 0.0, 0.0));",
        &inputs,
        2,
    );
    let mut cdf = Compare::new("filter_cdf_1d", 0.0, 0.0);
    let mut erf = Compare::new("erfc", 64.0 * f32::EPSILON, 1e-9);
    for (o, &(f, x, lo, hi, e)) in out.iter().zip(&want) {
        let what = format!("{f:?} x {x} on [{lo}, {hi}]");
        let rad = f.radius();
        let interval = mass(f, lo.max(-rad), hi.min(rad)).max(1e-30);
        let tol = 64.0 * f32::EPSILON * magnitude(f) / interval;
        cdf.scalar_conditioned(o[0], f.cdf_1d(x, lo, hi), tol, &what);
        erf.scalar(o[1], erfc(e), &format!("erfc({e})"));
    }
    cdf.finish(0);
    erf.finish(0);
}

/// The signed filters (Lanczos with 3, 2 and 16 lobes; Mitchell at the reference scene's B, C,
/// Mitsuba's default and Catmull–Rom): `film_position`'s positions and sample weights against
/// the CPU's `film_sample` on the films and pixels of [`cases`]. Tolerances: a position as
/// [`position_tolerance`]'s, with `M = 2r` (|f| ≤ 1 on `[−r, r]`, and the GPU's `sin` is not
/// correctly rounded either); a weight `A / S` within 1e-5 relative (both sides sum the same
/// Gauss–Legendre terms), of the CPU's sign wherever |f| at the position exceeds 1e-3. Catches a
/// different piece walk, quadrature node, Mitchell coefficient or weight. Deliberate bug tried:
/// the WGSL weight `m.x / m.y` without its sign: failed (see the closing note).
#[test]
fn signed_film_samples_match_the_cpu() {
    let Some(gpu) = any_scene_gpu() else {
        return;
    };
    let mut r = Rng::new(18, 2, 0);
    let films = [(64u32, 48u32), (7, 5), (1, 1), (3, 2), (5, 1)];
    let filters = [
        PixelFilter::Lanczos { lobes: 3 },
        PixelFilter::Lanczos { lobes: 2 },
        PixelFilter::Lanczos { lobes: 16 },
        PixelFilter::mitchell(0.4, 0.3),
        PixelFilter::mitchell(1.0 / 3.0, 1.0 / 3.0),
        PixelFilter::mitchell(0.0, 0.5),
    ];
    let mut inputs = Vec::new();
    let mut want = Vec::new();
    for f in filters {
        let [tag, stddev, radius] = filter_vec(f);
        let (shape, breaks) = FilterTag::shape(f);
        for (w, h) in films {
            for (px, py) in pixels(w, h, &mut r) {
                for u in uniforms(&mut r).into_iter().take(24) {
                    let bits = |v: u32| f32::from_bits(v);
                    inputs.push([tag, stddev, radius, u[0]]);
                    inputs.push([u[1], bits(px), bits(py), 0.0]);
                    inputs.push([bits(w), bits(h), 0.0, 0.0]);
                    inputs.push(shape);
                    inputs.push(breaks[0]);
                    inputs.push(breaks[1]);
                    want.push((f, u, px, py, w, h));
                }
            }
        }
    }
    let out = run(
        &gpu,
        "let a = inp(0u); let b = inp(1u); let c = bitcast<vec4<u32>>(inp(2u)); let s = inp(3u);
         let f = PixelFilter(bitcast<u32>(a.x), a.y, a.z, s.x, s.y, inp(4u), inp(5u));
         let p = film_position(f, vec2f(a.w, b.x), bitcast<u32>(b.y), bitcast<u32>(b.z), c.x, c.y);
         outp(0u, vec4f(p, select(0.0, 1.0, unknown_tag_seen)));",
        &inputs,
        6,
    );
    let mut c = Compare::new("signed film_position", 0.0, 0.0);
    let mut weights = Compare::new("signed sample weight", 1e-5, 0.0);
    for (o, &(f, u, px, py, w, h)) in out.iter().zip(&want) {
        assert_eq!(o[3], 0.0, "{f:?}: unknown tag flagged");
        let (p, weight) = f.film_sample(glam::Vec2::from(u), px, py, w, h);
        let what = format!("{f:?} film {w}x{h} pixel ({px},{py}) u {u:?}");
        let mut tiny = false;
        for (axis, (got, want, q, n)) in [(o[0], p.x, px, w), (o[1], p.y, py, h)]
            .into_iter()
            .enumerate()
        {
            let centre = q as f32 + 0.5;
            let (lo, hi) = (-centre, n as f32 - centre);
            let r = f.radius();
            let offset = want - centre;
            let density = f.eval(offset).abs().max(1e-30);
            tiny |= density < 1e-3;
            let conditioned = (64.0 * f32::EPSILON * 2.0 * r / density).min(hi.min(r) - lo.max(-r));
            let tol = 4.0 * f32::EPSILON * want.abs()
                + 4.0 * TOLERANCE * (1.0 + offset.abs())
                + conditioned;
            c.scalar_conditioned(got, want, tol, &format!("{what} axis {axis}"));
            assert!(
                (0.0..=n as f32).contains(&got),
                "{what}: {got} off the film"
            );
        }
        if tiny {
            weights.scalar(o[2].abs(), weight.abs(), &what);
        } else {
            weights.scalar(o[2], weight, &what);
        }
    }
    c.finish(0);
    weights.finish(0);
}

/// A filter tag `camera/filter.wgsl` does not know flags the sample (NaN position, `unknown_tag_seen`),
/// like every other tag `switch`. Deliberate bug tried: `film_position`'s default case returning
/// the box's position: failed (a finite position, no flag).
#[test]
fn an_unknown_filter_tag_fails_loudly() {
    let Some(gpu) = any_scene_gpu() else {
        return;
    };
    let unknown = FilterTag::ALL.len() as u32;
    let out = run(
        &gpu,
        "let a = inp(0u);
         let f = PixelFilter(bitcast<u32>(a.x), 0.5, 2.0, 0.0, 0.0, vec4f(0.0), vec4f(0.0));
         let p = film_position(f, vec2f(0.5), 3u, 3u, 8u, 8u);
         outp(0u, vec4f(p.xy, select(0.0, 1.0, unknown_tag_seen), 0.0));",
        &[[f32::from_bits(unknown), 0.0, 0.0, 0.0]],
        1,
    );
    assert!(out[0][0].is_nan() && out[0][1].is_nan(), "{:?}", out[0]);
    assert_eq!(out[0][2], 1.0, "the unknown tag was not flagged");
}
