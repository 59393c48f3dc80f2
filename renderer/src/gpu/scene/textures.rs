//! Textures on the GPU: every texture a material slot names, then every emission texture, as a
//! small record, and the texels of every bitmap in one `rgba32float` 2D texture used as a linear
//! array.
//!
//! Where things go, within wgpu's portable limits (the path tracer already binds the 8 storage
//! buffers they allow per stage):
//!
//! - **Records** (4 vec4 each, u32 fields stored as f32 bits like every record's indices) are
//!   appended to the `vertex_data` buffer (binding 5) after the mesh attributes; their offset
//!   reaches the shaders through the per-dispatch uniform (`params.textures`). A texture's id is
//!   its index among the records. Their number counts against that buffer's binding size, which
//!   `GpuScene` checks with a clear error.
//! - **Texels** of all bitmaps, one after another (a bitmap shared by several textures, one
//!   `Arc`'d image, is stored once), in one `rgba32float` texture (binding 10): texel `i` at
//!   `(i % W, i / W)`, `W` = the texture's width, at most [`TEXELS_PER_ROW`] (or the device's
//!   largest 2D dimension if smaller). Read with `textureLoad` and filtered by hand like the
//!   environment map, so a lookup is the CPU's bilinear one and not the sampler hardware's. The
//!   capacity is `W ×` the device's largest dimension (33.5M texels at wgpu's default 8192);
//!   [`TextureTexels::layout`] names the texture that does not fit.
//! - **Materials** name their textures in two slots every record has free (see
//!   `materials/mod.wgsl`): `a.w` the colour texture (albedo of a diffuse or plastic, a conductor's
//!   reflectance), `c.w` the roughness textures (α, or α_u in the low 16 bits and α_v in the high
//!   16, `0xFFFF` for none: [`super::materials::roughness_slot`]); the bits of `NONE` where the
//!   slot is constant. Hence at most [`MAX_TEXTURES`] textures.
//! - **Area lights** name their emission texture in `h.w` of their record (see `lights/mod.wgsl`),
//!   `NONE` for a constant radiance.
//! - **Masks**: a material's opacity, constant or not, is a record, named by the table that leads
//!   `tables` in a scene with masks (`materials/mask.wgsl`).
//!
//! Record of a texture (`TextureRecord` in `textures/mod.wgsl`):
//! - `h` = bits of (kind [`TextureTag`], wrap [`WrapTag`], channel [`ChannelTag`], offset of the
//!   first texel);
//! - `uv` = (su, sv, ou, ov), the [`UvTransform`] (identity for a constant);
//! - `c0` = (the constant, the bitmap's `scale` or the checkerboard's `color0`; bits of the
//!   bitmap's width);
//! - `c1` = (the checkerboard's `color1`; bits of the bitmap's height);
//! - a mesh attribute's: `h.w` = bits of its slot, `c0.x` = its scale.
//!
//! WGSL twin: `textures/mod.wgsl`.

use super::{bits, v4};
use crate::gpu::GpuError;
use crate::gpu::prelude::gpu_tags;
use crate::image_io::Image;
use crate::materials::textured::MaterialTextures;
use crate::scene::Scene;
use crate::textures::{Channel, Texture, UvTransform, WrapMode};
use std::collections::HashMap;
use std::sync::Arc;

/// The widest row of the texel texture: wide enough that a row holds a typical bitmap row, small
/// enough that a scene's texels fill few rows (the texture is `W × ⌈texels / W⌉`).
pub const TEXELS_PER_ROW: u32 = 4096;

/// 16-byte vec4s per texture record.
pub const RECORD_VEC4S: u32 = 4;

gpu_tags! {
    /// A texture record's kind (`h.x`), in the variant order of [`Texture`].
    pub enum TextureTag {
        /// [`Texture::Constant`].
        Constant => "TEXTURE_CONSTANT",
        /// [`Texture::Bitmap`].
        Bitmap => "TEXTURE_BITMAP",
        /// [`Texture::Checkerboard`].
        Checkerboard => "TEXTURE_CHECKERBOARD",
        /// [`Texture::MeshAttribute`].
        MeshAttribute => "TEXTURE_MESH_ATTRIBUTE",
    }
}

impl TextureTag {
    /// The tag of `t`.
    pub fn of(t: &Texture) -> TextureTag {
        match t {
            Texture::Constant(_) => TextureTag::Constant,
            Texture::Bitmap(_) => TextureTag::Bitmap,
            Texture::Checkerboard(_) => TextureTag::Checkerboard,
            Texture::MeshAttribute(_) => TextureTag::MeshAttribute,
        }
    }
}

gpu_tags! {
    /// A bitmap record's wrap mode (`h.y`), in the variant order of [`WrapMode`].
    pub enum WrapTag {
        /// [`WrapMode::Repeat`].
        Repeat => "WRAP_REPEAT",
        /// [`WrapMode::Mirror`].
        Mirror => "WRAP_MIRROR",
        /// [`WrapMode::Clamp`].
        Clamp => "WRAP_CLAMP",
    }
}

impl WrapTag {
    /// The tag of `w`.
    pub fn of(w: WrapMode) -> WrapTag {
        match w {
            WrapMode::Repeat => WrapTag::Repeat,
            WrapMode::Mirror => WrapTag::Mirror,
            WrapMode::Clamp => WrapTag::Clamp,
        }
    }
}

gpu_tags! {
    /// What a scalar slot reads of a texture (`h.z`), in the variant order of [`Channel`].
    pub enum ChannelTag {
        /// [`Channel::Luminance`].
        Luminance => "CHANNEL_LUMINANCE",
        /// [`Channel::R`].
        R => "CHANNEL_R",
        /// [`Channel::G`].
        G => "CHANNEL_G",
        /// [`Channel::B`].
        B => "CHANNEL_B",
    }
}

impl ChannelTag {
    /// The tag of `c`.
    pub fn of(c: Channel) -> ChannelTag {
        match c {
            Channel::Luminance => ChannelTag::Luminance,
            Channel::R => ChannelTag::R,
            Channel::G => ChannelTag::G,
            Channel::B => ChannelTag::B,
        }
    }
}

/// One bitmap's texels in the linear array, and what to call it in an error.
pub(crate) struct TexelRange {
    /// `material "wood" albedo (bitmap "wood.png", 512×512)`.
    pub(crate) what: String,
    /// First texel.
    pub(crate) offset: u64,
    /// Texels.
    pub(crate) len: u64,
}

/// The texels of every bitmap of a scene, one after another, as the texture will hold them.
pub(crate) struct TextureTexels {
    /// Linear RGB, a = 0.
    pub(crate) rgba: Vec<[f32; 4]>,
    /// Each distinct image's place.
    pub(crate) images: Vec<TexelRange>,
}

impl TextureTexels {
    /// The texture's `(width, height)` for a device whose 2D textures are at most `max_dim`
    /// texels on a side: one row up to [`TEXELS_PER_ROW`] wide, as many rows as needed; an
    /// error naming the first bitmap that does not fit.
    pub(crate) fn layout(&self, max_dim: u32) -> Result<(u32, u32), GpuError> {
        let w = TEXELS_PER_ROW.min(max_dim).max(1);
        let n = self.rgba.len() as u64;
        if n <= w as u64 {
            return Ok(((n as u32).max(1), 1));
        }
        let capacity = w as u64 * max_dim as u64;
        if let Some(r) = self.images.iter().find(|r| r.offset + r.len > capacity) {
            return Err(GpuError::TooLarge(format!(
                "{} brings the scene's texture texels to {}, beyond the {w}×{max_dim} = \
                 {capacity} that the device's one texel texture holds",
                r.what,
                r.offset + r.len
            )));
        }
        Ok((w, n.div_ceil(w as u64) as u32))
    }

    /// Uploads the texels as a `width × height` `rgba32float` texture (from
    /// [`TextureTexels::layout`]), padded with zeros; a 1×1 black one without bitmaps (the
    /// binding must hold a texture; programs without textures never read it).
    pub(crate) fn upload(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        (width, height): (u32, u32),
    ) -> wgpu::Texture {
        let mut rgba = self.rgba.clone();
        rgba.resize(width as usize * height as usize, [0.0; 4]);
        upload_rgba32float(
            device,
            queue,
            "lumis texture texels",
            (width, height),
            &rgba,
        )
    }
}

/// Uploads `rgba` (row-major, `width × height` texels) as a sampled `rgba32float` texture: the one
/// format both the bitmaps and the environment map use, read with `textureLoad` (no sampler).
pub(crate) fn upload_rgba32float(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    (width, height): (u32, u32),
    rgba: &[[f32; 4]],
) -> wgpu::Texture {
    use wgpu::util::DeviceExt;
    debug_assert_eq!(rgba.len(), width as usize * height as usize);
    device.create_texture_with_data(
        queue,
        &wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba32Float,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        bytemuck::cast_slice(rgba),
    )
}

/// A scene's textures as the GPU holds them.
pub(crate) struct SceneTextures {
    /// [`RECORD_VEC4S`] vec4s per texture, for `vertex_data`.
    pub(crate) records: Vec<[f32; 4]>,
    /// Per material: the ids of its colour, roughness (α or α_u) and α_v textures (`NONE`:
    /// constant).
    pub(crate) slots: Vec<[u32; 3]>,
    /// Per material: the ids of a principled's scalar textures in
    /// [`crate::materials::principled::PrincipledParam::ALL`]'s order, or a thin principled's in
    /// [`crate::materials::principled_thin::ThinParam::ALL`]'s (`NONE`: constant).
    pub(crate) principled: Vec<[u32; 10]>,
    /// Per material: the id of its weight's texture if it is a mix with a textured weight, else
    /// `NONE` (`materials/mix.wgsl`).
    pub(crate) mix_weights: Vec<u32>,
    /// Per material: the id of its normal map's texture, else `NONE`
    /// (`materials/normal_map.wgsl`).
    pub(crate) normal_maps: Vec<u32>,
    /// Per material: the id of its opacity's record, else `NONE` (`materials/mask.wgsl`); empty
    /// in a scene without masks.
    pub(crate) opacity: Vec<u32>,
    /// Per emission texture ([`Scene::emission_textures`]): its id, after the materials'.
    pub(crate) emission: Vec<u32>,
    /// Per record: `material "wood" albedo`, for errors.
    pub(crate) names: Vec<String>,
    /// The bitmaps' texels.
    pub(crate) texels: TextureTexels,
}

/// The slots of `t` in the record's order, with their names: colour (`albedo` or `reflectance`),
/// then roughness (`alpha`), then `alpha_v`. Destructured without `..`, so that a slot added to
/// [`MaterialTextures`] does not compile here until the GPU has it.
fn slots(t: &MaterialTextures) -> [(Option<&Texture>, &'static str); 3] {
    let MaterialTextures {
        albedo,
        reflectance,
        alpha,
        alpha_v,
        // Uploaded with the plastic's record (`materials::push_grid`).
        coat_grid: _,
        // Their own ids (`SceneTextures::principled`).
        principled: _,
    } = t;
    // `MaterialTextures::check` admits at most one colour slot per material kind.
    let colour = match (albedo, reflectance) {
        (Some(t), _) => (Some(t), "albedo"),
        (None, Some(t)) => (Some(t), "reflectance"),
        (None, None) => (None, "albedo"),
    };
    [
        colour,
        (alpha.as_ref(), "alpha"),
        (alpha_v.as_ref(), "alpha_v"),
    ]
}

/// The most textures a scene may have on the GPU: a material's roughness slot holds two ids in
/// 16 bits each, `0xFFFF` standing for none.
pub(crate) const MAX_TEXTURES: usize = 0xFFFF;

/// Encodes the textures of `scene`'s materials, then its emission textures, in one record
/// array (layout in the module doc).
pub(crate) fn encode(scene: &Scene) -> SceneTextures {
    let none = crate::geometry::primitive::NONE;
    let mut out = SceneTextures {
        records: Vec::new(),
        slots: Vec::with_capacity(scene.materials.len()),
        principled: vec![[none; 10]; scene.materials.len()],
        mix_weights: vec![none; scene.materials.len()],
        normal_maps: vec![none; scene.materials.len()],
        opacity: vec![none; scene.opacity.len()],
        emission: Vec::with_capacity(scene.emission_textures.len()),
        names: Vec::new(),
        texels: TextureTexels {
            rgba: Vec::new(),
            images: Vec::new(),
        },
    };
    // Texel offsets of the images stored so far, by identity (textures share an `Arc`).
    let mut stored: HashMap<*const Image, u32> = HashMap::new();
    for (i, textures) in scene.material_textures.iter().enumerate() {
        let Some(textures) = textures else {
            out.slots.push([none; 3]);
            continue;
        };
        let ids = slots(textures).map(|(texture, slot)| {
            let Some(texture) = texture else {
                return none;
            };
            let what = format!("material \"{}\" {slot}", scene.material_names[i]);
            let id = (out.records.len() as u32) / RECORD_VEC4S;
            out.records
                .extend(record(texture, &what, &mut out.texels, &mut stored));
            out.names.push(what);
            id
        });
        out.slots.push(ids);
        let thin = matches!(
            scene.materials[i],
            crate::materials::Material::PrincipledThin(_)
        );
        let gltf = matches!(scene.materials[i], crate::materials::Material::GltfPbr(_));
        for (k, texture) in textures.principled.iter().enumerate() {
            let Some(texture) = texture else { continue };
            let name = if gltf {
                crate::materials::gltf_pbr::GltfParam::ALL[k].name()
            } else if thin {
                crate::materials::principled_thin::ThinParam::ALL[k].name()
            } else {
                crate::materials::principled::PrincipledParam::ALL[k].name()
            };
            let what = format!("material \"{}\" {name}", scene.material_names[i]);
            out.principled[i][k] = (out.records.len() as u32) / RECORD_VEC4S;
            out.records
                .extend(record(texture, &what, &mut out.texels, &mut stored));
            out.names.push(what);
        }
    }
    for e in &scene.emission_textures {
        let what = format!("{}.emission", e.shape);
        out.emission.push((out.records.len() as u32) / RECORD_VEC4S);
        out.records
            .extend(record(&e.texture, &what, &mut out.texels, &mut stored));
        out.names.push(what);
    }
    // A mix's textured weight (a constant one lives in the mix's record).
    for (i, mix) in scene.mixes.iter().enumerate() {
        let Some(mix) = mix else { continue };
        if matches!(mix.weight, Texture::Constant(_)) {
            continue;
        }
        let what = format!("material \"{}\" weight", scene.material_names[i]);
        out.mix_weights[i] = (out.records.len() as u32) / RECORD_VEC4S;
        out.records
            .extend(record(&mix.weight, &what, &mut out.texels, &mut stored));
        out.names.push(what);
    }
    for (i, map) in scene.normal_maps.iter().enumerate() {
        let Some(map) = map else { continue };
        let what = format!("material \"{}\" normal_map", scene.material_names[i]);
        out.normal_maps[i] = (out.records.len() as u32) / RECORD_VEC4S;
        let mut r = record(&map.texture, &what, &mut out.texels, &mut stored);
        // A bump map's scale in its own record's free c1.x (`materials/normal_map.wgsl`).
        if let Some(scale) = map.height_scale {
            r[3][0] = scale;
        }
        out.records.extend(r);
        out.names.push(what);
    }
    for (i, opacity) in scene.opacity.iter().enumerate() {
        let Some(opacity) = opacity else { continue };
        let what = format!("material \"{}\" opacity", scene.material_names[i]);
        out.opacity[i] = (out.records.len() as u32) / RECORD_VEC4S;
        out.records
            .extend(record(opacity, &what, &mut out.texels, &mut stored));
        out.names.push(what);
    }
    out
}

/// Checks that the texture records, starting at vec4 `start` of the vertex data, fit a storage
/// binding of `limit` bytes; else an error naming the first texture whose record does not.
pub(crate) fn check_records(names: &[String], start: usize, limit: usize) -> Result<(), GpuError> {
    if names.len() > MAX_TEXTURES {
        return Err(GpuError::TooLarge(format!(
            "{} textures, beyond the {MAX_TEXTURES} a scene may have on the GPU",
            names.len()
        )));
    }
    let vec4s = limit / size_of::<[f32; 4]>();
    let per = RECORD_VEC4S as usize;
    match (0..names.len()).find(|k| start + (k + 1) * per > vec4s) {
        Some(k) => Err(GpuError::TooLarge(format!(
            "the record of texture {k} ({}) ends beyond the {limit} bytes the device binds for \
             light triangles, mesh vertex attributes and texture records",
            names[k]
        ))),
        None => Ok(()),
    }
}

/// The record of `texture`, storing a bitmap's texels if they are not stored yet.
fn record(
    texture: &Texture,
    what: &str,
    texels: &mut TextureTexels,
    stored: &mut HashMap<*const Image, u32>,
) -> [[f32; 4]; 4] {
    let kind = TextureTag::of(texture).gpu_tag();
    let channel = ChannelTag::of(texture.channel()).gpu_tag();
    let identity = UvTransform::IDENTITY;
    let uv = |t: &UvTransform| [t.scale.x, t.scale.y, t.offset.x, t.offset.y];
    let repeat = WrapTag::Repeat.gpu_tag();
    match texture {
        Texture::Constant(c) => [
            [bits(kind), bits(repeat), bits(channel), 0.0],
            uv(&identity),
            v4(*c, 0.0),
            [0.0; 4],
        ],
        Texture::Checkerboard(c) => [
            [bits(kind), bits(repeat), bits(channel), 0.0],
            uv(&c.uv),
            v4(c.color0, 0.0),
            v4(c.color1, 0.0),
        ],
        Texture::MeshAttribute(m) => [
            [bits(kind), bits(repeat), bits(channel), bits(m.slot)],
            uv(&identity),
            [m.scale, 0.0, 0.0, 0.0],
            [0.0; 4],
        ],
        Texture::Bitmap(b) => {
            let image = b.image();
            let offset = *stored.entry(Arc::as_ptr(image)).or_insert_with(|| {
                let offset = texels.rgba.len() as u64;
                let file = if b.file.as_os_str().is_empty() {
                    "made in memory".to_string()
                } else {
                    format!("\"{}\"", b.file.display())
                };
                texels.images.push(TexelRange {
                    what: format!("{what} (bitmap {file}, {}×{})", image.width, image.height),
                    offset,
                    len: image.data.len() as u64,
                });
                texels
                    .rgba
                    .extend(image.data.iter().map(|t| [t.x, t.y, t.z, 0.0]));
                // Beyond u32 the layout refuses the scene (its capacity is far below).
                offset.min(u32::MAX as u64) as u32
            });
            let o = b.options();
            [
                [
                    bits(kind),
                    bits(WrapTag::of(o.wrap).gpu_tag()),
                    bits(channel),
                    bits(offset),
                ],
                uv(&o.uv),
                v4(o.scale, bits(image.width)),
                [0.0, 0.0, 0.0, bits(image.height)],
            ]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::parse_scene;
    use crate::textures::{BitmapOptions, BitmapTexture, Checkerboard};
    use glam::{Vec2, Vec3};

    fn image(w: u32, h: u32) -> Arc<Image> {
        Arc::new(Image {
            width: w,
            height: h,
            data: (0..w * h).map(|i| Vec3::splat(i as f32 / 100.0)).collect(),
        })
    }

    /// Two materials: a conductor "a" with a shared bitmap in both slots and a diffuse "b" with a
    /// checkerboard; the last (the black default) untextured.
    fn scene() -> Scene {
        let json = r#"{
          "camera": {"from": [0, 0, -3], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40, "width": 2, "height": 2},
          "materials": {"a": {"type": "conductor", "reflectance": [0.9, 0.9, 0.9], "alpha": 0.2},
                        "b": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
          "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "a"},
                     {"type": "sphere", "center": [0, 3, 0], "radius": 1, "material": "b"}]
        }"#;
        let mut scene = Scene::from_desc(&parse_scene(json).unwrap()).unwrap();
        let img = image(3, 2);
        let options = BitmapOptions {
            wrap: WrapMode::Mirror,
            channel: Channel::G,
            uv: UvTransform {
                scale: Vec2::new(2.0, 3.0),
                offset: Vec2::new(0.5, -1.0),
            },
            scale: Vec3::new(1.0, 0.5, 0.25),
        };
        let bitmap = Texture::Bitmap(BitmapTexture::new(img.clone(), options));
        let other = Texture::Bitmap(BitmapTexture::new(img, BitmapOptions::default()));
        scene.material_textures[0] = Some(MaterialTextures {
            reflectance: Some(bitmap),
            alpha: Some(other),
            ..Default::default()
        });
        scene.material_textures[1] = Some(MaterialTextures {
            albedo: Some(Texture::Checkerboard(Checkerboard::default())),
            ..Default::default()
        });
        scene
    }

    /// The roughness slot: NONE without an α texture; α's id low and α_v's high (0xFFFF for
    /// none) with one; a scene with more textures than the 16 bits hold is refused.
    #[test]
    fn roughness_slots_pack_two_ids() {
        use super::super::materials::roughness_slot;
        let none = crate::geometry::primitive::NONE;
        assert_eq!(roughness_slot(none, none), none);
        assert_eq!(roughness_slot(7, none), 0xFFFF_0007);
        assert_eq!(roughness_slot(7, 9), 0x0009_0007);
        let names = vec![String::new(); MAX_TEXTURES + 1];
        assert!(check_records(&names, 0, usize::MAX / 2).is_err());
        assert!(check_records(&names[1..], 0, usize::MAX / 2).is_ok());
    }

    #[test]
    fn records_name_their_texels_once_per_image() {
        let t = encode(&scene());
        let none = crate::geometry::primitive::NONE;
        assert_eq!(
            t.slots,
            vec![[0, 1, none], [2, none, none], [none, none, none]]
        );
        assert_eq!(t.records.len(), 3 * RECORD_VEC4S as usize);
        // One image, stored once for both bitmaps.
        assert_eq!(t.texels.rgba.len(), 6);
        assert_eq!(t.texels.images.len(), 1);
        assert!(
            t.texels.images[0]
                .what
                .contains("material \"a\" reflectance (bitmap made in memory, 3×2)"),
            "{}",
            t.texels.images[0].what
        );
        let u = |x: f32| x.to_bits();
        let r = &t.records;
        assert_eq!(
            r[0].map(u),
            [
                TextureTag::Bitmap.gpu_tag(),
                WrapTag::Mirror.gpu_tag(),
                ChannelTag::G.gpu_tag(),
                0
            ]
        );
        assert_eq!(r[1], [2.0, 3.0, 0.5, -1.0]);
        assert_eq!(r[2][..3], [1.0, 0.5, 0.25]);
        assert_eq!((u(r[2][3]), u(r[3][3])), (3, 2));
        assert_eq!(u(r[4][1]), WrapTag::Repeat.gpu_tag());
        assert_eq!(u(r[4][2]), ChannelTag::Luminance.gpu_tag());
        assert_eq!(u(r[8][0]), TextureTag::Checkerboard.gpu_tag());
        assert_eq!(r[10][..3], [0.4; 3]);
        assert_eq!(r[11][..3], [0.2; 3]);
    }

    #[test]
    fn records_beyond_the_binding_are_named() {
        let t = encode(&scene());
        assert_eq!(t.names.len(), 3);
        assert!(check_records(&t.names, 10, (10 + 12) * 16).is_ok());
        let e = check_records(&t.names, 10, (10 + 11) * 16)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("texture 2 (material \"b\" albedo) ends beyond the 336 bytes"),
            "{e}"
        );
    }

    #[test]
    fn the_layout_fills_rows_and_names_the_bitmap_that_does_not_fit() {
        let mut t = encode(&scene()).texels;
        assert_eq!(t.layout(8192).unwrap(), (6, 1));
        assert_eq!(t.layout(4).unwrap(), (4, 2));
        let e = t.layout(2).unwrap_err().to_string();
        assert!(
            e.contains("material \"a\" reflectance (bitmap made in memory, 3×2)")
                && e.contains("to 6, beyond the 2×2 = 4"),
            "{e}"
        );
        t.rgba.clear();
        t.images.clear();
        assert_eq!(t.layout(8192).unwrap(), (1, 1));
    }
}
