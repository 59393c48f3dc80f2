//! The `principled` material (Mitsuba's principled BSDF, `materials/principled.rs`): its keys,
//! Mitsuba's defaults and rules, and their range checks. Keys are Mitsuba's: `base_color` (a
//! colour in [0, 1] or a texture, default 0.5), the scalars of
//! [`PrincipledParam::ALL`] (each a number in [0, 1] or a texture; roughness 0.5, the rest 0),
//! `eta` (> 0) or `specular` (in [0, 1], default 0.5; never both), the three sampling rates
//! ([`RATE_KEYS`], ≥ 0, default 1), and `two_sided`, `normal_map`, `bump_map`, `opacity` as
//! every material has them. A `spec_trans` given as a texture or as a number other than 0 turns
//! on specular transmission (Mitsuba's flag): the back side is then the inside, and the material
//! is never two-sided.

use super::desc::{MaterialDesc, MaterialTextures, PrincipledDesc};
use super::error::SceneError;
use super::parse_materials::unit_color;
use super::parse_texture::{TextureLoader, TextureUse, texture_at};
use super::walk::Obj;
use crate::materials::principled::{PrincipledParam, mitsuba_eta};

/// The sampling rates' keys, in [`PrincipledDesc::rates`]' order.
pub(crate) const RATE_KEYS: [&str; 3] = [
    "main_specular_sampling_rate",
    "clearcoat_sampling_rate",
    "diffuse_reflectance_sampling_rate",
];

/// The largest `eta` (as a dielectric's `ior`).
const MAX_ETA: f64 = crate::materials::dielectric::MAX_IOR as f64;

/// A `principled` material; its textures go into `t` (`base_color` into `albedo`).
pub(crate) fn parse_principled(
    obj: &Obj,
    loader: &mut TextureLoader,
    t: &mut MaterialTextures,
) -> Result<MaterialDesc, SceneError> {
    let mut keys = vec![
        "type",
        "base_color",
        "eta",
        "specular",
        "two_sided",
        "normal_map",
        "bump_map",
        "opacity",
    ];
    keys.extend(PrincipledParam::ALL.map(PrincipledParam::name));
    keys.extend(RATE_KEYS);
    obj.only_keys(&keys, true)?;
    let mut p = PrincipledDesc::default();
    t.albedo = texture_at(obj, "base_color", TextureUse::Albedo, loader)?;
    p.base_color = match &t.albedo {
        Some(tex) => tex.mean_color(),
        None if obj.get("base_color").is_some() => unit_color(obj, "base_color")?,
        None => p.base_color,
    };
    for (k, param) in PrincipledParam::ALL.into_iter().enumerate() {
        let key = param.name();
        t.principled[k] = texture_at(obj, key, TextureUse::Parameter, loader)?;
        p.scalars[k] = match &t.principled[k] {
            Some(tex) => tex.mean_scalar(),
            None => match obj.opt_number(key)? {
                Some(x) if !(0.0..=1.0).contains(&x) => {
                    return Err(SceneError::new(
                        obj.at(key),
                        format!("{key} {x} is outside [0, 1]"),
                    ));
                }
                Some(x) => x,
                None => p.scalars[k],
            },
        };
    }
    let spec_trans = PrincipledParam::SpecTrans as usize;
    p.transmission = t.principled[spec_trans].is_some() || p.scalars[spec_trans] != 0.0;
    for (key, rate) in RATE_KEYS.iter().zip(&mut p.rates) {
        if let Some(x) = obj.opt_number(key)? {
            if !(x >= 0.0 && x.is_finite()) {
                let msg = format!("{key} {x} must be a finite number ≥ 0");
                return Err(SceneError::new(obj.at(key), msg));
            }
            *rate = x;
        }
    }
    let (eta, specular) = (obj.opt_number("eta")?, obj.opt_number("specular")?);
    if eta.is_some() && specular.is_some() {
        let msg = "give eta or specular, not both: each sets the other (Mitsuba's rule)";
        return Err(SceneError::new(obj.at("specular"), msg));
    }
    if let Some(e) = eta
        && !(e > 0.0 && e <= MAX_ETA)
    {
        let msg = format!("eta {e} must be positive and at most {MAX_ETA}");
        return Err(SceneError::new(obj.at("eta"), msg));
    }
    if let Some(s) = specular
        && !(0.0..=1.0).contains(&s)
    {
        let msg = format!("specular {s} is outside [0, 1]");
        return Err(SceneError::new(obj.at("specular"), msg));
    }
    // A given eta keeps its bits (the exporter's round trip); `mitsuba_eta` (in f32) gives what
    // Mitsuba changes or computes.
    p.eta = match eta {
        Some(e) if !(p.transmission && e == 1.0) => e,
        _ => mitsuba_eta(
            eta.map(|e| e as f32),
            specular.map(|s| s as f32),
            p.transmission,
        ) as f64,
    };
    if p.transmission && obj.get("two_sided").is_some() {
        let msg = "a principled with spec_trans is never two-sided: its two sides are its two \
                   media";
        return Err(SceneError::new(obj.at("two_sided"), msg));
    }
    Ok(MaterialDesc::Principled(p))
}

#[cfg(test)]
#[path = "parse_principled_tests.rs"]
mod tests;
