//! `lumis render`: every output format, determinism over threads, every estimator option and its
//! effect on the image, the time limit.

use super::*;

#[test]
fn render_writes_exr_pfm_and_png() {
    let dir = TempDir::new("formats");
    let scene = dir.scene(16, 16);

    let exr = dir.path("out.exr");
    let pfm = dir.path("out.pfm");
    let png = dir.path("out.png");
    for out in [&exr, &pfm, &png] {
        let stats = render(&scene, out, &["--spp", "3", "--seed", "5"]);
        assert_eq!(stats.spp, 3, "{}", out.display());
    }

    let from_exr = read(&exr);
    let from_pfm = read(&pfm);
    assert!(check_pixels(&from_exr, 16, 16), "EXR image is black");
    assert!(check_pixels(&from_pfm, 16, 16), "PFM image is black");
    // Both are linear float RGB of the same render.
    assert_eq!(
        from_exr.data, from_pfm.data,
        "EXR and PFM of the same render differ"
    );

    let bytes = std::fs::read(&png).expect("read PNG");
    assert!(bytes.len() > 33, "PNG is only {} bytes", bytes.len());
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "PNG signature");
    assert_eq!(
        &bytes[8..16],
        b"\0\0\0\x0dIHDR",
        "first chunk is a 13-byte IHDR"
    );
    let be = |i: usize| u32::from_be_bytes(bytes[i..i + 4].try_into().unwrap());
    assert_eq!((be(16), be(20)), (16, 16), "PNG width and height");
    assert_eq!(bytes[24], 8, "8 bits per channel");

    // A non-square image keeps width and height apart.
    let wide = dir.scene(12, 7);
    let out = dir.path("wide.exr");
    assert_eq!(render(&wide, &out, &["--spp", "1"]).spp, 1);
    assert!(check_pixels(&read(&out), 12, 7), "12×7 image is black");
    let out = dir.path("wide.png");
    render(&wide, &out, &["--spp", "1", "--exposure", "-1"]);
    let bytes = std::fs::read(&out).expect("read PNG");
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "PNG signature");
    let be = |i: usize| u32::from_be_bytes(bytes[i..i + 4].try_into().unwrap());
    assert_eq!((be(16), be(20)), (12, 7), "PNG width and height");
}

#[test]
fn same_seed_same_image_for_any_thread_count() {
    let dir = TempDir::new("determinism");
    let scene = dir.scene(16, 16);
    let run = |name: &str, seed: &str, threads: &str| -> PathBuf {
        let out = dir.path(name);
        let stats = render(
            &scene,
            &out,
            &["--spp", "4", "--seed", seed, "--threads", threads],
        );
        assert_eq!(stats.spp, 4);
        out
    };
    let a = run("a.exr", "7", "2");
    let b = run("b.exr", "7", "2");
    let one = run("one.exr", "7", "1");
    let other = run("other.exr", "8", "2");

    let bytes = |p: &Path| std::fs::read(p).expect("read EXR");
    assert!(
        bytes(&a) == bytes(&b),
        "two renders with the same seed wrote different files"
    );
    let (a, one, other) = (read(&a), read(&one), read(&other));
    assert!(check_pixels(&a, 16, 16), "image is black");
    assert_eq!(
        a.data, one.data,
        "--threads 1 and --threads 2 give different pixels"
    );
    let n = differing_pixels(&a, &other);
    assert!(
        n > 100,
        "--seed 7 and --seed 8 differ in only {n} of 256 pixels"
    );
}

#[test]
fn every_estimator_option_is_accepted() {
    let dir = TempDir::new("options");
    let scene = dir.scene(16, 16);
    let cases: &[&[&str]] = &[
        &["--strategy", "light"],
        &["--strategy", "bsdf"],
        &["--strategy", "mixture", "--mix-weight", "0.3"],
        &["--strategy", "mixture", "--mix-weight", "0"],
        &["--strategy", "mixture", "--mix-weight", "1"],
        &["--strategy", "mis", "--heuristic", "balance"],
        &["--strategy", "mis", "--heuristic", "power"],
        &["--strategy", "mis-optimal"],
        &["--light-sampling", "area"],
        &["--light-sampling", "solid-angle"],
        &["--strategy", "light", "--light-sampling", "area"],
        &["--max-depth", "3"],
        &["--max-depth", "-1"],
    ];
    for (i, opts) in cases.iter().enumerate() {
        let out = dir.path(&format!("case{i}.exr"));
        let mut args = vec!["--spp", "2"];
        args.extend_from_slice(opts);
        assert_eq!(render(&scene, &out, &args).spp, 2, "{opts:?}");
        assert!(
            check_pixels(&read(&out), 16, 16),
            "{opts:?} gives a black image"
        );
    }

    // --max-depth overrides the scene's 2: at depth 1 only directly seen emission remains, and the
    // camera does not see the light.
    let out = dir.path("depth1.exr");
    render(&scene, &out, &["--spp", "2", "--max-depth", "1"]);
    assert!(
        !check_pixels(&read(&out), 16, 16),
        "--max-depth 1 still shows reflected light"
    );
}

// ---- Effects of the estimator options (issue 14, item 5) ----
//
// Accepting an option proves nothing: a CLI that ignored it would pass the test above. Each
// test below asserts what the option does to the image, on a scene built so that the effect is
// exact or far above the noise, with a negative control where the option could be ignored in
// favour of its default (`mis`, power heuristic, mixture weight 0.5, solid-angle light
// sampling, the scene's max_depth, seed 0).

/// The standard view, seeing the floor's far edge and the black beyond it.
const FRONT_CAMERA: &str = r#"{"from": [0, 1, -3], "to": [0, 0, 0], "up": [0, 1, 0],
              "vfov_deg": 60, "width": 16, "height": 16}"#;

/// Straight down onto the middle of the floor, which fills the image: no edges, so a pixel's
/// value varies little over its area and the error of a render is the estimator's own.
const TOP_CAMERA: &str = r#"{"from": [0, 1.5, 0], "to": [0, 0, 0], "up": [0, 0, 1],
              "vfov_deg": 60, "width": 16, "height": 16}"#;

/// A 16×16 scene with `max_depth` 2: a diffuse floor (albedo exactly representable in f32)
/// seen by `camera`, a constant `background`, and `extra_shapes` (JSON objects, each starting
/// with a comma).
fn floor_scene(camera: &str, background: [f32; 3], extra_shapes: &str) -> String {
    let [r, g, b] = background;
    format!(
        r#"{{
  "camera": {camera},
  "max_depth": 2,
  "background": [{r}, {g}, {b}],
  "materials": {{"floor": {{"type": "diffuse", "albedo": [0.5, 0.625, 0.75]}}}},
  "shapes": [
    {{"type": "quad", "corner": [-2, 0, -2], "edge_u": [0, 0, 4], "edge_v": [4, 0, 0],
      "material": "floor"}}{extra_shapes}
  ]
}}
"#
    )
}

/// A sphere light of radius 0.01 at height 2 above the floor's centre (behind [`TOP_CAMERA`]).
/// Sampled by its cone of directions, each light sample carries nearly the pixel's whole value
/// (the cosine at the floor varies by about r/d = 0.5% across the cone), so light sampling is
/// nearly noise-free here; a BSDF-sampled ray hits the light about once in 10⁴.
const SMALL_SPHERE_LIGHT: &str = r#",
    {"type": "sphere", "center": [0, 2, 0], "radius": 0.01, "emission": [20000, 20000, 20000]}"#;

/// The small sphere light over the floor, seen from above.
fn small_sphere_scene(dir: &TempDir) -> PathBuf {
    dir.write(
        "sphere.json",
        &floor_scene(TOP_CAMERA, [0.0; 3], SMALL_SPHERE_LIGHT),
    )
}

/// Renders `scene` at 16×16 with `--spp 16 --seed 3` and `opts`; returns the image, whose pixels
/// are checked to be valid.
fn render_effect(dir: &TempDir, scene: &Path, name: &str, opts: &[&str]) -> Image {
    let out = dir.path(&format!("{name}.exr"));
    // The independent sampler: the spreads measured below are its noise (Sobol's stratified
    // mixture coin leaves w = 0.9 within 0.042 of light sampling, not a whole sample short).
    let mut args = vec!["--spp", "16", "--seed", "3", "--sampler", "independent"];
    args.extend_from_slice(opts);
    assert_eq!(render(scene, &out, &args).spp, 16, "{opts:?}");
    let img = read(&out);
    assert_valid_pixels(&img, 16, 16);
    img
}

/// A 256-spp light-sampled render of `scene` with another seed than [`render_effect`]'s.
fn light_reference(dir: &TempDir, scene: &Path) -> Image {
    let out = dir.path("reference.exr");
    render(
        scene,
        &out,
        &["--spp", "256", "--seed", "99", "--strategy", "light"],
    );
    let img = read(&out);
    assert!(check_pixels(&img, 16, 16), "the reference is black");
    img
}

/// How many pixels of `a` and `b` differ in any bit.
fn differing_pixels(a: &Image, b: &Image) -> usize {
    assert_eq!(a.data.len(), b.data.len());
    a.data.iter().zip(&b.data).filter(|(x, y)| x != y).count()
}

/// The largest per-pixel, per-channel difference of two images, relative to `reference`'s
/// largest value.
fn max_relative_difference(a: &Image, reference: &Image) -> f32 {
    let scale = reference
        .data
        .iter()
        .map(|p| p.max_element())
        .fold(0.0, f32::max);
    assert!(scale > 0.0, "the reference is black");
    a.data
        .iter()
        .zip(&reference.data)
        .map(|(x, y)| (*x - *y).abs().max_element())
        .fold(0.0, f32::max)
        / scale
}

#[test]
fn mix_weight_0_is_bit_identical_to_bsdf_sampling_where_that_is_exact() {
    // A diffuse floor under a constant sky, direct light only. Cosine-weighted BSDF sampling
    // always reaches the sky, and every such sample is exactly albedo·L, whatever direction was
    // drawn: the BSDF estimator has no noise at all. The mixture at w = 0 never takes its light
    // branch (its coin u < 0 never holds) and weighs the BSDF sample by
    // p_bsdf / (0·p_light + 1·p_bsdf) = 1 exactly. It draws one more random number per vertex
    // (the coin), so its directions are not the BSDF strategy's: in general w = 0 equals `bsdf`
    // in distribution only. Here, where the value does not depend on the direction, the images
    // must be identical bit for bit. Any w > 0 samples the sky uniformly over the sphere some of
    // the time, which is noisy.
    let dir = TempDir::new("mix-weight-0");
    let scene = dir.write(
        "sky.json",
        &floor_scene(FRONT_CAMERA, [0.75, 0.875, 1.0], ""),
    );
    let bsdf = render_effect(&dir, &scene, "bsdf", &["--strategy", "bsdf"]);
    // The centre pixel sees the floor only: exactly albedo·L per channel (all exact in f32).
    assert_eq!(
        bsdf.data[8 * 16 + 8],
        glam::Vec3::new(0.5 * 0.75, 0.625 * 0.875, 0.75),
        "BSDF sampling of a Lambert floor under a constant sky is not exact"
    );
    let w0 = render_effect(
        &dir,
        &scene,
        "w0",
        &["--strategy", "mixture", "--mix-weight", "0"],
    );
    let n = differing_pixels(&w0, &bsdf);
    assert_eq!(
        n, 0,
        "--strategy mixture --mix-weight 0 differs from --strategy bsdf in {n} pixels"
    );
    // Negative controls: the default weight (what an ignored --mix-weight leaves), light only,
    // and light sampling itself are noisy here.
    for opts in [
        &["--strategy", "mixture"][..],
        &["--strategy", "mixture", "--mix-weight", "1"],
        &["--strategy", "light"],
    ] {
        let img = render_effect(&dir, &scene, "other", opts);
        let n = differing_pixels(&img, &bsdf);
        // Measured: 142 (every pixel that sees the floor; the rest see only the sky).
        assert!(n > 100, "{opts:?} differs from bsdf in only {n} pixels");
    }
}

/// How far (relative to the image's maximum) two 16-spp light-sampled renders of the small
/// sphere light with different random numbers may differ. Measured: 6.3e-4 between `light` and
/// the mixture at w = 1; 0.23 at w = 0.9 and 0.66 at w = 0.5.
const LIGHT_SAMPLING_SPREAD: f32 = 0.005;

#[test]
fn mix_weight_1_is_light_sampling() {
    // The small sphere light: light sampling is nearly exact. The mixture at w = 1 always takes
    // its light branch and divides by 1·p_light + 0·p_bsdf = p_light, as `light` does. It is not
    // bit-identical by construction: it draws its coin first, so it samples other points on the
    // light, and `f·L/p` rounds differently from `light`'s `f·L·(1/p)`. What must hold is that
    // it is the light estimator: it agrees with `light` within that estimator's own (tiny)
    // noise, whereas any other weight leaves some vertices to BSDF sampling, which misses this
    // light and leaves the pixel a whole sample short.
    let dir = TempDir::new("mix-weight-1");
    let scene = small_sphere_scene(&dir);
    let light = render_effect(&dir, &scene, "light", &["--strategy", "light"]);
    assert!(check_pixels(&light, 16, 16), "the floor is black");
    let w1 = render_effect(
        &dir,
        &scene,
        "w1",
        &["--strategy", "mixture", "--mix-weight", "1"],
    );
    let d1 = max_relative_difference(&w1, &light);
    assert!(
        d1 < LIGHT_SAMPLING_SPREAD,
        "--mix-weight 1 differs from --strategy light by {d1} of the image's maximum"
    );
    // Negative controls: at w < 1 about (1 − w)·16 of a pixel's 16 samples are BSDF samples. 0.5
    // is the default an ignored --mix-weight would leave.
    for w in ["0.9", "0.5"] {
        let img = render_effect(
            &dir,
            &scene,
            &format!("w{w}"),
            &["--strategy", "mixture", "--mix-weight", w],
        );
        let d = max_relative_difference(&img, &light);
        assert!(
            d > 10.0 * LIGHT_SAMPLING_SPREAD,
            "--mix-weight {w} is as close to light sampling as w = 1: {d}"
        );
    }
}

#[test]
fn strategies_give_different_images_at_equal_spp_and_seed() {
    // On the standard scene (a large quad light near the floor) every strategy weighs or draws
    // its samples differently, so no two give the same pixels; an ignored --strategy (always
    // the default, mis) would.
    let dir = TempDir::new("strategies");
    let scene = dir.scene(16, 16);
    let strategies = ["light", "bsdf", "mixture", "mis"];
    let images: Vec<Image> = strategies
        .iter()
        .map(|s| render_effect(&dir, &scene, s, &["--strategy", s]))
        .collect();
    for i in 0..images.len() {
        for j in i + 1..images.len() {
            let n = differing_pixels(&images[i], &images[j]);
            assert!(
                n > 100,
                "--strategy {} and {} differ in only {n} of 256 pixels",
                strategies[i],
                strategies[j]
            );
        }
    }
}

#[test]
fn strategies_differ_in_noise_as_expected() {
    // On the small sphere light the strategies' errors are orders of magnitude apart: light
    // sampling and MIS (whose weights give the light samples everything: here it draws and
    // weighs exactly like `light`) are nearly exact, the mixture at w = 0.5 has about half its
    // samples on the light (relative variance about 1 per sample), BSDF sampling almost never
    // finds the light.
    let dir = TempDir::new("strategy-noise");
    let scene = small_sphere_scene(&dir);
    let reference = light_reference(&dir, &scene);
    let relmse = |s: &str| {
        let img = render_effect(&dir, &scene, s, &["--strategy", s]);
        lumis::metrics::relmse(&img.data, &reference.data)
    };
    let [light, mis, mixture, bsdf] = ["light", "mis", "mixture", "bsdf"].map(relmse);
    eprintln!(
        "relMSE at 16 spp: light {light:.3e} mis {mis:.3e} mixture {mixture:.3e} bsdf {bsdf:.3e}"
    );
    assert!(
        light.max(mis) * NOISE_RATIO < mixture,
        "light ({light:e}) and mis ({mis:e}) are not far below mixture ({mixture:e})"
    );
    assert!(
        mixture * 5.0 < bsdf,
        "mixture ({mixture:e}) is not far below bsdf ({bsdf:e})"
    );
}

/// The least ratio of relMSEs asserted between a noisy and a nearly exact estimator of the
/// small sphere light. Measured at 16 spp: light and mis 1.3e-5, mixture (w = 0.5) 5.4e-2,
/// bsdf 0.86; light sampling by area 9.1e-2.
const NOISE_RATIO: f64 = 100.0;

#[test]
fn light_sampling_method_changes_the_image() {
    // Light sampling of the small sphere by solid angle draws directions in its cone (nearly
    // exact); by area it draws points uniformly on the whole sphere, and the half facing away
    // from the floor contributes nothing, so about every other sample is zero.
    let dir = TempDir::new("light-sampling");
    let scene = small_sphere_scene(&dir);
    let reference = light_reference(&dir, &scene);
    let run = |method: &str| {
        render_effect(
            &dir,
            &scene,
            method,
            &["--strategy", "light", "--light-sampling", method],
        )
    };
    let (solid_angle, area) = (run("solid-angle"), run("area"));
    let (e_solid, e_area) = (
        lumis::metrics::relmse(&solid_angle.data, &reference.data),
        lumis::metrics::relmse(&area.data, &reference.data),
    );
    eprintln!("relMSE at 16 spp: solid-angle {e_solid:.3e} area {e_area:.3e}");
    assert!(
        e_solid * NOISE_RATIO < e_area,
        "area sampling ({e_area:e}) is not far noisier than solid-angle sampling ({e_solid:e})"
    );
}

#[test]
fn heuristic_changes_the_mis_weights() {
    // At equal seed both heuristics draw the same random numbers and the same samples; only the
    // weights differ (balance pa/(pa+pb), power pa²/(pa²+pb²)), so an ignored --heuristic gives
    // the same pixels bit for bit. The standard scene's quad light is large and near: both
    // strategies' pdfs are comparable there, and the weights differ substantially.
    let dir = TempDir::new("heuristic");
    let scene = dir.scene(16, 16);
    let run = |h: &str| render_effect(&dir, &scene, h, &["--strategy", "mis", "--heuristic", h]);
    let (balance, power) = (run("balance"), run("power"));
    assert!(check_pixels(&power, 16, 16), "the floor is black");
    let n = differing_pixels(&balance, &power);
    assert!(
        n > 100,
        "--heuristic balance and power differ in only {n} of 256 pixels"
    );
    // The default is power.
    let default = render_effect(&dir, &scene, "default", &["--strategy", "mis"]);
    assert_eq!(
        differing_pixels(&default, &power),
        0,
        "the default heuristic is not power"
    );
}

#[test]
fn max_depth_adds_bounces_in_order() {
    // A floor and a wall behind it under the quad light: depth 2 is direct light, 3 adds one
    // bounce between floor and wall. At equal seed a longer path draws the same random numbers
    // for its first segments and adds only non-negative terms after them (Russian roulette
    // starts at depth 5), so every pixel is at least its value at a smaller depth, exactly.
    let dir = TempDir::new("max-depth");
    let wall = r#",
    {"type": "quad", "corner": [-2, 0, 2], "edge_u": [4, 0, 0], "edge_v": [0, 3, 0],
     "material": "floor"},
    {"type": "quad", "corner": [-0.5, 2, -0.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1],
     "emission": [5, 5, 5]}"#;
    let scene = dir.write("wall.json", &floor_scene(FRONT_CAMERA, [0.0; 3], wall));
    let scene_depth = render_effect(&dir, &scene, "scene", &[]);
    let depths = ["1", "2", "3", "-1"];
    let images: Vec<Image> = depths
        .iter()
        .map(|d| render_effect(&dir, &scene, &format!("d{d}"), &["--max-depth", d]))
        .collect();
    // The camera sees neither the light nor its emitting side: depth 1 is black.
    assert!(
        !check_pixels(&images[0], 16, 16),
        "--max-depth 1 shows reflected light"
    );
    assert_eq!(
        differing_pixels(&images[1], &scene_depth),
        0,
        "--max-depth 2 differs from the scene's max_depth 2"
    );
    let total = |img: &Image| -> f64 { img.data.iter().map(|p| p.element_sum() as f64).sum() };
    for k in 1..images.len() {
        let (lower, higher) = (&images[k - 1], &images[k]);
        for (i, (a, b)) in lower.data.iter().zip(&higher.data).enumerate() {
            assert!(
                a.cmple(*b).all(),
                "pixel {i}: {a} at --max-depth {} but {b} at {}",
                depths[k - 1],
                depths[k]
            );
        }
        // Measured sums: 0, 53.45, 58.14, 59.13 (an ignored --max-depth gives equal ones).
        assert!(
            total(higher) > total(lower),
            "--max-depth {} adds nothing to {}: {} vs {}",
            depths[k],
            depths[k - 1],
            total(higher),
            total(lower)
        );
    }
}

#[test]
fn time_limit_stops_early_but_renders_at_least_one_pass() {
    let dir = TempDir::new("time-limit");
    let scene = dir.scene(16, 16);
    for limit in ["0.0001", "0"] {
        let out = dir.path(&format!("limit{limit}.exr"));
        let start = Instant::now();
        let stats = render(
            &scene,
            &out,
            &["--spp", "1000000000", "--time-limit", limit],
        );
        assert!(
            start.elapsed().as_secs() < 60,
            "--time-limit {limit} took {:?}",
            start.elapsed()
        );
        assert!(
            stats.spp >= 1,
            "--time-limit {limit} wrote an image of 0 spp"
        );
        assert!(
            stats.spp < 1_000_000_000,
            "--time-limit {limit} did not stop early"
        );
        assert!(
            check_pixels(&read(&out), 16, 16),
            "--time-limit {limit} wrote a black image"
        );
    }
}
