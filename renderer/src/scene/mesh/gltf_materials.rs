//! glTF 2.0 materials as lumis materials, for a glTF file opened on its own (the rule is in
//! docs/scene-format.md, "glTF materials"): each material the placed primitives use becomes
//! JSON materials of the scene format (glTF's own metallic-roughness material, `gltf_pbr`; with
//! `KHR_materials_transmission`, mixes of it and a dielectric) and an emission, with its textures as `bitmap` objects whose images this module has decoded
//! already, so that the JSON front end checks everything exactly as it checks a scene file.
//!
//! The base colour's alpha becomes the material's `opacity` (alpha masks): `MASK` the alpha
//! against `alphaCutoff` per texel, `BLEND` the alpha itself as stochastic opacity.
//!
//! What lumis does not render (normal maps, extensions other than
//! `KHR_materials_ior`, `KHR_materials_specular` (its factors; not its textures),
//! `KHR_materials_transmission`, `KHR_materials_emissive_strength`, `KHR_materials_unlit`,
//! `KHR_texture_transform` and `KHR_lights_punctual` (`gltf_lights.rs`), texture rotation, a second texture coordinate set, a sampler whose
//! two axes wrap differently, nearest filtering) is collected by glTF path into
//! [`Materials::ignored`], which the caller writes as one warning (occlusion maps are not named:
//! a path tracer computes occlusion). Errors name the file and
//! the glTF path of the problem (`materials[2].pbrMetallicRoughness.baseColorTexture`).
//!
//! Raw JSON is read for the extensions (the `gltf` crate is built without its typed ones) and
//! for images, whose typed accessors unwrap what validation does not check.
//! The material extensions' readers are in `gltf_material_extensions.rs`.

use super::buffers::{read_uri, relative_path};
use crate::image_io::Image;
use crate::scene::mesh::MeshError;
use crate::textures::load::{decode_alpha, decode_texture_image};
use ::gltf::Document;
use ::gltf::json;
use ::gltf::json::texture::{MagFilter, WrappingMode};
use ::gltf::json::validation::Checked;
use glam::Vec3;
use serde_json::{Map, Value, json};
use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

/// The extensions lumis maps (all others are named in the warning; the lights are read by
/// `gltf_lights.rs`); required, they do not stop the geometry either.
pub const HANDLED: [&str; 7] = [
    "KHR_materials_ior",
    "KHR_materials_specular",
    "KHR_materials_transmission",
    "KHR_materials_emissive_strength",
    "KHR_texture_transform",
    "KHR_materials_unlit",
    super::lights::EXTENSION,
];

/// The lumis side of the materials a glTF file's primitives use.
#[derive(Debug, Default)]
pub struct Materials {
    /// Per glTF material used (`None`: the default material), what its primitives get.
    pub mapped: Vec<(Option<usize>, Mapped)>,
    /// Every scene-format material the mapped ones need, by name.
    pub json: Map<String, Value>,
    /// The decoded images the textures name: (name relative to the file's folder, raw, image).
    pub images: Vec<(String, bool, Arc<Image>)>,
    /// What the materials have that lumis does not render, by glTF path, in file order.
    pub ignored: Vec<String>,
}

/// What the primitives of one glTF material get.
#[derive(Clone, Debug, PartialEq)]
pub struct Mapped {
    /// The scene-format material (a key of [`Materials::json`]).
    pub name: String,
    /// The shape's `emission` (a colour or a texture), if it emits.
    pub emission: Option<Value>,
    /// Whether a parameter is textured (so the primitive needs texture coordinates).
    pub textured: bool,
}

/// Marks the buffers that hold the images of the materials in `used` (bad indices are left to
/// [`read`], which names them).
pub fn mark_image_buffers(doc: &Document, used: &[Option<usize>], needed: &mut [bool]) {
    let root = doc.as_json();
    for &i in used.iter().flatten() {
        let Some(m) = root.materials.get(i) else {
            continue;
        };
        let pbr = &m.pbr_metallic_roughness;
        let mut textures: Vec<usize> = [
            &pbr.base_color_texture,
            &pbr.metallic_roughness_texture,
            &m.emissive_texture,
        ]
        .into_iter()
        .flatten()
        .map(|t| t.index.value())
        .collect();
        textures.extend(
            extension(
                m.extensions.as_ref().map(|e| &e.others),
                "KHR_materials_transmission",
            )
            .and_then(|t| t.get("transmissionTexture")?.get("index")?.as_u64())
            .map(|t| t as usize),
        );
        for t in textures {
            let image = root.textures.get(t).map(|t| t.source.value());
            let view = image.and_then(|k| root.images.get(k)?.buffer_view);
            let buffer = view.and_then(|v| root.buffer_views.get(v.value()));
            if let Some(b) = buffer.and_then(|v| needed.get_mut(v.buffer.value())) {
                *b = true;
            }
        }
    }
}

/// The lumis materials of the glTF materials in `used` (`None`: the default material), whose
/// images are in `buffers` (those [`mark_image_buffers`] marked) or beside `file`.
pub fn read(
    file: &Path,
    doc: &Document,
    buffers: &[&[u8]],
    used: &[Option<usize>],
) -> Result<Materials, MeshError> {
    let root = doc.as_json();
    let mut reader = Reader {
        file,
        root,
        buffers,
        file_name: file
            .file_name()
            .map_or_else(|| "model".into(), |n| n.to_string_lossy().into_owned()),
        decoded: HashMap::new(),
        out: Materials::default(),
    };
    for &index in used {
        let mapped = reader.material(index)?;
        reader.out.mapped.push((index, mapped));
    }
    for name in &root.extensions_used {
        if !HANDLED.contains(&name.as_str()) {
            reader.out.ignored.push(format!("extension {name}"));
        }
    }
    let mut out = reader.out;
    let decoded = reader.decoded.into_iter();
    out.images
        .extend(decoded.map(|((_, raw), (name, image))| (name, raw, image)));
    out.images.sort_by(|a, b| (&a.0, a.1).cmp(&(&b.0, b.1)));
    Ok(out)
}

/// A parameter: a constant or a texture object.
#[derive(Clone, Debug)]
enum Param {
    Constant(Value),
    Texture(Value),
}

impl Param {
    fn json(&self) -> Value {
        match self {
            Param::Constant(v) | Param::Texture(v) => v.clone(),
        }
    }

    fn is_texture(&self) -> bool {
        matches!(self, Param::Texture(_))
    }
}

/// A texture as read: its `bitmap` object (file, raw, wrap, uv transform) and its image.
struct TextureRef {
    json: Value,
    image: Arc<Image>,
}

struct Reader<'a> {
    file: &'a Path,
    root: &'a json::Root,
    buffers: &'a [&'a [u8]],
    /// The file's name, which names embedded images (`model.glb#images[2]`).
    file_name: String,
    /// Images decoded so far, by (image, raw): their name and texels (images derived from them,
    /// such as a baked roughness², go straight to `out.images`).
    decoded: HashMap<(usize, bool), (String, Arc<Image>)>,
    out: Materials,
}

impl Reader<'_> {
    fn error(&self, at: &str, message: impl std::fmt::Display) -> MeshError {
        MeshError::at(self.file, at, message)
    }

    /// Maps one glTF material (`None`: the default one, all properties at their defaults).
    fn material(&mut self, index: Option<usize>) -> Result<Mapped, MeshError> {
        let default = json::Material::default();
        let m = match index {
            Some(i) => self
                .root
                .materials
                .get(i)
                .ok_or_else(|| self.error("", format!("material {i} does not exist")))?,
            None => &default,
        };
        let at = index.map_or_else(
            || "default material".to_owned(),
            |i| format!("materials[{i}]"),
        );
        let name = match (&m.name, index) {
            (Some(n), Some(_)) if !n.is_empty() => format!("{at} {n}"),
            _ => at.clone(),
        };
        let others = m.extensions.as_ref().map(|e| &e.others);
        for key in others.into_iter().flat_map(|o| o.keys()) {
            if !HANDLED.contains(&key.as_str()) {
                self.out.ignored.push(format!("{at}.extensions.{key}"));
            }
        }
        if m.normal_texture.is_some() {
            self.out.ignored.push(format!("{at}.normalTexture"));
        }
        // `occlusionTexture` is not named: a path tracer computes occlusion, so a warning about
        // it would change nothing.
        // The alpha mode: `Some(Some(cutoff))` for MASK, `Some(None)` for BLEND.
        let alpha_mode = match m.alpha_mode {
            Checked::Valid(json::material::AlphaMode::Opaque) => None,
            Checked::Valid(json::material::AlphaMode::Mask) => {
                Some(Some(m.alpha_cutoff.map_or(0.5, |c| c.0)))
            }
            Checked::Valid(json::material::AlphaMode::Blend) => Some(None),
            Checked::Invalid => {
                self.out.ignored.push(format!("{at}.alphaMode"));
                None
            }
        };
        if m.alpha_cutoff.is_some() && !matches!(alpha_mode, Some(Some(_))) {
            self.out
                .ignored
                .push(format!("{at}.alphaCutoff (without MASK)"));
        }

        let pbr = &m.pbr_metallic_roughness;
        let pbr_at = format!("{at}.pbrMetallicRoughness");
        let f = pbr.base_color_factor.0;
        let base_factor = Vec3::new(f[0], f[1], f[2]);
        unit_components(self, &format!("{pbr_at}.baseColorFactor"), &f[..3])?;
        let metallic = unit(
            self,
            &format!("{pbr_at}.metallicFactor"),
            pbr.metallic_factor.0,
        )?;
        let roughness = unit(
            self,
            &format!("{pbr_at}.roughnessFactor"),
            pbr.roughness_factor.0,
        )?;

        let base_at = format!("{pbr_at}.baseColorTexture");
        let (base, base_texture) = match &pbr.base_color_texture {
            Some(info) => {
                let t = self.texture(&base_at, info, false)?;
                let mut j = t.json.clone();
                j["scale"] = vec3(base_factor);
                let image = self.root.textures[info.index.value()].source.value();
                (Param::Texture(j), Some((t, image)))
            }
            None => (Param::Constant(vec3(base_factor)), None),
        };
        let textured_base = base.is_texture();
        let alpha_factor = unit(self, &format!("{pbr_at}.baseColorFactor[3]"), f[3])?;
        let opacity = match alpha_mode {
            Some(cutoff) => self.opacity(&at, &base_at, base_texture, alpha_factor, cutoff)?,
            None => None,
        };
        if extension(others, "KHR_materials_unlit").is_some() {
            return Ok(self.unlit(&at, name, base, base_factor == Vec3::ZERO, opacity));
        }
        // glTF keeps roughness in G and metallic in B of one linear texture.
        let mr = match &pbr.metallic_roughness_texture {
            Some(info) => {
                Some(self.texture(&format!("{pbr_at}.metallicRoughnessTexture"), info, true)?)
            }
            None => None,
        };
        // The gltf_pbr material squares the roughness at the hit, after filtering, as glTF does.
        let roughness_param = match &mr {
            Some(t) => {
                let mut j = t.json.clone();
                j["channel"] = json!("g");
                j["scale"] = json!(roughness);
                Param::Texture(j)
            }
            None => Param::Constant(json!(roughness)),
        };
        let metallic_param = match &mr {
            Some(t) if metallic > 0.0 => {
                let mut j = t.json.clone();
                j["channel"] = json!("b");
                j["scale"] = json!(metallic);
                Param::Texture(j)
            }
            _ => Param::Constant(json!(metallic)),
        };
        // The weight of the metal in a transmitting material's mix.
        let metal_weight = match &mr {
            Some(t) if metallic > 0.0 => {
                let mut j = t.json.clone();
                j["channel"] = json!("b");
                j["scale"] = json!(metallic);
                Some(Param::Texture(j))
            }
            _ => (metallic > 0.0 && metallic < 1.0).then(|| Param::Constant(json!(metallic))),
        };

        let ior_at = format!("{at}.extensions.KHR_materials_ior.ior");
        let ior = match extension(others, "KHR_materials_ior") {
            Some(e) => self.number(e, "ior", &ior_at, 1.5)?,
            None => 1.5,
        };
        // `number` is finite.
        if ior < 1.0 {
            return Err(self.error(&ior_at, format!("{ior} must be at least 1")));
        }

        let (specular, specular_color) = match extension(others, "KHR_materials_specular") {
            Some(e) => self.specular(e, &at)?,
            None => (1.0, [1.0; 3]),
        };
        let transmission = match extension(others, "KHR_materials_transmission") {
            Some(e) => Some(self.transmission(e, &at)?),
            None => None,
        };
        let transmission = transmission.filter(|(factor, _)| *factor > 0.0);
        // A transmitting material's glass takes α = roughness², which is not linear in the texel:
        // baked per texel, before filtering.
        let alpha = match &mr {
            Some(t) if transmission.is_some() => {
                let name = format!("{}#{at}.alpha", self.file_name);
                let data = t
                    .image
                    .data
                    .iter()
                    .map(|c| Vec3::splat((roughness * c.y).powi(2)));
                let image = Image {
                    width: t.image.width,
                    height: t.image.height,
                    data: data.collect(),
                };
                self.out.images.push((name.clone(), true, Arc::new(image)));
                let mut j = t.json.clone();
                j["file"] = json!(name);
                Param::Texture(j)
            }
            _ => Param::Constant(json!((roughness as f64).powi(2))),
        };
        if transmission.is_some() {
            if base.is_texture() || base_factor != Vec3::ONE {
                self.out.ignored.push(format!(
                    "{at}: the base colour's tint of light through KHR_materials_transmission"
                ));
            }
            if specular != 1.0 || specular_color != [1.0; 3] {
                self.out.ignored.push(format!(
                    "{at}: KHR_materials_specular on the light through \
                     KHR_materials_transmission (lumis' glass takes its Fresnel from the ior)"
                ));
            }
            if extension(others, "KHR_materials_volume").is_none() {
                self.out.ignored.push(format!(
                    "{at}: thin-walled KHR_materials_transmission (without KHR_materials_volume; \
                     lumis refracts it as a solid dielectric)"
                ));
            }
            let max = crate::materials::dielectric::MAX_IOR as f64;
            if ior == 1.0 || ior > max {
                return Err(self.error(
                    &ior_at,
                    format!(
                        "{ior}: a transmitting material needs an index of refraction other \
                         than 1 and at most {max}"
                    ),
                ));
            }
        }

        let two_sided = |mut v: Value| {
            if !m.double_sided {
                v["two_sided"] = json!(false);
            }
            v
        };
        let json = &mut self.out.json;
        let mut add = |suffix: &str, v: Value| -> String {
            let key = format!("{name}{suffix}");
            json.insert(key.clone(), v);
            key
        };
        // glTF's material as its specification defines it, with the metallic given.
        let pbr = |metallic: &Param| {
            let mut v = json!({
                "type": "gltf_pbr", "base_color": base.json(), "roughness": roughness_param.json(),
                "metallic": metallic.json(), "ior": ior,
            });
            if specular != 1.0 {
                v["specular"] = json!(specular);
            }
            if specular_color != [1.0; 3] {
                v["specular_color"] = json!(specular_color);
            }
            two_sided(v)
        };
        let Some(transmission) = transmission else {
            let top = add("", pbr(&metallic_param));
            return self.finish(m, others, &at, top, opacity, textured_base || mr.is_some());
        };
        // With transmission, the dielectric part is the opaque material (metallic 0), a glass,
        // or a mix of the two by the transmission; the metal (metallic 1) is mixed in by the
        // metallic (the material is linear in it, so this is the material's expected value).
        let opaque = pbr(&Param::Constant(json!(0.0)));
        let glass = json!({"type": "dielectric", "ior": ior, "alpha": alpha.json()});
        let metal = pbr(&Param::Constant(json!(1.0)));
        let mix = |a: &str, b: &str, w: &Param| json!({"type": "mix", "materials": [a, b], "weight": w.json()});
        let metal_only = metallic == 1.0 && metal_weight.is_none();
        let top_suffix = |part: &str| {
            if metallic == 0.0 || metal_only {
                String::new()
            } else {
                part.to_owned()
            }
        };
        let dielectric_part = match &transmission {
            _ if metal_only => None,
            (factor, None) if *factor == 1.0 => Some(add(&top_suffix(" (glass)"), glass)),
            (factor, texture) => {
                let w = texture.clone().unwrap_or(Param::Constant(json!(factor)));
                let a = add(" (opaque)", opaque);
                let b = add(" (glass)", glass);
                Some(add(&top_suffix(" (dielectric)"), mix(&a, &b, &w)))
            }
        };
        let top = match (dielectric_part, &metal_weight) {
            (None, _) => add("", metal),
            (Some(d), None) => d,
            (Some(d), Some(w)) => {
                let c = add(" (metal)", metal);
                add("", mix(&d, &c, w))
            }
        };

        let textured = textured_base || mr.is_some() || transmission.1.is_some();
        self.finish(m, others, &at, top, opacity, textured)
    }

    /// The emission of `m` (at `at`) and the opacity of its material `top`, and what its
    /// primitives get (`textured`: a parameter of the material is).
    fn finish(
        &mut self,
        m: &json::Material,
        others: Option<&Map<String, Value>>,
        at: &str,
        top: String,
        opacity: Option<Param>,
        textured: bool,
    ) -> Result<Mapped, MeshError> {
        let emission = self.emission(m, others, at)?;
        // An emitter's material takes no opacity (Mitsuba masks a BSDF, not its emission).
        let opacity = match opacity {
            Some(_) if emission.is_some() => {
                self.out.ignored.push(format!(
                    "{at}.alphaMode on an emissive material (lumis masks no emitter)"
                ));
                None
            }
            o => o,
        };
        if let Some(o) = &opacity {
            self.out.json[&top]["opacity"] = o.json();
        }
        let textured = textured
            || emission.as_ref().is_some_and(Param::is_texture)
            || opacity.as_ref().is_some_and(Param::is_texture);
        Ok(Mapped {
            name: top,
            emission: emission.map(|e| e.json()),
            textured,
        })
    }

    /// The opacity of glTF's alpha (the base colour texture's alpha, `image`, times `factor`):
    /// for MASK (`cutoff`) 1 where it reaches the cutoff and 0 elsewhere, decided per texel
    /// (before bilinear filtering, so an edge is a band of partial opacity where glTF cuts the
    /// filtered alpha), for BLEND the alpha itself. A texture on the base colour's sampler and
    /// transform, baked per texel; a constant without one (or where the image has no alpha);
    /// `None` where everything is opaque.
    fn opacity(
        &mut self,
        at: &str,
        base_at: &str,
        base: Option<(TextureRef, usize)>,
        factor: f32,
        cutoff: Option<f32>,
    ) -> Result<Option<Param>, MeshError> {
        let alpha_of = |a: f32| match cutoff {
            Some(c) => f32::from(a * factor >= c),
            None => a * factor,
        };
        let alpha = match &base {
            Some((_, image)) => self.alpha(base_at, *image)?,
            None => None,
        };
        let (Some((t, _)), Some(alpha)) = (base, alpha) else {
            let a = alpha_of(1.0);
            return Ok((a < 1.0).then(|| Param::Constant(json!(a))));
        };
        let name = format!("{}#{at}.opacity", self.file_name);
        let image = Image {
            width: alpha.width,
            height: alpha.height,
            data: alpha
                .data
                .iter()
                .map(|a| Vec3::splat(alpha_of(a.x)))
                .collect(),
        };
        self.out.images.push((name.clone(), true, Arc::new(image)));
        let mut j = t.json;
        j["file"] = json!(name);
        j["raw"] = json!(true);
        Ok(Some(Param::Texture(j)))
    }

    /// The number `key` of the extension object `e` (at `at`), `default` if absent.
    fn number(
        &self,
        e: &Map<String, Value>,
        key: &str,
        at: &str,
        default: f64,
    ) -> Result<f64, MeshError> {
        match e.get(key) {
            None => Ok(default),
            Some(v) => v
                .as_f64()
                .filter(|x| x.is_finite() && (*x as f32).is_finite())
                .ok_or_else(|| self.error(at, format!("expected a finite number, found {v}"))),
        }
    }

    /// The texture `info` at `at` as a `bitmap` object (`file`, `raw`, `wrap`, uv transform),
    /// with its image decoded (`raw`: linear data, else sRGB).
    fn texture(
        &mut self,
        at: &str,
        info: &json::texture::Info,
        raw: bool,
    ) -> Result<TextureRef, MeshError> {
        let root = self.root;
        let texture = &root.textures[info.index.value()];
        let mut coord = info.tex_coord;
        let (mut scale, mut offset) = ([1.0f64, 1.0], [0.0f64, 0.0]);
        let others = info.extensions.as_ref().map(|e| &e.others);
        for (key, v) in others.into_iter().flatten() {
            if key != "KHR_texture_transform" {
                self.out.ignored.push(format!("{at}.extensions.{key}"));
                continue;
            }
            let t_at = format!("{at}.extensions.KHR_texture_transform");
            let t = v
                .as_object()
                .ok_or_else(|| self.error(&t_at, "expected an object"))?;
            for (key, out) in [("scale", &mut scale), ("offset", &mut offset)] {
                if let Some(v) = t.get(key) {
                    let pair = v.as_array().filter(|a| a.len() == 2);
                    let pair = pair.and_then(|a| Some([a[0].as_f64()?, a[1].as_f64()?]));
                    *out = pair
                        .filter(|p| p.iter().all(|x| (*x as f32).is_finite()))
                        .ok_or_else(|| {
                            self.error(&format!("{t_at}.{key}"), "expected 2 finite numbers")
                        })?;
                }
            }
            if t.get("rotation")
                .and_then(Value::as_f64)
                .is_some_and(|r| r != 0.0)
            {
                self.out.ignored.push(format!("{t_at}.rotation"));
            }
            if let Some(c) = t.get("texCoord").and_then(Value::as_u64) {
                coord = c as u32;
            }
        }
        if coord != 0 {
            self.out
                .ignored
                .push(format!("{at} TEXCOORD_{coord} (lumis reads TEXCOORD_0)"));
        }

        let mut wrap = "repeat";
        if let Some(s) = texture.sampler {
            let sampler = &root.samplers[s.value()];
            let mode = |m: &Checked<WrappingMode>| match m {
                Checked::Valid(WrappingMode::ClampToEdge) => "clamp",
                Checked::Valid(WrappingMode::MirroredRepeat) => "mirror",
                _ => "repeat",
            };
            wrap = mode(&sampler.wrap_s);
            if mode(&sampler.wrap_t) != wrap {
                self.out.ignored.push(format!(
                    "samplers[{}].wrapT (lumis wraps both axes as wrapS)",
                    s.value()
                ));
            }
            if sampler.mag_filter == Some(Checked::Valid(MagFilter::Nearest)) {
                self.out.ignored.push(format!(
                    "samplers[{}].magFilter NEAREST (lumis filters bilinearly)",
                    s.value()
                ));
            }
        }
        let (name, image) = self.image(at, texture.source.value(), raw)?;
        let mut j = json!({"type": "bitmap", "file": name, "raw": raw, "wrap": wrap});
        if scale != [1.0, 1.0] {
            j["uv_scale"] = json!(scale);
        }
        if offset != [0.0, 0.0] {
            j["uv_offset"] = json!(offset);
        }
        Ok(TextureRef { json: j, image })
    }

    /// Image `k` decoded (once per `raw`), and the name the JSON texture gives it: its path for
    /// an external file (so a scene written back reads the same file), `model.glb#images[k]`
    /// for an embedded one.
    fn image(&mut self, at: &str, k: usize, raw: bool) -> Result<(String, Arc<Image>), MeshError> {
        if let Some((name, image)) = self.decoded.get(&(k, raw)) {
            return Ok((name.clone(), image.clone()));
        }
        let (bytes, name) = self.image_bytes(at, k)?;
        let image = decode_texture_image(&bytes, Path::new(&name), raw)
            .map_err(|e| self.error(at, format!("images[{k}] ('{name}'): {}", e.message)))?;
        let image = Arc::new(image);
        self.decoded.insert((k, raw), (name.clone(), image.clone()));
        Ok((name, image))
    }

    /// Image `k`'s alpha channel (linear), or `None` where it has none.
    fn alpha(&self, at: &str, k: usize) -> Result<Option<Image>, MeshError> {
        let (bytes, name) = self.image_bytes(at, k)?;
        decode_alpha(&bytes, Path::new(&name))
            .map_err(|e| self.error(at, format!("images[{k}] ('{name}'): {}", e.message)))
    }

    /// Image `k`'s encoded bytes and the name the JSON texture gives it (see [`Reader::image`]).
    fn image_bytes(&self, at: &str, k: usize) -> Result<(Vec<u8>, String), MeshError> {
        let fail = |what: &str, m: String| self.error(at, format!("images[{k}] ({what}): {m}"));
        let img = &self.root.images[k];
        let embedded = format!("{}#images[{k}]", self.file_name);
        let folder = self.file.parent().unwrap_or(Path::new(""));
        let (bytes, name): (Vec<u8>, String) = match (&img.buffer_view, &img.uri) {
            (Some(v), _) => {
                let view = &self.root.buffer_views[v.value()];
                let data = self
                    .buffers
                    .get(view.buffer.value())
                    .copied()
                    .unwrap_or_default();
                let start = view.byte_offset.map_or(0, |o| o.0) as usize;
                let len = view.byte_length.0 as usize;
                let bytes = start.checked_add(len).and_then(|end| data.get(start..end));
                let bytes = bytes.ok_or_else(|| {
                    fail(
                        &format!("buffer view {}", v.value()),
                        format!(
                            "bytes {start}..+{len} run past the end of buffer {} ({} bytes)",
                            view.buffer.value(),
                            data.len()
                        ),
                    )
                })?;
                (bytes.to_vec(), embedded)
            }
            (None, Some(uri)) if uri.starts_with("data:") => (
                read_uri(folder, uri)
                    .map_err(|m| fail("its data URI", m))?
                    .0,
                embedded,
            ),
            (None, Some(uri)) => {
                let name = relative_path(uri).map_err(|m| fail(uri, m))?;
                let (bytes, _) =
                    read_uri(folder, uri).map_err(|m| fail(&format!("'{name}'"), m))?;
                (bytes, name)
            }
            (None, None) => {
                return Err(fail(
                    "no source",
                    "it has neither a uri nor a bufferView".into(),
                ));
            }
        };
        Ok((bytes, name))
    }
}

/// The extension `name` of an `extensions` map, if it is an object.
fn extension<'j>(
    others: Option<&'j Map<String, Value>>,
    name: &str,
) -> Option<&'j Map<String, Value>> {
    others?.get(name)?.as_object()
}

/// A factor in [0, 1].
fn unit(r: &Reader, at: &str, x: f32) -> Result<f32, MeshError> {
    if (0.0..=1.0).contains(&x) {
        Ok(x)
    } else {
        Err(r.error(at, format!("{x} is outside [0, 1]")))
    }
}

/// Every component of a colour factor in [0, 1].
fn unit_components(r: &Reader, at: &str, c: &[f32]) -> Result<(), MeshError> {
    for (i, &x) in c.iter().enumerate() {
        unit(r, &format!("{at}[{i}]"), x)?;
    }
    Ok(())
}

fn vec3(c: Vec3) -> Value {
    json!([c.x, c.y, c.z])
}

#[path = "gltf_material_extensions.rs"]
mod extensions;

#[cfg(test)]
#[path = "gltf_materials_tests.rs"]
mod tests;
