//! A plastic whose coat roughness α is textured. Its coat albedo table E(μ) (and E_avg, and so
//! 1/(1 − E_avg)) depends on α and takes ≈ 1.3 ms to build ([`super::coat_albedo`]): far too
//! slow per hit. So at scene build the tables are computed once per such material, on a grid of
//! α for its F0 ([`CoatGrid`]), and at a hit the two tables around the hit's α are blended,
//! linearly in ln α ([`CoatGrid::coat`]). α itself is not quantised: the GGX lobe uses the exact
//! value, only the coupling table is interpolated.
//!
//! **Grid.** [`GRID_SIZE`] values of α from [`ggx::SMOOTH_ALPHA`] to 1, evenly spaced in ln α
//! (ratio ≈ 1.16 between neighbours). For small α the table's shape is a function of μ/α (the
//! dip of E near μ ≈ α), which moves evenly in ln α; that is where E changes fastest, so even
//! spacing in ln α puts the nodes where they are needed. Interpolation error, the blended table
//! against the one built at that α, at the midpoint in ln α of every grid interval, max over the
//! μ nodes (`plastic_textured_tests::blend_error_at_mid_grid`): ≤ 9e-4 on E(μ) and ≤ 2e-4 on
//! E_avg for IOR 1.1 … 3 (bound [`MAX_BLEND_ERROR`]; 4.8e-4 at IOR 1.1 and 1.5); at IOR 10
//! (F0 0.67) 2.4e-3 and 5.5e-4, most of it the exact tables' own quadrature error, which
//! jitters with α (against converged E the blend is off by ≤ 8.6e-4 there). Measured
//! alternatives (`blend_variables_compared`, all four IORs): 64 nodes in ln α 1.7e-3, 32 nodes
//! 2.9e-3, 24 nodes 3.6e-3; 48 nodes linear in √α 6× worse, linear in α 26× (both at small α);
//! a Catmull–Rom cubic in ln α was worse at the α = 1 end. Below
//! [`ggx::SMOOTH_ALPHA`] the coat is a smooth mirror with the exact Schlick E, as for an
//! untextured plastic.
//!
//! **Consistency.** The hit's [`Plastic`] holds the blended table like any other: eval, sample
//! and pdf read the same E(μ), so every strategy agrees, and the base reflects exactly
//! albedo·(1 − E_blend(μo)). The white plastic's albedo is E_true + 1 − E_blend, 1 within the
//! table's error plus the blend's.
//!
//! **Cost.** Building a grid: [`GRID_SIZE`] tables, ≈ 60 ms on one core (in parallel over the
//! rayon pool). At a hit: one blend of two 64-entry tables into the copy of the material that
//! the hit builds anyway. Memory: [`GRID_SIZE`] × 264 bytes (13 KB) per material.
//!
//! **GPU.** `gpu/scene/materials.rs` uploads the [`GRID_SIZE`] tables and their E_avg to the
//! `tables` buffer (13 KB per such plastic, as here) and `material_at` (`materials/mod.wgsl`) locates
//! the hit's α in the grid by the same expression; the blend itself happens lazily where E(μ) is
//! read (`coat_albedo_eval` in `materials/plastic.wgsl`), entry by entry as `CoatAlbedo::blend` does it.
//!
//! WGSL twin: `materials/plastic.wgsl`.

use super::coat_albedo::CoatAlbedo;
use super::ggx;
use rayon::prelude::*;

/// Number of α nodes of a [`CoatGrid`].
pub const GRID_SIZE: usize = 48;

/// Bound on |E_blend(μ) − E_exact(μ)| at any α ≥ [`ggx::SMOOTH_ALPHA`] for IOR 1.1 … 3 (the
/// measured worst case at mid-grid, 9e-4, rounded up; see the module doc).
pub const MAX_BLEND_ERROR: f32 = 1e-3;

/// ln of the first node (α = [`ggx::SMOOTH_ALPHA`]); the last node is α = 1 (ln 0). Public for
/// the GPU's twin of [`CoatGrid::coat`] (`material_at` in `materials/mod.wgsl`), whose prelude holds it.
pub fn ln_first() -> f32 {
    ggx::SMOOTH_ALPHA.ln()
}

/// α of grid node `i` (`i` = 0: [`ggx::SMOOTH_ALPHA`], `i` = [`GRID_SIZE`] − 1: 1).
pub fn node_alpha(i: usize) -> f32 {
    if i + 1 >= GRID_SIZE {
        return 1.0; // exactly, not exp(0 ± rounding)
    }
    let s = i as f32 / (GRID_SIZE - 1) as f32;
    (ln_first() * (1.0 - s)).exp().max(ggx::SMOOTH_ALPHA)
}

/// The grid interval holding `alpha` (≥ [`ggx::SMOOTH_ALPHA`], ≤ 1) and the blend weight of its
/// upper node, linear in ln α (the nodes are evenly spaced there, so one logarithm does).
fn locate(alpha: f32) -> (usize, f32) {
    let x = (alpha.ln() - ln_first()) / -ln_first() * (GRID_SIZE - 1) as f32;
    let i = (x.max(0.0) as usize).min(GRID_SIZE - 2);
    (i, (x - i as f32).clamp(0.0, 1.0))
}

/// A plastic coat's albedo tables on the α grid, for one F0.
#[derive(Clone, Debug, PartialEq)]
pub struct CoatGrid {
    f0: f32,
    /// The table of each [`node_alpha`].
    tables: Vec<CoatAlbedo>,
}

impl CoatGrid {
    /// Tabulates the coat of normal reflectance `f0` at every node (≈ 60 ms of work).
    pub fn new(f0: f32) -> CoatGrid {
        let tables = (0..GRID_SIZE)
            .into_par_iter()
            .map(|i| CoatAlbedo::new(node_alpha(i), f0))
            .collect();
        CoatGrid { f0, tables }
    }

    /// The F0 the grid was built for.
    pub fn f0(&self) -> f32 {
        self.f0
    }

    /// The table of node `i` (see [`node_alpha`]).
    pub fn node(&self, i: usize) -> &CoatAlbedo {
        &self.tables[i]
    }

    /// The coat of roughness `alpha` ∈ [0, 1]: below [`ggx::SMOOTH_ALPHA`] the smooth coat, as
    /// an untextured plastic has it (64 Schlick values, no quadrature); else the two
    /// neighbouring node tables blended linearly in ln α (a node's own table at a node, to
    /// rounding).
    pub fn coat(&self, alpha: f32) -> CoatAlbedo {
        if ggx::is_smooth(alpha) {
            return CoatAlbedo::new(alpha, self.f0);
        }
        let alpha = alpha.min(1.0);
        let (i, t) = locate(alpha);
        CoatAlbedo::blend(&self.tables[i], &self.tables[i + 1], t, alpha)
    }
}

#[cfg(test)]
#[path = "plastic_textured_tests.rs"]
mod tests;
