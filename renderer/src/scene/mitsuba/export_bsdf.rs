//! Export of materials and textures: each material a shape uses becomes one `<bsdf>` declared
//! with the material's name as its `id` (the importer names a material by its id), wrapped in
//! `twosided` (id on the wrapper) unless it is one-sided or a dielectric, in `normalmap` or
//! `bumpmap` (inside the twosided) where it has one, and in `mask` (outermost) where it has an
//! opacity; a two-sided pair is a `twosided` and a mix a `blendbsdf` (its weight read as a scalar)
//! of `<ref>`s to its two materials; the inverse of
//! [`super::bsdf`] and [`super::texture`]: lumis' `ior` becomes `int_ior` with `ext_ior` 1,
//! a reflectance conductor Mitsuba's `material="none"` (Fresnel 1) times
//! `specular_reflectance`, α > 0 or a textured α the rough variant with `distribution="ggx"`,
//! and a checkerboard read as a scalar (α) has its colours swapped (Mitsuba's `eval_1`).

use super::export::{Xml, file_name, num, num32};
use crate::scene::desc::{
    Distribution, FresnelDesc, MaterialDesc, NamedMaterial, PlasticModel, TextureDesc,
};
use crate::scene::error::SceneError;
use crate::scene::walk::join;
use crate::textures::{Channel, Texture, UvTransform};
use glam::{DVec3, Vec2, Vec3};
use std::path::Path;

/// The materials shapes refer to, in order of first use.
#[derive(Default)]
pub(crate) struct Bsdfs {
    used: Vec<usize>,
}

impl Bsdfs {
    /// Marks material `index` as used; returns the id to `<ref>`.
    pub fn use_material(&mut self, materials: &[NamedMaterial], index: usize) -> String {
        if !self.used.contains(&index) {
            // A mix's or pair's parts first: Mitsuba resolves a `<ref>` to an id declared
            // before it.
            for p in materials[index].parts().into_iter().flatten() {
                self.use_material(materials, p);
            }
            self.used.push(index);
        }
        materials[index].name.clone()
    }

    /// The declarations of the used materials, at nesting `depth`, in a scene of `max_depth`.
    pub fn xml(
        &self,
        materials: &[NamedMaterial],
        folder: &Path,
        depth: usize,
        max_depth: i32,
    ) -> Result<String, SceneError> {
        let mut x = Xml {
            depth,
            ..Xml::default()
        };
        for &i in &self.used {
            let m = &materials[i];
            // Mitsuba spends a bounce on each pass through a mask (`crate::materials::mask`).
            if m.opacity.is_some() && max_depth >= 0 {
                return Err(SceneError::new(
                    format!("{}.opacity", path_of(&m.name)),
                    format!(
                        "an opacity cannot be exported with max_depth {max_depth}: Mitsuba \
                         counts each pass through its mask as a bounce, lumis does not, so the \
                         image would change (masks export at max_depth -1)"
                    ),
                ));
            }
            material(&mut x, m, materials, folder)?;
        }
        Ok(x.out)
    }
}

/// JSON path of material `name`.
fn path_of(name: &str) -> String {
    join("materials", name)
}

/// Whether the material reads texture coordinates (a texture of them in a slot, its
/// opacity, its normal or bump map or a mix's weight, or one of its parts does); `all` are the scene's
/// materials, which a mix or pair names (acyclic: the parser checked).
pub(crate) fn is_textured(m: &NamedMaterial, all: &[NamedMaterial]) -> bool {
    if m.parts()
        .is_some_and(|p| p.iter().any(|&i| is_textured(&all[i], all)))
    {
        return true;
    }
    let t = &m.textures;
    let map = m.normal_map.as_ref().map(|n| &n.texture);
    let weight = m.mix.as_ref().and_then(|x| x.weight_texture.as_ref());
    [
        weight,
        t.albedo.as_ref(),
        t.reflectance.as_ref(),
        t.alpha.as_ref(),
        m.opacity.as_ref(),
        map,
    ]
    .iter()
    .any(|s| s.is_some_and(|d| d.texture.reads_uv()))
}

/// The `<bsdf>` elements of one material, outermost first: the material's name is the first's
/// `id`, and each is closed at the end.
struct Nest<'a> {
    id: &'a str,
    open: usize,
}

impl Nest<'_> {
    fn open(&mut self, x: &mut Xml, ty: &str) {
        if self.open == 0 {
            x.open("bsdf", &[("type", ty), ("id", self.id)]);
        } else {
            x.open("bsdf", &[("type", ty)]);
        }
        self.open += 1;
    }

    fn close(self, x: &mut Xml) {
        for _ in 0..self.open {
            x.close("bsdf");
        }
    }
}

/// One material as a declared `<bsdf>`; `all` are the scene's materials, which a pair names.
fn material(
    x: &mut Xml,
    m: &NamedMaterial,
    all: &[NamedMaterial],
    folder: &Path,
) -> Result<(), SceneError> {
    let path = path_of(&m.name);
    if let MaterialDesc::GltfPbr(_) = m.material {
        return Err(no_gltf_pbr(path));
    }
    // The wrappers, outermost first: mask, then twosided around normalmap, the nesting whose
    // back side lumis renders.
    let mut nest = Nest {
        id: &m.name,
        open: 0,
    };
    if let Some(opacity) = &m.opacity {
        nest.open(x, "mask");
        texture_xml(
            x,
            "opacity",
            opacity,
            true,
            folder,
            &format!("{path}.opacity"),
        )?;
    }
    // A mix or pair names its two materials, declared before it (`Bsdfs::use_material`).
    if let Some(parts) = m.parts() {
        match &m.mix {
            // Mitsuba's blend has lumis' mix's expected image (docs/scene-format.md), but for
            // a delta lobe, which it weighs against the other part as only a mix of model
            // mitsuba does (docs/mitsuba.md).
            Some(mix) => {
                if let Some(&p) = parts
                    .iter()
                    .find(|&&p| !mix.mitsuba && has_delta_lobe(&all[p], all))
                {
                    return Err(SceneError::new(
                        path,
                        format!(
                            "a mix of `{}`, which has a delta lobe, cannot be exported: Mitsuba \
                             3.9.1's blendbsdf weighs a delta lobe's sample against its \
                             partner's density, so its image would not be this mix's (a mix \
                             of `\"model\": \"mitsuba\"` exports)",
                            all[p].name
                        ),
                    ));
                }
                nest.open(x, "blendbsdf");
                let weight = match &mix.weight_texture {
                    Some(t) => t.clone(),
                    None => TextureDesc {
                        texture: Texture::Constant(Vec3::splat(mix.weight as f32)),
                    },
                };
                texture_xml(
                    x,
                    "weight",
                    &weight,
                    true,
                    folder,
                    &format!("{path}.weight"),
                )?;
            }
            None => nest.open(x, "twosided"),
        }
        for p in parts {
            x.leaf("ref", &[("id", &all[p].name)]);
        }
        nest.close(x);
        return Ok(());
    }
    if m.two_sided && !m.material.transmits() {
        nest.open(x, "twosided");
    }
    if let Some(map) = &m.normal_map {
        // A bump map is Mitsuba's bumpmap, its heights the one nested texture.
        let (plugin, key, texture) = match map.height_scale {
            None => ("normalmap", "normal_map", "normalmap"),
            Some(_) => ("bumpmap", "bump_map", "height"),
        };
        nest.open(x, plugin);
        texture_xml(
            x,
            texture,
            &map.texture,
            false,
            folder,
            &format!("{path}.{key}.texture"),
        )?;
        if let Some(scale) = map.height_scale {
            x.leaf("float", &[("name", "scale"), ("value", &num(scale))]);
        }
        for (name, value) in [
            ("flip_invalid_normals", map.flip_invalid_normals),
            ("use_shadowing_function", map.shadowing),
        ] {
            if !value {
                x.leaf("boolean", &[("name", name), ("value", "false")]);
            }
        }
    }
    let ty = bsdf_type(m);
    nest.open(x, ty);
    let t = &m.textures;
    let tex = |slot: &Option<TextureDesc>| slot.clone().filter(|d| !d.texture.is_constant());
    match &m.material {
        MaterialDesc::Diffuse { albedo } => {
            color_slot(x, "reflectance", *albedo, tex(&t.albedo), folder, &path)?;
        }
        MaterialDesc::Conductor {
            alpha,
            alpha_v,
            distribution,
            fresnel,
        } => {
            match fresnel {
                FresnelDesc::Complex { eta, k, tint } => {
                    color_value(x, "eta", *eta);
                    color_value(x, "k", *k);
                    if *tint != DVec3::ONE {
                        color_value(x, "specular_reflectance", *tint);
                    }
                }
                FresnelDesc::Reflectance(r) => {
                    x.leaf("string", &[("name", "material"), ("value", "none")]);
                    color_slot(
                        x,
                        "specular_reflectance",
                        *r,
                        tex(&t.reflectance),
                        folder,
                        &format!("{path}.reflectance"),
                    )?;
                }
            }
            let a = Alpha(*alpha, *alpha_v);
            rough(
                x,
                ty,
                *distribution,
                a,
                [tex(&t.alpha), tex(&t.alpha_v)],
                folder,
                &path,
            )?;
        }
        MaterialDesc::Plastic {
            albedo,
            alpha,
            ior,
            specular,
            model,
        } => {
            if tex(&t.alpha).is_some() {
                return Err(SceneError::new(
                    format!("{path}.alpha"),
                    "a plastic's textured alpha cannot be exported: Mitsuba's roughplastic \
                     takes a constant alpha",
                ));
            }
            color_slot(
                x,
                "diffuse_reflectance",
                *albedo,
                tex(&t.albedo),
                folder,
                &path,
            )?;
            color_value(x, "specular_reflectance", *specular);
            index(x, *ior);
            // lumis' own coupling has no Mitsuba equivalent: Mitsuba's GGX plastic is the
            // nearest (the image differs slightly, see docs/mitsuba.md).
            let distribution = match model {
                PlasticModel::Lumis => Distribution::Ggx,
                PlasticModel::Mitsuba {
                    distribution,
                    nonlinear,
                } => {
                    if *nonlinear {
                        x.leaf("boolean", &[("name", "nonlinear"), ("value", "true")]);
                    }
                    *distribution
                }
            };
            rough(
                x,
                ty,
                distribution,
                Alpha(*alpha, None),
                [None, None],
                folder,
                &path,
            )?;
        }
        MaterialDesc::Dielectric {
            ior,
            alpha,
            alpha_v,
            distribution,
        } => {
            index(x, *ior);
            let a = Alpha(*alpha, *alpha_v);
            rough(
                x,
                ty,
                *distribution,
                a,
                [tex(&t.alpha), tex(&t.alpha_v)],
                folder,
                &path,
            )?;
        }
        MaterialDesc::ThinDielectric { ior } => index(x, *ior),
        // Mitsuba's own keys; `eta` as lumis holds it (from `specular` or not).
        MaterialDesc::Principled(p) => {
            color_slot(x, "base_color", p.base_color, tex(&t.albedo), folder, &path)?;
            let params = crate::materials::principled::PrincipledParam::ALL;
            for ((k, v), slot) in params.iter().zip(p.scalars).zip(&t.principled) {
                let key = k.name();
                match tex(slot) {
                    Some(tt) => texture_xml(x, key, &tt, true, folder, &format!("{path}.{key}"))?,
                    None => x.leaf("float", &[("name", key), ("value", &num(v))]),
                }
            }
            x.leaf("float", &[("name", "eta"), ("value", &num(p.eta))]);
            let keys = crate::scene::parse_principled::RATE_KEYS;
            for (key, rate) in keys.iter().zip(p.rates) {
                x.leaf("float", &[("name", key), ("value", &num(rate))]);
            }
        }
        // Mitsuba's own keys, `diff_trans` in its [0, 2] and a texturable `eta`.
        MaterialDesc::PrincipledThin(p) => {
            color_slot(x, "base_color", p.base_color, tex(&t.albedo), folder, &path)?;
            let params = crate::materials::principled_thin::ThinParam::ALL;
            for ((k, v), slot) in params.iter().zip(p.scalars).zip(&t.principled) {
                let key = k.name();
                match tex(slot) {
                    Some(tt) => texture_xml(x, key, &tt, true, folder, &format!("{path}.{key}"))?,
                    None => x.leaf("float", &[("name", key), ("value", &num(v))]),
                }
            }
            let keys = crate::materials::principled_thin::ThinRates::KEYS;
            for (key, rate) in keys.iter().zip(p.rates) {
                x.leaf("float", &[("name", key), ("value", &num(rate))]);
            }
        }
        // Refused above.
        MaterialDesc::GltfPbr(_) => return Err(no_gltf_pbr(path)),
    }
    nest.close(x);
    Ok(())
}

/// The refusal of a `gltf_pbr` material: Mitsuba 3 has no BSDF of glTF's model, and the nearest
/// ones (its `principled`, a plastic and conductor blend) render differently.
fn no_gltf_pbr(path: String) -> SceneError {
    SceneError::new(
        path,
        "a gltf_pbr material cannot be exported: Mitsuba 3.9.1 has no BSDF of glTF's \
         metallic-roughness model (its principled is Burley's Disney BSDF, another model)",
    )
}

/// Whether `m` has a delta lobe (a smooth conductor, plastic coat or dielectric with no textured
/// α, a thin dielectric), itself or in a part; `all` are the scene's materials.
fn has_delta_lobe(m: &NamedMaterial, all: &[NamedMaterial]) -> bool {
    if let Some(parts) = m.parts() {
        return parts.iter().any(|&p| has_delta_lobe(&all[p], all));
    }
    let smooth = |alpha: f64| alpha == 0.0 && m.textures.alpha.is_none();
    match &m.material {
        MaterialDesc::Diffuse { .. }
        | MaterialDesc::Principled(_)
        | MaterialDesc::PrincipledThin(_)
        | MaterialDesc::GltfPbr(_) => false,
        MaterialDesc::ThinDielectric { .. } => true,
        MaterialDesc::Conductor { alpha, .. }
        | MaterialDesc::Plastic { alpha, .. }
        | MaterialDesc::Dielectric { alpha, .. } => smooth(*alpha),
    }
}

/// The Mitsuba plugin of a material with a BSDF of its own (no mix, no pair).
fn bsdf_type(m: &NamedMaterial) -> &'static str {
    let textured = m
        .textures
        .alpha
        .as_ref()
        .is_some_and(|t| !t.texture.is_constant());
    let rough = |alpha: f64| alpha > 0.0 || textured;
    match &m.material {
        MaterialDesc::Diffuse { .. } => "diffuse",
        MaterialDesc::Conductor { alpha, .. } if rough(*alpha) => "roughconductor",
        MaterialDesc::Conductor { .. } => "conductor",
        MaterialDesc::Plastic { alpha, .. } if rough(*alpha) => "roughplastic",
        MaterialDesc::Plastic { .. } => "plastic",
        MaterialDesc::Dielectric { alpha, .. } if rough(*alpha) => "roughdielectric",
        MaterialDesc::Dielectric { .. } => "dielectric",
        MaterialDesc::ThinDielectric { .. } => "thindielectric",
        MaterialDesc::Principled(_) => "principled",
        MaterialDesc::PrincipledThin(_) => "principledthin",
        // Refused before any plugin is written (`no_gltf_pbr`).
        MaterialDesc::GltfPbr(_) => "gltf_pbr",
    }
}

/// lumis' relative index as `int_ior` inside an explicit `ext_ior` of 1 (Mitsuba's default
/// outside is air, 1.000277); the importer divides them back exactly.
fn index(x: &mut Xml, ior: f64) {
    x.leaf("float", &[("name", "int_ior"), ("value", &num(ior))]);
    x.leaf("float", &[("name", "ext_ior"), ("value", "1.0")]);
}

/// A rough model's GGX α (constant or texture); nothing for a smooth one.
/// A constant roughness: α, or α_u with an α_v.
struct Alpha(f64, Option<f64>);

fn rough(
    x: &mut Xml,
    ty: &str,
    distribution: Distribution,
    alpha: Alpha,
    texture: [Option<TextureDesc>; 2],
    folder: &Path,
    path: &str,
) -> Result<(), SceneError> {
    if !ty.starts_with("rough") {
        return Ok(());
    }
    x.leaf(
        "string",
        &[("name", "distribution"), ("value", distribution.name())],
    );
    let [tu, tv] = texture;
    match alpha {
        Alpha(a, None) => match tu {
            Some(t) => texture_xml(x, "alpha", &t, true, folder, &format!("{path}.alpha")),
            None => {
                x.leaf("float", &[("name", "alpha"), ("value", &num(a))]);
                Ok(())
            }
        },
        // A pair: each element its texture, or its number.
        Alpha(u, Some(v)) => {
            for (i, (key, t, c)) in [("alpha_u", tu, u), ("alpha_v", tv, v)]
                .into_iter()
                .enumerate()
            {
                match t {
                    Some(t) => {
                        texture_xml(x, key, &t, true, folder, &format!("{path}.alpha[{i}]"))?
                    }
                    None => x.leaf("float", &[("name", key), ("value", &num(c))]),
                }
            }
            Ok(())
        }
    }
}

/// A colour parameter: its texture if it has a non-constant one, else the constant.
fn color_slot(
    x: &mut Xml,
    name: &str,
    constant: DVec3,
    texture: Option<TextureDesc>,
    folder: &Path,
    path: &str,
) -> Result<(), SceneError> {
    match texture {
        Some(t) => texture_xml(x, name, &t, false, folder, path),
        None => {
            color_value(x, name, constant);
            Ok(())
        }
    }
}

/// `<rgb name=… value="r g b"/>`.
pub(crate) fn color_value(x: &mut Xml, name: &str, c: DVec3) {
    let v = format!("{} {} {}", num(c.x), num(c.y), num(c.z));
    x.leaf("rgb", &[("name", name), ("value", &v)]);
}

fn color32(x: &mut Xml, name: &str, c: Vec3) {
    let v = format!("{} {} {}", num32(c.x), num32(c.y), num32(c.z));
    x.leaf("rgb", &[("name", name), ("value", &v)]);
}

/// A texture (or a constant one as its value) as parameter `name`; `scalar` when the slot reads
/// a scalar (Mitsuba's `eval_1`).
pub(crate) fn texture_xml(
    x: &mut Xml,
    name: &str,
    t: &TextureDesc,
    scalar: bool,
    folder: &Path,
    path: &str,
) -> Result<(), SceneError> {
    match &t.texture {
        Texture::Constant(c) if scalar => {
            x.leaf("float", &[("name", name), ("value", &num32(c.x))]);
        }
        Texture::Constant(c) => color32(x, name, *c),
        Texture::Bitmap(b) => {
            let o = b.options();
            if o.scale != Vec3::ONE {
                return Err(SceneError::new(
                    path,
                    "a bitmap's `scale` cannot be exported: Mitsuba's bitmap has none (bake \
                     it into the image)",
                ));
            }
            if scalar && o.channel != Channel::Luminance {
                return Err(SceneError::new(
                    path,
                    format!(
                        "a bitmap's `channel` {} cannot be exported: Mitsuba's scalar lookup \
                         reads the luminance",
                        o.channel.name()
                    ),
                ));
            }
            x.open("texture", &[("type", "bitmap"), ("name", name)]);
            x.leaf(
                "string",
                &[("name", "filename"), ("value", &file_name(&b.file, folder))],
            );
            x.leaf("string", &[("name", "filter_type"), ("value", "bilinear")]);
            x.leaf("string", &[("name", "wrap_mode"), ("value", o.wrap.name())]);
            if b.raw {
                x.leaf("boolean", &[("name", "raw"), ("value", "true")]);
            }
            to_uv(x, &o.uv);
            x.close("texture");
        }
        Texture::Checkerboard(c) => {
            x.open("texture", &[("type", "checkerboard"), ("name", name)]);
            // Mitsuba's eval_1 picks the other colour; the importer swaps them back.
            let (c0, c1) = if scalar {
                (c.color1, c.color0)
            } else {
                (c.color0, c.color1)
            };
            color32(x, "color0", c0);
            color32(x, "color1", c1);
            to_uv(x, &c.uv);
            x.close("texture");
        }
        Texture::MeshAttribute(m) => {
            x.open("texture", &[("type", "mesh_attribute"), ("name", name)]);
            x.leaf("string", &[("name", "name"), ("value", &m.name)]);
            if m.scale != 1.0 {
                x.leaf("float", &[("name", "scale"), ("value", &num32(m.scale))]);
            }
            x.close("texture");
        }
    }
    Ok(())
}

/// A texture's scale and offset as `to_uv` (nothing for the identity).
fn to_uv(x: &mut Xml, uv: &UvTransform) {
    if uv.scale == Vec2::ONE && uv.offset == Vec2::ZERO {
        return;
    }
    let (s, o) = (uv.scale, uv.offset);
    let m = format!(
        "{} 0 0 {} 0 {} 0 {} 0 0 1 0 0 0 0 1",
        num32(s.x),
        num32(o.x),
        num32(s.y),
        num32(o.y)
    );
    x.open("transform", &[("name", "to_uv")]);
    x.leaf("matrix", &[("value", &m)]);
    x.close("transform");
}
