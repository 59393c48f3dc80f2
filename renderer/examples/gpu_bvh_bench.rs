//! CWBVH against BVH2 on the GPU, with the real path tracer and with bare ray queries:
//! `cargo run --release -p lumis-renderer --example gpu_bvh_bench --
//! (SCENE.json | --mesh N) [SPP [ROUNDS]]`.
//!
//! `--mesh N` generates a bumpy N×N grid (2N² triangles) inside a closed box with a sphere and a
//! quad light. The two BVH kinds are measured alternately, ROUNDS times each, so a machine loaded
//! by other work slows both alike; the best and the median of the rounds are printed.
//!
//! * Path tracing: samples per second of `GpuProgressive` (SPP samples per pixel per round).
//! * Ray queries: Mrays/s of `scene_intersect` on incoherent rays (origins uniform in the scene's
//!   bounds, uniform directions) and of `scene_occluded` on shadow rays (from the CPU's hit points
//!   of those rays, spawned as the path tracer does, to random points in the bounds). A query
//!   kernel's time is its run with all rays minus its run with one workgroup, so the shader
//!   compilation that `run_snippet` repeats every call is not counted.

use glam::Vec3;
use lumis::geometry::Ray;
use lumis::geometry::ray::spawn_ray_to;
use lumis::gpu::kernel::run_snippet;
use lumis::gpu::{GpuContext, GpuProgressive, GpuScene};
use lumis::integrator::Settings;
use lumis::rng::Rng;
use lumis::scene::{Scene, parse_scene};
use std::sync::Arc;
use std::time::Instant;

/// Rays per query kernel run: enough that tracing takes longer than the compilation subtracted
/// from it (about 1 s on lavapipe), whose jitter would otherwise swamp it.
const RAYS: usize = 1 << 20;

/// A bumpy `n`×`n` grid over [-4, 4]² in a box with a sphere and a quad light, 256² pixels.
fn mesh_scene(n: usize) -> String {
    let mut pos = Vec::with_capacity((n + 1) * (n + 1));
    for j in 0..=n {
        for i in 0..=n {
            let x = 8.0 * i as f32 / n as f32 - 4.0;
            let z = 8.0 * j as f32 / n as f32 - 4.0;
            let y =
                0.5 + 0.25 * (1.7 * x).sin() * (1.3 * z).cos() + 0.1 * (5.0 * x + 3.0 * z).sin();
            pos.push(format!("[{x},{y},{z}]"));
        }
    }
    let mut idx = Vec::with_capacity(2 * n * n);
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i;
            let (b, c, d) = (a + 1, a + n + 1, a + n + 2);
            idx.push(format!("[{a},{c},{b}]"));
            idx.push(format!("[{b},{c},{d}]"));
        }
    }
    format!(
        r#"{{
  "camera": {{"from": [0, 3, -7], "to": [0, 0.5, 0], "up": [0, 1, 0], "vfov_deg": 50, "width": 256, "height": 256}},
  "materials": {{"white": {{"type": "diffuse", "albedo": [0.7, 0.7, 0.7]}},
                "red": {{"type": "diffuse", "albedo": [0.6, 0.1, 0.1]}}}},
  "shapes": [
    {{"type": "box", "min": [-5, -0.5, -8], "max": [5, 5, 5], "material": "white"}},
    {{"type": "sphere", "center": [1.5, 1.6, 0.5], "radius": 0.7, "material": "red"}},
    {{"type": "quad", "corner": [-1, 4.9, -1], "edge_u": [2, 0, 0], "edge_v": [0, 0, 2], "emission": [8, 8, 8]}},
    {{"type": "triangles", "positions": [{}], "indices": [{}], "material": "white"}}
  ]
}}"#,
        pos.join(","),
        idx.join(",")
    )
}

/// The query rays: incoherent closest-hit rays, and shadow rays from their hits.
fn query_rays(scene: &Scene) -> (Vec<[f32; 4]>, Vec<[f32; 4]>) {
    let (lo, hi) = scene.accel.bounds();
    let mut r = Rng::new(3, 0, 0);
    let point = |r: &mut Rng| lo + (hi - lo) * Vec3::new(r.next_f32(), r.next_f32(), r.next_f32());
    let f4 = |v: Vec3, w: f32| [v.x, v.y, v.z, w];
    let (mut random, mut shadow) = (Vec::new(), Vec::new());
    while random.len() < 2 * RAYS || shadow.len() < 2 * RAYS {
        let ray = Ray::new(
            point(&mut r),
            lumis::sampling::sample_uniform_sphere(r.next_2d()),
        );
        if random.len() < 2 * RAYS {
            random.extend([f4(ray.o, ray.t_max), f4(ray.d, 0.0)]);
        }
        if shadow.len() < 2 * RAYS
            && let Some(h) = scene.accel.intersect(&ray)
        {
            let s = spawn_ray_to(h.p, h.p_error, h.n, point(&mut r), Vec3::ZERO, ray.d);
            shadow.extend([f4(s.o, s.t_max), f4(s.d, 0.0)]);
        }
    }
    (random, shadow)
}

/// Seconds `body` takes on `inputs` beyond its fixed cost (compilation, setup, readback).
fn query_seconds(gpu: &GpuScene, body: &str, inputs: &[[f32; 4]]) -> f64 {
    let time = |inp: &[[f32; 4]]| {
        let t = Instant::now();
        run_snippet(gpu, &Settings::default(), body, inp, 2, 1).unwrap_or_else(|e| panic!("{e}"));
        t.elapsed().as_secs_f64()
    };
    let fixed = time(&inputs[..128]);
    (time(inputs) - fixed).max(1e-9)
}

const CLOSEST: &str = "let h = scene_intersect_t(Ray(inp(0u).xyz, inp(1u).xyz, inp(0u).w));
     outp(0u, vec4f(h.t, bitcast<f32>(h.prim), 0.0, 0.0));";
const OCCLUDED: &str = "let o = scene_occluded(Ray(inp(0u).xyz, inp(1u).xyz, inp(0u).w));
     outp(0u, vec4f(select(0.0, 1.0, o), 0.0, 0.0, 0.0));";

fn summary(v: &mut [f64]) -> String {
    v.sort_by(f64::total_cmp);
    format!("best {:.3}, median {:.3}", v[v.len() - 1], v[v.len() / 2])
}

fn main() {
    let mut args = std::env::args().skip(1);
    let usage = "usage: gpu_bvh_bench (SCENE.json | --mesh N) [SPP [ROUNDS]]";
    let what = args.next().expect(usage);
    let t = Instant::now();
    let scene = if what == "--mesh" {
        let n: usize = args.next().expect(usage).parse().expect("N");
        let desc = parse_scene(&mesh_scene(n)).unwrap_or_else(|e| panic!("{e}"));
        Scene::from_desc(&desc).unwrap_or_else(|e| panic!("{e}"))
    } else {
        Scene::load(what.as_ref()).unwrap_or_else(|e| panic!("{e}"))
    };
    let scene = Arc::new(scene);
    let spp: u32 = args.next().map_or(4, |s| s.parse().expect("SPP"));
    let rounds: usize = args.next().map_or(3, |s| s.parse().expect("ROUNDS"));
    let pixels = scene.camera.width as f64 * scene.camera.height as f64;
    println!(
        "scene: {what}, {} primitives, {}x{}, built in {:.2} s",
        scene.accel.primitives().len(),
        scene.camera.width,
        scene.camera.height,
        t.elapsed().as_secs_f64()
    );
    let ctx = GpuContext::new().unwrap_or_else(|e| panic!("{e}"));
    println!(
        "adapter: {} ({:?})",
        ctx.adapter_info.name, ctx.adapter_info.backend
    );
    let (random, shadow) = query_rays(&scene);

    let names = ["CWBVH", "BVH2"];
    let mut renders = Vec::new();
    let mut gpus = Vec::new();
    for bvh2 in [false, true] {
        let t = Instant::now();
        let gpu =
            GpuScene::with_bvh2(ctx.clone(), scene.clone(), bvh2).unwrap_or_else(|e| panic!("{e}"));
        let upload = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let mut r = GpuProgressive::with_context_and_bvh2(
            ctx.clone(),
            scene.clone(),
            Settings::default(),
            0,
            bvh2,
        )
        .unwrap_or_else(|e| panic!("{e}"));
        r.render_pass(1);
        println!(
            "{}: upload (incl. BVH2 build) {upload:.2} s, renderer + program + first pass {:.2} s",
            names[bvh2 as usize],
            t.elapsed().as_secs_f64()
        );
        gpus.push(gpu);
        renders.push(r);
    }
    let mut sps = [Vec::new(), Vec::new()];
    let mut closest = [Vec::new(), Vec::new()];
    let mut occluded = [Vec::new(), Vec::new()];
    for round in 0..rounds {
        // Alternate the order too, so neither kind always runs first in a round.
        let order = if round % 2 == 0 { [0, 1] } else { [1, 0] };
        for k in order {
            let t = Instant::now();
            renders[k].render_pass(spp);
            sps[k].push(spp as f64 * pixels / t.elapsed().as_secs_f64() / 1e6);
            closest[k].push(RAYS as f64 / query_seconds(&gpus[k], CLOSEST, &random) / 1e6);
            occluded[k].push(RAYS as f64 / query_seconds(&gpus[k], OCCLUDED, &shadow) / 1e6);
        }
    }
    for k in 0..2 {
        println!(
            "{:5}: path tracing Msamples/s {} | closest-hit Mrays/s {} | shadow Mrays/s {}",
            names[k],
            summary(&mut sps[k]),
            summary(&mut closest[k]),
            summary(&mut occluded[k])
        );
    }
    let med = |v: &[f64]| v[v.len() / 2];
    println!(
        "BVH2 / CWBVH (medians): path tracing {:.2}x, closest hit {:.2}x, shadow {:.2}x",
        med(&sps[1]) / med(&sps[0]),
        med(&closest[1]) / med(&closest[0]),
        med(&occluded[1]) / med(&occluded[0])
    );
}
