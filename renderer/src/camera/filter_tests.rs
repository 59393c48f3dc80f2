//! Tests of the pixel filter: Mitsuba's weight, the sampler against its CDF and pdf, a χ² test of
//! sampled film positions against the filter, and the signed filters' pieces and sample weights.

use super::*;
use crate::rng::Rng;
use crate::stats::gamma::{chi2_sf, sidak};

const MITSUBA: PixelFilter = PixelFilter::Gaussian {
    stddev: 0.5,
    radius: 2.0,
};

/// Filters the tests cover: Mitsuba's default, a narrow one, and a short window (r = 1.5σ) where
/// the subtracted floor exp(−r²/2σ²) ≈ 0.32 matters.
const FILTERS: [PixelFilter; 3] = [
    MITSUBA,
    PixelFilter::Gaussian {
        stddev: 0.3,
        radius: 1.2,
    },
    PixelFilter::Gaussian {
        stddev: 1.0,
        radius: 1.5,
    },
];

/// Tents: Mitsuba's default radius, one narrower than a pixel, and one as wide as the widest
/// filter the scene format takes.
const TENTS: [PixelFilter; 3] = [
    PixelFilter::Tent { radius: 1.0 },
    PixelFilter::Tent { radius: 0.4 },
    PixelFilter::Tent { radius: 16.0 },
];

/// Filters with negative lobes: Mitsuba's default Lanczos (3 lobes), a 2-lobe one, the Mitchell
/// filter at the B, C of tests/data/mitsuba/mitchell_edges.xml, Mitsuba's default (⅓, ⅓) and
/// Catmull–Rom (0, ½).
fn signed_filters() -> [PixelFilter; 5] {
    [
        PixelFilter::Lanczos { lobes: 3 },
        PixelFilter::Lanczos { lobes: 2 },
        PixelFilter::mitchell(0.4, 0.3),
        PixelFilter::mitchell(1.0 / 3.0, 1.0 / 3.0),
        PixelFilter::mitchell(0.0, 0.5),
    ]
}

/// Mitsuba's `lanczos.cpp` and `mitchell.cpp` at hand-computed points: Lanczos(3) at ½ is
/// sinc(½)·sinc(⅙) = (2/π)(3/π); Mitchell(⅓, ⅓) is 8/9 at 0, 1/18 at 1, 0 at 8/7 (a root of
/// its outer cubic, (x − 2)(−7x² + 22x − 16)/18) and negative between 8/7 and 2; Catmull–Rom is
/// 1 at 0 and 0 at 1.
#[test]
fn signed_weights_are_mitsubas() {
    let pi = std::f64::consts::PI;
    let l3 = PixelFilter::Lanczos { lobes: 3 };
    for (x, want) in [
        (0.0f32, 1.0f64),
        (0.5, 6.0 / (pi * pi)),
        (-0.5, 6.0 / (pi * pi)),
    ] {
        assert!(
            (l3.eval(x) as f64 - want).abs() < 1e-6,
            "lanczos({x}) = {}",
            l3.eval(x)
        );
    }
    // sinc(1.5)·sinc(0.5) = (−2/3π)(2/π) < 0; 0 at integers and beyond the radius.
    assert!((l3.eval(1.5) as f64 + 4.0 / (3.0 * pi * pi)).abs() < 1e-6);
    assert!(l3.eval(1.0).abs() < 1e-6 && l3.eval(3.5) == 0.0);
    assert_eq!(l3.radius(), 3.0);
    let m = PixelFilter::mitchell(1.0 / 3.0, 1.0 / 3.0);
    for (x, want) in [
        (0.0f32, 8.0 / 9.0),
        (1.0, 1.0 / 18.0),
        (8.0 / 7.0, 0.0),
        (2.0, 0.0),
    ] {
        assert!(
            (m.eval(x) as f64 - want).abs() < 1e-6,
            "mitchell({x}) = {}",
            m.eval(x)
        );
    }
    assert!(m.eval(1.5) < 0.0 && m.eval(-1.5) == m.eval(1.5));
    assert_eq!(m.radius(), 2.0);
    let cr = PixelFilter::mitchell(0.0, 0.5);
    assert!((cr.eval(0.0) - 1.0).abs() < 1e-7 && cr.eval(1.0).abs() < 1e-7);
}

/// A Mitchell filter's pieces end at 1, 2 and its cubics' sign changes: (⅓, ⅓) at 8/7,
/// Catmull–Rom at none but 1 and 2 (its roots there are ends already); and for any B, C (here
/// a grid with unusual ones, whose inner cubic also changes sign) the filter keeps one sign on
/// each piece, which is what integrating |f| piece by piece needs.
#[test]
fn mitchell_pieces_keep_one_sign() {
    let PixelFilter::Mitchell { breaks, .. } = PixelFilter::mitchell(1.0 / 3.0, 1.0 / 3.0) else {
        unreachable!()
    };
    assert!((breaks[0] - 1.0).abs() < 1e-7 && (breaks[1] - 8.0 / 7.0).abs() < 1e-6);
    assert!(breaks[2..].iter().all(|&b| b == 2.0), "{breaks:?}");
    let PixelFilter::Mitchell { breaks, .. } = PixelFilter::mitchell(0.0, 0.5) else {
        unreachable!()
    };
    assert_eq!(breaks[0], 1.0);
    assert!(breaks[1..].iter().all(|&b| b == 2.0), "{breaks:?}");
    let mut inner_changes = 0;
    for b in [-1.0f32, -0.3, 0.0, 0.5, 1.0, 2.0, 4.0] {
        for c in [-1.0f32, -0.2, 0.0, 0.5, 1.0, 3.0] {
            let f = PixelFilter::mitchell(b, c);
            let PixelFilter::Mitchell { breaks, .. } = f else {
                unreachable!()
            };
            let mut start = 0.0f32;
            for end in breaks {
                let signs: Vec<f32> = (1..200)
                    .map(|i| f.eval(start + (end - start) * i as f32 / 200.0))
                    .filter(|v| v.abs() > 1e-5)
                    .map(f32::signum)
                    .collect();
                assert!(
                    signs.windows(2).all(|w| w[0] == w[1]),
                    "B {b} C {c}: piece [{start}, {end}] changes sign"
                );
                if end < 1.0 {
                    inner_changes += 1;
                }
                start = end;
            }
        }
    }
    assert!(
        inner_changes > 0,
        "no B, C of the grid makes the inner cubic change sign"
    );
}

/// A signed filter's sample weight is `sign f(x) · A / S` on its interval, `A = ∫|f|` and
/// `S = ∫f` there, computed here independently (midpoint rule in f64, 200,000 points): the
/// magnitude within 1e-4, the sign f's wherever |f| is not tiny.
#[test]
fn signed_weights_are_sign_times_mass_ratio() {
    let mut rng = Rng::new(2423, 0, 0);
    for f in signed_filters() {
        for (lo, hi) in intervals(&f) {
            let (a, b) = (lo.max(-f.radius()), hi.min(f.radius()));
            let n = 200_000;
            let h = (b - a) as f64 / n as f64;
            let (mut abs, mut signed) = (0.0, 0.0);
            for i in 0..n {
                let v = f.eval((a as f64 + (i as f64 + 0.5) * h) as f32) as f64 * h;
                abs += v.abs();
                signed += v;
            }
            for _ in 0..500 {
                let (x, w) = f.sample_1d(rng.next_f32(), lo, hi);
                assert!(
                    ((w.abs() as f64) - abs / signed).abs() < 1e-4 * abs / signed,
                    "{f:?} [{lo}, {hi}]: |w| = {w}, A/S = {}",
                    abs / signed
                );
                let fx = f.eval(x);
                if fx.abs() > 1e-3 {
                    assert_eq!(w.signum(), fx.signum(), "{f:?} at {x}: w {w}, f {fx}");
                }
            }
        }
    }
}

/// A filter whose integral over some pixel's part of the film is not positive is refused:
/// Mitchell with B = 10 (∫ over an edge pixel's [−½, 2] is −0.16); with C = −20 only a 1-pixel
/// film is (∫ over [−½, ½] is −0.23, over [−½, 2] +0.39). The filters of the tests pass on a
/// 1-pixel film and a large one.
#[test]
fn check_film_refuses_a_non_positive_pixel_integral() {
    assert!(PixelFilter::mitchell(10.0, 0.0).check_film(8, 8).is_err());
    assert!(PixelFilter::mitchell(0.0, -20.0).check_film(1, 1).is_err());
    assert_eq!(PixelFilter::mitchell(0.0, -20.0).check_film(8, 8), Ok(()));
    for f in signed_filters() {
        assert_eq!(f.check_film(1, 1), Ok(()), "{f:?}");
        assert_eq!(f.check_film(64, 48), Ok(()), "{f:?}");
    }
}

/// Mitsuba's `tent.cpp`: `max(0, 1 − |x|/r)`.
#[test]
fn tent_weight_is_mitsubas() {
    let t = PixelFilter::Tent { radius: 1.5 };
    for (x, want) in [
        (0.0f32, 1.0f32),
        (0.75, 0.5),
        (-0.75, 0.5),
        (1.5, 0.0),
        (-2.0, 0.0),
    ] {
        assert!((t.eval(x) - want).abs() < 1e-7, "f({x}) = {}", t.eval(x));
    }
    assert_eq!(t.radius(), 1.5);
}

#[test]
fn gaussian_weight_is_mitsubas() {
    // Mitsuba: exp(−x²/(2σ²)) − exp(−r²/(2σ²)), clamped at 0; r = 4σ.
    let floor = (-8.0f64).exp();
    for x in [0.0f32, 0.3, -0.7, 1.0, 1.9, 2.0, 2.5, -3.0] {
        let want = ((-(x as f64).powi(2) / 0.5).exp() - floor).max(0.0);
        let got = MITSUBA.eval(x) as f64;
        assert!((got - want).abs() < 1e-7, "f({x}) = {got}, want {want}");
    }
    assert_eq!(MITSUBA.radius(), 2.0);
    assert_eq!(PixelFilter::Box.eval(0.49), 1.0);
    assert_eq!(PixelFilter::Box.eval(0.51), 0.0);
}

/// Intervals `[lo, hi]` a pixel's offset can be restricted to: the whole support, a pixel at
/// the film's left edge (centre 0.5), one pixel further in, and a 1-pixel-wide film.
fn intervals(f: &PixelFilter) -> Vec<(f32, f32)> {
    let r = f.radius();
    vec![
        (-r, r),
        (-0.5, 100.0),
        (-1.5, r),
        (-0.5, 0.5),
        (-100.0, 1.5),
    ]
}

#[test]
fn sample_inverts_the_cdf_and_stays_inside() {
    let mut rng = Rng::new(91, 0, 0);
    let signed = signed_filters();
    for f in FILTERS
        .iter()
        .chain(&TENTS)
        .chain(&signed)
        .chain([&PixelFilter::Box])
    {
        for (lo, hi) in intervals(f) {
            for i in 0..2000 {
                let u = if i < 3 {
                    [0.0, 0.5, 0.999_999_9][i]
                } else {
                    rng.next_f32()
                };
                let (x, w) = f.sample_1d(u, lo, hi);
                assert!(f.is_signed() || w == 1.0, "{f:?}: weight {w}");
                let r = f.radius();
                assert!(
                    x >= lo.max(-r) && x <= hi.min(r),
                    "{f:?} [{lo}, {hi}] u {u}: {x}"
                );
                let back = f.cdf_1d(x, lo, hi);
                assert!(
                    (back - u).abs() < 2e-5,
                    "{f:?} [{lo}, {hi}]: cdf(sample({u})) = {back}"
                );
            }
        }
    }
}

#[test]
fn pdf_is_the_cdfs_derivative_and_integrates_to_one() {
    let signed = signed_filters();
    for f in FILTERS.iter().chain(&TENTS).chain(&signed) {
        for (lo, hi) in intervals(f) {
            let (a, b) = (lo.max(-f.radius()), hi.min(f.radius()));
            // Midpoint rule in f64 on the f32 pdf.
            let n = 20_000;
            let h = (b - a) as f64 / n as f64;
            let total: f64 = (0..n)
                .map(|i| f.pdf_1d((a as f64 + (i as f64 + 0.5) * h) as f32, lo, hi) as f64 * h)
                .sum();
            assert!(
                (total - 1.0).abs() < 1e-4,
                "{f:?} [{lo}, {hi}]: ∫pdf = {total}"
            );
            // Odd eighths: never the tent's kink at 0, where the difference quotient is not the pdf.
            for k in [1, 3, 5, 7] {
                let x = a + (b - a) * k as f32 / 8.0;
                let d = 1e-2;
                let slope = (f.cdf_1d(x + d, lo, hi) - f.cdf_1d(x - d, lo, hi)) / (2.0 * d);
                let p = f.pdf_1d(x, lo, hi);
                assert!(
                    (slope - p).abs() < 2e-3 * (1.0 + p),
                    "{f:?} at {x}: {slope} vs {p}"
                );
            }
        }
    }
}

#[test]
fn box_filter_is_the_original_jitter() {
    let mut rng = Rng::new(3, 0, 0);
    for _ in 0..100 {
        let u = rng.next_2d();
        let p = PixelFilter::Box.film_position(u, 7, 0, 16, 1);
        assert_eq!(p, Vec2::new(7.0 + u.x, u.y));
    }
}

/// χ² of `n` film positions of pixel `(px, py)` on a `w × h` film, drawn by `draw` from seeded
/// uniforms, against `filter`'s |weight| restricted to the film (normalised by quadrature, not by
/// the sampler's own CDF), over a 24 × 24 grid on the pixel's support. Returns the p-value.
fn chi2_p(
    filter: &PixelFilter,
    draw: &dyn Fn(Vec2) -> Vec2,
    (px, py, w, h): (u32, u32, u32, u32),
    n: usize,
    seed: u32,
) -> f64 {
    const CELLS: usize = 24;
    let r = filter.radius();
    let (cx, cy) = (px as f32 + 0.5, py as f32 + 0.5);
    let x0 = (cx - r).max(0.0);
    let x1 = (cx + r).min(w as f32);
    let y0 = (cy - r).max(0.0);
    let y1 = (cy + r).min(h as f32);
    // Expected mass per cell: the separable weight integrated per axis (midpoint rule, 64 points
    // per cell), normalised over the film part of the support.
    let axis = |a: f32, b: f32, c: f32| -> Vec<f64> {
        let m: Vec<f64> = (0..CELLS)
            .map(|i| {
                let (s, e) = (
                    a as f64 + (b - a) as f64 * i as f64 / CELLS as f64,
                    a as f64 + (b - a) as f64 * (i + 1) as f64 / CELLS as f64,
                );
                (0..64)
                    .map(|k| {
                        filter
                            .eval((s + (e - s) * (k as f64 + 0.5) / 64.0 - c as f64) as f32)
                            .abs() as f64
                    })
                    .sum::<f64>()
                    * (e - s)
                    / 64.0
            })
            .collect();
        let t: f64 = m.iter().sum();
        m.into_iter().map(|v| v / t).collect()
    };
    let (ex, ey) = (axis(x0, x1, cx), axis(y0, y1, cy));
    let mut counts = vec![0f64; CELLS * CELLS];
    let mut rng = Rng::new(seed, 0, 0);
    for _ in 0..n {
        let p = draw(rng.next_2d());
        assert!(
            p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1,
            "{p} outside the support"
        );
        let i = (((p.x - x0) / (x1 - x0) * CELLS as f32) as usize).min(CELLS - 1);
        let j = (((p.y - y0) / (y1 - y0) * CELLS as f32) as usize).min(CELLS - 1);
        counts[j * CELLS + i] += 1.0;
    }
    // Pearson's statistic; cells expecting fewer than 5 samples are pooled into one.
    let (mut stat, mut dof, mut pool_o, mut pool_e) = (0.0, 0usize, 0.0, 0.0);
    for j in 0..CELLS {
        for i in 0..CELLS {
            let e = ex[i] * ey[j] * n as f64;
            let o = counts[j * CELLS + i];
            if e < 5.0 {
                pool_o += o;
                pool_e += e;
            } else {
                stat += (o - e).powi(2) / e;
                dof += 1;
            }
        }
    }
    if pool_e > 0.0 {
        stat += (pool_o - pool_e).powi(2) / pool_e;
        dof += 1;
    }
    chi2_sf(stat, (dof - 1) as f64)
}

/// [`chi2_p`] of `n` positions for each of `filters` at four pixels of a 10 × 8 film (interior,
/// left edge, one pixel in from the top, bottom-right corner), case `k` at seed `seed + k`, each
/// held to the family-wise α = 0.01 over all cases (Šidák).
fn assert_film_positions_pass(filters: &[PixelFilter], n: usize, seed: u32) {
    let pixels = [(5, 4), (0, 4), (5, 1), (9, 7)];
    let alpha = sidak(0.01, filters.len() * pixels.len());
    let mut case = 0;
    for f in filters {
        for &(px, py) in &pixels {
            let draw = |u: Vec2| f.film_position(u, px, py, 10, 8);
            let p = chi2_p(f, &draw, (px, py, 10, 8), n, seed + case);
            assert!(
                p >= alpha,
                "{f:?} pixel ({px}, {py}): χ² p = {p:.3e} < {alpha:.2e}"
            );
            case += 1;
        }
    }
}

/// The sampled film positions have the filter's density, inside the film and at its edges and
/// corner (truncated and renormalised, as Mitsuba's `sample_border = false` film weights).
/// Significance: family-wise α = 0.01 over the 12 cases (3 filters × 4 pixels), Šidák-corrected
/// (≈ 8.4e-4 per case); 400,000 samples per case, seeds 1800 + case. Detects a wrong σ or floor,
/// an untruncated or wrongly truncated edge, and CDF inversion errors above ~1% of a cell's mass.
#[test]
fn film_positions_pass_chi_square() {
    assert_film_positions_pass(&FILTERS, 400_000, 1800);
}

/// The tents' film positions have the tent's density, inside the film and at its edges and
/// corner, as [`film_positions_pass_chi_square`] for the gaussians. Significance: family-wise
/// α = 0.01 over the 12 cases (3 tents × 4 pixels), Šidák-corrected; 400,000 samples per case,
/// seeds 2120 + case. Power: a tent 5% narrower is rejected (the control below).
#[test]
fn tent_film_positions_pass_chi_square() {
    assert_film_positions_pass(&TENTS, 400_000, 2120);
}

/// The signed filters' film positions have density ∝ |f| (their weights carry the sign), inside
/// the film and at its edges and corner, as [`film_positions_pass_chi_square`]: Lanczos (3
/// lobes), Mitchell (0.4, 0.3) and Catmull–Rom. Significance: family-wise α = 0.01 over the 12
/// cases (3 filters × 4 pixels), Šidák-corrected; 200,000 samples per case, seeds 2424 + case.
/// Power: the control below (Mitchell's positions tested as Catmull–Rom's) is rejected.
#[test]
fn signed_film_positions_pass_chi_square() {
    let f = signed_filters();
    assert_film_positions_pass(&[f[0], f[2], f[4]], 200_000, 2424);
}

/// Control of the signed filters' χ²: positions drawn from the Mitchell (⅓, ⅓) filter are
/// rejected as Catmull–Rom's (p < 1e-6; the two differ by a few percent of a cell's mass near the
/// centre), seed 2436.
#[test]
fn signed_chi_square_rejects_a_different_filter() {
    let (mitchell, catmull) = (
        PixelFilter::mitchell(1.0 / 3.0, 1.0 / 3.0),
        PixelFilter::mitchell(0.0, 0.5),
    );
    let draw = |u: Vec2| mitchell.film_position(u, 5, 4, 10, 8);
    let p = chi2_p(&catmull, &draw, (5, 4, 10, 8), 200_000, 2436);
    assert!(p < 1e-6, "Mitchell not told from Catmull–Rom: p = {p:.3e}");
}

/// Control of the tents' χ²: samples of a tent 5% narrower than the filter tested are rejected
/// (p < 1e-6), seed 2140 (a wider one would fail sooner, off the tested support).
#[test]
fn tent_chi_square_rejects_a_narrower_tent() {
    let narrow = PixelFilter::Tent { radius: 0.95 };
    let draw = |u: Vec2| narrow.film_position(u, 5, 4, 10, 8);
    let p = chi2_p(&TENTS[0], &draw, (5, 4, 10, 8), 400_000, 2140);
    assert!(p < 1e-6, "a 5% narrower tent not rejected: p = {p:.3e}");
}

/// Controls: the same test rejects (p < 1e-6) a sampler with σ 3% too large, and one that
/// ignores the film's edge (draws on the whole support, then clamps into the film).
#[test]
fn chi_square_rejects_wrong_samplers() {
    let wide = PixelFilter::Gaussian {
        stddev: 0.515,
        radius: 2.0,
    };
    let draw = |u: Vec2| wide.film_position(u, 5, 4, 10, 8);
    let p = chi2_p(&MITSUBA, &draw, (5, 4, 10, 8), 400_000, 1900);
    assert!(p < 1e-6, "σ·1.03 not rejected: p = {p:.3e}");
    let clamped = |u: Vec2| {
        let p = MITSUBA.film_position(u, 50, 50, 100, 100) - Vec2::splat(50.0);
        p.clamp(Vec2::ZERO, Vec2::new(10.0, 8.0))
    };
    let p = chi2_p(&MITSUBA, &clamped, (0, 0, 10, 8), 400_000, 1901);
    assert!(p < 1e-6, "untruncated edge not rejected: p = {p:.3e}");
}

#[test]
fn film_pdf_matches_the_sampled_support() {
    // At the corner pixel the density is 0 off the film and renormalised on it.
    let f = MITSUBA;
    assert_eq!(f.film_pdf(Vec2::new(-0.1, 0.5), 0, 0, 10, 8), 0.0);
    let on = f.film_pdf(Vec2::new(0.5, 0.5), 0, 0, 10, 8);
    let inner = f.film_pdf(Vec2::new(5.5, 4.5), 5, 4, 10, 8);
    // The corner pixel's centre is 0.5 from the film's edge: per axis the mass on
    // [−0.5, r] of the whole [−r, r] is cut to, by quadrature of the weight.
    let mass = |a: f64, b: f64| -> f64 {
        let n = 100_000;
        (0..n)
            .map(|i| f.eval((a + (b - a) * (i as f64 + 0.5) / n as f64) as f32) as f64)
            .sum::<f64>()
            * (b - a)
            / n as f64
    };
    let ratio = (mass(-2.0, 2.0) / mass(-0.5, 2.0)).powi(2);
    assert!(
        (on as f64 / inner as f64 - ratio).abs() < 1e-4 * ratio,
        "{on} / {inner} vs {ratio}"
    );
}
