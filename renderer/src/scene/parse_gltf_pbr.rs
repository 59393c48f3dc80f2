//! The `gltf_pbr` material (glTF 2.0's metallic-roughness material, `materials/gltf_pbr.rs`):
//! its keys, glTF's defaults, and their range checks. Keys: `base_color` (a colour in [0, 1] or
//! a texture, default 1), `roughness` and `metallic` (each a number in [0, 1] or a texture read as
//! a scalar, default 1: glTF's `roughnessFactor` and `metallicFactor`, or the G and B channels of
//! its `metallicRoughnessTexture` through a bitmap's `channel`), `ior` (a number ≥ 1, default 1.5,
//! `KHR_materials_ior`), `specular` (a number in [0, 1], default 1) and `specular_color` (a colour
//! of finite components ≥ 0, default white; `KHR_materials_specular`, which allows them above 1),
//! and `two_sided`, `normal_map`, `bump_map`, `opacity` as every reflecting material has them.

use super::desc::{GltfPbrDesc, MaterialDesc, MaterialTextures};
use super::error::SceneError;
use super::parse_materials::unit_color;
use super::parse_texture::{TextureLoader, TextureUse, texture_at};
use super::walk::{Obj, check_components};
use crate::materials::gltf_pbr::GltfParam;

/// A `gltf_pbr` material; its textures go into `t` (`base_color` into `albedo`, the scalars into
/// `principled` in [`GltfParam::ALL`]'s order).
pub(crate) fn parse_gltf_pbr(
    obj: &Obj,
    loader: &mut TextureLoader,
    t: &mut MaterialTextures,
) -> Result<MaterialDesc, SceneError> {
    let mut keys = vec![
        "type",
        "base_color",
        "ior",
        "specular",
        "specular_color",
        "two_sided",
        "normal_map",
        "bump_map",
        "opacity",
    ];
    keys.extend(GltfParam::ALL.map(GltfParam::name));
    obj.only_keys(&keys, true)?;
    let mut p = GltfPbrDesc::default();
    t.albedo = texture_at(obj, "base_color", TextureUse::Albedo, loader)?;
    p.base_color = match &t.albedo {
        Some(tex) => tex.mean_color(),
        None if obj.get("base_color").is_some() => unit_color(obj, "base_color")?,
        None => p.base_color,
    };
    for (k, param) in GltfParam::ALL.into_iter().enumerate() {
        let key = param.name();
        t.principled[k] = texture_at(obj, key, TextureUse::Parameter, loader)?;
        p.scalars[k] = match &t.principled[k] {
            Some(tex) => tex.mean_scalar(),
            None => match obj.opt_number(key)? {
                Some(x) => match TextureUse::Parameter.problem(x) {
                    Some(why) => {
                        return Err(SceneError::new(obj.at(key), format!("{key} {x} {why}")));
                    }
                    None => x,
                },
                None => p.scalars[k],
            },
        };
    }
    if let Some(ior) = obj.opt_number("ior")? {
        // Only its f0 ((ior − 1)/(ior + 1))² matters: nothing refracts.
        if !(ior >= 1.0 && ior.is_finite()) {
            let msg = format!("ior {ior} must be a finite number ≥ 1");
            return Err(SceneError::new(obj.at("ior"), msg));
        }
        p.ior = ior;
    }
    if let Some(x) = obj.opt_number("specular")? {
        if !(0.0..=1.0).contains(&x) {
            let msg = format!("specular {x} is outside [0, 1]");
            return Err(SceneError::new(obj.at("specular"), msg));
        }
        p.specular = x;
    }
    if obj.get("specular_color").is_some() {
        p.specular_color = check_components(
            obj.vec3("specular_color")?,
            &obj.at("specular_color"),
            |x| x >= 0.0 && (x as f32).is_finite(),
            "must be a finite number ≥ 0",
        )?;
    }
    Ok(MaterialDesc::GltfPbr(p))
}

#[cfg(test)]
#[path = "parse_gltf_pbr_tests.rs"]
mod tests;
