//! Samples per second of the GPU and CPU backends on one scene:
//! `cargo run --release -p lumis-renderer --example gpu_bench -- SCENE.json [SPP [MAX_DEPTH]]`.
//! Prints the adapter, the pipeline build time and both rates (the CPU on all cores).

use lumis::engine::Progressive;
use lumis::gpu::{GpuContext, GpuProgressive};
use lumis::integrator::Settings;
use lumis::scene::Scene;
use std::sync::Arc;
use std::time::Instant;

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args
        .next()
        .expect("usage: gpu_bench SCENE.json [SPP [MAX_DEPTH]]");
    let spp: u32 = args.next().map_or(16, |s| s.parse().expect("SPP"));
    let max_depth: Option<i32> = args.next().map(|s| s.parse().expect("MAX_DEPTH"));
    let settings = Settings {
        max_depth,
        ..Settings::default()
    };
    let scene = Arc::new(Scene::load(path.as_ref()).unwrap_or_else(|e| panic!("{e}")));
    let pixels = scene.camera.width as f64 * scene.camera.height as f64;
    let ctx = GpuContext::new().unwrap_or_else(|e| panic!("{e}"));
    println!(
        "adapter: {} ({:?})",
        ctx.adapter_info.name, ctx.adapter_info.backend
    );
    let t = Instant::now();
    let mut gpu = GpuProgressive::with_context(ctx, scene.clone(), settings, 0)
        .unwrap_or_else(|e| panic!("{e}"));
    gpu.render_pass(1);
    println!(
        "gpu: program build + first pass {:.2} s",
        t.elapsed().as_secs_f64()
    );
    let t = Instant::now();
    gpu.render_pass(spp);
    let s = t.elapsed().as_secs_f64();
    println!(
        "gpu: {spp} spp in {s:.2} s = {:.3e} samples/s",
        spp as f64 * pixels / s
    );
    let mut cpu = Progressive::new(scene, settings, 0);
    let t = Instant::now();
    cpu.render_pass(spp);
    let s = t.elapsed().as_secs_f64();
    println!(
        "cpu: {spp} spp in {s:.2} s = {:.3e} samples/s",
        spp as f64 * pixels / s
    );
}
