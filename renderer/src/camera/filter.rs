//! The pixel (reconstruction) filter, sampled by filter importance sampling (pbrt-v4): a camera
//! sample's film offset from the pixel centre is drawn with density ∝ the filter, so every sample
//! has weight 1 and a pixel's mean is the filter-weighted average of the image around it.
//!
//! * [`PixelFilter::Box`]: uniform over the pixel (lumis' original jitter, bit for bit).
//! * [`PixelFilter::Gaussian`]: Mitsuba 3's `gaussian` rfilter, the windowed Gaussian
//!   `f(x) = max(0, exp(−x²/(2σ²)) − exp(−r²/(2σ²)))` per axis, separable (`f(x)·f(y)`), as
//!   Mitsuba's `ImageBlock::put` weights a splat (`src/rfilters/gaussian.cpp`: its CPU variants
//!   evaluate a Remez fit of the same function, equal within ~1e-7). Mitsuba fixes `r = 4σ`.
//! * [`PixelFilter::Tent`]: Mitsuba 3's `tent` rfilter, `f(x) = max(0, 1 − |x|/r)` per axis,
//!   separable (`src/rfilters/tent.cpp`; its radius defaults to 1 pixel).
//!
//! **Film edges** follow Mitsuba's `hdrfilm` with `sample_border = false` (its default): Mitsuba
//! places samples only on the film and divides each pixel's weighted sum by its summed weights,
//! so a pixel within `r` of the border converges to the filter restricted to the film and
//! renormalised. Per axis the film is an interval, so that is the 1-D filter on
//! `[max(−r, −c), min(r, n − c)]` about the pixel centre `c`: [`PixelFilter::film_position`]
//! samples exactly that truncated density, by inverting its CDF (Newton steps kept inside a
//! bisection bracket, a fixed iteration cap, the same code in `camera/filter.wgsl`, whose
//! cap and tolerance are these constants through the generated WGSL prelude).
//!
//! WGSL twin: `camera/filter.wgsl`.

use crate::erf::erfc;
use glam::Vec2;

/// A pixel filter. Parameters are validated by the scene parser: `stddev > 0`,
/// `stddev ≤ radius ≤` [`MAX_FILTER_RADIUS`]; a tent's `0 < radius ≤` [`MAX_FILTER_RADIUS`].
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
}

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
        }
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
        }
    }

    /// `∫_{−r}^{x} eval`, for `x` in `[−r, r]`.
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
        }
    }

    /// The 1-D filter's CDF on `[lo, hi]` (a sub-interval of `[−r, r]`) at `x`: the inverse of
    /// [`PixelFilter::sample_1d`].
    pub fn cdf_1d(&self, x: f32, lo: f32, hi: f32) -> f32 {
        let (lo, hi) = self.clip(lo, hi);
        let x = x.clamp(lo, hi);
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
        }
    }

    /// `[lo, hi] ∩ [−r, r]`.
    fn clip(&self, lo: f32, hi: f32) -> (f32, f32) {
        let r = self.radius();
        (lo.max(-r), hi.min(r))
    }

    /// An offset in `[lo, hi] ∩ [−r, r]` with density ∝ the filter there, from a uniform `u`.
    /// The interval must hold some of the filter's mass (a pixel's own half-pixel always does).
    pub fn sample_1d(&self, u: f32, lo: f32, hi: f32) -> f32 {
        let (lo, hi) = self.clip(lo, hi);
        if let PixelFilter::Box = self {
            return (lo + u * (hi - lo)).clamp(lo, hi);
        }
        let base = self.integral(lo);
        let target = u * (self.integral(hi) - base);
        // Newton on F(x) = target inside a bisection bracket [a, b] that always holds the root;
        // a step leaving the bracket (or a flat spot) bisects instead.
        let (mut a, mut b) = (lo, hi);
        let mut x = lo + u * (hi - lo);
        for _ in 0..MAX_STEPS {
            let g = self.integral(x) - base - target;
            if g < 0.0 {
                a = x;
            } else {
                b = x;
            }
            let f = self.eval(x);
            let mut next = x - g / f;
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

    /// The film position (pixels, `0..width` × `0..height`) of a camera sample of pixel
    /// `(px, py)` from the uniforms `u`: the pixel centre plus an offset with density ∝ the
    /// filter restricted to the film (see the module docs on edges). The box filter gives
    /// `(px + u.x, py + u.y)`, lumis' original jitter, exactly.
    pub fn film_position(&self, u: Vec2, px: u32, py: u32, width: u32, height: u32) -> Vec2 {
        match self {
            PixelFilter::Box => Vec2::new(px as f32 + u.x, py as f32 + u.y),
            PixelFilter::Gaussian { .. } | PixelFilter::Tent { .. } => {
                let axis = |u: f32, p: u32, n: u32| {
                    let c = p as f32 + 0.5;
                    c + self.sample_1d(u, -c, n as f32 - c)
                };
                Vec2::new(axis(u.x, px, width), axis(u.y, py, height))
            }
        }
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
}

#[cfg(test)]
#[path = "filter_tests.rs"]
mod tests;
