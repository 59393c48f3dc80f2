//! The suite's statistical protocol, one rule for every image z-test (docs/testing.md,
//! "The protocol"). Each test renders at its own seed, fixed in the source before the test's
//! first run and never changed after a failure. A decision is two stages:
//!
//! 1. the render at the test's seed and sample count, tested at family-wise α₁ = 0.01 (Šidák
//!    over its blocks and channels);
//! 2. only if stage 1 finds a bias: a fresh render at a seed derived from the decision's name
//!    ([`second_seed`]: no one picks it, and it is known before any run) with twice the samples,
//!    tested at α₂ = 0.005. The decision fails only if stage 2 fails too.
//!
//! An unbiased renderer fails one decision with probability α₁·α₂ = 5·10⁻⁵ (the two renders are
//! independent), so the suite's ≈ 180 decisions keep the chance of a false alarm in a run with
//! fresh seeds below 1% (it was ≈ 84% with one stage at 0.01). A real bias fails stage 1 about as
//! often as before and stage 2 more often (2× the samples: its z grows √2×), so a test's power is
//! at least its one-stage power times stage 2's; power checks (a mutant must be detected) go
//! through the same [`decide`], so a test can never be more sensitive to a mutant than to a bug.

use lumis::engine::Progressive;
use lumis::image_io::Image;
use lumis::metrics::BlockTest;

/// Stage 1's family-wise significance per decision.
pub const ALPHA_FIRST: f64 = 0.01;
/// Stage 2's family-wise significance.
pub const ALPHA_SECOND: f64 = 0.005;
/// Stage 2 renders this many times stage 1's samples per pixel.
/// (Twice, not four times: a power check always runs both stages, and at 4× they added about
/// 7 minutes to the suite on 2 cores, 2026-12-05; every mutant kept a wide margin at 2×.)
pub const SECOND_STAGE_SPP: u32 = 2;

/// The 32-bit FNV-1a hash of `text`: seeds derived from names, fixed before any run.
pub fn fnv1a(text: &str) -> u32 {
    text.bytes()
        .fold(0x811c_9dc5, |h, b| (h ^ b as u32).wrapping_mul(0x0100_0193))
}

/// Stage 2's seed for the decision named `what`: [`fnv1a`] of the name, folded into
/// [2³⁰, 2³¹), a range no stage-1 seed of the suite uses.
pub fn second_seed(what: &str) -> u32 {
    (1 << 30) | (fnv1a(what) >> 2)
}

/// One decision under the protocol: `run(seed, spp, alpha)` renders with that seed and sample
/// count and returns its block z-test at `alpha`. `Err` holds both stages' reports. Each
/// stage prints the `z-test|…` line `tools/power_table.py` reads, stage 2's name marked.
pub fn decide(
    what: &str,
    seed: u32,
    spp: u32,
    run: impl Fn(u32, u32, f64) -> BlockTest,
) -> Result<(), String> {
    let first = match super::check_unbiased(what, &run(seed, spp, ALPHA_FIRST)) {
        Ok(()) => return Ok(()),
        Err(msg) => msg,
    };
    let seed2 = second_seed(what);
    let what2 = format!(
        "{what} [stage 2: seed {seed2}, {} spp]",
        SECOND_STAGE_SPP * spp
    );
    let second = run(seed2, SECOND_STAGE_SPP * spp, ALPHA_SECOND);
    super::check_unbiased(&what2, &second).map_err(|msg| format!("{first}{msg}"))
}

/// [`decide`] for the common case: `render(seed, spp)` (no non-finite samples allowed) against
/// `reference` and its variance image (none for a closed-form image) in `block`×`block` blocks.
pub fn decide_against(
    what: &str,
    seed: u32,
    spp: u32,
    reference: &Image,
    reference_var: Option<&Image>,
    block: u32,
    render: impl Fn(u32, u32) -> Progressive,
) -> Result<(), String> {
    decide(what, seed, spp, |seed, n, alpha| {
        let r = render(seed, n);
        assert_eq!(r.film().nonfinite, 0, "{what}: non-finite samples");
        super::test_against_at(&r, reference, reference_var, block, alpha)
    })
}
