//! The validated scene description: plain data in `f64`, exactly what the file says (with
//! defaults filled in), before any render-ready structures are built from it.
//!
//! Everything in a [`SceneDesc`] has passed every rule of the format, so builders may rely on
//! it: finite numbers, positive radii, unit disk normals, valid polygons, in-range indices.

use crate::image_io::Image;
pub use crate::materials::Distribution;
use crate::textures::{Channel, Texture, UvTransform, WrapMode};
use glam::{DVec3, Vec2, Vec3};
use serde_json::{Map, Value, json};
use std::path::PathBuf;
use std::sync::Arc;

/// A whole scene.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneDesc {
    /// The pinhole camera.
    pub camera: CameraDesc,
    /// Longest path in vertices, Mitsuba's convention: `-1` = unlimited, otherwise ≥ 1.
    pub max_depth: i32,
    /// Emitters (shapes and the background) are not seen directly by camera rays, only through
    /// the light they cast (Mitsuba's `hide_emitters`).
    pub hide_emitters: bool,
    /// Radiance from every direction that hits nothing.
    pub background: BackgroundDesc,
    /// All materials, sorted by name; shapes refer to them by index.
    pub materials: Vec<NamedMaterial>,
    /// All shapes, in file order.
    pub shapes: Vec<ShapeDesc>,
    /// The lights that are neither shapes nor the background (point, spot, directional,
    /// projector: scene format Version 3's `lights`), in file order.
    pub lights: Vec<LightDesc>,
    /// Things that were accepted but look wrong (e.g. dropped degenerate triangles).
    pub warnings: Vec<String>,
    /// The mesh attributes that `mesh_attribute` textures read, in the order of their slots
    /// ([`crate::textures::MeshAttributeTexture::slot`]); empty in most scenes.
    pub mesh_attributes: Vec<String>,
}

/// What a ray that hits nothing sees.
#[derive(Clone, Debug, PartialEq)]
pub enum BackgroundDesc {
    /// The same radiance from every direction (black: no background light).
    Constant(DVec3),
    /// A latitude-longitude environment map.
    Envmap(EnvmapDesc),
}

/// An environment map, loaded and checked: finite, non-negative texels.
#[derive(Clone, Debug, PartialEq)]
pub struct EnvmapDesc {
    /// The EXR file, resolved against the scene file's folder.
    pub file: PathBuf,
    /// Its pixels, row 0 at the top (the zenith).
    pub image: Arc<Image>,
    /// Radiance multiplier, ≥ 0.
    pub scale: f64,
    /// Rotation of the map about +y, in degrees (the box's convention), applied after
    /// [`EnvmapDesc::rotation`].
    pub rotate_y_deg: f64,
    /// Any rotation from the map's frame to the world (a proper rotation, orthonormalised where
    /// it was read), applied before `rotate_y_deg`; `None` is the identity (scene format
    /// Version 3's `rotation`; Mitsuba's `to_world`).
    pub rotation: Option<glam::DMat3>,
}

/// A camera looking from `from` towards `to`.
#[derive(Clone, Debug, PartialEq)]
pub struct CameraDesc {
    /// Eye position (the lens centre; an orthographic camera's film centre).
    pub from: DVec3,
    /// A point the camera looks at; never equal to `from`.
    pub to: DVec3,
    /// Up hint; never parallel to `to - from`.
    pub up: DVec3,
    /// The projection (`"type"`) and its parameters.
    pub projection: ProjectionDesc,
    /// Mitsuba's principal point offset in film widths and heights (`principal_point_offset`,
    /// default `[0, 0]`).
    pub principal_point_offset: [f64; 2],
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// The pixel filter (`"filter"`, a lumis addition; default box).
    pub filter: FilterDesc,
}

/// The camera's projection (`camera.type`, scene format Version 3; Mitsuba's three sensors),
/// rendered as [`crate::camera::Projection`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ProjectionDesc {
    /// `"perspective"` (the default): a pinhole.
    Perspective {
        /// Vertical field of view in degrees, in (0, 180).
        vfov_deg: f64,
    },
    /// `"thinlens"`: a pinhole's view through a thin lens (depth of field).
    ThinLens {
        /// Vertical field of view in degrees, in (0, 180).
        vfov_deg: f64,
        /// Lens radius in world units, ≥ 0 (0: the pinhole's image).
        aperture_radius: f64,
        /// Distance of the plane in focus along the view direction, > 0.
        focus_distance: f64,
    },
    /// `"orthographic"`: parallel rays; the film spans `view_size` world units.
    Orthographic {
        /// Film width and height in world units, each > 0.
        view_size: [f64; 2],
    },
}

impl CameraDesc {
    /// The vertical field of view in degrees; `None` for an orthographic camera.
    pub fn vfov_deg(&self) -> Option<f64> {
        match self.projection {
            ProjectionDesc::Perspective { vfov_deg }
            | ProjectionDesc::ThinLens { vfov_deg, .. } => Some(vfov_deg),
            ProjectionDesc::Orthographic { .. } => None,
        }
    }

    /// The file format's `camera` object.
    pub fn to_json(&self) -> Value {
        let mut v = json!({
            "from": vec3(self.from), "to": vec3(self.to), "up": vec3(self.up),
            "width": self.width, "height": self.height,
            "filter": self.filter.to_json(),
        });
        if self.principal_point_offset != [0.0; 2] {
            v["principal_point_offset"] = json!(self.principal_point_offset);
        }
        match self.projection {
            ProjectionDesc::Perspective { vfov_deg } => v["vfov_deg"] = json!(vfov_deg),
            ProjectionDesc::ThinLens {
                vfov_deg,
                aperture_radius,
                focus_distance,
            } => {
                v["type"] = json!("thinlens");
                v["vfov_deg"] = json!(vfov_deg);
                v["aperture_radius"] = json!(aperture_radius);
                v["focus_distance"] = json!(focus_distance);
            }
            ProjectionDesc::Orthographic { view_size } => {
                v["type"] = json!("orthographic");
                v["view_size"] = json!(view_size);
            }
        }
        v
    }
}

/// The camera's pixel filter (`camera.filter`), rendered as [`crate::camera::PixelFilter`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum FilterDesc {
    /// `{"type": "box"}`: uniform over the pixel.
    #[default]
    Box,
    /// `{"type": "gaussian", "stddev", "radius"}`: Mitsuba's windowed Gaussian. Validated:
    /// `0 < stddev ≤ radius ≤` [`crate::camera::filter::MAX_FILTER_RADIUS`].
    Gaussian {
        /// Standard deviation in pixels.
        stddev: f64,
        /// Support half-width in pixels.
        radius: f64,
    },
    /// `{"type": "tent", "radius"}`: Mitsuba's tent, `max(0, 1 − |x|/radius)`. Validated:
    /// `0 < radius ≤` [`crate::camera::filter::MAX_FILTER_RADIUS`].
    Tent {
        /// Support half-width in pixels (default 1, Mitsuba's).
        radius: f64,
    },
    /// `{"type": "lanczos", "lobes"}`: Mitsuba's windowed sinc, radius `lobes` (default 3).
    /// Validated: `1 ≤ lobes ≤` [`crate::camera::filter::MAX_FILTER_RADIUS`], and a positive
    /// integral on every pixel's part of the film.
    Lanczos {
        /// Side lobes (an integer).
        lobes: u32,
    },
    /// `{"type": "mitchell", "b", "c"}`: Mitsuba's Mitchell–Netravali cubic, radius 2 (defaults
    /// ⅓, ⅓; Mitsuba's `B`, `C`). Validated: finite, and a positive integral on every pixel's
    /// part of the film.
    Mitchell {
        /// B.
        b: f64,
        /// C.
        c: f64,
    },
    /// `{"type": "catmullrom"}`: Mitsuba's Catmull–Rom, the Mitchell cubic with B = 0, C = ½.
    CatmullRom,
}

impl FilterDesc {
    /// The render-ready filter.
    pub fn filter(&self) -> crate::camera::PixelFilter {
        match *self {
            FilterDesc::Box => crate::camera::PixelFilter::Box,
            FilterDesc::Gaussian { stddev, radius } => crate::camera::PixelFilter::Gaussian {
                stddev: stddev as f32,
                radius: radius as f32,
            },
            FilterDesc::Tent { radius } => crate::camera::PixelFilter::Tent {
                radius: radius as f32,
            },
            FilterDesc::Lanczos { lobes } => crate::camera::PixelFilter::Lanczos { lobes },
            FilterDesc::Mitchell { b, c } => {
                crate::camera::PixelFilter::mitchell(b as f32, c as f32)
            }
            FilterDesc::CatmullRom => crate::camera::PixelFilter::mitchell(0.0, 0.5),
        }
    }

    /// The file format's `filter` object.
    pub fn to_json(&self) -> Value {
        match *self {
            FilterDesc::Box => json!({"type": "box"}),
            FilterDesc::Gaussian { stddev, radius } => {
                json!({"type": "gaussian", "stddev": stddev, "radius": radius})
            }
            FilterDesc::Tent { radius } => json!({"type": "tent", "radius": radius}),
            FilterDesc::Lanczos { lobes } => json!({"type": "lanczos", "lobes": lobes}),
            FilterDesc::Mitchell { b, c } => json!({"type": "mitchell", "b": b, "c": c}),
            FilterDesc::CatmullRom => json!({"type": "catmullrom"}),
        }
    }
}

/// A material with the name it has in the file.
#[derive(Clone, Debug, PartialEq)]
pub struct NamedMaterial {
    /// The key in the file's `materials` map.
    pub name: String,
    /// The BSDF.
    pub material: MaterialDesc,
    /// Whether the back side sees the same BSDF with the normal flipped (default) or is black.
    pub two_sided: bool,
    /// The parameters given as textures; an untextured material has none.
    pub textures: MaterialTextures,
    /// Its normal map (`"normal_map"`; never on a mix).
    pub normal_map: Option<NormalMapDesc>,
    /// Its opacity (`"opacity"`, Mitsuba's `mask`): a scalar in [0, 1], constant or textured;
    /// `None` is opaque ([`crate::materials::mask`]). Never on a mix's materials (on the mix
    /// itself it is), never on an emitter's.
    pub opacity: Option<TextureDesc>,
    /// `Some` for a mix of two other materials (`{"type": "mix"}`). `material` then holds the
    /// description of the material its mean weight favours (through nested mixes: the second
    /// at a weight ≥ ½), as a texture's mean stands in for it, for code that reads one BSDF;
    /// `textures` is empty and `two_sided` is its materials' (which agree).
    pub mix: Option<MixDesc>,
    /// `Some([front, back])` for a two-sided pair (`{"type": "two_sided"}`, Mitsuba's `twosided`
    /// with two BSDFs, [`crate::materials::two_sided`]): indices into [`SceneDesc::materials`],
    /// neither transmitting, never the pair itself. `material` then holds the front's
    /// description (for code that reads one BSDF), `textures` is empty and `two_sided` true.
    pub sides: Option<[usize; 2]>,
}

impl NamedMaterial {
    /// The materials this one resolves to at a hit (a mix's two, a pair's front and back), or
    /// `None` for a BSDF of its own.
    pub fn parts(&self) -> Option<[usize; 2]> {
        self.mix.as_ref().map(|m| m.materials).or(self.sides)
    }
}

/// A material's normal map (Mitsuba's `normalmap`, [`crate::materials::normal_map`]).
#[derive(Clone, Debug, PartialEq)]
pub struct NormalMapDesc {
    /// The encoded normals `(n + 1)/2`, every channel in [0, 1].
    pub texture: TextureDesc,
    /// Mitsuba's `flip_invalid_normals` (default true).
    pub flip_invalid_normals: bool,
    /// Mitsuba's `use_shadowing_function` (default true).
    pub shadowing: bool,
    /// `Some(scale)` for a bump map (`"bump_map"`, Mitsuba's `bumpmap`): the texture is a height
    /// field, its gradient times `scale` tilts the normal ([`crate::materials::bump_map`]).
    pub height_scale: Option<f64>,
}

impl NormalMapDesc {
    /// The renderer's normal map.
    pub fn normal_map(&self) -> crate::materials::normal_map::NormalMap {
        crate::materials::normal_map::NormalMap {
            texture: self.texture.texture.clone(),
            flip_invalid_normals: self.flip_invalid_normals,
            shadowing: self.shadowing,
            height_scale: self.height_scale.map(|s| s as f32),
        }
    }
}

/// A mix of two materials (pbrt-v4's `MixMaterial`): each shading point sees one of them, the
/// second with probability `weight` ([`crate::materials::mix`]).
#[derive(Clone, Debug, PartialEq)]
pub struct MixDesc {
    /// Indices into [`SceneDesc::materials`]; never the mix itself, directly or through other
    /// mixes.
    pub materials: [usize; 2],
    /// The probability of the second, in [0, 1]; with a texture, its mean.
    pub weight: f64,
    /// The weight as a scalar texture (every scalar texel in [0, 1]), if given as one.
    pub weight_texture: Option<TextureDesc>,
    /// `"model": "mitsuba"`: Mitsuba 3.9.1's `blendbsdf` estimator, which weighs a delta lobe's
    /// sample against the other part's density ([`crate::materials::mix::blend_delta_weight`]);
    /// the same image as the mix but where a part has a delta lobe.
    pub mitsuba: bool,
}

/// The textured parameters of a material, one `Option` per slot. Where a slot has a texture,
/// the constant field of [`MaterialDesc`] holds the texture's mean over the unit uv square
/// ([`TextureDesc::mean_color`], [`TextureDesc::mean_scalar`]), so that code which ignores
/// textures still sees a sensible value; the texture is what renders.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MaterialTextures {
    /// `albedo` of a diffuse or a plastic material (every texel in [0, 1]).
    pub albedo: Option<TextureDesc>,
    /// `reflectance` of a conductor (every texel in [0, 1]); never with `eta`/`k`.
    pub reflectance: Option<TextureDesc>,
    /// GGX `alpha` of a conductor, plastic or dielectric, read by
    /// [`crate::textures::Texture::eval_scalar`] (every scalar texel in [0, 1]); α_u where
    /// `alpha_v` is set.
    pub alpha: Option<TextureDesc>,
    /// α_v of a conductor or dielectric whose `alpha` is a pair with a texture in it (then
    /// `alpha` holds α_u, a number of the pair as a constant texture).
    pub alpha_v: Option<TextureDesc>,
    /// A principled's scalars, in [`crate::materials::principled::PrincipledParam::ALL`]'s order,
    /// a thin principled's in [`crate::materials::principled_thin::ThinParam::ALL`]'s, or a glTF
    /// material's in [`crate::materials::gltf_pbr::GltfParam::ALL`]'s (the base colour of each is
    /// `albedo`).
    pub principled: [Option<TextureDesc>; 10],
}

impl MaterialTextures {
    /// Whether no slot has a texture.
    pub fn is_empty(&self) -> bool {
        self.albedo.is_none()
            && self.reflectance.is_none()
            && self.alpha.is_none()
            && self.alpha_v.is_none()
            && self.principled.iter().all(Option::is_none)
    }
}

/// A texture in a texturable slot, loaded and checked for that slot's range (texels of a
/// bitmap are linear; the file and options are kept for messages and writing the scene back).
#[derive(Clone, Debug, PartialEq)]
pub struct TextureDesc {
    /// The texture, ready to evaluate.
    pub texture: Texture,
}

impl TextureDesc {
    /// The mean over the unit uv square, as a colour (the constant a texture slot stands in for).
    pub fn mean_color(&self) -> DVec3 {
        self.texture.mean().as_dvec3()
    }

    /// The mean of the scalar a scalar slot reads.
    pub fn mean_scalar(&self) -> f64 {
        self.texture.mean_scalar() as f64
    }

    /// The texture in the scene format.
    pub fn to_json(&self) -> Value {
        let uv_keys = |obj: &mut Value, uv: &UvTransform| {
            if uv.scale != Vec2::ONE {
                obj["uv_scale"] = json!([uv.scale.x, uv.scale.y]);
            }
            if uv.offset != Vec2::ZERO {
                obj["uv_offset"] = json!([uv.offset.x, uv.offset.y]);
            }
        };
        let color = |c: Vec3| json!([c.x, c.y, c.z]);
        match &self.texture {
            Texture::Constant(c) => color(*c),
            Texture::Bitmap(b) => {
                let o = b.options();
                let mut obj = json!({"type": "bitmap", "file": b.file.to_string_lossy()});
                if o.wrap != WrapMode::Repeat {
                    obj["wrap"] = json!(o.wrap.name());
                }
                if b.raw {
                    obj["raw"] = json!(true);
                }
                uv_keys(&mut obj, &o.uv);
                if o.scale != Vec3::ONE {
                    obj["scale"] = color(o.scale);
                }
                if o.channel != Channel::Luminance {
                    obj["channel"] = json!(o.channel.name());
                }
                obj
            }
            Texture::Checkerboard(c) => {
                let mut obj = json!({
                    "type": "checkerboard", "color0": color(c.color0), "color1": color(c.color1),
                });
                uv_keys(&mut obj, &c.uv);
                obj
            }
            Texture::MeshAttribute(m) => {
                let mut obj = json!({"type": "mesh_attribute", "name": m.name});
                if m.scale != 1.0 {
                    obj["scale"] = json!(m.scale);
                }
                obj
            }
        }
    }
}

/// A BSDF and its parameters.
#[derive(Clone, Debug, PartialEq)]
pub enum MaterialDesc {
    /// Lambertian reflection, `albedo / π`; albedo in [0, 1].
    Diffuse {
        /// Reflectance per channel.
        albedo: DVec3,
    },
    /// Microfacet conductor; `alpha == 0` is a perfect mirror.
    Conductor {
        /// Roughness α (not squared), in [0, 1]; α_u (along ∂p/∂u) where `alpha_v` is given.
        alpha: f64,
        /// α_v (along the second tangent), in [0, 1], for anisotropic roughness; `None`:
        /// isotropic.
        alpha_v: Option<f64>,
        /// The microfacet distribution of a rough conductor.
        distribution: Distribution,
        /// How the Fresnel term is given.
        fresnel: FresnelDesc,
    },
    /// Lambertian base under a dielectric coating: lumis' (GGX, Schlick Fresnel, energy
    /// conserving) or Mitsuba's coupling (`model`).
    Plastic {
        /// Base reflectance, in [0, 1].
        albedo: DVec3,
        /// Roughness α of the coating, in [0, 1].
        alpha: f64,
        /// Index of refraction of the coating, > 1.
        ior: f64,
        /// Tint of the specular reflection, in [0, 1].
        specular: DVec3,
        /// How the base is coupled to the coat.
        model: PlasticModel,
    },
    /// A boundary between index 1 (the side the normal points to) and `ior`; smooth at α = 0,
    /// else rough (Walter et al. 2007). Never two-sided.
    Dielectric {
        /// Index of refraction of the inside, in (0, 10], ≠ 1.
        ior: f64,
        /// Roughness α, in [0, 1]; α_u where `alpha_v` is given.
        alpha: f64,
        /// α_v for anisotropic roughness; `None`: isotropic.
        alpha_v: Option<f64>,
        /// The microfacet distribution of a rough interface.
        distribution: Distribution,
    },
    /// A thin sheet of index `ior` (Mitsuba's `thindielectric`): mirror reflection or straight
    /// transmission. The same from both sides, so it has no `two_sided`.
    ThinDielectric {
        /// Index of refraction of the sheet, in (0, 10].
        ior: f64,
    },
    /// Mitsuba's principled BSDF (`materials/principled.rs`).
    Principled(PrincipledDesc),
    /// Mitsuba's thin principled BSDF (`materials/principled_thin.rs`): the same from both
    /// sides, so it has no `two_sided`.
    PrincipledThin(PrincipledThinDesc),
    /// glTF 2.0's metallic-roughness material (`materials/gltf_pbr.rs`).
    GltfPbr(GltfPbrDesc),
}

/// glTF's metallic-roughness material's parameters (`scene/parse_gltf_pbr.rs`).
#[derive(Clone, Debug, PartialEq)]
pub struct GltfPbrDesc {
    /// Base colour, in [0, 1].
    pub base_color: DVec3,
    /// The scalars in [`crate::materials::gltf_pbr::GltfParam::ALL`]'s order (roughness,
    /// metallic), each in [0, 1].
    pub scalars: [f64; 2],
    /// The dielectric's index of refraction, finite and ≥ 1.
    pub ior: f64,
    /// `KHR_materials_specular`'s factor, in [0, 1].
    pub specular: f64,
    /// `KHR_materials_specular`'s colour factor, each component finite and ≥ 0.
    pub specular_color: DVec3,
}

impl Default for GltfPbrDesc {
    /// glTF's defaults.
    fn default() -> Self {
        let p = crate::materials::GltfPbr::default();
        GltfPbrDesc {
            base_color: p.base_color.as_dvec3(),
            scalars: crate::materials::gltf_pbr::GltfParam::ALL.map(|k| k.get(&p) as f64),
            ior: p.ior as f64,
            specular: p.specular as f64,
            specular_color: p.specular_color.as_dvec3(),
        }
    }
}

impl GltfPbrDesc {
    /// The material it describes.
    pub fn material(&self) -> crate::materials::GltfPbr {
        let mut p = crate::materials::GltfPbr {
            base_color: self.base_color.as_vec3(),
            ior: self.ior as f32,
            specular: self.specular as f32,
            specular_color: self.specular_color.as_vec3(),
            ..Default::default()
        };
        for (k, v) in crate::materials::gltf_pbr::GltfParam::ALL
            .into_iter()
            .zip(self.scalars)
        {
            k.set(&mut p, v as f32);
        }
        p
    }
}

/// A thin principled BSDF's parameters (`scene/parse_principled_thin.rs`).
#[derive(Clone, Debug, PartialEq)]
pub struct PrincipledThinDesc {
    /// Base colour, in [0, 1].
    pub base_color: DVec3,
    /// The scalars in [`crate::materials::principled_thin::ThinParam::ALL`]'s order, each in its
    /// range ([`crate::materials::principled_thin::ThinParam::range`]).
    pub scalars: [f64; 9],
    /// Sampling rates in [`crate::materials::principled_thin::ThinRates::KEYS`]' order (each ≥ 0).
    pub rates: [f64; 4],
}

impl Default for PrincipledThinDesc {
    /// Mitsuba's defaults.
    fn default() -> Self {
        let p = crate::materials::PrincipledThin::default();
        let params = crate::materials::principled_thin::ThinParam::ALL;
        PrincipledThinDesc {
            base_color: p.base_color.as_dvec3(),
            scalars: params.map(|k| k.get(&p) as f64),
            rates: p.rates.to_array().map(f64::from),
        }
    }
}

impl PrincipledThinDesc {
    /// The material it describes.
    pub fn material(&self) -> crate::materials::PrincipledThin {
        let mut p = crate::materials::PrincipledThin {
            base_color: self.base_color.as_vec3(),
            rates: crate::materials::principled_thin::ThinRates::from_array(
                self.rates.map(|r| r as f32),
            ),
            ..Default::default()
        };
        for (k, v) in crate::materials::principled_thin::ThinParam::ALL
            .into_iter()
            .zip(self.scalars)
        {
            k.set(&mut p, v as f32);
        }
        p
    }
}

/// A principled BSDF's parameters, Mitsuba's rules applied (`scene/parse_principled.rs`).
#[derive(Clone, Debug, PartialEq)]
pub struct PrincipledDesc {
    /// Base colour, in [0, 1].
    pub base_color: DVec3,
    /// The scalars in [`crate::materials::principled::PrincipledParam::ALL`]'s order, each in
    /// [0, 1].
    pub scalars: [f64; 10],
    /// Interior over exterior index (> 0; given, or from `specular`).
    pub eta: f64,
    /// Sampling rates: main specular, clearcoat, diffuse (each ≥ 0).
    pub rates: [f64; 3],
    /// Specular transmission (`spec_trans` given as a texture or a number other than 0): the
    /// back side is the inside; never two-sided.
    pub transmission: bool,
}

impl Default for PrincipledDesc {
    /// Mitsuba's defaults.
    fn default() -> Self {
        let p = crate::materials::Principled::default();
        let params = crate::materials::principled::PrincipledParam::ALL;
        PrincipledDesc {
            base_color: p.base_color.as_dvec3(),
            scalars: params.map(|k| k.get(&p) as f64),
            eta: p.eta as f64,
            rates: [1.0; 3],
            transmission: false,
        }
    }
}

impl PrincipledDesc {
    /// The material it describes.
    pub fn material(&self) -> crate::materials::Principled {
        let mut p = crate::materials::Principled {
            base_color: self.base_color.as_vec3(),
            eta: self.eta as f32,
            rates: crate::materials::principled::SamplingRates {
                specular: self.rates[0] as f32,
                clearcoat: self.rates[1] as f32,
                diffuse: self.rates[2] as f32,
            },
            transmission: self.transmission,
            ..Default::default()
        };
        for (k, v) in crate::materials::principled::PrincipledParam::ALL
            .into_iter()
            .zip(self.scalars)
        {
            k.set(&mut p, v as f32);
        }
        p
    }
}

impl MaterialDesc {
    /// True for a material light passes through: its two sides are its two media (or, for a
    /// thin sheet, alike), so `two_sided` does not apply.
    pub fn transmits(&self) -> bool {
        match self {
            MaterialDesc::Dielectric { .. }
            | MaterialDesc::ThinDielectric { .. }
            | MaterialDesc::PrincipledThin(_) => true,
            MaterialDesc::Principled(p) => p.transmission,
            _ => false,
        }
    }
}

/// How a plastic couples its base to its coat (`materials/plastic.rs`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum PlasticModel {
    /// lumis': GGX coat, Schlick Fresnel, energy conserving.
    #[default]
    Lumis,
    /// Mitsuba 3's `plastic`/`roughplastic` (`materials/plastic_mitsuba.rs`).
    Mitsuba {
        /// The coat's microfacets.
        distribution: Distribution,
        /// Whether the base's internal bounces tint by its albedo.
        nonlinear: bool,
    },
}

/// A conductor's Fresnel term.
#[derive(Clone, Debug, PartialEq)]
pub enum FresnelDesc {
    /// Exact conductor Fresnel from the complex index of refraction `eta + i k` per channel,
    /// times `tint`.
    Complex {
        /// Real part, > 0.
        eta: DVec3,
        /// Imaginary part (absorption), ≥ 0.
        k: DVec3,
        /// Factor on the Fresnel term (`specular`), each channel in [0, 1]; 1 for a metal.
        tint: DVec3,
    },
    /// Fresnel = this reflectance at every angle, in [0, 1].
    Reflectance(DVec3),
}

/// A light of `lights`: Mitsuba 3.9.1's delta emitters (`renderer/src/lights/point.rs`,
/// `spot.rs`, `directional.rs`, `projector.rs` say what each emits).
#[derive(Clone, Debug, PartialEq)]
pub enum LightDesc {
    /// A point light.
    Point {
        /// Where it is.
        position: DVec3,
        /// Radiant intensity per channel, in [0, 1e30].
        intensity: DVec3,
    },
    /// A spot light at `from` aimed at `to`.
    Spot {
        /// Its frame, Mitsuba's `look_at(from, to, up)`.
        frame: LookAt,
        /// Radiant intensity on the axis per channel, in [0, 1e30].
        intensity: DVec3,
        /// Cutoff angle in degrees, in (0, 180] (below 90 with a texture).
        cutoff_angle_deg: f64,
        /// Beam width in degrees, in [0, `cutoff_angle_deg`].
        beam_width_deg: f64,
        /// A texture projected through the cone (texels ≥ 0).
        texture: Option<TextureDesc>,
    },
    /// A directional light.
    Directional {
        /// The unit direction the light travels in.
        direction: DVec3,
        /// Irradiance per channel on a surface facing it, in [0, 1e30].
        irradiance: DVec3,
    },
    /// A projector at `from` aimed at `to`.
    Projector {
        /// Its frame, Mitsuba's `look_at(from, to, up)`.
        frame: LookAt,
        /// Horizontal field of view in degrees, in (0, 180); the vertical one follows from the
        /// image's aspect (1 for a constant).
        fov_x_deg: f64,
        /// The projected irradiance where constant (the texture's mean where textured).
        irradiance: DVec3,
        /// The projected image.
        texture: Option<TextureDesc>,
        /// Multiplier, in [0, 1e30].
        scale: f64,
    },
}

/// A frame given as Mitsuba's `look_at`: at `from`, its axis (+z) towards `to`, +x along
/// `up × axis` (to the left, looking along the axis), +y completing it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LookAt {
    /// The origin.
    pub from: DVec3,
    /// A point on the axis.
    pub to: DVec3,
    /// Up (not parallel to the axis).
    pub up: DVec3,
}

impl LookAt {
    /// The frame's axes `(x, y, z)`, unit and orthogonal (Mitsuba's `look_at`).
    pub fn axes(&self) -> (DVec3, DVec3, DVec3) {
        let dir = (self.to - self.from).normalize();
        let left = self.up.normalize().cross(dir).normalize();
        let up = dir.cross(left);
        (left, up, dir)
    }
}

/// One shape of the scene with its material and emission.
#[derive(Clone, Debug, PartialEq)]
pub struct ShapeDesc {
    /// The surface.
    pub geometry: GeometryDesc,
    /// Index into [`SceneDesc::materials`]; `None` = black diffuse.
    pub material: Option<usize>,
    /// Emitted radiance on the side the normal points to; zero for non-emitters. With an
    /// [`ShapeDesc::emission_texture`], its mean over the unit uv square.
    pub emission: DVec3,
    /// Emitted radiance as a texture (every texel ≥ 0 and finite), if given as one; whether the
    /// shape emits at all is then `texture.max() > 0`, not `emission != 0`.
    pub emission_texture: Option<TextureDesc>,
    /// Where the shape is in the file (`shapes[3]`), for messages.
    pub json_path: String,
}

/// The surface of a shape.
#[derive(Clone, Debug, PartialEq)]
pub enum GeometryDesc {
    /// Parallelogram `corner + s·edge_u + t·edge_v`, `s, t ∈ [0, 1]`; normal along
    /// `edge_u × edge_v` (never zero).
    Quad {
        /// One corner.
        corner: DVec3,
        /// First edge from the corner.
        edge_u: DVec3,
        /// Second edge from the corner.
        edge_v: DVec3,
    },
    /// Planar simple polygon, normal by the right-hand rule (validated by
    /// [`crate::geometry::polygon::validate_polygon`]).
    Polygon {
        /// The vertices in order, at least 3.
        vertices: Vec<DVec3>,
    },
    /// Flat-shaded triangle mesh; every triangle has non-zero area and in-range indices.
    Triangles {
        /// Vertex positions.
        positions: Vec<DVec3>,
        /// Triangles as indices into `positions`, right-hand-rule normals.
        indices: Vec<[u32; 3]>,
    },
    /// Triangles from a mesh file (`mesh`), zero-area triangles (after `to_world`) removed.
    Mesh {
        /// The file, resolved against the scene file's folder.
        file: PathBuf,
        /// Which mesh of the file (Mitsuba's `.serialized` holds several; 0 for other formats).
        shape_index: u32,
        /// Object to world, affine and invertible.
        to_world: glam::DMat4,
        /// Whether to ignore the file's vertex normals (flat shading).
        face_normals: bool,
        /// Whether vertex normals were computed for a file without them (Mitsuba's rule,
        /// [`crate::scene::mesh::normals`]); they are then in `mesh.normals`.
        recompute_normals: bool,
        /// What the file holds, in its own coordinates.
        mesh: Arc<crate::scene::mesh::MeshData>,
    },
    /// Disk facing along `normal`.
    Disk {
        /// Centre.
        center: DVec3,
        /// Unit normal.
        normal: DVec3,
        /// Radius, > 0.
        radius: f64,
        /// Where its texture coordinates' φ = 0 lies, as given (not along the normal; made
        /// perpendicular to it, φ growing towards `normal × u_axis`); `None`: the first tangent
        /// of the normal's frame.
        u_axis: Option<DVec3>,
    },
    /// Sphere with outward normals.
    Sphere {
        /// Centre.
        center: DVec3,
        /// Radius, > 0.
        radius: f64,
        /// Its texture coordinates' pole (θ = 0), as given; `None`: +z.
        pole: Option<DVec3>,
        /// Where φ = 0 lies, as given (not along the pole; made perpendicular to it, φ growing
        /// towards `pole × u_axis`); `None`: +x.
        u_axis: Option<DVec3>,
    },
    /// Mitsuba's cylinder: the open tube (no end caps) of `radius` around the segment
    /// `p0 → p1`, normals away from the axis unless `flip_normals`; texture coordinates
    /// `u = φ/2π` from `u_axis` (made perpendicular to the axis; by default the first axis of
    /// the axis' frame, as Mitsuba's), `v` from 0 at `p0` to 1 at `p1`. Does not emit.
    Cylinder {
        /// Centre of the base circle.
        p0: DVec3,
        /// Centre of the top circle, ≠ `p0`.
        p1: DVec3,
        /// Radius, > 0.
        radius: f64,
        /// Where `u = 0`, as given (not parallel to the axis); `None`: Mitsuba's default.
        u_axis: Option<DVec3>,
        /// Whether the normals point towards the axis.
        flip_normals: bool,
    },
    /// Axis-aligned box `[min, max]`, rotated about +y through the origin, then translated.
    Box {
        /// Lower corner; `min < max` on every axis.
        min: DVec3,
        /// Upper corner.
        max: DVec3,
        /// Rotation about +y in degrees (x' = cos·x + sin·z, z' = −sin·x + cos·z).
        rotate_y_deg: f64,
        /// Translation applied after the rotation.
        translate: DVec3,
    },
}

impl SceneDesc {
    /// Writes the scene back in the file format (without comments and warnings), such that
    /// parsing the result gives this description again.
    pub fn to_json(&self) -> Value {
        let c = &self.camera;
        let materials: Map<String, Value> = self
            .materials
            .iter()
            .map(|m| (m.name.clone(), material_json(m, &self.materials)))
            .collect();
        let shapes: Vec<Value> = self.shapes.iter().map(|s| self.shape_json(s)).collect();
        json!({
            "camera": c.to_json(),
            "max_depth": self.max_depth,
            "hide_emitters": self.hide_emitters,
            "background": match &self.background {
                BackgroundDesc::Constant(c) => vec3(*c),
                BackgroundDesc::Envmap(e) => {
                    let mut v = json!({
                        "envmap": e.file.to_string_lossy(),
                        "scale": e.scale,
                        "rotate_y_deg": e.rotate_y_deg,
                    });
                    if let Some(r) = e.rotation {
                        v["rotation"] = super::parse_background::rotation_json(r);
                    }
                    v
                }
            },
            "materials": materials,
            "shapes": shapes,
            "lights": self.lights.iter().map(LightDesc::to_json).collect::<Vec<_>>(),
        })
    }

    fn shape_json(&self, shape: &ShapeDesc) -> Value {
        let mut obj = match &shape.geometry {
            GeometryDesc::Quad {
                corner,
                edge_u,
                edge_v,
            } => json!({
                "type": "quad", "corner": vec3(*corner),
                "edge_u": vec3(*edge_u), "edge_v": vec3(*edge_v),
            }),
            GeometryDesc::Polygon { vertices } => json!({
                "type": "polygon",
                "vertices": vertices.iter().map(|&v| vec3(v)).collect::<Vec<_>>(),
            }),
            GeometryDesc::Triangles { positions, indices } => json!({
                "type": "triangles",
                "positions": positions.iter().map(|&v| vec3(v)).collect::<Vec<_>>(),
                "indices": indices,
            }),
            GeometryDesc::Mesh {
                file,
                shape_index,
                to_world,
                face_normals,
                recompute_normals,
                ..
            } => {
                let rows = to_world.transpose().to_cols_array_2d();
                let mut m = json!({
                    "type": "mesh",
                    "file": file.to_string_lossy(),
                    "to_world": rows,
                    "face_normals": face_normals,
                });
                if *shape_index != 0 {
                    m["shape_index"] = json!(shape_index);
                }
                if *recompute_normals {
                    m["recompute_normals"] = json!(true);
                }
                m
            }
            GeometryDesc::Disk {
                center,
                normal,
                radius,
                u_axis,
            } => {
                let mut d = json!({
                    "type": "disk", "center": vec3(*center), "normal": vec3(*normal),
                    "radius": radius,
                });
                if let Some(u) = u_axis {
                    d["u_axis"] = vec3(*u);
                }
                d
            }
            GeometryDesc::Sphere {
                center,
                radius,
                pole,
                u_axis,
            } => {
                let mut s = json!({"type": "sphere", "center": vec3(*center), "radius": radius});
                if let Some(p) = pole {
                    s["pole"] = vec3(*p);
                }
                if let Some(u) = u_axis {
                    s["u_axis"] = vec3(*u);
                }
                s
            }
            GeometryDesc::Cylinder {
                p0,
                p1,
                radius,
                u_axis,
                flip_normals,
            } => {
                let mut c = json!({
                    "type": "cylinder", "p0": vec3(*p0), "p1": vec3(*p1), "radius": radius,
                });
                if let Some(u) = u_axis {
                    c["u_axis"] = vec3(*u);
                }
                if *flip_normals {
                    c["flip_normals"] = json!(true);
                }
                c
            }
            GeometryDesc::Box {
                min,
                max,
                rotate_y_deg,
                translate,
            } => json!({
                "type": "box", "min": vec3(*min), "max": vec3(*max),
                "rotate_y_deg": rotate_y_deg, "translate": vec3(*translate),
            }),
        };
        if let Some(i) = shape.material {
            obj["material"] = json!(self.materials[i].name);
        }
        if let Some(t) = &shape.emission_texture {
            obj["emission"] = t.to_json();
        } else if shape.emission != DVec3::ZERO {
            obj["emission"] = vec3(shape.emission);
        }
        obj
    }
}

/// `alpha` as [α_u, α_v] where anisotropic, and `distribution` unless it is the default (files
/// written before either existed stay unchanged).
fn microfacet_keys(obj: &mut Value, alpha: f64, alpha_v: Option<f64>, distribution: Distribution) {
    if let Some(v) = alpha_v {
        obj["alpha"] = json!([alpha, v]);
    }
    if distribution != Distribution::default() {
        obj["distribution"] = json!(distribution.name());
    }
}

/// `m` in the file format; `all` are the scene's materials, which a mix names.
fn material_json(m: &NamedMaterial, all: &[NamedMaterial]) -> Value {
    let name = |i: usize| all[i].name.as_str();
    let mut obj = if let Some(mix) = &m.mix {
        let weight = match &mix.weight_texture {
            Some(t) if !t.texture.is_constant() => t.to_json(),
            _ => json!(mix.weight),
        };
        let mut obj =
            json!({"type": "mix", "materials": mix.materials.map(name), "weight": weight});
        if mix.mitsuba {
            obj["model"] = json!("mitsuba");
        }
        obj
    } else if let Some([front, back]) = m.sides {
        json!({"type": "two_sided", "front": name(front), "back": name(back)})
    } else {
        bsdf_json(m)
    };
    if let Some(opacity) = &m.opacity {
        obj["opacity"] = match &opacity.texture {
            crate::textures::Texture::Constant(c) => json!(c.x),
            _ => opacity.to_json(),
        };
    }
    obj
}

/// A principled kind's keys into `obj`: each scalar of `names` (its texture where `textures`
/// has one in that slot, else the constant: a constant "texture" is written as the constant),
/// each sampling rate, and a textured base colour over the constant one.
fn principled_family_keys(
    obj: &mut Value,
    names: &[&str],
    scalars: &[f64],
    rate_keys: &[&str],
    rates: &[f64],
    textures: &MaterialTextures,
) {
    for ((key, v), tex) in names.iter().zip(scalars).zip(&textures.principled) {
        obj[*key] = match tex {
            Some(t) if !t.texture.is_constant() => t.to_json(),
            _ => json!(v),
        };
    }
    for (key, rate) in rate_keys.iter().zip(rates) {
        obj[*key] = json!(rate);
    }
    if let Some(tex) = textures.albedo.as_ref()
        && !tex.texture.is_constant()
    {
        obj["base_color"] = tex.to_json();
    }
}

/// A material with a BSDF of its own (no mix, no pair) in the file format, without its opacity.
fn bsdf_json(m: &NamedMaterial) -> Value {
    let mut obj = match &m.material {
        MaterialDesc::Diffuse { albedo } => json!({"type": "diffuse", "albedo": vec3(*albedo)}),
        MaterialDesc::Conductor {
            alpha,
            alpha_v,
            distribution,
            fresnel,
        } => {
            let mut obj = match fresnel {
                FresnelDesc::Complex { eta, k, tint } => {
                    let mut obj = json!({
                        "type": "conductor", "alpha": alpha, "eta": vec3(*eta), "k": vec3(*k),
                    });
                    if *tint != DVec3::ONE {
                        obj["specular"] = vec3(*tint);
                    }
                    obj
                }
                FresnelDesc::Reflectance(r) => {
                    json!({"type": "conductor", "alpha": alpha, "reflectance": vec3(*r)})
                }
            };
            microfacet_keys(&mut obj, *alpha, *alpha_v, *distribution);
            obj
        }
        MaterialDesc::Plastic {
            albedo,
            alpha,
            ior,
            specular,
            model,
        } => {
            let mut obj = json!({
                "type": "plastic", "albedo": vec3(*albedo), "alpha": alpha,
                "ior": ior, "specular": vec3(*specular),
            });
            if let PlasticModel::Mitsuba {
                distribution,
                nonlinear,
            } = model
            {
                obj["model"] = json!("mitsuba");
                obj["distribution"] = json!(distribution.name());
                obj["nonlinear"] = json!(nonlinear);
            }
            obj
        }
        MaterialDesc::Dielectric {
            ior,
            alpha,
            alpha_v,
            distribution,
        } => {
            let mut obj = json!({"type": "dielectric", "ior": ior, "alpha": alpha});
            microfacet_keys(&mut obj, *alpha, *alpha_v, *distribution);
            obj
        }
        MaterialDesc::ThinDielectric { ior } => json!({"type": "thin_dielectric", "ior": ior}),
        MaterialDesc::Principled(p) => {
            let mut obj = json!({
                "type": "principled", "base_color": vec3(p.base_color), "eta": p.eta,
            });
            let names = crate::materials::principled::PrincipledParam::ALL.map(|k| k.name());
            let rates = crate::scene::parse_principled::RATE_KEYS;
            principled_family_keys(&mut obj, &names, &p.scalars, &rates, &p.rates, &m.textures);
            obj
        }
        MaterialDesc::PrincipledThin(p) => {
            let mut obj = json!({"type": "principled_thin", "base_color": vec3(p.base_color)});
            let names = crate::materials::principled_thin::ThinParam::ALL.map(|k| k.name());
            let rates = crate::materials::principled_thin::ThinRates::KEYS;
            principled_family_keys(&mut obj, &names, &p.scalars, &rates, &p.rates, &m.textures);
            obj
        }
        MaterialDesc::GltfPbr(p) => {
            let mut obj = json!({
                "type": "gltf_pbr", "base_color": vec3(p.base_color), "ior": p.ior,
            });
            let names = crate::materials::gltf_pbr::GltfParam::ALL.map(|k| k.name());
            principled_family_keys(&mut obj, &names, &p.scalars, &[], &[], &m.textures);
            // KHR_materials_specular's keys only where they change something.
            if p.specular != 1.0 {
                obj["specular"] = json!(p.specular);
            }
            if p.specular_color != DVec3::ONE {
                obj["specular_color"] = vec3(p.specular_color);
            }
            obj
        }
    };
    let t = &m.textures;
    // A principled's base colour is its `base_color` (written above).
    let albedo = match &m.material {
        MaterialDesc::Principled(_)
        | MaterialDesc::PrincipledThin(_)
        | MaterialDesc::GltfPbr(_) => &None,
        _ => &t.albedo,
    };
    for (key, slot) in [
        ("albedo", albedo),
        ("reflectance", &t.reflectance),
        ("alpha", &t.alpha),
    ] {
        // A constant "texture" is already written as the slot's constant.
        if let Some(tex) = slot.as_ref().filter(|t| !t.texture.is_constant()) {
            obj[key] = tex.to_json();
        }
    }
    // A textured pair [α_u, α_v]: a constant element as its number (the material's constant).
    if let (Some(u), Some(v)) = (&t.alpha, &t.alpha_v) {
        let (cu, cv) = match &m.material {
            MaterialDesc::Conductor { alpha, alpha_v, .. }
            | MaterialDesc::Dielectric { alpha, alpha_v, .. } => {
                (*alpha, alpha_v.unwrap_or(*alpha))
            }
            _ => (0.0, 0.0),
        };
        let element = |t: &TextureDesc, c: f64| {
            if t.texture.is_constant() {
                json!(c)
            } else {
                t.to_json()
            }
        };
        obj["alpha"] = json!([element(u, cu), element(v, cv)]);
    }
    if !m.two_sided && !m.material.transmits() {
        obj["two_sided"] = json!(false);
    }
    if let Some(map) = &m.normal_map {
        let mut v = json!({
            "texture": map.texture.to_json(),
            "flip_invalid_normals": map.flip_invalid_normals,
            "shadowing": map.shadowing,
        });
        match map.height_scale {
            Some(scale) => {
                v["scale"] = json!(scale);
                obj["bump_map"] = v;
            }
            None => obj["normal_map"] = v,
        }
    }
    obj
}

fn vec3(v: DVec3) -> Value {
    json!([v.x, v.y, v.z])
}

impl LightDesc {
    /// The light in the scene format.
    pub fn to_json(&self) -> Value {
        let frame = |f: &LookAt| (vec3(f.from), vec3(f.to), vec3(f.up));
        match self {
            LightDesc::Point {
                position,
                intensity,
            } => {
                json!({"type": "point", "position": vec3(*position), "intensity": vec3(*intensity)})
            }
            LightDesc::Spot {
                frame: f,
                intensity,
                cutoff_angle_deg,
                beam_width_deg,
                texture,
            } => {
                let (from, to, up) = frame(f);
                let mut v = json!({
                    "type": "spot", "from": from, "to": to, "up": up,
                    "intensity": vec3(*intensity),
                    "cutoff_angle_deg": cutoff_angle_deg, "beam_width_deg": beam_width_deg,
                });
                if let Some(t) = texture {
                    v["texture"] = t.to_json();
                }
                v
            }
            LightDesc::Directional {
                direction,
                irradiance,
            } => json!({
                "type": "directional", "direction": vec3(*direction),
                "irradiance": vec3(*irradiance),
            }),
            LightDesc::Projector {
                frame: f,
                fov_x_deg,
                irradiance,
                texture,
                scale,
            } => {
                let (from, to, up) = frame(f);
                json!({
                    "type": "projector", "from": from, "to": to, "up": up,
                    "fov_deg": fov_x_deg,
                    "irradiance": texture.as_ref().map_or_else(|| vec3(*irradiance), TextureDesc::to_json),
                    "scale": scale,
                })
            }
        }
    }
}
