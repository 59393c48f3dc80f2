//! The `lights` list (scene format Version 3): Mitsuba 3.9.1's delta emitters `point`, `spot`,
//! `directional` and `projector`, each read and checked here once, so that every front end gets
//! the same errors. What each emits is said where it is defined (`renderer/src/lights/`).

use super::desc::{LightDesc, LookAt};
use super::error::SceneError;
use super::parse::MAX_RADIANCE;
use super::parse_mesh_attribute::off_mesh;
use super::parse_texture::{TextureLoader, TextureUse, texture_at};
use super::walk::{Obj, check_components};
use glam::DVec3;
use serde_json::Value;

/// Every light of `lights`, in file order; textures come from `loader`.
pub(crate) fn parse_lights(
    items: &[Value],
    loader: &mut TextureLoader,
) -> Result<Vec<LightDesc>, SceneError> {
    items
        .iter()
        .enumerate()
        .map(|(i, v)| parse_light(&Obj::new(v, format!("lights[{i}]"))?, loader))
        .collect()
}

fn parse_light(obj: &Obj, loader: &mut TextureLoader) -> Result<LightDesc, SceneError> {
    let ty = obj.string("type")?;
    let keys: &[&str] = match ty {
        "point" => &["type", "position", "intensity"],
        "spot" => &[
            "type",
            "from",
            "to",
            "up",
            "intensity",
            "cutoff_angle_deg",
            "beam_width_deg",
            "texture",
        ],
        "directional" => &["type", "direction", "irradiance"],
        "projector" => &[
            "type",
            "from",
            "to",
            "up",
            "fov_deg",
            "fov_axis",
            "irradiance",
            "scale",
        ],
        other => {
            let hint = match other {
                "area" => " (an area light is a shape with `emission`)",
                "constant" | "envmap" => " (that is the `background`)",
                "sunsky" | "sky" | "sun" => {
                    " (a sun is a `directional` light; skies are not modelled)"
                }
                _ => "",
            };
            return Err(SceneError::new(
                obj.at("type"),
                format!(
                    "unknown light type `{other}`{hint}: expected point, spot, directional or \
                     projector"
                ),
            ));
        }
    };
    obj.only_keys(keys, true)?;
    // Mitsuba's default for every intensity and irradiance: 1.
    let power = |key: &str| -> Result<DVec3, SceneError> {
        let v = obj.opt_vec3(key)?.unwrap_or(DVec3::ONE);
        check_components(v, &obj.at(key), |x| x >= 0.0, "is negative: it must be ≥ 0")?;
        check_components(
            v,
            &obj.at(key),
            |x| x <= MAX_RADIANCE,
            "is too large: at most 1e30 (single precision would overflow)",
        )
    };
    match ty {
        "point" => Ok(LightDesc::Point {
            position: position(obj, "position")?,
            intensity: power("intensity")?,
        }),
        "spot" => {
            let frame = look_at(obj)?;
            let cutoff_angle_deg = obj.opt_number("cutoff_angle_deg")?.unwrap_or(20.0);
            if !(cutoff_angle_deg > 0.0 && cutoff_angle_deg <= 180.0) {
                return Err(SceneError::new(
                    obj.at("cutoff_angle_deg"),
                    format!("{cutoff_angle_deg} is out of range: the cutoff angle is in (0, 180]"),
                ));
            }
            // Mitsuba's default: three quarters of the cutoff.
            let beam_width_deg = obj
                .opt_number("beam_width_deg")?
                .unwrap_or(0.75 * cutoff_angle_deg);
            if !(0.0..=cutoff_angle_deg).contains(&beam_width_deg) {
                return Err(SceneError::new(
                    obj.at("beam_width_deg"),
                    format!(
                        "{beam_width_deg} is out of range: the beam width is in [0, the cutoff \
                         angle {cutoff_angle_deg}] (Mitsuba asserts the same)"
                    ),
                ));
            }
            let texture = texture_at(obj, "texture", TextureUse::Emission, loader)?;
            if let Some(t) = &texture {
                off_mesh(t, &obj.at("texture"), "a spot light")?;
            }
            if obj.get("texture").is_some() && texture.is_none() {
                return Err(SceneError::new(
                    obj.at("texture"),
                    "expected a texture object (a constant colour belongs in `intensity`)",
                ));
            }
            if texture.is_some() && cutoff_angle_deg >= 90.0 {
                return Err(SceneError::new(
                    obj.at("cutoff_angle_deg"),
                    format!(
                        "{cutoff_angle_deg}: a textured spot needs a cutoff angle below 90 (its \
                         texture is projected through the plane one unit along the axis)"
                    ),
                ));
            }
            Ok(LightDesc::Spot {
                frame,
                intensity: power("intensity")?,
                cutoff_angle_deg,
                beam_width_deg,
                texture,
            })
        }
        "directional" => {
            let d = obj.vec3("direction")?;
            if d == DVec3::ZERO || !d.length().is_finite() {
                return Err(SceneError::new(
                    obj.at("direction"),
                    "the direction has zero length",
                ));
            }
            Ok(LightDesc::Directional {
                direction: d.normalize(),
                irradiance: power("irradiance")?,
            })
        }
        "projector" => {
            let frame = look_at(obj)?;
            let texture = texture_at(obj, "irradiance", TextureUse::Emission, loader)?;
            if let Some(t) = &texture {
                off_mesh(t, &obj.at("irradiance"), "a projector")?;
            }
            // Mitsuba's rule: the field of view on `fov_axis` of the image's aspect (a
            // constant's is 1).
            let (w, h) = texture.as_ref().map_or((1, 1), |t| t.texture.resolution());
            let fov = obj.number("fov_deg")?;
            let axis = match obj.get("fov_axis") {
                None => "x",
                Some(_) => obj.string("fov_axis")?,
            };
            let fov_x_deg =
                horizontal_fov_deg(fov, axis, w as f64 / h as f64).ok_or_else(|| {
                    SceneError::new(
                        obj.at("fov_axis"),
                        format!("`{axis}`: the axis is x, y, diagonal, smaller or larger"),
                    )
                })?;
            if !(fov > 0.0 && fov < 180.0 && fov_x_deg > 0.0 && fov_x_deg < 180.0) {
                return Err(SceneError::new(
                    obj.at("fov_deg"),
                    format!(
                        "{fov} is out of range: the field of view is in (0, 180) (horizontally \
                         {fov_x_deg})"
                    ),
                ));
            }
            let irradiance = match &texture {
                Some(t) => t.mean_color(),
                None => power("irradiance")?,
            };
            let scale = obj.opt_number("scale")?.unwrap_or(1.0);
            if !(0.0..=MAX_RADIANCE).contains(&scale) {
                return Err(SceneError::new(
                    obj.at("scale"),
                    format!("{scale} is out of range: the scale is in [0, 1e30]"),
                ));
            }
            Ok(LightDesc::Projector {
                frame,
                fov_x_deg,
                irradiance,
                texture,
                scale,
            })
        }
        _ => unreachable!("the keys' match above lists every type"),
    }
}

/// A point within the supported scene size.
fn position(obj: &Obj, key: &str) -> Result<DVec3, SceneError> {
    let p = obj.vec3(key)?;
    let limit = crate::scene::build::MAX_SCENE_SIZE as f64;
    if p.abs().max_element() > limit {
        return Err(SceneError::new(
            obj.at(key),
            format!(
                "coordinate {:e} is beyond the supported scene size {limit:e} (single precision)",
                p.abs().max_element()
            ),
        ));
    }
    Ok(p)
}

/// `from`, `to` and `up` (default +y), checked as the camera's are: distinct points, an `up`
/// not parallel to the axis.
fn look_at(obj: &Obj) -> Result<LookAt, SceneError> {
    let from = position(obj, "from")?;
    let to = position(obj, "to")?;
    let up = obj.opt_vec3("up")?.unwrap_or(DVec3::Y);
    let axis = to - from;
    let scale = from.abs().max(to.abs()).max_element();
    if axis == DVec3::ZERO || axis.length() <= 1e-12 * scale {
        return Err(SceneError::new(
            obj.at("to"),
            "`to` equals `from`, so the light's axis is undefined",
        ));
    }
    if up == DVec3::ZERO || axis.normalize().cross(up.normalize()).length() < 1e-6 {
        return Err(SceneError::new(
            obj.at("up"),
            "`up` is zero or parallel to the axis `to - from`",
        ));
    }
    Ok(LookAt { from, to, up })
}

/// Mitsuba's `parse_fov`: the horizontal field of view (degrees) of a view `fov` degrees wide on
/// `axis` (x, y, diagonal, smaller, larger) with aspect ratio `aspect` (width / height); `None`
/// for another axis name.
pub(crate) fn horizontal_fov_deg(fov: f64, axis: &str, aspect: f64) -> Option<f64> {
    let axis = match axis {
        "smaller" if aspect > 1.0 => "y",
        "smaller" => "x",
        "larger" if aspect > 1.0 => "x",
        "larger" => "y",
        a => a,
    };
    let half = |deg: f64| (0.5 * deg.to_radians()).tan();
    match axis {
        "x" => Some(fov),
        "y" => Some(2.0 * (half(fov) * aspect).atan().to_degrees()),
        "diagonal" => {
            let width = 2.0 * half(fov) / (1.0 + 1.0 / (aspect * aspect)).sqrt();
            Some(2.0 * (0.5 * width).atan().to_degrees())
        }
        _ => None,
    }
}

#[cfg(test)]
#[path = "parse_lights_tests.rs"]
mod tests;
