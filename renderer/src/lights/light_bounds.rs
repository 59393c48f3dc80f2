//! Spatial and directional bounds of emitters, and the importance of a bounded set of emitters
//! to a receiving point (after pbrt-v4's `LightBounds`): the box the emitters lie in, their total
//! power, and a cone of normals `(w, θo)` from which they emit into a further angle `θe`.
//! [`crate::lights::light_bvh::LightBvh`] builds its nodes from these.
//! WGSL twin: `lights/light_bvh.wgsl` (`light_bounds_importance`).

use super::Light;
use crate::math::safe_sqrt;
use glam::Vec3;
use std::f32::consts::{FRAC_PI_2, PI};

/// How much the emission cone of a spot or projector is widened in the bounds (in its cosine):
/// any wider cone keeps selection unbiased, a narrower one would not.
const DELTA_CONE_SLACK: f32 = 1e-4;

/// Bounds of one emitter or of a set of them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightBounds {
    /// Lower corner of the box holding the emitters.
    pub lo: Vec3,
    /// Upper corner of the box.
    pub hi: Vec3,
    /// Total power ([`Light::power`], the weight of power selection too).
    pub phi: f32,
    /// Axis of the cone of emitting normals (unit).
    pub w: Vec3,
    /// cos θo: the normals lie within θo of `w`.
    pub cos_theta_o: f32,
    /// cos θe: each point emits within θe of its normal (π/2 for the one-sided area lights).
    pub cos_theta_e: f32,
    /// Whether the emitters emit on both sides of their normals (none of this renderer's lights
    /// do yet; kept so a two-sided emitter has a place).
    pub two_sided: bool,
}

impl LightBounds {
    /// The bounds of `light` (a point light's box is its point); `None` for the lights at
    /// infinity, directional ones included (sampled apart), and for lights
    /// without positive finite power (never selected, as with power selection).
    pub fn of(light: &Light) -> Option<LightBounds> {
        let phi = light.power();
        if !(phi > 0.0 && phi.is_finite()) {
            return None;
        }
        let planar = |points: &mut dyn Iterator<Item = Vec3>, n: Vec3| {
            let (lo, hi) = points.fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), q| {
                (lo.min(q), hi.max(q))
            });
            // A plane's normals are one direction (θo = 0) emitting into the hemisphere.
            (lo, hi, n, 1.0, 0.0)
        };
        let (lo, hi, w, cos_theta_o, cos_theta_e) = match light {
            Light::Triangle(l) => planar(&mut l.v.iter().copied(), l.n),
            Light::Polygon(l) => planar(&mut l.vertices.iter().copied(), l.n),
            Light::Quad(l) => {
                let c = [
                    l.corner,
                    l.corner + l.edge_u,
                    l.corner + l.edge_v,
                    l.corner + l.edge_u + l.edge_v,
                ];
                planar(&mut c.into_iter(), l.n)
            }
            Light::Disk(l) => {
                // The disk's extent along axis i is r·sin(angle between n and axis i).
                let n = l.disk.n;
                let e = l.disk.radius * (Vec3::ONE - n * n).max(Vec3::ZERO).map(f32::sqrt);
                (l.disk.center - e, l.disk.center + e, n, 1.0, 0.0)
            }
            Light::Sphere(l) => {
                let r = Vec3::splat(l.sphere.radius);
                // Normals in every direction (θo = π), each emitting into its hemisphere.
                (l.sphere.center - r, l.sphere.center + r, Vec3::Z, -1.0, 0.0)
            }
            // A point emits in every direction: its "normals" fill the sphere.
            Light::Point(l) => (l.position, l.position, Vec3::Z, -1.0, 0.0),
            // Spot and projector: one normal (the axis), emitting within the cutoff or the
            // frustum's corner of it. The cone is widened by DELTA_CONE_SLACK so that rounding
            // never gives a zero importance where the light's own test lets light through.
            Light::Spot(l) => {
                let cos_e = (l.cos_cutoff - DELTA_CONE_SLACK).max(-1.0);
                (l.position, l.position, l.frame.n, 1.0, cos_e)
            }
            Light::Projector(l) => {
                let cos_corner = 1.0 / (1.0 + l.tan_half.length_squared()).sqrt();
                let cos_e = (cos_corner - DELTA_CONE_SLACK).max(-1.0);
                (l.position, l.position, l.frame.n, 1.0, cos_e)
            }
            Light::Background(_) | Light::Envmap(_) | Light::Directional(_) => return None,
        };
        let finite = lo.is_finite() && hi.is_finite() && w.is_finite();
        finite.then_some(LightBounds {
            lo,
            hi,
            phi,
            w,
            cos_theta_o,
            cos_theta_e,
            two_sided: false,
        })
    }

    /// The centre of the box.
    #[inline]
    pub fn centroid(&self) -> Vec3 {
        0.5 * (self.lo + self.hi)
    }

    /// Surface area of the box (0 for a point).
    pub fn surface_area(&self) -> f32 {
        let d = (self.hi - self.lo).max(Vec3::ZERO);
        2.0 * (d.x * d.y + d.y * d.z + d.z * d.x)
    }

    /// Bounds of both sets: the boxes' union, the powers' sum, the smallest cone holding both
    /// cones of normals, the wider emission angle.
    pub fn union(&self, b: &LightBounds) -> LightBounds {
        let (w, cos_theta_o) = cone_union(self.w, self.cos_theta_o, b.w, b.cos_theta_o);
        LightBounds {
            lo: self.lo.min(b.lo),
            hi: self.hi.max(b.hi),
            phi: self.phi + b.phi,
            w,
            cos_theta_o,
            cos_theta_e: self.cos_theta_e.min(b.cos_theta_e),
            two_sided: self.two_sided || b.two_sided,
        }
    }

    /// How much the emitters may contribute at `p`, a receiver with normal `n` (zero: no
    /// normal, e.g. a medium): power / squared distance, times the cosine at the emitters of the
    /// smallest angle between a bounded normal and the direction to `p`, times the receiver's
    /// |cos| of the smallest angle to the box (|cos|: a transmitting receiver takes light from
    /// both sides). The angles are widened by the cone the box subtends from `p`, so this bounds
    /// every emitter inside; the squared distance is clamped below by the squared half diagonal
    /// (pbrt-v4 clamps d² by the half diagonal itself, which mixes units), so points near or in
    /// the box do not blow up. 0 where no emitter can face `p`.
    pub fn importance(&self, p: Vec3, n: Vec3) -> f32 {
        let pc = self.centroid();
        let r2 = 0.25 * (self.hi - self.lo).length_squared();
        let d2 = p.distance_squared(pc);
        if d2 <= r2 {
            // Inside the bounding sphere: every direction may reach p, at the clamped distance.
            return self.phi / r2.max(d2);
        }
        let wi = (p - pc) / d2.sqrt();
        let mut cos_w = self.w.dot(wi);
        if self.two_sided {
            cos_w = cos_w.abs();
        }
        let sin_w = safe_sqrt(1.0 - cos_w * cos_w);
        // The bounding sphere subtends θb from p.
        let cos_b = safe_sqrt(1.0 - r2 / d2);
        let sin_b = safe_sqrt(r2 / d2);
        // θ' = max(0, θw − θo − θb): the smallest angle between a normal and a direction to p.
        let sin_o = safe_sqrt(1.0 - self.cos_theta_o * self.cos_theta_o);
        let (cos_x, sin_x) = angle_sub(cos_w, sin_w, self.cos_theta_o, sin_o);
        let (cos_p, _) = angle_sub(cos_x, sin_x, cos_b, sin_b);
        if cos_p <= self.cos_theta_e {
            return 0.0;
        }
        let mut importance = self.phi * cos_p / d2;
        if n != Vec3::ZERO {
            let cos_i = n.dot(wi).abs();
            let sin_i = safe_sqrt(1.0 - cos_i * cos_i);
            importance *= angle_sub(cos_i, sin_i, cos_b, sin_b).0;
        }
        importance.max(0.0)
    }
}

/// `(cos, sin)` of max(0, a − b) for angles a, b ∈ [0, π] given by their cosines and sines.
#[inline]
fn angle_sub(cos_a: f32, sin_a: f32, cos_b: f32, sin_b: f32) -> (f32, f32) {
    if cos_a > cos_b {
        (1.0, 0.0)
    } else {
        (cos_a * cos_b + sin_a * sin_b, sin_a * cos_b - cos_a * sin_b)
    }
}

/// The smallest cone holding the cones `(wa, cos θa)` and `(wb, cos θb)` (pbrt-v4's
/// `DirectionCone::Union`); `cos θ = −1` is the whole sphere.
fn cone_union(wa: Vec3, cos_a: f32, wb: Vec3, cos_b: f32) -> (Vec3, f32) {
    // Without trigonometry when one cone is a single direction inside the other (most unions
    // of a build: planar lights into a node's cone); θd ≤ θa ⇔ cos θd ≥ cos θa.
    if cos_b == 1.0 && wa.dot(wb) >= cos_a {
        return (wa, cos_a);
    }
    if cos_a == 1.0 && wa.dot(wb) >= cos_b {
        return (wb, cos_b);
    }
    let theta_a = cos_a.clamp(-1.0, 1.0).acos();
    let theta_b = cos_b.clamp(-1.0, 1.0).acos();
    let theta_d = angle_between(wa, wb);
    if (theta_d + theta_b).min(PI) <= theta_a {
        return (wa, cos_a);
    }
    if (theta_d + theta_a).min(PI) <= theta_b {
        return (wb, cos_b);
    }
    let theta_o = 0.5 * (theta_a + theta_d + theta_b);
    if theta_o >= PI {
        return (wa, -1.0);
    }
    // Rotate wa towards wb by θo − θa about their common perpendicular.
    let k = wa.cross(wb);
    if k.length_squared() == 0.0 {
        return (wa, -1.0);
    }
    let k = k.normalize();
    let theta_r = theta_o - theta_a;
    let w = wa * theta_r.cos() + k.cross(wa) * theta_r.sin();
    (w.normalize(), theta_o.cos())
}

/// The angle between unit vectors, accurate near 0 and π.
#[inline]
fn angle_between(a: Vec3, b: Vec3) -> f32 {
    if a.dot(b) < 0.0 {
        PI - 2.0 * (0.5 * (a + b).length()).min(1.0).asin()
    } else {
        2.0 * (0.5 * (b - a).length()).min(1.0).asin()
    }
}

/// pbrt-v4's orientation-aware surface-area cost of a node holding `b` split along `axis` of the
/// parent box's diagonal `diag`: power × the solid angle of the emission cone (`M_Ω`) × box
/// area × how elongated the parent is across the axis (`K_r`, which favours cuts across the
/// long side).
pub(crate) fn split_cost(b: &LightBounds, diag: Vec3, axis: usize) -> f32 {
    let theta_o = b.cos_theta_o.clamp(-1.0, 1.0).acos();
    let theta_e = b.cos_theta_e.clamp(-1.0, 1.0).acos();
    let theta_w = (theta_o + theta_e).min(PI);
    let sin_o = safe_sqrt(1.0 - b.cos_theta_o * b.cos_theta_o);
    let m_omega = 2.0 * PI * (1.0 - b.cos_theta_o)
        + FRAC_PI_2
            * (2.0 * theta_w * sin_o - (theta_o - 2.0 * theta_w).cos() - 2.0 * theta_o * sin_o
                + b.cos_theta_o);
    let kr = diag.max_element() / diag[axis];
    b.phi * m_omega * kr * b.surface_area()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad_bounds(z: f32, n: Vec3) -> LightBounds {
        LightBounds {
            lo: Vec3::new(-0.5, -0.5, z),
            hi: Vec3::new(0.5, 0.5, z),
            phi: 1.0,
            w: n,
            cos_theta_o: 1.0,
            cos_theta_e: 0.0,
            two_sided: false,
        }
    }

    /// A downward-facing emitter is important below it and not at all above it; the receiver's
    /// normal term is |cos| (a receiver facing away still counts: transmission) and small for a
    /// far receiver whose normal is perpendicular to the direction of the box.
    #[test]
    fn importance_sees_sides_and_distance() {
        let b = quad_bounds(1.0, -Vec3::Z);
        let below = b.importance(Vec3::new(0.0, 0.0, -1.0), Vec3::ZERO);
        let far_below = b.importance(Vec3::new(0.0, 0.0, -3.0), Vec3::ZERO);
        assert!(below > 0.0 && far_below > 0.0 && far_below < below);
        assert_eq!(b.importance(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO), 0.0);
        let up = b.importance(Vec3::new(0.0, 0.0, -1.0), Vec3::Z);
        let down = b.importance(Vec3::new(0.0, 0.0, -1.0), -Vec3::Z);
        assert_eq!(up, down);
        let grazing = b.importance(Vec3::new(0.0, 0.0, -10.0), Vec3::X);
        assert!(grazing < 0.1 * b.importance(Vec3::new(0.0, 0.0, -10.0), Vec3::Z));
    }

    /// The union of opposite cones is the sphere; of a cone with itself, the cone; of two thin
    /// cones 90° apart, a 45° cone between them.
    #[test]
    fn cone_union_bounds_both() {
        assert_eq!(cone_union(Vec3::Z, 1.0, -Vec3::Z, 1.0).1, -1.0);
        assert_eq!(cone_union(Vec3::Z, 0.5, Vec3::Z, 0.5), (Vec3::Z, 0.5));
        let (w, c) = cone_union(Vec3::Z, 1.0, Vec3::X, 1.0);
        assert!((c - std::f32::consts::FRAC_1_SQRT_2).abs() < 1e-6, "{c}");
        assert!(
            (w - Vec3::new(1.0, 0.0, 1.0).normalize()).length() < 1e-6,
            "{w}"
        );
    }

    /// A point light's bounds are its point, emitting everywhere; a spot's importance is zero
    /// exactly outside its cutoff cone (within the slack) and positive inside, so BVH selection
    /// never drops a spot where it lights a point; a projector's cone holds its frustum's corners.
    #[test]
    fn delta_lights_bounds_cover_where_they_emit() {
        use crate::lights::{PointLight, ProjectorLight, SpotLight};
        use crate::math::Frame;
        let frame = Frame {
            s: Vec3::X,
            t: Vec3::Y,
            n: Vec3::Z,
        };
        let point = Light::Point(PointLight {
            position: Vec3::new(1.0, 2.0, 3.0),
            intensity: Vec3::ONE,
        });
        let b = LightBounds::of(&point).unwrap();
        assert_eq!(
            (b.lo, b.hi),
            (Vec3::new(1.0, 2.0, 3.0), Vec3::new(1.0, 2.0, 3.0))
        );
        for d in [Vec3::X, -Vec3::Y, Vec3::Z, Vec3::new(-1.0, 1.0, -1.0)] {
            assert!(b.importance(b.lo + 2.0 * d, Vec3::ZERO) > 0.0, "{d}");
        }
        let spot = Light::Spot(SpotLight::new(
            Vec3::ZERO,
            frame,
            Vec3::ONE,
            30f32.to_radians(),
            10f32.to_radians(),
        ));
        let b = LightBounds::of(&spot).unwrap();
        for deg in [0.0f32, 10.0, 29.0, 29.9] {
            let t = deg.to_radians();
            let p = 3.0 * Vec3::new(t.sin(), 0.0, t.cos());
            assert!(b.importance(p, Vec3::ZERO) > 0.0, "inside at {deg}°");
        }
        for deg in [31.0f32, 90.0, 180.0] {
            let t = deg.to_radians();
            let p = 3.0 * Vec3::new(t.sin(), 0.0, t.cos());
            assert_eq!(b.importance(p, Vec3::ZERO), 0.0, "outside at {deg}°");
        }
        let projector = Light::Projector(ProjectorLight {
            position: Vec3::ZERO,
            frame,
            tan_half: glam::Vec2::new(0.5, 0.25),
            intensity: Vec3::ONE,
            selection: Vec3::ONE,
            texture: crate::geometry::primitive::NONE,
        });
        let b = LightBounds::of(&projector).unwrap();
        assert!(b.importance(Vec3::new(0.5, 0.25, 1.0) * 4.0, Vec3::ZERO) > 0.0);
        assert_eq!(b.importance(Vec3::new(0.0, 0.0, -1.0), Vec3::ZERO), 0.0);
        let directional = Light::Directional(crate::lights::DirectionalLight {
            direction: -Vec3::Y,
            irradiance: Vec3::ONE,
            scene_radius: 1.0,
        });
        assert!(
            LightBounds::of(&directional).is_none(),
            "sampled with the infinite lights"
        );
    }
}
