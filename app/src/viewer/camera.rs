//! Mouse camera control on the scene's look-at camera (orbit about the look-at point, pan,
//! zoom), and writing the camera back into the scene file.

use glam::DVec3;
use lumis::scene::{CameraDesc, ProjectionDesc};
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
    // The image's height in world units at the look-at point.
    let height = match cam.projection {
        ProjectionDesc::Orthographic { view_size } => view_size[1],
        ProjectionDesc::Perspective { vfov_deg } | ProjectionDesc::ThinLens { vfov_deg, .. } => {
            2.0 * (cam.to - cam.from).length() * (vfov_deg.to_radians() * 0.5).tan()
        }
    };
    let world_per_point = height / view_height.max(1.0) as f64;
    let shift = (-(dx as f64) * right + dy as f64 * up) * world_per_point;
    cam.from += shift;
    cam.to += shift;
}

/// Moves the camera towards the look-at point (`steps > 0`) or away from it; each step is 10%.
/// An orthographic camera's image does not change with distance: its film shrinks instead.
pub fn zoom(cam: &mut CameraDesc, steps: f32) {
    let factor = 0.9f64.powf(steps as f64).max(1e-3);
    if let ProjectionDesc::Orthographic { view_size } = &mut cam.projection {
        *view_size = view_size.map(|s| s * factor);
        return;
    }
    let offset = cam.from - cam.to;
    cam.from = cam.to + offset * factor;
}

fn vec3(v: DVec3) -> Value {
    json!([v.x, v.y, v.z])
}

/// Replaces the camera's view (`from`, `to`, `up`) and projection (`vfov_deg`, a thin lens's
/// aperture and focus, an orthographic film's size) in the scene file `path`. Only the top-level
/// `camera` object's text changes; everything else in the file (the rest of the scene, key
/// order, formatting) stays as it is on disk.
pub fn save_camera(path: &Path, cam: &CameraDesc) -> Result<(), String> {
    let at = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
    let text = std::fs::read_to_string(path).map_err(|e| at(&e))?;
    let value: Value = serde_json::from_str(&text).map_err(|e| at(&e))?;
    let mut camera = value
        .get("camera")
        .and_then(Value::as_object)
        .cloned()
        .ok_or_else(|| at(&"no camera object"))?;
    camera.insert("from".into(), vec3(cam.from));
    camera.insert("to".into(), vec3(cam.to));
    camera.insert("up".into(), vec3(cam.up));
    let written = cam.to_json();
    for key in ["vfov_deg", "aperture_radius", "focus_distance", "view_size"] {
        if let Some(v) = written.get(key) {
            camera.insert(key.into(), v.clone());
        }
    }
    let span = top_level_value_span(&text, "camera").ok_or_else(|| at(&"no camera object"))?;
    let new_camera = serde_json::to_string(&Value::Object(camera)).map_err(|e| at(&e))?;
    let out = format!("{}{new_camera}{}", &text[..span.start], &text[span.end..]);
    std::fs::write(path, out).map_err(|e| at(&e))
}

/// Byte range of the value of `key` in the top-level object of the JSON document `text` (which
/// must be valid JSON: the caller has parsed it). A scan that tracks strings and nesting depth.
fn top_level_value_span(text: &str, key: &str) -> Option<std::ops::Range<usize>> {
    let bytes = text.as_bytes();
    let (mut depth, mut i) = (0usize, 0usize);
    // Start of the value being measured, and the depth it opened at.
    let mut value_start: Option<usize> = None;
    let mut expect_value = false;
    while i < bytes.len() {
        match bytes[i] {
            b'"' => {
                let s = i;
                i += 1;
                while bytes[i] != b'"' {
                    i += if bytes[i] == b'\\' { 2 } else { 1 };
                }
                if depth == 1 && value_start.is_none() && !expect_value {
                    // A key of the top-level object: is it ours?
                    let name: Result<String, _> = serde_json::from_str(&text[s..=i]);
                    expect_value = name.is_ok_and(|n| n == key);
                }
            }
            b':' if expect_value && depth == 1 => {
                let mut j = i + 1;
                while bytes[j].is_ascii_whitespace() {
                    j += 1;
                }
                value_start = Some(j);
                expect_value = false;
                if bytes[j] != b'{' && bytes[j] != b'[' {
                    // A scalar: it ends at the next ',' or '}' outside strings.
                    let mut k = j;
                    while bytes[k] != b',' && bytes[k] != b'}' {
                        k += 1;
                    }
                    return Some(j..k);
                }
            }
            b'{' | b'[' => depth += 1,
            b'}' | b']' => {
                depth -= 1;
                if depth == 1
                    && let Some(s) = value_start
                {
                    return Some(s..i + 1);
                }
            }
            _ => {}
        }
        i += 1;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cam() -> CameraDesc {
        CameraDesc {
            from: DVec3::new(0.0, 1.0, -5.0),
            to: DVec3::new(0.0, 1.0, 0.0),
            up: DVec3::Y,
            projection: ProjectionDesc::Perspective { vfov_deg: 40.0 },
            principal_point_offset: [0.0; 2],
            width: 64,
            height: 64,
            filter: Default::default(),
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
        // Only the camera's text changed: the rest of the file is byte for byte the same.
        let text = std::fs::read_to_string(&path).unwrap();
        let original = std::fs::read_to_string(src).unwrap();
        let (a, b) = (
            top_level_value_span(&original, "camera").unwrap(),
            top_level_value_span(&text, "camera").unwrap(),
        );
        assert!(original[a.clone()].starts_with('{') && original[a.clone()].ends_with('}'));
        assert_eq!(original[..a.start], text[..b.start]);
        assert_eq!(original[a.end..], text[b.end..]);
        assert!(original[a.end..].contains("\"materials\""));
        assert!(
            save_camera(&dir.join("missing.json"), &c)
                .unwrap_err()
                .contains("missing.json")
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn value_spans_skip_nested_keys_and_strings() {
        let t = r#"{"a": {"camera": 1}, "s": "\"camera\": {", "camera" : { "x": [1, {"y": 2}] } , "z": 3}"#;
        assert_eq!(
            &t[top_level_value_span(t, "camera").unwrap()],
            r#"{ "x": [1, {"y": 2}] }"#
        );
        assert_eq!(&t[top_level_value_span(t, "z").unwrap()], "3");
        assert_eq!(top_level_value_span(t, "y"), None);
    }
}
