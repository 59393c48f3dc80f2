//! Mitsuba's `hide_emitters` on the GPU (`integrator/path.wgsl`), checked as on the CPU
//! (`renderer/tests/hide_emitters.rs`, the checks in `tests/common/hidden.rs`): the camera
//! ray's own emission is dropped and nothing else changes, at the same seed.

use crate::common::STRATEGIES_AND_OPTIMAL;
use crate::common::hidden::{check_hidden, classify, hidden_scene};
use crate::gpu_common::images::gpu_render;
use lumis::integrator::Settings;

const SIZE: u32 = 48;
/// Past mis-optimal's first 8 samples, so its learnt weights are used too.
const SPP: u32 = 12;

#[test]
fn hidden_emitters_drop_only_what_the_camera_ray_sees() {
    let (hidden, shown) = (hidden_scene(true, SIZE), hidden_scene(false, SIZE));
    let classes = classify(&shown, SIZE);
    for strategy in STRATEGIES_AND_OPTIMAL {
        let settings = Settings {
            strategy,
            ..Settings::default()
        };
        let Some(h) = gpu_render(&hidden, settings, SPP, 11) else {
            return;
        };
        let s = gpu_render(&shown, settings, SPP, 11).expect("a GPU");
        check_hidden(&classes, &h.mean(), &s.mean());
    }
}
