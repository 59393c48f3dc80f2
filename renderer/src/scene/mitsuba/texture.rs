//! Textures and texturable parameters: `<texture type="bitmap">`, `"checkerboard"` and
//! `"mesh_attribute"` become
//! the scene format's texture objects (whose conventions are Mitsuba 3.9.1's: `docs/
//! scene-format.md`, Textures), and a parameter given as a constant becomes its RGB or scalar
//! ([`super::values`]).

use super::Ctx;
use super::plugin::{Plugin, Prop, Value};
use super::values::{Slot, constant_color, constant_scalar};
use super::xml::Element;
use crate::scene::error::SceneError;
use serde_json::{Value as Json, json};

/// What a parameter reads from a texture: a colour, or a scalar (Mitsuba's `eval_1`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reads {
    /// An RGB colour (`reflectance`, `radiance`, …).
    Color,
    /// A scalar (`alpha`): a bitmap's luminance, a checkerboard with its colours swapped.
    Scalar,
}

/// The colour parameter `name` of `plugin` for the scene format (a colour array or a texture
/// object), or `default` where it is not given. `json_path` is where the value goes, for
/// messages from the JSON validation.
pub fn color_param(
    ctx: &mut Ctx,
    plugin: &Plugin,
    name: &str,
    default: f64,
    slot: Slot,
    json_path: &str,
) -> Result<Json, SceneError> {
    match plugin.get(name) {
        None => Ok(json!([default, default, default])),
        Some(p) => {
            ctx.origin(json_path, p.pos());
            match constant_color(p, slot, &mut ctx.warnings)? {
                Some(c) => Ok(json!([c.x, c.y, c.z])),
                None => texture(ctx, p, Reads::Color, json_path),
            }
        }
    }
}

/// A bump map's height texture object (`prop`, a `<texture>`), for the scene format: a bitmap
/// (any other texture has no gradient; the scene format says so where it is read).
pub fn height_texture(ctx: &mut Ctx, prop: &Prop, json_path: &str) -> Result<Json, SceneError> {
    ctx.origin(json_path, prop.pos());
    texture(ctx, prop, Reads::Color, json_path)
}

/// The scalar parameter `name` (a number or a texture object), or `default`.
pub fn scalar_param(
    ctx: &mut Ctx,
    plugin: &Plugin,
    name: &str,
    default: f64,
    json_path: &str,
) -> Result<Json, SceneError> {
    match plugin.get(name) {
        None => Ok(json!(default)),
        Some(p) => {
            ctx.origin(json_path, p.pos());
            match constant_scalar(p)? {
                Some(x) => Ok(json!(x)),
                None => texture(ctx, p, Reads::Scalar, json_path),
            }
        }
    }
}

/// Whether a parameter is given as a texture object (for shapes without lumis texture
/// coordinates).
pub fn is_texture(prop: &Prop) -> bool {
    matches!(prop.value, Value::Object(_))
}

/// The texture object a property names, in the scene format.
fn texture(ctx: &mut Ctx, prop: &Prop, reads: Reads, json_path: &str) -> Result<Json, SceneError> {
    let el: &Element = super::target(prop);
    if el.tag != "texture" {
        return Err(el.pos.error(format!(
            "<{}> is not a texture (expected <texture>, <rgb>, <float> or <spectrum>)",
            el.tag
        )));
    }
    let t = ctx.plugin(el)?;
    ctx.origin(json_path, t.pos());
    let obj = match t.ty {
        "bitmap" => {
            let (file, fprop) = t
                .string("filename")?
                .ok_or_else(|| t.error("a bitmap needs `filename`"))?;
            ctx.origin(&format!("{json_path}.file"), fprop.pos());
            let file = ctx.resolve_file(file);
            let mut obj = json!({"type": "bitmap", "file": file});
            if let Some((f, p)) = t.string("filter_type")?
                && f != "bilinear"
            {
                return Err(p.error(format!(
                    "filter_type `{f}` is not supported (lumis filters bitmaps bilinearly)"
                )));
            }
            if let Some((w, p)) = t.string("wrap_mode")? {
                if !matches!(w, "repeat" | "mirror" | "clamp") {
                    return Err(p.error(format!("wrap_mode `{w}` must be repeat, mirror or clamp")));
                }
                obj["wrap"] = json!(w);
            }
            if t.bool("raw", false)? {
                obj["raw"] = json!(true);
            }
            // Storage precision and a lookup acceleration: the values are the same.
            t.ignore(&["format", "accel"]);
            uv_transform(&t, &mut obj)?;
            t.finish("filename, filter_type bilinear, wrap_mode, raw, to_uv; format and accel are ignored")?;
            obj
        }
        "checkerboard" => {
            let mut colors = Vec::new();
            for (key, default) in [("color0", 0.4), ("color1", 0.2)] {
                colors.push(match t.get(key) {
                    None => (json!(default), None),
                    Some(p) => match constant_color(p, Slot::Reflectance, &mut ctx.warnings)? {
                        Some(c) => (json!([c.x, c.y, c.z]), Some(p.pos().clone())),
                        None => {
                            return Err(p.error(format!(
                                "a textured `{key}` is not supported: lumis' checkerboard \
                                 colours are constants"
                            )));
                        }
                    },
                });
            }
            // Mitsuba's eval_1 of a checkerboard returns the other colour (docs/scene-format.md).
            if reads == Reads::Scalar {
                colors.swap(0, 1);
            }
            for (key, (_, pos)) in ["color0", "color1"].iter().zip(&colors) {
                if let Some(pos) = pos {
                    ctx.origin(&format!("{json_path}.{key}"), pos);
                }
            }
            let mut obj =
                json!({"type": "checkerboard", "color0": colors[0].0, "color1": colors[1].0});
            uv_transform(&t, &mut obj)?;
            t.finish("color0, color1, to_uv")?;
            obj
        }
        "mesh_attribute" => {
            let (name, nprop) = t
                .string("name")?
                .ok_or_else(|| t.error("a mesh_attribute needs `name`"))?;
            ctx.origin(&format!("{json_path}.name"), nprop.pos());
            let mut obj = json!({"type": "mesh_attribute", "name": name});
            if let Some(p) = t.get("scale") {
                ctx.origin(&format!("{json_path}.scale"), p.pos());
                obj["scale"] = json!(t.float("scale", 1.0)?);
            }
            t.finish("name, scale")?;
            obj
        }
        other => {
            return Err(t.error(format!(
                "texture type `{other}` is not supported (lumis maps bitmap, checkerboard and \
                 mesh_attribute)"
            )));
        }
    };
    Ok(obj)
}

/// `to_uv`: lumis textures take a scale and an offset per axis, the 3×3 affine map
/// `[[su, 0, ou], [0, sv, ov], [0, 0, 1]]` Mitsuba keeps of the 4×4 matrix (rows and
/// columns 0, 1 and 3); a rotation or shear is refused.
fn uv_transform(t: &Plugin, obj: &mut Json) -> Result<(), SceneError> {
    let Some((m, p)) = t.transform("to_uv")? else {
        return Ok(());
    };
    let r = |i: usize, j: usize| m.col(j)[i];
    if r(0, 1) != 0.0 || r(1, 0) != 0.0 {
        return Err(p.el.pos.error(
            "to_uv rotates or shears: lumis textures take a scale and an offset per axis only",
        ));
    }
    let (su, sv, ou, ov) = (r(0, 0), r(1, 1), r(0, 3), r(1, 3));
    if (su, sv) != (1.0, 1.0) {
        obj["uv_scale"] = json!([su, sv]);
    }
    if (ou, ov) != (0.0, 0.0) {
        obj["uv_offset"] = json!([ou, ov]);
    }
    Ok(())
}
