//! `KHR_lights_punctual` as lumis' `lights` (docs/scene-format.md, "glTF materials"), for a glTF
//! file opened on its own: each node of the default scene that names a light places it, at the
//! node's origin and aimed along the node's −z (the extension's rule).
//!
//! glTF's intensities are photometric (a point or spot light's `intensity` in candela, lm/sr; a
//! directional light's in lux, lm/m²) and lumis' are radiometric (W/sr, W/m²): they are divided
//! by [`LUMENS_PER_WATT`], the luminous efficacy at 555 nm, the factor by which the photometric
//! units are defined (and the one Blender's glTF importer uses). `color` multiplies it.
//!
//! lumis' spot is Mitsuba's: full within `beam_width`, falling linearly in angle to 0 at
//! `cutoff_angle`. glTF's falloff is the square of a ramp linear in cos θ between the two cone
//! angles (the extension's recommended implementation); the spot takes `cutoff = outerConeAngle`
//! and `beam_width = innerConeAngle`, and the difference is named in the warning. So is `range`:
//! a physically based light has none (its light falls as 1/d²).
//!
//! Errors name the file and the JSON path of the value
//! (`extensions.KHR_lights_punctual.lights[1].spot.outerConeAngle`, `nodes[3].extensions…`).

use crate::scene::mesh::MeshError;
use ::gltf::json;
use glam::{DVec3, Mat4, Vec3};
use serde_json::{Map, Value, json};
use std::path::Path;

/// The extension's name.
pub const EXTENSION: &str = "KHR_lights_punctual";

/// Lumens per watt: the photometric units' factor (683 lm/W at 555 nm).
pub const LUMENS_PER_WATT: f64 = 683.0;

/// The lights of a glTF file, as scene-format JSON, and what lumis does not render of them.
#[derive(Debug, Default)]
pub struct Lights {
    /// The `lights` entries, in the order of the nodes that place them (depth first).
    pub json: Vec<Value>,
    /// What lumis approximates or ignores, by glTF path (for the model's one warning).
    pub ignored: Vec<String>,
}

/// Whether a node names a `KHR_lights_punctual` light.
pub(super) fn has_light(node: &::gltf::Node) -> bool {
    node.extension_value(EXTENSION).is_some()
}

/// The lights that `nodes` (index, world matrix: those [`has_light`] found) place.
pub fn read(file: &Path, root: &json::Root, nodes: &[(usize, Mat4)]) -> Result<Lights, MeshError> {
    let mut out = Lights::default();
    if nodes.is_empty() {
        return Ok(out);
    }
    let err = |at: &str, m: String| MeshError::at(file, at, m);
    let list_at = format!("extensions.{EXTENSION}.lights");
    let list = root
        .extensions
        .as_ref()
        .and_then(|e| e.others.get(EXTENSION))
        .and_then(|e| e.get("lights"))
        .and_then(Value::as_array);
    for &(node, world) in nodes {
        let node_at = format!("nodes[{node}].extensions.{EXTENSION}.light");
        let value = root.nodes[node]
            .extensions
            .as_ref()
            .and_then(|e| e.others.get(EXTENSION))
            .and_then(|e| e.get("light"));
        let index = value.and_then(Value::as_u64).ok_or_else(|| {
            let found = value.map_or("nothing".to_owned(), Value::to_string);
            err(&node_at, format!("expected a light index, found {found}"))
        })? as usize;
        let count = list.map_or(0, Vec::len);
        let light = list
            .and_then(|l| l.get(index))
            .ok_or_else(|| {
                err(
                    &node_at,
                    format!("light {index} does not exist ({count} lights in {list_at})"),
                )
            })?
            .as_object()
            .ok_or_else(|| err(&format!("{list_at}[{index}]"), "expected an object".into()))?;
        let at = format!("{list_at}[{index}]");
        let position = world.transform_point3(Vec3::ZERO).as_dvec3();
        let forward = world.transform_vector3(Vec3::NEG_Z).as_dvec3();
        let aim = || {
            if !(forward.is_finite() && forward.length() > 0.0) {
                let m = format!("its transform flattens the direction of {at} (its −z)");
                return Err(err(&format!("nodes[{node}]"), m));
            }
            Ok(forward.normalize())
        };
        let power = color(light, &at).map_err(|m| err(&m.0, m.1))?
            * number(light, "intensity", &at, 1.0).map_err(|m| err(&m.0, m.1))?
            / LUMENS_PER_WATT;
        if light.contains_key("range") {
            out.ignored.push(format!("{at}.range"));
        }
        let ty = light.get("type").and_then(Value::as_str);
        out.json.push(match ty {
            Some("point") => json!({
                "type": "point", "position": position.to_array(), "intensity": power.to_array(),
            }),
            Some("directional") => json!({
                "type": "directional", "direction": aim()?.to_array(),
                "irradiance": power.to_array(),
            }),
            Some("spot") => {
                let d = aim()?;
                let (inner, outer) = cone(light, &at).map_err(|m| err(&m.0, m.1))?;
                // A spot is round: any up vector not along the axis gives the same light.
                let up = if d.y.abs() < 0.9 { DVec3::Y } else { DVec3::X };
                out.ignored.push(format!(
                    "{at}.spot: its falloff (lumis' spot falls linearly in angle from \
                     innerConeAngle to outerConeAngle, glTF's as the square of a ramp in cos θ)"
                ));
                json!({
                    "type": "spot", "from": position.to_array(),
                    "to": (position + d).to_array(), "up": up.to_array(),
                    "intensity": power.to_array(),
                    "cutoff_angle_deg": outer.to_degrees(), "beam_width_deg": inner.to_degrees(),
                })
            }
            _ => {
                let found = light
                    .get("type")
                    .map_or("nothing".to_owned(), Value::to_string);
                let m = format!("expected \"point\", \"spot\" or \"directional\", found {found}");
                return Err(err(&format!("{at}.type"), m));
            }
        });
    }
    Ok(out)
}

/// An error's JSON path and message (the caller adds the file).
type At = (String, String);

/// `color`: 3 numbers in [0, 1], default white.
fn color(light: &Map<String, Value>, at: &str) -> Result<DVec3, At> {
    let Some(v) = light.get("color") else {
        return Ok(DVec3::ONE);
    };
    let c = v.as_array().filter(|a| a.len() == 3);
    let c = c.and_then(|a| Some(DVec3::new(a[0].as_f64()?, a[1].as_f64()?, a[2].as_f64()?)));
    c.filter(|c| c.min_element() >= 0.0 && c.max_element() <= 1.0)
        .ok_or_else(|| {
            let m = format!("expected 3 numbers in [0, 1], found {v}");
            (format!("{at}.color"), m)
        })
}

/// A finite number ≥ 0 (`default` if absent).
fn number(o: &Map<String, Value>, key: &str, at: &str, default: f64) -> Result<f64, At> {
    let Some(v) = o.get(key) else {
        return Ok(default);
    };
    v.as_f64()
        .filter(|x| *x >= 0.0 && (*x as f32).is_finite())
        .ok_or_else(|| {
            let m = format!("expected a finite number ≥ 0, found {v}");
            (format!("{at}.{key}"), m)
        })
}

/// A spot's `innerConeAngle` (default 0) and `outerConeAngle` (default π/4), radians, with the
/// extension's rule 0 ≤ inner < outer ≤ π/2.
fn cone(light: &Map<String, Value>, at: &str) -> Result<(f64, f64), At> {
    let empty = Map::new();
    let spot_at = format!("{at}.spot");
    let spot = match light.get("spot") {
        None => &empty,
        Some(v) => v
            .as_object()
            .ok_or_else(|| (spot_at.clone(), format!("expected an object, found {v}")))?,
    };
    let inner = number(spot, "innerConeAngle", &spot_at, 0.0)?;
    let outer = number(
        spot,
        "outerConeAngle",
        &spot_at,
        std::f64::consts::FRAC_PI_4,
    )?;
    if !(outer > 0.0 && outer <= std::f64::consts::FRAC_PI_2) {
        let m = format!("{outer} is outside (0, π/2]");
        return Err((format!("{spot_at}.outerConeAngle"), m));
    }
    if inner >= outer {
        let m = format!("{inner} is not below outerConeAngle {outer}");
        return Err((format!("{spot_at}.innerConeAngle"), m));
    }
    Ok((inner, outer))
}
