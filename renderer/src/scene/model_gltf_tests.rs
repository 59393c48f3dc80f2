//! A glTF file's `KHR_lights_punctual` lights as lumis' lights (`mesh/gltf_lights.rs`): placed
//! by their nodes, photometric units over 683 lm/W, and counted by the studio's rule.

use super::super::desc::{BackgroundDesc, LightDesc, LookAt};
use super::super::model::{ModelOptions, model_scene, model_scene_with};
use crate::scene::mesh::gltf::test_asset::*;
use glam::DVec3;
use serde_json::{Value, json};
use std::path::PathBuf;

const NO_STUDIO: ModelOptions = ModelOptions { studio: false };

/// A unit quad (z = 0, facing +z) and the nodes `lights` (each a node JSON object), with the
/// light list `list`.
fn with_lights(dir: &Dir, name: &str, list: Value, light_nodes: &[Value]) -> PathBuf {
    let mut a = quad(U16);
    for n in light_nodes {
        a.node(n.clone());
    }
    a.root.insert(
        "extensions".into(),
        json!({"KHR_lights_punctual": {"lights": list}}),
    );
    a.root
        .insert("extensionsUsed".into(), json!(["KHR_lights_punctual"]));
    a.write_glb(dir, name)
}

fn light_node(light: usize, rest: Value) -> Value {
    let mut n = rest;
    n["extensions"] = json!({"KHR_lights_punctual": {"light": light}});
    n
}

fn close(a: DVec3, b: DVec3) -> bool {
    (a - b).abs().max_element() < 1e-6
}

/// Point, spot and directional lights at their nodes, aimed along the node's −z, with
/// glTF's candela and lux over 683; `range` and the spot's falloff are named in the warning.
#[test]
fn punctual_lights_become_lumis_lights() {
    let dir = Dir::new("model-lights");
    let half = std::f32::consts::FRAC_1_SQRT_2;
    let path = with_lights(
        &dir,
        "lights.glb",
        json!([
            {"type": "point", "color": [1, 0.5, 0.25], "intensity": 1366},
            {"type": "spot", "intensity": 683, "range": 10,
             "spot": {"innerConeAngle": 0.25, "outerConeAngle": 0.5}},
            {"type": "directional", "intensity": 341.5},
        ]),
        &[
            light_node(0, json!({"translation": [1, 2, 3]})),
            // −90° about x: its −z points down.
            light_node(
                1,
                json!({"translation": [0, 4, 0], "rotation": [-half, 0, 0, half]}),
            ),
            light_node(2, json!({})),
        ],
    );
    let d = model_scene_with(&path, NO_STUDIO).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(d.lights.len(), 3);
    let LightDesc::Point {
        position,
        intensity,
    } = &d.lights[0]
    else {
        panic!("{:?}", d.lights[0])
    };
    assert!(close(*position, DVec3::new(1.0, 2.0, 3.0)), "{position}");
    assert!(close(*intensity, DVec3::new(2.0, 1.0, 0.5)), "{intensity}");
    let LightDesc::Spot {
        frame: LookAt { from, to, .. },
        intensity,
        cutoff_angle_deg,
        beam_width_deg,
        texture: None,
    } = &d.lights[1]
    else {
        panic!("{:?}", d.lights[1])
    };
    assert!(close(*from, DVec3::new(0.0, 4.0, 0.0)), "{from}");
    assert!(close((*to - *from).normalize(), DVec3::NEG_Y), "{to}");
    assert!(close(*intensity, DVec3::ONE), "{intensity}");
    assert!((cutoff_angle_deg - 0.5f64.to_degrees()).abs() < 1e-9);
    assert!((beam_width_deg - 0.25f64.to_degrees()).abs() < 1e-9);
    let LightDesc::Directional {
        direction,
        irradiance,
    } = &d.lights[2]
    else {
        panic!("{:?}", d.lights[2])
    };
    assert!(close(*direction, DVec3::NEG_Z), "{direction}");
    assert!(close(*irradiance, DVec3::splat(0.5)), "{irradiance}");
    let w = d.warnings.join("\n");
    assert!(
        w.contains("extensions.KHR_lights_punctual.lights[1].range"),
        "{w}"
    );
    assert!(
        w.contains("extensions.KHR_lights_punctual.lights[1].spot: its falloff"),
        "{w}"
    );
    // The extension is read: not named as one lumis ignores.
    assert!(!w.contains("extension KHR_lights_punctual"), "{w}");
}

/// The lights count in the rule that keeps or drops the environment: without the studio
/// (radiance 1) the unit quad's box receives Φ_environment = π·1·2 (its two faces; the box is
/// flat); a white point light of 683 cd (1 W/sr) emits 4π, more, and the environment goes; one
/// of a quarter of that, π, keeps it.
#[test]
fn punctual_lights_alone_can_switch_off_the_environment() {
    let dir = Dir::new("model-lights-flux");
    for (candela, kept) in [(683.0, false), (170.75, true)] {
        let path = with_lights(
            &dir,
            &format!("point{kept}.glb"),
            json!([{"type": "point", "intensity": candela}]),
            &[light_node(0, json!({"translation": [0, 0, 1]}))],
        );
        let d = model_scene_with(&path, NO_STUDIO).unwrap_or_else(|e| panic!("{e}"));
        let want = if kept { DVec3::ONE } else { DVec3::ZERO };
        assert_eq!(d.background, BackgroundDesc::Constant(want), "{candela} cd");
    }
}

/// Bad lights are errors that name the file and the JSON path; a required
/// `KHR_lights_punctual` is read, not refused.
#[test]
fn bad_punctual_lights_are_named() {
    let dir = Dir::new("model-lights-bad");
    let node = |l| [light_node(l, json!({}))];
    let cases = [
        (
            json!([{"type": "point"}]),
            node(1),
            "nodes[1].extensions.KHR_lights_punctual.light: light 1 does not exist (1 lights in \
             extensions.KHR_lights_punctual.lights)",
        ),
        (
            json!([{"type": "spot", "spot": {"outerConeAngle": 2}}]),
            node(0),
            "extensions.KHR_lights_punctual.lights[0].spot.outerConeAngle: 2 is outside (0, π/2]",
        ),
        (
            json!([{"type": "spot", "spot": {"innerConeAngle": 0.5, "outerConeAngle": 0.5}}]),
            node(0),
            "extensions.KHR_lights_punctual.lights[0].spot.innerConeAngle: 0.5 is not below \
             outerConeAngle 0.5",
        ),
        (
            json!([{"type": "area"}]),
            node(0),
            "extensions.KHR_lights_punctual.lights[0].type: expected \"point\", \"spot\" or \
             \"directional\", found \"area\"",
        ),
        (
            json!([{"type": "point", "intensity": -1}]),
            node(0),
            "extensions.KHR_lights_punctual.lights[0].intensity: expected a finite number ≥ 0, \
             found -1",
        ),
        (
            json!([{"type": "point", "color": [2, 0, 0]}]),
            node(0),
            "extensions.KHR_lights_punctual.lights[0].color: expected 3 numbers in [0, 1]",
        ),
        (
            json!([{"type": "directional"}]),
            [light_node(0, json!({"scale": [1, 1, 0]}))],
            "nodes[1]: its transform flattens the direction of \
             extensions.KHR_lights_punctual.lights[0] (its −z)",
        ),
    ];
    for (k, (list, nodes, want)) in cases.into_iter().enumerate() {
        let path = with_lights(&dir, &format!("bad{k}.glb"), list, &nodes);
        let e = model_scene(&path).unwrap_err().to_string();
        assert!(e.contains(&format!("bad{k}.glb {want}")), "{e}");
    }
    let mut a = quad(U16);
    a.node(light_node(0, json!({})));
    a.root.insert(
        "extensions".into(),
        json!({"KHR_lights_punctual": {"lights": [{"type": "point"}]}}),
    );
    a.root
        .insert("extensionsRequired".into(), json!(["KHR_lights_punctual"]));
    a.root
        .insert("extensionsUsed".into(), json!(["KHR_lights_punctual"]));
    let d = model_scene(&a.write_glb(&dir, "required.glb")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(d.lights.len(), 1);
}

/// The lights render: a quad lit only by a point light in front of it is not black (the
/// environment is off: the light's 4π·10 outweighs it), and black without the light.
#[test]
fn a_point_light_lights_the_model() {
    use crate::engine::Progressive;
    use crate::integrator::Settings;
    use crate::scene::Scene;
    use std::sync::Arc;
    let dir = Dir::new("model-lights-render");
    let path = with_lights(
        &dir,
        "lit.glb",
        json!([{"type": "point", "intensity": 6830}]),
        &[light_node(0, json!({"translation": [0, 0, 1]}))],
    );
    let mut d = model_scene_with(&path, NO_STUDIO).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(d.background, BackgroundDesc::Constant(DVec3::ZERO));
    (d.camera.width, d.camera.height) = (8, 8);
    let mean = |d: &super::super::desc::SceneDesc| {
        let mut p = Progressive::new(
            Arc::new(Scene::from_desc(d).unwrap()),
            Settings::default(),
            1,
        );
        assert!(p.render_pass(4));
        let f = p.film();
        f.mean()
            .iter()
            .map(|c| crate::math::luminance(*c))
            .sum::<f32>()
            / f.mean().len() as f32
    };
    assert!(mean(&d) > 0.0);
    d.lights.clear();
    assert_eq!(mean(&d), 0.0);
}
