//! The suite's two tiers (docs/testing.md, "Tiers"). `cargo test --release --workspace` runs
//! the **CI tier**: every deterministic test, and every statistical test once per feature it
//! covers. `cargo test --release --workspace --features lumis-renderer/full-suite` runs the
//! **full tier** as well: the cross products (every strategy on every scene, every GPU sampler
//! by χ² beside its pointwise parity test) and the power checks (a mutant must fail), which
//! measure what the CI tier's tests can detect. The full tier is run before each stop's note
//! and by `tools/power_table.py`.
//!
//! A test keeps its seed in both tiers: a cross product skips its other members in the CI tier,
//! it does not renumber them.

use lumis::integrator::{Heuristic, Strategy};

/// True in the full tier.
pub const FULL: bool = cfg!(feature = "full-suite");

/// The strategy a scene-level cross product keeps in the CI tier: MIS with the power heuristic,
/// lumis' default, which draws from both the light and the BSDF, so a bias in either sampler
/// (or in the weights' pdfs) moves its image.
pub const CI_STRATEGY: Strategy = Strategy::Mis {
    heuristic: Heuristic::Power,
};

/// Whether a cross product over strategies renders `strategy` in this tier.
pub fn runs(strategy: Strategy) -> bool {
    FULL || strategy == CI_STRATEGY
}

/// Whether a scene that stands for the estimators themselves (seed_cornell) renders `strategy`
/// in this tier: the CI tier keeps light sampling alone and BSDF sampling alone beside
/// [`CI_STRATEGY`], the two techniques every other strategy weights (the mixture's and the
/// heuristics' weights are compared across strategies by `strategy_agreement.rs` and pinned to
/// the CPU's on the GPU by same-seed renders, both in the CI tier).
pub fn runs_estimator(strategy: Strategy) -> bool {
    runs(strategy) || matches!(strategy, Strategy::Light | Strategy::Bsdf)
}
