//! Projected-solid-angle sampling of a convex spherical polygon clipped to the upper hemisphere,
//! after Peters 2021 ("BRDF Importance Sampling for Polygonal Lights", ACM TOG 40(4), §4), written
//! from the paper's geometry: directions with density `cos θ / Ω⊥`, so that a Lambertian
//! receiver's light from a polygon of constant radiance has no variance outside penumbrae.
//!
//! **Projection.** In the receiver's frame (normal +z) the orthographic projection
//! `(x, y, z) → (x, y)` maps `cos θ dω` to area on the unit disk: `Ω⊥ = ∫ cos θ dω` is the area of
//! the projected polygon, and a uniform point of it, lifted by `z = √(1 − x² − y²)`, has the
//! density `cos θ / Ω⊥`. A great circle of unit normal `m` projects to an ellipse centred at the
//! origin (semi-axes 1 and `|m_z|`), and the projection of the spherical triangle (zenith, a, b)
//! is an elliptic sector of area `½ |m_z| ∠(a, b)`: linear in the arc length. Summed with signs
//! over the edges that is Lambert's formula, `Ω⊥ = ½ Σ ∠(v_i, v_{i+1}) m_i·z`.
//!
//! **Partition.** The polygon is clipped to `z ≥ 0` (Sutherland–Hodgman; an edge on the horizon
//! projects to an arc of the unit circle). Radial lines through the origin and every vertex cut
//! its projection into wedges. Where the zenith is outside, each wedge lies between an arc of the
//! outer chain (the edges running counter-clockwise about the zenith) and one of the inner chain;
//! where it is inside, each edge's elliptic sector is a wedge (the inner boundary is the origin).
//!
//! **Sampling.** `u.x · Ω⊥` picks the wedge by area, then the azimuth `φ` within it by inverting
//! the wedge's distribution function `C(φ) = ½|m_o,z| ∠(o₀, o(φ)) − ½|m_i,z| ∠(i₀, i(φ))` (the
//! outer arc's sector minus the inner one's), whose derivative is `½ (r_o(φ)² − r_i(φ)²)`: a
//! Newton iteration kept inside a shrinking bracket (bisection where a step leaves it), started
//! from the inverse for a density linear in `φ` and capped at [`NEWTON_STEPS`] so a GPU lane's
//! work is bounded. With the zenith inside, `C` is linear in the outer arc's length: closed
//! form. `u.y` then picks `r²` uniformly between the inner and outer arcs (the area element is
//! `½ d(r²) dφ`), the lift written through `z²` directly so that it keeps its digits near the
//! horizon. The inverse ([`ProjectedPolygon::invert`]) runs the same partition backwards.
//!
//! **Conditioning.** Lambert's sum and `C` are differences of sectors measured from the zenith.
//! For a light that is small, or close to the horizon, they cancel to a result much smaller than
//! their terms, and f32 loses digits in proportion to `Σ|S_e| / Ω⊥`. Callers fall back to
//! solid-angle sampling where that exceeds [`MAX_CONDITION`] ([`ProjectedPolygon::well_conditioned`]);
//! the light is then small or near the horizon, where the cosine varies little over it relative
//! to its value or contributes little.
//! WGSL twin: `sampling/projected_solid_angle.wgsl`.

use crate::math::{atan2, safe_sqrt};
use glam::{Vec2, Vec3};

/// Most vertices of a clipped polygon: a parallelogram cut by the horizon gains one.
pub const PSA_MAX_VERTICES: usize = 5;

/// Most Newton steps per sample (each narrowing a bracket, so the azimuth converges even where a
/// step would not; see the convergence test for how many are used).
pub const NEWTON_STEPS: u32 = 10;

/// Newton stops once a step moves the azimuth by less than this fraction of the wedge.
pub const NEWTON_TOLERANCE: f32 = 1e-5;

/// Largest `Σ|S_e| / Ω⊥` (sum of the sectors' magnitudes over their signed sum) for which
/// projected-solid-angle sampling is used; beyond it, rounding of order `MAX_CONDITION · 1e-7`
/// would reach the projected solid angle (chosen from the measured errors: see the tests).
pub const MAX_CONDITION: f32 = 64.0;

/// A convex spherical polygon clipped to `z ≥ 0` in a receiver's local frame (normal +z), ready
/// to be sampled in proportion to `cos θ`.
#[derive(Clone, Copy, Debug)]
pub struct ProjectedPolygon {
    /// Unit vertices, counter-clockwise about +z (positive projected area).
    v: [Vec3; PSA_MAX_VERTICES],
    /// Number of vertices (3 to [`PSA_MAX_VERTICES`]).
    n: usize,
    /// The projected solid angle Ω⊥ (Lambert's formula).
    area: f32,
    /// `Σ|S_e|`, the sectors' magnitudes (for [`ProjectedPolygon::condition`]).
    abs_sum: f32,
    /// With the zenith outside, the vertex of smallest azimuth (where the outer chain begins) and
    /// that of largest azimuth (where it ends); `None` with the zenith inside or on the boundary.
    chains: Option<(usize, usize)>,
}

/// Signed area of the elliptic sector from the origin along the arc `a → b` (unit vectors): the
/// projection of the spherical triangle (zenith, a, b), `½ ∠(a, b) · m_z`, positive where the arc
/// runs counter-clockwise about +z. Zero for coincident points.
#[inline]
pub fn sector(a: Vec3, b: Vec3) -> f32 {
    // a × (b − a) = a × b, but the difference keeps the digits of close vertices.
    let c = a.cross(b - a);
    let len = c.length();
    if len > 0.0 {
        0.5 * atan2(len, a.dot(b)) * (c.z / len)
    } else {
        0.0
    }
}

/// The angle between unit vectors `a` and `b`, accurate for close ones.
#[inline]
fn angle(a: Vec3, b: Vec3) -> f32 {
    atan2(a.cross(b - a).length(), a.dot(b))
}

/// The unit normal of the great circle through `a` and `b` (either sign; zero if they coincide).
#[inline]
fn arc_normal(a: Vec3, b: Vec3) -> Vec3 {
    a.cross(b - a).normalize_or_zero()
}

/// The point at horizontal azimuth `h` (unit, `h.z = 0`) of the great circle with unit normal
/// `m` on the upper hemisphere, unnormalised: `(|m_z| h, −sign(m_z) m·h)`. Its squared length is
/// `m_z² + (m·h)²`.
#[inline]
fn arc_point_unnormalised(m: Vec3, h: Vec3) -> Vec3 {
    let mh = m.x * h.x + m.y * h.y;
    let mz = m.z.abs();
    let z = if m.z < 0.0 { mh } else { -mh };
    Vec3::new(mz * h.x, mz * h.y, z)
}

/// `(r², z²)` of the point of great circle `m` at azimuth `h`: `(m_z², (m·h)²) / (m_z² + (m·h)²)`,
/// each from its own numerator so that neither loses digits near 0.
#[inline]
fn arc_r2_z2(m: Vec3, h: Vec3) -> (f32, f32) {
    let mh = m.x * h.x + m.y * h.y;
    let (a, b) = (m.z * m.z, mh * mh);
    let d = a + b;
    if d > 0.0 { (a / d, b / d) } else { (0.0, 1.0) }
}

/// `h` rotated counter-clockwise about +z by `phi`.
#[inline]
fn rotate(h: Vec3, phi: f32) -> Vec3 {
    let (s, c) = phi.sin_cos();
    Vec3::new(c * h.x - s * h.y, s * h.x + c * h.y, 0.0)
}

/// Azimuth of `v` measured counter-clockwise from the horizontal unit vector `h`, in
/// `[−π/2, 3π/2)` (the polygon spans at most π from its first vertex, so rounding below 0 stays
/// near 0 and rounding past π stays near π).
#[inline]
fn azimuth_from(h: Vec3, v: Vec3) -> f32 {
    let a = atan2(h.x * v.y - h.y * v.x, h.x * v.x + h.y * v.y);
    if a < -std::f32::consts::FRAC_PI_2 {
        a + std::f32::consts::TAU
    } else {
        a
    }
}

/// One wedge of the partition with the zenith outside: azimuths `phi0..phi1` (from the chains'
/// reference direction `h`), the outer arc on great circle `mo` from its point `o0` at `phi0`, the
/// inner one on `mi` from `i0`.
#[derive(Clone, Copy, Debug)]
struct Wedge {
    h: Vec3,
    phi0: f32,
    phi1: f32,
    mo: Vec3,
    o0: Vec3,
    mi: Vec3,
    i0: Vec3,
}

impl Wedge {
    /// `C(φ)`: the wedge's projected area between `phi0` and the azimuth `hp` (a unit horizontal
    /// vector).
    #[inline]
    fn cdf(&self, hp: Vec3) -> f32 {
        let o = arc_point_unnormalised(self.mo, hp).normalize_or_zero();
        let i = arc_point_unnormalised(self.mi, hp).normalize_or_zero();
        0.5 * (self.mo.z.abs() * angle(self.o0, o) - self.mi.z.abs() * angle(self.i0, i))
    }

    /// `C'(φ) = ½ (r_o² − r_i²)`, written as `½ (z_i² − z_o²)` where that keeps more digits.
    #[inline]
    fn density(&self, hp: Vec3) -> f32 {
        let (ro, zo) = arc_r2_z2(self.mo, hp);
        let (ri, zi) = arc_r2_z2(self.mi, hp);
        if ro < 0.5 {
            0.5 * (ro - ri)
        } else {
            0.5 * (zi - zo)
        }
    }

    /// The azimuth where `C` reaches `target` (`0 ≤ target ≤ area`), and the Newton steps taken
    /// (for the test of the cap).
    fn solve(&self, target: f32, area: f32) -> (f32, u32) {
        let width = self.phi1 - self.phi0;
        // Start from the inverse for a density linear between the ends.
        let f0 = self.density(rotate(self.h, self.phi0)).max(0.0);
        let f1 = self.density(rotate(self.h, self.phi1)).max(0.0);
        let t = if area > 0.0 {
            (target / area).clamp(0.0, 1.0)
        } else {
            0.5
        };
        let den = f0 + safe_sqrt((1.0 - t) * f0 * f0 + t * f1 * f1);
        let x = if den > 0.0 { t * (f0 + f1) / den } else { t };
        let (mut lo, mut hi) = (self.phi0, self.phi1);
        let mut phi = self.phi0 + x.clamp(0.0, 1.0) * width;
        for step in 1..=NEWTON_STEPS {
            let hp = rotate(self.h, phi);
            let f = self.cdf(hp) - target;
            if f > 0.0 {
                hi = phi;
            } else {
                lo = phi;
            }
            let newton = phi - f / self.density(hp);
            // A step below the tolerance ends it (also one that rounds to nothing at the bracket's
            // end; NaN, where the density is 0, fails the test), and so does a bracket narrower
            // than it (where the rounding of `C` points Newton out of it).
            if (newton - phi).abs() <= NEWTON_TOLERANCE * width {
                return (newton.clamp(lo, hi), step);
            }
            if hi - lo <= NEWTON_TOLERANCE * width {
                return (0.5 * (lo + hi), step);
            }
            // Outside the bracket: bisect.
            phi = if newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
        }
        (phi, NEWTON_STEPS)
    }

    /// The direction at azimuth `phi` whose `r²` is the fraction `uy` of the way from the inner
    /// arc's to the outer arc's.
    #[inline]
    fn lift(&self, phi: f32, uy: f32) -> Vec3 {
        let hp = rotate(self.h, phi);
        let (ro, zo) = arc_r2_z2(self.mo, hp);
        let (ri, zi) = arc_r2_z2(self.mi, hp);
        let r = safe_sqrt(ri + uy * (ro - ri));
        let z = safe_sqrt(zi + uy * (zo - zi));
        Vec3::new(r * hp.x, r * hp.y, z)
    }
}

impl ProjectedPolygon {
    /// The polygon with vertex vectors `w` (from the receiver, in its local frame; any length,
    /// convex, at most `PSA_MAX_VERTICES − 1` of them, either winding) clipped to `z ≥ 0`. `None`
    /// where nothing of it is above the horizon (fewer than three distinct vertices remain).
    pub fn new(w: &[Vec3]) -> Option<ProjectedPolygon> {
        debug_assert!(w.len() < PSA_MAX_VERTICES);
        let mut clipped = [Vec3::ZERO; PSA_MAX_VERTICES];
        let mut k = 0;
        let mut push = |x: Vec3| {
            if k < PSA_MAX_VERTICES {
                clipped[k] = x;
                k += 1;
            }
        };
        for (i, &a) in w.iter().enumerate() {
            let b = w[(i + 1) % w.len()];
            if a.z >= 0.0 {
                push(a);
            }
            // Strictly across: a vertex on the plane is kept as it is, not doubled.
            if (a.z > 0.0 && b.z < 0.0) || (a.z < 0.0 && b.z > 0.0) {
                let t = a.z / (a.z - b.z);
                let x = a + t * (b - a);
                push(Vec3::new(x.x, x.y, 0.0));
            }
        }
        let mut v = [Vec3::ZERO; PSA_MAX_VERTICES];
        let mut n = 0;
        for x in &clipped[..k] {
            let d = x.normalize_or_zero();
            if d != Vec3::ZERO && (n == 0 || d != v[n - 1]) {
                v[n] = d;
                n += 1;
            }
        }
        if n > 1 && v[n - 1] == v[0] {
            n -= 1;
        }
        if n < 3 {
            return None;
        }
        let (mut area, mut abs_sum) = (0.0, 0.0);
        for i in 0..n {
            let s = sector(v[i], v[(i + 1) % n]);
            area += s;
            abs_sum += s.abs();
        }
        if area < 0.0 {
            v[..n].reverse();
            area = -area;
        }
        // Outer edges run counter-clockwise (positive sector), inner ones clockwise.
        let outer = |i: usize| sector(v[i % n], v[(i + 1) % n]) > 0.0;
        let chains = if (0..n).all(|i| sector(v[i], v[(i + 1) % n]) >= 0.0) {
            None
        } else {
            let start = (0..n).find(|&i| outer(i) && !outer(i + n - 1));
            let end = (0..n).find(|&i| !outer(i) && outer(i + n - 1));
            start.zip(end)
        };
        Some(ProjectedPolygon {
            v,
            n,
            area,
            abs_sum,
            chains,
        })
    }

    /// The projected solid angle Ω⊥ of the clipped polygon.
    #[inline]
    pub fn area(&self) -> f32 {
        self.area
    }

    /// `Σ|S_e|`, the magnitudes of the sectors Lambert's formula sums.
    #[inline]
    pub fn abs_sum(&self) -> f32 {
        self.abs_sum
    }

    /// The clipped polygon's unit vertices, counter-clockwise about +z.
    #[inline]
    pub fn vertices(&self) -> &[Vec3] {
        &self.v[..self.n]
    }

    /// Whether the zenith is inside the polygon (or on its boundary).
    #[inline]
    pub fn contains_zenith(&self) -> bool {
        self.chains.is_none()
    }

    /// Whether it is accurate to sample it (see the module doc): [`conditioned`] of its own sums.
    #[inline]
    pub fn well_conditioned(&self) -> bool {
        conditioned(self.area, self.abs_sum)
    }

    /// The density `cos θ / Ω⊥` of local direction `w` (unit; 0 below the horizon). Inside the
    /// polygon only: the caller knows whether `w` hits it.
    #[inline]
    pub fn pdf(&self, w: Vec3) -> f32 {
        w.z.max(0.0) / self.area
    }

    /// The chains' reference direction: the horizontal unit vector of the first vertex of the
    /// outer chain.
    #[inline]
    fn reference(&self, start: usize) -> Vec3 {
        let s = self.v[start];
        Vec3::new(s.x, s.y, 0.0).normalize_or_zero()
    }

    /// Calls `visit(wedge, area)` for each wedge of the partition with the zenith outside, in
    /// order of azimuth, until it returns `true`; returns whether one did.
    fn wedges(&self, start: usize, end: usize, mut visit: impl FnMut(&Wedge, f32) -> bool) -> bool {
        let n = self.n;
        let h = self.reference(start);
        let (mut io, mut ii) = (start, start);
        let (mut o0, mut i0) = (self.v[start], self.v[start]);
        let mut phi0 = 0.0f32;
        let phi_end = azimuth_from(h, self.v[end]);
        // Each step advances at least one chain; together they have n edges.
        for _ in 0..n {
            if io == end && ii == end {
                break;
            }
            let (no, ni) = ((io + 1) % n, (ii + n - 1) % n);
            let phi_o = if io == end {
                f32::INFINITY
            } else if no == end {
                phi_end
            } else {
                azimuth_from(h, self.v[no])
            };
            let phi_i = if ii == end {
                f32::INFINITY
            } else if ni == end {
                phi_end
            } else {
                azimuth_from(h, self.v[ni])
            };
            let mo = arc_normal(self.v[io], self.v[no]);
            let mi = arc_normal(self.v[ii], self.v[ni]);
            let phi1 = phi_o.min(phi_i).max(phi0);
            let h1 = rotate(h, phi1);
            // A chain that has arrived (only where rounding disorders the azimuths) stays put.
            let o1 = if io == end {
                o0
            } else if phi_o <= phi_i {
                self.v[no]
            } else {
                arc_point_unnormalised(mo, h1).normalize_or_zero()
            };
            let i1 = if ii == end {
                i0
            } else if phi_i <= phi_o {
                self.v[ni]
            } else {
                arc_point_unnormalised(mi, h1).normalize_or_zero()
            };
            let w = Wedge {
                h,
                phi0,
                phi1,
                mo,
                o0,
                mi,
                i0,
            };
            let area = 0.5 * (mo.z.abs() * angle(o0, o1) - mi.z.abs() * angle(i0, i1));
            if visit(&w, area) {
                return true;
            }
            if phi_o <= phi_i {
                io = no;
            }
            if phi_i <= phi_o {
                ii = ni;
            }
            (o0, i0, phi0) = (o1, i1, phi1);
        }
        false
    }

    /// The local direction (unit, `z ≥ 0`) for `u ∈ [0,1)²`, distributed as `cos θ / Ω⊥` over
    /// the polygon.
    pub fn sample(&self, u: Vec2) -> Vec3 {
        self.sample_steps(u).0
    }

    /// [`ProjectedPolygon::sample`] and the Newton steps it took (0 around the zenith), which
    /// the tests count.
    pub(crate) fn sample_steps(&self, u: Vec2) -> (Vec3, u32) {
        let target = u.x * self.area;
        let Some((start, end)) = self.chains else {
            return (self.sample_around_zenith(target, u.y), 0);
        };
        let mut acc = 0.0;
        let mut last: Option<(Wedge, f32)> = None;
        let mut out = None;
        self.wedges(start, end, |w, area| {
            if area > 0.0 {
                last = Some((*w, area));
                if target < acc + area {
                    let (phi, steps) = w.solve(target - acc, area);
                    out = Some((w.lift(phi, u.y), steps));
                    return true;
                }
                acc += area;
            }
            false
        });
        if let Some(d) = out {
            return d;
        }
        // Rounding left `target` past the last wedge: its far end.
        match last {
            Some((w, area)) => {
                let (phi, steps) = w.solve(area, area);
                (w.lift(phi, u.y), steps)
            }
            None => (self.v[start], 0),
        }
    }

    /// [`ProjectedPolygon::sample`] with the zenith inside: the edge's sector by area, the point
    /// at that fraction of its arc (sector area is linear in arc length), then `r²` uniform
    /// between the origin and that point.
    fn sample_around_zenith(&self, target: f32, uy: f32) -> Vec3 {
        let n = self.n;
        let mut acc = 0.0;
        let mut chosen = None;
        for i in 0..n {
            let (a, b) = (self.v[i], self.v[(i + 1) % n]);
            let s = sector(a, b);
            if s <= 0.0 {
                continue;
            }
            chosen = Some((a, b, ((target - acc) / s).clamp(0.0, 1.0)));
            if target < acc + s {
                break;
            }
            acc += s;
        }
        let Some((a, b, f)) = chosen else {
            return Vec3::Z;
        };
        let (sin, cos) = (f * angle(a, b)).sin_cos();
        let e = b - a;
        let t = (e - e.dot(a) * a).normalize_or_zero();
        let x = cos * a + sin * t;
        let s = uy.sqrt();
        Vec3::new(s * x.x, s * x.y, safe_sqrt((1.0 - uy) + uy * x.z * x.z))
    }

    /// The `u` that [`ProjectedPolygon::sample`] maps to local direction `w` (unit, in the
    /// polygon); `None` where `w` is outside the partition (off the polygon by more than rounding).
    pub fn invert(&self, w: Vec3) -> Option<Vec2> {
        let h = Vec3::new(w.x, w.y, 0.0).normalize_or_zero();
        let r2 = w.x * w.x + w.y * w.y;
        let Some((start, end)) = self.chains else {
            return self.invert_around_zenith(w, h, r2);
        };
        let mut acc = 0.0;
        let phi_w = azimuth_from(self.reference(start), w);
        let mut out = None;
        self.wedges(start, end, |wedge, area| {
            if phi_w >= wedge.phi0 && phi_w <= wedge.phi1 && wedge.phi1 > wedge.phi0 {
                let c = wedge.cdf(h);
                let (ro, _) = arc_r2_z2(wedge.mo, h);
                let (ri, _) = arc_r2_z2(wedge.mi, h);
                let uy = if ro > ri { (r2 - ri) / (ro - ri) } else { 0.5 };
                out = Some(Vec2::new((acc + c) / self.area, uy));
                return true;
            }
            acc += area.max(0.0);
            false
        });
        out.map(|u| u.clamp(Vec2::ZERO, Vec2::ONE))
    }

    /// [`ProjectedPolygon::invert`] with the zenith inside.
    fn invert_around_zenith(&self, w: Vec3, h: Vec3, r2: f32) -> Option<Vec2> {
        if h == Vec3::ZERO {
            return Some(Vec2::ZERO);
        }
        let n = self.n;
        let mut acc = 0.0;
        for i in 0..n {
            let (a, b) = (self.v[i], self.v[(i + 1) % n]);
            let s = sector(a, b);
            // The edge whose azimuth range holds w's.
            let inside = a.x * w.y - a.y * w.x >= 0.0 && w.x * b.y - w.y * b.x >= 0.0;
            if s > 0.0 && inside {
                let m = arc_normal(a, b);
                let x = arc_point_unnormalised(m, h).normalize_or_zero();
                let ux = (acc + 0.5 * m.z.abs() * angle(a, x)) / self.area;
                let (rx, _) = arc_r2_z2(m, h);
                let uy = if rx > 0.0 { r2 / rx } else { 0.0 };
                return Some(Vec2::new(ux, uy).clamp(Vec2::ZERO, Vec2::ONE));
            }
            acc += s.max(0.0);
        }
        None
    }
}

/// Whether a projected solid angle `area` summed from sectors of total magnitude `abs_sum` is
/// accurate enough to sample by: positive, and `abs_sum ≤ MAX_CONDITION · area`. Sums over
/// several polygons (a triangulated light) are judged the same way.
#[inline]
pub fn conditioned(area: f32, abs_sum: f32) -> bool {
    area > 0.0 && abs_sum <= MAX_CONDITION * area
}

#[cfg(test)]
#[path = "projected_solid_angle_tests.rs"]
mod tests;
