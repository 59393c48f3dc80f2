//! The pixel (reconstruction) filter, sampled by filter importance sampling (pbrt-v4): a camera
//! sample's film offset from the pixel centre is drawn with density ∝ |filter|, and a pixel's mean
//! is the filter-weighted average of the image around it.
//!
//! * [`PixelFilter::Box`]: uniform over the pixel (lumis' original jitter, bit for bit).
//! * [`PixelFilter::Gaussian`]: Mitsuba 3's `gaussian` rfilter, the windowed Gaussian
//!   `f(x) = max(0, exp(−x²/(2σ²)) − exp(−r²/(2σ²)))` per axis, separable (`f(x)·f(y)`), as
//!   Mitsuba's `ImageBlock::put` weights a splat (`src/rfilters/gaussian.cpp`: its CPU variants
//!   evaluate a Remez fit of the same function, equal within ~1e-7). Mitsuba fixes `r = 4σ`.
//! * [`PixelFilter::Tent`]: Mitsuba 3's `tent` rfilter, `f(x) = max(0, 1 − |x|/r)` per axis,
//!   separable (`src/rfilters/tent.cpp`; its radius defaults to 1 pixel).
//! * [`PixelFilter::Lanczos`] and [`PixelFilter::Mitchell`] (Mitsuba's `lanczos`, `mitchell` and
//!   `catmullrom`) have **negative lobes**: see [Signed filters](#signed-filters).
//!
//! **Film edges** follow Mitsuba's `hdrfilm` with `sample_border = false` (its default): Mitsuba
//! places samples only on the film and divides each pixel's weighted sum by its summed weights,
//! so a pixel within `r` of the border converges to the filter restricted to the film and
//! renormalised. Per axis the film is an interval, so that is the 1-D filter on
//! `[max(−r, −c), min(r, n − c)]` about the pixel centre `c`: [`PixelFilter::film_sample`]
//! samples exactly that truncated density, by inverting its CDF (Newton steps kept inside a
//! bisection bracket, a fixed iteration cap, the same code in `camera/filter.wgsl`, whose
//! cap and tolerance are these constants through the generated WGSL prelude).
//!
//! # Signed filters
//!
//! A filter `f` with negative lobes is sampled with density `|f| / A` on the pixel's interval
//! (`A = ∫|f|`, `S = ∫f` there) and the sample carries the weight `sign f(x) · A / S` per axis
//! (the product of both axes'), so `E[weight · L] = ∫ f L / S`: the pixel value Mitsuba's film
//! converges to, without bias, every sample's weight of the same magnitude. `|f|` has no closed
//! antiderivative for Lanczos (it needs the sine integral), so both are integrated piece by piece
//! between the points where `f` may change sign or its formula changes (Lanczos: the integers;
//! Mitchell: 0, 1, 2 and the roots of its cubics, found once when the filter is made), by
//! 8-point Gauss–Legendre quadrature ([`GAUSS_LEGENDRE`]), which on such a piece is exact for
//! the cubics and within ~1e-12 for Lanczos' unit intervals: far below f32. On each piece `f`
//! keeps one sign, so `∫|f| = |∫f|` there and the CDF of `|f|` is exact up to that quadrature.
//! [`PixelFilter::check_film`] refuses a filter whose `S` is not above `A/1000` on some pixel of
//! the film (possible only for unusual Mitchell B, C).
//!
//! WGSL twin: `camera/filter.wgsl`.

use crate::erf::erfc;
use glam::Vec2;

/// A pixel filter. Parameters are validated by the scene parser: `stddev > 0`,
/// `stddev ≤ radius ≤` [`MAX_FILTER_RADIUS`]; a tent's `0 < radius ≤` [`MAX_FILTER_RADIUS`];
/// Lanczos' `1 ≤ lobes ≤` [`MAX_FILTER_RADIUS`]. Make a Mitchell filter with
/// [`PixelFilter::mitchell`] (it finds its pieces).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum PixelFilter {
    /// Uniform over the pixel (radius ½).
    #[default]
    Box,
    /// Mitsuba's windowed Gaussian: `exp(−x²/(2σ²))` minus its value at `radius`, clamped at 0.
    Gaussian {
        /// Standard deviation σ in pixels.
        stddev: f32,
        /// Support half-width in pixels (Mitsuba: 4σ).
        radius: f32,
    },
    /// Mitsuba's tent: `1 − |x|/radius`, clamped at 0.
    Tent {
        /// Support half-width in pixels (Mitsuba's default 1).
        radius: f32,
    },
    /// Mitsuba's `lanczos`: `sinc(x)·sinc(x/lobes)` (`sinc t = sin πt / πt`) for `|x| < lobes`,
    /// the radius; negative on every other unit interval.
    Lanczos {
        /// Side lobes, and the radius in pixels (Mitsuba's default 3).
        lobes: u32,
    },
    /// Mitsuba's `mitchell` (Mitchell–Netravali's cubic with parameters B and C, radius 2) and
    /// `catmullrom` (B = 0, C = ½).
    Mitchell {
        /// B (Mitsuba's default ⅓).
        b: f32,
        /// C (Mitsuba's default ⅓).
        c: f32,
        /// Where the pieces on `[0, 2]` end, ascending: 1, 2 and the cubics' sign changes,
        /// padded with 2 (empty pieces).
        breaks: [f32; MITCHELL_BREAKS],
    },
}

/// The positive piece ends a Mitchell filter keeps: 1, 2 and at most two sign changes of each
/// cubic (the inner has one turning point inside `(0, 1)`; the outer is `(x − 2)` times a
/// quadratic), padded.
pub const MITCHELL_BREAKS: usize = 8;

/// 8-point Gauss–Legendre quadrature on [−1, 1]: the positive nodes and their weights (the rule is
/// symmetric). `FILTER_GL_X0..3`, `FILTER_GL_W0..3` in the WGSL prelude.
pub const GAUSS_LEGENDRE: [(f32, f32); 4] = [
    (0.183_434_64, 0.362_683_78),
    (0.525_532_4, 0.313_706_65),
    (0.796_666_5, 0.222_381_03),
    (0.960_289_9, 0.101_228_54),
];

/// The widest filter the scene format accepts, in pixels.
pub const MAX_FILTER_RADIUS: f32 = 16.0;

/// Newton/bisection steps at most per axis (typically 3–6 are taken); `FILTER_MAX_STEPS` in
/// the WGSL prelude.
pub const MAX_STEPS: u32 = 40;

/// [`PixelFilter::sample_1d`] stops once a step moves less than this times `1 + |x|`, or the
/// bracket is narrower than this (pixels); `FILTER_TOLERANCE` in the WGSL prelude.
pub const TOLERANCE: f32 = 1e-6;

impl PixelFilter {
    /// Half-width of the support in pixels.
    pub fn radius(&self) -> f32 {
        match *self {
            PixelFilter::Box => 0.5,
            PixelFilter::Gaussian { radius, .. } | PixelFilter::Tent { radius } => radius,
            PixelFilter::Lanczos { lobes } => lobes as f32,
            PixelFilter::Mitchell { .. } => 2.0,
        }
    }

    /// Mitsuba's `mitchell` with parameters B and C (`catmullrom`: 0 and ½), with its pieces.
    pub fn mitchell(b: f32, c: f32) -> PixelFilter {
        PixelFilter::Mitchell {
            b,
            c,
            breaks: mitchell_breaks(b as f64, c as f64),
        }
    }

    /// Whether the filter has negative lobes (samples then carry signed weights).
    pub fn is_signed(&self) -> bool {
        matches!(
            self,
            PixelFilter::Lanczos { .. } | PixelFilter::Mitchell { .. }
        )
    }

    /// The 1-D filter weight at offset `x` from the pixel centre (unnormalised, Mitsuba's `eval`).
    pub fn eval(&self, x: f32) -> f32 {
        match *self {
            PixelFilter::Box => {
                if x.abs() <= 0.5 {
                    1.0
                } else {
                    0.0
                }
            }
            PixelFilter::Gaussian { stddev, radius } => {
                let k = -0.5 / (stddev * stddev);
                ((k * x * x).exp() - (k * radius * radius).exp()).max(0.0)
            }
            PixelFilter::Tent { radius } => (1.0 - x.abs() / radius).max(0.0),
            PixelFilter::Lanczos { lobes } => {
                let (x, r) = (x.abs(), lobes as f32);
                if x < f32::EPSILON {
                    return 1.0;
                }
                if x > r {
                    return 0.0;
                }
                let x1 = std::f32::consts::PI * x;
                let x2 = x1 / r;
                (x1.sin() * x2.sin()) / (x1 * x2)
            }
            PixelFilter::Mitchell { b, c, .. } => {
                let x = x.abs();
                if x >= 2.0 {
                    return 0.0;
                }
                mitchell_cubic(b, c, x)
            }
        }
    }

    /// `∫_{−r}^{x} eval`, for `x` in `[−r, r]` (box, gaussian and tent: the unsigned filters).
    fn integral(&self, x: f32) -> f32 {
        match *self {
            PixelFilter::Box => x + 0.5,
            PixelFilter::Gaussian { stddev, radius } => {
                // ∫ exp(−t²/2σ²) = σ√(π/2)·erf(t/(σ√2)); erf(b) − erf(a) = erfc(a) − erfc(b).
                let s = std::f32::consts::FRAC_1_SQRT_2 / stddev;
                let scale = stddev * (std::f32::consts::FRAC_PI_2).sqrt();
                let floor = (-0.5 * radius * radius / (stddev * stddev)).exp();
                scale * (erfc(-radius * s) - erfc(x * s)) - floor * (x + radius)
            }
            // The rising half's triangle (x ≤ 0), or all of it less the falling half's rest.
            PixelFilter::Tent { radius } => {
                if x <= 0.0 {
                    (x + radius) * (x + radius) / (2.0 * radius)
                } else {
                    radius - (radius - x) * (radius - x) / (2.0 * radius)
                }
            }
            PixelFilter::Lanczos { .. } | PixelFilter::Mitchell { .. } => {
                unreachable!("signed filters are integrated by pieces")
            }
        }
    }

    /// The CDF on `[lo, hi]` (a sub-interval of `[−r, r]`) at `x` of the density
    /// [`PixelFilter::sample_1d`] draws from (∝ |filter|): its inverse.
    pub fn cdf_1d(&self, x: f32, lo: f32, hi: f32) -> f32 {
        let (lo, hi) = self.clip(lo, hi);
        let x = x.clamp(lo, hi);
        if self.is_signed() {
            let (total, _) = self.masses(lo, hi);
            return (self.masses(lo, x).0 / total).clamp(0.0, 1.0);
        }
        let base = self.integral(lo);
        ((self.integral(x) - base) / (self.integral(hi) - base)).clamp(0.0, 1.0)
    }

    /// The density of [`PixelFilter::sample_1d`] on `[lo, hi]` at `x` (0 outside).
    pub fn pdf_1d(&self, x: f32, lo: f32, hi: f32) -> f32 {
        let (lo, hi) = self.clip(lo, hi);
        if !(x >= lo && x <= hi) {
            return 0.0;
        }
        match self {
            PixelFilter::Box => 1.0 / (hi - lo),
            PixelFilter::Gaussian { .. } | PixelFilter::Tent { .. } => {
                self.eval(x) / (self.integral(hi) - self.integral(lo))
            }
            PixelFilter::Lanczos { .. } | PixelFilter::Mitchell { .. } => {
                self.eval(x).abs() / self.masses(lo, hi).0
            }
        }
    }

    /// `[lo, hi] ∩ [−r, r]`.
    fn clip(&self, lo: f32, hi: f32) -> (f32, f32) {
        let r = self.radius();
        (lo.max(-r), hi.min(r))
    }

    /// An offset in `[lo, hi] ∩ [−r, r]` with density ∝ |filter| there, from a uniform `u`, and
    /// its weight: 1, or for a signed filter `sign f · A / S` (see the module docs). The interval
    /// must hold some of the filter's mass (a pixel's own half-pixel always does).
    pub fn sample_1d(&self, u: f32, lo: f32, hi: f32) -> (f32, f32) {
        let (lo, hi) = self.clip(lo, hi);
        if let PixelFilter::Box = self {
            return ((lo + u * (hi - lo)).clamp(lo, hi), 1.0);
        }
        if self.is_signed() {
            return self.sample_signed(u, lo, hi);
        }
        let base = self.integral(lo);
        let target = u * (self.integral(hi) - base);
        let x = self.invert(
            |x| self.integral(x) - base,
            target,
            lo,
            hi,
            lo + u * (hi - lo),
        );
        (x, 1.0)
    }

    /// The `x` in `[lo, hi]` where the increasing `g` (whose derivative is |filter|) reaches
    /// `target`, from `x`: Newton inside a bisection bracket `[a, b]` that always holds the root;
    /// a step leaving the bracket (or a flat spot) bisects instead.
    fn invert(&self, g: impl Fn(f32) -> f32, target: f32, lo: f32, hi: f32, mut x: f32) -> f32 {
        let (mut a, mut b) = (lo, hi);
        for _ in 0..MAX_STEPS {
            let gx = g(x) - target;
            if gx < 0.0 {
                a = x;
            } else {
                b = x;
            }
            let f = self.eval(x).abs();
            let mut next = x - gx / f;
            if !(f > 0.0 && next > a && next < b) {
                next = 0.5 * (a + b);
            }
            let done = (next - x).abs() <= TOLERANCE * (1.0 + x.abs()) || b - a <= TOLERANCE;
            x = next;
            if done {
                break;
            }
        }
        x.clamp(lo, hi)
    }

    /// A signed filter's pieces on each side of 0: where `f` keeps one sign and one formula.
    fn half_pieces(&self) -> usize {
        match *self {
            PixelFilter::Lanczos { lobes } => lobes as usize,
            _ => MITCHELL_BREAKS,
        }
    }

    /// The end of piece `k` (1-based) on the positive side; 0 for `k = 0`.
    fn piece_end(&self, k: usize) -> f32 {
        match *self {
            _ if k == 0 => 0.0,
            PixelFilter::Mitchell { breaks, .. } => breaks[k - 1],
            _ => k as f32,
        }
    }

    /// Piece `i` of `2 · half_pieces` on `[−r, r]`, left to right, cut to `[lo, hi]` (empty when
    /// the start is not below the end).
    fn piece(&self, i: usize, lo: f32, hi: f32) -> (f32, f32) {
        let n = self.half_pieces();
        let (a, b) = if i < n {
            (-self.piece_end(n - i), -self.piece_end(n - i - 1))
        } else {
            (self.piece_end(i - n), self.piece_end(i - n + 1))
        };
        (a.max(lo), b.min(hi))
    }

    /// `∫_a^b f` by 8-point Gauss–Legendre (`a ≤ b` inside one piece).
    fn quadrature(&self, a: f32, b: f32) -> f32 {
        let (m, h) = (0.5 * (a + b), 0.5 * (b - a));
        let mut s = 0.0;
        for (x, w) in GAUSS_LEGENDRE {
            s += w * (self.eval(m - h * x) + self.eval(m + h * x));
        }
        s * h
    }

    /// Each piece's `∫f` over its part of `[lo, hi]` (0 for an empty part), and how many pieces
    /// there are.
    fn piece_integrals(&self, lo: f32, hi: f32) -> ([f32; 2 * MAX_FILTER_RADIUS as usize], usize) {
        let pieces = 2 * self.half_pieces();
        let mut parts = [0.0f32; 2 * MAX_FILTER_RADIUS as usize];
        debug_assert!(pieces <= parts.len(), "more pieces than the parser allows");
        for (i, part) in parts.iter_mut().enumerate().take(pieces) {
            let (a, b) = self.piece(i, lo, hi);
            if a < b {
                *part = self.quadrature(a, b);
            }
        }
        (parts, pieces)
    }

    /// `(∫|f|, ∫f)` of the pieces' integrals, summed left to right.
    fn sums(parts: &[f32]) -> (f32, f32) {
        parts.iter().fold((0.0, 0.0), |(total, signed), &v| {
            (total + v.abs(), signed + v)
        })
    }

    /// `(∫|f|, ∫f)` over `[lo, hi]` (inside `[−r, r]`), piece by piece.
    fn masses(&self, lo: f32, hi: f32) -> (f32, f32) {
        let (parts, pieces) = self.piece_integrals(lo, hi);
        Self::sums(&parts[..pieces])
    }

    /// [`PixelFilter::sample_1d`] of a signed filter on `[lo, hi]` (already clipped): the piece
    /// holding `u`'s share of `∫|f|`, then Newton inside it. Each piece is integrated once.
    fn sample_signed(&self, u: f32, lo: f32, hi: f32) -> (f32, f32) {
        let (parts, pieces) = self.piece_integrals(lo, hi);
        let (total, signed) = Self::sums(&parts[..pieces]);
        let target = u * total;
        // The last non-empty piece takes what rounding leaves past the others.
        let last = (0..pieces).rev().find(|&i| parts[i] != 0.0).unwrap_or(0);
        let mut below = 0.0;
        for (i, &v) in parts.iter().enumerate().take(pieces) {
            if v == 0.0 {
                continue;
            }
            if below + v.abs() >= target || i == last {
                let (a, b) = self.piece(i, lo, hi);
                let s = v.signum();
                let t = (target - below).clamp(0.0, v.abs());
                let start = a + (t / v.abs()) * (b - a);
                let x = self.invert(|x| s * self.quadrature(a, x), t, a, b, start);
                return (x, s * total / signed);
            }
            below += v.abs();
        }
        (0.5 * (lo + hi), 0.0)
    }

    /// The film position (pixels, `0..width` × `0..height`) of a camera sample of pixel
    /// `(px, py)` from the uniforms `u`: the pixel centre plus an offset with density ∝ |filter|
    /// restricted to the film (see the module docs on edges), and the sample's weight (1 but for
    /// signed filters). The box filter gives `(px + u.x, py + u.y)`, lumis' original jitter,
    /// exactly.
    pub fn film_sample(&self, u: Vec2, px: u32, py: u32, width: u32, height: u32) -> (Vec2, f32) {
        match self {
            PixelFilter::Box => (Vec2::new(px as f32 + u.x, py as f32 + u.y), 1.0),
            _ => {
                let axis = |u: f32, p: u32, n: u32| {
                    let c = p as f32 + 0.5;
                    let (x, w) = self.sample_1d(u, -c, n as f32 - c);
                    (c + x, w)
                };
                let ((x, wx), (y, wy)) = (axis(u.x, px, width), axis(u.y, py, height));
                (Vec2::new(x, y), wx * wy)
            }
        }
    }

    /// [`PixelFilter::film_sample`]'s position.
    pub fn film_position(&self, u: Vec2, px: u32, py: u32, width: u32, height: u32) -> Vec2 {
        self.film_sample(u, px, py, width, height).0
    }

    /// The density (per pixel², over film positions) with which
    /// [`PixelFilter::film_position`] places a sample of pixel `(px, py)` at `p`.
    pub fn film_pdf(&self, p: Vec2, px: u32, py: u32, width: u32, height: u32) -> f32 {
        let axis = |x: f32, q: u32, n: u32| {
            let c = q as f32 + 0.5;
            self.pdf_1d(x - c, -c, n as f32 - c)
        };
        axis(p.x, px, width) * axis(p.y, py, height)
    }

    /// Whether every pixel of a `width × height` film has a filter integral `S` on its part of
    /// the support above 1/1000 of `A = ∫|f|` there (a signed filter's weights are `±A/S`); the
    /// error says which pixel fails.
    pub fn check_film(&self, width: u32, height: u32) -> Result<(), String> {
        if !self.is_signed() {
            return Ok(());
        }
        // Only pixels within the radius of an edge see a cut support; one inside stands for the
        // rest.
        let near = self.radius().ceil() as u32 + 1;
        for n in [width, height] {
            for p in (0..n).filter(|&p| p <= near || n - 1 - p <= near) {
                let c = p as f32 + 0.5;
                let (lo, hi) = self.clip(-c, n as f32 - c);
                let (total, signed) = self.masses(lo, hi);
                // NaN fails too.
                let positive = signed > 1e-3 * total;
                if !positive {
                    return Err(format!(
                        "the filter's integral over pixel {p}'s part of a film {n} pixels wide \
                         is {signed:.3e}, not above 1/1000 of its absolute integral {total:.3e}: \
                         that pixel's sample weights (their ratio) would be unbounded"
                    ));
                }
            }
        }
        Ok(())
    }
}

/// Mitchell–Netravali's cubic at `x` in `[0, 2)`, as Mitsuba's `mitchell.cpp` writes it.
fn mitchell_cubic(b: f32, c: f32, x: f32) -> f32 {
    let (x2, x3) = (x * x, x * x * x);
    let v = if x < 1.0 {
        (12.0 - 9.0 * b - 6.0 * c) * x3 + (-18.0 + 12.0 * b + 6.0 * c) * x2 + (6.0 - 2.0 * b)
    } else {
        (-b - 6.0 * c) * x3
            + (6.0 * b + 30.0 * c) * x2
            + (-12.0 * b - 48.0 * c) * x
            + (8.0 * b + 24.0 * c)
    };
    v / 6.0
}

/// The ends of a Mitchell filter's pieces on `[0, 2]`: 1, 2 and every sign change of its cubics,
/// ascending, padded with 2. Each cubic is cut at its turning points, so each part is monotone
/// and holds at most one root, which bisection finds (in f64).
fn mitchell_breaks(b: f64, c: f64) -> [f32; MITCHELL_BREAKS] {
    // Coefficients (x³, x², x, 1) of the inner (x < 1) and outer cubic.
    let inner = [
        12.0 - 9.0 * b - 6.0 * c,
        -18.0 + 12.0 * b + 6.0 * c,
        0.0,
        6.0 - 2.0 * b,
    ];
    let outer = [
        -b - 6.0 * c,
        6.0 * b + 30.0 * c,
        -12.0 * b - 48.0 * c,
        8.0 * b + 24.0 * c,
    ];
    let mut ends = Vec::with_capacity(MITCHELL_BREAKS);
    for (k, (lo, hi)) in [(inner, (0.0, 1.0)), (outer, (1.0, 2.0))] {
        let f = |x: f64| ((k[0] * x + k[1]) * x + k[2]) * x + k[3];
        // Turning points: roots of 3k₀x² + 2k₁x + k₂ inside (lo, hi).
        let mut cuts = vec![lo];
        let (qa, qb, qc) = (3.0 * k[0], 2.0 * k[1], k[2]);
        let mut turns: Vec<f64> = if qa.abs() < 1e-12 {
            if qb.abs() < 1e-12 {
                vec![]
            } else {
                vec![-qc / qb]
            }
        } else {
            let d = qb * qb - 4.0 * qa * qc;
            if d < 0.0 {
                vec![]
            } else {
                vec![(-qb - d.sqrt()) / (2.0 * qa), (-qb + d.sqrt()) / (2.0 * qa)]
            }
        };
        turns.sort_by(f64::total_cmp);
        cuts.extend(turns.into_iter().filter(|&t| t > lo && t < hi));
        cuts.push(hi);
        for w in cuts.windows(2) {
            let (mut a, mut z) = (w[0], w[1]);
            let (fa, fz) = (f(a), f(z));
            // A sign change strictly inside; a root at an end is a piece end already or a
            // touching zero (no change of sign).
            let changes = fa * fz < 0.0;
            if !changes {
                continue;
            }
            for _ in 0..100 {
                let m = 0.5 * (a + z);
                if (f(m) < 0.0) == (fa < 0.0) {
                    a = m;
                } else {
                    z = m;
                }
            }
            ends.push((0.5 * (a + z)) as f32);
        }
        ends.push(hi as f32);
    }
    ends.sort_by(f32::total_cmp);
    let mut out = [2.0; MITCHELL_BREAKS];
    out[..ends.len()].copy_from_slice(&ends);
    out
}

#[cfg(test)]
#[path = "filter_tests.rs"]
mod tests;
