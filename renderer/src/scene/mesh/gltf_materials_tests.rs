//! The glTF material rules (docs/scene-format.md, "glTF materials"), on files built here and
//! opened on their own ([`model_scene`]): each rule's lumis material, textures from a GLB
//! buffer, a data URI and an external file, the one warning, and errors with glTF paths.

use crate::scene::Scene;
use crate::scene::desc::{
    BackgroundDesc, GltfPbrDesc, MaterialDesc, NamedMaterial, SceneDesc, TextureDesc,
};
use crate::scene::mesh::gltf::test_asset::*;
use crate::scene::model::{ModelOptions, model_scene, model_scene_with};
use crate::textures::load::srgb_to_linear;
use crate::textures::{BitmapTexture, Channel, Texture, WrapMode};
use glam::{DVec3, Vec2, Vec3};
use serde_json::{Value, json};
use std::path::Path;

/// One unit quad per material of `materials` (quad `i` at x = 2i, with material `i`), normals
/// and texture coordinates included.
fn quads(materials: Value) -> Asset {
    let mut a = Asset::default();
    let n = materials.as_array().map_or(0, Vec::len);
    for i in 0..n.max(1) {
        let x = 2.0 * i as f32;
        let pos = a.vec3(&QUAD.map(|p| [p[0] + x, p[1], p[2]]));
        let nrm = a.vec3(&[[0.0, 0.0, 1.0]; 4]);
        let uv = a.vec2(&QUAD_UV);
        let idx = a.indices(&QUAD_TRIS, U16);
        let mut p = primitive(pos, Some(nrm), Some(uv), Some(idx));
        if n > 0 {
            p["material"] = json!(i);
        }
        let mesh = a.mesh(vec![p]);
        a.node(json!({ "mesh": mesh }));
    }
    if n > 0 {
        a.root.insert("materials".into(), materials);
    }
    a
}

/// A PNG of `w × h` RGB bytes.
fn png(w: u32, h: u32, bytes: Vec<u8>) -> Vec<u8> {
    let mut out = Vec::new();
    image::RgbImage::from_raw(w, h, bytes)
        .unwrap()
        .write_to(&mut std::io::Cursor::new(&mut out), image::ImageFormat::Png)
        .unwrap();
    out
}

/// The 4 × 2 test image: texel (i, j) = (40i + 10, 100j + 20, 250 − 50i).
fn test_png() -> (Vec<u8>, Vec<[u8; 3]>) {
    let texels: Vec<[u8; 3]> = (0..2u8)
        .flat_map(|j| (0..4u8).map(move |i| [40 * i + 10, 100 * j + 20, 250 - 50 * i]))
        .collect();
    (png(4, 2, texels.concat()), texels)
}

/// The model's scene without the studio (its lighting is `model_tests.rs`'s).
fn open(path: &Path) -> SceneDesc {
    let options = ModelOptions { studio: false };
    model_scene_with(path, options).unwrap_or_else(|e| panic!("{e}"))
}

fn named<'a>(d: &'a SceneDesc, name: &str) -> &'a NamedMaterial {
    d.materials
        .iter()
        .find(|m| m.name == name)
        .unwrap_or_else(|| {
            let names: Vec<_> = d.materials.iter().map(|m| &m.name).collect();
            panic!("no material {name:?} in {names:?}")
        })
}

fn bitmap(t: &Option<TextureDesc>) -> &BitmapTexture {
    match t.as_ref().map(|t| &t.texture) {
        Some(Texture::Bitmap(b)) => b,
        other => panic!("expected a bitmap, found {other:?}"),
    }
}

fn f(x: f32) -> f64 {
    x as f64
}

/// The glTF material of `base_color`, roughness, metallic and ior.
fn gltf_pbr(base_color: DVec3, roughness: f64, metallic: f64, ior: f64) -> MaterialDesc {
    MaterialDesc::GltfPbr(GltfPbrDesc {
        base_color,
        scalars: [roughness, metallic],
        ior,
        ..Default::default()
    })
}

/// Each glTF material is one `gltf_pbr` material, its factors as they are (roughness not
/// squared: the material squares it). Fails if the old mapping (a conductor, a plastic and a mix
/// of the two by the metallic, or a diffuse at ior 1) comes back: every scene material must be
/// the glTF one, and the built scene's BSDFs are `Material::GltfPbr`.
#[test]
fn factors_map_to_the_gltf_material() {
    let dir = Dir::new("mat-factors");
    let a = quads(json!([
        {"name": "Gold", "doubleSided": true, "pbrMetallicRoughness": {
            "baseColorFactor": [1.0, 0.75, 0.25, 0.5], "metallicFactor": 1, "roughnessFactor": 0.5}},
        {"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 0.125, 1],
            "metallicFactor": 0, "roughnessFactor": 0.25},
         "extensions": {"KHR_materials_ior": {"ior": 1.25}}},
        {"doubleSided": true, "pbrMetallicRoughness": {"metallicFactor": 0.5}},
        {"pbrMetallicRoughness": {"metallicFactor": 0}, "extensions": {"KHR_materials_ior": {"ior": 1}}},
    ]));
    let d = open(&a.write_glb(&dir, "m.glb"));
    let gold = named(&d, "materials[0] Gold");
    assert_eq!(
        gold.material,
        gltf_pbr(DVec3::new(1.0, 0.75, 0.25), 0.5, 1.0, 1.5),
        "the base colour's alpha is not a colour"
    );
    assert!(gold.two_sided);
    let dielectric = named(&d, "materials[1]");
    assert_eq!(
        dielectric.material,
        gltf_pbr(DVec3::new(0.5, 0.25, 0.125), 0.25, 0.0, 1.25)
    );
    assert!(!dielectric.two_sided, "doubleSided defaults to false");
    let half = named(&d, "materials[2]");
    assert_eq!(
        half.material,
        gltf_pbr(DVec3::ONE, 1.0, 0.5, 1.5),
        "the defaults: base colour 1, roughness 1, ior 1.5; metallic 0.5 is no mix"
    );
    assert!(half.two_sided && half.mix.is_none());
    // ior 1: no reflection at normal incidence, Schlick's towards grazing (the specification's).
    assert_eq!(
        named(&d, "materials[3]").material,
        gltf_pbr(DVec3::ONE, 1.0, 0.0, 1.0)
    );
    assert_eq!(d.materials.len(), 4, "one material per glTF material");
    assert!(
        d.materials
            .iter()
            .all(|m| matches!(m.material, MaterialDesc::GltfPbr(_)) && m.parts().is_none())
    );
    let shape_materials: Vec<&str> = d
        .shapes
        .iter()
        .map(|s| d.materials[s.material.unwrap()].name.as_str())
        .collect();
    assert_eq!(
        shape_materials,
        [
            "materials[0] Gold",
            "materials[1]",
            "materials[2]",
            "materials[3]"
        ]
    );
    assert_eq!(d.background, BackgroundDesc::Constant(DVec3::ONE));
    assert!(d.warnings.is_empty(), "{:?}", d.warnings);
    let scene = Scene::from_desc(&d).unwrap();
    assert!(scene.mixes.iter().all(Option::is_none));
    let i = d
        .materials
        .iter()
        .position(|m| m.name == "materials[2]")
        .unwrap();
    assert_eq!(
        scene.materials[i],
        crate::materials::Material::GltfPbr(crate::materials::GltfPbr {
            base_color: Vec3::ONE,
            metallic: 0.5,
            roughness: 1.0,
            ..Default::default()
        })
    );
}

#[test]
fn a_primitive_without_a_material_gets_the_default_material() {
    let dir = Dir::new("mat-default");
    let d = open(&quad(U16).write_glb(&dir, "q.glb"));
    assert_eq!(d.materials.len(), 1);
    let m = named(&d, "default material");
    // glTF 2.0, 3.9.6: every property at its default: base colour 1, metallic 1, roughness 1,
    // single-sided.
    assert_eq!(m.material, gltf_pbr(DVec3::ONE, 1.0, 1.0, 1.5));
    assert!(!m.two_sided && m.mix.is_none());
}

/// The base colour texture from a GLB buffer view, a data URI and an external file (its name
/// percent-encoded): the same texels, sRGB-decoded, times the factor, with the sampler's wrap
/// mode and `KHR_texture_transform`'s offset and scale.
#[test]
fn textures_from_a_glb_a_data_uri_and_a_file_are_the_same() {
    let dir = Dir::new("mat-textures");
    let (bytes, texels) = test_png();
    let material = json!([{"pbrMetallicRoughness": {
        "baseColorFactor": [0.5, 1, 1, 1], "metallicFactor": 1, "roughnessFactor": 0,
        "baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {
            "offset": [0.5, 0.25], "scale": [2, 4]}}}}}]);
    let mut files = Vec::new();
    for (case, image) in ["glb", "data", "file"].into_iter().zip([
        Value::Null,
        json!({"uri": format!("data:image/png;base64,{}", base64(&bytes))}),
        json!({"uri": "tex%20a.png"}),
    ]) {
        let mut a = quads(material.clone());
        let image = match image {
            Value::Null => json!({"bufferView": a.view(&bytes), "mimeType": "image/png"}),
            other => other,
        };
        a.root.insert("images".into(), json!([image]));
        a.root
            .insert("samplers".into(), json!([{"wrapS": 33071, "wrapT": 33071}]));
        a.root
            .insert("textures".into(), json!([{"source": 0, "sampler": 0}]));
        std::fs::write(dir.file("tex a.png"), &bytes).unwrap();
        let path = match case {
            "glb" => a.write_glb(&dir, "t.glb"),
            _ => a.write_embedded(&dir, &format!("t-{case}.gltf"), "application/octet-stream"),
        };
        let d = open(&path);
        assert!(d.warnings.is_empty(), "{case}: {:?}", d.warnings);
        let m = named(&d, "materials[0]");
        let b = bitmap(&m.textures.albedo);
        let o = b.options();
        assert_eq!(o.wrap, WrapMode::Clamp, "{case}");
        assert_eq!(
            (o.uv.scale, o.uv.offset),
            (Vec2::new(2.0, 4.0), Vec2::new(0.5, 0.25))
        );
        assert_eq!(
            o.scale,
            Vec3::new(0.5, 1.0, 1.0),
            "{case}: the base colour factor"
        );
        assert!(!b.raw, "{case}: base colour is sRGB");
        let expected: Vec<Vec3> = texels
            .iter()
            .map(|t| Vec3::from_array(t.map(|c| srgb_to_linear(c as f64 / 255.0) as f32)))
            .collect();
        assert_eq!(b.image().data, expected, "{case}");
        let file = b.file.file_name().unwrap().to_string_lossy().into_owned();
        match case {
            "file" => assert_eq!(file, "tex a.png", "an external image keeps its path"),
            _ => assert!(file.ends_with("#images[0]"), "{case}: {file}"),
        }
        Scene::from_desc(&d).unwrap_or_else(|e| panic!("{case}: {e}"));
        files.push(b.image().clone());
    }
    assert!(files.windows(2).all(|w| w[0] == w[1]));
}

/// The base colour's alpha (texture alpha × factor) becomes the top material's opacity: MASK
/// against `alphaCutoff` (default ½) per texel, 0 or 1; BLEND the alpha itself; a constant
/// without a texture, none where that is 1 (OPAQUE, or MASK at or above the cutoff); on an
/// emissive material it is named in the warning and left out.
#[test]
fn alpha_modes_become_opacities() {
    let dir = Dir::new("mat-alpha");
    // A 4 × 1 RGBA image, alphas 0, 60, 128, 255.
    let alphas = [0u8, 60, 128, 255];
    let mut bytes = Vec::new();
    let rgba: Vec<u8> = alphas.iter().flat_map(|&a| [200, 100, 50, a]).collect();
    image::RgbaImage::from_raw(4, 1, rgba)
        .unwrap()
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .unwrap();
    let textured = |mode: &str, extra: Value| {
        let mut m = json!({"alphaMode": mode, "pbrMetallicRoughness": {
            "baseColorFactor": [1, 1, 1, 0.8], "metallicFactor": 0,
            "baseColorTexture": {"index": 0}}});
        for (k, v) in extra.as_object().unwrap() {
            m[k] = v.clone();
        }
        m
    };
    let mut a = quads(json!([
        textured("MASK", json!({"alphaCutoff": 0.3})),
        textured("BLEND", json!({})),
        textured("OPAQUE", json!({})),
        {"alphaMode": "MASK", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.2]}},
        {"alphaMode": "BLEND", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.25]}},
        {"alphaMode": "MASK", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.6]}},
        {"alphaMode": "BLEND", "emissiveFactor": [1, 1, 1],
         "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.5]}},
    ]));
    let view = a.view(&bytes);
    a.root.insert(
        "images".into(),
        json!([{"bufferView": view, "mimeType": "image/png"}]),
    );
    a.root.insert("textures".into(), json!([{"source": 0}]));
    let d = open(&a.write_glb(&dir, "alpha.glb"));
    let texels = |i: usize| -> Vec<f32> {
        bitmap(&named(&d, &format!("materials[{i}]")).opacity)
            .image()
            .data
            .iter()
            .map(|c| c.x)
            .collect()
    };
    // MASK at 0.3: alpha × 0.8 = 0, 0.19, 0.40, 0.8.
    assert_eq!(texels(0), [0.0, 0.0, 1.0, 1.0]);
    let blend: Vec<f32> = alphas.iter().map(|&a| a as f32 / 255.0 * 0.8).collect();
    assert_eq!(texels(1), blend, "BLEND: linear alpha × factor");
    assert!(bitmap(&named(&d, "materials[0]").opacity).raw);
    let constant = |i: usize| {
        named(&d, &format!("materials[{i}]"))
            .opacity
            .as_ref()
            .map(|t| t.texture.eval_scalar(Vec2::ZERO))
    };
    assert_eq!(constant(2), None, "OPAQUE");
    assert_eq!(constant(3), Some(0.0), "MASK below the cutoff ½");
    assert_eq!(constant(4), Some(0.25), "BLEND: the factor");
    assert_eq!(constant(5), None, "MASK above the cutoff");
    assert_eq!(constant(6), None, "an emitter takes no opacity");
    assert_eq!(d.warnings.len(), 1, "{:?}", d.warnings);
    assert!(
        d.warnings[0].contains("materials[6].alphaMode on an emissive material"),
        "{:?}",
        d.warnings
    );
    let scene = Scene::from_desc(&d).unwrap_or_else(|e| panic!("{e}"));
    assert!(!scene.opacity.is_empty());
}

/// metallicRoughnessTexture: roughness (G) × factor and metallic (B) × factor as the glTF
/// material's textured scalars, read linearly (the material squares the filtered roughness, as
/// glTF does); no mix and no baked α.
#[test]
fn the_metallic_roughness_texture_gives_roughness_and_metallic() {
    let dir = Dir::new("mat-mr");
    let mut a = quads(json!([{"pbrMetallicRoughness": {
        "metallicFactor": 0.5, "roughnessFactor": 0.5,
        "metallicRoughnessTexture": {"index": 0}}}]));
    let view = a.view(&png(2, 1, vec![0, 128, 255, 7, 255, 0]));
    a.root.insert(
        "images".into(),
        json!([{"bufferView": view, "mimeType": "image/png"}]),
    );
    a.root.insert("textures".into(), json!([{"source": 0}]));
    let d = open(&a.write_glb(&dir, "mr.glb"));
    assert_eq!(d.materials.len(), 1);
    let m = named(&d, "materials[0]");
    assert!(m.mix.is_none());
    let [rough, metal] = [0, 1].map(|k| bitmap(&m.textures.principled[k]));
    for (t, channel) in [(rough, Channel::G), (metal, Channel::B)] {
        assert!(t.raw && t.options().channel == channel);
        assert_eq!(t.options().scale, Vec3::splat(0.5));
        assert_eq!(t.options().wrap, WrapMode::Repeat, "no sampler: repeat");
        assert_eq!(t.image().data[0], Vec3::new(0.0, 128.0 / 255.0, 1.0));
    }
    // At the texel centres (u = 0.25 and 0.75): G × 0.5 and B × 0.5.
    let (u0, u1) = (Vec2::new(0.25, 0.5), Vec2::new(0.75, 0.5));
    let [rough, metal] = [rough, metal].map(|t| Texture::Bitmap(t.clone()));
    assert_eq!(rough.eval_scalar(u0), 0.5 * 128.0 / 255.0);
    assert_eq!(rough.eval_scalar(u1), 0.5);
    assert_eq!(metal.eval_scalar(u0), 0.5);
    assert_eq!(metal.eval_scalar(u1), 0.0);
    let MaterialDesc::GltfPbr(p) = &m.material else {
        panic!("{:?}", m.material)
    };
    assert!((p.scalars[1] - 0.25).abs() < 1e-6, "metallic's mean");
    assert!(
        !d.materials.iter().any(|m| m.textures.alpha.is_some()),
        "no baked α without transmission"
    );
    // At a hit: the textures' values, the α their square.
    let scene = Scene::from_desc(&d).unwrap();
    let t = scene.material_textures[0].as_ref().expect("textured");
    let crate::materials::Material::GltfPbr(at) = t.at(&scene.materials[0], u1) else {
        panic!()
    };
    assert_eq!((at.roughness, at.metallic, at.alpha()), (0.5, 0.0, 0.25));
}

#[test]
fn emission_is_the_factor_times_the_strength_and_the_texture() {
    let dir = Dir::new("mat-emission");
    let mut a = quads(json!([
        {"emissiveFactor": [1, 0.5, 0.25],
         "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}}},
        {"emissiveFactor": [0.5, 0.5, 0.5], "emissiveTexture": {"index": 0}},
        {"emissiveTexture": {"index": 0}},
    ]));
    let view = a.view(&test_png().0);
    a.root.insert(
        "images".into(),
        json!([{"bufferView": view, "mimeType": "image/png"}]),
    );
    a.root.insert("textures".into(), json!([{"source": 0}]));
    let d = open(&a.write_glb(&dir, "e.glb"));
    assert_eq!(d.shapes[0].emission, DVec3::new(4.0, 2.0, 1.0));
    assert!(d.shapes[0].emission_texture.is_none());
    let t = bitmap(&d.shapes[1].emission_texture);
    assert_eq!(t.options().scale, Vec3::splat(0.5));
    assert!(!t.raw, "emission is sRGB");
    assert_eq!(
        d.shapes[2].emission,
        DVec3::ZERO,
        "the factor defaults to black"
    );
    assert!(d.shapes[2].emission_texture.is_none());
    // Whether the environment stays is the lighting rule's (`model_tests.rs`).
}

#[test]
fn transmission_is_a_dielectric_or_a_mix_with_one() {
    let dir = Dir::new("mat-transmission");
    let ior = json!({"ior": 1.33});
    let a = quads(json!([
        {"pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0.5},
         "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                        "KHR_materials_ior": ior, "KHR_materials_volume": {}}},
        {"pbrMetallicRoughness": {"metallicFactor": 0, "baseColorFactor": [0.5, 1, 1, 1]},
         "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.25}}},
        {"pbrMetallicRoughness": {"metallicFactor": 0.5, "roughnessFactor": 0},
         "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.5}}},
    ]));
    let d = open(&a.write_glb(&dir, "t.glb"));
    assert_eq!(
        named(&d, "materials[0]").material,
        MaterialDesc::Dielectric {
            ior: 1.33,
            alpha: 0.25,
            alpha_v: None,
            distribution: crate::materials::Distribution::Ggx,
        },
        "KHR_materials_ior as written (raw JSON, not rounded to f32)"
    );
    let m1 = named(&d, "materials[1]").mix.as_ref().unwrap();
    assert_eq!(m1.weight, f(0.25));
    let names = m1.materials.map(|i| d.materials[i].name.as_str());
    assert_eq!(names, ["materials[1] (opaque)", "materials[1] (glass)"]);
    assert_eq!(
        d.materials[m1.materials[0]].material,
        gltf_pbr(DVec3::new(0.5, 1.0, 1.0), 1.0, 0.0, 1.5),
        "the reflecting part is the glTF material without its metal"
    );
    // Metallic over a partly transmitting dielectric: two mixes.
    let m2 = named(&d, "materials[2]").mix.as_ref().unwrap();
    let names = m2.materials.map(|i| d.materials[i].name.as_str());
    assert_eq!(names, ["materials[2] (dielectric)", "materials[2] (metal)"]);
    assert_eq!(
        d.materials[m2.materials[1]].material,
        gltf_pbr(DVec3::ONE, 0.0, 1.0, 1.5)
    );
    let inner = d.materials[m2.materials[0]].mix.as_ref().unwrap();
    assert_eq!(inner.weight, 0.5);
    assert_eq!(
        d.materials[inner.materials[1]].material,
        MaterialDesc::Dielectric {
            ior: 1.5,
            alpha: 0.0,
            alpha_v: None,
            distribution: crate::materials::Distribution::Ggx,
        }
    );
    assert_eq!(d.warnings.len(), 1);
    let w = &d.warnings[0];
    assert!(w.contains("materials[1]: the base colour's tint"), "{w}");
    assert!(
        w.contains("materials[1]: thin-walled KHR_materials_transmission"),
        "{w}"
    );
    assert!(!w.contains("materials[0]: thin-walled"), "{w}");
    assert!(
        w.contains("materials[0].extensions.KHR_materials_volume"),
        "{w}"
    );
    let scene = Scene::from_desc(&d).unwrap();
    assert!(scene.has_transmission());
}

/// `KHR_materials_specular`: its factors become the material's `specular` and
/// `specular_color` (a colour above 1 allowed, as the extension allows it), its textures are
/// named in the warning; a factor out of range is an error at its glTF path.
#[test]
fn khr_materials_specular_gives_the_specular_weight_and_colour() {
    let dir = Dir::new("mat-specular");
    let a = quads(json!([
        {"pbrMetallicRoughness": {"metallicFactor": 0},
         "extensions": {"KHR_materials_specular": {
            "specularFactor": 0.5, "specularColorFactor": [2.0, 1.0, 0.25],
            "specularTexture": {"index": 0}}}},
        {"pbrMetallicRoughness": {"metallicFactor": 0},
         "extensions": {"KHR_materials_specular": {}}},
    ]));
    let d = open(&a.write_glb(&dir, "s.glb"));
    let MaterialDesc::GltfPbr(p) = &named(&d, "materials[0]").material else {
        panic!()
    };
    assert_eq!(
        (p.specular, p.specular_color),
        (0.5, DVec3::new(2.0, 1.0, 0.25))
    );
    assert_eq!(
        named(&d, "materials[1]").material,
        gltf_pbr(DVec3::ONE, 1.0, 0.0, 1.5),
        "the extension's defaults change nothing"
    );
    assert_eq!(d.warnings.len(), 1, "{:?}", d.warnings);
    let w = &d.warnings[0];
    assert!(
        w.contains("materials[0].extensions.KHR_materials_specular.specularTexture"),
        "{w}"
    );
    assert!(!w.contains("extensions.KHR_materials_specular,"), "{w}");
    let scene = Scene::from_desc(&d).unwrap();
    let crate::materials::Material::GltfPbr(m) = &scene.materials[0] else {
        panic!()
    };
    assert_eq!((m.specular, m.specular_color.x), (0.5, 2.0));
    for (bad, key) in [
        (json!({"specularFactor": 1.5}), "specularFactor"),
        (
            json!({"specularColorFactor": [1, -1, 1]}),
            "specularColorFactor",
        ),
    ] {
        let a = quads(json!([{"extensions": {"KHR_materials_specular": bad}}]));
        let e = model_scene(&a.write_glb(&dir, "bad.glb"))
            .expect_err("must be rejected")
            .to_string();
        assert!(
            e.contains(&format!(
                "materials[0].extensions.KHR_materials_specular.{key}"
            )),
            "{e}"
        );
    }
}

/// Everything lumis does not render is named in one warning.
#[test]
fn one_warning_names_every_feature_that_is_not_rendered() {
    let dir = Dir::new("mat-warning");
    let mut a = quads(json!([{
        "normalTexture": {"index": 0}, "occlusionTexture": {"index": 0},
        "alphaMode": "MASK", "alphaCutoff": 0.3,
        "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1}},
        "pbrMetallicRoughness": {"baseColorTexture": {"index": 1, "texCoord": 1,
            "extensions": {"KHR_texture_transform": {"rotation": 0.5}}}},
    }]));
    let colors = a.vec3(&[[1.0, 0.0, 0.0]; 4]);
    a.meshes[0]["primitives"][0]["attributes"]["COLOR_0"] = json!(colors);
    // A second primitive, without texture coordinates, in the same (textured) material.
    let pos = a.vec3(&QUAD.map(|p| [p[0], p[1], p[2] - 3.0]));
    let idx = a.indices(&QUAD_TRIS, U16);
    let mut p = primitive(pos, None, None, Some(idx));
    p["material"] = json!(0);
    let mesh = a.mesh(vec![p]);
    a.node(json!({ "mesh": mesh }));
    let view = a.view(&test_png().0);
    a.root.insert(
        "images".into(),
        json!([{"bufferView": view, "mimeType": "image/png"}]),
    );
    a.root.insert(
        "samplers".into(),
        json!([{"wrapS": 33071, "wrapT": 10497, "magFilter": 9728}]),
    );
    a.root.insert(
        "textures".into(),
        json!([{"source": 0}, {"source": 0, "sampler": 0}]),
    );
    a.root.insert(
        "extensionsUsed".into(),
        json!([
            "KHR_lights_punctual",
            "KHR_materials_variants",
            "KHR_materials_clearcoat",
            "KHR_texture_transform"
        ]),
    );
    let d = open(&a.write_glb(&dir, "w.glb"));
    assert_eq!(d.warnings.len(), 1, "{:?}", d.warnings);
    let w = &d.warnings[0];
    // The file is named by whoever prints the warning, once (issue 43 item 5).
    assert!(
        w.starts_with("glTF features lumis does not render: "),
        "{w}"
    );
    assert!(!w.contains("w.glb"), "{w}");
    // A path tracer computes occlusion: naming the occlusion map would change nothing.
    assert!(!w.contains("occlusionTexture"), "{w}");
    for name in [
        "materials[0].normalTexture",
        "materials[0].extensions.KHR_materials_clearcoat",
        "materials[0].pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform.rotation",
        "materials[0].pbrMetallicRoughness.baseColorTexture TEXCOORD_1",
        "samplers[0].wrapT",
        "samplers[0].magFilter NEAREST",
        "extension KHR_materials_variants",
        "extension KHR_materials_clearcoat",
        "nodes[0] meshes[0].primitives[0] COLOR_0",
        "nodes[1] meshes[1].primitives[0]: the textures of its material (it has no TEXCOORD_0)",
    ] {
        assert!(w.contains(name), "{name} is not in: {w}");
    }
    assert!(!w.contains("extension KHR_texture_transform"), "{w}");
    // Read as lights (`gltf_lights.rs`), so not named.
    assert!(!w.contains("extension KHR_lights_punctual"), "{w}");
    assert_eq!(
        w.matches("materials[0].normalTexture").count(),
        1,
        "each named once: {w}"
    );
}

/// Bad input: one error naming the file and the glTF path.
#[test]
fn bad_materials_textures_and_images_are_named_by_their_gltf_path() {
    let dir = Dir::new("mat-errors");
    let plain = json!({"pbrMetallicRoughness": {"metallicFactor": 0}});
    let with_third = |third: Value| quads(json!([plain, plain, third]));
    let error = |a: &Asset, name: &str| -> String {
        let path = a.write_glb(&dir, name);
        let e = model_scene(&path)
            .expect_err("must be rejected")
            .to_string();
        assert!(
            e.starts_with(&path.display().to_string()),
            "names the file: {e}"
        );
        assert!(!e.contains('\n'), "one line: {e}");
        e
    };
    let mut a = with_third(plain.clone());
    a.meshes[1]["primitives"][0]["material"] = json!(5);
    let e = error(&a, "material.glb");
    assert!(e.contains("meshes[1].primitives[0].material"), "{e}");

    let tex =
        |index: usize| json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": index}}});
    let mut a = with_third(tex(7));
    a.root.insert("images".into(), json!([{"uri": "wood.png"}]));
    a.root.insert("textures".into(), json!([{"source": 0}]));
    let e = error(&a, "texture.glb");
    assert!(
        e.contains("materials[2].pbrMetallicRoughness.baseColorTexture.index"),
        "{e}"
    );

    let mut a = with_third(tex(0));
    a.root.insert("images".into(), json!([{"uri": "wood.png"}]));
    a.root.insert("textures".into(), json!([{"source": 0}]));
    let e = error(&a, "image.glb");
    assert!(
        e.contains("materials[2].pbrMetallicRoughness.baseColorTexture: images[0] ('wood.png'): cannot read 'wood.png'"),
        "{e}"
    );
    std::fs::write(dir.file("wood.png"), b"not a png").unwrap();
    let e = error(&a, "image2.glb");
    assert!(
        e.contains("materials[2].pbrMetallicRoughness.baseColorTexture: images[0]"),
        "{e}"
    );
    assert!(e.contains("wood.png"), "{e}");

    let e = error(
        &with_third(json!({"pbrMetallicRoughness": {"baseColorFactor": [1, 1.5, 1, 1]}})),
        "factor.glb",
    );
    assert!(
        e.contains("materials[2].pbrMetallicRoughness.baseColorFactor[1]: 1.5 is outside [0, 1]"),
        "{e}"
    );
    let e = error(
        &with_third(json!({"extensions": {"KHR_materials_transmission": {
            "transmissionFactor": 1, "transmissionTexture": {"index": 3}}}})),
        "transmission.glb",
    );
    assert!(
        e.contains("materials[2].extensions.KHR_materials_transmission.transmissionTexture.index"),
        "{e}"
    );
    let e = error(
        &with_third(json!({"extensions": {"KHR_materials_ior": {"ior": 0.5}}})),
        "ior.glb",
    );
    assert!(
        e.contains("materials[2].extensions.KHR_materials_ior.ior: 0.5 must be at least 1"),
        "{e}"
    );
}

/// A required extension that lumis maps does not stop the file; another still does.
#[test]
fn required_material_extensions_that_lumis_reads_are_accepted() {
    let dir = Dir::new("mat-required");
    let mut a = quads(json!([{"pbrMetallicRoughness": {"metallicFactor": 0}}]));
    a.root.insert(
        "extensionsRequired".into(),
        json!(["KHR_texture_transform", "KHR_materials_ior"]),
    );
    let d = open(&a.write_glb(&dir, "ok.glb"));
    assert_eq!(d.shapes.len(), 1);
    a.root.insert(
        "extensionsRequired".into(),
        json!(["KHR_texture_transform", "KHR_materials_clearcoat"]),
    );
    let e = model_scene(&a.write_glb(&dir, "no.glb"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("requires glTF extension KHR_materials_clearcoat, which lumis does not support"),
        "{e}"
    );
}

/// `KHR_materials_unlit`: a black diffuse that emits its base colour (factor × sRGB texture),
/// named in the warning (it lights other surfaces too); a black one emits nothing.
#[test]
fn unlit_materials_emit_their_base_colour() {
    let dir = Dir::new("mat-unlit");
    let unlit = json!({"KHR_materials_unlit": {}});
    let mut a = quads(json!([
        {"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 1, 1]}, "extensions": unlit},
        {"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1],
            "baseColorTexture": {"index": 0}}, "extensions": unlit},
        {"pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1]}, "extensions": unlit},
    ]));
    let view = a.view(&test_png().0);
    a.root.insert(
        "images".into(),
        json!([{"bufferView": view, "mimeType": "image/png"}]),
    );
    a.root.insert("textures".into(), json!([{"source": 0}]));
    a.root
        .insert("extensionsUsed".into(), json!(["KHR_materials_unlit"]));
    let d = open(&a.write_glb(&dir, "u.glb"));
    let black = MaterialDesc::Diffuse {
        albedo: DVec3::ZERO,
    };
    for k in 0..3 {
        assert_eq!(named(&d, &format!("materials[{k}]")).material, black);
    }
    assert_eq!(d.shapes[0].emission, DVec3::new(0.5, 0.25, 1.0));
    let t = bitmap(&d.shapes[1].emission_texture);
    assert!(!t.raw, "the base colour texture is sRGB");
    assert_eq!(
        (d.shapes[2].emission, &d.shapes[2].emission_texture),
        (DVec3::ZERO, &None)
    );
    let w = d.warnings.join("\n");
    assert!(
        w.contains("materials[0].extensions.KHR_materials_unlit: an emitter of its base colour"),
        "{w}"
    );
    assert!(!w.contains("extension KHR_materials_unlit"), "{w}");
}
