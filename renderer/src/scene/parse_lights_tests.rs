//! The `lights` list: each type parses to its description and writes back to the same JSON,
//! defaults are Mitsuba's, and each bad value is one error at its JSON path.

use super::*;
use crate::scene::build::Scene;
use crate::scene::parse::{parse_scene_value, parse_scene_value_in};
use crate::scene::tests::{base, expect_err};
use serde_json::json;

fn with_lights(lights: Value) -> Value {
    let mut s = base();
    s["lights"] = lights;
    s
}

fn parse(lights: Value) -> Vec<LightDesc> {
    parse_scene_value(&with_lights(lights))
        .unwrap_or_else(|e| panic!("{e}"))
        .lights
}

/// One of each, with Mitsuba's defaults filled in; `to_json` gives JSON that parses back to
/// the same descriptions.
#[test]
fn each_type_parses_and_round_trips() {
    let lights = json!([
        {"type": "point", "position": [1, 2, 3], "intensity": [4, 5, 6]},
        {"type": "spot", "from": [0, 3, 0], "to": [0, 0, 0], "up": [0, 0, 1],
         "intensity": [10, 10, 10], "cutoff_angle_deg": 40},
        {"type": "directional", "direction": [0, -2, 0], "irradiance": [1, 1, 1]},
        {"type": "projector", "from": [0, 3, 0], "to": [0, 0, 1], "fov_deg": 30,
         "irradiance": [1, 2, 3], "scale": 2}
    ]);
    let d = parse(lights);
    assert_eq!(d.len(), 4);
    match &d[1] {
        LightDesc::Spot {
            cutoff_angle_deg,
            beam_width_deg,
            texture,
            ..
        } => {
            assert_eq!(*cutoff_angle_deg, 40.0);
            assert_eq!(
                *beam_width_deg, 30.0,
                "Mitsuba's default: 3/4 of the cutoff"
            );
            assert!(texture.is_none());
        }
        other => panic!("{other:?}"),
    }
    match &d[2] {
        LightDesc::Directional { direction, .. } => assert_eq!(*direction, -DVec3::Y),
        other => panic!("{other:?}"),
    }
    match &d[3] {
        LightDesc::Projector {
            fov_x_deg, frame, ..
        } => {
            assert_eq!(*fov_x_deg, 30.0);
            assert_eq!(frame.up, DVec3::Y, "up defaults to +y");
        }
        other => panic!("{other:?}"),
    }
    let again: Vec<Value> = d.iter().map(LightDesc::to_json).collect();
    assert_eq!(parse(Value::Array(again)), d);
}

/// A spot's texture and a projector's image are texture objects; the projector's vertical
/// field of view follows the image's aspect (Mitsuba's `fov_axis` rule).
#[test]
fn textures_and_the_projectors_aspect() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/data/scenes");
    let image = json!({"type": "bitmap", "file": "textured_mesh_albedo.png"});
    let s = with_lights(json!([
        {"type": "spot", "from": [0, 3, 0], "to": [0, 0, 0], "up": [0, 0, 1],
         "intensity": [10, 10, 10], "cutoff_angle_deg": 30, "texture": image},
        {"type": "projector", "from": [0, 3, 0], "to": [0, 0, 1], "fov_deg": 30,
         "fov_axis": "y", "irradiance": image}
    ]));
    let d = parse_scene_value_in(&s, &dir).unwrap_or_else(|e| panic!("{e}"));
    let LightDesc::Projector {
        fov_x_deg, texture, ..
    } = &d.lights[1]
    else {
        panic!("{:?}", d.lights[1]);
    };
    let (w, h) = texture.as_ref().unwrap().texture.resolution();
    let want = 2.0
        * ((15f64).to_radians().tan() * w as f64 / h as f64)
            .atan()
            .to_degrees();
    assert!((fov_x_deg - want).abs() < 1e-9, "{fov_x_deg} vs {want}");
    // Built: two lights with their textures, before the background.
    let scene = Scene::from_desc(&d).unwrap_or_else(|e| panic!("{e}"));
    let kinds: Vec<&str> = scene.lights.iter().map(|l| l.kind_name()).collect();
    assert_eq!(
        kinds[kinds.len() - 3..],
        ["spot", "projector", "background"]
    );
    assert_eq!(scene.emission_textures.len(), 2);
}

/// Each bad value is one error at its path.
#[test]
fn bad_lights_are_located_errors() {
    let spot = |extra: Value| {
        let mut l = json!({"type": "spot", "from": [0, 3, 0], "to": [0, 0, 0], "up": [0, 0, 1],
                           "intensity": [1, 1, 1]});
        for (k, v) in extra.as_object().unwrap() {
            l[k] = v.clone();
        }
        with_lights(json!([l]))
    };
    expect_err(
        &with_lights(json!([{"type": "sun"}])),
        "lights[0].type",
        "a sun is a `directional` light",
    );
    expect_err(
        &with_lights(json!([{"type": "point", "position": [0, 1, 0], "intensity": [1, -1, 1]}])),
        "lights[0].intensity[1]",
        "negative",
    );
    expect_err(
        &with_lights(
            json!([{"type": "point", "position": [0, 1, 0], "intensity": [1, 1, 1],
                             "radius": 1}]),
        ),
        "lights[0].radius",
        "unknown key",
    );
    expect_err(
        &spot(json!({"cutoff_angle_deg": 30, "beam_width_deg": 31})),
        "lights[0].beam_width_deg",
        "out of range",
    );
    expect_err(
        &spot(json!({"cutoff_angle_deg": 0})),
        "lights[0].cutoff_angle_deg",
        "(0, 180]",
    );
    expect_err(
        &spot(json!({"cutoff_angle_deg": 95, "texture": {"type": "checkerboard"}})),
        "lights[0].cutoff_angle_deg",
        "below 90",
    );
    expect_err(
        &spot(json!({"texture": [1, 1, 1]})),
        "lights[0].texture",
        "expected a texture object",
    );
    expect_err(
        &spot(json!({"to": [0, 3, 0]})),
        "lights[0].to",
        "equals `from`",
    );
    expect_err(&spot(json!({"up": [0, 2, 0]})), "lights[0].up", "parallel");
    expect_err(
        &with_lights(json!([{"type": "directional", "direction": [0, 0, 0],
                             "irradiance": [1, 1, 1]}])),
        "lights[0].direction",
        "zero length",
    );
    let projector = |fov: Value, axis: &str| {
        with_lights(
            json!([{"type": "projector", "from": [0, 3, 0], "to": [0, 0, 0],
                            "up": [0, 0, 1], "fov_deg": fov, "fov_axis": axis,
                            "irradiance": [1, 1, 1]}]),
        )
    };
    expect_err(
        &projector(json!(180), "x"),
        "lights[0].fov_deg",
        "out of range",
    );
    expect_err(
        &projector(json!(30), "z"),
        "lights[0].fov_axis",
        "the axis is",
    );
    expect_err(
        &with_lights(json!([{"type": "point", "position": [1e16, 0, 0],
                             "intensity": [1, 1, 1]}])),
        "lights[0].position",
        "beyond the supported scene size",
    );
}

/// Mitsuba's `parse_fov` on every axis: a square image sees the same angle on x, y, smaller
/// and larger; a 2:1 image's vertical 30° is a wider horizontal angle; the diagonal's.
#[test]
fn horizontal_fov_follows_mitsubas_rule() {
    for axis in ["x", "y", "smaller", "larger"] {
        let x = horizontal_fov_deg(40.0, axis, 1.0).unwrap();
        assert!((x - 40.0).abs() < 1e-12, "{axis}: {x}");
    }
    let y = horizontal_fov_deg(30.0, "y", 2.0).unwrap();
    assert!((y - 2.0 * (2.0 * 15f64.to_radians().tan()).atan().to_degrees()).abs() < 1e-12);
    assert_eq!(horizontal_fov_deg(30.0, "larger", 2.0), Some(30.0));
    assert_eq!(horizontal_fov_deg(30.0, "smaller", 2.0), Some(y));
    let d = horizontal_fov_deg(30.0, "diagonal", 1.0).unwrap();
    let want = 2.0 * (15f64.to_radians().tan() / 2f64.sqrt()).atan().to_degrees();
    assert!((d - want).abs() < 1e-12, "{d} vs {want}");
    assert_eq!(horizontal_fov_deg(30.0, "z", 1.0), None);
}

/// A black light is no light (as a black emitter), so it costs nothing at render time.
#[test]
fn black_lights_are_dropped() {
    let d = parse_scene_value(&with_lights(json!([
        {"type": "point", "position": [0, 1, 0], "intensity": [0, 0, 0]},
        {"type": "directional", "direction": [0, -1, 0], "irradiance": [0, 0, 0]}
    ])))
    .unwrap();
    assert_eq!(d.lights.len(), 2);
    let scene = Scene::from_desc(&d).unwrap();
    assert!(!scene.lights.iter().any(|l| l.is_delta()));
}
