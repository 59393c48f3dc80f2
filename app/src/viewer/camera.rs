//! Mouse camera control on the scene's look-at camera (orbit about the look-at point, pan,
//! zoom), and writing the camera back into the scene file.

use glam::DVec3;
use lumis::scene::CameraDesc;
use serde_json::{Value, json};
use std::path::Path;

/// Radians of orbit per point of mouse drag.
const ORBIT_PER_POINT: f64 = 0.005;
/// Keep the view this far (radians) from the up axis, where the look-at frame degenerates.
const POLE_MARGIN: f64 = 0.02;

/// Orbits `cam` about its look-at point: `dx` turns about the up axis, `dy` tilts, both in
/// screen points. Dragging right turns the scene right (the camera moves left).
pub fn orbit(cam: &mut CameraDesc, dx: f32, dy: f32) {
    let up = cam.up.normalize();
    let offset = cam.from - cam.to;
    let dist = offset.length();
    let dir = offset / dist;
    // Angle from the up axis, and the azimuth in the plane perpendicular to it.
    let polar = dir.dot(up).clamp(-1.0, 1.0).acos();
    let new_polar = (polar - dy as f64 * ORBIT_PER_POINT)
        .clamp(POLE_MARGIN, std::f64::consts::PI - POLE_MARGIN);
    let flat = (dir - dir.dot(up) * up)
        .try_normalize()
        .unwrap_or_else(|| up.any_orthonormal_vector());
    let yaw = -(dx as f64) * ORBIT_PER_POINT;
    let side = up.cross(flat);
    let flat = flat * yaw.cos() + side * yaw.sin();
    let new_dir = up * new_polar.cos() + flat * new_polar.sin();
    cam.from = cam.to + new_dir * dist;
}

/// Moves camera and look-at point in the image plane by `dx`, `dy` screen points, scaled so that
/// the look-at point follows the mouse on a `view_height`-point-high image.
pub fn pan(cam: &mut CameraDesc, dx: f32, dy: f32, view_height: f32) {
    let forward = (cam.to - cam.from).normalize();
    let right = forward.cross(cam.up).normalize();
    let up = right.cross(forward);
    let dist = (cam.to - cam.from).length();
    let world_per_point =
        2.0 * dist * (cam.vfov_deg.to_radians() * 0.5).tan() / view_height.max(1.0) as f64;
    let shift = (-(dx as f64) * right + dy as f64 * up) * world_per_point;
    cam.from += shift;
    cam.to += shift;
}

/// Moves the camera towards the look-at point (`steps > 0`) or away from it; each step is 10%.
pub fn zoom(cam: &mut CameraDesc, steps: f32) {
    let offset = cam.from - cam.to;
    let factor = 0.9f64.powf(steps as f64);
    cam.from = cam.to + offset * factor.max(1e-3);
}

fn vec3(v: DVec3) -> Value {
    json!([v.x, v.y, v.z])
}

/// Replaces the camera's view (`from`, `to`, `up`, `vfov_deg`) in the scene file `path`, keeping
/// everything else in it (image size, the rest of the scene, the order of keys); the file is
/// rewritten as pretty-printed JSON.
pub fn save_camera(path: &Path, cam: &CameraDesc) -> Result<(), String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut value: Value =
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    let camera = value
        .get_mut("camera")
        .and_then(Value::as_object_mut)
        .ok_or_else(|| format!("{}: no camera object", path.display()))?;
    camera.insert("from".into(), vec3(cam.from));
    camera.insert("to".into(), vec3(cam.to));
    camera.insert("up".into(), vec3(cam.up));
    camera.insert("vfov_deg".into(), json!(cam.vfov_deg));
    let out = serde_json::to_string_pretty(&value).map_err(|e| e.to_string())? + "\n";
    std::fs::write(path, out).map_err(|e| format!("{}: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cam() -> CameraDesc {
        CameraDesc {
            from: DVec3::new(0.0, 1.0, -5.0),
            to: DVec3::new(0.0, 1.0, 0.0),
            up: DVec3::Y,
            vfov_deg: 40.0,
            width: 64,
            height: 64,
        }
    }

    #[test]
    fn orbit_keeps_distance_and_target_pan_moves_both_zoom_approaches() {
        let mut c = cam();
        orbit(&mut c, 120.0, 40.0);
        assert!(((c.from - c.to).length() - 5.0).abs() < 1e-9);
        assert_eq!(c.to, cam().to);
        // The scene turns with the mouse: dragging down tips its top towards the camera.
        assert!(c.from.y > 1.0, "dragging down looks from above");
        // Dragging right turns the scene right: the camera moves to its left (the image's
        // right is forward × up, as in `pan`).
        let right = (cam().to - cam().from).cross(cam().up);
        assert!((c.from - cam().from).dot(right) < 0.0, "{:?}", c.from);
        let mut p = cam();
        pan(&mut p, 10.0, 0.0, 100.0);
        assert!(((p.from - p.to) - (cam().from - cam().to)).length() < 1e-12);
        assert!(p.to != cam().to);
        let mut z = cam();
        zoom(&mut z, 1.0);
        assert!(((z.from - z.to).length() - 4.5).abs() < 1e-9);
    }

    #[test]
    fn saved_camera_loads_back_and_the_rest_of_the_scene_is_kept() {
        let src = concat!(env!("CARGO_MANIFEST_DIR"), "/../assets/seed_cornell.json");
        let dir = std::env::temp_dir().join(format!("lumis-camera-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("scene.json");
        std::fs::copy(src, &path).unwrap();
        let before = lumis::scene::load_scene(&path).unwrap();
        let mut c = before.camera.clone();
        orbit(&mut c, 40.0, 10.0);
        zoom(&mut c, 2.0);
        save_camera(&path, &c).unwrap();
        let after = lumis::scene::load_scene(&path).unwrap();
        assert_eq!(after.camera, c);
        assert_ne!(after.camera, before.camera);
        assert_eq!(after.materials, before.materials);
        assert_eq!(after.shapes.len(), before.shapes.len());
        // Top-level keys stay in the file's order, read from the raw text (a parsed map could
        // have sorted them).
        let text = std::fs::read_to_string(&path).unwrap();
        let original = std::fs::read_to_string(src).unwrap();
        let order = |t: &str| {
            let mut keys: Vec<(usize, &str)> = ["camera", "materials", "shapes", "max_depth"]
                .iter()
                .filter_map(|k| t.find(&format!("\"{k}\"")).map(|i| (i, *k)))
                .collect();
            keys.sort();
            keys.into_iter().map(|(_, k)| k).collect::<Vec<_>>()
        };
        assert_eq!(order(&text), order(&original));
        assert!(order(&original).len() >= 3);
        assert!(
            save_camera(&dir.join("missing.json"), &c)
                .unwrap_err()
                .contains("missing.json")
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
