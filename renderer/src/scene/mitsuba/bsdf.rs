//! BSDFs: `diffuse`, `conductor`/`roughconductor`, `plastic`/`roughplastic`,
//! `dielectric`/`roughdielectric`, `thindielectric`, `null`, the wrappers `twosided`,
//! `normalmap`/`bumpmap` and `mask` (a material's `opacity`, [`crate::materials::mask`]), and
//! `blendbsdf` (a `mix`, but around a delta lobe, which Mitsuba 3.9.1's blend mis-weighs) onto
//! lumis' materials.
//!
//! Mitsuba's BSDFs are one-sided (black from the back) unless wrapped in `twosided`, so a
//! material is `"two_sided": false` unless it comes through a `twosided` (one with two different
//! BSDFs becomes a `"two_sided"` pair of the two, each translated as on its own); dielectrics
//! have two media and neither. Mitsuba's defaults are filled in (diffuse reflectance 0.5, conductor
//! `material` "none" = a perfect mirror, `bk7`/`polypropylene` inside and `air` outside, rough
//! α 0.1, and Beckmann where no `distribution` is named; plastics become lumis' plastic with
//! Mitsuba's coupling, `"model": "mitsuba"`), and an index pair becomes lumis' relative `ior` =
//! int_ior / ext_ior (the Fresnel terms and the (η_i/η_t)² radiance scaling depend on the ratio
//! only).

use super::presets::conductor_preset;
use super::texture::{color_param, is_texture, scalar_param};
use super::values::{Slot, constant_color, constant_scalar, ior};
use super::xml::Element;
use super::{Ctx, target};
use crate::materials::Distribution;
use crate::scene::error::SceneError;
use glam::DVec3;
use serde_json::{Value as Json, json};

/// The BSDF types lumis maps, for messages.
const SUPPORTED: &str = "diffuse, conductor, roughconductor, plastic, roughplastic, dielectric, \
                         roughdielectric, thindielectric, principled, principledthin, \
                         twosided, normalmap, bumpmap, mask, blendbsdf, null";

/// The scene format's material for BSDF element `el` (translated once, then named again),
/// or `None` for a `null` BSDF.
pub fn material(ctx: &mut Ctx, el: &Element) -> Result<Option<String>, SceneError> {
    if let Some(name) = ctx.material_names.get(&(el as *const Element)) {
        return Ok(name.clone());
    }
    // The wrappers, outermost first: `twosided`, `normalmap` or `bumpmap`, and `mask`, each at
    // most once, in any order (but a map inside a twosided).
    let mut inner = el;
    let mut inner_plugin = ctx.plugin(el)?;
    let mut two_sided = false;
    let mut normal_map: Option<super::plugin::Plugin> = None;
    let mut map_outside = false;
    let mut mask = None;
    loop {
        inner = match inner_plugin.ty {
            "mask" if mask.is_none() => {
                let Some(nested) = inner_plugin.object("bsdf")?.map(target) else {
                    return Err(inner_plugin.error("a mask needs a nested <bsdf>"));
                };
                // Mitsuba spends a bounce on each pass through a mask, lumis none (its masks are
                // tested where rays meet surfaces): the images agree only without a depth bound.
                if ctx.max_depth >= 0 {
                    return Err(inner_plugin.error(format!(
                        "a mask with max_depth {}: Mitsuba counts each pass through a mask as a \
                         bounce and lumis does not, so the images would differ (lumis renders \
                         masks at max_depth -1)",
                        ctx.max_depth
                    )));
                }
                mask = Some(inner_plugin);
                nested
            }
            "twosided" if !two_sided => {
                two_sided = true;
                let nested = inner_plugin.objects("bsdf");
                let first = match nested.as_slice() {
                    [] => return Err(inner_plugin.error("a twosided BSDF needs a nested <bsdf>")),
                    [one] => *one,
                    [a, b] if std::ptr::eq(target(a), target(b)) => *a,
                    [a, b] => {
                        inner_plugin.finish("one or two nested <bsdf>")?;
                        if let Some(map) = &normal_map {
                            let ty = map.ty;
                            return Err(map.error(format!(
                                "a {ty} around a twosided BSDF with two BSDFs is not supported \
                                 (a {ty} inside it, around either BSDF, is)"
                            )));
                        }
                        return composite(
                            ctx,
                            el,
                            &inner_plugin,
                            [a, b],
                            mask,
                            Composite::TwoSided,
                        );
                    }
                    [_, _, c, ..] => {
                        return Err(c
                            .el
                            .pos
                            .error("a twosided BSDF has at most two nested <bsdf>"));
                    }
                };
                inner_plugin.finish("one or two nested <bsdf>")?;
                target(first)
            }
            "normalmap" | "bumpmap" if normal_map.is_none() => {
                let nested = match inner_plugin.object("bsdf")? {
                    Some(b) => target(b),
                    None => {
                        let ty = inner_plugin.ty;
                        return Err(inner_plugin.error(format!("a {ty} needs a nested <bsdf>")));
                    }
                };
                // Inside a twosided (read first) is what lumis renders on the back side.
                map_outside = !two_sided;
                normal_map = Some(inner_plugin);
                nested
            }
            _ => break,
        };
        inner_plugin = ctx.plugin(inner)?;
    }
    if let (Some(map), true) = (&normal_map, two_sided && map_outside) {
        let ty = map.ty;
        return Err(map.error(format!(
            "a {ty} around a twosided BSDF is not supported: its back side is not what lumis \
             renders (a twosided around the {ty} is)"
        )));
    }
    if inner_plugin.ty == "blendbsdf" {
        // Its parts are one-sided as Mitsuba's BSDFs are, and a mix's sides are its materials'.
        if let Some(outer) = normal_map.as_ref().or(two_sided.then_some(&inner_plugin)) {
            let what = if normal_map.is_some() {
                "a normalmap or bumpmap"
            } else {
                "a twosided"
            };
            return Err(outer.error(format!(
                "{what} around a blendbsdf is not supported (around either of its BSDFs, it is)"
            )));
        }
        let nested = inner_plugin.objects("bsdf");
        let [a, b] = nested.as_slice() else {
            return Err(inner_plugin.error(format!(
                "a blendbsdf needs two nested <bsdf>, it has {}",
                nested.len()
            )));
        };
        return composite(ctx, el, &inner_plugin, [a, b], mask, Composite::Blend);
    }
    if two_sided
        && matches!(
            inner_plugin.ty,
            "dielectric"
                | "roughdielectric"
                | "thindielectric"
                | "principledthin"
                | "twosided"
                | "null"
        )
    {
        return Err(inner_plugin.error(format!(
            "a `{}` cannot be nested in twosided (Mitsuba refuses transmitting BSDFs there too)",
            inner_plugin.ty
        )));
    }
    if inner_plugin.ty == "null" {
        if let Some(map) = &normal_map {
            let ty = map.ty;
            return Err(map.error(format!("a {ty} around a null BSDF has nothing to shade")));
        }
        if let Some(mask) = &mask {
            return Err(mask.error("a mask around a null BSDF has nothing to mask"));
        }
        inner_plugin.finish("nothing")?;
        ctx.material_names.insert(el as *const Element, None);
        return Ok(None);
    }
    let (name, path) = name_material(ctx, el, inner, inner_plugin.pos());
    let mut m = bsdf(ctx, &inner_plugin, &path)?;
    let transmits = matches!(
        inner_plugin.ty,
        "dielectric" | "roughdielectric" | "thindielectric" | "principledthin"
    ) || principled_transmits(&m);
    if two_sided && transmits {
        return Err(inner_plugin.error(
            "a principled with spec_trans cannot be nested in twosided (Mitsuba refuses \
             transmitting BSDFs there too)",
        ));
    }
    if !transmits {
        m["two_sided"] = json!(two_sided);
    }
    match &normal_map {
        Some(map) if map.ty == "bumpmap" => {
            m["bump_map"] = bump_map_json(ctx, map, &format!("{path}.bump_map"))?;
        }
        Some(map) => m["normal_map"] = normal_map_json(ctx, map, &format!("{path}.normal_map"))?,
        None => {}
    }
    add_material(ctx, el, name, &path, m, mask.as_ref())
}

/// The name of the material of element `el` (whose BSDF is `inner`) and its JSON path, with `pos`
/// recorded as where it comes from.
fn name_material(
    ctx: &mut Ctx,
    el: &Element,
    inner: &Element,
    pos: &super::xml::Pos,
) -> (String, String) {
    let name = ctx.material_name(el, inner);
    // Quoted as the JSON front end quotes it in its messages (`materials."diffuse@3:5"`).
    let path = crate::scene::walk::join("materials", &name);
    ctx.origin(&path, pos);
    (name, path)
}

/// Adds `m`, material `name` at `path`, with `mask`'s opacity where there is one, as the material
/// of element `el`.
fn add_material(
    ctx: &mut Ctx,
    el: &Element,
    name: String,
    path: &str,
    mut m: Json,
    mask: Option<&super::plugin::Plugin>,
) -> Result<Option<String>, SceneError> {
    if let Some(mask) = mask {
        // Mitsuba's default opacity is ½.
        m["opacity"] = scalar_param(ctx, mask, "opacity", 0.5, &format!("{path}.opacity"))?;
        mask.finish("opacity, one nested <bsdf>")?;
    }
    ctx.materials.insert(name.clone(), m);
    ctx.material_names
        .insert(el as *const Element, Some(name.clone()));
    Ok(Some(name))
}

/// What a material made of two Mitsuba BSDFs is.
#[derive(Clone, Copy, PartialEq)]
enum Composite {
    /// A `twosided` with two different BSDFs: lumis' two-sided pair
    /// ([`crate::materials::two_sided`]), front then back.
    TwoSided,
    /// A `blendbsdf`: lumis' mix ([`crate::materials::mix`]), whose choice of the second BSDF
    /// with probability `weight` at each hit has the blend's expected image.
    Blend,
}

/// A material made of two BSDFs (`parts`, in document order; `el` the outermost element,
/// under `mask` if there is one): each translated (and named) as if on its own.
fn composite(
    ctx: &mut Ctx,
    el: &Element,
    plugin: &super::plugin::Plugin,
    parts: [&super::plugin::Prop; 2],
    mask: Option<super::plugin::Plugin>,
    kind: Composite,
) -> Result<Option<String>, SceneError> {
    let mut names = Vec::with_capacity(2);
    let mut delta = false;
    let mut positions = Vec::with_capacity(2);
    for part in parts {
        let part = target(part);
        positions.push(part.pos.clone());
        let ty = part.value("type").unwrap_or("");
        // Mitsuba's twosided refuses every BSDF with a transmission or null component; lumis'
        // mix and pair take no null lobe and no opacity on their parts (a ray meets or passes a
        // surface before its material is chosen).
        let refused = match kind {
            Composite::TwoSided => matches!(
                ty,
                "dielectric"
                    | "roughdielectric"
                    | "thindielectric"
                    | "principledthin"
                    | "null"
                    | "mask"
            ),
            Composite::Blend => matches!(ty, "null" | "mask"),
        };
        if refused {
            let msg = match kind {
                Composite::TwoSided => format!(
                    "a `{ty}` cannot be nested in twosided (Mitsuba refuses transmitting BSDFs \
                     there too)"
                ),
                Composite::Blend => format!(
                    "a `{ty}` in a blendbsdf is not supported (lumis' blend chooses one of its \
                     BSDFs where a ray has met the surface; a mask around the blendbsdf is)"
                ),
            };
            return Err(part.pos.error(msg));
        }
        let name = material(ctx, part)?.expect("only a null BSDF has no material");
        delta |= kind == Composite::Blend && has_delta_lobe(ctx, &name);
        names.push(name);
    }
    let (name, path) = name_material(ctx, el, el, plugin.pos());
    // The scene format's rules about a part are reported at that part.
    let keys = match kind {
        Composite::TwoSided => ["front".to_owned(), "back".to_owned()],
        Composite::Blend => ["materials[0]".to_owned(), "materials[1]".to_owned()],
    };
    for (key, pos) in keys.iter().zip(&positions) {
        ctx.origin(&format!("{path}.{key}"), pos);
    }
    let m = match kind {
        Composite::TwoSided => json!({"type": "two_sided", "front": names[0], "back": names[1]}),
        Composite::Blend => {
            // 0 is the first BSDF, 1 the second. Mitsuba documents a default of ½ but 3.9.1
            // refuses a blend without one.
            if !plugin.has("weight") {
                return Err(plugin
                    .error("a blendbsdf needs a `weight` (Mitsuba 3.9.1 refuses one without)"));
            }
            let weight = scalar_param(ctx, plugin, "weight", 0.5, &format!("{path}.weight"))?;
            plugin.finish("weight, two nested <bsdf>")?;
            let mut mix = json!({"type": "mix", "materials": names, "weight": weight});
            // Mitsuba's blend weighs a delta lobe's sample against the other part, which lumis'
            // mix does only as model mitsuba (docs/mitsuba.md); elsewhere the two agree.
            if delta {
                mix["model"] = json!("mitsuba");
            }
            mix
        }
    };
    add_material(ctx, el, name, &path, m, mask.as_ref())
}

/// Whether imported material `name` has a delta lobe (a smooth conductor, plastic coat or
/// dielectric, a thin dielectric), itself or in a part: what Mitsuba's `blendbsdf` weighs
/// against the other part.
fn has_delta_lobe(ctx: &Ctx, name: &str) -> bool {
    let Some(m) = ctx.materials.get(name) else {
        return false;
    };
    let part = |key: &str| m[key].as_str().is_some_and(|p| has_delta_lobe(ctx, p));
    match m["type"].as_str() {
        Some("thin_dielectric") => true,
        Some("conductor" | "plastic" | "dielectric") => m["alpha"].as_f64() == Some(0.0),
        Some("two_sided") => part("front") || part("back"),
        Some("mix") => m["materials"].as_array().is_some_and(|ps| {
            ps.iter()
                .any(|p| p.as_str().is_some_and(|p| has_delta_lobe(ctx, p)))
        }),
        _ => false,
    }
}

/// A `normalmap`'s parameters as the material's `normal_map` object (its nested BSDF is read
/// by the caller).
fn normal_map_json(
    ctx: &mut Ctx,
    map: &super::plugin::Plugin,
    path: &str,
) -> Result<Json, SceneError> {
    if !map.has("normalmap") {
        return Err(map.error("a normalmap needs its `normalmap` texture"));
    }
    let texture = color_param(
        ctx,
        map,
        "normalmap",
        0.5,
        Slot::Reflectance,
        &format!("{path}.texture"),
    )?;
    let flip = map.bool("flip_invalid_normals", true)?;
    let shadowing = map.bool("use_shadowing_function", true)?;
    map.finish("normalmap, flip_invalid_normals, use_shadowing_function, one nested <bsdf>")?;
    Ok(json!({"texture": texture, "flip_invalid_normals": flip, "shadowing": shadowing}))
}

/// A `bumpmap`'s parameters as the material's `bump_map` object: its one nested texture
/// (whatever its name, as Mitsuba takes it) a bitmap of heights, `scale` (default 1) and the
/// flags a normalmap has (its nested BSDF is read by the caller).
fn bump_map_json(
    ctx: &mut Ctx,
    map: &super::plugin::Plugin,
    path: &str,
) -> Result<Json, SceneError> {
    let textures = map.objects("texture");
    let prop = match textures.as_slice() {
        [one] => *one,
        _ => return Err(map.error("a bumpmap needs exactly one nested <texture>")),
    };
    let texture = super::texture::height_texture(ctx, prop, &format!("{path}.texture"))?;
    let scale = map.float("scale", 1.0)?;
    let flip = map.bool("flip_invalid_normals", true)?;
    let shadowing = map.bool("use_shadowing_function", true)?;
    map.finish(
        "one <texture>, scale, flip_invalid_normals, use_shadowing_function, one nested <bsdf>",
    )?;
    Ok(
        json!({"texture": texture, "scale": scale, "flip_invalid_normals": flip, "shadowing": shadowing}),
    )
}

/// One non-wrapper BSDF as a material object.
fn bsdf(ctx: &mut Ctx, b: &super::plugin::Plugin, path: &str) -> Result<Json, SceneError> {
    let at = |k: &str| format!("{path}.{k}");
    let m = match b.ty {
        "diffuse" => {
            let albedo = color_param(ctx, b, "reflectance", 0.5, Slot::Reflectance, &at("albedo"))?;
            b.finish("reflectance")?;
            json!({"type": "diffuse", "albedo": albedo})
        }
        "conductor" | "roughconductor" => {
            let (alpha, distribution) = match b.ty {
                "conductor" => (json!(0.0), Distribution::Ggx),
                _ => rough_alpha(ctx, b, &at("alpha"), true)?,
            };
            let mut m = json!({"type": "conductor", "alpha": alpha});
            distribution_key(&mut m, distribution);
            conductor_fresnel(ctx, b, path, &mut m)?;
            b.finish(
                "material, eta, k, specular_reflectance, and for roughconductor distribution \
                 (beckmann or ggx), alpha or alpha_u and alpha_v; sample_visible is ignored",
            )?;
            m
        }
        "plastic" | "roughplastic" => {
            let albedo = color_param(
                ctx,
                b,
                "diffuse_reflectance",
                0.5,
                Slot::Reflectance,
                &at("albedo"),
            )?;
            let specular = match b.get("specular_reflectance") {
                None => json!([1.0, 1.0, 1.0]),
                Some(p) => match constant_color(p, Slot::Reflectance, &mut ctx.warnings)? {
                    Some(c) => {
                        ctx.origin(&at("specular"), p.pos());
                        json!([c.x, c.y, c.z])
                    }
                    None => {
                        return Err(p.error(
                            "a textured specular_reflectance is not supported (lumis' plastic \
                             takes a constant specular tint)",
                        ));
                    }
                },
            };
            let eta = index_ratio(ctx, b, "polypropylene", &at("ior"))?;
            let nonlinear = b.bool("nonlinear", false)?;
            let (alpha, distribution) = match b.ty {
                "plastic" => (json!(0.0), Distribution::Ggx),
                _ => rough_alpha(ctx, b, &at("alpha"), false)?,
            };
            b.finish(
                "diffuse_reflectance, specular_reflectance, int_ior, ext_ior, nonlinear, and \
                 for roughplastic distribution (beckmann or ggx) and alpha; sample_visible is \
                 ignored",
            )?;
            // Mitsuba's own coupling, exactly (`materials/plastic_mitsuba.rs`).
            json!({
                "type": "plastic", "model": "mitsuba", "albedo": albedo, "alpha": alpha,
                "ior": eta, "specular": specular, "distribution": distribution.name(),
                "nonlinear": nonlinear,
            })
        }
        "principled" => principled(ctx, b, path)?,
        "principledthin" => principled_thin(ctx, b, path)?,
        "dielectric" | "roughdielectric" | "thindielectric" => {
            let eta = index_ratio(ctx, b, "bk7", &at("ior"))?;
            for key in ["specular_reflectance", "specular_transmittance"] {
                if let Some(p) = b.get(key) {
                    let c = constant_color(p, Slot::Reflectance, &mut ctx.warnings)?;
                    if c != Some(DVec3::ONE) {
                        return Err(p.error(format!(
                            "{key} other than 1 is not supported (lumis' dielectric is exactly \
                             the Fresnel boundary)"
                        )));
                    }
                }
            }
            if b.ty == "thindielectric" {
                b.finish("int_ior, ext_ior, specular_reflectance and specular_transmittance 1")?;
                return Ok(json!({"type": "thin_dielectric", "ior": eta}));
            }
            let (alpha, distribution) = match b.ty {
                "dielectric" => (json!(0.0), Distribution::Ggx),
                _ => rough_alpha(ctx, b, &at("alpha"), true)?,
            };
            b.finish(
                "int_ior, ext_ior, specular_reflectance and specular_transmittance 1, and for \
                 roughdielectric distribution (beckmann or ggx) and alpha; sample_visible is \
                 ignored",
            )?;
            let mut m = json!({"type": "dielectric", "ior": eta, "alpha": alpha});
            distribution_key(&mut m, distribution);
            m
        }
        other => {
            let why = match other {
                "normalmap" | "bumpmap" => {
                    " here (a material has one normalmap or bumpmap, around its BSDF or its \
                     twosided)"
                }
                "mask" => " here (a material has one mask)",
                _ => "",
            };
            return Err(b.error(format!(
                "BSDF type `{other}` is not supported{why}; lumis maps {SUPPORTED}"
            )));
        }
    };
    Ok(m)
}

/// The relative index of refraction int_ior / ext_ior (lumis' outside is index 1).
fn index_ratio(
    ctx: &mut Ctx,
    b: &super::plugin::Plugin,
    int_default: &str,
    json_path: &str,
) -> Result<f64, SceneError> {
    let int = ior(b, "int_ior", int_default)?;
    let ext = ior(b, "ext_ior", "air")?;
    if !(int > 0.0 && ext > 0.0 && int != ext) {
        return Err(b.error(format!(
            "int_ior {int} and ext_ior {ext} must be positive and differ (as Mitsuba requires)"
        )));
    }
    let pos = b
        .get("int_ior")
        .or(b.get("ext_ior"))
        .map_or(b.pos(), |p| p.pos());
    ctx.origin(json_path, pos);
    Ok(int / ext)
}

/// `distribution` into a material object, unless it is the scene format's default (GGX).
fn distribution_key(m: &mut Json, distribution: Distribution) {
    if distribution != Distribution::default() {
        m["distribution"] = json!(distribution.name());
    }
}

/// A rough model's α and distribution: `distribution` beckmann (Mitsuba's default) or ggx,
/// Mitsuba's `principled`: its keys are the scene format's (`scene/parse_principled.rs`), which
/// applies Mitsuba's defaults and rules; a parameter it does not give is left out. Mitsuba
/// refuses both `eta` and `specular`; the scene format says so at the same place.
fn principled(ctx: &mut Ctx, b: &super::plugin::Plugin, path: &str) -> Result<Json, SceneError> {
    let scalars = crate::materials::principled::PrincipledParam::ALL.map(|k| k.name());
    let numbers = ["eta", "specular"]
        .into_iter()
        .chain(crate::scene::parse_principled::RATE_KEYS);
    let m = principled_keys(ctx, b, path, "principled", &scalars, numbers)?;
    b.finish(
        "base_color, roughness, anisotropic, metallic, spec_trans, spec_tint, sheen, sheen_tint, \
         flatness, clearcoat, clearcoat_gloss, eta or specular, and the three sampling rates",
    )?;
    Ok(m)
}

/// Mitsuba's `principledthin`: its keys are the scene format's `principled_thin`
/// (`scene/parse_principled_thin.rs`), which applies Mitsuba's defaults; a parameter it does not
/// give is left out. `eta` may be a texture there, as in Mitsuba.
fn principled_thin(
    ctx: &mut Ctx,
    b: &super::plugin::Plugin,
    path: &str,
) -> Result<Json, SceneError> {
    let scalars = crate::materials::principled_thin::ThinParam::ALL.map(|k| k.name());
    let numbers = crate::materials::principled_thin::ThinRates::KEYS;
    let m = principled_keys(ctx, b, path, "principled_thin", &scalars, numbers)?;
    b.finish(
        "base_color, roughness, anisotropic, spec_trans, spec_tint, sheen, sheen_tint, flatness, \
         diff_trans, eta and the four sampling rates",
    )?;
    Ok(m)
}

/// A principled kind's material object (`ty`) with the keys that `b` gives, copied: its
/// `base_color` (a colour or a texture), its `scalars` (each a number or a texture read as a
/// scalar) and its `numbers` (plain floats).
fn principled_keys<'a>(
    ctx: &mut Ctx,
    b: &super::plugin::Plugin,
    path: &str,
    ty: &str,
    scalars: &[&str],
    numbers: impl IntoIterator<Item = &'a str>,
) -> Result<Json, SceneError> {
    let at = |k: &str| format!("{path}.{k}");
    let mut m = json!({ "type": ty });
    if b.has("base_color") {
        m["base_color"] = color_param(
            ctx,
            b,
            "base_color",
            0.5,
            Slot::Reflectance,
            &at("base_color"),
        )?;
    }
    for &key in scalars {
        if b.has(key) {
            m[key] = scalar_param(ctx, b, key, 0.0, &at(key))?;
        }
    }
    for key in numbers {
        if let Some(p) = b.get(key) {
            ctx.origin(&at(key), p.pos());
            m[key] = json!(b.float(key, 0.0)?);
        }
    }
    Ok(m)
}

/// Whether an imported principled has specular transmission (Mitsuba's flag: `spec_trans` a
/// texture, or a number other than 0).
fn principled_transmits(m: &Json) -> bool {
    m["type"] == "principled"
        && match &m["spec_trans"] {
            Json::Null => false,
            Json::Number(x) => x.as_f64() != Some(0.0),
            _ => true,
        }
}

/// `alpha` (default 0.1) or `alpha_u` and `alpha_v` (the pair [α_u, α_v] where they differ or
/// either is a texture); `textured` says whether lumis takes a texture or an anisotropic pair
/// there (conductor and dielectric, not plastic).
fn rough_alpha(
    ctx: &mut Ctx,
    b: &super::plugin::Plugin,
    json_path: &str,
    textured: bool,
) -> Result<(Json, Distribution), SceneError> {
    let distribution = match b.string("distribution")? {
        None => Distribution::Beckmann,
        Some((d, p)) => Distribution::from_name(&d.to_ascii_lowercase()).ok_or_else(|| {
            p.error(format!(
                "unknown distribution `{d}` (Mitsuba's are beckmann and ggx)"
            ))
        })?,
    };
    b.ignore(&["sample_visible"]);
    let key = match (b.has("alpha"), b.has("alpha_u"), b.has("alpha_v")) {
        (_, false, false) => "alpha",
        (false, true, true) => {
            let value = |k: &str| b.get(k).map(constant_scalar).transpose();
            match (value("alpha_u")?.flatten(), value("alpha_v")?.flatten()) {
                (Some(u), Some(v)) if u == v => "alpha_u",
                // Anisotropic: α_u along the surface's ∂p/∂u, as in Mitsuba.
                (Some(u), Some(v)) if textured => {
                    if let Some(p) = b.get("alpha_u") {
                        ctx.origin(json_path, p.pos());
                    }
                    return Ok((json!([u, v]), distribution));
                }
                (Some(_), Some(_)) => {
                    return Err(b.error(format!(
                        "anisotropic alpha_u, alpha_v are not supported in {} (Mitsuba refuses \
                         them there too)",
                        b.ty
                    )));
                }
                // A texture in the pair: [α_u, α_v], each a number or a texture (the scene
                // format's textured pair).
                _ if textured => {
                    let u = scalar_param(ctx, b, "alpha_u", 0.1, &format!("{json_path}[0]"))?;
                    let v = scalar_param(ctx, b, "alpha_v", 0.1, &format!("{json_path}[1]"))?;
                    if let Some(p) = b.get("alpha_u") {
                        ctx.origin(json_path, p.pos());
                    }
                    return Ok((json!([u, v]), distribution));
                }
                _ => {
                    return Err(b.error(format!(
                        "textured alpha_u and alpha_v are not supported in {} (Mitsuba's has \
                         no textured roughness)",
                        b.ty
                    )));
                }
            }
        }
        _ => {
            return Err(b.error("give either alpha or both alpha_u and alpha_v"));
        }
    };
    if !textured && b.get(key).is_some_and(is_texture) {
        return Err(b.get(key).map_or_else(
            || b.error("alpha"),
            |p| p.error(format!("a textured alpha is not supported in {}", b.ty)),
        ));
    }
    Ok((scalar_param(ctx, b, key, 0.1, json_path)?, distribution))
}

/// A conductor's Fresnel term into `m`: a named preset, `eta` + `k` (a constant
/// specular_reflectance other than 1 their `specular` tint), or with neither (or eta = 0:
/// Fresnel 1 everywhere) a `reflectance` = specular_reflectance.
fn conductor_fresnel(
    ctx: &mut Ctx,
    b: &super::plugin::Plugin,
    path: &str,
    m: &mut Json,
) -> Result<(), SceneError> {
    let material = b.string("material")?;
    let named = material.filter(|(n, _)| *n != "none");
    if named.is_some() && (b.has("eta") || b.has("k")) {
        return Err(b.error("give either `material` or `eta` and `k`, not both"));
    }
    let constant = |ctx: &mut Ctx, key: &str, default: f64| -> Result<DVec3, SceneError> {
        match b.get(key) {
            None => Ok(DVec3::splat(default)),
            Some(p) => {
                ctx.origin(&format!("{path}.{key}"), p.pos());
                constant_color(p, Slot::Unbounded, &mut ctx.warnings)?.ok_or_else(|| {
                    p.error(format!(
                        "a textured `{key}` is not supported (lumis' eta and k are constants)"
                    ))
                })
            }
        }
    };
    let (eta, k) = match named {
        Some((name, p)) => {
            ctx.origin(&format!("{path}.eta"), p.pos());
            ctx.origin(&format!("{path}.k"), p.pos());
            conductor_preset(name).ok_or_else(|| {
                p.error(format!(
                    "unknown conductor material `{name}` (Mitsuba's presets: {})",
                    super::presets::names().join(", ")
                ))
            })?
        }
        None => (constant(ctx, "eta", 0.0)?, constant(ctx, "k", 1.0)?),
    };
    let refl = b.get("specular_reflectance");
    if eta == DVec3::ZERO {
        // |(cos θ − i k)/(cos θ + i k)|² = 1: a perfect mirror times specular_reflectance.
        m["reflectance"] = color_param(
            ctx,
            b,
            "specular_reflectance",
            1.0,
            Slot::Reflectance,
            &format!("{path}.reflectance"),
        )?;
        return Ok(());
    }
    if eta.min_element() <= 0.0 {
        return Err(b.get("eta").map_or_else(
            || b.error("eta"),
            |p| p.error("eta must be positive in every channel (or 0 in all: a perfect mirror)"),
        ));
    }
    if let Some(p) = refl {
        // A factor on the complex Fresnel: lumis' conductor `specular`.
        match constant_color(p, Slot::Reflectance, &mut ctx.warnings)? {
            Some(c) if c == DVec3::ONE => {}
            Some(c) => {
                ctx.origin(&format!("{path}.specular"), p.pos());
                m["specular"] = json!(c.to_array());
            }
            None => {
                return Err(p.error(
                    "a textured specular_reflectance together with eta and k is not supported \
                     (lumis tints a metal's Fresnel by a constant; a texture replaces a \
                     Fresnel of 1)",
                ));
            }
        }
    }
    m["eta"] = json!(eta.to_array());
    m["k"] = json!(k.to_array());
    Ok(())
}
