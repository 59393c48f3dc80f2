//! `<sensor>` (`perspective`, `thinlens`, `orthographic`) with its `hdrfilm`, `rfilter` and
//! `sampler`: lumis' camera and the sample count.
//!
//! Mitsuba's perspective and thin-lens cameras look along their `to_world`'s +z, with +y up and
//! +x to the left (`look_at`), which is lumis' camera with `from` = the origin, `to` = origin + z
//! and `up` = y, exactly when `to_world` is a rotation and translation (Mitsuba refuses scale
//! factors; a mirroring one is refused here, lumis' image axis being `cross(forward, up)`). The
//! field of view follows Mitsuba's `parse_fov` (`fov` on `fov_axis` x, y, diagonal, smaller or
//! larger, or a 35 mm `focal_length`, default 50 mm) and becomes lumis' vertical one. A thin
//! lens keeps `aperture_radius` and `focus_distance` (default: the far clip plane, as Mitsuba).
//! The orthographic camera's `to_world` may scale: that is how Mitsuba sizes its film.

use super::plugin::Plugin;
use super::xml::Pos;
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

/// A `<sensor>`: `perspective`, `thinlens` or `orthographic`.
pub fn sensor(ctx: &mut Ctx, sensor: &Plugin) -> Result<SensorOut, SceneError> {
    if !matches!(sensor.ty, "perspective" | "thinlens" | "orthographic") {
        let why = match sensor.ty {
            "telecentric" => " (a telecentric lens; lumis has orthographic, its pinhole limit)",
            "radiancemeter" | "irradiancemeter" | "distant" | "batch" => {
                " (lumis renders one image)"
            }
            _ => "",
        };
        return Err(sensor.error(format!(
            "sensor type `{}` is not supported{why}; use perspective, thinlens or orthographic",
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
    let (to_world, tpos) = match sensor.transform("to_world")? {
        Some((m, p)) => (m, p.el.pos.clone()),
        None => (glam::DMat4::IDENTITY, sensor.pos().clone()),
    };
    let mut camera = if sensor.ty == "orthographic" {
        orthographic(ctx, sensor, &to_world, &tpos, aspect)?
    } else {
        projective(ctx, sensor, &to_world, &tpos, aspect)?
    };
    camera["width"] = json!(width);
    camera["height"] = json!(height);
    camera["filter"] = filter;
    // Far clip planes beyond the scene, as assumed throughout (docs/mitsuba.md).
    sensor.ignore(&["far_clip", "shutter_open", "shutter_close"]);
    let spp = match sensor.object("sampler")? {
        Some(p) => sampler(&ctx.plugin(target(p))?)?,
        None => 4,
    };
    sensor.finish(match sensor.ty {
        "orthographic" => {
            "to_world, near_clip, film, sampler; far_clip, shutter_open and shutter_close are \
             ignored"
        }
        "thinlens" => {
            "to_world, fov, fov_axis, focal_length, aperture_radius, focus_distance, film, \
             sampler; near_clip, far_clip, shutter_open and shutter_close are ignored"
        }
        _ => {
            "to_world, fov, fov_axis, focal_length, film, sampler; near_clip, far_clip, \
             focus_distance, shutter_open and shutter_close are ignored"
        }
    })?;
    ctx.origin("camera", sensor.pos());
    for key in ["camera.from", "camera.to", "camera.up"] {
        ctx.origin(key, &tpos);
    }
    ctx.origin(
        "camera.width",
        film.get("width").map_or(film.pos(), |p| p.pos()),
    );
    ctx.origin(
        "camera.height",
        film.get("height").map_or(film.pos(), |p| p.pos()),
    );
    Ok(SensorOut { camera, spp })
}

/// The frame of a `to_world` that is a rotation and translation (Mitsuba refuses scale factors
/// for its perspective and thin-lens cameras; a mirroring one is refused here, lumis' image axis
/// being `cross(forward, up)`): `(from, forward, up)`.
fn rigid_frame(to_world: &glam::DMat4, tpos: &Pos) -> Result<(DVec3, DVec3, DVec3), SceneError> {
    let r = DMat3::from_mat4(*to_world);
    let rrt = r * r.transpose();
    let off = (rrt - DMat3::IDENTITY).to_cols_array();
    if off.iter().any(|x| x.abs() > 1e-3) {
        return Err(tpos.error(
            "the camera's to_world has a scale factor, which Mitsuba does not allow either",
        ));
    }
    if r.determinant() < 0.0 {
        return Err(tpos.error(MIRRORED));
    }
    Ok((to_world.w_axis.truncate(), r.z_axis, r.y_axis))
}

const MIRRORED: &str = "the camera's to_world mirrors the image (negative determinant, e.g. a \
                        scale by -1): lumis' image always runs along cross(forward, up)";

/// A `perspective` or `thinlens` sensor's camera (without its film).
fn projective(
    ctx: &mut Ctx,
    sensor: &Plugin,
    to_world: &glam::DMat4,
    tpos: &Pos,
    aspect: f64,
) -> Result<Value, SceneError> {
    let x_fov = x_fov(sensor, aspect)?;
    let vfov = 2.0
        * ((0.5 * x_fov.to_radians()).tan() / aspect)
            .atan()
            .to_degrees();
    let (from, forward, up) = rigid_frame(to_world, tpos)?;
    let v = |d: DVec3| json!([d.x, d.y, d.z]);
    let mut camera =
        json!({"from": v(from), "to": v(from + forward), "up": v(up), "vfov_deg": vfov});
    ctx.origin(
        "camera.vfov_deg",
        sensor.get("fov").map_or(sensor.pos(), |p| p.pos()),
    );
    if sensor.ty == "thinlens" {
        // Mitsuba requires the aperture; its focus distance defaults to the far clip plane.
        let aperture = sensor.get("aperture_radius").ok_or_else(|| {
            sensor.error("a thinlens needs `aperture_radius` (Mitsuba requires it too)")
        })?;
        let radius = sensor.float("aperture_radius", 0.0)?;
        let far = sensor.float("far_clip", 1e4)?;
        let focus = sensor.float("focus_distance", far)?;
        camera["type"] = json!("thinlens");
        camera["aperture_radius"] = json!(radius);
        camera["focus_distance"] = json!(focus);
        ctx.origin("camera.aperture_radius", aperture.pos());
        ctx.origin(
            "camera.focus_distance",
            sensor
                .get("focus_distance")
                .map_or(sensor.pos(), |p| p.pos()),
        );
        sensor.ignore(&["near_clip"]);
    } else {
        // Mitsuba's perspective camera only (its thinlens and orthographic do not read them).
        let offset = [
            sensor.float("principal_point_offset_x", 0.0)?,
            sensor.float("principal_point_offset_y", 0.0)?,
        ];
        if offset != [0.0; 2] {
            camera["principal_point_offset"] = json!(offset);
            let p = sensor.get("principal_point_offset_x");
            let p = p.or_else(|| sensor.get("principal_point_offset_y"));
            ctx.origin(
                "camera.principal_point_offset",
                p.map_or(sensor.pos(), |p| p.pos()),
            );
        }
        // A pinhole's image does not depend on them (clip planes outside the scene assumed).
        sensor.ignore(&["near_clip", "focus_distance"]);
    }
    Ok(camera)
}

/// An `orthographic` sensor's camera (without its film). Mitsuba's film spans [−1, 1] ×
/// [−1/aspect, 1/aspect] in camera space, mapped by `to_world` (any affine map, usually a
/// `scale` before the `lookat`); rays start on the near plane z = `near_clip`. lumis takes
/// `to_world`s whose axes stay perpendicular (no shear) and that do not mirror: the film's
/// world-space size is then the scaled axes' lengths, and `from` the near plane's centre.
fn orthographic(
    ctx: &mut Ctx,
    sensor: &Plugin,
    to_world: &glam::DMat4,
    tpos: &Pos,
    aspect: f64,
) -> Result<Value, SceneError> {
    let m = DMat3::from_mat4(*to_world);
    let (x, y, z) = (m.x_axis, m.y_axis, m.z_axis);
    let sheared = [(x, y), (y, z), (x, z)]
        .iter()
        .any(|(a, b)| a.dot(*b).abs() > 1e-6 * a.length() * b.length());
    if sheared || m.determinant() == 0.0 || !m.determinant().is_finite() {
        return Err(tpos.error(
            "the orthographic camera's to_world shears or flattens its axes: lumis takes a \
             scale, rotation and translation",
        ));
    }
    if m.determinant() < 0.0 {
        return Err(tpos.error(MIRRORED));
    }
    let near = sensor.float("near_clip", 1e-2)?;
    if near.is_nan() || near <= 0.0 {
        return Err(sensor.get("near_clip").map_or_else(
            || sensor.error("near_clip"),
            |p| p.error("near_clip must be > 0"),
        ));
    }
    let from = to_world.transform_point3(DVec3::new(0.0, 0.0, near));
    let v = |d: DVec3| json!([d.x, d.y, d.z]);
    let view = [2.0 * x.length(), 2.0 * y.length() / aspect];
    ctx.origin("camera.view_size", tpos);
    Ok(json!({
        "type": "orthographic",
        "from": v(from), "to": v(from + z.normalize()), "up": v(y.normalize()),
        "view_size": view,
    }))
}

/// Mitsuba's horizontal field of view in degrees (`parse_fov`).
fn x_fov(sensor: &Plugin, aspect: f64) -> Result<f64, SceneError> {
    let (fov, axis, pos) = fov_and_axis(sensor)?;
    let x =
        crate::scene::parse_lights::horizontal_fov_deg(fov, &axis, aspect).ok_or_else(|| {
            sensor.get("fov_axis").map_or_else(
                || sensor.error("bad fov_axis"),
                |p| {
                    p.error(format!(
                        "fov_axis `{axis}` must be x, y, diagonal, smaller or larger"
                    ))
                },
            )
        })?;
    if !(x > 0.0 && x < 180.0) {
        return Err(pos.error(format!(
            "the horizontal field of view {x}° is outside (0, 180)"
        )));
    }
    Ok(x)
}

/// The field of view in degrees of a sensor or projector and the axis it is measured on
/// (lower case), as Mitsuba's `parse_fov` reads them: `fov` on `fov_axis` (default x), or
/// `focal_length` (default 50 mm, on a 36 × 24 mm film's diagonal); with where it was given.
pub(super) fn fov_and_axis(plugin: &Plugin) -> Result<(f64, String, Pos), SceneError> {
    if plugin.has("fov") && plugin.has("focal_length") {
        return Err(plugin.error("give either `fov` or `focal_length`, not both"));
    }
    Ok(match plugin.get("fov") {
        Some(p) => {
            let fov = plugin.float("fov", 0.0)?;
            let axis = match plugin.string("fov_axis")? {
                Some((s, _)) => s.to_ascii_lowercase(),
                None => "x".to_owned(),
            };
            (fov, axis, p.pos().clone())
        }
        None => {
            let (text, pos) = match plugin.string("focal_length")? {
                Some((s, p)) => (s.to_owned(), p.pos().clone()),
                None => ("50mm".to_owned(), plugin.pos().clone()),
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
    })
}

/// An `hdrfilm`'s size and lumis' `camera.filter` for its `rfilter`: `box`, `gaussian` (also
/// when there is none, Mitsuba's default) with Mitsuba's stddev (default 0.5) and its fixed
/// radius 4·stddev, `tent` with its radius (default 1), `lanczos` with its lobes (default 3),
/// `mitchell` with its B and C (default ⅓ each) or `catmullrom`. lumis samples the film like
/// Mitsuba's default `sample_border = false`.
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
                "tent" => {
                    let radius = f.float("radius", 1.0)?;
                    let max = crate::camera::filter::MAX_FILTER_RADIUS as f64;
                    if !(radius > 0.0 && radius <= max) {
                        return Err(f.get("radius").map_or_else(
                            || f.error("radius"),
                            |p| p.error(format!("radius {radius} must be in (0, {max}]")),
                        ));
                    }
                    f.finish("radius")?;
                    json!({"type": "tent", "radius": radius})
                }
                "lanczos" => {
                    let lobes = f.int("lobes", 3)?;
                    let max = crate::camera::filter::MAX_FILTER_RADIUS as i64;
                    if !(1..=max).contains(&lobes) {
                        return Err(f.get("lobes").map_or_else(
                            || f.error("lobes"),
                            |p| p.error(format!("lobes {lobes} must be in [1, {max}]")),
                        ));
                    }
                    f.finish("lobes")?;
                    json!({"type": "lanczos", "lobes": lobes})
                }
                "mitchell" => {
                    // Mitsuba's plugin reads `B` and `C` (its documentation says `A` and `B`).
                    let (b, c) = (f.float("B", 1.0 / 3.0)?, f.float("C", 1.0 / 3.0)?);
                    f.finish("B and C")?;
                    json!({"type": "mitchell", "b": b, "c": c})
                }
                "catmullrom" => {
                    f.finish("nothing")?;
                    json!({"type": "catmullrom"})
                }
                other => {
                    return Err(f.error(format!(
                        "reconstruction filter `{other}` is not supported: lumis has `box`, \
                         `gaussian`, `tent`, `lanczos`, `mitchell` and `catmullrom`"
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
