//! Textured materials on the GPU (issue 17, item 7): the WGSL twins of `Texture::eval` and
//! `eval_scalar` (`textures/mod.wgsl`), of `MaterialTextures::at` (`material_at`) and of `Scene::uv`
//! (`surface_uv`) against the Rust functions, and a textured scene rendered on the GPU against
//! the CPU's render (`renderer/tests/gpu/textured_images.rs`).
//!
//! Tolerances (u = 2⁻²⁴). Vulkan rounds +, −, × correctly but may fuse a product into a sum
//! (FMA), so the two sides' `uv' = uv·s + o` differ by at most u·|uv·s| + 2u·|uv'|, and the texel
//! coordinate `x = uv'·n − ½` by Δx ≤ u·(n|uv·s| + 3n|uv'| + 2|x|), doubled for safety. Bilinear
//! filtering is continuous in x (also across cells and wrap seams), so a lookup agrees to
//! Δx·(texel range) per axis plus 16u·(largest texel) for the blend's own rounding, times the
//! bitmap's scale. Where uv' and x are exact on both sides (identity transform, power-of-two size)
//! Δx = 0: those lookups, including the ones beyond 2²⁴ texels and at infinite or NaN uv, must
//! agree to the blend's rounding alone, which checks the exact wrap of huge indices. A
//! checkerboard is exact, except within the Δuv' above of a square's edge, where either colour
//! is right. The luminance adds 4u·max|c|. Everything else (kind, wrap, channel dispatch,
//! constants, NaN for NaN) must agree exactly.

use crate::gpu_common;
use glam::{Vec2, Vec3};
use gpu_common::{Compare, context};
use lumis::geometry::Ray;
use lumis::geometry::primitive::{NONE, Shape};
use lumis::gpu::GpuScene;
use lumis::gpu::kernel::run_snippet;
use lumis::image_io::Image;
use lumis::integrator::Settings;
use lumis::materials::textured::MaterialTextures;
use lumis::materials::{ConductorFresnel, Material};
use lumis::rng::Rng;
use lumis::scene::mesh::{MeshData, obj};
use lumis::scene::{Scene, parse_scene};
use lumis::textures::{
    BitmapOptions, BitmapTexture, Channel, Checkerboard, Texture, UvTransform, WrapMode,
};
use std::f32::consts::{PI, TAU};
use std::sync::Arc;

/// f32's unit roundoff, 2⁻²⁴.
const U: f32 = f32::EPSILON / 2.0;

fn run(gpu: &GpuScene, body: &str, inputs: &[[f32; 4]], ins: usize, outs: usize) -> Vec<[f32; 4]> {
    run_snippet(gpu, &Settings::default(), body, inputs, ins, outs)
        .unwrap_or_else(|e| panic!("{e}"))
}

/// A scene of `n` conductor materials (the textures' holders) and one sphere.
fn holder_scene(n: usize) -> Scene {
    let materials: Vec<String> = (0..n)
        .map(|i| {
            format!(
                r#""t{i}": {{"type": "conductor", "reflectance": [0.5, 0.5, 0.5], "alpha": 0.1}}"#
            )
        })
        .collect();
    let json = format!(
        r#"{{"camera": {{"from": [0, 0, -3], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40, "width": 2, "height": 2}},
            "materials": {{{}}},
            "shapes": [{{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "t0"}}]}}"#,
        materials.join(",")
    );
    Scene::from_desc(&parse_scene(&json).unwrap_or_else(|e| panic!("{e}"))).unwrap()
}

/// A `w × h` image of texels in [0.05, 0.95] (grey ones if `grey`).
fn image(w: u32, h: u32, grey: bool, r: &mut Rng) -> Arc<Image> {
    let data = (0..w * h)
        .map(|_| {
            let c = Vec3::new(r.next_f32(), r.next_f32(), r.next_f32()) * 0.9 + 0.05;
            if grey { Vec3::splat(c.x) } else { c }
        })
        .collect();
    Arc::new(Image {
        width: w,
        height: h,
        data,
    })
}

/// The transforms every kind is tried with: identity, a general one with a negative scale, and
/// one that freezes u.
fn transforms() -> [UvTransform; 3] {
    [
        UvTransform::IDENTITY,
        UvTransform {
            scale: Vec2::new(3.7, -2.3),
            offset: Vec2::new(0.25, -0.6),
        },
        UvTransform {
            scale: Vec2::new(0.0, 1.5),
            offset: Vec2::new(0.3, 0.0),
        },
    ]
}

/// Every texture kind × wrap mode × channel × transform: bitmaps of 1×1, 4×4 and 16×8 texels
/// (powers of two: exact texel coordinates under the identity), 3×5 and 7×2, a grey 4×2 (the
/// luminance's exact grey branch), with and without a colour scale; checkerboards; constants.
fn textures_under_test(r: &mut Rng) -> Vec<Texture> {
    let images = [
        image(1, 1, false, r),
        image(4, 4, false, r),
        image(16, 8, false, r),
        image(3, 5, false, r),
        image(7, 2, false, r),
        image(4, 2, true, r),
    ];
    let channels = [Channel::Luminance, Channel::R, Channel::G, Channel::B];
    let mut out = Vec::new();
    for (k, img) in images.iter().enumerate() {
        for wrap in [WrapMode::Repeat, WrapMode::Mirror, WrapMode::Clamp] {
            for (c, &channel) in channels.iter().enumerate() {
                for uv in transforms() {
                    let grey = k == 5;
                    let scale = if (k + c) % 2 == 1 && !grey {
                        Vec3::new(1.5, 0.5, 2.0)
                    } else {
                        Vec3::ONE
                    };
                    let options = BitmapOptions {
                        wrap,
                        uv,
                        scale,
                        channel,
                    };
                    out.push(Texture::Bitmap(BitmapTexture::new(img.clone(), options)));
                }
            }
        }
    }
    for uv in transforms() {
        out.push(Texture::Checkerboard(Checkerboard {
            color0: Vec3::new(0.9, 0.2, 0.1),
            color1: Vec3::new(0.05, 0.4, 0.8),
            uv,
        }));
    }
    out.push(Texture::Constant(Vec3::new(0.3, 0.6, 0.9)));
    out.push(Texture::Constant(Vec3::splat(0.25)));
    out
}

/// Lookup points: exact special values (edges, tiny, negative, beyond 2²⁴ texels, beyond 2⁶³,
/// infinite, NaN) paired with each other, texel centres and edges of an `n × m` bitmap, and
/// random points in [−3, 4]².
fn lookup_points(n: u32, m: u32, r: &mut Rng) -> Vec<Vec2> {
    let s = [
        0.0,
        1.0,
        -1.0,
        0.5,
        1e-8,
        -1e-8,
        1.0 - U,
        1.0 + 2.0 * U,
        2.0,
        -2.5,
        1000.3,
        -777.7,
        123_456.7,
        -5.0e6,
        3.0e7,
        -4.1e9,
        1e19,
        -1e19,
        3e38,
        -3e38,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
    ];
    let mut out = Vec::new();
    for (i, &a) in s.iter().enumerate() {
        out.push(Vec2::new(a, s[(i * 7 + 3) % s.len()]));
        out.push(Vec2::new(r.next_f32(), a));
    }
    // Texel centres (k + ½)/n and edges k/n, two periods either side.
    let (n2, m2) = (2 * n as i32, 2 * m as i32);
    for k in -2 * n2..=3 * n2 {
        out.push(Vec2::new(k as f32 / n2 as f32, r.next_f32()));
    }
    for k in -2 * m2..=3 * m2 {
        out.push(Vec2::new(r.next_f32() * 3.0, k as f32 / m2 as f32));
    }
    for _ in 0..48 {
        out.push(r.next_2d() * 7.0 - 3.0);
    }
    out
}

/// Δx of one axis (module doc); 0 where the coordinate is exact on both sides.
fn texel_coordinate_error(uv: f32, s: f32, o: f32, n: u32) -> f32 {
    if s == 1.0 && o == 0.0 && n.is_power_of_two() {
        return 0.0;
    }
    let p = uv * s + o;
    let n = n as f32;
    let x = p * n - 0.5;
    2.0 * U * (n * (uv * s).abs() + 3.0 * n * p.abs() + 2.0 * x.abs())
}

/// Δuv' of one axis of a checkerboard (module doc); 0 under the identity.
fn uv_error(uv: f32, s: f32, o: f32) -> f32 {
    if s == 1.0 && o == 0.0 {
        return 0.0;
    }
    2.0 * U * ((uv * s).abs() + 3.0 * (uv * s + o).abs())
}

/// Distance (in f64) from `p` to the nearest checkerboard edge k/2.
fn edge_distance(p: f32) -> f64 {
    let p = p as f64 * 2.0;
    (p - p.round()).abs() / 2.0
}

/// Per channel, the largest texel and the range, of a bitmap.
fn texel_stats(b: &BitmapTexture) -> (Vec3, Vec3) {
    let d = &b.image().data;
    let lo = d.iter().fold(Vec3::splat(f32::INFINITY), |a, &t| a.min(t));
    let hi = d
        .iter()
        .fold(Vec3::splat(f32::NEG_INFINITY), |a, &t| a.max(t));
    (hi, hi - lo)
}

/// WGSL item: inputs (bits of the material, u, v, _); outputs the colour texture's value and the
/// roughness texture's scalar (both slots hold the same texture; the roughness slot's low 16
/// bits are α's id, `roughness_slot` in `gpu/scene/materials.rs`).
const LOOKUP_BODY: &str = "let a = inp(0u);
    let m = materials[bitcast<u32>(a.x)];
    let uv = tex_uv(a.yz);
    let alpha = bitcast<u32>(m.c.w) & 0xFFFFu;
    outp(0u, vec4f(texture_eval(bitcast<u32>(m.a.w), uv), texture_eval_scalar(alpha, uv)));";

/// `texture_eval` and `texture_eval_scalar` against `Texture::eval` and `eval_scalar` for every
/// texture of [`textures_under_test`] at its [`lookup_points`] (41936 lookups), to the
/// tolerances of the module doc; seed 17/70.
#[test]
fn texture_lookups_match_the_cpu() {
    let Some(ctx) = context() else {
        return;
    };
    let mut r = Rng::new(17, 70, 0);
    let textures = textures_under_test(&mut r);
    let mut scene = holder_scene(textures.len());
    for (i, t) in textures.iter().enumerate() {
        let textures = MaterialTextures::new(
            None,
            Some(t.clone()),
            Some(t.clone()),
            None,
            &scene.materials[i],
        );
        scene.material_textures[i] = Some(textures.unwrap());
    }
    let gpu = GpuScene::new(ctx, Arc::new(scene)).unwrap();
    let mut items: Vec<(usize, Vec2)> = Vec::new();
    for (i, t) in textures.iter().enumerate() {
        let (n, m) = match t {
            Texture::Bitmap(b) => (b.image().width, b.image().height),
            _ => (2, 2),
        };
        items.extend(lookup_points(n, m, &mut r).into_iter().map(|uv| (i, uv)));
    }
    let inputs: Vec<[f32; 4]> = items
        .iter()
        .map(|&(i, uv)| [f32::from_bits(i as u32), uv.x, uv.y, 0.0])
        .collect();
    let out = run(&gpu, LOOKUP_BODY, &inputs, 1, 1);
    let mut bitmap = Compare::new("bitmap lookup", 0.0, 0.0);
    let mut exact = Compare::new("bitmap lookup with exact texel coordinates", 0.0, 0.0);
    let mut scalar = Compare::new("scalar", 0.0, 0.0);
    let mut other = Compare::new("checkerboard and constant", 0.0, 0.0);
    let (mut far, mut ambiguous, mut non_finite) = (0, 0, 0);
    for (&(i, uv), o) in items.iter().zip(&out) {
        let t = &textures[i];
        let what = format!("texture {i} at uv ({:e}, {:e})", uv.x, uv.y);
        let want = t.eval(uv);
        let got = Vec3::new(o[0], o[1], o[2]);
        non_finite += !want.is_finite() as usize;
        // What the scalar slot must read: the CPU's, or at a checkerboard's edge either colour's.
        let mut want_scalar = t.eval_scalar(uv);
        let tol = match t {
            Texture::Bitmap(b) => {
                let (img, opt) = (b.image(), b.options());
                let (hi, range) = texel_stats(b);
                let dx = texel_coordinate_error(uv.x, opt.uv.scale.x, opt.uv.offset.x, img.width)
                    + texel_coordinate_error(uv.y, opt.uv.scale.y, opt.uv.offset.y, img.height);
                let tol = (range * dx + hi * (16.0 * U)) * opt.scale;
                let p = opt.uv.apply(uv);
                let beyond = |t: f32, n: u32| (t * n as f32).abs() >= 16_777_216.0;
                let c = if dx == 0.0 {
                    far += (beyond(p.x, img.width) || beyond(p.y, img.height)) as usize;
                    &mut exact
                } else {
                    &mut bitmap
                };
                for k in 0..3 {
                    c.scalar_conditioned(got[k], want[k], tol[k], &what);
                }
                tol.max_element()
            }
            Texture::Checkerboard(cb) => {
                let p = cb.uv.apply(uv);
                let du = uv_error(uv.x, cb.uv.scale.x, cb.uv.offset.x);
                let dv = uv_error(uv.y, cb.uv.scale.y, cb.uv.offset.y);
                let near = |p: f32, d: f32| d > 0.0 && edge_distance(p) <= d as f64;
                if near(p.x, du) || near(p.y, dv) {
                    ambiguous += 1;
                    let either = got == cb.color0 || got == cb.color1;
                    other.scalar(either as u32 as f32, 1.0, &format!("{what}: one colour"));
                    if got == cb.color1 {
                        want_scalar = t.channel().pick(cb.color1);
                    } else {
                        want_scalar = t.channel().pick(cb.color0);
                    }
                } else {
                    other.v3([o[0], o[1], o[2], 0.0], want, &what);
                }
                0.0
            }
            Texture::Constant(_) => {
                other.v3([o[0], o[1], o[2], 0.0], want, &what);
                0.0
            }
            Texture::MeshAttribute(_) => unreachable!("the scene has no meshes"),
        };
        let largest = want.abs().max_element();
        scalar.scalar_conditioned(o[3], want_scalar, tol + 4.0 * U * largest, &what);
    }
    eprintln!(
        "{} lookups of {} textures: {} with exact texel coordinates ({far} beyond 2^24 texels), \
         {ambiguous} checkerboard points at an edge, {non_finite} NaN on the CPU",
        items.len(),
        textures.len(),
        exact.n / 3
    );
    assert!(
        far >= 300 && non_finite >= 500,
        "{far} far, {non_finite} NaN"
    );
    bitmap.finish(0);
    exact.finish(0);
    scalar.finish(0);
    other.finish(0);
}

/// Materials with every textured slot, for `material_at`: their textures take exact values at
/// the points tried (checkerboard square centres, texel centres of a power-of-two bitmap).
fn resolution_scene() -> Scene {
    let json = r#"{
      "camera": {"from": [0, 0, -3], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40, "width": 2, "height": 2},
      "materials": {
        "matte": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]},
        "smooth_plastic": {"type": "plastic", "albedo": [0.5, 0.5, 0.5], "alpha": 0.0},
        "rough_plastic": {"type": "plastic", "albedo": [0.5, 0.5, 0.5], "alpha": 0.2, "ior": 1.4},
        "gold": {"type": "conductor", "eta": [0.2, 0.4, 1.4], "k": [3.5, 2.4, 1.8], "alpha": 0.2},
        "tinted": {"type": "conductor", "reflectance": [0.9, 0.8, 0.7], "alpha": 0.3},
        "glass": {"type": "dielectric", "ior": 1.5, "alpha": 0.1},
        "plain": {"type": "diffuse", "albedo": [0.25, 0.5, 0.75]},
        "principled": {"type": "principled", "spec_trans": 0.5, "sheen": 0.3},
        "thin": {"type": "principled_thin", "spec_trans": 0.5, "sheen": 0.3},
        "gltf": {"type": "gltf_pbr", "metallic": 0.5, "roughness": 0.5},
        "gltf_metallic": {"type": "gltf_pbr", "base_color": [0.9, 0.6, 0.2], "roughness": 0.3}
      },
      "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "matte"}]
    }"#;
    let mut scene = Scene::from_desc(&parse_scene(json).unwrap()).unwrap();
    let checker = |a: Vec3, b: Vec3| {
        Some(Texture::Checkerboard(Checkerboard {
            color0: a,
            color1: b,
            uv: UvTransform::IDENTITY,
        }))
    };
    let mut r = Rng::new(17, 71, 0);
    // Texel values in [0.05, 0.95], some green channels 0: a smooth α (below SMOOTH_ALPHA).
    let mut img = (*image(4, 4, false, &mut r)).clone();
    for t in img.data.iter_mut().step_by(3) {
        t.y = 0.0;
    }
    let bitmap = |channel| {
        Some(Texture::Bitmap(BitmapTexture::new(
            Arc::new(img.clone()),
            BitmapOptions {
                channel,
                ..BitmapOptions::default()
            },
        )))
    };
    // Built by `MaterialTextures::new`, as the scene builder does, so a kind's slots are checked.
    let mut set = |name: &str, [albedo, reflectance, alpha]: [Option<Texture>; 3]| {
        let i = scene.material_names.iter().position(|n| n == name).unwrap();
        let t = MaterialTextures::new(albedo, reflectance, alpha, None, &scene.materials[i]);
        scene.material_textures[i] = Some(t.unwrap());
    };
    set(
        "matte",
        [
            checker(Vec3::new(0.8, 0.2, 0.1), Vec3::new(0.1, 0.5, 0.9)),
            None,
            None,
        ],
    );
    // Black squares: a smooth coat over a black base has no smooth part there.
    set(
        "smooth_plastic",
        [checker(Vec3::new(0.5, 0.4, 0.3), Vec3::ZERO), None, None],
    );
    set("rough_plastic", [bitmap(Channel::Luminance), None, None]);
    // A textured reflectance turns the complex Fresnel into a tint; α 0 squares are mirrors.
    set(
        "gold",
        [
            None,
            bitmap(Channel::Luminance),
            checker(Vec3::ZERO, Vec3::splat(0.4)),
        ],
    );
    set("tinted", [None, None, bitmap(Channel::G)]);
    set(
        "glass",
        [None, None, checker(Vec3::splat(0.25), Vec3::ZERO)],
    );
    // A principled's base colour in the colour slot and four of its scalars (slots 0, 2, 3, 9:
    // each vec4 of its record).
    let i = scene
        .material_names
        .iter()
        .position(|n| n == "principled")
        .unwrap();
    let base = checker(Vec3::new(0.8, 0.2, 0.1), Vec3::new(0.1, 0.5, 0.9));
    let mut t = MaterialTextures::new(base, None, None, None, &scene.materials[i]).unwrap();
    t.principled[0] = bitmap(Channel::G);
    t.principled[2] = checker(Vec3::ZERO, Vec3::ONE);
    t.principled[3] = bitmap(Channel::R);
    t.principled[9] = checker(Vec3::splat(0.2), Vec3::splat(0.9));
    scene.material_textures[i] = Some(t);
    // A thin principled's: its own slot order (`ThinParam::ALL`), slots 1, 5, 7 and 8 (b, c
    // and d of its record), diff_trans and η beyond [0, 1].
    let i = scene
        .material_names
        .iter()
        .position(|n| n == "thin")
        .unwrap();
    let base = checker(Vec3::new(0.3, 0.7, 0.2), Vec3::new(0.5, 0.7, 0.2));
    let mut t = MaterialTextures::new(base, None, None, None, &scene.materials[i]).unwrap();
    t.principled[1] = bitmap(Channel::B);
    t.principled[5] = checker(Vec3::ZERO, Vec3::ONE);
    t.principled[7] = checker(Vec3::splat(0.4), Vec3::splat(1.6));
    t.principled[8] = checker(Vec3::splat(1.2), Vec3::splat(1.8));
    scene.material_textures[i] = Some(t);
    // glTF materials: base colour, roughness (G) and metallic (B, as glTF's texture holds them),
    // both ids in c.w; and a metallic alone (the roughness half 0xFFFF).
    let i = scene
        .material_names
        .iter()
        .position(|n| n == "gltf")
        .unwrap();
    let base = checker(Vec3::new(0.8, 0.2, 0.1), Vec3::new(0.1, 0.5, 0.9));
    let mut t = MaterialTextures::new(base, None, None, None, &scene.materials[i]).unwrap();
    t.principled[0] = bitmap(Channel::G);
    t.principled[1] = bitmap(Channel::B);
    scene.material_textures[i] = Some(t);
    let i = scene
        .material_names
        .iter()
        .position(|n| n == "gltf_metallic")
        .unwrap();
    let mut t = MaterialTextures::new(None, None, None, None, &scene.materials[i]).unwrap();
    t.principled[1] = checker(Vec3::ZERO, Vec3::ONE);
    scene.material_textures[i] = Some(t);
    scene
}

/// `material_at` (and `material_textured`) against `MaterialTextures::at` for every textured
/// slot of every kind (the glTF material's too), at 4096 points where the textures are exact (centres of checkerboard
/// squares and of texels), so every field must agree exactly, the recomputed has-a-smooth-part
/// flag (a plastic's black base, a conductor's or dielectric's α below SMOOTH_ALPHA) and the
/// conductor's switch to a tint included; untextured materials are not touched. Seed 17/72.
#[test]
fn textured_materials_resolve_as_on_the_cpu() {
    let Some(ctx) = context() else {
        return;
    };
    let scene = Arc::new(resolution_scene());
    let gpu = GpuScene::new(ctx, scene.clone()).unwrap();
    let mut r = Rng::new(17, 72, 0);
    let n = scene.materials.len() as u32;
    let items: Vec<(u32, Vec2)> = (0..4096)
        .map(|k| {
            // (k + ½)/4, k in −4..12: the 4×4 bitmap's texel centres (x = 4u − ½ = k: one
            // texel, weight 1), inside the checkerboard's squares of side ½ (never at k/2).
            let c = |x: f32| ((x * 16.0).floor() - 4.0 + 0.5) / 4.0;
            (k % n, Vec2::new(c(r.next_f32()), c(r.next_f32())))
        })
        .collect();
    let inputs: Vec<[f32; 4]> = items
        .iter()
        .map(|&(m, uv)| [f32::from_bits(m), uv.x, uv.y, 0.0])
        .collect();
    let out = run(
        &gpu,
        "let a = inp(0u);
         let base = materials[bitcast<u32>(a.x)];
         var m = base;
         if material_textured(base) {
             m = material_at(base, tex_uv(a.yz));
         }
         outp(0u, bitcast<vec4f>(m.h));
         outp(1u, m.a);
         outp(2u, m.c);
         outp(3u, vec4f(select(0.0, 1.0, material_textured(base)), 0.0, 0.0, 0.0));
         outp(4u, m.b);
         outp(5u, m.d);",
        &inputs,
        1,
        6,
    );
    let (mut flips, mut tints, mut principled, mut thin, mut gltf) = (0, 0, 0, 0, 0);
    for (&(mi, uv), o) in items.iter().zip(out.chunks(6)) {
        let what = format!("material {} at {uv}", scene.material_names[mi as usize]);
        let base = &scene.materials[mi as usize];
        let textures = &scene.material_textures[mi as usize];
        assert_eq!(o[3][0] == 1.0, textures.is_some(), "{what}: textured");
        let want = textures.as_ref().map_or(base.clone(), |t| t.at(base, uv));
        let h = o[0].map(f32::to_bits);
        assert_eq!(h[3] == 1, want.has_smooth_part(), "{what}: smooth part");
        flips += (want.has_smooth_part() != base.has_smooth_part()) as usize;
        let xyz = |v: [f32; 4]| Vec3::new(v[0], v[1], v[2]);
        match &want {
            Material::Diffuse(d) => assert_eq!(xyz(o[1]), d.albedo, "{what}"),
            Material::Plastic(p) => {
                assert_eq!(xyz(o[1]), p.albedo(), "{what}");
                assert_eq!(o[2][0], p.alpha(), "{what}: the coat is unchanged");
            }
            Material::Conductor(c) => {
                let m = &c.microfacet;
                assert_eq!((o[2][0], o[2][1]), (m.alpha_u, m.alpha_v), "{what}: alpha");
                match c.fresnel {
                    ConductorFresnel::Tint(t) => {
                        tints += matches!(
                            base,
                            Material::Conductor(b) if matches!(b.fresnel, ConductorFresnel::Complex { .. })
                        ) as usize;
                        assert_eq!(h[2], 1, "{what}: FRESNEL_TINT");
                        assert_eq!(xyz(o[1]), t, "{what}: tint");
                    }
                    ConductorFresnel::Complex { eta, .. } => {
                        assert_eq!(h[2], 0, "{what}: FRESNEL_COMPLEX");
                        assert_eq!(xyz(o[1]), eta, "{what}: eta");
                    }
                }
            }
            Material::Dielectric(d) => {
                let m = &d.microfacet;
                assert_eq!(
                    (o[1][0], o[2][0], o[2][1]),
                    (d.ior, m.alpha_u, m.alpha_v),
                    "{what}"
                );
            }
            Material::ThinDielectric(t) => assert_eq!(o[1][0], t.ior, "{what}"),
            Material::Principled(p) => {
                principled += 1;
                assert_eq!(xyz(o[1]), p.base_color, "{what}: base colour");
                let b = [p.roughness, p.anisotropic, p.metallic, p.spec_trans];
                assert_eq!(o[4], b, "{what}: b");
                assert_eq!(
                    xyz(o[2]),
                    Vec3::new(p.spec_tint, p.sheen, p.sheen_tint),
                    "{what}"
                );
                let d = [p.flatness, p.clearcoat, p.clearcoat_gloss, p.eta];
                assert_eq!(o[5], d, "{what}: d");
            }
            Material::PrincipledThin(p) => {
                thin += 1;
                assert_eq!(xyz(o[1]), p.base_color, "{what}: base colour");
                let b = [p.roughness, p.anisotropic, p.spec_trans, p.spec_tint];
                assert_eq!(o[4], b, "{what}: b");
                let c = Vec3::new(p.sheen, p.sheen_tint, p.flatness);
                assert_eq!(xyz(o[2]), c, "{what}: c");
                assert_eq!((o[5][0], o[5][1]), (p.diff_trans, p.eta), "{what}: d");
            }
            Material::GltfPbr(p) => {
                gltf += 1;
                assert_eq!(xyz(o[1]), p.base_color, "{what}: base colour");
                let b = [p.roughness, p.metallic, p.ior];
                assert_eq!([o[4][0], o[4][1], o[4][2]], b, "{what}: b");
            }
        }
    }
    assert!(
        principled > 300 && thin > 300 && gltf > 600,
        "{principled} principled, {thin} thin, {gltf} glTF points"
    );
    eprintln!("{flips} points changed the smooth-part flag, {tints} turned a conductor to a tint");
    assert!(flips > 500 && tints > 200, "{flips} flips, {tints} tints");
}

/// A small grid mesh with texture coordinates beyond [0, 1], written to a temporary OBJ.
fn grid_mesh(uvs: bool) -> MeshData {
    let mut m = MeshData {
        uvs: uvs.then(Vec::new),
        ..MeshData::default()
    };
    for i in 0..4 {
        for j in 0..4 {
            m.positions.push(Vec3::new(
                j as f32 * 0.5,
                i as f32 * 0.4 + 0.1 * j as f32,
                0.0,
            ));
            if let Some(uv) = &mut m.uvs {
                uv.push(Vec2::new(j as f32 * 0.9 - 0.7, 2.0 - i as f32 * 1.3));
            }
        }
    }
    for i in 0..3 {
        for j in 0..3 {
            let a = 4 * i + j;
            m.indices.push([a, a + 1, a + 5]);
            m.indices.push([a, a + 5, a + 4]);
        }
    }
    m
}

/// One shape of every kind: a sphere, a tilted disk, a quad, a rotated box, `triangles`
/// (barycentrics), a mesh with texture coordinates and one without, a slanted cylinder with its
/// own u axis.
fn uv_scene() -> Arc<Scene> {
    let dir = std::env::temp_dir().join(format!("lumis-gpu-tex-uv-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (with, without) = (dir.join("with.obj"), dir.join("without.obj"));
    obj::write(&with, &grid_mesh(true)).unwrap();
    obj::write(&without, &grid_mesh(false)).unwrap();
    let json = format!(
        r#"{{
  "camera": {{"from": [0, 0, -6], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40, "width": 2, "height": 2}},
  "shapes": [
    {{"type": "sphere", "center": [-1.5, 0.8, 0.3], "radius": 0.7}},
    {{"type": "disk", "center": [1.4, 1.0, 0.2], "normal": [0.3, -0.2, -1], "radius": 0.6}},
    {{"type": "quad", "corner": [-2.5, -2, -0.5], "edge_u": [1.5, 0, 0.3], "edge_v": [0, 1.2, 0.2]}},
    {{"type": "box", "min": [-0.4, -0.4, -0.4], "max": [0.4, 0.5, 0.3], "rotate_y_deg": 30, "translate": [0.1, -0.2, 0]}},
    {{"type": "triangles", "positions": [[1, -2, 0], [2.4, -2, 0.4], [1.5, -0.8, -0.2]], "indices": [[0, 1, 2]]}},
    {{"type": "mesh", "file": "{}", "to_world": [[1, 0, 0, -0.9], [0, 1, 0, 1.3], [0, 0, 1, 1.5], [0, 0, 0, 1]]}},
    {{"type": "mesh", "file": "{}", "to_world": [[1, 0, 0, 0.6], [0, 1, 0, -2.4], [0, 0, 1, 1.2], [0, 0, 0, 1]]}},
    {{"type": "cylinder", "p0": [1.3, -0.6, 0.6], "p1": [2.4, -0.1, 0.9], "radius": 0.35, "u_axis": [0.2, 0.3, -1]}}
  ]
}}"#,
        with.display(),
        without.display()
    );
    let scene = Scene::from_desc(&parse_scene(&json).unwrap_or_else(|e| panic!("{e}"))).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    Arc::new(scene)
}

/// The difference of periodic coordinates, wrapped into [−½, ½].
fn circular(a: f32, b: f32) -> f32 {
    let d = a - b;
    d - d.round()
}

/// `surface_uv` against `Scene::uv` (seed 17/73, 16k rays at the scene of [`uv_scene`]):
///
/// - at the CPU's own hits (its point and barycentrics fed to the WGSL function), to the
///   rounding of the formulas: a sphere's d = (p − c)/r agrees to 8u|dᵢ|, so φ = atan2(d.y, d.x)
///   to 8u plus the two atan2s' 4πu, u = φ/2π to that over 2π plus 2u; θ = acos(d.z) to
///   min(8u/sin θ, √(16u)) plus 8u (libm's acos against atan2 of √((1−z)(1+z))), v = θ/π plus
///   2u. A disk's local coordinates come from dot products with a frame that FMA may round
///   differently, 16u·|p − c| each: r/radius agrees to that over the radius plus 8u, φ to
///   16u·|p − c|/ρ + 4πu; its φ is compared modulo 1 (the sign of a local y within rounding of 0
///   may differ: the seam). A cylinder's likewise: φ to 16u·|p − p0|/r + 4πu over 2π plus 2u,
///   v = (p − p0)·ẑ/h to 16u·|p − p0|/h + 8u. Triangles as `renderer/tests/gpu/parity_mesh.rs`: 6u·Σ|wᵢ||tᵢ|, barycentrics
///   exactly;
/// - end to end, at the GPU's own hits (`scene_intersect`, whose points agree to 1e-5 and
///   barycentrics to 1e-6): 4e-6 for triangles' uvs (within [−1.6, 2.1]: 6e-6), and for
///   spheres and disks 2e-5 over the distance from the pole or centre (ρ), cylinders 2e-5
///   over the radius (u) and the height (v), periodic coordinates modulo 1. The same primitive must be hit.
#[test]
fn surface_uvs_match_scene_uv() {
    let Some(ctx) = context() else {
        return;
    };
    let scene = uv_scene();
    let gpu = GpuScene::new(ctx, scene.clone()).unwrap();
    let prims = scene.accel.primitives();
    let mut r = Rng::new(17, 73, 0);
    let rays: Vec<Ray> = (0..16384)
        .map(|_| {
            let o = Vec3::new(r.next_f32() * 8.0 - 4.0, r.next_f32() * 8.0 - 4.0, -5.0);
            let target = Vec3::new(r.next_f32() * 5.0 - 2.5, r.next_f32() * 5.0 - 2.5, 0.0);
            Ray::new(o, (target - o).normalize())
        })
        .collect();
    let hits: Vec<_> = rays.iter().map(|ray| scene.accel.intersect(ray)).collect();
    let f4 = |v: Vec3, w: f32| [v.x, v.y, v.z, w];
    let inputs: Vec<[f32; 4]> = rays
        .iter()
        .zip(&hits)
        .flat_map(|(ray, h)| {
            let (p, b, prim) = h.map_or((Vec3::ZERO, Vec2::ZERO, NONE), |h| (h.p, h.b, h.prim));
            [
                f4(ray.o, ray.t_max),
                f4(ray.d, 0.0),
                f4(p, f32::from_bits(prim)),
                [b.x, b.y, 0.0, 0.0],
            ]
        })
        .collect();
    let out = run(
        &gpu,
        "let c = inp(2u);
         let prim = bitcast<u32>(c.w);
         if prim != NONE {
             let cpu_hit = SurfaceHit(0.0, c.xyz, vec3f(0.0), vec3f(0.0, 0.0, 1.0), prim, inp(3u).xy);
             outp(0u, vec4f(surface_uv(prims[prim], cpu_hit), 0.0, 0.0));
         }
         let h = scene_intersect(Ray(inp(0u).xyz, inp(1u).xyz, inp(0u).w));
         var uv = vec2f(0.0);
         if h.prim != NONE {
             uv = surface_uv(prims[h.prim], h);
         }
         outp(1u, vec4f(uv, bitcast<f32>(h.prim), 0.0));",
        &inputs,
        4,
        2,
    );
    let mut at_cpu = Compare::new("uv at the CPU's hits", 0.0, 0.0);
    let mut at_gpu = Compare::new("uv at the GPU's hits", 0.0, 0.0);
    let mut counts = [0usize; 4];
    for ((h, o), ray) in hits.iter().zip(out.chunks(2)).zip(&rays) {
        let Some(h) = h else {
            assert_eq!(o[1][2].to_bits(), NONE, "a miss");
            continue;
        };
        assert_eq!(o[1][2].to_bits(), h.prim, "the hit primitive of {ray:?}");
        let want = scene.uv(h);
        let prim = &prims[h.prim as usize];
        let what = format!("prim {} {:?} at {}", h.prim, prim.shape, h.p);
        match prim.shape {
            Shape::Sphere(s) => {
                counts[0] += 1;
                let d = ((h.p - s.center) / s.radius).as_dvec3();
                let rho = d.x.hypot(d.y) as f32;
                let du = (8.0 + 4.0 * PI) * U / TAU + 2.0 * U;
                let dtheta = (8.0 * U / rho).min((16.0 * U).sqrt()) + 8.0 * U;
                at_cpu.scalar_conditioned(o[0][0], want.x, du, &format!("{what}: u"));
                let dv = dtheta / PI + 2.0 * U;
                at_cpu.scalar_conditioned(o[0][1], want.y, dv, &format!("{what}: v"));
                let e = 2e-5 / rho.max(1e-6);
                at_gpu.scalar_conditioned(circular(o[1][0], want.x), 0.0, e, &what);
                at_gpu.scalar_conditioned(o[1][1], want.y, e.min(4e-3), &what);
            }
            Shape::Disk(k) => {
                counts[1] += 1;
                let pc = (h.p - k.center).length();
                let rho = scene.uv(h).x * k.radius;
                let dl = 16.0 * U * pc;
                let dphi = (dl / rho.max(1e-30) + 4.0 * PI * U) / TAU + 2.0 * U;
                at_cpu.scalar_conditioned(o[0][0], want.x, dl / k.radius + 8.0 * U, &what);
                at_cpu.scalar_conditioned(circular(o[0][1], want.y), 0.0, dphi, &what);
                let e = 2e-5 / rho.max(1e-6);
                at_gpu.scalar_conditioned(o[1][0], want.x, 2e-5 / k.radius, &what);
                at_gpu.scalar_conditioned(circular(o[1][1], want.y), 0.0, e, &what);
            }
            Shape::Cylinder(c) => {
                counts[3] += 1;
                let (rel, height) = ((h.p - c.p0).length(), c.axis.length());
                let dl = 16.0 * U * rel;
                let dphi = (dl / c.radius + 4.0 * PI * U) / TAU + 2.0 * U;
                at_cpu.scalar_conditioned(circular(o[0][0], want.x), 0.0, dphi, &what);
                at_cpu.scalar_conditioned(o[0][1], want.y, dl / height + 8.0 * U, &what);
                let e = 2e-5 / c.radius;
                at_gpu.scalar_conditioned(circular(o[1][0], want.x), 0.0, e, &what);
                at_gpu.scalar_conditioned(o[1][1], want.y, 2e-5 / height, &what);
            }
            Shape::Triangle { .. } => {
                counts[2] += 1;
                let a = &scene.attributes;
                let extra = if prim.attr == NONE {
                    0.0
                } else {
                    let t = &a.triangles[prim.attr as usize];
                    let base = a.meshes[t.mesh as usize].uv_base;
                    let w = [1.0 - h.b.x - h.b.y, h.b.x, h.b.y];
                    6.0 * U
                        * (0..3)
                            .map(|i| {
                                w[i].abs() * a.uvs[(base + t.v[i]) as usize].abs().max_element()
                            })
                            .sum::<f32>()
                };
                at_cpu.scalar_conditioned(o[0][0], want.x, extra, &what);
                at_cpu.scalar_conditioned(o[0][1], want.y, extra, &what);
                at_gpu.scalar_conditioned(o[1][0], want.x, 6e-6, &what);
                at_gpu.scalar_conditioned(o[1][1], want.y, 6e-6, &what);
            }
        }
    }
    eprintln!(
        "hits: {} sphere, {} disk, {} triangle, {} cylinder",
        counts[0], counts[1], counts[2], counts[3]
    );
    assert!(counts.iter().all(|&c| c > 500), "{counts:?}");
    at_cpu.finish(0);
    at_gpu.finish(0);
}
