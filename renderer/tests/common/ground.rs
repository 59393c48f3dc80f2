//! The background furnace's scene: a 10⁴-wide diffuse ground quad under a background, seen from
//! 1 unit above it, and which pixels see only the ground or only the sky (`renderer/tests/furnace.rs`,
//! `renderer/tests/envmap.rs`).

use super::{build, json_vec};
use glam::Vec3;
use lumis::scene::Scene;
use std::sync::Arc;

/// Camera of the background furnace: 1 unit above the ground, looking down 35° with a 90° field of
/// view, so the top rows see the sky and the rest the ground.
const BG_FROM: Vec3 = Vec3::new(0.0, 1.0, 0.0);
const BG_TO: Vec3 = Vec3::new(0.0, 0.3, 1.0);
const BG_VFOV: f32 = 90.0;
/// Half width of the ground quad.
const GROUND_HALF: f32 = 5000.0;

/// The ground (diffuse, `albedo`) under `background` (its JSON: a colour or an envmap object),
/// `size × size` pixels.
pub fn background_scene(albedo: Vec3, background: &str, size: u32) -> Arc<Scene> {
    let h = GROUND_HALF;
    let json = format!(
        r#"{{
  "camera": {{"from": {}, "to": {}, "up": [0, 1, 0], "vfov_deg": {BG_VFOV}, "width": {size}, "height": {size}}},
  "background": {background},
  "materials": {{"ground": {{"type": "diffuse", "albedo": {}}}}},
  "shapes": [{{"type": "quad", "corner": [-{h}, 0, -{h}], "edge_u": [0, 0, {}], "edge_v": [{}, 0, 0], "material": "ground"}}]
}}"#,
        json_vec(BG_FROM),
        json_vec(BG_TO),
        json_vec(albedo),
        2.0 * h,
        2.0 * h,
    );
    let scene = build(&json);
    assert_eq!(scene.lights.len(), 1, "the background is the only light");
    scene
}

/// Whether the ray through film position `(x, y)` hits the ground quad.
fn sees_ground(scene: &Scene, x: f32, y: f32) -> bool {
    let ray = scene.camera.ray(x, y);
    if ray.d.y >= 0.0 {
        return false;
    }
    let t = -ray.o.y / ray.d.y;
    let hit = ray.o + t * ray.d;
    hit.x.abs() < GROUND_HALF && hit.z.abs() < GROUND_HALF
}

/// Pixels whose whole square (with half a pixel of margin) sees the ground, and those that see
/// only the sky. The set of directions that hit a convex quad (or the upper hemisphere) is convex,
/// as is a pixel's square of directions, so checking the corners suffices.
pub fn classify_pixels(scene: &Scene, size: u32) -> (Vec<usize>, Vec<usize>) {
    let (mut ground, mut sky) = (Vec::new(), Vec::new());
    for py in 0..size {
        for px in 0..size {
            let corners = [(-0.5, -0.5), (1.5, -0.5), (-0.5, 1.5), (1.5, 1.5)]
                .map(|(dx, dy)| sees_ground(scene, px as f32 + dx, py as f32 + dy));
            let i = (py * size + px) as usize;
            if corners.iter().all(|&g| g) {
                ground.push(i);
            } else if corners.iter().all(|&g| !g) {
                sky.push(i);
            }
        }
    }
    (ground, sky)
}
