//! The studio's map and the lighting rule's two fluxes.

use super::*;
use crate::lights::envmap::EnvmapLight;
use crate::scene::mesh::MeshData;
use glam::DMat4;
use glam::Mat3;
use std::sync::Arc;

/// Every texel finite and positive (an environment map with a black or NaN texel would be
/// refused, or darken whole directions); the map is grey.
#[test]
fn the_studio_map_is_finite_positive_and_grey() {
    let map = studio_map();
    assert_eq!((map.width, map.height), STUDIO_MAP_SIZE);
    for t in &map.data {
        assert!(t.is_finite() && t.min_element() > 0.0, "{t}");
        assert_eq!(t.x, t.y);
        assert_eq!(t.y, t.z);
    }
}

/// The key light faces the model's front from above the camera's left: the map's brightest
/// direction, looked up through the environment map's own convention, has y > 0 (above), z > 0
/// (the camera's side) and x < 0 (the image's left). A map written in another convention
/// (φ measured from +z, or rows upside down) would light the model from behind or below.
#[test]
fn the_key_light_is_above_the_cameras_left() {
    let map = studio_map();
    let (w, h) = (map.width as usize, map.height as usize);
    let env = EnvmapLight::new(w, h, &map.data, 1.0, Mat3::IDENTITY, 1.0).unwrap();
    let toward = Vec3::from(SOFTBOXES[0].toward).normalize();
    let key = env.eval(toward).x;
    assert!(key > 0.9 * SOFTBOXES[0].radiance, "{key}");
    let (mut best, mut best_d) = (0.0f32, Vec3::ZERO);
    for j in 0..64 {
        for i in 0..128 {
            let (theta, phi) = (
                std::f32::consts::PI * (j as f32 + 0.5) / 64.0,
                2.0 * std::f32::consts::PI * (i as f32 + 0.5) / 128.0,
            );
            let d = Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            );
            let l = env.eval(d).x;
            if l > best {
                (best, best_d) = (l, d);
            }
        }
    }
    assert!(
        best_d.y > 0.3 && best_d.z > 0.2 && best_d.x < -0.2,
        "{best_d}"
    );
}

/// The mean luminance weighs rows by sin θ: a map bright in its top half only (rows 0..H/2)
/// has mean ½ over the sphere, not the plain texel average.
#[test]
fn the_mean_weighs_rows_by_their_solid_angle() {
    let (w, h) = (8u32, 101u32);
    let data = (0..h)
        .flat_map(|j| {
            std::iter::repeat_n(
                Vec3::splat(if 2 * j < h - 1 { 1.0 } else { 0.0 }),
                w as usize,
            )
        })
        .collect();
    let map = Image {
        width: w,
        height: h,
        data,
    };
    let mean = mean_luminance(&map);
    assert!((mean - 0.5).abs() < 0.02, "{mean}");
    let flat = Image {
        width: 2,
        height: 3,
        data: vec![Vec3::splat(2.0); 6],
    };
    assert!((mean_luminance(&flat) - 2.0).abs() < 1e-12);
}

/// `Φ_environment = π·Ȳ·(surface of the box)`, and the emitted flux counts each emitting mesh
/// by its placed area and luminance, the rest not at all.
#[test]
fn the_fluxes_are_area_times_luminance() {
    let unit = environment_flux(2.0, DVec3::ZERO, DVec3::ONE);
    assert!((unit - std::f64::consts::PI * 2.0 * 6.0).abs() < 1e-12);
    let flat = environment_flux(1.0, DVec3::ZERO, DVec3::new(2.0, 3.0, 0.0));
    assert!(
        (flat - std::f64::consts::PI * 12.0).abs() < 1e-12,
        "both faces of a flat box"
    );

    // A unit square (two triangles), scaled by 2 in x: area 2.
    let mesh = Arc::new(MeshData {
        positions: vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
        indices: vec![[0, 1, 2], [0, 2, 3]],
        ..Default::default()
    });
    let shape = |emission: DVec3| super::super::desc::ShapeDesc {
        geometry: GeometryDesc::Mesh {
            file: "m.obj".into(),
            shape_index: 0,
            to_world: DMat4::from_scale(DVec3::new(2.0, 1.0, 1.0)),
            face_normals: false,
            recompute_normals: false,
            mesh: mesh.clone(),
        },
        material: None,
        emission,
        emission_texture: None,
        json_path: String::new(),
    };
    let mut desc = crate::scene::parse::parse_scene(
        r#"{"camera": {"from": [0, 0, 5], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40,
            "width": 4, "height": 4}, "shapes": []}"#,
    )
    .unwrap();
    desc.shapes = vec![shape(DVec3::new(0.0, 3.0, 0.0)), shape(DVec3::ZERO)];
    let flux = emitted_flux(&desc, DVec3::ZERO, DVec3::ONE);
    let want = std::f64::consts::PI * 2.0 * 3.0 * 0.7152;
    assert!((flux - want).abs() < 1e-9, "{flux} vs {want}");
}

/// A light's flux: a point light's 4π·I, a spot's I times the solid angle of the cone halfway
/// between its beam and cutoff, a directional light's E times the box's shadow across it.
#[test]
fn the_lights_flux_counts_towards_the_emitters() {
    use crate::scene::desc::LightDesc;
    let mut desc = crate::scene::parse::parse_scene(
        r#"{"camera": {"from": [0, 0, 5], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40,
            "width": 4, "height": 4}, "shapes": [], "lights": [
            {"type": "point", "position": [0, 0, 0], "intensity": [2, 2, 2]},
            {"type": "spot", "from": [0, 0, 0], "to": [0, 0, 1], "up": [0, 1, 0],
             "intensity": [3, 3, 3], "cutoff_angle_deg": 60, "beam_width_deg": 60}]}"#,
    )
    .unwrap();
    let (lo, hi) = (DVec3::ZERO, DVec3::new(1.0, 2.0, 3.0));
    let pi = std::f64::consts::PI;
    // The spot's hard-edged cone of 60°: 2π(1 − cos 60°) = π.
    let want = 4.0 * pi * 2.0 + 3.0 * pi;
    let flux = emitted_flux(&desc, lo, hi);
    assert!((flux - want).abs() < 1e-9, "{flux} vs {want}");
    // Straight down onto the 1 × 3 top of the box, and along x onto its 2 × 3 side.
    for (direction, shadow) in [(DVec3::NEG_Y, 3.0), (DVec3::X, 6.0)] {
        desc.lights = vec![LightDesc::Directional {
            direction,
            irradiance: DVec3::splat(5.0),
        }];
        let flux = emitted_flux(&desc, lo, hi);
        assert!(
            (flux - 5.0 * shadow).abs() < 1e-9,
            "{flux} vs {}",
            5.0 * shadow
        );
    }
}
