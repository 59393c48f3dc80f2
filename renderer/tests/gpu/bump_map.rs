//! Bump maps on the GPU (issue 40 item 1): Mitsuba's gallery scene `bsdf_bumpmap_with.xml` (the
//! material preview's rough plastic under a PNG of heights, scale 0.02, the museum environment
//! map), opened unchanged from `tests/data/gallery/` at an eighth of its film size (120×90),
//! rendered by the GPU and by the CPU with light sampling, BSDF sampling and MIS
//! (`GPU_VS_CPU_STRATEGIES`) and compared by the block z-test of
//! `renderer/tests/gpu/images.rs` (8×8 blocks, family-wise α = 0.01, both films' variances, the
//! suite's two stages; 32 spp each, GPU seeds 4500 + i, CPU 5500 + i for strategy i of
//! `STRATEGIES_AND_OPTIMAL`), as `normal_map.rs` does for the normal map and for the same reason
//! (the flip and the side rule branch on continuous inputs: same-seed films differ in a few
//! pixels). The CPU agrees with Mitsuba 3.9.1 (`renderer/tests/gallery.rs`); the WGSL functions
//! (`texture_eval_1_grad`, `triangle_dp_duv`'s formula, `bump_normal`) are compared with the
//! CPU's one by one; the back of a two-sided bump map renders Mitsuba's one exact value; a GPU
//! at half the scale is detected by the image test (its power).

use crate::common::STRATEGIES_AND_OPTIMAL;
use crate::common::surface_detail::gallery_scene_at;
use crate::gpu_common::images::{CPU_SEED_OFFSET, cpu_render, gpu_render, gpu_vs_cpu_estimators};
use crate::gpu_common::parity::{f4, run};
use crate::gpu_common::{Compare, context};
use glam::Vec2;
use lumis::gpu::GpuScene;
use lumis::integrator::Settings;
use lumis::materials::bump_map;
use lumis::rng::Rng;
use lumis::scene::Scene;
use std::sync::Arc;

const BLOCK: u32 = 8;
const SPP: u32 = 32;

/// The gallery's bump-mapped material preview at an eighth of its film, its bump scale times
/// `scale`.
fn scene(scale: f32) -> Arc<Scene> {
    let mut scene = gallery_scene_at("bsdf_bumpmap_with", 1.0 / 8.0);
    for map in scene.normal_maps.iter_mut().flatten() {
        map.height_scale = map.height_scale.map(|s| s * scale);
    }
    Arc::new(scene)
}

#[test]
fn the_gpu_renders_the_cpus_bump_mapped_image_with_each_estimator() {
    let scene = scene(1.0);
    assert_eq!(
        scene
            .normal_maps
            .iter()
            .flatten()
            .filter(|m| m.height_scale.is_some())
            .count(),
        1
    );
    let Some(failures) = gpu_vs_cpu_estimators("gpu bsdf_bumpmap_with", &scene, SPP, 4500, BLOCK)
    else {
        return;
    };
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The image test's power: the GPU's render at half the bump scale against the CPU's at the
/// scene's must fail (MIS, seed 4506).
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn a_gpu_at_half_the_bump_scale_is_detected() {
    if context().is_none() {
        return;
    }
    let (with, half) = (scene(1.0), scene(0.5));
    let settings = Settings {
        strategy: STRATEGIES_AND_OPTIMAL[3],
        ..Settings::default()
    };
    let what = "gpu bsdf_bumpmap_with at half its bump scale vs cpu";
    let decision = crate::common::protocol::decide(what, 4506, SPP, |seed, n, alpha| {
        let gpu = gpu_render(&half, settings, n, seed).expect("a GPU");
        let cpu = cpu_render(&with, settings, n, seed.wrapping_add(CPU_SEED_OFFSET));
        gpu.z_test(&cpu, BLOCK, alpha)
    });
    assert!(decision.is_err(), "half the bump scale went undetected");
}

/// The back of a two-sided bump-mapped material on the GPU: `bumpmap_back.xml` renders
/// Mitsuba's one exact value to 1e-4 with MIS (`renderer/tests/bump_map.rs` has the CPU's, to
/// 1e-5).
#[test]
fn the_gpus_back_of_a_two_sided_bump_map_is_mitsubas() {
    let scene = crate::common::surface_detail::mitsuba_scene("bumpmap_back");
    let settings = Settings {
        strategy: STRATEGIES_AND_OPTIMAL[3],
        ..Settings::default()
    };
    let Some(film) = gpu_render(&scene, settings, 4, 4507) else {
        return;
    };
    crate::common::surface_detail::assert_pixels_match(
        &film.mean(),
        "bumpmap_back.exr",
        1e-4,
        "MIS",
    );
}

/// `texture_eval_1_grad` against `BitmapTexture::eval_1_grad` on the gallery's 1024² height PNG
/// at random uvs (the same f32 expressions in the same order: to 1e-5 of the gradient's scale,
/// the texels' luminances being sums of three products), and `bump_normal` against
/// `bump_map::local_normal` on random partials, normals and gradients (to 1e-5: a cross product,
/// a normalisation, a change of frame).
#[test]
fn bump_functions_match_the_cpu() {
    let Some(ctx) = context() else {
        return;
    };
    let scene = scene(1.0);
    let (index, map) = scene
        .normal_maps
        .iter()
        .enumerate()
        .find_map(|(i, m)| m.as_ref().map(|m| (i, m.clone())))
        .unwrap();
    let gpu = GpuScene::new(ctx, scene.clone()).expect("upload");
    let mut r = Rng::new(4508, 0, 0);
    let unit = |r: &mut Rng| lumis::sampling::sample_uniform_sphere(r.next_2d());
    let n_items = 4096;
    let mut inputs = Vec::new();
    let mut cases = Vec::new();
    for _ in 0..n_items {
        let uv = Vec2::new(r.next_f32() * 3.0 - 1.0, r.next_f32() * 3.0 - 1.0);
        let (du, dv) = (unit(&mut r) * 2.0, unit(&mut r) * 0.5);
        let ns = unit(&mut r);
        let ng = (ns + 0.3 * unit(&mut r)).normalize();
        let grad = Vec2::new(r.next_f32() - 0.5, r.next_f32() - 0.5) * 4.0;
        let front = lumis::geometry::tangent::tangent_frame(ns, du);
        inputs.extend([
            [uv.x, uv.y, grad.x, grad.y],
            f4(du, 0.0),
            f4(dv, 0.0),
            f4(ns, 0.0),
            f4(ng, 0.0),
        ]);
        cases.push((uv, grad, du, dv, ns, ng, front));
    }
    let body = format!(
        "let g = texture_eval_1_grad(normal_map_texture(materials[{index}u]) - 1u, inp(0u).xy);
         outp(0u, vec4f(g, 0.0, 0.0));
         let ns = inp(3u).xyz;
         let front = tangent_frame(ns, inp(1u).xyz);
         outp(1u, bump_normal(inp(0u).zw, inp(1u).xyz, inp(2u).xyz, ns, inp(4u).xyz, front));"
    );
    let out = run(&gpu, &body, &inputs, 5, 2);
    let mut grad_c = Compare::new("texture_eval_1_grad", 1e-5, 1e-5);
    let mut normal_c = Compare::new("bump_normal", 1e-5, 1e-6);
    let mut tilted = 0;
    for ((uv, grad, du, dv, ns, ng, front), o) in cases.iter().zip(out.chunks(2)) {
        let g = map.texture.eval_1_grad(*uv).unwrap();
        let scale = g.abs().max_element().max(1.0);
        for k in 0..2 {
            grad_c.scalar_scaled(o[0][k], g[k], scale, &format!("gradient at {uv}"));
        }
        let want = bump_map::local_normal(*grad, *du, *dv, *ns, *ng, front);
        match want {
            Some(n) => {
                tilted += 1;
                normal_c.scalar(o[1][3], 1.0, "tilt flag");
                for k in 0..3 {
                    normal_c.scalar_scaled(o[1][k], n[k], 1.0, &format!("normal {grad} {du} {dv}"));
                }
            }
            None => normal_c.scalar(o[1][3], 0.0, "no tilt"),
        }
    }
    assert!(tilted > n_items * 9 / 10, "{tilted}");
    grad_c.finish(0);
    normal_c.finish(0);
}
