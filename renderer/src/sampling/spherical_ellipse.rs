//! Uniform solid-angle sampling of a disk seen from a point, through the spherical ellipse it
//! subtends (Guillén, Ureña, King, Fajardo, Georgiev, López-Moreno & Jarabo 2017,
//! "Area-Preserving Parameterizations for Spherical Ellipses"), and its inverse.
//!
//! **The ellipse.** The directions from `p` to a disk (centre `c`, normal `n`, radius `R`) form
//! an oblique circular cone, which is a *right elliptic* cone about another axis. In the frame
//! where `p` is the origin, the disk's plane is `z = h` and its centre `(cx, 0, h)`, the cone is
//! `dᵀQd ≤ 0` with `Q = [[h², 0, −h·cx], [0, h², 0], [−h·cx, 0, cx² − R²]]`; its eigenvectors are
//! the elliptic cone's axes: `y` (eigenvalue `h²`), and in the x–z plane the cone's axis (the
//! negative eigenvalue `λ₋`) and the minor axis (`λ₊`). With the lengths scaled by `|c − p|`,
//! `λ₊λ₋ = −h²R²` gives the tangent-plane semi-axes (the ellipse where the cone meets the plane
//! one unit along its axis) without cancellation: `a = hR/λ₊` (minor) and `b = R/√λ₊` (major;
//! `λ₊ ≥ h²`, so `a ≤ b`), and the axis is `(cx, h(1 + R²/λ₊))`.
//!
//! **The parameterisation** is the paper's polar one: the azimuth `φ` about the cone's axis by
//! inverting the ellipse's area up to `φ`, then `cos θ` uniform between 1 and the boundary's
//! `cos θ_max(φ)`, which is closed form. Chosen over the paper's concentric variant (the same
//! 1D inversion, only the square is mapped differently) and its cylindrical one (Ureña's, whose
//! CDF is a *difference* of first- and third-kind integrals that cancels for thin ellipses)
//! because its inner step is exact, its inverse is two lines, and the quadrant symmetry confines
//! Newton to `[0, π/2]`. `u.x` picks the quadrant (mirrored in every other one, so the map is
//! continuous) and the fraction of its area; `u.y` the versine `1 − cos θ = u.y·(1 − cos θ_max)`.
//!
//! With `ψ` the azimuth from the major axis towards the minor one and `r(ψ)` the tangent-plane
//! boundary, `tan θ_max = r`, the area of the sector `[0, ψ]` is
//! `F(ψ) = ∫₀^ψ (1 − cos θ_max) = ψ − G(ψ)` where, by Carlson's forms (derived here from the
//! substitution `t = cot²ψ` in `∫ √(D/(D + a²b²))`, `D = a² cos²ψ + b² sin²ψ`, every term
//! positive):
//!
//! `G(ψ) = a/√(1 + b²) · [s·R_F(x, y, z) + (b² − a²)/3 · s³·R_J(x, y, z, a²)]`,
//! `s = sin ψ`, `x = a² cos²ψ`, `y = D`, `z = a² + (b² − a²)s²/(1 + b²)`,
//!
//! and the solid angle is `Ω = 4 F(π/2)`, the complete case. Newton's method on `F` (its
//! derivative `1 − cos θ_max(ψ)` is closed form) is seeded by `tan ψ = (A/B) tan(π/2 · t)`, the
//! exact inverse if the outline were an ellipse of semi-axes `A = 2 sin(α/2)`, `B = 2 sin(β/2)` in
//! the Lambert azimuthal equal-area projection (it is for circles and small cones), and is
//! safeguarded by bisection within a bracket; both it and the duplication loops of `R_F`/`R_J` have fixed caps, so a GPU lane's
//! work is bounded ([`MAX_ELLIPSE_NEWTON_STEPS`], [`super::elliptic::MAX_CARLSON_STEPS`]).
//!
//! **Limits.** `F = ψ − G` cancels for small cones: f32 leaves it an absolute error of a few
//! 1e-7, so `Ω` is good to ~1e-6/Ω relatively and callers sample by area below
//! [`MIN_ELLIPSE_SOLID_ANGLE`], where the area density is within a few percent of uniform anyway.
//! Near 2π (`p` almost on a huge disk) and for a rim seen from within its own plane (`b` → ∞)
//! the construction is refused too ([`MAX_ELLIPSE_SOLID_ANGLE`], [`MAX_ELLIPSE_TAN`]).
//! WGSL twin: `sampling/spherical_ellipse.wgsl`.

use super::elliptic::carlson_rf_rj;
use crate::math::{Frame, atan2, safe_sqrt};
use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_PI_2, PI};

/// Below this solid angle (sr) the ellipse is refused and callers sample by area: the f32
/// cancellation in `F = ψ − G` (a few 1e-7 absolute) is then above 1e-4 of `Ω`, while a disk
/// this small (radius ≲ 0.06 of its distance) has an area density within ±12% of uniform in
/// solid angle, which costs almost no variance.
pub const MIN_ELLIPSE_SOLID_ANGLE: f32 = 1e-2;

/// Above this solid angle (sr, 2π − 0.03) the ellipse is refused: its tangent-plane semi-axes
/// exceed ~100 and `p` is within a few thousandths of the disk's radius from its plane, where
/// the receiving surface is almost always the disk's own neighbourhood.
pub const MAX_ELLIPSE_SOLID_ANGLE: f32 = 6.25;

/// Largest tangent-plane semi-axis accepted (`tan` of the half-angle, 89.9°): beyond it `p` sees
/// the rim from within about 0.1° of the disk's plane.
pub const MAX_ELLIPSE_TAN: f32 = 600.0;

/// Most safeguarded Newton steps of the azimuth inversion. The seed is exact for circles and small
/// cones, so most samples take 1–2; thin ellipses of large solid angle, whose area piles up near
/// the major axis, fall back to bisection for a few steps.
pub const MAX_ELLIPSE_NEWTON_STEPS: usize = 20;

/// Newton stops once a step is below this many radians of azimuth: the next error is then below
/// ~1e-8, far under the f32 noise of `F`.
pub const ELLIPSE_NEWTON_TOLERANCE: f32 = 1e-4;

/// Largest disk radius, relative to its distance from `p`, that is looked at (such a disk covers
/// all but ~1e-4 of the hemisphere and is refused by [`MAX_ELLIPSE_SOLID_ANGLE`] anyway): keeps
/// the fourth powers of the construction finite.
pub const MAX_ELLIPSE_RELATIVE_RADIUS: f32 = 1e4;

/// A disk as seen from a point: its spherical ellipse, ready to be sampled uniformly by solid
/// angle.
#[derive(Clone, Copy, Debug)]
pub struct SphericalEllipse {
    /// The elliptic cone's frame: `s` the minor axis, `t` the major axis, `n` the cone's axis.
    frame: Frame,
    /// Tangent-plane semi-axes, `a ≤ b`.
    a: f32,
    b: f32,
    /// `a / √(1 + b²)`, the factor of `G`.
    g_scale: f32,
    /// `A/B`, the ratio of the semi-axes in the Lambert azimuthal equal-area projection about the
    /// axis (`A = 2 sin(α/2)` for `tan α = a`): Newton's seed.
    seed_ratio: f32,
    /// The solid angle of one quadrant, `Ω/4`.
    quarter: f32,
}

impl SphericalEllipse {
    /// The spherical ellipse of the disk (centre `center`, unit normal `n`, radius `radius`) seen
    /// from `p`, if `p` is strictly in front of it (on the side of `n`) and the solid angle lies in
    /// `[MIN_ELLIPSE_SOLID_ANGLE, MAX_ELLIPSE_SOLID_ANGLE]` with both semi-axes under
    /// [`MAX_ELLIPSE_TAN`]; `None` otherwise (callers sample by area).
    pub fn new(p: Vec3, center: Vec3, n: Vec3, radius: f32) -> Option<SphericalEllipse> {
        let v = center - p;
        let h = -v.dot(n);
        // Behind the one-sided disk, in its plane, or NaN.
        if h.is_nan() || h <= 0.0 {
            return None;
        }
        // The centre's offset from p's foot on the plane: the disk-plane axis towards the centre.
        let w = v + h * n;
        let cx = w.length();
        let d = (h * h + cx * cx).sqrt();
        let (hn, cn, rn) = (h / d, cx / d, radius / d);
        if !(rn > 0.0 && rn < MAX_ELLIPSE_RELATIVE_RADIUS && hn > 0.0) {
            return None;
        }
        let t = (1.0 - rn) * (1.0 + rn);
        let hr = hn * rn;
        let s = (t * t + 4.0 * hr * hr).sqrt();
        let lambda = if t >= 0.0 {
            0.5 * (t + s)
        } else {
            2.0 * hr * hr / (s - t)
        };
        let a = hr / lambda;
        let b = rn / lambda.sqrt();
        if !(PI * a * b >= MIN_ELLIPSE_SOLID_ANGLE && b <= MAX_ELLIPSE_TAN) {
            return None;
        }
        let zl = -n;
        // Gram–Schmidt against n: w's normal component is f32 rounding of v·n, which matters when
        // the centre is almost straight ahead (the ellipse is then a circle, so the in-plane
        // direction is immaterial; any perpendicular one serves when there is none).
        let xl = (w - n * w.dot(n)).normalize_or(Frame::from_normal(n).s);
        let axis = Vec2::new(cn, hn * (1.0 + rn * rn / lambda)).normalize();
        let frame = Frame {
            s: axis.y * xl - axis.x * zl,
            t: zl.cross(xl),
            n: axis.x * xl + axis.y * zl,
        };
        // (2 sin(α/2))² = 2(1 − cos α) = 2a²/(√(1 + a²)(√(1 + a²) + 1)), without cancellation.
        let lambert2 = |t: f32| {
            let r = (1.0 + t * t).sqrt();
            2.0 * t * t / (r * (r + 1.0))
        };
        let mut e = SphericalEllipse {
            frame,
            a,
            b,
            g_scale: a / (1.0 + b * b).sqrt(),
            seed_ratio: (lambert2(a) / lambert2(b)).sqrt(),
            quarter: 0.0,
        };
        e.quarter = FRAC_PI_2 - e.g(1.0, 0.0);
        let omega = 4.0 * e.quarter;
        (MIN_ELLIPSE_SOLID_ANGLE..=MAX_ELLIPSE_SOLID_ANGLE)
            .contains(&omega)
            .then_some(e)
    }

    /// Solid angle of the ellipse (sr).
    pub fn solid_angle(&self) -> f32 {
        4.0 * self.quarter
    }

    /// Solid-angle pdf of [`SphericalEllipse::sample`]: `1 / Ω`.
    pub fn pdf(&self) -> f32 {
        0.25 / self.quarter
    }

    /// The tangent-plane semi-axes `(a, b)`, `a ≤ b`.
    pub fn semi_axes(&self) -> (f32, f32) {
        (self.a, self.b)
    }

    /// The cone's axis (unit, world).
    pub fn axis(&self) -> Vec3 {
        self.frame.n
    }

    /// `G(ψ)` for `(s, c) = (sin ψ, cos ψ)`: see the module doc.
    fn g(&self, s: f32, c: f32) -> f32 {
        if s == 0.0 {
            return 0.0;
        }
        let (a2, b2) = (self.a * self.a, self.b * self.b);
        let diff = b2 - a2;
        let x = a2 * c * c;
        let y = x + b2 * s * s;
        let z = a2 + diff * s * s / (1.0 + b2);
        // A circle (a = b) has no third-kind part: diff = 0 multiplies a finite R_J.
        let (rf, rj) = carlson_rf_rj(x, y, z, a2);
        self.g_scale * s * (rf + diff / 3.0 * s * s * rj)
    }

    /// The area `F(ψ) = ψ − G(ψ)` of the sector `[0, ψ]` of a quadrant (ψ from the major axis).
    fn sector(&self, psi: f32, s: f32, c: f32) -> f32 {
        psi - self.g(s, c)
    }

    /// `1 − cos θ_max(ψ)`, the boundary's versine, without cancellation: with
    /// `D = a² cos²ψ + b² sin²ψ`, `cos θ_max = √(D/(D + a²b²))`.
    fn versine_max(&self, s: f32, c: f32) -> f32 {
        let (a2, b2) = (self.a * self.a, self.b * self.b);
        let d = a2 * c * c + b2 * s * s;
        let ab2 = a2 * b2;
        let outer = (d + ab2).sqrt();
        ab2 / (outer * (outer + d.sqrt()))
    }

    /// The azimuth `ψ ∈ [0, π/2]` (from the major axis) whose sector holds the fraction `t` of
    /// the quadrant, with its sine and cosine and the number of Newton steps taken.
    pub fn solve_azimuth(&self, t: f32) -> (f32, f32, f32, usize) {
        let target = t * self.quarter;
        // Seed: the inverse for an outline that is an ellipse in the Lambert azimuthal
        // equal-area projection, where the sector's area is the plane's (exact for circles and in
        // the small-cone limit; about 1.4 evaluations of F per sample instead of 2.7 from the
        // tangent-plane ellipse's).
        let (st, ct) = (FRAC_PI_2 * t).sin_cos();
        let mut psi = atan2(self.seed_ratio * st, ct);
        let (mut lo, mut hi) = (0.0f32, FRAC_PI_2);
        let mut steps = 0;
        while steps < MAX_ELLIPSE_NEWTON_STEPS {
            steps += 1;
            let (s, c) = psi.sin_cos();
            // The angle of (s, c) itself, so that F is evaluated consistently even where sin and
            // cos are approximate (GPUs); a no-op up to an ulp here.
            psi = atan2(s, c);
            let f = self.sector(psi, s, c) - target;
            if f == 0.0 {
                break;
            } else if f > 0.0 {
                hi = psi;
            } else {
                lo = psi;
            }
            let newton = psi - f / self.versine_max(s, c);
            if newton > lo && newton < hi {
                let step = newton - psi;
                psi = newton;
                if step.abs() <= ELLIPSE_NEWTON_TOLERANCE {
                    break;
                }
            } else {
                psi = 0.5 * (lo + hi);
                if hi - lo <= ELLIPSE_NEWTON_TOLERANCE {
                    break;
                }
            }
        }
        let (s, c) = psi.sin_cos();
        (psi, s, c, steps)
    }

    /// The direction (unit, world) for `u ∈ [0,1)²`; uniform in solid angle over the ellipse.
    pub fn sample(&self, u: Vec2) -> Vec3 {
        self.sample_steps(u).0
    }

    /// [`SphericalEllipse::sample`] with the number of Newton steps it took.
    pub fn sample_steps(&self, u: Vec2) -> (Vec3, usize) {
        // Quadrant q and the fraction t of its area; every other quadrant runs backwards, so the
        // azimuth grows continuously with u.x: ψ, π − ψ, π + ψ, 2π − ψ from the major axis.
        let q = ((4.0 * u.x) as u32).min(3);
        let f = 4.0 * u.x - q as f32;
        let t = if q % 2 == 1 { 1.0 - f } else { f };
        let (_, s, c, steps) = self.solve_azimuth(t.clamp(0.0, 1.0));
        let (sx, sy) = match q {
            0 => (s, c),
            1 => (s, -c),
            2 => (-s, -c),
            _ => (-s, c),
        };
        let h = u.y * self.versine_max(s, c);
        let sin_theta = safe_sqrt(h * (2.0 - h));
        let local = Vec3::new(sin_theta * sx, sin_theta * sy, 1.0 - h);
        (self.frame.to_world(local), steps)
    }

    /// Inverse of [`SphericalEllipse::sample`]: the `u` that samples direction `w` (in the
    /// ellipse).
    pub fn invert(&self, w: Vec3) -> Vec2 {
        let l = self.frame.to_local(w.normalize());
        let (ax, ay) = (l.x.abs(), l.y.abs());
        let r = (ax * ax + ay * ay).sqrt();
        let (s, c) = if r > 0.0 {
            (ax / r, ay / r)
        } else {
            (0.0, 1.0)
        };
        let psi = atan2(ax, ay);
        let t = (self.sector(psi, s, c) / self.quarter).clamp(0.0, 1.0);
        let q = match (l.x >= 0.0, l.y >= 0.0) {
            (true, true) => t,
            (true, false) => 2.0 - t,
            (false, false) => 2.0 + t,
            (false, true) => 4.0 - t,
        };
        // 1 − cos θ from the components across the axis, where l.z alone has lost them.
        let versine = r * r / (1.0 + l.z);
        let v = (versine / self.versine_max(s, c)).clamp(0.0, 1.0);
        Vec2::new((0.25 * q).clamp(0.0, 1.0), v)
    }
}

#[cfg(test)]
#[path = "spherical_ellipse_tests.rs"]
mod tests;
