//! The `materials` map: diffuse, conductor, plastic, dielectric, thin dielectric, and the
//! materials made of others (mix, two_sided: `parse_composite`), with their range rules.

use super::desc::Distribution;
use super::desc::{
    FresnelDesc, MaterialDesc, MaterialTextures, NamedMaterial, PlasticModel, TextureDesc,
};
use super::error::SceneError;
use super::parse_composite::{Pending, parse_mix, parse_two_sided, resolve_parts};
use super::parse_surface_detail::{bump_map, normal_map, opacity};
use super::parse_texture::{TextureLoader, TextureUse, parse_texture, texture_at};
use super::walk::{Obj, check_components};
use crate::textures::Texture;
use glam::DVec3;
use serde_json::Value;

/// Every material of the map, sorted by name (the map's order); texture files come from
/// `loader`. Mixes and pairs are resolved once every material is known (`resolve_parts`).
pub(crate) fn parse_materials(
    obj: &Obj,
    loader: &mut TextureLoader,
) -> Result<Vec<NamedMaterial>, SceneError> {
    let mut materials = Vec::with_capacity(obj.map().len());
    let mut pending = Vec::with_capacity(obj.map().len());
    for (name, value) in obj.map() {
        let m = Obj::new(value, obj.at(name))?;
        if name.is_empty() {
            return Err(SceneError::new(m.path, "a material name must not be empty"));
        }
        let (material, parts) = parse_material(name, &m, loader)?;
        materials.push(material);
        pending.push(parts);
    }
    resolve_parts(obj, &mut materials, pending)?;
    Ok(materials)
}

fn parse_material(
    name: &str,
    obj: &Obj,
    loader: &mut TextureLoader,
) -> Result<(NamedMaterial, Option<Pending>), SceneError> {
    let kind = obj.string("type")?;
    let mut textures = MaterialTextures::default();
    let t = &mut textures;
    let mut parts = None;
    let material = match kind {
        "diffuse" => {
            obj.only_keys(
                &[
                    "type",
                    "albedo",
                    "two_sided",
                    "normal_map",
                    "bump_map",
                    "opacity",
                ],
                true,
            )?;
            MaterialDesc::Diffuse {
                albedo: albedo(obj, loader, &mut t.albedo)?,
            }
        }
        "conductor" => {
            obj.only_keys(
                &[
                    "type",
                    "alpha",
                    "distribution",
                    "eta",
                    "k",
                    "reflectance",
                    "specular",
                    "two_sided",
                    "normal_map",
                    "bump_map",
                    "opacity",
                ],
                true,
            )?;
            let (alpha, alpha_v) = microfacet_alpha(obj, loader, t)?;
            MaterialDesc::Conductor {
                alpha,
                alpha_v,
                distribution: distribution(obj)?,
                fresnel: fresnel(obj, loader, &mut t.reflectance)?,
            }
        }
        "plastic" => {
            obj.only_keys(
                &[
                    "type",
                    "albedo",
                    "alpha",
                    "ior",
                    "specular",
                    "two_sided",
                    "model",
                    "distribution",
                    "nonlinear",
                    "normal_map",
                    "bump_map",
                    "opacity",
                ],
                true,
            )?;
            let ior = obj.opt_number("ior")?.unwrap_or(1.5);
            if ior <= 1.0 {
                let msg = format!("ior {ior} must be greater than 1");
                return Err(SceneError::new(obj.at("ior"), msg));
            }
            let specular = match obj.get("specular") {
                Some(_) => unit_color(obj, "specular")?,
                None => DVec3::ONE,
            };
            let albedo = albedo(obj, loader, &mut t.albedo)?;
            let alpha = alpha(obj, loader, &mut t.alpha)?;
            let model = plastic_model(obj)?;
            if model != PlasticModel::Lumis && t.alpha.is_some() {
                let msg = "a textured alpha needs lumis' coupling (Mitsuba's roughplastic has \
                           none: its tables are built for one alpha)";
                return Err(SceneError::new(obj.at("alpha"), msg));
            }
            MaterialDesc::Plastic {
                albedo,
                alpha,
                ior,
                specular,
                model,
            }
        }
        "dielectric" => {
            if obj.get("two_sided").is_some() {
                let msg = "a dielectric is never two-sided: its two sides are its two media";
                return Err(SceneError::new(obj.at("two_sided"), msg));
            }
            obj.only_keys(
                &[
                    "type",
                    "ior",
                    "alpha",
                    "distribution",
                    "normal_map",
                    "bump_map",
                    "opacity",
                ],
                true,
            )?;
            let ior = obj.opt_number("ior")?.unwrap_or(1.5);
            let max = crate::materials::dielectric::MAX_IOR as f64;
            if !(ior > 0.0 && ior != 1.0 && ior <= max) {
                let msg = format!("ior {ior} must be positive, not 1, and at most {max}");
                return Err(SceneError::new(obj.at("ior"), msg));
            }
            let (alpha, alpha_v) = match obj.get("alpha") {
                Some(_) => microfacet_alpha(obj, loader, t)?,
                None => (0.0, None),
            };
            MaterialDesc::Dielectric {
                ior,
                alpha,
                alpha_v,
                distribution: distribution(obj)?,
            }
        }
        "thin_dielectric" => {
            if obj.get("two_sided").is_some() {
                let msg = "a thin dielectric has no two_sided: it is the same from both sides";
                return Err(SceneError::new(obj.at("two_sided"), msg));
            }
            obj.only_keys(&["type", "ior", "opacity"], true)?;
            let ior = obj.opt_number("ior")?.unwrap_or(1.5);
            let max = crate::materials::dielectric::MAX_IOR as f64;
            if !(ior > 0.0 && ior <= max) {
                let msg = format!("ior {ior} must be positive and at most {max}");
                return Err(SceneError::new(obj.at("ior"), msg));
            }
            MaterialDesc::ThinDielectric { ior }
        }
        "principled" => super::parse_principled::parse_principled(obj, loader, t)?,
        "principled_thin" => super::parse_principled_thin::parse_principled_thin(obj, loader, t)?,
        "gltf_pbr" => super::parse_gltf_pbr::parse_gltf_pbr(obj, loader, t)?,
        "mix" => {
            if obj.get("two_sided").is_some() {
                let msg = "a mix has no sides of its own: its materials' `two_sided` apply";
                return Err(SceneError::new(obj.at("two_sided"), msg));
            }
            obj.only_keys(&["type", "materials", "weight", "model", "opacity"], true)?;
            parts = Some(parse_mix(obj, loader)?);
            // Replaced by the favoured material's once the names resolve.
            MaterialDesc::Diffuse {
                albedo: DVec3::ZERO,
            }
        }
        "two_sided" => {
            parts = Some(parse_two_sided(obj)?);
            // Replaced by the front's once the names resolve.
            MaterialDesc::Diffuse {
                albedo: DVec3::ZERO,
            }
        }
        other => {
            return Err(SceneError::new(
                obj.at("type"),
                format!(
                    "unknown material type `{other}` (expected diffuse, conductor, plastic, \
                     dielectric, thin_dielectric, principled, principled_thin, gltf_pbr, mix \
                     or two_sided)"
                ),
            ));
        }
    };
    let two_sided = !material.transmits() && obj.opt_bool("two_sided")?.unwrap_or(true);
    let named = NamedMaterial {
        name: name.to_owned(),
        material,
        two_sided,
        textures,
        normal_map: match bump_map(obj, loader)? {
            Some(b) => Some(b),
            None => normal_map(obj, loader)?,
        },
        opacity: opacity(obj, loader)?,
        mix: None,
        sides: None,
    };
    Ok((named, parts))
}

/// The required `albedo`: a colour in [0, 1] or a texture (then its mean, and `slot` is set).
fn albedo(
    obj: &Obj,
    loader: &mut TextureLoader,
    slot: &mut Option<TextureDesc>,
) -> Result<DVec3, SceneError> {
    *slot = texture_at(obj, "albedo", TextureUse::Albedo, loader)?;
    match slot {
        Some(t) => Ok(t.mean_color()),
        None => unit_color(obj, "albedo"),
    }
}

/// A required colour with every channel in [0, 1] (reflectances: more would create energy).
pub(super) fn unit_color(obj: &Obj, key: &str) -> Result<DVec3, SceneError> {
    let c = obj.vec3(key)?;
    check_components(
        c,
        &obj.at(key),
        |x| (0.0..=1.0).contains(&x),
        "is outside [0, 1]",
    )
}

/// The required GGX α in [0, 1], or a texture (then its mean, and `slot` is set).
fn alpha(
    obj: &Obj,
    loader: &mut TextureLoader,
    slot: &mut Option<TextureDesc>,
) -> Result<f64, SceneError> {
    *slot = texture_at(obj, "alpha", TextureUse::Alpha, loader)?;
    if let Some(t) = slot {
        return Ok(t.mean_scalar());
    }
    let a = obj.number("alpha")?;
    if !(0.0..=1.0).contains(&a) {
        return Err(SceneError::new(
            obj.at("alpha"),
            format!("alpha {a} is outside [0, 1]"),
        ));
    }
    Ok(a)
}

/// A microfacet material's `alpha`: as [`alpha`], or [α_u, α_v] (each a number in [0, 1] or a
/// texture) for anisotropic roughness, `None` as the second where two numbers are equal. A pair
/// with a texture fills both slots (`alpha`: α_u, `alpha_v`), a number as a constant texture.
fn microfacet_alpha(
    obj: &Obj,
    loader: &mut TextureLoader,
    t: &mut MaterialTextures,
) -> Result<(f64, Option<f64>), SceneError> {
    let Some(pair) = obj.get("alpha").and_then(Value::as_array) else {
        return Ok((alpha(obj, loader, &mut t.alpha)?, None));
    };
    let at = obj.at("alpha");
    let [u, v] = &pair[..] else {
        return Err(SceneError::new(
            at,
            "alpha must be a number, a texture or a pair [alpha_u, alpha_v] of numbers or textures",
        ));
    };
    if !(u.is_object() || v.is_object()) {
        let (Some(u), Some(v)) = (u.as_f64(), v.as_f64()) else {
            let msg = "alpha_u and alpha_v must be numbers or textures";
            return Err(SceneError::new(at, msg));
        };
        for a in [u, v] {
            if !(0.0..=1.0).contains(&a) {
                return Err(SceneError::new(at, format!("alpha {a} is outside [0, 1]")));
            }
        }
        return Ok((u, (u != v).then_some(v)));
    }
    // Textured: each element a texture or a number, both kept as slots.
    let mut element = |i: usize, v: &Value| -> Result<TextureDesc, SceneError> {
        let path = format!("{at}[{i}]");
        if v.is_object() {
            return parse_texture(v, &path, TextureUse::Alpha, loader);
        }
        match v.as_f64() {
            Some(a) if (0.0..=1.0).contains(&a) => Ok(TextureDesc {
                texture: Texture::Constant(glam::Vec3::splat(a as f32)),
            }),
            Some(a) => Err(SceneError::new(
                path,
                format!("alpha {a} is outside [0, 1]"),
            )),
            None => Err(SceneError::new(
                path,
                "alpha_u and alpha_v must be numbers or textures",
            )),
        }
    };
    let (tu, tv) = (element(0, u)?, element(1, v)?);
    // A number's constant is the number itself, a texture's its mean.
    let constant = |v: &Value, t: &TextureDesc| v.as_f64().unwrap_or_else(|| t.mean_scalar());
    let (mu, mv) = (constant(u, &tu), constant(v, &tv));
    t.alpha = Some(tu);
    t.alpha_v = Some(tv);
    Ok((mu, Some(mv)))
}

/// `distribution`: `ggx` (the default) or `beckmann`.
fn distribution(obj: &Obj) -> Result<Distribution, SceneError> {
    if obj.get("distribution").is_none() {
        return Ok(Distribution::default());
    }
    let name = obj.string("distribution")?;
    Distribution::from_name(name).ok_or_else(|| {
        SceneError::new(
            obj.at("distribution"),
            format!("unknown distribution `{name}` (expected ggx or beckmann)"),
        )
    })
}

/// A plastic's `model`: `"lumis"` (the default) or `"mitsuba"`, which alone takes
/// `distribution` (default GGX) and `nonlinear` (default false).
fn plastic_model(obj: &Obj) -> Result<PlasticModel, SceneError> {
    let name = match obj.get("model") {
        None => "lumis",
        Some(_) => obj.string("model")?,
    };
    match name {
        "lumis" => {
            for key in ["distribution", "nonlinear"] {
                if obj.get(key).is_some() {
                    let msg = format!("`{key}` needs \"model\": \"mitsuba\" (lumis' coat is GGX)");
                    return Err(SceneError::new(obj.at(key), msg));
                }
            }
            Ok(PlasticModel::Lumis)
        }
        "mitsuba" => Ok(PlasticModel::Mitsuba {
            distribution: distribution(obj)?,
            nonlinear: obj.opt_bool("nonlinear")?.unwrap_or(false),
        }),
        other => Err(SceneError::new(
            obj.at("model"),
            format!("unknown plastic model `{other}` (expected lumis or mitsuba)"),
        )),
    }
}

/// Either `eta` + `k` or `reflectance` (a colour or a texture: then its mean, and `slot` is
/// set), never both or a half.
fn fresnel(
    obj: &Obj,
    loader: &mut TextureLoader,
    slot: &mut Option<TextureDesc>,
) -> Result<FresnelDesc, SceneError> {
    let (eta, k, refl) = (obj.get("eta"), obj.get("k"), obj.get("reflectance"));
    match (eta.is_some(), k.is_some(), refl.is_some()) {
        (true, true, false) => {
            let eta = obj.vec3("eta")?;
            check_components(eta, &obj.at("eta"), |x| x > 0.0, "must be positive")?;
            let k = obj.vec3("k")?;
            check_components(k, &obj.at("k"), |x| x >= 0.0, "must not be negative")?;
            let tint = match obj.get("specular") {
                Some(_) => unit_color(obj, "specular")?,
                None => DVec3::ONE,
            };
            Ok(FresnelDesc::Complex { eta, k, tint })
        }
        (false, false, true) if obj.get("specular").is_some() => Err(SceneError::new(
            obj.at("specular"),
            "`specular` tints the Fresnel of `eta` and `k`; with `reflectance`, fold it into \
             the reflectance",
        )),
        (false, false, true) => {
            *slot = texture_at(obj, "reflectance", TextureUse::Reflectance, loader)?;
            Ok(FresnelDesc::Reflectance(match slot {
                Some(t) => t.mean_color(),
                None => unit_color(obj, "reflectance")?,
            }))
        }
        (true, false, false) => Err(SceneError::new(obj.at("k"), "`eta` is given without `k`")),
        (false, true, false) => Err(SceneError::new(obj.at("eta"), "`k` is given without `eta`")),
        (false, false, false) => Err(SceneError::new(
            obj.path.clone(),
            "a conductor needs either `eta` and `k`, or `reflectance`",
        )),
        (_, _, true) => Err(SceneError::new(
            obj.at("reflectance"),
            "give either `eta` and `k`, or `reflectance`, not both",
        )),
    }
}

#[cfg(test)]
mod tests {
    use crate::scene::desc::{Distribution, FresnelDesc, MaterialDesc, PlasticModel};
    use crate::scene::parse::parse_scene_value;
    use crate::scene::tests::{base, expect_err};
    use glam::DVec3;
    use serde_json::{Value, json};

    /// The base scene with material `m` replaced by `value`.
    fn with(m: &str, value: Value) -> Value {
        let mut s = base();
        s["materials"][m] = value;
        s
    }

    #[test]
    fn parsed_with_defaults_and_sorted() {
        let d = parse_scene_value(&base()).unwrap();
        let names: Vec<_> = d.materials.iter().map(|m| m.name.as_str()).collect();
        assert_eq!(names, ["copper", "metal", "plastic", "white"]);
        let plastic = &d.materials[2];
        assert!(plastic.two_sided);
        assert_eq!(
            plastic.material,
            MaterialDesc::Plastic {
                albedo: DVec3::splat(0.5),
                alpha: 0.2,
                ior: 1.5,
                specular: DVec3::ONE,
                model: Default::default(),
            }
        );
        assert!(matches!(
            d.materials[0].material,
            MaterialDesc::Conductor {
                fresnel: FresnelDesc::Complex { .. },
                ..
            }
        ));
        let s = with(
            "white",
            json!({"type": "diffuse", "albedo": [1, 0, 0], "two_sided": false}),
        );
        assert!(!parse_scene_value(&s).unwrap().materials[3].two_sided);
    }

    #[test]
    fn albedo_and_reflectance_outside_unit_interval() {
        let s = with(
            "white",
            json!({"type": "diffuse", "albedo": [0.5, 1.2, 0.5]}),
        );
        expect_err(&s, "materials.white.albedo[1]", "outside [0, 1]");
        let s = with(
            "white",
            json!({"type": "diffuse", "albedo": [-0.1, 0.5, 0.5]}),
        );
        expect_err(&s, "materials.white.albedo[0]", "outside [0, 1]");
        let s = with(
            "metal",
            json!({"type": "conductor", "alpha": 0, "reflectance": [1, 1, 2]}),
        );
        expect_err(&s, "materials.metal.reflectance[2]", "outside [0, 1]");
        let s = with(
            "plastic",
            json!({"type": "plastic", "albedo": [0.5, 0.5, 0.5], "alpha": 0, "specular": [1.5, 1, 1]}),
        );
        expect_err(&s, "materials.plastic.specular[0]", "outside [0, 1]");
    }

    #[test]
    fn alpha_outside_unit_interval() {
        let s = with(
            "metal",
            json!({"type": "conductor", "alpha": 1.5, "reflectance": [1, 1, 1]}),
        );
        expect_err(&s, "materials.metal.alpha", "alpha 1.5 is outside [0, 1]");
        let s = with(
            "plastic",
            json!({"type": "plastic", "albedo": [0, 0, 0], "alpha": -0.1}),
        );
        expect_err(&s, "materials.plastic.alpha", "outside [0, 1]");
    }

    /// A pair with a texture: both slots textured (a number as a constant), the constants the
    /// means (a number's exactly), written back as the same pair.
    #[test]
    fn textured_anisotropic_alpha() {
        use crate::scene::desc::TextureDesc;
        let s = with(
            "metal",
            json!({"type": "conductor", "reflectance": [1, 1, 1], "distribution": "beckmann",
                "alpha": [{"type": "checkerboard", "color0": 0.05, "color1": 0.3}, 0.2]}),
        );
        let d = parse_scene_value(&s).unwrap();
        let m = d.materials.iter().find(|m| m.name == "metal").unwrap();
        let MaterialDesc::Conductor { alpha, alpha_v, .. } = m.material else {
            panic!("{m:?}")
        };
        assert!(
            (alpha - 0.175).abs() < 1e-6 && alpha_v == Some(0.2),
            "{alpha} {alpha_v:?}"
        );
        let t = &m.textures;
        assert!(matches!(
            t.alpha,
            Some(TextureDesc {
                texture: crate::textures::Texture::Checkerboard(_)
            })
        ));
        assert!(t.alpha_v.as_ref().is_some_and(|v| v.texture.is_constant()));
        let again = parse_scene_value(&d.to_json()).unwrap();
        assert_eq!(
            again.materials, d.materials,
            "written back as the same pair"
        );
        // Not for a plastic: its alpha is one number or one texture.
        let s = with(
            "plastic",
            json!({"type": "plastic", "albedo": [0, 0, 0],
                "alpha": [{"type": "checkerboard", "color0": 0.05, "color1": 0.3}, 0.2]}),
        );
        expect_err(&s, "materials.plastic.alpha", "");
    }

    #[test]
    fn microfacet_distribution_and_anisotropic_alpha() {
        let metal = |v: Value| with("metal", v);
        let d = parse_scene_value(&metal(json!({"type": "conductor", "alpha": [0.1, 0.4],
            "distribution": "beckmann", "reflectance": [1, 1, 1]})))
        .unwrap();
        let m = &d
            .materials
            .iter()
            .find(|m| m.name == "metal")
            .unwrap()
            .material;
        assert!(
            matches!(m, MaterialDesc::Conductor { alpha, alpha_v: Some(v), distribution, .. }
                if *alpha == 0.1 && *v == 0.4 && *distribution == crate::materials::Distribution::Beckmann),
            "{m:?}"
        );
        // Equal: isotropic, written back as one number.
        let d = parse_scene_value(&metal(
            json!({"type": "dielectric", "alpha": [0.3, 0.3], "ior": 1.5}),
        ))
        .unwrap();
        let m = &d.materials.iter().find(|m| m.name == "metal").unwrap();
        assert!(matches!(
            m.material,
            MaterialDesc::Dielectric { alpha_v: None, .. }
        ));
        for (bad, path, why) in [
            (
                json!([0.1, 1.5]),
                "materials.metal.alpha",
                "alpha 1.5 is outside [0, 1]",
            ),
            (
                json!([0.1]),
                "materials.metal.alpha",
                "a pair [alpha_u, alpha_v] of numbers or textures",
            ),
            (
                json!([0.1, 0.2, 0.3]),
                "materials.metal.alpha",
                "a pair [alpha_u, alpha_v]",
            ),
            (
                json!([{"type": "checkerboard", "color0": 0.05, "color1": 0.3}, 1.5]),
                "materials.metal.alpha[1]",
                "alpha 1.5 is outside [0, 1]",
            ),
            (
                json!([{"type": "checkerboard", "color0": 0.05, "color1": 0.3}, "rough"]),
                "materials.metal.alpha[1]",
                "alpha_u and alpha_v must be numbers or textures",
            ),
            (
                json!([0.1, {"type": "checkerboard", "color0": 0.05, "color1": 1.3}]),
                "materials.metal.alpha[1].color1",
                "outside [0, 1]",
            ),
        ] {
            let s = metal(json!({"type": "conductor", "alpha": bad, "reflectance": [1, 1, 1]}));
            expect_err(&s, path, why);
        }
        let s = metal(
            json!({"type": "conductor", "alpha": 0.1, "distribution": "phong",
            "reflectance": [1, 1, 1]}),
        );
        expect_err(
            &s,
            "materials.metal.distribution",
            "unknown distribution `phong`",
        );
        // A plastic in lumis' coupling has none (Mitsuba's has: `plastic_model_keys`).
        let s = metal(json!({"type": "plastic", "albedo": [0, 0, 0], "alpha": 0.1,
            "distribution": "beckmann"}));
        expect_err(
            &s,
            "materials.metal.distribution",
            "`distribution` needs \"model\": \"mitsuba\"",
        );
    }

    #[test]
    fn plastic_model_keys() {
        let plastic = |v: Value| with("plastic", v);
        let d = parse_scene_value(&plastic(
            json!({"type": "plastic", "albedo": [0.5, 0.5, 0.5],
            "alpha": 0.2, "model": "mitsuba", "distribution": "beckmann", "nonlinear": true}),
        ))
        .unwrap();
        assert!(matches!(
            d.materials[2].material,
            MaterialDesc::Plastic {
                model: PlasticModel::Mitsuba {
                    distribution: Distribution::Beckmann,
                    nonlinear: true
                },
                ..
            }
        ));
        // Mitsuba's defaults here: GGX, linear.
        let d = parse_scene_value(&plastic(
            json!({"type": "plastic", "albedo": [0.5, 0.5, 0.5], "alpha": 0.2, "model": "mitsuba"}),
        ))
        .unwrap();
        assert!(matches!(
            d.materials[2].material,
            MaterialDesc::Plastic {
                model: PlasticModel::Mitsuba {
                    distribution: Distribution::Ggx,
                    nonlinear: false
                },
                ..
            }
        ));
        let s = plastic(
            json!({"type": "plastic", "albedo": [0.5, 0.5, 0.5], "alpha": 0.2,
            "nonlinear": true}),
        );
        expect_err(
            &s,
            "materials.plastic.nonlinear",
            "needs \"model\": \"mitsuba\"",
        );
        let s = plastic(
            json!({"type": "plastic", "albedo": [0.5, 0.5, 0.5], "alpha": 0.2,
            "model": "pbrt"}),
        );
        expect_err(
            &s,
            "materials.plastic.model",
            "unknown plastic model `pbrt`",
        );
        let s = plastic(
            json!({"type": "plastic", "albedo": [0.5, 0.5, 0.5], "model": "mitsuba",
            "alpha": {"type": "checkerboard", "color0": 0.1, "color1": 0.3}}),
        );
        expect_err(
            &s,
            "materials.plastic.alpha",
            "a textured alpha needs lumis' coupling",
        );
    }

    #[test]
    fn ior_must_exceed_one() {
        let s = with(
            "plastic",
            json!({"type": "plastic", "albedo": [0, 0, 0], "alpha": 0, "ior": 1}),
        );
        expect_err(&s, "materials.plastic.ior", "greater than 1");
    }

    #[test]
    fn dielectric_defaults_and_rules() {
        let glass = |v: Value| with("white", v);
        let d = parse_scene_value(&glass(json!({"type": "dielectric"}))).unwrap();
        let m = &d.materials[3];
        assert_eq!(
            m.material,
            MaterialDesc::Dielectric {
                ior: 1.5,
                alpha: 0.0,
                alpha_v: None,
                distribution: crate::materials::Distribution::Ggx,
            }
        );
        assert!(!m.two_sided, "a dielectric's two sides are its two media");
        let ok = glass(json!({"type": "dielectric", "ior": 0.75, "alpha": 0.3}));
        assert!(parse_scene_value(&ok).is_ok(), "an ior below 1 is a bubble");
        let p = "materials.white";
        for bad in [0.0, -1.5, 1.0, 10.5, 1e30] {
            let s = glass(json!({"type": "dielectric", "ior": bad}));
            expect_err(
                &s,
                &format!("{p}.ior"),
                "must be positive, not 1, and at most 10",
            );
        }
        let s = glass(json!({"type": "dielectric", "ior": "NaN"}));
        expect_err(&s, &format!("{p}.ior"), "expected a number");
        for bad in [-0.1, 1.01] {
            let s = glass(json!({"type": "dielectric", "alpha": bad}));
            expect_err(&s, &format!("{p}.alpha"), "outside [0, 1]");
        }
        for two_sided in [true, false] {
            let s = glass(json!({"type": "dielectric", "two_sided": two_sided}));
            expect_err(&s, &format!("{p}.two_sided"), "never two-sided");
        }
        let s = glass(json!({"type": "dielectric", "albedo": [1, 1, 1]}));
        expect_err(&s, &format!("{p}.albedo"), "unknown key `albedo`");
    }

    #[test]
    fn thin_dielectric_defaults_and_rules() {
        let sheet = |v: Value| with("white", v);
        let d = parse_scene_value(&sheet(json!({"type": "thin_dielectric"}))).unwrap();
        let m = &d.materials[3];
        assert_eq!(m.material, MaterialDesc::ThinDielectric { ior: 1.5 });
        assert!(!m.two_sided, "a sheet is the same from both sides");
        for ok in [0.7, 1.0, 10.0] {
            let s = sheet(json!({"type": "thin_dielectric", "ior": ok}));
            assert!(parse_scene_value(&s).is_ok(), "ior {ok}");
        }
        let p = "materials.white";
        for bad in [0.0, -1.5, 10.5] {
            let s = sheet(json!({"type": "thin_dielectric", "ior": bad}));
            expect_err(&s, &format!("{p}.ior"), "must be positive and at most 10");
        }
        let s = sheet(json!({"type": "thin_dielectric", "two_sided": true}));
        expect_err(&s, &format!("{p}.two_sided"), "same from both sides");
        let s = sheet(json!({"type": "thin_dielectric", "alpha": 0.1}));
        expect_err(&s, &format!("{p}.alpha"), "unknown key `alpha`");
        // The description writes back what it read.
        let back = parse_scene_value(&d.to_json()).unwrap();
        assert_eq!(back.materials[3].material, m.material);
    }

    #[test]
    fn conductor_fresnel_rules() {
        let m = |v: Value| with("copper", v);
        let c = "materials.copper";
        let s = m(json!({"type": "conductor", "alpha": 0, "eta": [1, 1, 1]}));
        expect_err(&s, &format!("{c}.k"), "`eta` is given without `k`");
        let s = m(json!({"type": "conductor", "alpha": 0, "k": [1, 1, 1]}));
        expect_err(&s, &format!("{c}.eta"), "without `eta`");
        let s = m(json!({"type": "conductor", "alpha": 0}));
        expect_err(&s, c, "needs either");
        let s = m(
            json!({"type": "conductor", "alpha": 0, "eta": [1, 1, 1], "k": [1, 1, 1],
                         "reflectance": [1, 1, 1]}),
        );
        expect_err(&s, &format!("{c}.reflectance"), "not both");
        let s = m(json!({"type": "conductor", "alpha": 0, "eta": [1, 0, 1], "k": [1, 1, 1]}));
        expect_err(&s, &format!("{c}.eta[1]"), "must be positive");
        let s = m(json!({"type": "conductor", "alpha": 0, "eta": [1, 1, 1], "k": [1, 1, -1]}));
        expect_err(&s, &format!("{c}.k[2]"), "must not be negative");
    }

    #[test]
    fn structure_rules() {
        let s = with("white", json!({"type": "lambert", "albedo": [0, 0, 0]}));
        expect_err(
            &s,
            "materials.white.type",
            "unknown material type `lambert`",
        );
        let s = with("white", json!({"albedo": [0, 0, 0]}));
        expect_err(&s, "materials.white.type", "missing required key `type`");
        let s = with(
            "white",
            json!({"type": "diffuse", "albedo": [0, 0, 0], "roughness": 1}),
        );
        expect_err(&s, "materials.white.roughness", "unknown key `roughness`");
        let s = with("white", json!({"type": "diffuse"}));
        expect_err(&s, "materials.white.albedo", "missing required key");
        let s = with(
            "white",
            json!({"type": "diffuse", "albedo": [0, 0, 0], "two_sided": 0}),
        );
        expect_err(&s, "materials.white.two_sided", "expected true or false");
        let s = with("white", json!([]));
        expect_err(&s, "materials.white", "expected an object");
        let s = with("", json!({"type": "diffuse", "albedo": [0, 0, 0]}));
        expect_err(&s, "materials.\"\"", "must not be empty");
        let ok = json!({"type": "diffuse", "albedo": [0, 0, 0], "comment": "x", "name": "White"});
        assert!(parse_scene_value(&with("white", ok)).is_ok());
    }
}
