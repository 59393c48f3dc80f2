//! Environment maps at scene level (issue 16), every strategy (light, BSDF, mixture w = 0.5, MIS
//! power and balance) × both methods (area = uniform sphere, solid angle = importance sampling),
//! seeded. The sampler's own χ² tests are in `chi2_samplers.rs`, the comparison with Mitsuba 3's
//! `envmap` in `reference_scenes.rs`.
//!
//! - **Constant-map identity.** A map holding one value everywhere renders, with uniform sampling
//!   and the same seed, the same image as the constant background of that value, pixel for pixel
//!   within float rounding (relative 1e-5; the bilinear lookup of a constant is exact only to an
//!   ulp). `max_depth` 4 keeps Russian roulette (from the fifth segment) out, which a rounding
//!   difference could otherwise turn into a different path.
//! - **Map furnace.** The background furnace's ground (diffuse, albedo `a`, 10⁴ wide) under a map:
//!   a plane sees only the sky, so every ground pixel is `a·E/π` at `max_depth` 2 and −1, E the
//!   map's irradiance on the ground, integrated here by a midpoint rule on a 2048 × 1024 grid in
//!   (u, v), far finer than the maps. Maps: a constant one (scale 2, rotated 40°; the sky pixels
//!   are also checked against the constant), and the test sky with its soft 1e3 sun
//!   (`tests/data/scenes/envmap_test_sky.exr`).
//!
//! **Test:** per render and channel, the mean over the ground (and sky) pixels against the closed
//! form by a two-sided z-test with sd from the film's per-pixel variances; family-wise α = 0.01
//! over [`N_COMPARISONS`], Šidák-corrected; the shared relative slack of 1e-5 (`closed_form_z`)
//! covers f32 rounding where the variance is 0 (the constant sky). Every render must have no
//! non-finite samples.

mod common;

use common::ground::{background_scene, classify_pixels};
use common::{METHODS, STRATEGIES, Tally, build, data_dir, json_vec, render};
use glam::Vec3;
use lumis::image_io::Image;
use lumis::integrator::Settings;
use lumis::lights::LightSampling;
use lumis::metrics::{normal_two_sided_critical, sidak};
use std::path::PathBuf;

/// Image size of the furnace (square).
const SIZE: u32 = 24;
/// Samples per pixel of the furnace.
const SPP: u32 = 256;
/// Maps × depths × settings × (ground, sky) × channels; the sky only for the constant map.
const N_COMPARISONS: usize = 2 * STRATEGIES.len() * METHODS.len() * 3 // constant: 2 depths
    + 2 * STRATEGIES.len() * METHODS.len() * 3 // constant: sky
    + 2 * STRATEGIES.len() * METHODS.len() * 3; // test sky: 2 depths, ground only

/// A folder of this test process for the maps it writes.
fn scratch() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("lumis-envmap-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes a `w × h` map of the constant `le`; returns its path.
fn constant_map(name: &str, w: u32, h: u32, le: Vec3) -> PathBuf {
    let path = scratch().join(name);
    let image = Image {
        width: w,
        height: h,
        data: vec![le; (w * h) as usize],
    };
    image.write(&path, 0.0).unwrap();
    path
}

fn envmap_json(path: &std::path::Path, scale: f32, rotate: f32) -> String {
    format!(
        r#"{{"envmap": {:?}, "scale": {scale}, "rotate_y_deg": {rotate}}}"#,
        path.to_str().unwrap()
    )
}

#[test]
fn constant_map_renders_the_constant_background() {
    let le = Vec3::new(0.4, 0.8, 1.2);
    let map = constant_map("identity.exr", 7, 5, le / 2.0);
    let text = std::fs::read_to_string(data_dir().join("scenes/envmap_objects.json")).unwrap();
    let mut value: serde_json::Value = serde_json::from_str(&text).unwrap();
    value["camera"]["width"] = 48.into();
    value["camera"]["height"] = 48.into();
    value["max_depth"] = 4.into();
    value["background"] = serde_json::from_str(&json_vec(le)).unwrap();
    let constant = build(&value.to_string());
    value["background"] = serde_json::from_str(&envmap_json(&map, 2.0, 40.0)).unwrap();
    let mapped = build(&value.to_string());
    let mut worst = 0.0f32;
    for (s, strategy) in STRATEGIES.into_iter().enumerate() {
        let settings = Settings {
            strategy,
            light_sampling: LightSampling::Area,
            ..Settings::default()
        };
        let a = render(&constant, settings, 16, 700 + s as u32)
            .film()
            .mean();
        let b = render(&mapped, settings, 16, 700 + s as u32).film().mean();
        for (i, (pa, pb)) in a.iter().zip(&b).enumerate() {
            let diff = ((*pa - *pb).abs() / pa.abs().max(Vec3::splat(1e-3))).max_element();
            worst = worst.max(diff);
            assert!(diff <= 1e-5, "{strategy:?} pixel {i}: {pa} vs {pb}");
        }
    }
    eprintln!("constant-map identity: worst relative pixel difference {worst:.2e}");
}

/// `∫ L(ω) cos θ dω` over the upper hemisphere (the ground's irradiance) of the map in `scene`,
/// by the midpoint rule in (u, v) (dω = 2π² sin(πv) du dv).
fn ground_irradiance(scene: &lumis::scene::Scene) -> Vec3 {
    let light = &scene.lights[scene.background_light.unwrap() as usize];
    let (nu, nv) = (2048, 1024);
    let mut sum = glam::DVec3::ZERO;
    for j in 0..nv / 2 {
        let v = (j as f64 + 0.5) / nv as f64;
        let theta = std::f64::consts::PI * v;
        let weight = theta.cos() * theta.sin();
        let mut row = glam::DVec3::ZERO;
        for i in 0..nu {
            let phi = std::f64::consts::TAU * (i as f64 + 0.5) / nu as f64;
            let d = glam::DVec3::new(
                theta.sin() * phi.sin(),
                theta.cos(),
                -theta.sin() * phi.cos(),
            );
            row += light.radiance(Vec3::ZERO, d.as_vec3()).as_dvec3();
        }
        sum += row * weight;
    }
    let dudv = 1.0 / (nu as f64 * nv as f64);
    (sum * 2.0 * std::f64::consts::PI.powi(2) * dudv).as_vec3()
}

#[test]
fn map_furnace() {
    let critical = normal_two_sided_critical(sidak(0.01, N_COMPARISONS));
    let mut tally = Tally::new(critical);
    let mut nonfinite = Vec::new();
    let le = Vec3::new(1.0, 0.5, 2.0);
    let constant = constant_map("furnace.exr", 8, 4, le / 2.0);
    let sky = data_dir().join("scenes/envmap_test_sky.exr");
    let maps = [
        ("constant", envmap_json(&constant, 2.0, 40.0), Some(le)),
        ("test sky", envmap_json(&sky, 0.75, 30.0), None),
    ];
    let albedo = Vec3::new(0.8, 0.5, 0.2);
    for (k, (name, background, sky_value)) in maps.iter().enumerate() {
        let scene = background_scene(albedo, background, SIZE);
        let (ground, sky) = classify_pixels(&scene, SIZE);
        assert!(ground.len() >= 200 && sky.len() >= 30, "{ground:?} {sky:?}");
        let irradiance = ground_irradiance(&scene);
        if let Some(le) = sky_value {
            // The quadrature itself: a constant sky's irradiance is π·L.
            let rel = (irradiance / (std::f32::consts::PI * *le) - Vec3::ONE).abs();
            assert!(rel.max_element() < 1e-5, "quadrature: {irradiance}");
        }
        let ground_value = albedo * irradiance / std::f32::consts::PI;
        for (d, max_depth) in [2, -1].into_iter().enumerate() {
            for (s, strategy) in STRATEGIES.into_iter().enumerate() {
                for (m, method) in METHODS.into_iter().enumerate() {
                    let seed = 80_000 + (1000 * k + 100 * d + 10 * s + m) as u32;
                    let settings = Settings {
                        strategy,
                        light_sampling: method,
                        max_depth: Some(max_depth),
                        ..Settings::default()
                    };
                    let r = render(&scene, settings, SPP, seed);
                    let film = r.film();
                    let what = format!("{name} depth {max_depth} {strategy:?} {method:?}");
                    if film.nonfinite != 0 {
                        nonfinite.push(format!("{what}: {} non-finite samples", film.nonfinite));
                    }
                    let mean = film.mean();
                    let var = film.variance_of_mean();
                    let mut regions = vec![("ground", &ground, ground_value)];
                    if let Some(le) = sky_value {
                        regions.push(("sky", &sky, *le));
                    }
                    for c in 0..3 {
                        for (region, pixels, value) in &regions {
                            let means: Vec<f64> =
                                pixels.iter().map(|&i| mean[i][c] as f64).collect();
                            let vars: Vec<f64> = pixels.iter().map(|&i| var[i][c]).collect();
                            tally.compare(
                                &format!("{what} ch {c} {region}"),
                                &means,
                                &vars,
                                value[c] as f64,
                            );
                        }
                    }
                }
            }
        }
    }
    assert!(nonfinite.is_empty(), "{}", nonfinite.join("\n"));
    tally.finish("map furnace", N_COMPARISONS);
}
