//! Mitsuba's `hide_emitters` on the CPU: the camera ray's own emission (the sky, an emitting
//! shape) is dropped and nothing else changes (`tests/common/hidden.rs` states the checks; the
//! GPU twin is `tests/gpu/hide_emitters.rs`). Deterministic: the same seed with and without.

mod common;

use common::hidden::{check_hidden, classify, hidden_scene};
use common::{STRATEGIES_AND_OPTIMAL, render};
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
        let h = render(&hidden, settings, SPP, 11).film().mean();
        let s = render(&shown, settings, SPP, 11).film().mean();
        check_hidden(&classes, &h, &s);
    }
}
