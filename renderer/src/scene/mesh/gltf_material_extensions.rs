//! The material extensions the glTF reader maps (`gltf_materials.rs`; docs/scene-format.md,
//! "glTF materials"), as methods of its reader: `KHR_materials_transmission`,
//! `KHR_materials_specular`, the emission with `KHR_materials_emissive_strength`, and
//! `KHR_materials_unlit`. Errors name
//! the glTF path of the value, as everywhere in the reader.

use super::{Mapped, Param, Reader, extension, unit_components};
use crate::scene::mesh::MeshError;
use ::gltf::json;
use glam::Vec3;
use serde_json::{Map, Value, json};

impl Reader<'_> {
    /// `KHR_materials_transmission`: the factor and, if given, the texture's R channel times
    /// it (as a mix weight).
    pub(super) fn transmission(
        &mut self,
        e: &Map<String, Value>,
        at: &str,
    ) -> Result<(f64, Option<Param>), MeshError> {
        let ext_at = format!("{at}.extensions.KHR_materials_transmission");
        let factor_at = format!("{ext_at}.transmissionFactor");
        let factor = self.number(e, "transmissionFactor", &factor_at, 0.0)?;
        if !(0.0..=1.0).contains(&factor) {
            return Err(self.error(&factor_at, format!("{factor} is outside [0, 1]")));
        }
        let tex_at = format!("{ext_at}.transmissionTexture");
        let texture = match e.get("transmissionTexture") {
            Some(v) if factor > 0.0 => {
                let info: json::texture::Info =
                    serde_json::from_value(v.clone()).map_err(|err| {
                        self.error(&tex_at, format!("invalid texture reference: {err}"))
                    })?;
                let count = self.root.textures.len();
                if info.index.value() >= count {
                    return Err(self.error(
                        &format!("{tex_at}.index"),
                        format!(
                            "texture {} does not exist ({count} textures)",
                            info.index.value()
                        ),
                    ));
                }
                let mut j = self.texture(&tex_at, &info, true)?.json;
                j["channel"] = json!("r");
                j["scale"] = json!(factor);
                Some(Param::Texture(j))
            }
            _ => None,
        };
        Ok((factor, texture))
    }

    /// `KHR_materials_specular`: `specularFactor` (in [0, 1], default 1) and
    /// `specularColorFactor` (finite, ≥ 0, default white); its textures are named in the warning.
    pub(super) fn specular(
        &mut self,
        e: &Map<String, Value>,
        at: &str,
    ) -> Result<(f64, [f64; 3]), MeshError> {
        let ext_at = format!("{at}.extensions.KHR_materials_specular");
        let factor_at = format!("{ext_at}.specularFactor");
        let factor = self.number(e, "specularFactor", &factor_at, 1.0)?;
        if !(0.0..=1.0).contains(&factor) {
            return Err(self.error(&factor_at, format!("{factor} is outside [0, 1]")));
        }
        let color_at = format!("{ext_at}.specularColorFactor");
        let color = match e.get("specularColorFactor") {
            None => [1.0; 3],
            Some(v) => {
                let c = v.as_array().filter(|a| a.len() == 3);
                let c = c.and_then(|a| Some([a[0].as_f64()?, a[1].as_f64()?, a[2].as_f64()?]));
                c.filter(|c| c.iter().all(|x| *x >= 0.0 && (*x as f32).is_finite()))
                    .ok_or_else(|| {
                        self.error(
                            &color_at,
                            format!("expected 3 finite numbers ≥ 0, found {v}"),
                        )
                    })?
            }
        };
        for key in ["specularTexture", "specularColorTexture"] {
            if e.contains_key(key) {
                self.out.ignored.push(format!("{ext_at}.{key}"));
            }
        }
        Ok((factor, color))
    }

    /// `emissiveFactor` × `KHR_materials_emissive_strength` (× `emissiveTexture`, sRGB), if
    /// not black.
    pub(super) fn emission(
        &mut self,
        m: &json::Material,
        others: Option<&Map<String, Value>>,
        at: &str,
    ) -> Result<Option<Param>, MeshError> {
        let factor = m.emissive_factor.0;
        unit_components(self, &format!("{at}.emissiveFactor"), &factor)?;
        let strength_at =
            format!("{at}.extensions.KHR_materials_emissive_strength.emissiveStrength");
        let strength = match extension(others, "KHR_materials_emissive_strength") {
            Some(e) => self.number(e, "emissiveStrength", &strength_at, 1.0)?,
            None => 1.0,
        };
        if strength < 0.0 {
            return Err(self.error(&strength_at, format!("{strength} must not be negative")));
        }
        let le = Vec3::from_array(factor).as_dvec3() * strength;
        if le == glam::DVec3::ZERO {
            return Ok(None);
        }
        Ok(Some(match &m.emissive_texture {
            Some(info) => {
                let mut j = self
                    .texture(&format!("{at}.emissiveTexture"), info, false)?
                    .json;
                j["scale"] = json!([le.x, le.y, le.z]);
                Param::Texture(j)
            }
            None => Param::Constant(json!([le.x, le.y, le.z])),
        }))
    }

    /// `KHR_materials_unlit`: glTF shows the base colour (`base`; `black`: its factor is 0) to
    /// the camera and lights nothing else with it. lumis has no emission seen by camera rays
    /// only (its `hide_emitters` is the opposite, for every emitter), so the nearest is a
    /// black diffuse surface that emits its base colour as radiance: seen the same, but it
    /// lights the surfaces around it too (named in the warning). Its other properties are
    /// ignored, as glTF's unlit material ignores them.
    pub(super) fn unlit(
        &mut self,
        at: &str,
        name: String,
        base: Param,
        black: bool,
        opacity: Option<Param>,
    ) -> Mapped {
        self.out.ignored.push(format!(
            "{at}.extensions.KHR_materials_unlit: an emitter of its base colour, which lumis              lets light other surfaces too"
        ));
        let mut material = json!({"type": "diffuse", "albedo": [0.0, 0.0, 0.0]});
        let emission = (!black).then_some(base);
        // An emitter's material takes no opacity (Mitsuba masks a BSDF, not its emission).
        match &opacity {
            Some(_) if emission.is_some() => self.out.ignored.push(format!(
                "{at}.alphaMode on an emissive material (lumis masks no emitter)"
            )),
            Some(o) => material["opacity"] = o.json(),
            None => {}
        }
        self.out.json.insert(name.clone(), material);
        let textured = emission.as_ref().is_some_and(Param::is_texture)
            || (emission.is_none() && opacity.as_ref().is_some_and(Param::is_texture));
        Mapped {
            name,
            emission: emission.map(|e| e.json()),
            textured,
        }
    }
}
