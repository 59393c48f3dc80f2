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
//!
//! ## Transmission: the generalised half-vector space
//!
//! A BSDF that transmits (an interface between the outside, index 1, where +z points and the
//! inside, index `ior`) sends `wi` to either side, so its histogram covers the whole sphere of
//! `wi` through two disjoint halves of the (φ, v) rectangle, each one the upper hemisphere of
//! microfacet normals `h` (facing +z) with its own versine `1 − cos θh`:
//!
//! * `v ∈ [0, 1)`, **reflection** (`wi` on the side of `wo`): `h = ±(wo + wi)/|wo + wi|`,
//!   `wi = 2(wo·h)h − wo`, `dωi/dωh = 4|wo·h|`. Every `wi` on wo's side has exactly one such `h`.
//! * `v ∈ [1, 2]`, **refraction** (`wi` on the other side): with η_o, η_i the indices on the sides
//!   of `wo` and `wi`, `h = ±(η_o wo + η_i wi)/|η_o wo + η_i wi|` (Walter et al. 2007 eq. 16).
//!   Given `h`, `η_o wo + η_i wi = λh` has two unit solutions `wi`, one on each side of the
//!   microfacet; the domain takes Snell's, the one with `(wo·h)(wi·h) < 0`:
//!   `λ = η_o(wo·h) − sign(wo·h)·√(η_i² − η_o²(1 − (wo·h)²))`, `wi = (λh − η_o wo)/η_i`.
//!   `H = η_o wo + η_i wi` moves on a sphere of radius η_i as `wi` moves, so a patch `dωi` sweeps
//!   `η_i² |wi·h| dωi` across the direction of `H`, seen from the origin at distance `|λ|`:
//!   `dωh = η_i² |wi·h| dωi / λ²`, i.e. `dωi/dωh = (η_o(wo·h) + η_i(wi·h))² / (η_i² |wi·h|)`.
//!   The refractions this reaches are those within `arccos(η_min/η_max)` of `−wo`; a sampled `wi`
//!   on the other side outside that cone (no microfacet refracts `wo` into it) still has coords (its
//!   generalised half vector), but the domain gives its cell no density for it: if the sampler's pdf
//!   is positive there, `∫pdf` misses that mass and the χ² harness fails the test.
//!
//! Cells whose `h` gives no `wi` of their half (total internal reflection; a reflection or a Snell
//! refraction that ends up on the wrong side of the macro surface) have density 0. In `h` the
//! density `pdf(wi(h))·dωi/dωh` is the visible-normal density times the Fresnel weight of the lobe:
//! smooth and round about +z for both lobes, from either side and at any incidence (a narrow
//! refraction lobe is far narrower than α in `wi` when η is near 1, and both kinds are slivers near
//! grazing). A cap zooms each half on its pole `h = +z` with half of that half's rows.

use glam::{DVec3, Vec3};
use std::f64::consts::{PI, TAU};

/// Which variable the histogram is over.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Space {
    /// The sampled direction itself.
    Direction,
    /// The half vector of the sampled direction with this (unit) `wo`.
    HalfVector(DVec3),
    /// Generalised half vectors of an interface seen from `wo`: reflection in `v < 1`,
    /// refraction in `v ≥ 1`, with the indices of the sides of `wo` and of a refracted `wi`.
    Generalised {
        /// The outgoing direction (unit).
        wo: DVec3,
        /// Index on the side of `wo`.
        eta_o: f64,
        /// Index on the other side.
        eta_i: f64,
    },
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

/// `n + 1` row boundaries in the versine from 0 to `v_end`: equal-area, or half of them uniform
/// in θ inside a cap of half-angle `cap` and the rest equal-area outside it.
fn rows(n: usize, cap: Option<f64>, v_end: f64) -> Vec<f64> {
    let n_in = n / 2;
    match cap {
        Some(tc) if n_in > 0 => {
            let n_out = n - n_in;
            // 1 − cos θ = 2 sin²(θ/2): no cancellation for tiny caps.
            let versine = |t: f64| 2.0 * (0.5 * t).sin().powi(2);
            let vc = versine(tc);
            let mut e: Vec<f64> = (0..n_in)
                .map(|i| versine(tc * i as f64 / n_in as f64))
                .collect();
            e.extend((0..=n_out).map(|j| vc + (v_end - vc) * j as f64 / n_out as f64));
            e
        }
        _ => (0..=n).map(|i| v_end * i as f64 / n as f64).collect(),
    }
}

/// Snell's refraction of `wo` (index `eta_o`) through the microfacet `h` into index `eta_i`: the
/// `wi` with `η_o wo + η_i wi = λh` on the other side of `h`, and `λ`; `None` under total
/// internal reflection or for `wo·h = 0`.
fn refract_through(wo: DVec3, h: DVec3, eta_o: f64, eta_i: f64) -> Option<(DVec3, f64)> {
    let c = wo.dot(h);
    let disc = eta_i * eta_i - eta_o * eta_o * (1.0 - c * c);
    if c == 0.0 || disc < 0.0 {
        return None;
    }
    let lambda = eta_o * c - c.signum() * disc.sqrt();
    Some(((lambda * h - eta_o * wo) / eta_i, lambda))
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

    /// Generalised half vectors (see the module doc) of an interface between index 1 (where +z
    /// points) and `ior`, seen from `wo` on either side, with a cap of half-angle `theta_c` about
    /// +z in each half if given.
    pub fn generalised_half_vector(wo: Vec3, ior: f32, theta_c: Option<f64>) -> Domain {
        let wo = wo.as_dvec3().normalize();
        let (eta_o, eta_i) = if wo.z > 0.0 {
            (1.0, ior as f64)
        } else {
            (ior as f64, 1.0)
        };
        Domain {
            frame: frame_about(DVec3::Z),
            cap: theta_c.filter(|&t| t < 0.45 * PI),
            space: Space::Generalised { wo, eta_o, eta_i },
        }
    }

    /// The `n + 1` row boundaries in `v`, from 0 to 2 (`n` even for a cap; a multiple of 4 in
    /// generalised half-vector space, whose halves `[0, 1]` and `[1, 2]` get `n/2` rows each).
    pub fn row_edges(&self, n: usize) -> Vec<f64> {
        match self.space {
            Space::Generalised { .. } => {
                let n_r = n / 2;
                let mut e = rows(n_r, self.cap, 1.0);
                e.extend(rows(n - n_r, self.cap, 1.0).iter().skip(1).map(|v| 1.0 + v));
                e
            }
            _ => rows(n, self.cap, 2.0),
        }
    }

    /// The coordinates `(φ ∈ [0, 2π), v ∈ [0, 2])` of a sampled direction, or `None` for a
    /// direction with no half vector (`wi = −wo`, a set of measure zero).
    pub fn coords(&self, w: Vec3) -> Option<(f64, f64)> {
        let w = w.as_dvec3().normalize();
        let d = match self.space {
            Space::Direction => w,
            Space::HalfVector(wo) => (wo + w).try_normalize()?,
            Space::Generalised { wo, eta_o, eta_i } => {
                let reflected = w.z * wo.z > 0.0;
                let h = if reflected {
                    wo + w
                } else {
                    eta_o * wo + eta_i * w
                };
                let h = h.try_normalize()?;
                let h = if h.z < 0.0 { -h } else { h };
                let (phi, v) = self.local_coords(h);
                // A reflection's h exactly on the horizon stays in the reflection half.
                let v = if reflected {
                    v.min(1.0 - f64::EPSILON)
                } else {
                    1.0 + v.min(1.0)
                };
                return Some((phi, v));
            }
        };
        Some(self.local_coords(d))
    }

    /// `(φ, v)` of the unit vector `d` in the frame.
    fn local_coords(&self, d: DVec3) -> (f64, f64) {
        let [s, t, n] = self.frame;
        let (x, y, z) = (d.dot(s), d.dot(t), d.dot(n));
        // Near the axis, 1 − z has lost the digits that x² + y² still holds.
        let v = if z > 0.0 {
            (x * x + y * y) / (1.0 + z)
        } else {
            1.0 - z
        };
        (y.atan2(x).rem_euclid(TAU), v.clamp(0.0, 2.0))
    }

    /// The unit vector (direction or half vector) at `(φ, v)`, in world coordinates.
    fn point(&self, phi: f64, v: f64) -> DVec3 {
        let sin_theta = (v * (2.0 - v)).max(0.0).sqrt();
        let (sp, cp) = phi.sin_cos();
        let [s, t, n] = self.frame;
        s * (sin_theta * cp) + t * (sin_theta * sp) + n * (1.0 - v)
    }

    /// The direction `wi` whose cell is `(φ, v)` and `dωi/dωh` there, in generalised half-vector
    /// space; `None` where no `wi` of that half has this half vector (see the module doc).
    fn generalised_wi(&self, phi: f64, v: f64) -> Option<(DVec3, f64)> {
        let Space::Generalised { wo, eta_o, eta_i } = self.space else {
            return None;
        };
        if v < 1.0 {
            let h = self.point(phi, v);
            let c = wo.dot(h);
            let wi = 2.0 * c * h - wo;
            (wi.z * wo.z > 0.0).then_some((wi.normalize(), 4.0 * c.abs()))
        } else {
            let h = self.point(phi, v - 1.0);
            let (wi, lambda) = refract_through(wo, h, eta_o, eta_i)?;
            let ci = wi.dot(h);
            (wi.z * wo.z < 0.0 && ci != 0.0)
                .then(|| (wi.normalize(), lambda * lambda / (eta_i * eta_i * ci.abs())))
        }
    }

    /// The density to integrate over `dφ dv` at `(φ, v)`: the sampler's pdf, times the
    /// half-vector Jacobian `4 (wo·h)` in half-vector space (zero for `wo·h ≤ 0`, which no
    /// sample's half vector reaches), or the reflection or refraction Jacobian `dωi/dωh` in
    /// generalised half-vector space.
    pub fn density(&self, pdf: &dyn Fn(Vec3) -> f32, phi: f64, v: f64) -> f64 {
        if let Space::Generalised { .. } = self.space {
            return self
                .generalised_wi(phi, v)
                .map_or(0.0, |(wi, jac)| pdf(wi.as_vec3()) as f64 * jac);
        }
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
            Space::Generalised { .. } => unreachable!("handled above"),
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

    /// Outgoing directions (outside, inside, near grazing) × IORs for the generalised space.
    fn generalised_domains() -> Vec<Domain> {
        let mut out = Vec::new();
        for ior in [1.1f32, 1.5, 2.4] {
            for deg in [0.0f32, 30.0, 60.0, 89.0] {
                let t = deg.to_radians();
                for z in [t.cos(), -t.cos()] {
                    let wo = Vec3::new(t.sin(), 0.0, z);
                    out.push(Domain::generalised_half_vector(wo, ior, None));
                }
            }
        }
        out
    }

    /// `∫∫ f dφ dv` over `[0, 2π) × [v0, v1]` by an `n × n` midpoint rule.
    fn integrate(f: &dyn Fn(f64, f64) -> f64, v0: f64, v1: f64, n: usize) -> f64 {
        let mut sum = 0.0;
        for i in 0..n {
            let v = v0 + (v1 - v0) * (i as f64 + 0.5) / n as f64;
            for j in 0..n {
                sum += f(TAU * (j as f64 + 0.5) / n as f64, v);
            }
        }
        sum * TAU * (v1 - v0) / (n * n) as f64
    }

    /// Every cell point with a `wi` maps back to itself, in both halves.
    #[test]
    fn generalised_coords_invert_wi() {
        for d in generalised_domains() {
            let mut hits = [0; 2];
            for phi in [0.05, 1.0, 3.1, 4.0, 6.2] {
                for v in [1e-5, 0.01, 0.3, 0.7, 0.99, 1.0 + 1e-5, 1.01, 1.3, 1.7, 1.99] {
                    let Some((wi, _)) = d.generalised_wi(phi, v) else {
                        continue;
                    };
                    hits[(v >= 1.0) as usize] += 1;
                    let (p2, v2) = d.coords(wi.as_vec3()).unwrap();
                    let dv = (v2 - v).abs();
                    // f32 directions: φ to ~1e-7/sin θh (looser where the Jacobian magnifies).
                    assert!(
                        ((p2 - phi).abs() < 1e-3 || v % 1.0 < 1e-4)
                            && dv < 1e-5 * (v % 1.0).max(0.1),
                        "{d:?} {phi} {v}: {p2} {v2}"
                    );
                }
            }
            // Reflection always reaches some h; refraction does unless wo is inside past the
            // critical angle where no normal-ish h transmits.
            assert!(hits[0] >= 10, "{d:?} {hits:?}");
        }
    }

    /// Uniform directions `wi` on the sphere: those on wo's side and the refractions within
    /// `arccos(η_min/η_max)` of −wo have coords whose `wi` is the same direction (the image of
    /// the domain); the others (no microfacet refracts wo into them) have no `wi` back.
    #[test]
    fn generalised_domain_covers_the_sphere_as_documented() {
        let mut rng = crate::rng::Rng::new(7, 0, 0);
        for d in generalised_domains() {
            let Space::Generalised { wo, eta_o, eta_i } = d.space else {
                unreachable!()
            };
            let r = eta_o.min(eta_i) / eta_o.max(eta_i);
            for _ in 0..2000 {
                let u = rng.next_2d().as_dvec2();
                let z = 1.0 - 2.0 * u.x;
                let s = (1.0 - z * z).sqrt();
                let w = DVec3::new(s * (TAU * u.y).cos(), s * (TAU * u.y).sin(), z);
                let w = w.as_vec3().as_dvec3().normalize();
                if (w.z * wo.z).abs() < 1e-4 || ((-wo).dot(w) - r).abs() < 1e-4 {
                    continue; // rounding at the image's edge
                }
                let covered = w.z * wo.z > 0.0 || (-wo).dot(w) > r;
                let (phi, v) = d.coords(w.as_vec3()).unwrap();
                let back = d.generalised_wi(phi, v);
                let same = back.is_some_and(|(b, _)| (b - w).length() < 1e-4);
                assert_eq!(same, covered, "{d:?} {w} ({phi} {v}) → {back:?}");
            }
        }
    }

    /// `dωi/dωh` equals the area of the image of a small (φ, v) patch on the sphere of `wi`
    /// (`dωh = dφ dv`), by central differences, in both halves.
    #[test]
    fn generalised_jacobian_matches_finite_differences() {
        let mut checked = 0;
        for d in generalised_domains() {
            for phi in [0.3, 2.0, 3.5, 5.0] {
                for v in [0.002, 0.1, 0.5, 0.9, 1.002, 1.1, 1.5, 1.9] {
                    let e = 1e-6;
                    let at = |p: f64, q: f64| d.generalised_wi(p, q).map(|w| w.0);
                    let (Some((_, jac)), Some(a), Some(b), Some(c), Some(dd)) = (
                        d.generalised_wi(phi, v),
                        at(phi + e, v),
                        at(phi - e, v),
                        at(phi, v + e),
                        at(phi, v - e),
                    ) else {
                        continue;
                    };
                    let numeric = ((a - b) / (2.0 * e)).cross((c - dd) / (2.0 * e)).length();
                    assert!(
                        (numeric - jac).abs() < 1e-4 * jac.max(1e-3),
                        "{d:?} {phi} {v}: {numeric} vs {jac}"
                    );
                    checked += 1;
                }
            }
        }
        assert!(checked > 400, "{checked}");
    }

    /// Known densities integrate to 1 through each half: uniform over wo's hemisphere through
    /// the reflection half, and a smooth bump of 20° about −wo (inside the refracting cone for
    /// every η here) through the refraction half.
    #[test]
    fn generalised_jacobian_integrates_to_one() {
        let cos_b = 20f64.to_radians().cos();
        let bump_norm = TAU * (1.0 - cos_b).powi(3) / 3.0;
        for d in generalised_domains() {
            let Space::Generalised { wo, .. } = d.space else {
                unreachable!()
            };
            if wo.z.abs() < 0.5 {
                continue; // the bump would cross the horizon
            }
            let wo32 = wo.as_vec3();
            let hemi = move |w: Vec3| {
                if w.z * wo32.z > 0.0 {
                    0.5 / std::f32::consts::PI
                } else {
                    0.0
                }
            };
            let bump = move |w: Vec3| {
                let c = (-wo32).dot(w) as f64 - cos_b;
                (c.max(0.0).powi(2) / bump_norm) as f32
            };
            let r = integrate(&|p, v| d.density(&hemi, p, v), 0.0, 1.0, 400);
            let t = integrate(&|p, v| d.density(&bump, p, v), 1.0, 2.0, 400);
            assert!(
                (r - 1.0).abs() < 2e-3 && (t - 1.0).abs() < 2e-3,
                "{d:?}: {r} {t}"
            );
            // Neither half sees the other's directions.
            let r0 = integrate(&|p, v| d.density(&bump, p, v), 0.0, 1.0, 100);
            let t0 = integrate(&|p, v| d.density(&hemi, p, v), 1.0, 2.0, 100);
            assert!(r0 == 0.0 && t0 == 0.0, "{r0} {t0}");
        }
        // The whole uniform sphere at normal incidence: wo's hemisphere and the refracting cone
        // of half-angle arccos(η_min/η_max) about −wo.
        for ior in [1.1f32, 2.4] {
            let d = Domain::generalised_half_vector(Vec3::Z, ior, None);
            let total = integrate(
                &|p, v| d.density(&|_| 0.25 / std::f32::consts::PI, p, v),
                0.0,
                2.0,
                800,
            );
            let expect = 0.5 + 0.5 * (1.0 - 1.0 / ior as f64);
            assert!((total - expect).abs() < 2e-3, "{ior}: {total} vs {expect}");
        }
    }

    /// A rough dielectric's pdf has the same integral over the whole sphere of directions as
    /// through generalised half vectors, from either side.
    #[test]
    fn generalised_density_of_a_dielectric_matches_directions() {
        use crate::materials::{Dielectric, Material, Microfacet};
        for ior in [1.1f32, 1.5, 2.4] {
            let m = Material::Dielectric(Dielectric {
                ior,
                microfacet: Microfacet::ggx(0.5),
            });
            for wo in [Vec3::new(0.6, 0.0, 0.8), Vec3::new(0.6, 0.0, -0.8)] {
                let pdf = |w: Vec3| m.pdf(wo, w);
                let sphere = Domain::sphere();
                let g = Domain::generalised_half_vector(wo, ior, None);
                let a = integrate(&|p, v| sphere.density(&pdf, p, v), 0.0, 2.0, 600);
                let b = integrate(&|p, v| g.density(&pdf, p, v), 0.0, 2.0, 600);
                assert!((a - b).abs() < 2e-3 && a > 0.5, "{ior} {wo}: {a} vs {b}");
            }
        }
    }

    #[test]
    fn generalised_rows_split_into_halves_and_caps() {
        let d = Domain::generalised_half_vector(Vec3::new(0.6, 0.0, 0.8), 1.5, Some(0.2));
        let e = d.row_edges(16);
        assert_eq!(e.len(), 17);
        let vc = 1.0 - 0.2f64.cos();
        assert!(e[0] == 0.0 && e[8] == 1.0 && e[16] == 2.0, "{e:?}");
        assert!(
            (e[4] - vc).abs() < 1e-15 && (e[12] - 1.0 - vc).abs() < 1e-15,
            "{e:?}"
        );
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
