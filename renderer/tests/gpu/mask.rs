//! Alpha masks on the GPU (issue 40 item 2; `materials/mask.wgsl`, `prim_hit_t` in
//! `geometry/bvh.wgsl`), beside `xml_mask.xml` against the CPU and Mitsuba 3.9.1
//! (`renderer/tests/gpu/mitsuba_refs.rs`):
//!
//! - [`mask_decisions_match_the_cpu`]: `mask_meets` against `Scene::meets` on `xml_mask.xml`'s
//!   masked primitives (a textured pane of two triangles, a sphere at the constant ½) at 8k
//!   random rays' candidate hits (seed 4600), the CPU's distance handed to the GPU. Exact on the
//!   sphere (the hash is bit for bit and the opacity a constant); on the pane exact except where
//!   the opacity lies within 1e-3 of the hash (the two sides' texture coordinates differ by
//!   rounding), skipped and counted (< 1 % required). Detects a wrong salt (the CPU's decision
//!   with the primitive's index + 1 disagrees at about half the hits, checked), the comparison
//!   the wrong way round, an opacity read at the wrong texture coordinates or from the wrong
//!   material's record.
//! - [`opacity_one_changes_no_gpu_bit`]: as `renderer/tests/mask.rs` on the CPU, opacity 1 on
//!   every material of `textured_mesh.json` leaves the GPU's film bit for bit as it was, though
//!   the program then carries the masked traversals (lavapipe: the same arithmetic, only the
//!   added any-hit test), and opacity ½ changes it (MIS, 4 spp, seed 4610).
//! - [`the_gpu_renders_the_cpus_masked_image_with_each_estimator`]: `xml_mask.xml` on the GPU and
//!   the CPU with light sampling, BSDF sampling and MIS, compared by the block z-test of
//!   `renderer/tests/gpu/images.rs`
//!   (8×8 blocks, family-wise α = 0.01, both films' variances, the suite's two stages; 32 spp,
//!   GPU seeds 4620 + i, CPU 5620 + i), as for the normal map's scene and for the same reason:
//!   a decision hashes the hit's distance, whose last bits the two sides round differently, so
//!   same-seed films diverge wherever a path meets a mask.

use crate::common::surface_detail::{mitsuba_scene, with_opacity};
use crate::gpu_common::context;
use crate::gpu_common::images::{gpu_render, gpu_vs_cpu_estimators};
use crate::gpu_common::parity::{f4, run};
use glam::Vec3;
use lumis::geometry::Ray;
use lumis::geometry::triangle::TriangleRay;
use lumis::gpu::GpuScene;
use lumis::integrator::{Heuristic, Settings, Strategy};
use lumis::materials::mask::kept;
use lumis::materials::mix::hash_unit;
use lumis::rng::Rng;

#[test]
fn mask_decisions_match_the_cpu() {
    let Some(ctx) = context() else {
        return;
    };
    let scene = mitsuba_scene("xml_mask");
    let prims = scene.accel.primitives();
    let masked: Vec<usize> = (0..prims.len())
        .filter(|&i| matches!(scene.opacity.get(prims[i].material as usize), Some(Some(_))))
        .collect();
    assert_eq!(masked.len(), 3, "the pane's two triangles and the sphere");
    let gpu = GpuScene::new(ctx, scene.clone()).expect("upload");
    let mut r = Rng::new(4600, 0, 0);
    let mut inputs = Vec::new();
    let mut cases = Vec::new();
    while cases.len() < 8192 {
        let id = masked[(r.next_f32() * masked.len() as f32) as usize % masked.len()];
        let (lo, hi) = prims[id].shape.bounds();
        let target = lo + (hi - lo) * Vec3::new(r.next_f32(), r.next_f32(), r.next_f32());
        let o = Vec3::new(
            4.0 * r.next_f32() - 2.0,
            0.2 + 2.5 * r.next_f32(),
            -3.0 * r.next_f32(),
        );
        let ray = Ray::new(o, (target - o).normalize());
        let Some(h) = prims[id].shape.intersect_t(&ray, &TriangleRay::new(&ray)) else {
            continue;
        };
        inputs.extend([f4(ray.o, h.t), f4(ray.d, id as f32)]);
        cases.push((id, ray, h));
    }
    let body = "let ray = Ray(inp(0u).xyz, inp(1u).xyz, inf());
         let meets = mask_meets(u32(inp(1u).w), ray, inp(0u).w);
         outp(0u, vec4f(select(0.0, 1.0, meets), 0.0, 0.0, 0.0));";
    let out = run(&gpu, body, &inputs, 2, 1);
    let (mut near, mut pane, mut wrong_salt, mut kept_n) = (0, 0, 0, 0);
    for ((id, ray, h), o) in cases.iter().zip(&out) {
        let cpu = scene.meets(*id, ray, h);
        let gpu_meets = o[0] == 1.0;
        kept_n += cpu as usize;
        let salted = kept(alpha_at(&scene, *id, ray, h), ray.o, h.t, *id as u32 + 1);
        wrong_salt += (salted != cpu) as usize;
        if matches!(prims[*id].shape, lumis::geometry::Shape::Triangle { .. }) {
            pane += 1;
            let u = hash_unit(ray.o, h.t, *id as u32);
            if (alpha_at(&scene, *id, ray, h) - u).abs() < 1e-3 {
                near += 1;
                continue;
            }
        }
        assert_eq!(gpu_meets, cpu, "prim {id}, {ray:?}, t {}", h.t);
    }
    let n = cases.len();
    assert!(
        near * 100 < pane,
        "{near} of {pane} pane hits near the threshold"
    );
    assert!(
        kept_n > n / 5 && kept_n < 4 * n / 5,
        "kept {kept_n} of {n}: both decisions are tested"
    );
    assert!(
        wrong_salt > n / 5,
        "a wrong salt changes only {wrong_salt} of {n} decisions"
    );
}

/// The CPU's opacity of primitive `id` at its hit `h` on `ray`.
fn alpha_at(
    scene: &lumis::scene::Scene,
    id: usize,
    ray: &Ray,
    h: &lumis::geometry::ShapeHit,
) -> f32 {
    let prim = &scene.accel.primitives()[id];
    let opacity = scene.opacity[prim.material as usize].as_ref().unwrap();
    opacity.eval_scalar(scene.uv(&prim.shape.surface_hit(ray, *h, id as u32)))
}

#[test]
fn opacity_one_changes_no_gpu_bit() {
    if context().is_none() {
        return;
    }
    let settings = Settings {
        strategy: Strategy::Mis {
            heuristic: Heuristic::Power,
        },
        ..Settings::default()
    };
    let sums = |opacity: Option<f32>| {
        let film =
            gpu_render(&with_opacity("textured_mesh", opacity), settings, 4, 4610).expect("a GPU");
        film.pixels.iter().map(|p| p.sum).collect::<Vec<_>>()
    };
    let base = sums(None);
    assert!(base == sums(Some(1.0)), "opacity 1 changed bits");
    assert!(base != sums(Some(0.5)), "opacity ½ changed nothing");
}

#[test]
fn the_gpu_renders_the_cpus_masked_image_with_each_estimator() {
    let scene = mitsuba_scene("xml_mask");
    let Some(failures) = gpu_vs_cpu_estimators("gpu xml_mask", &scene, 32, 4620, 8) else {
        return;
    };
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
