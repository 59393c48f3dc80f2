//! Mitsuba's delta emitters `point`, `spot`, `directional` and `projector` as lumis' `lights`
//! (scene format Version 3). Each parameter of Mitsuba 3.9.1's plugin is read here or refused:
//! a point's `position` or `to_world` (not both, as Mitsuba), a direction's `direction` or
//! `to_world`; a spot's and a projector's frame is their `to_world`, which lumis takes as a
//! rotation and a translation (`from`, `to`, `up` of the scene format: a look-at, Mitsuba's
//! only way to aim one in its gallery); a scale or mirror there is refused, since it would
//! change what Mitsuba computes in ways lumis does not model. Intensities and irradiances are
//! colours; Mitsuba refuses a texture for `point`'s intensity, `spot`'s intensity and
//! `directional`'s irradiance, and so does lumis.

use super::Ctx;
use super::plugin::Plugin;
use super::texture::color_param;
use super::values::{Slot, constant_color};
use crate::scene::error::SceneError;
use crate::scene::parse_background::proper_rotation;
use glam::{DMat3, DMat4, DVec3};
use serde_json::{Value as Json, json};

/// Whether `ty` is one of the delta emitters this module maps.
pub fn is_delta(ty: &str) -> bool {
    matches!(ty, "point" | "spot" | "directional" | "projector")
}

/// The scene-level delta emitter `e` as the light at `json_path` (`lights[i]`).
pub fn light(ctx: &mut Ctx, e: &Plugin, json_path: &str) -> Result<Json, SceneError> {
    ctx.origin(json_path, e.pos());
    let v = |d: DVec3| json!([d.x, d.y, d.z]);
    match e.ty {
        "point" => {
            let position = match (e.get("position"), e.transform("to_world")?) {
                (Some(_), Some(_)) => {
                    return Err(e.error(
                        "give either `position` or `to_world`, not both (Mitsuba refuses both)",
                    ));
                }
                (Some(_), None) => e.vector("position", DVec3::ZERO)?,
                (None, Some((m, _))) => m.w_axis.truncate(),
                (None, None) => DVec3::ZERO,
            };
            let intensity = constant(ctx, e, "intensity", json_path)?;
            e.finish("intensity, position or to_world")?;
            Ok(json!({"type": "point", "position": v(position), "intensity": intensity}))
        }
        "spot" => {
            let (from, to, up) = frame(ctx, e, json_path)?;
            let intensity = constant(ctx, e, "intensity", json_path)?;
            let cutoff = e.float("cutoff_angle", 20.0)?;
            let beam = e.float("beam_width", 0.75 * cutoff)?;
            for (name, key) in [
                ("cutoff_angle", "cutoff_angle_deg"),
                ("beam_width", "beam_width_deg"),
            ] {
                if let Some(p) = e.get(name) {
                    ctx.origin(&format!("{json_path}.{key}"), p.pos());
                }
            }
            let mut light = json!({
                "type": "spot", "from": v(from), "to": v(to), "up": v(up),
                "intensity": intensity, "cutoff_angle_deg": cutoff, "beam_width_deg": beam,
            });
            if let Some(p) = e.get("texture") {
                let t = color_param(
                    ctx,
                    e,
                    "texture",
                    1.0,
                    Slot::Emission,
                    &format!("{json_path}.texture"),
                )?;
                if !t.is_object() {
                    // Mitsuba's rule: the texture must vary (a constant belongs in intensity).
                    return Err(p.error(
                        "a spot's `texture` must be spatially varying (e.g. a bitmap), as Mitsuba \
                         requires; a constant colour belongs in `intensity`",
                    ));
                }
                light["texture"] = t;
            }
            e.finish("intensity, cutoff_angle, beam_width, texture, to_world")?;
            Ok(light)
        }
        "directional" => {
            let direction = match (e.get("direction"), e.transform("to_world")?) {
                (Some(_), Some(_)) => {
                    return Err(e.error(
                        "give either `direction` or `to_world`, not both (Mitsuba refuses both)",
                    ));
                }
                (Some(p), None) => {
                    let d = e.vector("direction", DVec3::ZERO)?;
                    if d == DVec3::ZERO {
                        return Err(p.error("the direction has zero length"));
                    }
                    d.normalize()
                }
                (None, Some((m, p))) => {
                    rigid(&m).map_err(|why| p.error(why))?;
                    m.z_axis.truncate()
                }
                // Mitsuba's default frame: the light travels along +z.
                (None, None) => DVec3::Z,
            };
            let irradiance = constant(ctx, e, "irradiance", json_path)?;
            e.finish("irradiance, direction or to_world")?;
            Ok(json!({"type": "directional", "direction": v(direction), "irradiance": irradiance}))
        }
        "projector" => {
            let (from, to, up) = frame(ctx, e, json_path)?;
            let irradiance = color_param(
                ctx,
                e,
                "irradiance",
                1.0,
                Slot::Emission,
                &format!("{json_path}.irradiance"),
            )?;
            let scale = e.float("scale", 1.0)?;
            let mut light = json!({
                "type": "projector", "from": v(from), "to": v(to), "up": v(up),
                "irradiance": irradiance, "scale": scale,
            });
            // Mitsuba's parse_fov; the axis is resolved once the image's aspect is known.
            let (fov, axis, pos) = super::sensor::fov_and_axis(e)?;
            ctx.origin(&format!("{json_path}.fov_deg"), &pos);
            light["fov_deg"] = json!(fov);
            light["fov_axis"] = json!(axis);
            e.finish("irradiance, scale, fov, fov_axis, focal_length, to_world")?;
            Ok(light)
        }
        other => unreachable!("{other} is not a delta emitter (callers check is_delta)"),
    }
}

/// A colour parameter that must be constant (Mitsuba refuses a spatially varying one).
fn constant(ctx: &mut Ctx, e: &Plugin, name: &str, json_path: &str) -> Result<Json, SceneError> {
    match e.get(name) {
        None => Ok(json!([1.0, 1.0, 1.0])),
        Some(p) => {
            ctx.origin(&format!("{json_path}.{name}"), p.pos());
            let c = constant_color(p, Slot::Emission, &mut ctx.warnings)?.ok_or_else(|| {
                p.error(format!(
                    "a `{}` emitter's `{name}` must not vary (no textures; Mitsuba refuses it too)",
                    e.ty
                ))
            })?;
            Ok(json!([c.x, c.y, c.z]))
        }
    }
}

/// `from`, `to` and `up` of a spot's or projector's `to_world` (the identity where absent: at the
/// origin, aimed along +z, +y up).
fn frame(ctx: &mut Ctx, e: &Plugin, json_path: &str) -> Result<(DVec3, DVec3, DVec3), SceneError> {
    let Some((m, p)) = e.transform("to_world")? else {
        return Ok((DVec3::ZERO, DVec3::Z, DVec3::Y));
    };
    ctx.origin(&format!("{json_path}.from"), p.pos());
    rigid(&m).map_err(|why| p.error(why))?;
    let from = m.w_axis.truncate();
    Ok((from, from + m.z_axis.truncate(), m.y_axis.truncate()))
}

/// Whether the linear part of `m` is a proper rotation (the environment map's rule,
/// [`proper_rotation`]): a scale changes a spot's texture mapping and a projector's brightness in
/// Mitsuba, a mirror its orientation, which lumis' look-at frames do not hold.
fn rigid(m: &DMat4) -> Result<(), String> {
    proper_rotation(DMat3::from_mat4(*m))
        .map(|_| ())
        .map_err(|_| {
            "this emitter's to_world scales, shears or mirrors; lumis takes a rotation and a \
         translation (a <lookat>) for spot, projector and directional emitters"
                .to_owned()
        })
}
