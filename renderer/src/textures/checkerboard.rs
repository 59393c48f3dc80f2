//! The checkerboard: Mitsuba 3.9.1's `checkerboard` plugin. With `uv' = uv·scale + offset`, a
//! point is `color0` where the fractional parts of `u'` and `v'` are both > ½ or both ≤ ½, and
//! `color1` elsewhere: `color0` on `[0, ½]²`, squares of side ½ in `uv'`.
//!
//! Mitsuba's `eval_1` (what its scalar slots, e.g. a conductor's `alpha`, read) swaps the two
//! colours (`mask.x != mask.y` selects `color0` there, `==` in `eval`); lumis has one rule for
//! both, so a converter writing a checkerboard into a Mitsuba *scalar* slot swaps `color0` and
//! `color1` to get the same image.
//!
//! WGSL twin: `textures/mod.wgsl`.

use super::UvTransform;
use glam::{Vec2, Vec3};

/// Mitsuba's default `color0`.
pub const DEFAULT_COLOR0: f32 = 0.4;
/// Mitsuba's default `color1`.
pub const DEFAULT_COLOR1: f32 = 0.2;

/// Two colours in a checkerboard.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Checkerboard {
    /// On the squares whose `u'` and `v'` halves agree (including `[0, ½]²`).
    pub color0: Vec3,
    /// On the others.
    pub color1: Vec3,
    /// Applied to `uv` first.
    pub uv: UvTransform,
}

impl Checkerboard {
    /// Whether `uv` is on a `color1` square.
    #[inline]
    pub fn is_color1(&self, uv: Vec2) -> bool {
        let p = self.uv.apply(uv);
        (p.x - p.x.floor() > 0.5) != (p.y - p.y.floor() > 0.5)
    }

    /// The colour at `uv`.
    #[inline]
    pub fn eval(&self, uv: Vec2) -> Vec3 {
        if self.is_color1(uv) {
            self.color1
        } else {
            self.color0
        }
    }

    /// The average over the unit square of `uv`, exact: per axis the fraction of `[lo, hi]`
    /// whose fractional part exceeds ½, and the two axes are independent.
    pub fn mean(&self) -> Vec3 {
        let [iu, iv] = self.uv.unit_square_image();
        let (fu, fv) = (upper_half_fraction(iu), upper_half_fraction(iv));
        let p1 = fu * (1.0 - fv) + (1.0 - fu) * fv;
        (self.color0.as_dvec3() * (1.0 - p1) + self.color1.as_dvec3() * p1).as_vec3()
    }
}

impl Default for Checkerboard {
    /// Mitsuba's defaults: 0.4 and 0.2, identity `to_uv`.
    fn default() -> Self {
        Checkerboard {
            color0: Vec3::splat(DEFAULT_COLOR0),
            color1: Vec3::splat(DEFAULT_COLOR1),
            uv: UvTransform::IDENTITY,
        }
    }
}

/// The fraction of `t ∈ [lo, hi]` with `t − ⌊t⌋ > ½`; at a point (`lo == hi`) 0 or 1, decided
/// in `f32` as [`Checkerboard::eval`] decides it.
fn upper_half_fraction((lo, hi): (f64, f64)) -> f64 {
    if hi <= lo {
        let t = lo as f32;
        return if t - t.floor() > 0.5 { 1.0 } else { 0.0 };
    }
    // Measure of the upper halves in [0, x]; shifted by whole periods to keep f64's digits.
    let g = |x: f64| x.floor() * 0.5 + (x - x.floor() - 0.5).max(0.0);
    let shift = lo.floor();
    ((g(hi - shift) - g(lo - shift)) / (hi - lo)).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn board(scale: Vec2, offset: Vec2) -> Checkerboard {
        Checkerboard {
            color0: Vec3::new(1.0, 0.0, 0.0),
            color1: Vec3::new(0.0, 0.0, 1.0),
            uv: UvTransform { scale, offset },
        }
    }

    /// Mitsuba's definition, transcribed: `mask = uv − floor(uv) > .5`,
    /// `m0 = mask.x == mask.y` → color0, else color1.
    fn mitsuba(c: &Checkerboard, uv: Vec2) -> Vec3 {
        let p = c.uv.scale * uv + c.uv.offset;
        let mask = (p.x - p.x.floor() > 0.5, p.y - p.y.floor() > 0.5);
        if mask.0 == mask.1 { c.color0 } else { c.color1 }
    }

    #[test]
    fn matches_mitsubas_definition_at_chosen_points() {
        let c = board(Vec2::ONE, Vec2::ZERO);
        let (c0, c1) = (c.color0, c.color1);
        // Quadrants of the unit square, the boundaries at ½ (≤ ½ is the lower half) and 0,
        // negative coordinates (floor, not truncation) and a second period.
        for (uv, want) in [
            ((0.25, 0.25), c0),
            ((0.75, 0.25), c1),
            ((0.25, 0.75), c1),
            ((0.75, 0.75), c0),
            ((0.5, 0.5), c0),
            ((0.5, 0.51), c1),
            ((0.0, 0.0), c0),
            ((-0.25, 0.25), c1),
            ((-0.25, -0.25), c0),
            ((1.25, 0.75), c1),
            ((2.75, 3.75), c0),
        ] {
            let uv = Vec2::new(uv.0, uv.1);
            assert_eq!(c.eval(uv), want, "{uv}");
            assert_eq!(mitsuba(&c, uv), want, "{uv}");
        }
        // With a transform, against the transcription on a grid that crosses many squares.
        let c = board(Vec2::new(4.0, -3.0), Vec2::new(0.1, 0.3));
        for i in 0..50 {
            for j in 0..50 {
                let uv = Vec2::new(i as f32 / 49.0, j as f32 / 37.0 - 0.2);
                assert_eq!(c.eval(uv), mitsuba(&c, uv), "{uv}");
            }
        }
        // 4 × 4 scale: the square [0.125, 0.25] × [0, 0.125] is the second of its row.
        let c = board(Vec2::splat(4.0), Vec2::ZERO);
        assert_eq!(c.eval(Vec2::new(0.2, 0.05)), c1);
    }

    #[test]
    fn mean_matches_a_brute_force_average() {
        for (scale, offset) in [
            (Vec2::ONE, Vec2::ZERO),
            (Vec2::splat(4.0), Vec2::ZERO),
            (Vec2::new(0.3, 1.0), Vec2::ZERO),
            (Vec2::new(0.7, 2.3), Vec2::new(0.4, -0.15)),
            (Vec2::new(-1.3, 0.6), Vec2::new(2.0, 0.9)),
            (Vec2::new(0.0, 0.4), Vec2::new(0.8, 0.3)),
        ] {
            let c = board(scale, offset);
            let n = 2000;
            let mut sum = DVec3::ZERO;
            for i in 0..n {
                for j in 0..n {
                    let uv = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                    sum += c.eval(uv).as_dvec3();
                }
            }
            let brute = sum / (n * n) as f64;
            let mean = c.mean().as_dvec3();
            assert!(
                (mean - brute).abs().max_element() < 2e-3,
                "scale {scale} offset {offset}: exact {mean} vs brute force {brute}"
            );
        }
        // Whole periods: exactly half and half.
        assert_eq!(
            board(Vec2::ONE, Vec2::ZERO).mean(),
            Vec3::new(0.5, 0.0, 0.5)
        );
        assert_eq!(
            Checkerboard::default().mean(),
            Vec3::splat(0.5 * (DEFAULT_COLOR0 + DEFAULT_COLOR1))
        );
    }
}
