//! The `principled_thin` material (Mitsuba's `principledthin`, `materials/principled_thin.rs`):
//! its keys, Mitsuba's defaults, and their range checks. Keys are Mitsuba's: `base_color` (a
//! colour in [0, 1] or a texture, default 0.5), the scalars of [`ThinParam::ALL`] (each a number
//! or a texture: in [0, 1], except `diff_trans` in [0, 2] and `eta` in (0, 10]; roughness 0.5, η
//! 1.5, the rest 0), the four sampling rates ([`ThinRates::KEYS`], ≥ 0, default 1), and
//! `normal_map`, `bump_map`, `opacity` as every material has them. It has no `two_sided`: its
//! two sides are alike (Mitsuba refuses it inside `twosided` too).

use super::desc::{MaterialDesc, MaterialTextures, PrincipledThinDesc};
use super::error::SceneError;
use super::parse_materials::unit_color;
use super::parse_texture::{TextureLoader, TextureUse, texture_at};
use super::walk::Obj;
use crate::materials::principled_thin::{ThinParam, ThinRates};

/// The texture use (and so the range) of `param`'s slot.
pub(crate) fn texture_use(param: ThinParam) -> TextureUse {
    match param {
        ThinParam::DiffTrans => TextureUse::DiffuseTransmission,
        ThinParam::Eta => TextureUse::Eta,
        _ => TextureUse::Parameter,
    }
}

/// A `principled_thin` material; its textures go into `t` (`base_color` into `albedo`, the
/// scalars into `principled` in [`ThinParam::ALL`]'s order).
pub(crate) fn parse_principled_thin(
    obj: &Obj,
    loader: &mut TextureLoader,
    t: &mut MaterialTextures,
) -> Result<MaterialDesc, SceneError> {
    if obj.get("two_sided").is_some() {
        let msg = "a principled_thin is the same from both sides: it has no two_sided";
        return Err(SceneError::new(obj.at("two_sided"), msg));
    }
    let mut keys = vec!["type", "base_color", "normal_map", "bump_map", "opacity"];
    keys.extend(ThinParam::ALL.map(ThinParam::name));
    keys.extend(ThinRates::KEYS);
    obj.only_keys(&keys, true)?;
    let mut p = PrincipledThinDesc::default();
    t.albedo = texture_at(obj, "base_color", TextureUse::Albedo, loader)?;
    p.base_color = match &t.albedo {
        Some(tex) => tex.mean_color(),
        None if obj.get("base_color").is_some() => unit_color(obj, "base_color")?,
        None => p.base_color,
    };
    for (k, param) in ThinParam::ALL.into_iter().enumerate() {
        let key = param.name();
        let use_ = texture_use(param);
        t.principled[k] = texture_at(obj, key, use_, loader)?;
        p.scalars[k] = match &t.principled[k] {
            Some(tex) => tex.mean_scalar(),
            None => match obj.opt_number(key)? {
                Some(x) => match use_.problem(x) {
                    Some(why) => {
                        return Err(SceneError::new(obj.at(key), format!("{key} {x} {why}")));
                    }
                    None => x,
                },
                None => p.scalars[k],
            },
        };
    }
    for (key, rate) in ThinRates::KEYS.iter().zip(&mut p.rates) {
        if let Some(x) = obj.opt_number(key)? {
            if !(x >= 0.0 && x.is_finite()) {
                let msg = format!("{key} {x} must be a finite number ≥ 0");
                return Err(SceneError::new(obj.at(key), msg));
            }
            *rate = x;
        }
    }
    Ok(MaterialDesc::PrincipledThin(p))
}

#[cfg(test)]
#[path = "parse_principled_thin_tests.rs"]
mod tests;
