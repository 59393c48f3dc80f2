//! Emitters: `area` (a shape's `emission`), `constant` and `envmap` (lumis' `background`).
//! Mitsuba's area emitters emit on the front side only, as lumis' do; an `envmap`'s `to_world`
//! is any proper rotation (its translation does not turn directions, so it is dropped): a
//! rotation about +y becomes `rotate_y_deg` (the same convention: docs/scene-format.md), any
//! other the background's `rotation`, which the scene parser checks (a scale, shear or mirror is
//! refused there, at the transform's position).

use super::Ctx;
use super::plugin::Plugin;
use super::texture::color_param;
use super::transform::rotation;
use super::values::{Slot, constant_color};
use crate::scene::error::SceneError;
use crate::scene::parse_background::rotation_json;
use glam::{DMat4, DVec3};
use serde_json::{Value as Json, json};

/// Emitter types Mitsuba has and lumis does not, with the reason.
fn unsupported(ty: &str) -> String {
    let why = match ty {
        "directionalarea" => " (lumis has no directional area lights)",
        "sunsky" | "sky" | "sun" => " (lumis' environment is a constant or an EXR or HDR map)",
        _ => "",
    };
    format!(
        "emitter type `{ty}` is not supported{why}; lumis maps area, constant, envmap, point, spot, directional and projector"
    )
}

/// The `radiance` of an `area` emitter inside a shape (a colour or a texture).
pub fn area(ctx: &mut Ctx, e: &Plugin, json_path: &str) -> Result<Json, SceneError> {
    if e.ty != "area" {
        return Err(e.error(
            if matches!(
                e.ty,
                "constant" | "envmap" | "point" | "spot" | "directional" | "projector"
            ) {
                format!(
                    "a `{}` emitter cannot be attached to a shape (it is a light of the scene: \
                 declare it at the top level)",
                    e.ty
                )
            } else {
                unsupported(e.ty)
            },
        ));
    }
    if e.has("to_world") {
        return Err(e.error("an area emitter takes no to_world (Mitsuba refuses it too)"));
    }
    let radiance = color_param(ctx, e, "radiance", 1.0, Slot::Emission, json_path)?;
    e.finish("radiance")?;
    Ok(radiance)
}

/// A scene-level emitter as lumis' `background`.
pub fn background(ctx: &mut Ctx, e: &Plugin) -> Result<Json, SceneError> {
    ctx.origin("background", e.pos());
    match e.ty {
        "constant" => {
            let c = match e.get("radiance") {
                None => DVec3::ONE,
                Some(p) => {
                    ctx.origin("background", p.pos());
                    constant_color(p, Slot::Emission, &mut ctx.warnings)?.ok_or_else(|| {
                        p.error("a constant emitter's radiance must not vary (no textures)")
                    })?
                }
            };
            e.finish("radiance")?;
            Ok(json!([c.x, c.y, c.z]))
        }
        "envmap" => {
            let (file, fp) = e
                .string("filename")?
                .ok_or_else(|| e.error("an envmap needs `filename` (an EXR or HDR file)"))?;
            ctx.origin("background.envmap", fp.pos());
            let file = ctx.resolve_file(file);
            let scale = e.float("scale", 1.0)?;
            if let Some(p) = e.get("scale") {
                ctx.origin("background.scale", p.pos());
            }
            let mut background = json!({"envmap": file, "scale": scale, "rotate_y_deg": 0.0});
            if let Some((m, p)) = e.transform("to_world")? {
                match y_rotation(&m) {
                    Some(angle) => background["rotate_y_deg"] = json!(angle),
                    None => {
                        ctx.origin("background.rotation", p.pos());
                        // The linear part; the scene parser checks that it is a rotation.
                        background["rotation"] = rotation_json(glam::DMat3::from_mat4(m));
                    }
                }
            }
            // Importance sampling only: the image is the same.
            e.ignore(&["mis_compensation"]);
            e.finish("filename, scale, to_world (a rotation); mis_compensation is ignored")?;
            Ok(background)
        }
        other => Err(e.error(if other == "area" {
            "an area emitter must be nested in a <shape>".to_owned()
        } else {
            unsupported(other)
        })),
    }
}

/// The angle in degrees of `m` if it is a rotation about +y (to 1e-9), else `None`.
fn y_rotation(m: &DMat4) -> Option<f64> {
    let angle = m.z_axis.x.atan2(m.x_axis.x).to_degrees();
    let r = rotation(DVec3::Y, angle);
    let close = m
        .to_cols_array()
        .iter()
        .zip(r.to_cols_array())
        .all(|(a, b)| (a - b).abs() <= 1e-9);
    close.then_some(angle)
}
