//! The histogram's domain: spherical coordinates (φ, v) with the versine `v = 1 − cos θ` about an
//! axis, so that `dω = dφ dv` (a constant Jacobian: Mitsuba's (φ, cos θ) domain) and every cell
//! is a rectangle in (φ, v) that quadrature integrates without a change of variables.
//!
//! The versine instead of `cos θ` keeps directions within 1e-4 rad of the axis apart in f64.
//! Rows are equal-area over the sphere by default. A *cap* spends half the rows inside a cone
//! of half-angle θc about the axis, uniform in θ there, and the other half equal-area outside it:
//! small lights and narrow lobes then cover thousands of cells instead of a few, and uniform-θ
//! rows resolve a peak at the axis radially. Cells need not have equal areas for the χ² test;
//! what matters is that each cell's expected count is integrated accurately.
//!
//! In the *half-vector* space of a BSDF with outgoing `wo`, a direction `wi` is histogrammed by
//! its half vector `h = (wo + wi)/|wo + wi|` and the density carries the Jacobian
//! `dωi/dωh = 4 (wo·h)`. Narrow GGX lobes are round bumps about the normal there at every
//! incidence angle, whereas in `wi` they become slivers thinner than any cell near grazing.

use glam::{DVec3, Vec3};
use std::f64::consts::{PI, TAU};

/// Which variable the histogram is over.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Space {
    /// The sampled direction itself.
    Direction,
    /// The half vector of the sampled direction with this (unit) `wo`.
    HalfVector(DVec3),
}

/// Spherical coordinates about an axis, optionally with a cap, in direction or half-vector space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Domain {
    /// Local → world: tangent, bitangent, axis.
    frame: [DVec3; 3],
    /// Half-angle θc of the cap, if the rows zoom on one.
    cap: Option<f64>,
    space: Space,
}

/// An orthonormal frame with `n` as its third axis (Duff et al. 2017), in f64.
fn frame_about(n: DVec3) -> [DVec3; 3] {
    let sign = 1.0f64.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    let s = DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    let t = DVec3::new(b, sign + n.y * n.y * a, -n.y);
    [s, t, n]
}

impl Domain {
    /// The whole sphere about +z, equal-area rows.
    pub fn sphere() -> Domain {
        Domain {
            frame: frame_about(DVec3::Z),
            cap: None,
            space: Space::Direction,
        }
    }

    /// Directions, with half the rows in the cone of half-angle `theta_c` about `axis`; the whole
    /// sphere about `axis` if the cone is (nearly) the whole sphere.
    pub fn cap(axis: Vec3, theta_c: f64) -> Domain {
        let axis = axis.as_dvec3().normalize();
        Domain {
            frame: frame_about(axis),
            cap: (theta_c < 0.9 * PI).then_some(theta_c.max(1e-6)),
            space: Space::Direction,
        }
    }

    /// Half vectors with the outgoing direction `wo` about the local normal +z, with a cap of
    /// half-angle `theta_c` if given.
    pub fn half_vector(wo: Vec3, theta_c: Option<f64>) -> Domain {
        Domain {
            frame: frame_about(DVec3::Z),
            cap: theta_c.filter(|&t| t < 0.9 * PI),
            space: Space::HalfVector(wo.as_dvec3().normalize()),
        }
    }

    /// The `n + 1` row boundaries in `v = 1 − cos θ`, from 0 to 2 (`n` even for a cap).
    pub fn row_edges(&self, n: usize) -> Vec<f64> {
        match self.cap {
            None => (0..=n).map(|i| 2.0 * i as f64 / n as f64).collect(),
            Some(tc) => {
                let n_in = n / 2;
                let n_out = n - n_in;
                // 1 − cos θ = 2 sin²(θ/2): no cancellation for tiny caps.
                let versine = |t: f64| 2.0 * (0.5 * t).sin().powi(2);
                let vc = versine(tc);
                let mut e: Vec<f64> = (0..n_in)
                    .map(|i| versine(tc * i as f64 / n_in as f64))
                    .collect();
                e.extend((0..=n_out).map(|j| vc + (2.0 - vc) * j as f64 / n_out as f64));
                e
            }
        }
    }

    /// The coordinates `(φ ∈ [0, 2π), v ∈ [0, 2])` of a sampled direction, or `None` for a
    /// direction with no half vector (`wi = −wo`, a set of measure zero).
    pub fn coords(&self, w: Vec3) -> Option<(f64, f64)> {
        let w = w.as_dvec3().normalize();
        let d = match self.space {
            Space::Direction => w,
            Space::HalfVector(wo) => (wo + w).try_normalize()?,
        };
        let [s, t, n] = self.frame;
        let (x, y, z) = (d.dot(s), d.dot(t), d.dot(n));
        // Near the axis, 1 − z has lost the digits that x² + y² still holds.
        let v = if z > 0.0 {
            (x * x + y * y) / (1.0 + z)
        } else {
            1.0 - z
        };
        Some((y.atan2(x).rem_euclid(TAU), v.clamp(0.0, 2.0)))
    }

    /// The unit vector (direction or half vector) at `(φ, v)`, in world coordinates.
    fn point(&self, phi: f64, v: f64) -> DVec3 {
        let sin_theta = (v * (2.0 - v)).max(0.0).sqrt();
        let (sp, cp) = phi.sin_cos();
        let [s, t, n] = self.frame;
        s * (sin_theta * cp) + t * (sin_theta * sp) + n * (1.0 - v)
    }

    /// The density to integrate over `dφ dv` at `(φ, v)`: the sampler's pdf, times the
    /// half-vector Jacobian `4 (wo·h)` in half-vector space (zero for `wo·h ≤ 0`, which no
    /// sample's half vector reaches).
    pub fn density(&self, pdf: &dyn Fn(Vec3) -> f32, phi: f64, v: f64) -> f64 {
        let p = self.point(phi, v);
        match self.space {
            Space::Direction => pdf(p.normalize().as_vec3()) as f64,
            Space::HalfVector(wo) => {
                let c = wo.dot(p);
                if c <= 0.0 {
                    return 0.0;
                }
                let wi = (2.0 * c * p - wo).normalize();
                pdf(wi.as_vec3()) as f64 * 4.0 * c
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coords_invert_point() {
        for d in [
            Domain::sphere(),
            Domain::cap(Vec3::new(0.3, -0.5, 0.8), 0.01),
        ] {
            for (phi, v) in [(0.1, 1e-5), (3.0, 0.5), (6.0, 1.9)] {
                // f32 directions: φ to ~1e-7/sin θ, v to ~1e-7·sin θ.
                let w = d.point(phi, v).as_vec3();
                let (p2, v2) = d.coords(w).unwrap();
                assert!(
                    (p2 - phi).abs() < 1e-4 && (v2 - v).abs() < 1e-6 * v.max(0.1),
                    "{phi} {v}: {p2} {v2}"
                );
            }
        }
    }

    #[test]
    fn cap_rows_split_at_the_cap() {
        let d = Domain::cap(Vec3::Z, 0.2);
        let e = d.row_edges(8);
        assert_eq!(e.len(), 9);
        assert!((e[4] - (1.0 - 0.2f64.cos())).abs() < 1e-15 && e[8] == 2.0 && e[0] == 0.0);
        assert!(e.windows(2).all(|w| w[0] < w[1]));
    }

    #[test]
    fn half_vector_jacobian_integrates_to_one() {
        // A uniform-sphere density integrated in half-vector space is still 1.
        let d = Domain::half_vector(Vec3::new(0.6, 0.0, 0.8), None);
        let n = 400;
        let mut sum = 0.0;
        for i in 0..n {
            for j in 0..n {
                let (phi, v) = (
                    TAU * (j as f64 + 0.5) / n as f64,
                    2.0 * (i as f64 + 0.5) / n as f64,
                );
                sum += d.density(&|_| 0.25 / std::f32::consts::PI, phi, v);
            }
        }
        sum *= TAU * 2.0 / (n * n) as f64;
        assert!((sum - 1.0).abs() < 1e-3, "{sum}");
    }
}
