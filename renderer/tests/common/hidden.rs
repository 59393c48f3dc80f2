//! The hide_emitters scene (Mitsuba's `hide_emitters`, `renderer/tests/hide_emitters.rs` and
//! its GPU twin `tests/gpu/hide_emitters.rs`): a grey sky, an emitting black quad and a diffuse
//! floor, each seen whole by some pixels, and which pixels see only one of them.

use super::build;
use lumis::geometry::primitive::NONE;
use lumis::scene::Scene;
use std::sync::Arc;

/// What a camera ray meets first.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Seen {
    /// Nothing: the background.
    Sky,
    /// An emitting shape.
    Emitter,
    /// A surface that does not emit.
    Surface,
}

/// The scene, `size × size` pixels, with `hide_emitters` as given.
pub fn hidden_scene(hide: bool, size: u32) -> Arc<Scene> {
    build(&format!(
        r#"{{
  "camera": {{"from": [0, 1, -3], "to": [0, 0.6, 0], "up": [0, 1, 0], "vfov_deg": 60, "width": {size}, "height": {size}}},
  "hide_emitters": {hide},
  "background": [0.3, 0.4, 0.5],
  "materials": {{"floor": {{"type": "diffuse", "albedo": [0.6, 0.6, 0.6]}}}},
  "shapes": [
    {{"type": "quad", "corner": [-50, 0, -50], "edge_u": [0, 0, 100], "edge_v": [100, 0, 0], "material": "floor"}},
    {{"type": "quad", "corner": [-0.5, 0.3, 0], "edge_u": [0, 1, 0], "edge_v": [1, 0, 0], "emission": [4, 3, 2]}}
  ]
}}"#
    ))
}

/// What the ray through film position `(x, y)` meets.
fn seen(scene: &Scene, x: f32, y: f32) -> Seen {
    let ray = scene.camera.ray(x, y);
    match scene.accel.intersect(&ray) {
        None => Seen::Sky,
        Some(hit) if scene.accel.primitives()[hit.prim as usize].light != NONE => Seen::Emitter,
        Some(_) => Seen::Surface,
    }
}

/// Per pixel, what all of a 5×5 grid over its square with half a pixel of margin (where a box
/// filter's samples land, and more) meets, or `None` where they differ.
pub fn classify(scene: &Scene, size: u32) -> Vec<Option<Seen>> {
    let mut out = Vec::new();
    for py in 0..size {
        for px in 0..size {
            let at = |i: u32, j: u32| {
                let (dx, dy) = (-0.5 + 0.5 * i as f32, -0.5 + 0.5 * j as f32);
                seen(scene, px as f32 + dx, py as f32 + dy)
            };
            let first = at(0, 0);
            let same = (0..5).all(|i| (0..5).all(|j| at(i, j) == first));
            out.push(same.then_some(first));
        }
    }
    out
}

/// Checks a film rendered with hide_emitters against one without, at the same seed: where the
/// camera sees the sky or an emitter whole, hidden is black and shown is not; where it sees a
/// surface whole, they are equal bit for bit (the same paths, and only the camera ray's own
/// emission is dropped); everywhere hidden ≤ shown. Each class must have pixels.
pub fn check_hidden(classes: &[Option<Seen>], hidden: &[glam::Vec3], shown: &[glam::Vec3]) {
    let mut counts = [0usize; 3];
    for (i, ((c, h), s)) in classes.iter().zip(hidden).zip(shown).enumerate() {
        assert!(h.cmple(*s).all(), "pixel {i}: hidden {h} > shown {s}");
        match c {
            Some(Seen::Sky) | Some(Seen::Emitter) => {
                assert_eq!(*h, glam::Vec3::ZERO, "pixel {i} ({c:?}) hidden");
                assert!(s.min_element() > 0.0, "pixel {i} ({c:?}) shown {s}");
                counts[if *c == Some(Seen::Sky) { 0 } else { 1 }] += 1;
            }
            Some(Seen::Surface) => {
                assert_eq!(h, s, "pixel {i} sees only the floor");
                counts[2] += 1;
            }
            None => {}
        }
    }
    assert!(
        counts.iter().all(|&n| n >= 10),
        "pixels per class (sky, emitter, floor): {counts:?}"
    );
}
