//! A material's surface detail, the keys every material type may carry: `normal_map` or
//! `bump_map` (the shading normal, [`crate::materials::normal_map`]) and `opacity` (an alpha
//! mask, [`crate::materials::mask`]).

use super::desc::{NormalMapDesc, TextureDesc};
use super::error::SceneError;
use super::parse_materials::unit_color;
use super::parse_texture::{TextureLoader, TextureUse, texture_at};
use super::walk::Obj;
use crate::textures::Texture;
use glam::DVec3;

/// The optional `normal_map`: `{"texture": T, "flip_invalid_normals": b, "shadowing": b}`, T a
/// texture object or a colour, every channel in [0, 1]; the flags default to Mitsuba's (true).
pub(super) fn normal_map(
    obj: &Obj,
    loader: &mut TextureLoader,
) -> Result<Option<NormalMapDesc>, SceneError> {
    let Some(v) = obj.get("normal_map") else {
        return Ok(None);
    };
    let m = Obj::new(v, obj.at("normal_map"))?;
    m.only_keys(&["texture", "flip_invalid_normals", "shadowing"], true)?;
    let texture = match texture_at(&m, "texture", TextureUse::NormalMap, loader)? {
        Some(t) => t,
        None => {
            let c = unit_color(&m, "texture")?;
            if c == DVec3::splat(0.5) {
                let msg = "(0.5, 0.5, 0.5) encodes the normal 2c − 1 = 0, which has no direction";
                return Err(SceneError::new(m.at("texture"), msg));
            }
            TextureDesc {
                texture: Texture::Constant(c.as_vec3()),
            }
        }
    };
    Ok(Some(NormalMapDesc {
        texture,
        flip_invalid_normals: m.opt_bool("flip_invalid_normals")?.unwrap_or(true),
        shadowing: m.opt_bool("shadowing")?.unwrap_or(true),
        height_scale: None,
    }))
}

/// The optional `bump_map`: `{"texture": T, "scale": s, "flip_invalid_normals": b,
/// "shadowing": b}`, T a bitmap of finite heights (a checkerboard has no gradient), `scale` a
/// finite number (default 1, Mitsuba's); the flags as a normal map's. Not beside a `normal_map`.
pub(super) fn bump_map(
    obj: &Obj,
    loader: &mut TextureLoader,
) -> Result<Option<NormalMapDesc>, SceneError> {
    let Some(v) = obj.get("bump_map") else {
        return Ok(None);
    };
    if obj.get("normal_map").is_some() {
        let msg = "a material has one normal_map or one bump_map, not both";
        return Err(SceneError::new(obj.at("bump_map"), msg));
    }
    let m = Obj::new(v, obj.at("bump_map"))?;
    m.only_keys(
        &["texture", "scale", "flip_invalid_normals", "shadowing"],
        true,
    )?;
    let texture = match texture_at(&m, "texture", TextureUse::Height, loader)? {
        Some(t) if matches!(t.texture, Texture::Bitmap(_)) => t,
        _ => {
            let msg = "a bump map's texture must be a bitmap: heights are differentiated, \
                       and a constant or a checkerboard has no gradient";
            return Err(SceneError::new(m.at("texture"), msg));
        }
    };
    let scale = m.opt_number("scale")?.unwrap_or(1.0);
    Ok(Some(NormalMapDesc {
        texture,
        flip_invalid_normals: m.opt_bool("flip_invalid_normals")?.unwrap_or(true),
        shadowing: m.opt_bool("shadowing")?.unwrap_or(true),
        height_scale: Some(scale),
    }))
}

/// The optional `opacity`: a number or a scalar texture, in [0, 1] (Mitsuba's `mask`; 1 is
/// opaque, 0 invisible).
pub(super) fn opacity(
    obj: &Obj,
    loader: &mut TextureLoader,
) -> Result<Option<TextureDesc>, SceneError> {
    if obj.get("opacity").is_none() {
        return Ok(None);
    }
    if let Some(t) = texture_at(obj, "opacity", TextureUse::Opacity, loader)? {
        return Ok(Some(t));
    }
    let x = obj.number("opacity")?;
    if !(0.0..=1.0).contains(&x) {
        let msg = format!("opacity {x} is outside [0, 1]");
        return Err(SceneError::new(obj.at("opacity"), msg));
    }
    Ok(Some(TextureDesc {
        texture: Texture::Constant(glam::Vec3::splat(x as f32)),
    }))
}
