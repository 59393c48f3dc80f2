//! Mixes and a plastic's textured α on the GPU (issue 17, items 3 and 5): the WGSL twins
//! (`materials/mix.wgsl`, `plastic_alpha_from_grid` and `coat_albedo_eval` in `materials/plastic.wgsl`) against the
//! Rust functions, and a scene with both rendered on the GPU against the CPU's render.
//!
//! - [`hash_is_bit_exact`]: `mix_hash_unit` == `hash_unit` bit for bit at 100k inputs (seed 17/90):
//!   random bit patterns (every finite float, NaN aside: a GPU may canonicalise NaN payloads),
//!   ±0, denormals, infinities, neighbouring floats, random salts and the salts 0, 1, 2³² − 1.
//!   Exact: the u64 emulation either reproduces SplitMix64 or it does not. Its power is shown in
//!   the test: against the CPU's hash at salt + 1 (a wrong salt) all but ~2⁻²⁴ of the values
//!   differ, and a dropped carry or a wrong shift changes most values likewise.
//! - [`resolve_matches_the_cpu`]: at the GPU's own hits (`scene_intersect`, 8k rays, seed 17/91)
//!   of a scene with a mix nested in a mix, one weight a bitmap (in-memory, bilinear) and one a
//!   constant, the material `material_resolve` chooses equals `Scene::resolve` at the same hit
//!   (the GPU's point, t and barycentrics handed to the CPU). Exact, except where a textured
//!   weight lies within 1e-3 of the hash (the two sides' texture coordinates differ by rounding,
//!   ≤ 2e-5 but more near a sphere's poles (`renderer/tests/gpu/parity_textures.rs`), and the 8×8
//!   bitmap's slope is ≤ 7.2 per unit uv), which are skipped and counted (≈ 1e-3 of the hits
//!   expected, < 1 % required). Detects a wrong salt (the outer mix's index used for the inner one: the
//!   test checks that the CPU chain with that salt disagrees at ≈ half of the nested hits), a
//!   swapped pair, and a textured weight read at the wrong uv.
//! - [`coat_grid_blend_matches_the_cpu`]: `coat_albedo_eval` after `plastic_alpha_from_grid` vs
//!   `Plastic::set_alpha_from_grid` then `CoatAlbedo::eval` (and 1/(1 − E_avg)) at 2k off-grid
//!   α (log-uniform in [SMOOTH_ALPHA/2, 1], plus the nodes and smooth α) × 9 μ, two IORs (two
//!   grids in one buffer). Tolerance: WGSL's `log` is within 3 ulp (2⁻²¹ absolute near 1), so
//!   the grid coordinate x = 47·(ln α − ln α₀)/(−ln α₀) is within Δx ≤ 1e-5 of the CPU's (doubled
//!   for safety to 2e-5); E is linear in x between nodes and continuous across them, so
//!   |ΔE| ≤ 2e-5·|E_{i+1}(μ) − E_i(μ)| + 8u, and 1/(1 − E_avg) relatively to that over
//!   (1 − E_avg). Detects blending with the wrong neighbour (the test checks that the
//!   alternative (1 − t)·E_{i−1} + t·E_i is beyond tolerance at ≥ 90 % of the rough points) and a
//!   wrong grid offset (the second IOR's grid).
//! - [`gpu_mix_scene_matches_the_cpu`]: the block z-test of `renderer/tests/gpu/images.rs` (8×8 blocks of
//!   the 64×64 image, family-wise α = 0.01, both films' variances; 32 spp, GPU seed 4300, CPU
//!   5300, MIS) of a scene with a mix (checkerboard weight 0.1/0.9) of a diffuse and a rough
//!   conductor nested in a mix (weight 0.5) with a plastic, and a plastic floor whose α is a
//!   checkerboard of 0.02 and 0.5 (IOR 1.5), under a quad light. The CPU's render of the same
//!   scene with the inner mix's weight inverted (0.9/0.1) must fail the same test: the test's
//!   power against a swapped choice.
//! - [`the_gpu_renders_the_cpus_blend_with_each_estimator`]: the scene
//!   `tests/data/mitsuba/xml_blend.xml` (Mitsuba's `blendbsdf`, which the importer maps onto
//!   mixes: a texture weight, a constant
//!   one, a blend nested in a blend), GPU against CPU with light sampling, BSDF sampling and
//!   MIS by the block z-test (8×8
//!   blocks, both films' variances, the suite's two stages; 32 spp, GPU seeds 4640 + i, CPU
//!   5640 + i). The CPU agrees with Mitsuba's image by `renderer/tests/mitsuba_xml_refs.rs`
//!   (`xml_blend_matches_its_mitsuba_reference`), the GPU's MIS by `gpu/mitsuba_refs.rs`.

use crate::common;
use crate::gpu_common;
use common::protocol::decide;
use glam::{Vec2, Vec3};
use gpu_common::images::{CPU_SEED_OFFSET, cpu_render, decide_gpu_vs_cpu, gpu_render};
use gpu_common::{Compare, build, context};
use lumis::geometry::primitive::NONE;
use lumis::geometry::{Ray, SurfaceHit};
use lumis::gpu::GpuScene;
use lumis::gpu::kernel::run_snippet;
use lumis::image_io::Image;
use lumis::integrator::{Heuristic, Settings, Strategy};
use lumis::materials::Material;
use lumis::materials::ggx::SMOOTH_ALPHA;
use lumis::materials::mix::{choice, hash_unit};
use lumis::materials::plastic_textured::{CoatGrid, GRID_SIZE, ln_first, node_alpha};
use lumis::rng::Rng;
use lumis::scene::Scene;
use lumis::textures::{BitmapOptions, BitmapTexture, Texture};
use std::sync::Arc;

/// f32's unit roundoff, 2⁻²⁴.
const U: f32 = f32::EPSILON / 2.0;

fn run(gpu: &GpuScene, body: &str, inputs: &[[f32; 4]], ins: usize, outs: usize) -> Vec<[f32; 4]> {
    run_snippet(gpu, &Settings::default(), body, inputs, ins, outs)
        .unwrap_or_else(|e| panic!("{e}"))
}

/// A scene for the kernels: one sphere and the materials `materials` (JSON members).
fn kernel_scene(materials: &str) -> Scene {
    let json = format!(
        r#"{{"camera": {{"from": [0, 0, -3], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40, "width": 2, "height": 2}},
            "materials": {{{materials}}},
            "shapes": [{{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m0"}}]}}"#
    );
    Arc::try_unwrap(build(&json)).unwrap_or_else(|_| unreachable!())
}

const MIX_MATERIALS: &str = r#""m0": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]},
    "m1": {"type": "conductor", "reflectance": [0.9, 0.8, 0.7], "alpha": 0.2}"#;

/// A float from a random bit pattern, never NaN.
fn random_float(r: &mut Rng) -> f32 {
    loop {
        let hi = (r.next_f32() * 65536.0) as u32;
        let lo = (r.next_f32() * 65536.0) as u32;
        let f = f32::from_bits(hi << 16 | lo);
        if !f.is_nan() {
            return f;
        }
    }
}

/// The hash inputs of the module doc: `(p, t, salt)`.
fn hash_inputs() -> Vec<(Vec3, f32, u32)> {
    let mut r = Rng::new(17, 90, 0);
    let special = [
        0.0,
        -0.0,
        f32::from_bits(1),
        f32::from_bits(0x8000_0001),
        f32::from_bits(0x007f_ffff),
        f32::MIN_POSITIVE,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::MAX,
        1.0,
        -1.0,
    ];
    let salt = |r: &mut Rng| match (r.next_f32() * 8.0) as u32 {
        0 => 0,
        1 => 1,
        2 => u32::MAX,
        _ => (r.next_f32() * 65536.0) as u32 * 65536 + (r.next_f32() * 65536.0) as u32,
    };
    let mut out = Vec::with_capacity(100_000);
    for k in 0..100_000u32 {
        let (p, t) = match k % 4 {
            // Special values and their combinations.
            0 => {
                let mut pick = || special[(r.next_f32() * special.len() as f32) as usize];
                (Vec3::new(pick(), pick(), pick()), pick())
            }
            // Every bit pattern.
            1 => (
                Vec3::new(
                    random_float(&mut r),
                    random_float(&mut r),
                    random_float(&mut r),
                ),
                random_float(&mut r),
            ),
            // Neighbouring floats of a hit-like point.
            2 => {
                let x = f32::from_bits(1.25f32.to_bits() + k);
                (Vec3::new(x, -0.75, 3.5), 2.0)
            }
            // Hit-like points.
            _ => (
                Vec3::new(r.next_f32(), r.next_f32(), r.next_f32()) * 20.0 - 10.0,
                r.next_f32() * 10.0,
            ),
        };
        out.push((p, t, salt(&mut r)));
    }
    out
}

/// `mix_hash_unit` is `hash_unit`, bit for bit (module doc).
#[test]
fn hash_is_bit_exact() {
    let Some(ctx) = context() else {
        return;
    };
    let gpu = GpuScene::new(ctx, Arc::new(kernel_scene(MIX_MATERIALS))).unwrap();
    let inputs = hash_inputs();
    let data: Vec<[f32; 4]> = inputs
        .iter()
        .flat_map(|&(p, t, s)| [[p.x, p.y, p.z, t], [f32::from_bits(s), 0.0, 0.0, 0.0]])
        .collect();
    let out = run(
        &gpu,
        "let a = inp(0u);
         let u = mix_hash_unit(a.xyz, a.w, bitcast<u32>(inp(1u).x));
         outp(0u, vec4f(u, f32(mix_choice(0.5, u)), 0.0, 0.0));",
        &data,
        2,
        1,
    );
    let (mut bad, mut wrong_salt_same) = (Vec::new(), 0usize);
    for (&(p, t, s), o) in inputs.iter().zip(&out) {
        let want = hash_unit(p, t, s);
        if o[0].to_bits() != want.to_bits() || o[1] != choice(0.5, want) as f32 {
            bad.push(format!("p {p:?} t {t:e} salt {s}: gpu {} cpu {want}", o[0]));
        }
        wrong_salt_same += (o[0] == hash_unit(p, t, s.wrapping_add(1))) as usize;
    }
    assert!(
        bad.is_empty(),
        "{} of {} hashes differ, e.g.\n{}",
        bad.len(),
        inputs.len(),
        bad[..bad.len().min(8)].join("\n")
    );
    // A wrong salt would be caught: 2^-24 of equal values expected, ~0.006 of 100k.
    assert!(wrong_salt_same <= 3, "{wrong_salt_same} equal at salt + 1");
}

/// A 8×8 bitmap of texels in [0.05, 0.95] (slope ≤ 8·0.9 per unit uv at most; module doc).
fn weight_bitmap() -> Texture {
    let mut r = Rng::new(17, 92, 0);
    let data = (0..64)
        .map(|_| Vec3::splat(0.05 + 0.9 * r.next_f32()))
        .collect();
    let image = Arc::new(Image {
        width: 8,
        height: 8,
        data,
    });
    Texture::Bitmap(BitmapTexture::new(image, BitmapOptions::default()))
}

/// The resolve scene: a quad, a sphere and a disk, each with the outer mix (of the inner mix
/// and a plastic, weight 0.4) whose inner mix (diffuse, conductor) has a bitmap weight.
fn resolve_scene() -> Scene {
    let json = r#"{
      "camera": {"from": [0, 0, -3], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40, "width": 2, "height": 2},
      "materials": {
        "red": {"type": "diffuse", "albedo": [0.8, 0.1, 0.1]},
        "metal": {"type": "conductor", "reflectance": [0.9, 0.8, 0.7], "alpha": 0.2},
        "shiny": {"type": "plastic", "albedo": [0.2, 0.3, 0.8], "alpha": 0.1},
        "inner": {"type": "mix", "materials": ["red", "metal"], "weight": 0.5},
        "outer": {"type": "mix", "materials": ["inner", "shiny"], "weight": 0.4}
      },
      "shapes": [
        {"type": "quad", "corner": [-3, -3, 1], "edge_u": [6, 0, 0], "edge_v": [0, 6, 0], "material": "outer"},
        {"type": "sphere", "center": [-1, 0, 0], "radius": 0.8, "material": "outer"},
        {"type": "disk", "center": [1.2, 0.5, 0], "normal": [0, 0, -1], "radius": 0.7, "material": "outer"}
      ]
    }"#;
    let mut scene = Arc::try_unwrap(build(json)).unwrap_or_else(|_| unreachable!());
    let inner = scene.material_names.iter().position(|n| n == "inner");
    let inner = inner.expect("the inner mix");
    scene.mixes[inner].as_mut().expect("a mix").weight = weight_bitmap();
    scene
}

/// `Scene::resolve` step by step: the chosen material, and the smallest |u − w| over its
/// textured steps (∞ if none), at the hit; `salt_of` gives each mix's salt.
fn cpu_chain(scene: &Scene, hit: &SurfaceHit, m0: u32, salt_of: impl Fn(u32) -> u32) -> (u32, f32) {
    let (mut m, mut margin) = (m0, f32::INFINITY);
    while let Some(Some(mix)) = scene.mixes.get(m as usize) {
        let u = hash_unit(hit.p, hit.t, salt_of(m));
        let w = match &mix.weight {
            Texture::Constant(c) => c.x,
            t => {
                let w = t.eval_scalar(scene.uv(hit));
                margin = margin.min((u - w).abs());
                w
            }
        };
        m = mix.materials[choice(w, u)];
    }
    (m, margin)
}

/// The GPU's choice at its hits == the CPU's at the same hits (module doc).
#[test]
fn resolve_matches_the_cpu() {
    let Some(ctx) = context() else {
        return;
    };
    let scene = Arc::new(resolve_scene());
    let gpu = GpuScene::new(ctx, scene.clone()).unwrap();
    assert!(gpu.features().has_mixes && gpu.features().has_textures);
    let mut r = Rng::new(17, 91, 0);
    let rays: Vec<Ray> = (0..8192)
        .map(|_| {
            let o = Vec3::new(r.next_f32() * 4.0 - 2.0, r.next_f32() * 4.0 - 2.0, -4.0);
            let target = Vec3::new(r.next_f32() * 5.0 - 2.5, r.next_f32() * 5.0 - 2.5, 0.5);
            Ray::new(o, (target - o).normalize())
        })
        .collect();
    let inputs: Vec<[f32; 4]> = rays
        .iter()
        .flat_map(|ray| {
            [
                [ray.o.x, ray.o.y, ray.o.z, ray.t_max],
                [ray.d.x, ray.d.y, ray.d.z, 0.0],
            ]
        })
        .collect();
    let out = run(
        &gpu,
        "let h = scene_intersect(Ray(inp(0u).xyz, inp(1u).xyz, inp(0u).w));
         var mi = NONE;
         if h.prim != NONE {
             let prim = prims[h.prim];
             mi = material_resolve(prim_material(prim), prim, h, false).index;
         }
         outp(0u, vec4f(h.p, h.t));
         outp(1u, vec4f(bitcast<f32>(mi), bitcast<f32>(h.prim), h.b));",
        &inputs,
        2,
        2,
    );
    let prims = scene.accel.primitives();
    let index = |name: &str| scene.material_names.iter().position(|n| n == name).unwrap();
    let (inner, outer) = (index("inner") as u32, index("outer") as u32);
    let (mut hits, mut skipped, mut nested, mut wrong_salt_differs) = (0, 0, 0, 0);
    let mut chosen = vec![0usize; scene.materials.len()];
    let mut bad = Vec::new();
    for o in out.chunks(2) {
        let prim = o[1][1].to_bits();
        if prim == NONE {
            continue;
        }
        hits += 1;
        let hit = SurfaceHit {
            t: o[0][3],
            p: Vec3::new(o[0][0], o[0][1], o[0][2]),
            p_error: Vec3::ZERO,
            n: Vec3::Z,
            prim,
            b: Vec2::new(o[1][2], o[1][3]),
        };
        let material = prims[prim as usize].material;
        let (want, margin) = cpu_chain(&scene, &hit, material, |m| m);
        assert_eq!(
            want,
            scene.resolve(&hit, material, false),
            "the chain is Scene::resolve"
        );
        if margin < 1e-3 {
            skipped += 1;
            continue;
        }
        let got = o[1][0].to_bits();
        if got != want {
            bad.push(format!(
                "prim {prim} at {:?} t {}: gpu {got} cpu {want}",
                hit.p, hit.t
            ));
        }
        chosen[want as usize] += 1;
        if hash_unit(hit.p, hit.t, outer) >= 0.4 {
            // The outer mix chose the inner one: it is nested here.
            nested += 1;
            let (alt, _) = cpu_chain(&scene, &hit, material, |_| outer);
            wrong_salt_differs += (alt != want) as usize;
        }
    }
    eprintln!(
        "{hits} hits, {skipped} skipped near a textured weight, chosen {chosen:?}, {nested} nested"
    );
    assert!(
        bad.is_empty(),
        "{} of {hits} choices differ, e.g.\n{}",
        bad.len(),
        bad[..bad.len().min(8)].join("\n")
    );
    assert!(
        hits > 6000 && skipped * 100 < hits,
        "{hits} hits, {skipped} skipped"
    );
    // Every leaf is reached; no mix is ever left unresolved.
    let leaves = ["red", "metal", "shiny"].map(|n| chosen[index(n)]);
    assert!(leaves.iter().all(|&c| c > 500), "{chosen:?}");
    assert_eq!(chosen[inner as usize] + chosen[outer as usize], 0);
    // A wrong salt changes the inner choice at about half of the nested hits.
    assert!(
        wrong_salt_differs * 4 > nested && nested > 2000,
        "{wrong_salt_differs} of {nested}"
    );
}

/// The E(μ) nodes the GPU is compared at.
const MUS: [f32; 9] = [0.0, 1e-4, 0.003, 0.02, 0.1, 0.3, 0.55, 0.9, 1.0];

/// `plastic_alpha_from_grid` + `coat_albedo_eval` against the CPU's grid coat (module doc).
#[test]
fn coat_grid_blend_matches_the_cpu() {
    let Some(ctx) = context() else {
        return;
    };
    let iors = [1.5f32, 3.0];
    let checker = r#"{"type": "checkerboard", "color0": 0.05, "color1": 0.4}"#;
    let materials = format!(
        r#""m0": {{"type": "plastic", "albedo": [0.5, 0.5, 0.5], "alpha": {checker}, "ior": {}}},
           "m1": {{"type": "plastic", "albedo": [0.5, 0.5, 0.5], "alpha": {checker}, "ior": {}}}"#,
        iors[0], iors[1]
    );
    let scene = Arc::new(kernel_scene(&materials));
    let gpu = GpuScene::new(ctx, scene.clone()).unwrap();
    let plastics: Vec<_> = (0..2)
        .map(|k| match &scene.materials[k] {
            Material::Plastic(p) => p.clone(),
            m => panic!("{m:?}"),
        })
        .collect();
    let grids: Vec<CoatGrid> = plastics.iter().map(|p| CoatGrid::new(p.f0())).collect();
    let mut r = Rng::new(17, 93, 0);
    let ln_lo = (0.5 * SMOOTH_ALPHA).ln();
    let mut alphas: Vec<f32> = (0..2000)
        .map(|_| (ln_lo * (1.0 - r.next_f32())).exp())
        .collect();
    alphas.extend((0..GRID_SIZE).map(node_alpha));
    alphas.extend([0.0, SMOOTH_ALPHA * 0.999, SMOOTH_ALPHA, 1.0]);
    let mut inputs = Vec::new();
    for k in 0..2 {
        for &a in &alphas {
            for mu in MUS {
                inputs.push([f32::from_bits(k), a, mu, 0.0]);
            }
        }
    }
    let out = run(
        &gpu,
        "let i = inp(0u);
         let m = plastic_alpha_from_grid(materials[bitcast<u32>(i.x)], i.y);
         outp(0u, vec4f(coat_albedo_eval(m, i.z), m.c.z, m.c.x, 0.0));",
        &inputs,
        1,
        1,
    );
    let mut e_cmp = Compare::new("E(μ) of the blended coat", 0.0, 0.0);
    let mut norm_cmp = Compare::new("1/(1 − E_avg) of the blended coat", 0.0, 0.0);
    let (mut rough, mut wrong_neighbour_caught) = (0usize, 0usize);
    for (i, o) in inputs.iter().zip(&out) {
        let (k, alpha, mu) = (i[0].to_bits() as usize, i[1], i[2]);
        let mut p = plastics[k].clone();
        p.set_alpha_from_grid(alpha, &grids[k]);
        let coat = p.coat().expect("lumis' coupling");
        let (e, avg) = (coat.eval(mu), coat.average());
        let what = format!("ior {} α {alpha:e} μ {mu}", iors[k]);
        assert_eq!(o[2], p.alpha(), "{what}: α");
        if alpha < SMOOTH_ALPHA {
            // The smooth coat: Schlick, exactly the CPU's expressions but for FMA.
            e_cmp.scalar_conditioned(o[0], e, 8.0 * U, &what);
            norm_cmp.scalar_conditioned(
                o[1],
                1.0 / (1.0 - avg),
                8.0 * U / (1.0 - avg).powi(2),
                &what,
            );
            continue;
        }
        let x = (alpha.ln() - ln_first()) / -ln_first() * (GRID_SIZE - 1) as f32;
        let n = (x.max(0.0) as usize).clamp(1, GRID_SIZE - 2);
        let t = (x - n as f32).clamp(0.0, 1.0);
        let node = |j: usize| grids[k].node(j);
        let step = (node(n + 1).eval(mu) - node(n).eval(mu))
            .abs()
            .max((node(n).eval(mu) - node(n - 1).eval(mu)).abs());
        let tol = 2e-5 * step + 8.0 * U;
        e_cmp.scalar_conditioned(o[0], e, tol, &what);
        let avg_step = (node(n + 1).average() - node(n - 1).average()).abs();
        let norm_tol = (2e-5 * avg_step + 8.0 * U) / (1.0 - avg).powi(2);
        norm_cmp.scalar_conditioned(o[1], 1.0 / (1.0 - avg), norm_tol, &what);
        // Blending with the wrong neighbour (nodes n − 1 and n) would be caught here.
        if x > 1.0 && t > 0.05 && mu < 0.5 {
            rough += 1;
            let wrong = (1.0 - t) * node(n - 1).eval(mu) + t * node(n).eval(mu);
            wrong_neighbour_caught += ((wrong - o[0]).abs() > 10.0 * tol) as usize;
        }
    }
    e_cmp.finish(0);
    norm_cmp.finish(0);
    assert!(
        wrong_neighbour_caught * 10 >= rough * 9 && rough > 1000,
        "the wrong neighbour is caught at {wrong_neighbour_caught} of {rough}"
    );
}

/// The image scene of the module doc; `inverted` swaps the inner mix's checkerboard weights.
fn image_scene(inverted: bool) -> Arc<Scene> {
    let (w0, w1) = if inverted { (0.9, 0.1) } else { (0.1, 0.9) };
    let json = format!(
        r#"{{
  "camera": {{"from": [0, 1.4, -3.8], "to": [0, 0.5, 0.5], "up": [0, 1, 0], "vfov_deg": 45, "width": 64, "height": 64}},
  "background": [0.15, 0.17, 0.2],
  "materials": {{
    "floor": {{"type": "plastic", "albedo": [0.6, 0.55, 0.4], "ior": 1.5,
               "alpha": {{"type": "checkerboard", "color0": 0.02, "color1": 0.5, "uv_scale": [4, 4]}}}},
    "red": {{"type": "diffuse", "albedo": [0.8, 0.15, 0.1]}},
    "metal": {{"type": "conductor", "reflectance": [0.9, 0.85, 0.6], "alpha": 0.25}},
    "blue": {{"type": "plastic", "albedo": [0.1, 0.2, 0.8], "alpha": 0.15}},
    "inner": {{"type": "mix", "materials": ["red", "metal"],
               "weight": {{"type": "checkerboard", "color0": {w0}, "color1": {w1}, "uv_scale": [2, 1]}}}},
    "outer": {{"type": "mix", "materials": ["inner", "blue"], "weight": 0.5}}
  }},
  "shapes": [
    {{"type": "quad", "corner": [-3, 0, -3], "edge_u": [0, 0, 6], "edge_v": [6, 0, 0], "material": "floor"}},
    {{"type": "sphere", "center": [-0.7, 0.8, 0.4], "radius": 0.8, "material": "inner"}},
    {{"type": "sphere", "center": [0.8, 0.5, 0.1], "radius": 0.5, "material": "outer"}},
    {{"type": "quad", "corner": [-1, 3, -1], "edge_u": [2, 0, 0], "edge_v": [0, 0, 2], "emission": [5, 5, 5]}}
  ]
}}"#
    );
    build(&json)
}

/// The block z-test of the module doc, and its power against an inverted weight.
#[test]
fn gpu_mix_scene_matches_the_cpu() {
    let scene = image_scene(false);
    let settings = Settings {
        strategy: Strategy::Mis {
            heuristic: Heuristic::Power,
        },
        ..Settings::default()
    };
    let Some(decision) = decide_gpu_vs_cpu("gpu mix scene vs cpu", &scene, settings, 32, 4300, 8)
    else {
        return;
    };
    decision.unwrap_or_else(|msg| panic!("{msg}"));
    // The power check through the same two-stage decision: the GPU's render against the CPU's
    // of the scene with the weight inverted.
    let inverted = image_scene(true);
    let what = "gpu mix scene vs the cpu's with the weight inverted";
    let decision = decide(what, 4300, 32, |seed, n, alpha| {
        let gpu = gpu_render(&scene, settings, n, seed).expect("a GPU");
        let cpu = cpu_render(&inverted, settings, n, seed + CPU_SEED_OFFSET);
        gpu.z_test(&cpu, 8, alpha)
    });
    assert!(
        decision.is_err(),
        "the z-test does not see an inverted mix weight"
    );
}

/// `xml_blend_delta.xml`'s mixes of model mitsuba, GPU against CPU with light sampling, BSDF
/// sampling and MIS by the z-test (GPU seeds 4650 + i, `GPU_VS_CPU_STRATEGIES`): the delta
/// samples' reweighting on both sides.
#[test]
fn the_gpu_renders_the_cpus_mitsuba_blend_with_each_estimator() {
    let scene = common::surface_detail::mitsuba_scene("xml_blend_delta");
    assert_eq!(
        scene.mixes.iter().flatten().filter(|m| m.mitsuba).count(),
        2
    );
    let Some(failures) =
        gpu_common::images::gpu_vs_cpu_estimators("gpu xml_blend_delta", &scene, 32, 4650, 8)
    else {
        return;
    };
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn the_gpu_renders_the_cpus_blend_with_each_estimator() {
    let scene = common::surface_detail::mitsuba_scene("xml_blend");
    assert_eq!(scene.mixes.iter().flatten().count(), 3);
    let Some(failures) =
        gpu_common::images::gpu_vs_cpu_estimators("gpu xml_blend", &scene, 32, 4640, 8)
    else {
        return;
    };
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
