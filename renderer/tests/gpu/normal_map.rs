//! Normal maps on the GPU (issue 40 item 1): Mitsuba's gallery scene `bsdf_normalmap_with.xml`
//! (a rough plastic on the material preview, a JPEG normal map, the museum environment map), opened
//! unchanged from `tests/data/gallery/` at an eighth of its film size (120×90), rendered by the
//! GPU and by the CPU with light sampling, BSDF sampling and MIS
//! (`GPU_VS_CPU_STRATEGIES`) and compared by the block z-test of
//! `renderer/tests/gpu/images.rs` (8×8 blocks, family-wise α = 0.01, both films' variances,
//! the suite's two stages, `common/protocol.rs`; 32 spp each, GPU seeds 4400 + i, CPU 5400 + i
//! for strategy i of `STRATEGIES_AND_OPTIMAL`). A first version at a sixteenth of the size
//! (60×45, 5×5 blocks) could not tell the scene without its normal map from the scene with it
//! (worst |z| 3.2 against 4.17); this one does (|z| 7.0 and 6.8 in the two stages at 32 spp). The CPU agrees with Mitsuba 3.9.1's image of
//! the scene by the block t-test of `renderer/tests/gallery.rs`
//! (`bsdf_normalmap_with_agrees_with_mitsuba`). The WGSL functions are compared with the CPU's
//! one by one in [`normal_map_functions_match_the_cpu`], which also covers the shadowing term
//! that the images here are too noisy to resolve; [`a_gpu_without_the_normal_map_is_detected`]
//! shows that the images see the map itself.
//!
//! The same random streams on both (`same_seed_check`, as `images.rs` does for most scenes) were
//! tried first: relMSE ≤ 4.6e-7 in every strategy, but up to 4 of the 2700 pixels diverged (the
//! mixture at seed 11; 0–2 elsewhere and at seeds 12, 13; none with the map removed): the flip and
//! the side rule are branches on continuous inputs (a bilinear JPEG texel, a normalisation) that
//! rounding sends either way, beyond that check's 1-in-1000 bound. It is not the criterion here.

use crate::common::STRATEGIES_AND_OPTIMAL;
use crate::common::surface_detail::gallery_scene_at;
use crate::gpu_common::images::{CPU_SEED_OFFSET, cpu_render, gpu_render, gpu_vs_cpu_estimators};
use lumis::integrator::Settings;
use lumis::scene::Scene;
use std::sync::Arc;

/// Block side of the z-test (60×45 = 12×9 blocks).
const BLOCK: u32 = 8;
/// Samples per pixel of each render.
const SPP: u32 = 32;

/// The gallery's normal-mapped material preview at `scale` of its film.
fn scene(scale: f64, shadowing: bool) -> Arc<Scene> {
    let mut scene = gallery_scene_at("bsdf_normalmap_with", scale);
    for map in scene.normal_maps.iter_mut().flatten() {
        map.shadowing = shadowing;
    }
    Arc::new(scene)
}

#[test]
fn the_gpu_renders_the_cpus_normal_mapped_image_with_each_estimator() {
    let scene = scene(1.0 / 8.0, true);
    assert_eq!(scene.normal_maps.iter().flatten().count(), 1);
    let Some(failures) = gpu_vs_cpu_estimators("gpu bsdf_normalmap_with", &scene, SPP, 4400, BLOCK)
    else {
        return;
    };
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The back of a two-sided normal-mapped material on the GPU: `normalmap_back.xml` renders
/// Mitsuba's image (one exact value) to 1e-4 with MIS (`renderer/tests/normal_map.rs` has the
/// CPU's, to 1e-5).
#[test]
fn the_gpus_back_of_a_two_sided_normal_map_is_mitsubas() {
    let scene = crate::common::surface_detail::mitsuba_scene("normalmap_back");
    let settings = Settings {
        strategy: STRATEGIES_AND_OPTIMAL[3],
        ..Settings::default()
    };
    let Some(film) = gpu_render(&scene, settings, 4, 4407) else {
        return;
    };
    crate::common::surface_detail::assert_pixels_match(
        &film.mean(),
        "normalmap_back.exr",
        1e-4,
        "MIS",
    );
}

/// The image test's power against a GPU that ignores the map (the record's bits, the feature
/// gate): the GPU's render of the scene with its normal map removed (the plain rough plastic)
/// must fail against the CPU's with it (MIS, seed 4406).
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn a_gpu_without_the_normal_map_is_detected() {
    if crate::gpu_common::context().is_none() {
        return;
    }
    let with = scene(1.0 / 8.0, true);
    let mut without = scene(1.0 / 8.0, true);
    Arc::get_mut(&mut without).unwrap().normal_maps.clear();
    let settings = Settings {
        strategy: STRATEGIES_AND_OPTIMAL[3],
        ..Settings::default()
    };
    let what = "gpu bsdf_normalmap_with without its normal map vs cpu";
    let decision = crate::common::protocol::decide(what, 4406, SPP, |seed, n, alpha| {
        let gpu = gpu_render(&without, settings, n, seed).expect("a GPU");
        let cpu = cpu_render(&with, settings, n, seed.wrapping_add(CPU_SEED_OFFSET));
        gpu.z_test(&cpu, BLOCK, alpha)
    });
    assert!(
        decision.is_err(),
        "a GPU without the normal map went undetected"
    );
}

/// Parity of `normal_map_perturb` and `perturbation_factor` with `NormalMap::perturb` and
/// `Perturbation::factor` at 20k random inputs (seed 17/92): a random base frame, texel (with
/// the identity, the undefined `(½, ½, ½)` and normals along the tangent mixed in), viewer and
/// light direction, and every combination of the two flags. Frames agree to 2e-5 and factors to
/// 2e-5 relative, except where the light lies within 1e-4 of either frame's horizon (the side
/// rule's branch, which rounding may send either way: counted, < 1 %). This is what shows the
/// GPU's shadowing term: on the scene it changes block means by less than the z-test above
/// resolves at its budget (dropped on the GPU alone, MIS, at a sixteenth of the film: worst |z|
/// 2.5 at 32 spp and 2.7 at 128 against a critical 4.17; the CPU's gallery test, against a 16384-spp reference, sees
/// it). Its power: against the CPU's factor without the shadowing term, most rough inputs differ.
#[test]
fn normal_map_functions_match_the_cpu() {
    use glam::Vec3;
    use lumis::geometry::tangent::tangent_frame;
    use lumis::materials::normal_map::NormalMap;
    use lumis::rng::Rng;
    use lumis::sampling::sample_uniform_sphere;
    let Some(gpu) = crate::gpu_common::parity::any_scene_gpu() else {
        return;
    };
    let mut r = Rng::new(17, 92, 0);
    let n_items = 20_000;
    let mut inputs = Vec::with_capacity(n_items * 6);
    let mut cases = Vec::with_capacity(n_items);
    for k in 0..n_items {
        let n = sample_uniform_sphere(r.next_2d());
        let base = tangent_frame(n, sample_uniform_sphere(r.next_2d()));
        let texel = match k % 50 {
            0 => Vec3::new(0.5, 0.5, 1.0),
            1 => Vec3::splat(0.5),
            2 => Vec3::new(1.0, 0.5, 0.5),
            _ => Vec3::new(r.next_f32(), r.next_f32(), r.next_f32()),
        };
        let wo = sample_uniform_sphere(r.next_2d());
        let wi = sample_uniform_sphere(r.next_2d());
        let (flip, shadowing) = (k % 2 == 0, k % 4 < 2);
        let word = 1 | (flip as u32) << 1 | (shadowing as u32) << 2;
        let f = |v: Vec3, w: f32| [v.x, v.y, v.z, w];
        inputs.extend([
            f(base.s, f32::from_bits(word)),
            f(base.t, 0.0),
            f(base.n, 0.0),
            f(texel, 0.0),
            f(wo, 0.0),
            f(wi, 0.0),
        ]);
        let map = NormalMap {
            texture: lumis::textures::Texture::Constant(texel),
            flip_invalid_normals: flip,
            shadowing,
            height_scale: None,
        };
        cases.push((map, base, texel, wo, wi));
    }
    let body = "
        let word = bitcast<u32>(inp(0u).w);
        let base = Frame(inp(0u).xyz, inp(1u).xyz, inp(2u).xyz);
        let p = normal_map_perturb(word, 2.0 * inp(3u).xyz - vec3f(1.0), base, inp(4u).xyz);
        let wi = to_local(p.frame, inp(5u).xyz);
        outp(0u, vec4f(select(0.0, 1.0, p.ok), perturbation_factor(p.p, wi), wi.z, dot(wi, p.p.up)));
        outp(1u, vec4f(p.frame.n, 0.0));
        outp(2u, vec4f(p.frame.s, 0.0));
    ";
    let out = lumis::gpu::kernel::run_snippet(&gpu, &Settings::default(), body, &inputs, 6, 3)
        .unwrap_or_else(|e| panic!("{e}"));
    let (mut horizon, mut differ_without_shadowing, mut rough) = (0, 0, 0);
    for (k, (map, base, texel, wo, wi)) in cases.iter().enumerate() {
        let [o, n, s] = [out[3 * k], out[3 * k + 1], out[3 * k + 2]];
        let what = format!("item {k}: texel {texel:?}");
        let got = map.perturb(NormalMap::decode(*texel), || *base, *wo);
        assert_eq!(o[0] == 1.0, got.is_some(), "{what}");
        let Some((frame, p)) = got else { continue };
        let v = |a: [f32; 4]| Vec3::new(a[0], a[1], a[2]);
        assert!(
            (v(n) - frame.n).length() < 2e-5,
            "{what}: n {n:?} vs {:?}",
            frame.n
        );
        assert!(
            (v(s) - frame.s).length() < 2e-5,
            "{what}: s {s:?} vs {:?}",
            frame.s
        );
        let wi_local = frame.to_local(*wi);
        if wi_local.z.abs() < 1e-4 || o[3].abs() < 1e-4 {
            horizon += 1;
            continue;
        }
        let want = p.factor(wi_local);
        assert!(
            (o[1] - want).abs() <= 2e-5 * want.max(1.0),
            "{what}: factor {} vs {want}",
            o[1]
        );
        if map.shadowing && want > 0.0 {
            rough += 1;
            let plain = NormalMap {
                shadowing: false,
                ..map.clone()
            };
            let (_, q) = plain
                .perturb(NormalMap::decode(*texel), || *base, *wo)
                .unwrap();
            differ_without_shadowing += ((o[1] - q.factor(wi_local)).abs() > 2e-5) as usize;
        }
    }
    assert!(horizon * 100 < n_items, "{horizon} inputs at a horizon");
    assert!(
        differ_without_shadowing * 10 > rough * 9,
        "without the shadowing term only {differ_without_shadowing} of {rough} differ"
    );
}
