//! Fuzz target: arbitrary bytes as a scene file. Text that is not UTF-8 is skipped (reading the
//! file fails before the parser sees it). Everything else goes through `Scene::from_json_str`, the
//! path of `lumis render`, and must either fail with a one-line error or build a scene, from
//! which a few camera paths are traced. Any panic (including debug assertions and integer
//! overflow, which `cargo fuzz` enables) is a crash. Non-finite samples are the property test's
//! business (`renderer/tests/scene_mutation.rs`), not this target's.

#![no_main]

use libfuzzer_sys::fuzz_target;
use lumis::integrator::{Settings, radiance};
use lumis::rng::Rng;
use lumis::sampler::Sampler;
use lumis::scene::Scene;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match Scene::from_json_str(text) {
        Err(e) => {
            let message = e.to_string();
            assert!(!message.contains(['\n', '\r']), "not one line: {message:?}");
        }
        Ok(scene) => {
            // Four paths through the image's corners and centre; short, so that runs stay fast.
            let settings = Settings {
                max_depth: Some(4),
                ..Settings::default()
            };
            let (w, h) = (scene.camera.width as f32, scene.camera.height as f32);
            for (i, (x, y)) in [
                (0.5, 0.5),
                (w - 0.5, 0.5),
                (0.5, h - 0.5),
                (w / 2.0, h / 2.0),
            ]
            .into_iter()
            .enumerate()
            {
                let mut rng = Sampler::from(Rng::new(0, i as u32, 0));
                radiance(&scene, scene.camera.ray(x, y), &mut rng, &settings);
            }
        }
    }
});
