//! The bitmap texture: bilinear lookups in a linear RGB image, exactly as Mitsuba 3.9.1's
//! `bitmap` plugin with `filter_type = bilinear` (Dr.Jit's `Texture2f::eval`): continuous texel
//! coordinate `u'·W − ½`, the two neighbouring integer texels wrapped by the [`WrapMode`], weights
//! `1 − {x}` and `{x}`; the conventions are in the module doc of [`crate::textures`].
//!
//! WGSL twin: `textures/mod.wgsl`.

use super::{Channel, UvTransform};
use crate::image_io::Image;
use glam::{DVec3, Vec2, Vec3};
use std::path::PathBuf;
use std::sync::Arc;

/// What happens to texel indices outside `[0, n)`: Dr.Jit's `WrapMode` (Mitsuba's `wrap_mode`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum WrapMode {
    /// Tile: index mod n.
    #[default]
    Repeat,
    /// Tile with every other period reflected: `… 1 0 | 0 1 … n−1 | n−1 n−2 …`.
    Mirror,
    /// The nearest edge texel.
    Clamp,
}

impl WrapMode {
    /// The texel index in `[0, n)` for any integer index `i` (`n ≥ 1`).
    #[inline]
    pub fn index(self, i: i64, n: u32) -> u32 {
        let n = n as i64;
        let k = match self {
            WrapMode::Clamp => i.clamp(0, n - 1),
            WrapMode::Repeat => i.rem_euclid(n),
            WrapMode::Mirror => {
                let m = i.rem_euclid(2 * n);
                if m < n { m } else { 2 * n - 1 - m }
            }
        };
        k as u32
    }

    /// The name in the scene format.
    pub fn name(self) -> &'static str {
        match self {
            WrapMode::Repeat => "repeat",
            WrapMode::Mirror => "mirror",
            WrapMode::Clamp => "clamp",
        }
    }
}

/// One axis of a bilinear lookup: texture coordinate `t` (after the uv transform) on an axis of
/// `n` texels → the two texels and their weights, `t·n − ½ = ⌊·⌋ + f`, weights `[1 − f, f]`.
/// A non-finite `t` gives NaN weights (the sample is then discarded as non-finite, and counted).
#[inline]
pub fn axis_lookup(t: f32, n: u32, wrap: WrapMode) -> ([u32; 2], [f32; 2]) {
    let x = t * n as f32 - 0.5;
    let fl = x.floor();
    let f = x - fl;
    // Saturating casts: a huge coordinate stays a valid (if meaningless) index.
    let i = fl as i64;
    (
        [wrap.index(i, n), wrap.index(i.saturating_add(1), n)],
        [1.0 - f, f],
    )
}

/// How a bitmap is looked up; everything but the texels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BitmapOptions {
    /// Outside `[0, 1)`.
    pub wrap: WrapMode,
    /// Applied to `uv` before the lookup.
    pub uv: UvTransform,
    /// Multiplies the filtered value, per channel, ≥ 0 (glTF's colour factors, bright emission
    /// from an 8-bit file; Mitsuba's `bitmap` has none: a converter bakes it into the file).
    pub scale: Vec3,
    /// What a scalar parameter reads.
    pub channel: Channel,
}

impl Default for BitmapOptions {
    fn default() -> Self {
        BitmapOptions {
            wrap: WrapMode::Repeat,
            uv: UvTransform::IDENTITY,
            scale: Vec3::ONE,
            channel: Channel::Luminance,
        }
    }
}

/// A bitmap texture: shared linear texels, lookup options, and statistics computed once.
#[derive(Clone, Debug, PartialEq)]
pub struct BitmapTexture {
    image: Arc<Image>,
    options: BitmapOptions,
    /// The file the texels were decoded from (empty for an image made in memory).
    pub file: PathBuf,
    /// Whether it was loaded without sRGB decoding (only matters for 8- and 16-bit files).
    pub raw: bool,
    mean: Vec3,
    max: Vec3,
    max_scalar: f32,
}

impl BitmapTexture {
    /// A texture over `image` (at least 1 × 1 texels); computes its mean and maxima (O(texels)).
    pub fn new(image: Arc<Image>, options: BitmapOptions) -> BitmapTexture {
        assert!(
            image.width >= 1
                && image.height >= 1
                && image.data.len() == image.width as usize * image.height as usize,
            "a bitmap texture needs at least one texel and width × height of them"
        );
        let scale = options.scale;
        let mut max = Vec3::splat(f32::NEG_INFINITY);
        let mut max_scalar = f32::NEG_INFINITY;
        for &t in &image.data {
            let c = t * scale;
            max = max.max(c);
            max_scalar = max_scalar.max(options.channel.pick(c));
        }
        let mean = mean_over_unit_square(&image, &options).as_vec3();
        BitmapTexture {
            image,
            options,
            file: PathBuf::new(),
            raw: false,
            mean,
            max,
            max_scalar,
        }
    }

    /// Its size in texels, `(width, height)`.
    pub fn size(&self) -> (u32, u32) {
        (self.image.width, self.image.height)
    }

    /// The same texture, recording where its texels came from.
    pub fn with_source(mut self, file: PathBuf, raw: bool) -> BitmapTexture {
        self.file = file;
        self.raw = raw;
        self
    }

    /// The texels (linear RGB, row 0 at the top, `v = 0`).
    pub fn image(&self) -> &Arc<Image> {
        &self.image
    }

    /// The lookup options.
    pub fn options(&self) -> &BitmapOptions {
        &self.options
    }

    /// The bilinear cell around `uv`: its four texels in Dr.Jit's corner order ((x0, y0),
    /// (x1, y0), (x0, y1), (x1, y1)), unscaled, and the weights `[1 − f, f]` of each axis.
    #[inline]
    fn cell(&self, uv: Vec2) -> ([Vec3; 4], [f32; 2], [f32; 2]) {
        let p = self.options.uv.apply(uv);
        let img = &*self.image;
        let wrap = self.options.wrap;
        let (xs, wx) = axis_lookup(p.x, img.width, wrap);
        let (ys, wy) = axis_lookup(p.y, img.height, wrap);
        let w = img.width as usize;
        let t = |i: u32, j: u32| img.data[j as usize * w + i as usize];
        (
            [
                t(xs[0], ys[0]),
                t(xs[1], ys[0]),
                t(xs[0], ys[1]),
                t(xs[1], ys[1]),
            ],
            wx,
            wy,
        )
    }

    /// The bilinearly filtered, scaled value at `uv`.
    #[inline]
    pub fn eval(&self, uv: Vec2) -> Vec3 {
        let ([t00, t10, t01, t11], wx, wy) = self.cell(uv);
        // Dr.Jit's per-corner weight wx·wy.
        let mut out = t00 * (wx[0] * wy[0]);
        out += t10 * (wx[1] * wy[0]);
        out += t01 * (wx[0] * wy[1]);
        out += t11 * (wx[1] * wy[1]);
        out * self.options.scale
    }

    /// The gradient (∂/∂u, ∂/∂v) of the filtered value's luminance at `uv`, Mitsuba 3.9.1's
    /// `bitmap::eval_1_grad` (what its `bumpmap` differentiates): the bilinear interpolant of the
    /// four corner texels' luminances, differentiated within its cell, through the uv transform
    /// (its scale, per axis) and times the resolution (texel coordinates per unit of uv').
    /// WGSL twin: `texture_eval_1_grad` in `textures/mod.wgsl`.
    #[inline]
    pub fn eval_1_grad(&self, uv: Vec2) -> Vec2 {
        let (texels, wx, wy) = self.cell(uv);
        let [f00, f10, f01, f11] = texels.map(|t| super::luminance(t * self.options.scale));
        // ∂/∂x and ∂/∂y in texels.
        let dx = wy[0] * (f10 - f00) + wy[1] * (f11 - f01);
        let dy = wx[0] * (f01 - f00) + wx[1] * (f11 - f10);
        let (s, img) = (self.options.uv.scale, &*self.image);
        Vec2::new(dx * s.x * img.width as f32, dy * s.y * img.height as f32)
    }

    /// The average of [`BitmapTexture::eval`] over the unit square of `uv`, exact.
    pub fn mean(&self) -> Vec3 {
        self.mean
    }

    /// Per channel, the largest scaled texel: no lookup exceeds it.
    pub fn max(&self) -> Vec3 {
        self.max
    }

    /// The largest scaled texel's [`BitmapOptions::channel`].
    pub fn max_scalar(&self) -> f32 {
        self.max_scalar
    }
}

/// `∫∫ eval over [0,1]²`: bilinear filtering is a sum of texels times separable weights
/// `a_i(u')·b_j(v')`, so the mean is `Σ t_ij · Ā_i · B̄_j` with the average weights of one axis
/// from [`axis_mean_weights`]. Repeat with an integer scale gives the plain texel average (what
/// Mitsuba's `mean()` returns, whatever its `to_uv`).
fn mean_over_unit_square(image: &Image, options: &BitmapOptions) -> DVec3 {
    let [iu, iv] = options.uv.unit_square_image();
    let a = axis_mean_weights(image.width, options.wrap, iu);
    let b = axis_mean_weights(image.height, options.wrap, iv);
    let w = image.width as usize;
    let mut sum = DVec3::ZERO;
    for (j, &bj) in b.iter().enumerate() {
        if bj == 0.0 {
            continue;
        }
        let row = &image.data[j * w..(j + 1) * w];
        let r: DVec3 = row.iter().zip(&a).map(|(t, &ai)| t.as_dvec3() * ai).sum();
        sum += r * bj;
    }
    sum * options.scale.as_dvec3()
}

/// For an axis of `n` texels, the average over `t ∈ [lo, hi]` of each texel's bilinear weight
/// (they sum to 1). The weights are continuous and piecewise linear between texel centres
/// `(k + ½)/n` (for every wrap mode), so each cell is integrated exactly by the trapezoid rule;
/// whole periods (1 for repeat, 2 for mirror) and the constant parts beyond the edges (clamp)
/// are added in closed form, so the cost is O(n) for any interval.
pub(crate) fn axis_mean_weights(n: u32, wrap: WrapMode, (lo, hi): (f64, f64)) -> Vec<f64> {
    let nf = n as f64;
    let mut w = vec![0.0; n as usize];
    if hi <= lo {
        // A point (scale 0): the weights there.
        let (i, f) = axis_lookup(lo as f32, n, wrap);
        w[i[0] as usize] += f[0] as f64;
        w[i[1] as usize] += f[1] as f64;
        return w;
    }
    let len = hi - lo;
    let (mut a, mut b) = (lo, hi);
    match wrap {
        WrapMode::Repeat | WrapMode::Mirror => {
            let period = if wrap == WrapMode::Repeat { 1.0 } else { 2.0 };
            let whole = (len / period).floor();
            // Over a whole period every texel's weight integrates to period / n.
            w.iter_mut().for_each(|x| *x += whole * period / nf);
            a += whole * period;
            // The weights are periodic: move the rest near 0, where f64 resolves texels.
            let shift = (a / period).floor() * period;
            a -= shift;
            b -= shift;
        }
        WrapMode::Clamp => {
            // Beyond the first and last texel centres the value is that texel's.
            let (c0, c1) = (0.5 / nf, (nf - 0.5) / nf);
            w[0] += (c0.min(b) - a).max(0.0);
            w[n as usize - 1] += (b - c1.max(a)).max(0.0);
            a = a.max(c0);
            b = b.min(c1);
        }
    }
    // Cells between consecutive texel centres: cell k spans x = t·n − ½ ∈ [k, k + 1].
    // At most 2n + 1 cells remain (less than a mirror period); the bound also stops the loop
    // where rounding would keep `a` from advancing.
    let mut k = (a * nf - 0.5).floor();
    for _ in 0..2 * n as usize + 3 {
        if a >= b {
            break;
        }
        let end = ((k + 1.0 + 0.5) / nf).min(b);
        if end > a {
            // The fractions at both ends, in [0, 1]; the weight of texel k+1 is linear in them.
            let fa = (a * nf - 0.5 - k).clamp(0.0, 1.0);
            let fb = (end * nf - 0.5 - k).clamp(0.0, 1.0);
            let upper = (end - a) * 0.5 * (fa + fb);
            let ki = k as i64;
            w[wrap.index(ki, n) as usize] += (end - a) - upper;
            w[wrap.index(ki.saturating_add(1), n) as usize] += upper;
            a = end;
        }
        k += 1.0;
    }
    w.iter_mut().for_each(|x| *x /= len);
    w
}
