//! Texture objects in texturable parameters (`albedo`, `reflectance`, `alpha`, `emission`):
//! `{"type": "bitmap", "file": …}` or `{"type": "checkerboard", …}` (docs/scene-format.md,
//! "Textures"). Files are read relative to the scene's folder, each (file, raw) pair once, and
//! checked texel by texel for the range of the parameter they fill, so that every front end gets
//! the same errors: the JSON path, the file, and the pixel of a bad texel.

use super::desc::TextureDesc;
use super::error::SceneError;
use super::mesh::MeshData;
use super::parse::MAX_RADIANCE;
use super::walk::{Obj, array, number, vec3};
use crate::image_io::Image;
use crate::textures::load::{is_float_format, load_texture_image};
use crate::textures::{
    BitmapOptions, BitmapTexture, Channel, Checkerboard, Texture, UvTransform, WrapMode,
    checkerboard,
};
use glam::{DVec3, Vec2, Vec3};
use serde_json::Value;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Which parameter a texture fills: decides its range and whether it is read as a scalar.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum TextureUse {
    /// A diffuse or plastic albedo: RGB in [0, 1].
    Albedo,
    /// A conductor's reflectance: RGB in [0, 1].
    Reflectance,
    /// GGX α: a scalar in [0, 1].
    Alpha,
    /// A mix's weight: a scalar in [0, 1].
    Weight,
    /// Emitted radiance: RGB ≥ 0, at most [`MAX_RADIANCE`].
    Emission,
    /// A normal map's encoded normals `(n + 1)/2`: RGB in [0, 1].
    NormalMap,
    /// A bump map's heights: any finite values, differentiated through their luminance.
    Height,
    /// An alpha mask's opacity: a scalar in [0, 1].
    Opacity,
    /// A principled's scalar parameter (roughness, metallic, …): a scalar in [0, 1].
    Parameter,
    /// A thin principled's `diff_trans`: a scalar in [0, 2].
    DiffuseTransmission,
    /// A thin principled's `eta`: a positive scalar, at most the dielectric's largest index.
    Eta,
}

impl TextureUse {
    pub(crate) fn is_scalar(self) -> bool {
        matches!(
            self,
            TextureUse::Alpha
                | TextureUse::Weight
                | TextureUse::Opacity
                | TextureUse::Parameter
                | TextureUse::DiffuseTransmission
                | TextureUse::Eta
        )
    }

    /// Why `x` is not allowed here, if it is not.
    pub(crate) fn problem(self, x: f64) -> Option<&'static str> {
        if x.is_nan() {
            return Some("is NaN");
        }
        match self {
            TextureUse::Albedo => (!(0.0..=1.0).contains(&x))
                .then_some("is outside [0, 1]: an albedo must lie in [0, 1]"),
            TextureUse::Reflectance => (!(0.0..=1.0).contains(&x))
                .then_some("is outside [0, 1]: a reflectance must lie in [0, 1]"),
            TextureUse::Alpha => {
                (!(0.0..=1.0).contains(&x)).then_some("is outside [0, 1]: alpha must lie in [0, 1]")
            }
            TextureUse::Weight => (!(0.0..=1.0).contains(&x))
                .then_some("is outside [0, 1]: a mix weight must lie in [0, 1]"),
            TextureUse::Opacity => (!(0.0..=1.0).contains(&x))
                .then_some("is outside [0, 1]: an opacity must lie in [0, 1]"),
            TextureUse::Parameter => (!(0.0..=1.0).contains(&x))
                .then_some("is outside [0, 1]: a principled parameter must lie in [0, 1]"),
            TextureUse::DiffuseTransmission => (!(0.0..=2.0).contains(&x))
                .then_some("is outside [0, 2]: diff_trans must lie in [0, 2]"),
            TextureUse::Eta => (!(x > 0.0 && x <= crate::materials::dielectric::MAX_IOR as f64))
                .then_some(
                    "is not in (0, 10]: an index of refraction must be positive and at most 10",
                ),
            TextureUse::NormalMap => (!(0.0..=1.0).contains(&x))
                .then_some("is outside [0, 1]: a normal map encodes (n + 1)/2 in [0, 1]"),
            TextureUse::Height => (!x.is_finite()).then_some("is not finite"),
            TextureUse::Emission => {
                if x < 0.0 {
                    Some("is negative: radiance must be ≥ 0")
                } else if x > MAX_RADIANCE {
                    Some("is too large: radiance must be at most 1e30")
                } else {
                    None
                }
            }
        }
    }
}

/// Reads texture files relative to the scene's folder, each (file, raw) once: textures that name
/// the same file (however spelled) share its texels. It also hands out the files a front end
/// has already read ([`Preloaded`]).
pub(crate) struct TextureLoader {
    folder: PathBuf,
    cache: HashMap<(PathBuf, bool), Arc<Image>>,
    /// Mesh files by (path, shape index), read once however many shapes place them.
    meshes: HashMap<(PathBuf, u32), Arc<MeshData>>,
    preloaded: Preloaded,
}

/// Files already in memory, by the path the scene's names resolve to (`folder/name`): a glTF
/// file opened on its own ([`super::model`]) hands its decoded images (per `raw`) and its
/// primitives to the JSON front end this way, which then checks them as it checks files.
#[derive(Default)]
pub(crate) struct Preloaded {
    /// Decoded images by (path, raw).
    pub images: HashMap<(PathBuf, bool), Arc<Image>>,
    /// Meshes by path, each for one `mesh` shape.
    pub meshes: HashMap<PathBuf, MeshData>,
}

impl TextureLoader {
    /// A loader for a scene whose files are relative to `folder`.
    pub fn new(folder: &Path) -> TextureLoader {
        TextureLoader {
            folder: folder.to_owned(),
            cache: HashMap::new(),
            meshes: HashMap::new(),
            preloaded: Preloaded::default(),
        }
    }

    /// The loader, looking in `preloaded` before the file system.
    pub fn with_preloaded(mut self, preloaded: Preloaded) -> TextureLoader {
        self.preloaded = preloaded;
        self
    }

    /// Mesh `shape_index` of the file at the resolved path `file`, read on first use; errors
    /// at `json_path` name the file.
    pub fn mesh(
        &mut self,
        file: &Path,
        shape_index: u32,
        json_path: &str,
    ) -> Result<Arc<MeshData>, SceneError> {
        let key = (file.to_owned(), shape_index);
        if let Some(m) = self.meshes.get(&key) {
            return Ok(m.clone());
        }
        let m = Arc::new(
            crate::scene::mesh::load_mesh_index(file, shape_index)
                .map_err(|e| SceneError::new(json_path, e.to_string()))?,
        );
        self.meshes.insert(key, m.clone());
        Ok(m)
    }

    /// The preloaded image (linear, as `raw`) that the resolved path `file` names.
    pub fn preloaded_image(&self, file: &Path) -> Option<Arc<Image>> {
        self.preloaded.images.get(&(file.to_owned(), true)).cloned()
    }

    /// The preloaded mesh that the resolved path `file` names, taken out (each is for one shape).
    pub fn take_mesh(&mut self, file: &Path) -> Option<MeshData> {
        self.preloaded.meshes.remove(file)
    }

    /// The file `name` resolved and decoded; errors at `json_path` name the file.
    fn load(
        &mut self,
        name: &str,
        raw: bool,
        json_path: &str,
    ) -> Result<(PathBuf, Arc<Image>), SceneError> {
        if name.is_empty() {
            return Err(SceneError::new(json_path, "the file name is empty"));
        }
        let file = self.folder.join(name);
        if let Some(image) = self.preloaded.images.get(&(file.clone(), raw)) {
            return Ok((file, image.clone()));
        }
        // `raw` changes nothing for float files, so they are shared either way.
        let key_raw = raw || is_float_format(&file);
        let key = (
            std::fs::canonicalize(&file).unwrap_or(file.clone()),
            key_raw,
        );
        if let Some(image) = self.cache.get(&key) {
            return Ok((file, image.clone()));
        }
        let image = load_texture_image(&file, raw)
            .map_err(|e| SceneError::new(json_path, e.to_string()))?;
        let image = Arc::new(image);
        self.cache.insert(key, image.clone());
        Ok((file, image))
    }
}

/// The texture at `obj.key` when that member is a texture object; `None` when it is absent or
/// anything else (a constant, read and checked by the caller as before).
pub(crate) fn texture_at(
    obj: &Obj,
    key: &str,
    use_: TextureUse,
    loader: &mut TextureLoader,
) -> Result<Option<TextureDesc>, SceneError> {
    match obj.get(key) {
        Some(v) if v.is_object() => parse_texture(v, &obj.at(key), use_, loader).map(Some),
        _ => Ok(None),
    }
}

/// A texture object at `path`, checked for `use_`.
pub(crate) fn parse_texture(
    v: &Value,
    path: &str,
    use_: TextureUse,
    loader: &mut TextureLoader,
) -> Result<TextureDesc, SceneError> {
    let obj = Obj::new(v, path)?;
    let texture = match obj.string("type")? {
        "bitmap" => Texture::Bitmap(bitmap(&obj, use_, loader)?),
        "checkerboard" => Texture::Checkerboard(checker(&obj, use_)?),
        "mesh_attribute" => {
            Texture::MeshAttribute(super::parse_mesh_attribute::mesh_attribute(&obj, use_)?)
        }
        other => {
            return Err(SceneError::new(
                obj.at("type"),
                format!(
                    "unknown texture type `{other}` (expected bitmap, checkerboard or \
                     mesh_attribute)"
                ),
            ));
        }
    };
    Ok(TextureDesc { texture })
}

fn bitmap(
    obj: &Obj,
    use_: TextureUse,
    loader: &mut TextureLoader,
) -> Result<BitmapTexture, SceneError> {
    if obj.get("channel").is_some() && !use_.is_scalar() {
        return Err(SceneError::new(
            obj.at("channel"),
            "`channel` is only for a scalar parameter (alpha, a mix weight): a colour reads all three",
        ));
    }
    let mut keys = vec![
        "type",
        "file",
        "wrap",
        "raw",
        "uv_scale",
        "uv_offset",
        "scale",
    ];
    if use_.is_scalar() {
        keys.push("channel");
    }
    obj.only_keys(&keys, false)?;

    let wrap = match obj.get("wrap") {
        None => WrapMode::Repeat,
        Some(_) => match obj.string("wrap")? {
            "repeat" => WrapMode::Repeat,
            "mirror" => WrapMode::Mirror,
            "clamp" => WrapMode::Clamp,
            other => {
                return Err(SceneError::new(
                    obj.at("wrap"),
                    format!("unknown wrap mode `{other}` (expected repeat, mirror or clamp)"),
                ));
            }
        },
    };
    let channel = match obj.get("channel") {
        None => Channel::Luminance,
        Some(_) => match obj.string("channel")? {
            "luminance" => Channel::Luminance,
            "r" => Channel::R,
            "g" => Channel::G,
            "b" => Channel::B,
            other => {
                return Err(SceneError::new(
                    obj.at("channel"),
                    format!("unknown channel `{other}` (expected luminance, r, g or b)"),
                ));
            }
        },
    };
    let raw = obj.opt_bool("raw")?.unwrap_or(false);
    let scale = match obj.get("scale") {
        None => DVec3::ONE,
        Some(v) => {
            let s = number_or_color(v, &obj.at("scale"))?;
            if let Some(i) = (0..3).find(|&i| s[i] < 0.0) {
                let path = if v.is_number() {
                    obj.at("scale")
                } else {
                    format!("{}[{i}]", obj.at("scale"))
                };
                return Err(SceneError::new(
                    path,
                    format!("{} must not be negative", s[i]),
                ));
            }
            s
        }
    };
    let uv = uv_transform(obj)?;

    let file_path = obj.at("file");
    let (file, image) = loader.load(obj.string("file")?, raw, &file_path)?;
    let options = BitmapOptions {
        wrap,
        uv,
        scale: scale.as_vec3(),
        channel,
    };
    check_texels(&image, &options, use_, &file, &file_path)?;
    if use_ == TextureUse::NormalMap && image.data.iter().all(|t| t.x == t.y && t.y == t.z) {
        let msg = format!(
            "{}: a normal map must be RGB (x, y, z); this one is grey (R = G = B in every \
             texel), which encodes no normal map",
            file.display()
        );
        return Err(SceneError::new(file_path, msg));
    }
    Ok(BitmapTexture::new(image, options).with_source(file, raw))
}

/// Every texel, once scaled, in the range of `use_` (for a scalar slot: its channel), and no
/// channel NaN or infinite; the error names the first bad texel by column and row.
fn check_texels(
    image: &Image,
    options: &BitmapOptions,
    use_: TextureUse,
    file: &Path,
    json_path: &str,
) -> Result<(), SceneError> {
    let scale = options.scale.as_dvec3();
    let scaled_note = if options.scale == Vec3::ONE {
        ""
    } else {
        " once scaled"
    };
    for (k, t) in image.data.iter().enumerate() {
        let c = t.as_dvec3() * scale;
        let bad = |what: String, x: f64, problem: &str| {
            let (col, row) = (k as u32 % image.width, k as u32 / image.width);
            SceneError::new(
                json_path,
                format!(
                    "{}: pixel (column {col}, row {row}) {what} = {x}{scaled_note} {problem}",
                    file.display()
                ),
            )
        };
        for (i, x) in c.to_array().into_iter().enumerate() {
            if !x.is_finite() {
                let problem = if x.is_nan() {
                    "is NaN"
                } else {
                    "is not finite"
                };
                return Err(bad(format!("channel {i}"), x, problem));
            }
        }
        if use_.is_scalar() {
            let x = options.channel.pick(c.as_vec3()) as f64;
            if let Some(problem) = use_.problem(x) {
                return Err(bad(options.channel.name().to_owned(), x, problem));
            }
        } else if let Some((i, problem)) = (0..3).find_map(|i| use_.problem(c[i]).map(|p| (i, p))) {
            return Err(bad(format!("channel {i}"), c[i], problem));
        }
    }
    Ok(())
}

fn checker(obj: &Obj, use_: TextureUse) -> Result<Checkerboard, SceneError> {
    obj.only_keys(
        &["type", "color0", "color1", "uv_scale", "uv_offset"],
        false,
    )?;
    let color = |key: &str, default: f32| -> Result<Vec3, SceneError> {
        let Some(v) = obj.get(key) else {
            return Ok(Vec3::splat(default));
        };
        let path = obj.at(key);
        let c = number_or_color(v, &path)?;
        for i in 0..3 {
            if let Some(problem) = use_.problem(c[i]) {
                let at = if v.is_number() {
                    path
                } else {
                    format!("{path}[{i}]")
                };
                return Err(SceneError::new(at, format!("{} {problem}", c[i])));
            }
        }
        Ok(c.as_vec3())
    };
    Ok(Checkerboard {
        color0: color("color0", checkerboard::DEFAULT_COLOR0)?,
        color1: color("color1", checkerboard::DEFAULT_COLOR1)?,
        uv: uv_transform(obj)?,
    })
}

/// A number `x` (grey: `[x, x, x]`) or `[r, g, b]`.
fn number_or_color(v: &Value, path: &str) -> Result<DVec3, SceneError> {
    if v.is_number() {
        Ok(DVec3::splat(number(v, path)?))
    } else {
        vec3(v, path)
    }
}

/// `uv_scale` (default `[1, 1]`) and `uv_offset` (default `[0, 0]`).
fn uv_transform(obj: &Obj) -> Result<UvTransform, SceneError> {
    let pair = |key: &str, default: Vec2| -> Result<Vec2, SceneError> {
        let Some(v) = obj.get(key) else {
            return Ok(default);
        };
        let path = obj.at(key);
        let items = array(v, &path)?;
        if items.len() != 2 {
            let n = items.len();
            return Err(SceneError::new(
                path,
                format!("expected 2 numbers, found {n}"),
            ));
        }
        let c = |i: usize| number(&items[i], &format!("{path}[{i}]"));
        Ok(Vec2::new(c(0)? as f32, c(1)? as f32))
    };
    Ok(UvTransform {
        scale: pair("uv_scale", Vec2::ONE)?,
        offset: pair("uv_offset", Vec2::ZERO)?,
    })
}

#[cfg(test)]
mod tests {
    use crate::image_io::Image;
    use crate::scene::desc::{FresnelDesc, MaterialDesc, SceneDesc};
    use crate::scene::parse::{parse_scene, parse_scene_value_in};
    use crate::scene::tests::{base, expect_err};
    use crate::textures::{Channel, Texture, WrapMode};
    use glam::{DVec3, Vec2, Vec3};
    use serde_json::{Value, json};
    use std::path::{Path, PathBuf};
    use std::sync::Arc;

    /// This test's own scratch folder (tests run in parallel).
    fn folder(test: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("lumis-parse-texture-{}-{test}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// A 4 × 3 sRGB PNG of bytes `(20·i, 60·j, 255 − 20·i)`.
    fn write_png(dir: &Path, name: &str) {
        let bytes = (0..3u8)
            .flat_map(|j| (0..4u8).flat_map(move |i| [20 * i, 60 * j, 255 - 20 * i]))
            .collect();
        image::RgbImage::from_raw(4, 3, bytes)
            .unwrap()
            .save(dir.join(name))
            .unwrap();
    }

    /// A 4 × 3 EXR, all `fill` but texel (2, 1).
    fn write_exr(dir: &Path, name: &str, fill: Vec3, bad: Vec3) {
        let mut data = vec![fill; 12];
        data[4 + 2] = bad;
        Image {
            width: 4,
            height: 3,
            data,
        }
        .write(&dir.join(name), 0.0)
        .unwrap();
    }

    fn with_material(m: &str, value: Value) -> Value {
        let mut s = base();
        s["materials"][m] = value;
        s
    }

    fn parse_in(s: &Value, dir: &Path) -> SceneDesc {
        parse_scene_value_in(s, dir).unwrap_or_else(|e| panic!("{e}"))
    }

    #[track_caller]
    fn expect_err_in(s: &Value, dir: &Path, path: &str, fragments: &[&str]) {
        let e = parse_scene_value_in(s, dir).unwrap_err();
        assert_eq!(e.path, path, "wrong path in: {e}");
        for f in fragments {
            assert!(e.message.contains(f), "expected {f:?} in: {e}");
        }
    }

    fn texture(slot: &Option<crate::scene::TextureDesc>) -> &Texture {
        &slot.as_ref().expect("no texture in the slot").texture
    }

    #[test]
    fn bitmap_albedo_parses_with_options_and_mean() {
        let dir = folder("albedo");
        write_png(&dir, "wood.png");
        let s = with_material(
            "white",
            json!({"type": "diffuse", "albedo": {"type": "bitmap", "file": "wood.png",
                   "wrap": "mirror", "uv_scale": [4, 2], "uv_offset": [0.5, 0]}}),
        );
        let d = parse_in(&s, &dir);
        let m = &d.materials[3];
        let Texture::Bitmap(b) = texture(&m.textures.albedo) else {
            panic!("not a bitmap")
        };
        assert_eq!(b.file, dir.join("wood.png"));
        assert_eq!(b.options().wrap, WrapMode::Mirror);
        assert_eq!(b.options().uv.scale, Vec2::new(4.0, 2.0));
        assert_eq!(b.options().uv.offset, Vec2::new(0.5, 0.0));
        assert!(!b.raw);
        // sRGB-decoded: texel (1, 2) was bytes (20, 120, 235).
        let t = b.image().data[2 * 4 + 1];
        let srgb = |v: f64| crate::textures::load::srgb_to_linear(v / 255.0) as f32;
        assert_eq!(t, Vec3::new(srgb(20.0), srgb(120.0), srgb(235.0)));
        // The constant is the mean, for code that ignores textures.
        let MaterialDesc::Diffuse { albedo } = m.material else {
            panic!()
        };
        assert_eq!(albedo, b.mean().as_dvec3());
        assert!(m.textures.reflectance.is_none() && m.textures.alpha.is_none());
        // Untextured materials have no textures.
        assert!(d.materials[..3].iter().all(|m| m.textures.is_empty()));
    }

    #[test]
    fn every_slot_accepts_a_texture_and_writes_back() {
        let dir = folder("slots");
        write_png(&dir, "wood.png");
        write_exr(
            &dir,
            "rough.exr",
            Vec3::splat(0.25),
            Vec3::new(0.1, 0.5, 0.9),
        );
        write_exr(
            &dir,
            "glow.exr",
            Vec3::splat(3.0),
            Vec3::new(0.0, 50.0, 1.0),
        );
        let checker = json!({"type": "checkerboard", "color0": 0.1, "color1": 0.6,
                             "uv_scale": [8, 8]});
        let mut s = base();
        s["materials"] = json!({
            "white": {"type": "diffuse", "albedo": {"type": "checkerboard",
                      "color0": [0.9, 0.9, 0.9], "color1": [0.1, 0.2, 0.3]}},
            "metal": {"type": "conductor", "alpha": {"type": "bitmap", "file": "rough.exr",
                      "channel": "g", "wrap": "clamp"},
                      "reflectance": {"type": "bitmap", "file": "wood.png", "scale": 0.5}},
            "copper": {"type": "conductor", "alpha": checker, "eta": [0.2, 0.92, 1.1],
                       "k": [3.9, 2.45, 2.14]},
            "plastic": {"type": "plastic", "albedo": {"type": "bitmap", "file": "wood.png",
                        "raw": true}, "alpha": {"type": "bitmap", "file": "rough.exr"}},
            "glass": {"type": "dielectric", "alpha": {"type": "checkerboard"}},
        });
        s["shapes"][4]["emission"] =
            json!({"type": "bitmap", "file": "glow.exr", "scale": [1, 2, 0.5]});
        let d = parse_in(&s, &dir);
        let by_name = |n: &str| d.materials.iter().find(|m| m.name == n).unwrap();

        let metal = by_name("metal");
        let alpha = texture(&metal.textures.alpha);
        assert_eq!(alpha.channel(), Channel::G);
        let MaterialDesc::Conductor {
            alpha: a, fresnel, ..
        } = &metal.material
        else {
            panic!()
        };
        assert_eq!(*a, alpha.mean_scalar() as f64);
        let FresnelDesc::Reflectance(r) = fresnel else {
            panic!()
        };
        assert_eq!(*r, texture(&metal.textures.reflectance).mean().as_dvec3());
        // Clamp over the unit square averages the texels: 11 × 0.25 and one 0.5 in G.
        assert!((a - (11.0 * 0.25 + 0.5) / 12.0).abs() < 1e-6, "{a}");

        let copper = by_name("copper");
        let MaterialDesc::Conductor { alpha: a, .. } = copper.material else {
            panic!()
        };
        assert!(
            (a - 0.35).abs() < 1e-6,
            "an even checkerboard averages its colours: {a}"
        );
        let plastic = by_name("plastic");
        let Texture::Bitmap(b) = texture(&plastic.textures.albedo) else {
            panic!()
        };
        assert!(b.raw);
        assert_eq!(b.image().data[1], Vec3::new(20.0, 0.0, 235.0) / 255.0);
        assert!(plastic.textures.alpha.is_some());
        let glass = by_name("glass");
        let MaterialDesc::Dielectric { alpha: a, .. } = glass.material else {
            panic!()
        };
        assert!(
            (a - 0.3).abs() < 1e-6,
            "Mitsuba's default colours 0.4 and 0.2: {a}"
        );

        let sphere = &d.shapes[4];
        let e = texture(&sphere.emission_texture);
        assert_eq!(sphere.emission, e.mean().as_dvec3());
        assert_eq!(e.max(), Vec3::new(3.0, 100.0, 1.5));

        // Written back and read again: the same description.
        let again = parse_scene_value_in(&d.to_json(), Path::new("")).unwrap();
        assert_eq!(again.materials, d.materials);
        assert_eq!(again.shapes, d.shapes);
        let text = d.to_json().to_string();
        assert_eq!(parse_scene(&text).unwrap().materials, d.materials);
    }

    #[test]
    fn identical_files_are_loaded_once() {
        let dir = folder("sharing");
        write_png(&dir, "wood.png");
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        let bitmap = |file: &str, raw: bool| json!({"type": "bitmap", "file": file, "raw": raw});
        let mut s = base();
        s["materials"]["white"] = json!({"type": "diffuse", "albedo": bitmap("wood.png", false)});
        s["materials"]["plastic"] = json!({"type": "plastic",
            "albedo": bitmap("sub/../wood.png", false), "alpha": bitmap("./wood.png", true)});
        s["shapes"][4]["emission"] = bitmap("wood.png", false);
        let d = parse_in(&s, &dir);
        let image = |t: &Texture| match t {
            Texture::Bitmap(b) => b.image().clone(),
            _ => panic!("not a bitmap"),
        };
        let white = image(texture(&d.materials[3].textures.albedo));
        let plastic = &d.materials[2].textures;
        let emission = image(texture(&d.shapes[4].emission_texture));
        assert!(Arc::ptr_eq(&white, &image(texture(&plastic.albedo))));
        assert!(Arc::ptr_eq(&white, &emission));
        // Raw texels are other texels.
        let raw = image(texture(&plastic.alpha));
        assert!(!Arc::ptr_eq(&white, &raw));
        assert_ne!(*white, *raw);
    }

    #[test]
    fn bad_textures_name_the_path_and_the_file() {
        let dir = folder("errors");
        write_png(&dir, "wood.png");
        let albedo = |t: Value| with_material("white", json!({"type": "diffuse", "albedo": t}));
        let p = "materials.white.albedo";
        let bitmap = |extra: Value| {
            let mut t = json!({"type": "bitmap", "file": "wood.png"});
            t.as_object_mut()
                .unwrap()
                .extend(extra.as_object().unwrap().clone());
            albedo(t)
        };
        let cases = [
            (
                bitmap(json!({"wrap": "tile"})),
                "wrap",
                "unknown wrap mode `tile`",
            ),
            (bitmap(json!({"wrap": 1})), "wrap", "expected a string"),
            (
                bitmap(json!({"filter": "nearest"})),
                "filter",
                "unknown key `filter`",
            ),
            (
                bitmap(json!({"channel": "g"})),
                "channel",
                "only for a scalar",
            ),
            (bitmap(json!({"raw": "yes"})), "raw", "true or false"),
            (
                bitmap(json!({"uv_scale": [1, 2, 3]})),
                "uv_scale",
                "expected 2 numbers",
            ),
            (
                bitmap(json!({"uv_offset": [0, "1"]})),
                "uv_offset[1]",
                "expected a number",
            ),
            (
                bitmap(json!({"scale": [1, -1, 1]})),
                "scale[1]",
                "must not be negative",
            ),
            (
                bitmap(json!({"file": "no_such.png"})),
                "file",
                "no_such.png",
            ),
            (bitmap(json!({"file": ""})), "file", "empty"),
            (
                bitmap(json!({"file": "wood.tga"})),
                "file",
                "unsupported texture format",
            ),
            (
                albedo(json!({"file": "wood.png"})),
                "type",
                "missing required key",
            ),
            (
                albedo(json!({"type": "noise"})),
                "type",
                "unknown texture type `noise`",
            ),
            (
                albedo(json!({"type": "checkerboard", "color0": [0.5, 1.5, 0.5]})),
                "color0[1]",
                "outside [0, 1]",
            ),
            (
                albedo(json!({"type": "checkerboard", "color1": -0.5})),
                "color1",
                "outside [0, 1]",
            ),
            (
                albedo(json!({"type": "checkerboard", "file": "wood.png"})),
                "file",
                "unknown key",
            ),
        ];
        for (s, key, fragment) in cases {
            expect_err_in(&s, &dir, &format!("{p}.{key}"), &[fragment]);
        }
        // A missing file names the file as resolved against the scene's folder.
        let s = bitmap(json!({"file": "no_such.png"}));
        let e = parse_scene_value_in(&s, &dir).unwrap_err();
        assert!(
            e.message
                .contains(&dir.join("no_such.png").display().to_string()),
            "{e}"
        );
        // Texture-free errors still come out of the text parser at the same paths.
        expect_err(
            &albedo(json!({"type": "noise"})),
            &format!("{p}.type"),
            "unknown",
        );
        // An unreadable image: one error, the path and the file.
        std::fs::write(dir.join("broken.png"), b"\x89PNG not really").unwrap();
        expect_err_in(
            &bitmap(json!({"file": "broken.png"})),
            &dir,
            &format!("{p}.file"),
            &["broken.png"],
        );
        // The constant syntax keeps its messages.
        expect_err(
            &albedo(json!([0.5, 2, 0.5])),
            &format!("{p}[1]"),
            "outside [0, 1]",
        );
    }

    /// A file, its fill and its bad texel (2, 1), the material, the error path ("" = accepted)
    /// and what the message names.
    type TexelCase = (
        &'static str,
        Vec3,
        Vec3,
        Value,
        &'static str,
        &'static [&'static str],
    );

    /// EXR texels outside the slot's range are rejected with file and pixel, by use.
    #[test]
    fn out_of_range_texels_are_named_by_pixel() {
        let dir = folder("texels");
        let cases: [TexelCase; 7] = [
            (
                "bright.exr",
                Vec3::splat(0.5),
                Vec3::new(0.5, 1.5, 0.5),
                json!({"type": "diffuse", "albedo": {"type": "bitmap", "file": "bright.exr"}}),
                "materials.white.albedo.file",
                &[
                    "pixel (column 2, row 1) channel 1 = 1.5",
                    "outside [0, 1]",
                    "albedo",
                ],
            ),
            (
                "nan.exr",
                Vec3::splat(0.5),
                Vec3::new(f32::NAN, 0.5, 0.5),
                json!({"type": "diffuse", "albedo": {"type": "bitmap", "file": "nan.exr"}}),
                "materials.white.albedo.file",
                &["pixel (column 2, row 1) channel 0", "NaN"],
            ),
            (
                "refl.exr",
                Vec3::splat(0.5),
                Vec3::new(0.5, 0.5, -0.25),
                json!({"type": "conductor", "alpha": 0,
                       "reflectance": {"type": "bitmap", "file": "refl.exr"}}),
                "materials.white.reflectance.file",
                &["channel 2 = -0.25", "a reflectance"],
            ),
            (
                "alpha.exr",
                Vec3::splat(0.5),
                Vec3::new(0.5, 1.25, 0.5),
                json!({"type": "conductor", "reflectance": [1, 1, 1],
                       "alpha": {"type": "bitmap", "file": "alpha.exr", "channel": "g"}}),
                "materials.white.alpha.file",
                &[
                    "pixel (column 2, row 1) g = 1.25",
                    "alpha must lie in [0, 1]",
                ],
            ),
            (
                "alpha.exr",
                Vec3::splat(0.5),
                Vec3::new(0.5, 1.25, 0.5),
                json!({"type": "conductor", "reflectance": [1, 1, 1],
                       "alpha": {"type": "bitmap", "file": "alpha.exr", "channel": "b"}}),
                "",
                &[],
            ),
            (
                "lum.exr",
                Vec3::splat(0.5),
                Vec3::new(0.0, 2.0, 0.0),
                json!({"type": "plastic", "albedo": [0, 0, 0],
                       "alpha": {"type": "bitmap", "file": "lum.exr"}}),
                "materials.white.alpha.file",
                &["luminance = 1.430", "alpha"],
            ),
            (
                "scaled.exr",
                Vec3::splat(0.5),
                Vec3::splat(0.6),
                json!({"type": "diffuse",
                       "albedo": {"type": "bitmap", "file": "scaled.exr", "scale": 2}}),
                "materials.white.albedo.file",
                &["channel 0 = 1.2", "once scaled"],
            ),
        ];
        for (file, fill, bad, material, path, fragments) in cases {
            write_exr(&dir, file, fill, bad);
            let s = with_material("white", material);
            if path.is_empty() {
                // The same texel is fine where the slot reads another channel.
                parse_in(&s, &dir);
            } else {
                let mut all = fragments.to_vec();
                all.push(file);
                expect_err_in(&s, &dir, path, &all);
            }
        }
        // Emission: non-negative and finite, any size up to 1e30.
        write_exr(&dir, "dark.exr", Vec3::ONE, Vec3::new(1.0, -1.0, 1.0));
        let mut s = base();
        s["shapes"][4]["emission"] = json!({"type": "bitmap", "file": "dark.exr"});
        expect_err_in(
            &s,
            &dir,
            "shapes[4].emission.file",
            &["channel 1 = -1", "negative"],
        );
        write_exr(&dir, "hot.exr", Vec3::ONE, Vec3::new(1.0, 1e20, 1.0));
        s["shapes"][4]["emission"] = json!({"type": "bitmap", "file": "hot.exr"});
        assert!(parse_scene_value_in(&s, &dir).is_ok());
        s["shapes"][4]["emission"] = json!({"type": "bitmap", "file": "hot.exr", "scale": 1e11});
        expect_err_in(&s, &dir, "shapes[4].emission.file", &["too large"]);
        s["shapes"][4]["emission"] = json!({"type": "checkerboard", "color0": [1, -2, 1]});
        expect_err_in(&s, &dir, "shapes[4].emission.color0[1]", &["negative"]);
    }

    /// A shape whose emission texture is black over the unit square but not elsewhere still
    /// counts as an emitter (its degenerate triangles are an error, not dropped).
    #[test]
    fn emission_texture_decides_emitting() {
        let mut s = base();
        s["shapes"][2] = json!({"type": "triangles", "positions": [[0, 0, 0], [1, 0, 0], [2, 0, 0]],
            "indices": [[0, 1, 2]],
            "emission": {"type": "checkerboard", "color0": 0, "color1": 5, "uv_scale": [0, 0]}});
        let e = crate::scene::parse::parse_scene_value(&s).unwrap_err();
        assert!(
            e.message.contains("zero area") || e.message.contains("degenerate"),
            "{e}"
        );
        s["shapes"][2]["emission"] = json!({"type": "checkerboard", "color0": 0, "color1": 0});
        let d = crate::scene::parse::parse_scene_value(&s).unwrap();
        assert_eq!(d.shapes[2].emission, DVec3::ZERO);
        assert!(
            !d.warnings.is_empty(),
            "a black degenerate triangle is dropped with a warning"
        );
    }
}
