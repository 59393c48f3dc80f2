//! Parity of `integrator/optimal.wgsl` with `integrator/optimal.rs` (mis-optimal's balance ratios, stage
//! schedule and 2×2 solve for α), on the same random inputs.
//!
//! Runs on any wgpu adapter (lavapipe where there is no GPU); `LUMIS_SKIP_GPU_TESTS=1` skips.

use crate::gpu_common;
use glam::Vec3;
use gpu_common::parity::{N, any_scene_gpu};
use gpu_common::*;
use lumis::gpu::kernel::run_snippet;
use lumis::integrator::Settings;
use lumis::integrator::optimal::{Moments, balance_ratios, is_stage_start};
use lumis::rng::Rng;

/// `integrator/optimal.wgsl` against `integrator::optimal`: the balance ratios (1e-6 relative, as the MIS
/// weights they are), the stage schedule (exact) and the 2×2 solve for α. The moments are sums of
/// 1 to 40 random samples (combined with contributions in [0, 2), or pure), rounded to f32 and
/// given to both sides; the CPU solves in f64, the GPU in f32, so α may differ by the f32 solve's
/// rounding amplified by the conditioning of `M + λI` (λ = 1e-3 of the trace bounds it by ~1e3):
/// 2e-3 relative plus 2e-3 absolute (α is O(1) here). Includes empty, pure-only and rank-one
/// systems.
#[test]
fn optimal_mis_matches() {
    let Some(gpu) = any_scene_gpu() else {
        return;
    };
    let mut r = Rng::new(13, 0, 0);
    let mut inputs = Vec::new();
    let mut cases = Vec::new();
    for i in 0..N {
        let mut m = Moments::default();
        let samples = match i % 50 {
            0 => 0,
            _ => 1 + r.next_u32() % 40,
        };
        for _ in 0..samples {
            let kind = r.next_u32() % 4;
            let c = Vec3::new(r.next_f32(), r.next_f32(), r.next_f32()) * 2.0;
            let rl = if i % 50 == 1 { 0.5 } else { r.next_f32() };
            match kind {
                0 => m.add_pure_light(),
                1 => m.add_pure_bsdf(c * 0.1),
                _ => m.add_combined(c, rl, 1.0 - rl),
            }
        }
        // The f32 sums both sides see.
        let f = |v: [f64; 3]| v.map(|x| x as f32);
        let (mm, bl, bb) = (f(m.m), f(m.b_light), f(m.b_bsdf));
        let m = Moments {
            m: mm.map(f64::from),
            b_light: bl.map(f64::from),
            b_bsdf: bb.map(f64::from),
        };
        let p_light = 10f32.powf(-20.0 + 40.0 * r.next_f32()) * (i % 7 != 0) as u32 as f32;
        let p_bsdf = 10f32.powf(-20.0 + 40.0 * r.next_f32());
        let s = r.next_u32() % 5000;
        inputs.push([mm[0], mm[1], mm[2], p_light]);
        inputs.push([bl[0], bl[1], bl[2], p_bsdf]);
        inputs.push([bb[0], bb[1], bb[2], f32::from_bits(s)]);
        cases.push((m, p_light, p_bsdf, s));
    }
    let out = run_snippet(
        &gpu,
        &Settings::default(),
        "let a = inp(0u); let b = inp(1u); let c = inp(2u);
         let al = optimal_solve(a.xyz, b.xyz, c.xyz);
         let r = balance_ratios(a.w, b.w);
         outp(0u, vec4f(al.light, select(0.0, 1.0, r.ok)));
         outp(1u, vec4f(al.bsdf, r.rl));
         outp(2u, vec4f(r.rb, select(0.0, 1.0, opt_is_stage_start(bitcast<u32>(c.w))), 0.0, 0.0));",
        &inputs,
        3,
        3,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let mut alpha = Compare::new("optimal alpha", 2e-3, 2e-3);
    let mut ratios = Compare::new("optimal ratios", 1e-6, 1e-7);
    for (k, (m, p_light, p_bsdf, s)) in cases.iter().enumerate() {
        let o = &out[3 * k..3 * k + 3];
        let a = m.solve();
        alpha.v3(o[0], a.light, "alpha light");
        alpha.v3(o[1], a.bsdf, "alpha bsdf");
        let want = balance_ratios(*p_light, *p_bsdf);
        assert_eq!(
            o[0][3] == 1.0,
            want.is_some(),
            "ratios ok, {p_light:e} {p_bsdf:e}"
        );
        if let Some((rl, rb)) = want {
            ratios.scalar(o[1][3], rl, "r_L");
            ratios.scalar(o[2][0], rb, "r_B");
        }
        assert_eq!(o[2][1] == 1.0, is_stage_start(*s), "stage start {s}");
    }
    alpha.finish(0);
    ratios.finish(0);
}
