//! Directional albedo E(μ) of a dielectric GGX coat (Schlick Fresnel, tint 1) and its cosine-
//! weighted average E_avg = 2∫E(μ)μ dμ: the Kulla–Conty / Kelemen table that couples the plastic's
//! base to its coat. Tabulated once per material (for a textured α, once per node of an α grid:
//! [`super::plastic_textured`]); a smooth coat uses Schlick in closed form.
//!
//! Accuracy (|E_table − E|, measured against a 64×256-node quadrature over μ): ≤ 2.6e-3 at
//! α = [`ggx::SMOOTH_ALPHA`] (E has a dip of width ~α near μ ≈ α that falls between nodes),
//! ≤ 1e-3 for α ≥ 0.005, ≤ 5e-4 for α ≥ 0.02, ≤ 1.5e-4 at α = 1 (IOR 3, μ = 1; measured by
//! `renderer/tests/plastic_furnace.rs` against an independent adaptive quadrature). Build: ~1.3 ms in
//! release.
//! WGSL twin: `materials/plastic.wgsl`.

use super::{fresnel, ggx};
use crate::math::reflect;
use glam::{Vec2, Vec3};

/// Nodes of the E(μ) table, at μ_i = (i/(N−1))³: crowded near grazing, where E changes on a
/// scale of ~α, sparser near normal incidence, where it is flat.
pub const E_TABLE_SIZE: usize = 64;
/// Quadrature nodes per table entry in VNDF sample space: half the φ range (the integrand is
/// mirror-symmetric in φ for an isotropic lobe) × the cap's z range. Quadrature error ≲ 2e-4,
/// below the interpolation error.
const QUAD_PHI: usize = 24;
const QUAD_Z: usize = 32;

/// μ of table node `i`.
#[inline]
pub fn node_mu(i: usize) -> f32 {
    let t = i as f32 / (E_TABLE_SIZE - 1) as f32;
    t * t * t
}

/// E(μ) of a GGX reflector with Schlick Fresnel `f0` (tint 1), by midpoint quadrature over the
/// unit square of [`ggx::sample_visible_normal`]: E = ∫ F(wo·h)·G1(wi)·[wi.z > 0] du. In VNDF
/// space the integrand is bounded and smooth for any α; in direction space a narrow lobe would
/// need thousands of nodes.
pub fn coat_albedo_quadrature(alpha: f32, f0: f32, mu: f32, n_phi: usize, n_z: usize) -> f32 {
    let mu = mu.clamp(0.0, 1.0);
    let wo = Vec3::new(crate::math::safe_sqrt(1.0 - mu * mu), 0.0, mu);
    let mut sum = 0.0f64; // f64: a long f32 sum of positive terms drifts by ~1e-3
    for i in 0..n_phi {
        // u.x ∈ [0, 1/2): the other half of the circle is its mirror image.
        let ux = 0.5 * (i as f32 + 0.5) / n_phi as f32;
        for j in 0..n_z {
            // u.y = smoothstep(v): the integrand has √ singularities at both ends of the cap
            // (c at its pole, h at the horizon); the warp's vanishing Jacobian tames them.
            let v = (j as f32 + 0.5) / n_z as f32;
            let uy = v * v * (3.0 - 2.0 * v);
            let jac = 6.0 * v * (1.0 - v);
            let h = ggx::sample_visible_normal(alpha, wo, Vec2::new(ux, uy));
            let wi = reflect(wo, h);
            if wi.z > 0.0 {
                let e = fresnel::fresnel_schlick(f0, wo.dot(h)) * ggx::g1(alpha, wi);
                sum += (jac * e) as f64;
            }
        }
    }
    (sum / (n_phi * n_z) as f64) as f32
}

/// A coat's E(μ) table and E_avg.
#[derive(Clone, Debug, PartialEq)]
pub struct CoatAlbedo {
    alpha: f32,
    f0: f32,
    /// E at [`node_mu`]; Schlick values for a smooth coat (which evaluates them exactly). Inline
    /// (256 bytes) rather than boxed: a textured plastic copies its material at every hit, which
    /// must not allocate.
    table: [f32; E_TABLE_SIZE],
    average: f32,
}

impl CoatAlbedo {
    /// Tabulates the coat of roughness `alpha` and normal reflectance `f0`.
    pub fn new(alpha: f32, f0: f32) -> CoatAlbedo {
        let smooth = ggx::is_smooth(alpha);
        let table: [f32; E_TABLE_SIZE] = std::array::from_fn(|i| {
            let mu = node_mu(i);
            if smooth {
                fresnel::fresnel_schlick(f0, mu)
            } else {
                coat_albedo_quadrature(alpha, f0, mu, QUAD_PHI, QUAD_Z)
            }
        });
        let average = if smooth {
            // 2∫(F0 + (1−F0)(1−μ)⁵)μ dμ = F0 + (1−F0)·2·B(2,6) = F0 + (1−F0)/21.
            f0 + (1.0 - f0) / 21.0
        } else {
            // Exact for the piecewise-linear interpolant, so a base coupled through this table
            // reflects exactly albedo·(1 − E(μo)) for the E that `eval` returns.
            let mut s = 0.0f64;
            for i in 0..E_TABLE_SIZE - 1 {
                let (ma, mb) = (node_mu(i) as f64, node_mu(i + 1) as f64);
                let (ea, eb) = (table[i] as f64, table[i + 1] as f64);
                s += (mb - ma) / 6.0 * (ea * (2.0 * ma + mb) + eb * (ma + 2.0 * mb));
            }
            (2.0 * s) as f32
        };
        CoatAlbedo {
            alpha,
            f0,
            table,
            average,
        }
    }

    /// The coat of roughness `alpha` whose table and E_avg are `a`'s and `b`'s blended by `t`
    /// (0: `a`, 1: `b`), entry by entry: a textured plastic's coat between two grid tables
    /// ([`super::plastic_textured`]). E_avg is linear in the table, so the blended average is
    /// the exact average of the blended table (up to f32 rounding, ~1e-7), and a base coupled
    /// through it still reflects albedo·(1 − E(μo)).
    pub(crate) fn blend(a: &CoatAlbedo, b: &CoatAlbedo, t: f32, alpha: f32) -> CoatAlbedo {
        debug_assert!(a.f0 == b.f0 && !ggx::is_smooth(alpha) && (0.0..=1.0).contains(&t));
        CoatAlbedo {
            alpha,
            f0: a.f0,
            table: std::array::from_fn(|i| a.table[i] + t * (b.table[i] - a.table[i])),
            average: a.average + t * (b.average - a.average),
        }
    }

    /// E(μ): Schlick for a smooth coat, otherwise the table interpolated linearly in μ.
    #[inline]
    pub fn eval(&self, mu: f32) -> f32 {
        let mu = mu.clamp(0.0, 1.0);
        if ggx::is_smooth(self.alpha) {
            return fresnel::fresnel_schlick(self.f0, mu);
        }
        let i = ((mu.cbrt() * (E_TABLE_SIZE - 1) as f32) as usize).min(E_TABLE_SIZE - 2);
        let (ma, mb) = (node_mu(i), node_mu(i + 1));
        let t = ((mu - ma) / (mb - ma)).clamp(0.0, 1.0);
        self.table[i] + t * (self.table[i + 1] - self.table[i])
    }

    /// E_avg = 2∫E(μ)μ dμ.
    pub fn average(&self) -> f32 {
        self.average
    }

    /// The table at μ_i = (i/(N−1))³ (for upload to the GPU).
    pub fn table(&self) -> &[f32; E_TABLE_SIZE] {
        &self.table
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A converged E(μ): ~1e-5 from exact (checked by doubling the nodes).
    pub(crate) fn e_reference(alpha: f32, f0: f32, mu: f32) -> f32 {
        if ggx::is_smooth(alpha) {
            fresnel::fresnel_schlick(f0, mu)
        } else {
            coat_albedo_quadrature(alpha, f0, mu, 64, 256)
        }
    }

    #[test]
    fn table_matches_reference() {
        // Tolerances ~20% above the worst errors measured over 121 μ (module docs).
        let cases = [
            (ggx::SMOOTH_ALPHA, 3e-3),
            (0.005, 1.2e-3),
            (0.05, 6e-4),
            (0.3, 6e-4),
            (1.0, 3e-4),
        ];
        for (alpha, tol) in cases {
            for ior in [1.1, 1.5, 3.0] {
                let f0 = fresnel::schlick_f0_from_ior(ior);
                let c = CoatAlbedo::new(alpha, f0);
                for k in 0..=120 {
                    let mu = (k as f32 / 120.0).powi(3);
                    let (e, r) = (c.eval(mu), e_reference(alpha, f0, mu));
                    assert!(
                        (e - r).abs() < tol,
                        "a {alpha} ior {ior} mu {mu}: {e} vs {r}"
                    );
                    assert!((0.0..=1.0).contains(&e));
                }
            }
        }
    }

    #[test]
    fn average_matches_brute_force() {
        for alpha in [0.0, 0.01, 0.3, 1.0] {
            let c = CoatAlbedo::new(alpha, 0.04);
            // Midpoint rule of 2·E(μ)·μ on a fine grid: agrees to its own O(h²) error.
            let n = 100_000;
            let num: f64 = (0..n)
                .map(|i| {
                    let mu = (i as f64 + 0.5) / n as f64;
                    2.0 * c.eval(mu as f32) as f64 * mu / n as f64
                })
                .sum();
            assert!(
                (c.average() as f64 - num).abs() < 1e-5,
                "{alpha}: {} {num}",
                c.average()
            );
        }
        // Smooth: exactly Schlick.
        let c = CoatAlbedo::new(0.0, 0.04);
        assert_eq!(c.eval(0.3), fresnel::fresnel_schlick(0.04, 0.3));
    }
}
