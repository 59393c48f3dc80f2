//! `<sensor type="perspective">` with its `hdrfilm`, `rfilter` and `sampler`: lumis' camera and
//! the sample count.
//!
//! Mitsuba's perspective camera looks along its `to_world`'s +z, with +y up and +x to the left
//! (`look_at`), which is lumis' camera with `from` = the origin, `to` = origin + z and `up` = y,
//! exactly when `to_world` is a rotation and translation (Mitsuba refuses scale factors; a
//! mirroring one is refused here, lumis' image axis being `cross(forward, up)`). The field of
//! view follows Mitsuba's `parse_fov` (`fov` on `fov_axis` x, y, diagonal, smaller or larger,
//! or a 35 mm `focal_length`, default 50 mm) and becomes lumis' vertical one.

use super::plugin::Plugin;
use super::{Ctx, target};
use crate::scene::error::SceneError;
use glam::{DMat3, DVec3};
use serde_json::{Value, json};

/// What the sensor gives the scene: lumis' `camera` object and the sample count.
pub struct SensorOut {
    /// The scene format's `camera`.
    pub camera: Value,
    /// `sampler.sample_count`.
    pub spp: u32,
}

/// A `<sensor>`.
pub fn sensor(ctx: &mut Ctx, sensor: &Plugin) -> Result<SensorOut, SceneError> {
    if sensor.ty != "perspective" {
        let why = match sensor.ty {
            "thinlens" => " (a thin lens has depth of field; lumis' camera is a pinhole)",
            "orthographic" | "telecentric" => " (lumis' camera is a perspective pinhole)",
            _ => "",
        };
        return Err(sensor.error(format!(
            "sensor type `{}` is not supported{why}; use `perspective`",
            sensor.ty
        )));
    }
    let film = match sensor.object("film")? {
        Some(p) => ctx.plugin(target(p))?,
        None => {
            return Err(sensor.error(
                "the sensor has no <film>: Mitsuba's default film is 768 × 576, which is \
                 unlikely to be meant; add <film type=\"hdrfilm\"> with its width and height",
            ));
        }
    };
    let (width, height, filter) = film_size(ctx, &film)?;
    let aspect = width as f64 / height as f64;
    let x_fov = x_fov(sensor, aspect)?;
    let vfov = 2.0
        * ((0.5 * x_fov.to_radians()).tan() / aspect)
            .atan()
            .to_degrees();

    let (to_world, tpos) = match sensor.transform("to_world")? {
        Some((m, p)) => (m, p.el.pos.clone()),
        None => (glam::DMat4::IDENTITY, sensor.pos().clone()),
    };
    let r = DMat3::from_mat4(to_world);
    let rrt = r * r.transpose();
    let off = (rrt - DMat3::IDENTITY).to_cols_array();
    if off.iter().any(|x| x.abs() > 1e-3) {
        return Err(tpos.error(
            "the camera's to_world has a scale factor, which Mitsuba does not allow either",
        ));
    }
    if r.determinant() < 0.0 {
        return Err(tpos.error(
            "the camera's to_world mirrors the image (negative determinant, e.g. a scale by \
             -1): lumis' image always runs along cross(forward, up)",
        ));
    }
    let from = to_world.w_axis.truncate();
    let forward = r.z_axis;
    let up = r.y_axis;
    for key in ["principal_point_offset_x", "principal_point_offset_y"] {
        if sensor.float(key, 0.0)? != 0.0 {
            return Err(sensor.error(format!("`{key}` other than 0 is not supported")));
        }
    }
    // A pinhole's image does not depend on them (clip planes far outside the scene assumed).
    sensor.ignore(&[
        "near_clip",
        "far_clip",
        "focus_distance",
        "shutter_open",
        "shutter_close",
    ]);
    let spp = match sensor.object("sampler")? {
        Some(p) => sampler(&ctx.plugin(target(p))?)?,
        None => 4,
    };
    sensor.finish(
        "to_world, fov, fov_axis, focal_length, film, sampler; near_clip, far_clip, \
         focus_distance, shutter_open and shutter_close are ignored",
    )?;
    ctx.origin("camera", sensor.pos());
    ctx.origin("camera.from", &tpos);
    ctx.origin("camera.to", &tpos);
    ctx.origin("camera.up", &tpos);
    ctx.origin(
        "camera.vfov_deg",
        sensor.get("fov").map_or(sensor.pos(), |p| p.pos()),
    );
    ctx.origin(
        "camera.width",
        film.get("width").map_or(film.pos(), |p| p.pos()),
    );
    ctx.origin(
        "camera.height",
        film.get("height").map_or(film.pos(), |p| p.pos()),
    );
    let v = |d: DVec3| json!([d.x, d.y, d.z]);
    Ok(SensorOut {
        camera: json!({
            "from": v(from), "to": v(from + forward), "up": v(up),
            "vfov_deg": vfov, "width": width, "height": height,
            "filter": filter,
        }),
        spp,
    })
}

/// Mitsuba's horizontal field of view in degrees (`parse_fov`).
fn x_fov(sensor: &Plugin, aspect: f64) -> Result<f64, SceneError> {
    if sensor.has("fov") && sensor.has("focal_length") {
        return Err(sensor.error("give either `fov` or `focal_length`, not both"));
    }
    let (fov, axis, pos) = match sensor.get("fov") {
        Some(p) => {
            let fov = sensor.float("fov", 0.0)?;
            let axis = match sensor.string("fov_axis")? {
                Some((s, _)) => s.to_ascii_lowercase(),
                None => "x".to_owned(),
            };
            let axis = match axis.as_str() {
                "smaller" if aspect > 1.0 => "y".to_owned(),
                "smaller" => "x".to_owned(),
                "larger" if aspect > 1.0 => "x".to_owned(),
                "larger" => "y".to_owned(),
                _ => axis,
            };
            (fov, axis, p.pos().clone())
        }
        None => {
            let (text, pos) = match sensor.string("focal_length")? {
                Some((s, p)) => (s.to_owned(), p.pos().clone()),
                None => ("50mm".to_owned(), sensor.pos().clone()),
            };
            let mm: f64 = text
                .strip_suffix("mm")
                .unwrap_or(&text)
                .trim()
                .parse()
                .map_err(|_| {
                    pos.error(format!("focal length `{text}` is not of the form <x>mm"))
                })?;
            let diagonal = (36.0f64 * 36.0 + 24.0 * 24.0).sqrt();
            let fov = 2.0 * (diagonal / (2.0 * mm)).atan().to_degrees();
            (fov, "diagonal".to_owned(), pos)
        }
    };
    let half = |deg: f64| (0.5 * deg.to_radians()).tan();
    let x = match axis.as_str() {
        "x" => fov,
        "y" => 2.0 * (half(fov) * aspect).atan().to_degrees(),
        "diagonal" => {
            let width = 2.0 * half(fov) / (1.0 + 1.0 / (aspect * aspect)).sqrt();
            2.0 * (0.5 * width).atan().to_degrees()
        }
        other => {
            return Err(sensor.get("fov_axis").map_or_else(
                || sensor.error("bad fov_axis"),
                |p| {
                    p.error(format!(
                        "fov_axis `{other}` must be x, y, diagonal, smaller or larger"
                    ))
                },
            ));
        }
    };
    if !(x > 0.0 && x < 180.0) {
        return Err(pos.error(format!(
            "the horizontal field of view {x}° is outside (0, 180)"
        )));
    }
    Ok(x)
}

/// An `hdrfilm`'s size and lumis' `camera.filter` for its `rfilter`: `box`, or `gaussian`
/// (also when there is none, Mitsuba's default) with Mitsuba's stddev (default 0.5) and its fixed
/// radius 4·stddev. lumis samples the film like Mitsuba's default `sample_border = false`.
fn film_size(ctx: &mut Ctx, film: &Plugin) -> Result<(i64, i64, Value), SceneError> {
    if film.ty != "hdrfilm" {
        return Err(film.error(format!(
            "film type `{}` is not supported; use `hdrfilm`",
            film.ty
        )));
    }
    let (w, h) = (film.int("width", 768)?, film.int("height", 576)?);
    let crop = (
        film.int("crop_offset_x", 0)?,
        film.int("crop_offset_y", 0)?,
        film.int("crop_width", w)?,
        film.int("crop_height", h)?,
    );
    if crop != (0, 0, w, h) {
        return Err(film.error("a crop window is not supported (lumis renders the whole film)"));
    }
    if let Some((fmt, p)) = film.string("pixel_format")?
        && !matches!(fmt.to_ascii_lowercase().as_str(), "rgb" | "rgba")
    {
        return Err(p.error(format!(
            "pixel_format `{fmt}` is not supported: lumis renders RGB"
        )));
    }
    // Output encodings; lumis chooses its own from the output file name.
    film.ignore(&["file_format", "component_format", "banner", "compensate"]);
    let border = film.bool("sample_border", false)?;
    let filter = match film.object("rfilter")? {
        None => json!({"type": "gaussian", "stddev": 0.5, "radius": 2.0}),
        Some(p) => {
            let f = ctx.plugin(target(p))?;
            let v = match f.ty {
                "box" => {
                    f.finish("nothing")?;
                    json!({"type": "box"})
                }
                "gaussian" => {
                    let stddev = f.float("stddev", 0.5)?;
                    let max = crate::camera::filter::MAX_FILTER_RADIUS as f64 / 4.0;
                    if !(stddev > 0.0 && stddev <= max) {
                        return Err(f.get("stddev").map_or_else(
                            || f.error("stddev"),
                            |p| p.error(format!("stddev {stddev} must be in (0, {max}]")),
                        ));
                    }
                    f.finish("stddev")?;
                    json!({"type": "gaussian", "stddev": stddev, "radius": 4.0 * stddev})
                }
                other => {
                    return Err(f.error(format!(
                        "reconstruction filter `{other}` is not supported: lumis has `box` and \
                         `gaussian`"
                    )));
                }
            };
            ctx.origin("camera.filter", f.pos());
            v
        }
    };
    // With a border Mitsuba also samples outside the film: the edge pixels see the whole
    // filter, where lumis renormalises it on the film.
    if border && filter["type"] != "box" {
        return Err(film.get("sample_border").map_or_else(
            || film.error("sample_border"),
            |p| {
                p.error(
                    "sample_border = true is not supported with a gaussian filter (lumis \
                     samples the film only, like Mitsuba's default false)",
                )
            },
        ));
    }
    film.finish(
        "width, height, rfilter, sample_border; pixel_format rgb or rgba; file_format and \
         component_format are ignored",
    )?;
    Ok((w, h, filter))
}

/// A sampler's `sample_count`; every Mitsuba sampler converges to the same image.
fn sampler(s: &Plugin) -> Result<u32, SceneError> {
    if !matches!(
        s.ty,
        "independent" | "stratified" | "multijitter" | "orthogonal" | "ldsampler"
    ) {
        return Err(s.error(format!("sampler type `{}` is not supported", s.ty)));
    }
    let n = s.int("sample_count", 4)?;
    s.ignore(&["seed", "jitter", "strength"]);
    s.finish("sample_count; seed, jitter and strength are ignored")?;
    u32::try_from(n).ok().filter(|&n| n >= 1).ok_or_else(|| {
        s.get("sample_count").map_or_else(
            || s.error("bad"),
            |p| p.error(format!("sample_count {n} must be at least 1")),
        )
    })
}
