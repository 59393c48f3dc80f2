//! Dispatches of several samples per pixel (`GpuProgressive::set_samples_per_dispatch`, what small
//! images get on a real GPU) give the same film, bit for bit, as one sample per dispatch: each
//! layer's radiance waits in a scratch plane and `fold` adds the layers in sample order with the
//! same updates. Passes of 5 and 6 samples exercise a last dispatch of fewer layers. On lavapipe
//! (a CPU adapter, where the default is one sample per dispatch) this is the only coverage of the
//! multi-sample path.

mod gpu_common;

use gpu_common::*;
use lumis::engine::Film;
use lumis::gpu::GpuProgressive;
use lumis::integrator::Settings;
use lumis::scene::Scene;
use std::sync::Arc;

/// The seed Cornell box at 40×30 (a Cornell box with a hexagonal light, all material kinds).
fn small_cornell() -> Arc<Scene> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../assets/seed_cornell.json");
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let mut json: serde_json::Value = serde_json::from_str(&text).unwrap();
    json["camera"]["width"] = 40.into();
    json["camera"]["height"] = 30.into();
    build(&json.to_string())
}

fn render(scene: &Arc<Scene>, samples_per_dispatch: u32) -> Option<Film> {
    let ctx = context()?;
    let mut r = GpuProgressive::with_context(ctx, scene.clone(), Settings::default(), 7)
        .unwrap_or_else(|e| panic!("{e}"));
    r.set_samples_per_dispatch(samples_per_dispatch);
    assert_eq!(r.samples_per_dispatch(), samples_per_dispatch);
    r.render_pass(5);
    r.render_pass(6);
    Some(r.film().unwrap_or_else(|e| panic!("{e}")))
}

#[test]
fn films_do_not_depend_on_samples_per_dispatch() {
    let scene = small_cornell();
    let Some(one) = render(&scene, 1) else {
        return;
    };
    assert!(one.pixels.iter().any(|p| p.sum[0] > 0.0), "a black image");
    for k in [2, 4, 8] {
        let layered = render(&scene, k).unwrap();
        assert_eq!(layered.spp, one.spp);
        assert_eq!(layered.nonfinite, one.nonfinite);
        for (i, (a, b)) in one.pixels.iter().zip(&layered.pixels).enumerate() {
            let bits = |p: &lumis::engine::PixelSums| {
                [p.sum, p.sum_sq, p.sum_even].map(|v| v.map(f64::to_bits))
            };
            assert_eq!(
                bits(a),
                bits(b),
                "{k} samples per dispatch, pixel {i}: {a:?} vs {b:?}"
            );
        }
    }
}
