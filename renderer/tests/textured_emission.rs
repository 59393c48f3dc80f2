//! Textured emission on the CPU (issue 17): every light shape (quad, emitting mesh with
//! texture coordinates, sphere, disk, polygon) with a checkerboard or bitmap `emission`.
//!
//! * `light_samples_and_hits_agree_on_texture_coordinates`: for points sampled on every
//!   textured light (both methods, 64 stratified samples from each of 144 points), the ray
//!   towards the sample hits the same light, and the texture coordinates the scene gives the hit
//!   equal those it gives the light sample (to 1e-3, periodic). Deterministic; catches any
//!   disagreement between the two lookups, including ones no image test sees (swapped
//!   barycentrics permute the texture within each triangle and keep every triangle's power).
//! * `strategies_agree_on_textured_emitters`: light, BSDF, mixture, MIS and MIS with optimal
//!   weights (both light-sampling methods; seeds 10–16) against a converged MIS render made here (1024 spp, seed 1), by the
//!   block z-test with both images' variances (8 × 8 blocks, family-wise α = 0.01 over all
//!   cases, blocks and channels, Šidák). Light sampling sees the texture at sampled points, BSDF
//!   sampling at hits: a wrong texture value on either side makes them disagree. `max_depth` 2
//!   keeps light-only sampling free of the heavy tails of caustics.
//! * `camera_sees_the_texture_exactly`: a textured quad, sphere and mesh seen directly
//!   (`max_depth` 1, seed 7): pixels whose corners and centre fall on one checkerboard square of
//!   one emitter (texture coordinates computed here in f64 from the geometry and the file's UVs)
//!   average exactly that square's colour (z-test with the pixels' variance, zero for such
//!   pixels, plus 1e-5 relative slack; family-wise α = 0.01 over 18 comparisons).
//! * `constant_texture_renders_like_constant_radiance`: every emitter textured with a
//!   checkerboard of one colour renders bit for bit like the same emitter with that constant
//!   radiance, in every strategy and method (same seeds, full depth): the selection weights, the
//!   sampled radiance and the hit radiance are exactly the untextured ones.
//! * The GPU renders textured emission too: `renderer/tests/gpu/textured_emission.rs`.
//!
//! Deliberate bugs, each run against this file (measured once, not part of the suite):
//! light-sample uv with `v` flipped: agreement fails (Light |z| 31); triangle-light samples with
//! `b1`, `b2` swapped: only the uv test fails (63920 disagreements); a quad's samples always
//! looked up in its first triangle: uv test (9272) and agreement (Light |z| 10); hits emitting
//! the texture's mean: exact test (18 of 18) and agreement (|z| 23); light samples emitting the
//! mean: agreement (|z| 16); hit uv with `v` flipped: exact test and agreement (|z| 34).

mod common;

use common::emitters::{Panel, emission_texels, kind, pentagon, scratch_dir};
use common::{METHODS, STRATEGIES, Tally, check_unbiased, render};
use glam::{DVec3, Vec2, Vec3};
use lumis::geometry::Ray;
use lumis::geometry::primitive::NONE;
use lumis::integrator::{Heuristic, Settings, Strategy};
use lumis::lights::LightSampling;
use lumis::metrics::{normal_two_sided_critical, sidak};
use lumis::scene::{Scene, parse_scene_in};
use lumis::textures::Texture;
use std::path::{Path, PathBuf};
use std::sync::Arc;

fn temp_dir(name: &str) -> PathBuf {
    scratch_dir("textured-emission", name)
}

fn build_in(json: &str, folder: &Path) -> Arc<Scene> {
    let desc = parse_scene_in(json, folder).unwrap_or_else(|e| panic!("{e}\n{json}"));
    assert!(desc.warnings.is_empty(), "{:?}", desc.warnings);
    Arc::new(Scene::from_desc(&desc).unwrap_or_else(|e| panic!("{e}\n{json}")))
}

fn write_pfm(path: &Path) {
    emission_texels().write(path, 1.0).unwrap();
}

fn checker(c0: [f32; 3], c1: [f32; 3], scale: [f32; 2]) -> String {
    format!(
        r#"{{"type": "checkerboard", "color0": {c0:?}, "color1": {c1:?}, "uv_scale": {scale:?}}}"#
    )
}

/// The emitters of the agreement scene, in shape order after the floor and the wall:
/// quad, mesh, sphere, disk, polygon.
const EMITTERS: usize = 5;

/// The textures of the agreement scene's emitters (the mesh's is a bitmap).
fn agreement_textures() -> [String; EMITTERS] {
    [
        checker([5.0, 2.0, 1.0], [0.3, 1.0, 4.0], [1.5, 1.0]),
        r#"{"type": "bitmap", "file": "panel.pfm", "scale": 3}"#.to_string(),
        checker([4.0, 4.0, 1.0], [0.5, 0.5, 3.0], [4.0, 2.0]),
        checker([1.0, 5.0, 2.0], [3.0, 0.2, 0.5], [2.0, 3.0]),
        r#"{"type": "checkerboard", "color0": [2, 2, 6], "color1": [6, 1, 1],
            "uv_scale": [1, 1.5], "uv_offset": [0.1, 0]}"#
            .to_string(),
    ]
}

/// A floor, half rough metal and half diffuse, and a diffuse back wall, lit by five textured
/// emitters of every shape (and a dim sky). The flat emitters lean over the floor, close to it,
/// facing down and towards the camera, which sees their emitting sides, the light they cast and
/// their reflections. `emission[k]` is the `emission` JSON of emitter `k`. Written to a fresh
/// folder with the mesh and bitmap.
fn agreement_scene(name: &str, size: u32, emission: &[String; EMITTERS]) -> Arc<Scene> {
    let dir = temp_dir(name);
    // The flat emitters face (0, −1, −1)/√2; their planes are y + z = const.
    let panel = Panel::leaning();
    std::fs::write(dir.join("panel.obj"), panel.obj()).unwrap();
    write_pfm(&dir.join("panel.pfm"));
    let pentagon = pentagon();
    let [quad, mesh, sphere, disk, polygon] = emission;
    let json = format!(
        r#"{{
  "camera": {{"from": [0, 1.6, -3.2], "to": [0, 0.4, 1.8], "up": [0, 1, 0], "vfov_deg": 60,
             "width": {size}, "height": {size}}},
  "max_depth": 2,
  "background": [0.05, 0.05, 0.05],
  "materials": {{
    "diffuse": {{"type": "diffuse", "albedo": [0.7, 0.7, 0.7]}},
    "metal": {{"type": "conductor", "alpha": 0.1, "reflectance": [0.9, 0.8, 0.6]}}
  }},
  "shapes": [
    {{"type": "quad", "corner": [-3, 0, -3], "edge_u": [0, 0, 7], "edge_v": [3, 0, 0],
      "material": "metal"}},
    {{"type": "quad", "corner": [0, 0, -3], "edge_u": [0, 0, 7], "edge_v": [3, 0, 0],
      "material": "diffuse"}},
    {{"type": "quad", "corner": [-3, 0, 4], "edge_u": [0, 3, 0], "edge_v": [6, 0, 0],
      "material": "diffuse"}},
    {{"type": "quad", "corner": [-2.4, 0.15, 1.5], "edge_u": [0, 1, -1], "edge_v": [1.4, 0, 0],
      "emission": {quad}}},
    {{"type": "mesh", "file": "panel.obj", "emission": {mesh}}},
    {{"type": "sphere", "center": [1.0, 0.4, 3.2], "radius": 0.35, "emission": {sphere}}},
    {{"type": "disk", "center": [-1.0, 0.8, 3.3], "normal": [0.1, -1, -1], "radius": 0.5,
      "emission": {disk}}},
    {{"type": "polygon", "vertices": [{}], "emission": {polygon}}}
  ]
}}"#,
        pentagon.join(", ")
    );
    let scene = build_in(&json, &dir);
    let _ = std::fs::remove_dir_all(&dir);
    scene
}

/// Distance between texture coordinates, each axis modulo 1 (a sphere's or disk's angle wraps).
fn periodic_distance(a: Vec2, b: Vec2) -> f32 {
    let d = (a - b).abs();
    let d = d - d.round();
    d.abs().max_element()
}

#[test]
fn light_samples_and_hits_agree_on_texture_coordinates() {
    let scene = agreement_scene("uv", 16, &agreement_textures());
    let textured: Vec<usize> = (0..scene.lights.len())
        .filter(|&i| scene.lights[i].texture() != NONE)
        .collect();
    // Quad, 4 mesh triangles, sphere, disk, polygon.
    assert_eq!(textured.len(), 8);
    let mut compared = std::collections::BTreeMap::<&str, usize>::new();
    let mut failures = Vec::new();
    let n = 8;
    for ix in 0..6 {
        for iy in 0..4 {
            for iz in 0..6 {
                // In front of the emitters' emitting sides.
                let p = Vec3::new(
                    -2.5 + 1.0 * ix as f32,
                    0.05 + 0.3 * iy as f32,
                    -2.0 + 0.65 * iz as f32,
                );
                for &l in &textured {
                    let light = &scene.lights[l];
                    for method in METHODS {
                        for k in 0..n * n {
                            let u = Vec2::new(
                                ((k % n) as f32 + 0.37) / n as f32,
                                ((k / n) as f32 + 0.61) / n as f32,
                            );
                            let Some(s) = light.sample(p, Vec3::ZERO, u, method) else {
                                continue;
                            };
                            let Some(hit) = scene.accel.intersect(&Ray::new(p, s.wi)) else {
                                continue;
                            };
                            let prim = &scene.accel.primitives()[hit.prim as usize];
                            // Occluded, or another light: not this comparison.
                            if prim.light != l as u32 || (hit.p - s.p).length() > 1e-3 {
                                continue;
                            }
                            let (a, b) = (scene.uv(&hit), scene.light_uv(light, &s).unwrap());
                            *compared.entry(kind(light)).or_default() += 1;
                            if periodic_distance(a, b) > 1e-3 {
                                failures.push(format!(
                                    "{} light {l} {method:?} from {p}: hit uv {a}, sample uv {b}",
                                    kind(light)
                                ));
                            }
                        }
                    }
                }
            }
        }
    }
    eprintln!("compared: {compared:?}");
    for k in ["quad", "triangle", "sphere", "disk", "polygon"] {
        assert!(
            compared.get(k).copied().unwrap_or(0) >= 500,
            "{k}: {compared:?}"
        );
    }
    assert!(
        failures.is_empty(),
        "{} disagreements:\n{}",
        failures.len(),
        failures[..failures.len().min(10)].join("\n")
    );
}

#[test]
fn strategies_agree_on_textured_emitters() {
    const SIZE: u32 = 64;
    let scene = agreement_scene("agree", SIZE, &agreement_textures());
    let mis = |heuristic| Strategy::Mis { heuristic };
    let reference = render(
        &scene,
        Settings {
            strategy: mis(Heuristic::Power),
            light_sampling: LightSampling::SolidAngle,
            ..Settings::default()
        },
        1024,
        1,
    );
    let cases = [
        (Strategy::Light, LightSampling::SolidAngle, 256),
        (Strategy::Light, LightSampling::Area, 256),
        (Strategy::Bsdf, LightSampling::SolidAngle, 512),
        (mis(Heuristic::Balance), LightSampling::Area, 256),
        (mis(Heuristic::Power), LightSampling::Area, 256),
        (
            Strategy::Mixture { light_weight: 0.5 },
            LightSampling::SolidAngle,
            256,
        ),
        // Its control variate needs light samples and BSDF hits to agree on which points emit.
        (Strategy::MisOptimal, LightSampling::SolidAngle, 256),
    ];
    let alpha = sidak(0.01, cases.len());
    let mut failures = Vec::new();
    for (i, (strategy, light_sampling, spp)) in cases.into_iter().enumerate() {
        let settings = Settings {
            strategy,
            light_sampling,
            ..Settings::default()
        };
        let r = render(&scene, settings, spp, 10 + i as u32);
        assert_eq!(r.film().nonfinite, 0);
        let t = common::renders_z_test(&r, &reference, 8, alpha);
        let what = format!("textured emitters {strategy:?} {light_sampling:?}");
        if let Err(msg) = check_unbiased(&what, &t) {
            failures.push(msg);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn camera_sees_the_texture_exactly() {
    const SIZE: u32 = 64;
    let dir = temp_dir("exact");
    // Facing the camera (−z).
    let panel = Panel {
        corners: [
            DVec3::new(-1.7, -1.6, 0.2),
            DVec3::new(0.2, -1.6, 0.2),
            DVec3::new(0.2, -0.6, 0.2),
            DVec3::new(-1.7, -0.6, 0.2),
        ],
        centre: DVec3::new(-0.6, -1.0, 0.2),
        facing: DVec3::NEG_Z,
    };
    std::fs::write(dir.join("panel.obj"), panel.obj()).unwrap();
    let textures = [
        ([5.0, 2.0, 1.0], [0.3, 1.0, 4.0], [2.0, 2.0]),
        ([4.0, 4.0, 1.0], [0.5, 0.5, 3.0], [4.0, 2.0]),
        ([1.0, 5.0, 2.0], [3.0, 0.2, 0.5], [3.0, 3.0]),
    ];
    let [tq, ts, tm] = textures.map(|(c0, c1, s)| checker(c0, c1, s));
    // Quad: u along edge_u (+y), v along edge_v (+x); normal edge_u × edge_v = −z.
    let json = format!(
        r#"{{
  "camera": {{"from": [0, 0, -5], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40,
             "width": {SIZE}, "height": {SIZE}}},
  "max_depth": 1,
  "shapes": [
    {{"type": "quad", "corner": [-1.7, -0.4, 0], "edge_u": [0, 1.5, 0], "edge_v": [1.5, 0, 0],
      "emission": {tq}}},
    {{"type": "sphere", "center": [0.9, 0.5, 0.3], "radius": 0.7, "emission": {ts}}},
    {{"type": "mesh", "file": "panel.obj", "emission": {tm}}}
  ]
}}"#
    );
    let scene = build_in(&json, &dir);
    let _ = std::fs::remove_dir_all(&dir);
    let checkers: Vec<lumis::textures::Checkerboard> = scene
        .emission_textures
        .iter()
        .map(|t| match &t.texture {
            Texture::Checkerboard(c) => *c,
            other => panic!("{other:?}"),
        })
        .collect();
    assert_eq!(checkers.len(), 3);

    // (emitter, uv) of the first emitter a camera ray through film position (x, y) meets, in f64.
    let sphere_c = DVec3::new(0.9, 0.5, 0.3);
    let lookup = |x: f32, y: f32| -> Option<(usize, Vec2)> {
        let ray = scene.camera.ray(x, y);
        let (o, d) = (ray.o.as_dvec3(), ray.d.as_dvec3().normalize());
        let mut best: Option<(f64, usize, [f64; 2])> = None;
        let mut consider = |t: f64, k: usize, uv: [f64; 2]| {
            if t > 0.0 && best.is_none_or(|b| t < b.0) {
                best = Some((t, k, uv));
            }
        };
        // Quad in z = 0.
        let t = -o.z / d.z;
        let p = o + t * d;
        let (s, tt) = ((p.y + 0.4) / 1.5, (p.x + 1.7) / 1.5);
        if (0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&tt) {
            consider(t, 0, [s, tt]);
        }
        // Sphere: u = φ/2π from +x towards +y, v = θ/π from +z (Mitsuba's).
        let oc = o - sphere_c;
        let (b, c) = (oc.dot(d), oc.length_squared() - 0.49);
        if b * b - c >= 0.0 {
            let t = -b - (b * b - c).sqrt();
            let n = (o + t * d - sphere_c) / 0.7;
            let phi = n.y.atan2(n.x).rem_euclid(std::f64::consts::TAU);
            consider(
                t,
                1,
                [
                    phi / std::f64::consts::TAU,
                    n.z.clamp(-1.0, 1.0).acos() / std::f64::consts::PI,
                ],
            );
        }
        if let Some((t, uv)) = panel.uv(o, d) {
            consider(t, 2, uv);
        }
        best.map(|(_, k, uv)| (k, Vec2::new(uv[0] as f32, uv[1] as f32)))
    };
    // Pixels by (emitter, colour): corners and centre on one square of one emitter.
    let mut groups = vec![Vec::new(); 6];
    for y in 0..SIZE {
        for x in 0..SIZE {
            let points = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0), (0.5, 0.5)];
            let cls: Option<Vec<(usize, bool)>> = points
                .iter()
                .map(|&(dx, dy)| {
                    lookup(x as f32 + dx, y as f32 + dy)
                        .map(|(k, uv)| (k, checkers[k].is_color1(uv)))
                })
                .collect();
            if let Some(c) = cls
                && c.iter().all(|&v| v == c[0])
            {
                groups[2 * c[0].0 + c[0].1 as usize].push((y * SIZE + x) as usize);
            }
        }
    }
    for (g, pixels) in groups.iter().enumerate() {
        assert!(pixels.len() >= 20, "group {g}: {} pixels", pixels.len());
    }
    let comparisons = groups.len() * 3;
    let mut tally = Tally::new(normal_two_sided_critical(sidak(0.01, comparisons)));
    let r = render(&scene, Settings::default(), 64, 7);
    let (mean, var) = (r.film().mean(), r.film().variance_of_mean());
    for (g, pixels) in groups.iter().enumerate() {
        let (k, colour1) = (g / 2, g % 2 == 1);
        let expected = if colour1 {
            checkers[k].color1
        } else {
            checkers[k].color0
        };
        for c in 0..3 {
            let means: Vec<f64> = pixels.iter().map(|&i| mean[i][c] as f64).collect();
            let vars: Vec<f64> = pixels.iter().map(|&i| var[i][c]).collect();
            let what = format!("emitter {k} colour{} ch {c}", colour1 as u8);
            tally.compare(&what, &means, &vars, expected[c] as f64);
        }
    }
    tally.finish("camera_sees_the_texture_exactly", comparisons);
}

#[test]
fn constant_texture_renders_like_constant_radiance() {
    let colours = [
        [2.0f32, 1.5, 0.5],
        [0.75, 3.0, 1.0],
        [1.25, 1.0, 2.5],
        [4.0, 0.5, 0.25],
        [1.0, 2.0, 3.0],
    ];
    let textured = agreement_scene(
        "constant-textured",
        24,
        &colours.map(|c| checker(c, c, [3.0, 2.0])),
    );
    let constant = agreement_scene("constant", 24, &colours.map(|c| format!("{c:?}")));
    assert!(constant.emission_textures.is_empty());
    assert_eq!(textured.emission_textures.len(), EMITTERS);
    assert_eq!(textured.lights.len(), constant.lights.len());
    for (a, b) in textured.lights.iter().zip(&constant.lights) {
        assert_eq!(a.power().to_bits(), b.power().to_bits(), "{}", kind(a));
    }
    for (k, strategy) in STRATEGIES.into_iter().enumerate() {
        for (m, light_sampling) in METHODS.into_iter().enumerate() {
            let settings = Settings {
                strategy,
                light_sampling,
                max_depth: Some(-1),
                ..Settings::default()
            };
            let seed = (1 + 10 * k + m) as u32;
            let (a, b) = (
                render(&textured, settings, 8, seed),
                render(&constant, settings, 8, seed),
            );
            let bits = |r: &lumis::engine::Progressive| -> Vec<u64> {
                r.film()
                    .pixels
                    .iter()
                    .flat_map(|p| p.sum.into_iter().chain(p.sum_sq))
                    .map(f64::to_bits)
                    .collect()
            };
            assert!(
                bits(&a) == bits(&b),
                "{strategy:?} {light_sampling:?}: the constant texture renders differently"
            );
            assert!(a.film().mean().iter().any(|c| c.max_element() > 0.0));
        }
    }
}
