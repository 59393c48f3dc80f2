//! End-to-end tests of the `lumis` binary: `render` to every output format, determinism, every
//! estimator option, the time limit, `compare`, and the one-line `lumis: ` error contract.
//!
//! Each test renders a tiny scene (16×16, a diffuse quad under a quad light, max_depth 2) with a
//! few samples per pixel into its own temporary directory.

use lumis::image_io::Image;
use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::Instant;

/// A temporary directory, removed when dropped (also when a test fails).
struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> TempDir {
        let dir = std::env::temp_dir().join(format!("lumis-cli-{}-{}", std::process::id(), name));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("create temp dir");
        TempDir(dir)
    }

    fn path(&self, file: &str) -> PathBuf {
        self.0.join(file)
    }

    /// Writes `text` to `file` in this directory and returns its path.
    fn write(&self, file: &str, text: &str) -> PathBuf {
        let path = self.path(file);
        std::fs::write(&path, text).expect("write temp file");
        path
    }

    /// The standard tiny scene at `width`×`height`.
    fn scene(&self, width: u32, height: u32) -> PathBuf {
        self.write(
            &format!("scene_{width}x{height}.json"),
            &scene_json(width, height),
        )
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// A diffuse floor under a downward-facing quad light that the camera does not see directly, so
/// the image is black at `max_depth` 1 and lit at 2.
fn scene_json(width: u32, height: u32) -> String {
    format!(
        r#"{{
  "camera": {{"from": [0, 1, -3], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 60,
              "width": {width}, "height": {height}}},
  "max_depth": 2,
  "materials": {{"floor": {{"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}}}},
  "shapes": [
    {{"type": "quad", "corner": [-2, 0, -2], "edge_u": [0, 0, 4], "edge_v": [4, 0, 0],
      "material": "floor"}},
    {{"type": "quad", "corner": [-0.5, 2, -0.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1],
      "emission": [5, 5, 5]}}
  ]
}}
"#
    )
}

/// Runs `lumis` with `args`.
fn lumis<I, S>(args: I) -> Output
where
    I: IntoIterator<Item = S>,
    S: AsRef<OsStr>,
{
    Command::new(env!("CARGO_BIN_EXE_lumis"))
        .args(args)
        .output()
        .expect("run lumis")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// The numbers of `render`'s last stdout line.
#[derive(Debug)]
struct Stats {
    spp: u64,
    seconds: f64,
    samples_per_second: f64,
    nonfinite: u64,
}

/// Parses `spp=N seconds=T samples_per_second=X nonfinite=K`, exactly those keys in that order.
fn parse_stats(stdout: &str) -> Stats {
    let line = stdout
        .lines()
        .rev()
        .find(|l| !l.trim().is_empty())
        .expect("render prints a summary line");
    let fields: Vec<(&str, &str)> = line
        .split(' ')
        .map(|f| {
            f.split_once('=')
                .unwrap_or_else(|| panic!("field {f:?} of {line:?} has no '='"))
        })
        .collect();
    let keys: Vec<&str> = fields.iter().map(|(k, _)| *k).collect();
    assert_eq!(
        keys,
        ["spp", "seconds", "samples_per_second", "nonfinite"],
        "summary line {line:?}"
    );
    let num = |i: usize| -> f64 {
        fields[i]
            .1
            .parse()
            .unwrap_or_else(|e| panic!("{:?} in {line:?}: {e}", fields[i].1))
    };
    let int = |i: usize| -> u64 {
        fields[i]
            .1
            .parse()
            .unwrap_or_else(|e| panic!("{:?} in {line:?}: {e}", fields[i].1))
    };
    Stats {
        spp: int(0),
        seconds: num(1),
        samples_per_second: num(2),
        nonfinite: int(3),
    }
}

/// Renders `scene` to `out` with `extra` options; asserts success and returns the summary.
fn render(scene: &Path, out: &Path, extra: &[&str]) -> Stats {
    let mut args: Vec<&OsStr> = vec![OsStr::new("render"), scene.as_os_str()];
    args.extend(extra.iter().map(OsStr::new));
    args.extend([OsStr::new("-o"), out.as_os_str()]);
    let output = lumis(&args);
    let stderr = text(&output.stderr);
    assert!(
        output.status.success(),
        "lumis {args:?} failed ({}): {stderr}",
        output.status
    );
    // No progress bar when stderr is not a terminal, and nothing else either.
    assert!(
        stderr.is_empty(),
        "lumis {args:?} wrote to stderr: {stderr}"
    );
    assert!(
        out.is_file(),
        "lumis {args:?} did not write {}",
        out.display()
    );
    let stats = parse_stats(&text(&output.stdout));
    assert_eq!(stats.nonfinite, 0, "lumis {args:?}: {stats:?}");
    assert!(
        stats.seconds.is_finite() && stats.seconds >= 0.0,
        "{stats:?}"
    );
    assert!(
        stats.samples_per_second.is_finite() && stats.samples_per_second > 0.0,
        "{stats:?}"
    );
    stats
}

fn read(path: &Path) -> Image {
    Image::read(path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()))
}

/// Asserts the size and that every pixel is finite and non-negative.
fn assert_valid_pixels(img: &Image, width: u32, height: u32) {
    assert_eq!((img.width, img.height), (width, height));
    assert_eq!(img.data.len(), (width * height) as usize);
    for (i, p) in img.data.iter().enumerate() {
        assert!(p.is_finite() && p.min_element() >= 0.0, "pixel {i} is {p}");
    }
}

/// [`assert_valid_pixels`], then whether any pixel is non-zero (must be used: a black image is
/// what an option that silently does nothing often gives).
#[must_use]
fn check_pixels(img: &Image, width: u32, height: u32) -> bool {
    assert_valid_pixels(img, width, height);
    img.data.iter().any(|p| p.max_element() > 0.0)
}

/// Asserts `output` is a failure reported as the single line `lumis: …` on stderr containing
/// every string of `needles`, with no panic; returns that line.
fn expect_error(output: &Output, needles: &[&str]) -> String {
    let stderr = text(&output.stderr);
    assert!(
        !output.status.success(),
        "expected a failure, got success; stderr: {stderr}"
    );
    assert!(
        matches!(output.status.code(), Some(c) if c != 0),
        "expected a non-zero exit code, got {} (killed by a signal?); stderr: {stderr}",
        output.status
    );
    assert!(!stderr.contains("panicked at"), "lumis panicked: {stderr}");
    let line = stderr.trim_end_matches('\n');
    assert!(!line.contains('\n'), "error is not one line: {stderr:?}");
    assert!(
        line.starts_with("lumis: "),
        "error does not start with 'lumis: ': {stderr:?}"
    );
    for needle in needles {
        assert!(
            line.contains(needle),
            "error {line:?} does not mention {needle:?}"
        );
    }
    line.to_owned()
}

fn compare(image: &Path, reference: &Path) -> (f64, f64) {
    let output = lumis([
        OsStr::new("compare"),
        image.as_os_str(),
        reference.as_os_str(),
    ]);
    let stderr = text(&output.stderr);
    assert!(output.status.success(), "compare failed: {stderr}");
    let stdout = text(&output.stdout);
    let line = stdout.trim_end();
    let fields: Vec<(&str, &str)> = line.split(' ').filter_map(|f| f.split_once('=')).collect();
    assert_eq!(fields.len(), 2, "compare printed {stdout:?}");
    assert_eq!(
        (fields[0].0, fields[1].0),
        ("relmse", "rmse"),
        "compare printed {stdout:?}"
    );
    let num = |s: &str| -> f64 {
        s.parse()
            .unwrap_or_else(|e| panic!("{s:?} in {stdout:?}: {e}"))
    };
    (num(fields[0].1), num(fields[1].1))
}

fn repo_file(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(path)
}

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

#[test]
fn compare_prints_relmse_and_rmse() {
    let dir = TempDir::new("compare");
    let scene = dir.scene(16, 16);
    let a = dir.path("a.exr");
    let a_pfm = dir.path("a.pfm");
    let b = dir.path("b.exr");
    render(&scene, &a, &["--spp", "2", "--seed", "1"]);
    render(&scene, &a_pfm, &["--spp", "2", "--seed", "1"]);
    render(&scene, &b, &["--spp", "2", "--seed", "2"]);

    assert_eq!(compare(&a, &a), (0.0, 0.0), "an image against itself");
    assert_eq!(
        compare(&a_pfm, &a),
        (0.0, 0.0),
        "the PFM against the EXR of the same render"
    );
    let (relmse, rmse) = compare(&a, &b);
    assert!(
        relmse.is_finite() && relmse > 0.0,
        "relmse of different images is {relmse}"
    );
    assert!(
        rmse.is_finite() && rmse > 0.0,
        "rmse of different images is {rmse}"
    );

    // A real scene against its shipped reference.
    let disk = dir.path("disk.exr");
    render(
        &repo_file("tests/data/scenes/analytic_disk.json"),
        &disk,
        &["--spp", "4"],
    );
    let (relmse, rmse) = compare(&disk, &repo_file("tests/data/refs/analytic_disk.exr"));
    assert!(
        relmse.is_finite() && relmse > 0.0 && relmse < 1.0,
        "analytic_disk at 4 spp: relmse {relmse}"
    );
    assert!(
        rmse.is_finite() && rmse > 0.0,
        "analytic_disk at 4 spp: rmse {rmse}"
    );

    // Sizes that differ are an error naming both files.
    let small = dir.path("small.exr");
    render(&dir.scene(8, 8), &small, &["--spp", "1"]);
    let output = lumis([OsStr::new("compare"), a.as_os_str(), small.as_os_str()]);
    expect_error(
        &output,
        &[a.to_str().unwrap(), small.to_str().unwrap(), "16x16", "8x8"],
    );
}

#[test]
fn compare_missing_files_are_named() {
    let dir = TempDir::new("compare-missing");
    let a = dir.path("a.exr");
    render(&dir.scene(16, 16), &a, &["--spp", "1"]);
    let missing = dir.path("missing.exr");
    let output = lumis([OsStr::new("compare"), a.as_os_str(), missing.as_os_str()]);
    expect_error(&output, &[missing.to_str().unwrap()]);
    let output = lumis([OsStr::new("compare"), missing.as_os_str(), a.as_os_str()]);
    expect_error(&output, &[missing.to_str().unwrap()]);
}

#[test]
fn missing_scene_file_is_named() {
    let dir = TempDir::new("missing-scene");
    let scene = dir.path("no-such-scene.json");
    let out = dir.path("out.exr");
    let output = lumis([
        OsStr::new("render"),
        scene.as_os_str(),
        OsStr::new("--spp"),
        OsStr::new("1"),
        OsStr::new("-o"),
        out.as_os_str(),
    ]);
    expect_error(&output, &[scene.to_str().unwrap()]);
    assert!(!out.exists(), "an image was written for a missing scene");
}

/// Renders `scene` with 1 spp to `out.exr` in `dir` and expects the error to mention `needles`.
fn expect_scene_error(dir: &TempDir, scene: &Path, needles: &[&str]) -> String {
    let out = dir.path("out.exr");
    let output = lumis([
        OsStr::new("render"),
        scene.as_os_str(),
        OsStr::new("--spp"),
        OsStr::new("1"),
        OsStr::new("-o"),
        out.as_os_str(),
    ]);
    let line = expect_error(&output, needles);
    assert!(!out.exists(), "an image was written for a bad scene");
    line
}

#[test]
fn malformed_json_names_line_and_column() {
    let dir = TempDir::new("bad-json");
    // A missing comma after line 2's value; serde_json notices on line 3.
    let scene = dir.write("bad.json", "{\n  \"max_depth\": 2\n  \"camera\": {}\n}\n");
    expect_scene_error(&dir, &scene, &[scene.to_str().unwrap(), "line 3", "column"]);
    // Truncated file.
    let scene = dir.write("truncated.json", &scene_json(16, 16)[..120]);
    expect_scene_error(&dir, &scene, &[scene.to_str().unwrap(), "line", "column"]);
}

#[test]
fn unknown_material_names_json_path() {
    let dir = TempDir::new("bad-material");
    let json = scene_json(16, 16).replace(r#""material": "floor""#, r#""material": "flooor""#);
    assert!(json.contains("flooor"));
    let scene = dir.write("bad.json", &json);
    expect_scene_error(
        &dir,
        &scene,
        &[scene.to_str().unwrap(), "shapes[0].material", "flooor"],
    );
}

#[test]
fn unsupported_output_extension_is_rejected() {
    let dir = TempDir::new("bad-ext");
    let scene = dir.scene(16, 16);
    for name in ["x.bmp", "x"] {
        let out = dir.path(name);
        let output = lumis([
            OsStr::new("render"),
            scene.as_os_str(),
            OsStr::new("--spp"),
            OsStr::new("1"),
            OsStr::new("-o"),
            out.as_os_str(),
        ]);
        expect_error(&output, &[out.to_str().unwrap(), ".exr"]);
        assert!(!out.exists(), "{name} was written");
    }
}

#[test]
fn unwritable_output_fails_before_rendering() {
    let dir = TempDir::new("unwritable");
    let scene = dir.scene(16, 16);
    let start = Instant::now();
    // Without the check before rendering this would render for the whole time limit first.
    let output = lumis([
        OsStr::new("render"),
        scene.as_os_str(),
        OsStr::new("--spp"),
        OsStr::new("1000000000"),
        OsStr::new("--time-limit"),
        OsStr::new("30"),
        OsStr::new("-o"),
        OsStr::new("/nonexistent-dir/x.exr"),
    ]);
    expect_error(&output, &["/nonexistent-dir/x.exr"]);
    assert!(
        start.elapsed().as_secs() < 15,
        "took {:?}: it rendered before failing",
        start.elapsed()
    );
    assert!(
        output.stdout.is_empty(),
        "printed a summary: {}",
        text(&output.stdout)
    );
}

#[test]
fn invalid_options_are_one_line_errors() {
    let dir = TempDir::new("bad-options");
    let scene = dir.scene(16, 16);
    let out = dir.path("out.exr");
    let cases: &[(&[&str], &[&str])] = &[
        (&["--spp", "0"], &["--spp"]),
        (
            &["--spp", "1", "--mix-weight", "1.5"],
            &["--mix-weight", "1.5"],
        ),
        (
            &["--spp", "1", "--mix-weight=-0.1"],
            &["--mix-weight", "-0.1"],
        ),
        (&["--spp", "1", "--mix-weight", "NaN"], &["--mix-weight"]),
        (&["--spp", "1", "--max-depth", "0"], &["--max-depth", "0"]),
        (&["--spp", "1", "--max-depth", "-2"], &["--max-depth", "-2"]),
        // Usage errors from the argument parser follow the same convention.
        (&["--spp", "1", "--strategy", "foo"], &["--strategy", "foo"]),
        (&["--spp", "1", "--heuristic", "foo"], &["--heuristic"]),
        (
            &["--spp", "1", "--light-sampling", "foo"],
            &["--light-sampling"],
        ),
        (&["--spp", "lots"], &["--spp"]),
        (&[], &["--spp"]),
    ];
    for (opts, needles) in cases {
        let mut args: Vec<&OsStr> = vec![OsStr::new("render"), scene.as_os_str()];
        args.extend(opts.iter().map(OsStr::new));
        args.extend([OsStr::new("-o"), out.as_os_str()]);
        expect_error(&lumis(&args), needles);
        assert!(!out.exists(), "{opts:?} wrote an image");
    }
    expect_error(&lumis(["frobnicate"]), &["frobnicate"]);
    expect_error(&lumis(["compare", "only-one.exr"]), &["REFERENCE"]);
}

// ---- Bad input and unwritable outputs (issue 7, item 4) ----

/// Runs `lumis render SCENE --spp 1 -o OUT`.
fn render_to(scene: &Path, out: &Path) -> Output {
    lumis([
        OsStr::new("render"),
        scene.as_os_str(),
        OsStr::new("--spp"),
        OsStr::new("1"),
        OsStr::new("-o"),
        out.as_os_str(),
    ])
}

/// Whether file permissions stop this process: not when the tests run as root (CI may), in which
/// case the permission cases below are replaced by paths under a regular file, which fail for
/// everyone.
fn permissions_enforced(dir: &TempDir) -> bool {
    use std::os::unix::fs::PermissionsExt;
    let probe = dir.write("permission-probe", "x");
    std::fs::set_permissions(&probe, std::fs::Permissions::from_mode(0o000)).expect("chmod");
    let enforced = std::fs::read(&probe).is_err();
    let _ = std::fs::remove_file(&probe);
    enforced
}

/// Makes `path` readable and writable again, so that `TempDir` can remove it.
fn restore_permissions(path: &Path, mode: u32) {
    use std::os::unix::fs::PermissionsExt;
    let _ = std::fs::set_permissions(path, std::fs::Permissions::from_mode(mode));
}

#[test]
fn scene_that_cannot_be_read_is_named() {
    let dir = TempDir::new("unreadable-scene");
    let not_a_dir = dir.write("somefile.txt", "not a directory");
    // A directory, a file that is not UTF-8, an empty file, a path through a regular file.
    let directory = dir.path("scenes.json");
    std::fs::create_dir(&directory).expect("create dir");
    let binary = dir.path("binary.json");
    std::fs::write(&binary, b"{\"camera\": \xff\xfe}").expect("write");
    let empty = dir.write("empty.json", "");
    let through_file = not_a_dir.join("scene.json");
    for (scene, problem) in [
        (&directory, "cannot read the scene file"),
        (&binary, "cannot read the scene file"),
        (&through_file, "cannot read the scene file"),
        (&empty, "EOF while parsing"),
    ] {
        expect_scene_error(&dir, scene, &[scene.to_str().unwrap(), problem]);
    }
    if permissions_enforced(&dir) {
        let locked = dir.write("locked.json", &scene_json(16, 16));
        restore_permissions(&locked, 0o000);
        expect_scene_error(
            &dir,
            &locked,
            &[locked.to_str().unwrap(), "Permission denied"],
        );
        restore_permissions(&locked, 0o644);
    }
}

#[test]
fn unwritable_outputs_are_named() {
    let dir = TempDir::new("unwritable-outputs");
    let scene = dir.scene(16, 16);
    // Under a regular file: the directory cannot exist, so this fails before rendering.
    let not_a_dir = dir.write("somefile.txt", "not a directory");
    for name in ["out.exr", "out.pfm", "out.png"] {
        let out = not_a_dir.join(name);
        let output = render_to(&scene, &out);
        expect_error(&output, &[out.to_str().unwrap()]);
        assert!(
            output.stdout.is_empty(),
            "{name}: rendered before failing: {}",
            text(&output.stdout)
        );
    }
    // An output that is a directory, in every format.
    for name in ["taken.exr", "taken.pfm", "taken.png"] {
        let out = dir.path(name);
        std::fs::create_dir(&out).expect("create dir");
        expect_error(&render_to(&scene, &out), &[out.to_str().unwrap()]);
        assert!(out.is_dir(), "{name} was replaced");
    }
    // A read-only directory, where permissions apply.
    if permissions_enforced(&dir) {
        let locked = dir.path("locked");
        std::fs::create_dir(&locked).expect("create dir");
        restore_permissions(&locked, 0o555);
        let out = locked.join("out.exr");
        let output = render_to(&scene, &out);
        restore_permissions(&locked, 0o755);
        expect_error(&output, &[out.to_str().unwrap(), "Permission denied"]);
        assert!(!out.exists(), "wrote into a read-only directory");
    }
}

#[test]
fn more_unknown_output_extensions_are_rejected() {
    let dir = TempDir::new("bad-ext-more");
    let scene = dir.scene(16, 16);
    for name in ["x.tiff", "x.exr.gz", "x.", ".exr"] {
        let out = dir.path(name);
        let output = render_to(&scene, &out);
        expect_error(&output, &[out.to_str().unwrap(), ".exr, .pfm or .png"]);
        assert!(!out.exists(), "{name} was written");
        assert!(output.stdout.is_empty(), "{name}: rendered before failing");
    }
}

#[test]
fn compare_unreadable_or_invalid_images_are_named() {
    let dir = TempDir::new("compare-invalid");
    let good = dir.path("good.exr");
    render(&dir.scene(16, 16), &good, &["--spp", "1"]);
    let bytes = std::fs::read(&good).expect("read EXR");

    let garbage = dir.write("garbage.exr", "this is not an EXR file");
    let truncated = dir.path("truncated.exr");
    std::fs::write(&truncated, &bytes[..bytes.len() / 2]).expect("write");
    let empty = dir.write("empty.exr", "");
    let bad_pfm = dir.write("bad.pfm", "PF\n16 sixteen\n-1.0\n");
    let short_pfm = dir.write("short.pfm", "PF\n16 16\n-1.0\n\0\0\0\0");
    let png = dir.path("image.png");
    render(&dir.scene(16, 16), &png, &["--spp", "1"]);
    let directory = dir.path("directory.exr");
    std::fs::create_dir(&directory).expect("create dir");
    let through_file = garbage.join("x.exr");

    for bad in [
        &garbage,
        &truncated,
        &empty,
        &bad_pfm,
        &short_pfm,
        &png,
        &directory,
        &through_file,
    ] {
        // As the reference and as the image: either way the bad file is the one named.
        for (image, reference) in [(&good, bad), (bad, &good)] {
            let output = lumis([
                OsStr::new("compare"),
                image.as_os_str(),
                reference.as_os_str(),
            ]);
            let line = expect_error(&output, &[bad.to_str().unwrap()]);
            assert!(
                !line.contains(good.to_str().unwrap()),
                "names the good file: {line}"
            );
            assert!(output.stdout.is_empty(), "printed metrics for {bad:?}");
        }
    }
    if permissions_enforced(&dir) {
        let locked = dir.path("locked.exr");
        std::fs::write(&locked, &bytes).expect("write");
        restore_permissions(&locked, 0o000);
        let output = lumis([OsStr::new("compare"), good.as_os_str(), locked.as_os_str()]);
        restore_permissions(&locked, 0o644);
        expect_error(&output, &[locked.to_str().unwrap()]);
    }
}

// ---- `lumis bench` ----

/// One row of `bench`'s CSV.
#[derive(Debug)]
struct BenchRow {
    strategy: String,
    seconds: f64,
    spp: u32,
    samples_per_second: f64,
    relmse: f64,
    rmse: f64,
    efficiency: f64,
    error_source: String,
}

const BENCH_HEADER: &str =
    "strategy,seconds,spp,samples_per_second,relmse,rmse,efficiency,error_source";

/// Parses `bench`'s CSV, checking the header.
fn read_bench_csv(path: &Path) -> Vec<BenchRow> {
    let csv = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some(BENCH_HEADER), "CSV header of {csv:?}");
    lines
        .map(|line| {
            let f: Vec<&str> = line.split(',').collect();
            assert_eq!(f.len(), 8, "CSV row {line:?}");
            let num = |i: usize| -> f64 {
                f[i].parse()
                    .unwrap_or_else(|e| panic!("{:?} in {line:?}: {e}", f[i]))
            };
            BenchRow {
                strategy: f[0].to_owned(),
                seconds: num(1),
                spp: f[2]
                    .parse()
                    .unwrap_or_else(|e| panic!("{:?} in {line:?}: {e}", f[2])),
                samples_per_second: num(3),
                relmse: num(4),
                rmse: num(5),
                efficiency: num(6),
                error_source: f[7].to_owned(),
            }
        })
        .collect()
}

/// Runs `lumis bench scene … -o out.csv`; asserts success and returns the stdout and the rows.
fn bench(scene: &Path, csv: &Path, extra: &[&str]) -> (String, Vec<BenchRow>) {
    let mut args: Vec<&OsStr> = vec![OsStr::new("bench"), scene.as_os_str()];
    args.extend(extra.iter().map(OsStr::new));
    args.extend([OsStr::new("-o"), csv.as_os_str()]);
    let output = lumis(&args);
    let stderr = text(&output.stderr);
    assert!(
        output.status.success(),
        "lumis {args:?} failed ({}): {stderr}",
        output.status
    );
    assert!(
        stderr.is_empty(),
        "lumis {args:?} wrote to stderr: {stderr}"
    );
    (text(&output.stdout), read_bench_csv(csv))
}

/// The rows of `strategy`, in file order.
fn rows_of<'a>(rows: &'a [BenchRow], strategy: &str) -> Vec<&'a BenchRow> {
    rows.iter().filter(|r| r.strategy == strategy).collect()
}

/// Every number of a row is finite, positive and consistent with the others.
fn check_bench_row(r: &BenchRow, pixels: f64) {
    assert!(r.seconds.is_finite() && r.seconds > 0.0, "{r:?}");
    assert!(r.relmse.is_finite() && r.relmse > 0.0, "{r:?}");
    assert!(r.rmse.is_finite() && r.rmse > 0.0, "{r:?}");
    // The CSV rounds seconds to microseconds, which bounds how well the ratios can agree.
    let close_timed = |a: f64, b: f64| (a - b).abs() <= (1e-4 + 1e-6 / r.seconds) * b.abs();
    assert!(
        close_timed(r.efficiency, 1.0 / (r.relmse * r.seconds)),
        "efficiency is not 1/(relmse·seconds): {r:?}"
    );
    assert!(
        close_timed(r.samples_per_second, r.spp as f64 * pixels / r.seconds),
        "samples_per_second is not spp·pixels/seconds for {pixels} pixels: {r:?}"
    );
}

#[test]
fn bench_writes_curves_and_plot_without_reference() {
    let dir = TempDir::new("bench-half");
    // --width/--height override the scene's 16×16: the samples/s below count 32×24 pixels.
    let scene = dir.scene(16, 16);
    let csv = dir.path("curves.csv");
    let png = dir.path("curves.png");
    let (stdout, rows) = bench(
        &scene,
        &csv,
        &[
            "--spp-list",
            "2,4,8",
            "--width",
            "32",
            "--height",
            "24",
            "--plot",
            png.to_str().unwrap(),
        ],
    );
    assert!(
        stdout.lines().any(|l| l.contains("half-buffer estimate")),
        "no notice that the error is a half-buffer estimate: {stdout}"
    );
    // The default strategies, in order, each with every checkpoint.
    let names: Vec<&str> = rows.iter().map(|r| r.strategy.as_str()).collect();
    assert_eq!(
        names,
        [
            "light", "light", "light", "bsdf", "bsdf", "bsdf", "mixture", "mixture", "mixture",
            "mis", "mis", "mis"
        ]
    );
    for strategy in ["light", "bsdf", "mixture", "mis"] {
        let rows = rows_of(&rows, strategy);
        let spp: Vec<u32> = rows.iter().map(|r| r.spp).collect();
        assert_eq!(spp, [2, 4, 8], "{strategy}");
        for w in rows.windows(2) {
            assert!(w[1].seconds > w[0].seconds, "time goes backwards: {w:?}");
        }
        for r in rows {
            check_bench_row(r, 32.0 * 24.0);
            assert_eq!(r.error_source, "half-buffer", "{r:?}");
        }
    }

    let plot = image::open(&png).unwrap_or_else(|e| panic!("cannot decode the plot: {e}"));
    assert_eq!((plot.width(), plot.height()), (1024, 640), "plot size");
    // Not a blank canvas: the axes, lines and legend leave non-white pixels.
    let rgb = plot.to_rgb8();
    let inked = rgb.pixels().filter(|p| p.0 != [255, 255, 255]).count();
    assert!(inked > 5000, "the plot has only {inked} non-white pixels");
}

#[test]
fn bench_relmse_against_a_reference_falls_with_spp() {
    let dir = TempDir::new("bench-ref");
    let scene = dir.scene(32, 32);
    // A long render with another seed, so that its noise is independent of the benchmark's.
    let reference = dir.path("ref.exr");
    render(&scene, &reference, &["--spp", "2048", "--seed", "999"]);
    let csv = dir.path("curves.csv");
    let (stdout, rows) = bench(
        &scene,
        &csv,
        &[
            "--reference",
            reference.to_str().unwrap(),
            "--strategies",
            "mis,light",
            "--spp-list",
            "1,4,16,64",
        ],
    );
    assert!(
        !stdout.contains("half-buffer"),
        "a half-buffer notice with a reference: {stdout}"
    );
    for strategy in ["mis", "light"] {
        let rows = rows_of(&rows, strategy);
        let spp: Vec<u32> = rows.iter().map(|r| r.spp).collect();
        assert_eq!(spp, [1, 4, 16, 64], "{strategy}");
        for r in &rows {
            check_bench_row(r, 32.0 * 32.0);
            assert_eq!(r.error_source, "reference", "{r:?}");
        }
        // The expected ratio is about 1/64 (plus the reference's own 1/2048); 1/8 leaves room for
        // the noise of a 32×32 image's error without passing a renderer whose error does not fall.
        let (first, last) = (rows[0], rows[3]);
        assert!(
            last.relmse < first.relmse / 8.0,
            "{strategy}: relmse {} at 64 spp against {} at 1 spp",
            last.relmse,
            first.relmse
        );
        assert!(
            last.rmse < first.rmse / 2.5,
            "{strategy}: {last:?} vs {first:?}"
        );
    }
    assert_eq!(rows.len(), 8, "rows for strategies not asked for: {rows:?}");
}

#[test]
fn bench_seconds_doubles_spp_until_the_budget_is_spent() {
    let dir = TempDir::new("bench-seconds");
    let scene = dir.scene(16, 16);
    let csv = dir.path("curves.csv");
    let (_, rows) = bench(&scene, &csv, &["--strategies", "mis", "--seconds", "0.3"]);
    // Without a reference the first checkpoint is 2 spp (each half image needs a sample).
    let spp: Vec<u32> = rows.iter().map(|r| r.spp).collect();
    let expected: Vec<u32> = (0..spp.len() as u32).map(|i| 2 << i).collect();
    assert_eq!(spp, expected, "checkpoints do not double from 2");
    let last = rows.last().expect("at least one checkpoint");
    assert!(last.seconds >= 0.3, "stopped before the budget: {last:?}");
    assert!(
        rows[..rows.len() - 1].iter().all(|r| r.seconds < 0.3),
        "went on after the budget was spent: {rows:?}"
    );
}

#[test]
fn bench_invalid_options_are_one_line_errors() {
    let dir = TempDir::new("bench-bad");
    let scene = dir.scene(16, 16);
    let small = dir.path("small.exr");
    render(&dir.scene(8, 8), &small, &["--spp", "1"]);
    let small = small.to_str().unwrap();
    let csv = dir.path("curves.csv");
    let cases: &[(&[&str], &[&str])] = &[
        (&["--strategies", "light,foo"], &["--strategies", "foo"]),
        (
            &["--strategies", "mis,mis"],
            &["--strategies", "mis", "twice"],
        ),
        (&["--spp-list", "4,2"], &["--spp-list", "increasing"]),
        (&["--spp-list", "0,2"], &["--spp-list"]),
        (&["--spp-list", "1,2"], &["--spp-list", "--reference"]),
        (&["--seconds", "0"], &["--seconds"]),
        (
            &["--seconds", "1", "--spp-list", "2"],
            &["--seconds", "--spp-list"],
        ),
        (&["--reference", small], &[small, "8x8", "16x16"]),
        (&["--plot", "x.svg"], &["x.svg", ".png"]),
        (&["--width", "0"], &["--width"]),
        (&["--mix-weight", "2"], &["--mix-weight"]),
    ];
    for (opts, needles) in cases {
        let mut args: Vec<&OsStr> = vec![OsStr::new("bench"), scene.as_os_str()];
        args.extend(opts.iter().map(OsStr::new));
        args.extend([OsStr::new("-o"), csv.as_os_str()]);
        expect_error(&lumis(&args), needles);
        assert!(!csv.exists(), "{opts:?} wrote a CSV");
    }
}

/// Runs `lumis view` with no display, so it renders headless.
fn view_headless<S: AsRef<OsStr>>(args: &[S]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lumis"))
        .arg("view")
        .args(args)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .expect("run lumis")
}

#[test]
fn view_without_a_display_renders_headless_and_says_so() {
    let dir = TempDir::new("view-headless");
    let scene = dir.scene(12, 8);
    let out = dir.path("shot.png");
    let o = view_headless(&[
        scene.as_os_str(),
        OsStr::new("--headless-spp"),
        OsStr::new("3"),
        OsStr::new("-o"),
        out.as_os_str(),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let stderr = text(&o.stderr);
    assert!(
        stderr.contains("no display") && stderr.contains("3 spp"),
        "{stderr}"
    );
    let png = image::open(&out).unwrap().into_rgb8();
    assert_eq!(png.dimensions(), (12, 8));
    assert!(png.pixels().any(|p| p.0 != [0, 0, 0]), "the floor is lit");

    // The comparison view writes one image per pane, named after its strategy.
    let o = view_headless(&[
        scene.as_os_str(),
        OsStr::new("--compare"),
        OsStr::new("light,bsdf"),
        OsStr::new("--spp-limit"),
        OsStr::new("2"),
        OsStr::new("-o"),
        out.as_os_str(),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    for lane in ["light", "bsdf"] {
        let p = dir.path(&format!("shot-{lane}.png"));
        assert_eq!(
            image::open(&p).unwrap().into_rgb8().dimensions(),
            (12, 8),
            "{p:?}"
        );
    }

    // So does the wipe, one image per rendered side (the reference side renders nothing).
    let out = dir.path("wipe.png");
    let o = view_headless(&[
        scene.as_os_str(),
        OsStr::new("--wipe"),
        OsStr::new("light,mis:cpu"),
        OsStr::new("--spp-limit"),
        OsStr::new("2"),
        OsStr::new("-o"),
        out.as_os_str(),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    for lane in ["light", "mis_power"] {
        assert!(dir.path(&format!("wipe-{lane}.png")).exists(), "{lane}");
    }
}

#[test]
fn view_errors_are_one_line_and_named() {
    let dir = TempDir::new("view-errors");
    let missing = dir.path("nope.json");
    expect_error(&view_headless(&[missing.as_os_str()]), &["nope.json"]);
    let bad = dir.write("bad.json", "{\"camera\": ");
    expect_error(&view_headless(&[bad.as_os_str()]), &["bad.json", "line 1"]);
    let scene = dir.scene(8, 8);
    expect_error(
        &view_headless(&[
            scene.as_os_str(),
            OsStr::new("--compare"),
            OsStr::new("mis"),
        ]),
        &["--compare takes 2 or 3 strategies"],
    );
    for (opts, needles) in [
        (&["--wipe", "mis"][..], &["--wipe takes 2 sides"][..]),
        (&["--wipe", "lite,mis"], &["lite", "reference"]),
        (&["--wipe", "mis:tpu,mis"], &["tpu", "cpu or gpu"]),
        (
            &["--wipe", "light,mis", "--compare", "light,bsdf"],
            &["--compare"],
        ),
        (&["--wipe-position", "1.5"], &["--wipe-position", "1.5"]),
        (&["--equal-error", "0"], &["--equal-error", "0"]),
        (&["--inspect", "3"], &["X,Y"]),
        (&["--window-size", "10x10"], &["WIDTHxHEIGHT"]),
    ] {
        let mut args = vec![scene.as_os_str()];
        args.extend(opts.iter().map(OsStr::new));
        expect_error(&view_headless(&args), needles);
    }
    expect_error(
        &view_headless(&[
            scene.as_os_str(),
            OsStr::new("--mix-weight"),
            OsStr::new("1.5"),
        ]),
        &["1.5"],
    );
}

/// A scene's warnings (here a dropped zero-area triangle, which leaves its shape empty) reach
/// stderr, one line each, and the render still succeeds.
#[test]
fn scene_warnings_are_printed() {
    let dir = TempDir::new("warnings");
    let json = scene_json(8, 8).replace(
        r#""shapes": ["#,
        r#""shapes": [
    {"type": "triangles", "positions": [[0, 0, 0], [1, 0, 0], [2, 0, 0]], "indices": [[0, 1, 2]],
     "material": "floor"},"#,
    );
    let scene = dir.path("warn.json");
    std::fs::write(&scene, json).unwrap();
    let out = dir.path("warn.exr");
    let output = lumis([
        "render".as_ref(),
        scene.as_os_str(),
        "--spp".as_ref(),
        "1".as_ref(),
        "-o".as_ref(),
        out.as_os_str(),
    ]);
    let stderr = text(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    let lines: Vec<&str> = stderr.lines().collect();
    assert_eq!(lines.len(), 2, "{stderr}");
    assert!(
        lines
            .iter()
            .all(|l| l.starts_with("warning: ") && l.contains("warn.json")),
        "{stderr}"
    );
    assert!(
        lines[0].contains("dropped 1 zero-area triangle"),
        "{stderr}"
    );
    assert!(lines[1].contains("no triangles"), "{stderr}");
}

/// A mesh file renders on its own (`scene/model.rs`): a convex tetrahedron (diffuse 0.8) under the
/// default white environment (1). With BSDF sampling every sample is exact (a ray leaving a
/// convex object escapes to the environment: 0.8 × 1), so every pixel lies between 0.8 (the
/// model) and 1 (the environment), and the model fills part of the frame.
#[test]
fn a_model_file_renders_on_its_own() {
    let dir = TempDir::new("model");
    let obj = dir.path("tet.obj");
    std::fs::write(
        &obj,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    )
    .unwrap();
    let out = dir.path("tet.exr");
    let stats = render(&obj, &out, &["--spp", "4", "--strategy", "bsdf"]);
    assert_eq!(stats.nonfinite, 0);
    let img = read(&out);
    assert_eq!((img.width, img.height), (640, 480));
    let lum: Vec<f32> = img.data.iter().map(|p| (p.x + p.y + p.z) / 3.0).collect();
    // A ray leaving a point on an edge between two faces, offset along one face's normal, can
    // hit the neighbouring face next to the edge (measured: one sample of 1.2M, at pixel
    // (447, 319)); so a few pixels may fall below 0.8, never above 1.
    let outside = lum
        .iter()
        .filter(|&&x| !(0.8 - 1e-4..=1.0 + 1e-4).contains(&x))
        .count();
    assert!(outside <= 30, "{outside} pixels outside [0.8, 1]");
    assert!(lum.iter().all(|&x| x <= 1.0 + 1e-4));
    let model = lum.iter().filter(|&&x| x < 0.81).count() as f32 / lum.len() as f32;
    assert!(
        (0.05..0.9).contains(&model),
        "the model covers {model} of the frame"
    );
}

/// A Mitsuba XML scene with `<default>` parameters: a twosided diffuse floor of reflectance
/// `$albedo` under a downward rectangle light the camera does not see, direct light only
/// (`max_depth` 2), `$spp` samples.
const XML_SCENE: &str = r#"<scene version="3.0.0">
    <default name="albedo" value="0.5"/>
    <default name="spp" value="4"/>
    <integrator type="path"><integer name="max_depth" value="2"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="50"/>
        <transform name="to_world"><lookat origin="0, 1, -3" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
        <film type="hdrfilm">
            <integer name="width" value="16"/><integer name="height" value="12"/>
            <rfilter type="box"/>
        </film>
    </sensor>
    <shape type="rectangle">
        <transform name="to_world"><scale value="3"/><rotate x="1" angle="-90"/></transform>
        <bsdf type="twosided">
            <bsdf type="diffuse"><rgb name="reflectance" value="$albedo"/></bsdf>
        </bsdf>
    </shape>
    <shape type="rectangle">
        <transform name="to_world"><scale value="0.5"/><rotate x="1" angle="90"/><translate y="2"/></transform>
        <emitter type="area"><rgb name="radiance" value="10"/></emitter>
    </shape>
</scene>
"#;

/// `lumis render scene.xml` reads Mitsuba XML by its extension, takes the spp of its sampler,
/// and `-D name=value` overrides its `<default>`s as Mitsuba's `-D` does: `-D albedo=0.25` halves
/// every pixel (same seed, the same draws: direct light is linear in the floor's albedo), `-D
/// spp=8` renders 8 samples; `-D` with a JSON scene, and a value that is not a number, are one
/// error naming the file (and the XML line). Catches `-D` ignored, applied to the wrong file,
/// or the XML's spp not used.
#[test]
fn xml_scenes_render_with_their_defaults_and_d_overrides() {
    let dir = TempDir::new("xml");
    let xml = dir.write("scene.xml", XML_SCENE);
    let (a, b, c) = (dir.path("a.exr"), dir.path("b.exr"), dir.path("c.exr"));
    assert_eq!(render(&xml, &a, &["--seed", "3"]).spp, 4);
    assert_eq!(
        render(&xml, &b, &["--seed", "3", "-D", "albedo=0.25"]).spp,
        4
    );
    assert_eq!(render(&xml, &c, &["-D", "spp=8"]).spp, 8);
    let (a, b) = (read(&a), read(&b));
    assert!(check_pixels(&a, 16, 12));
    for (i, (pa, pb)) in a.data.iter().zip(&b.data).enumerate() {
        assert!(
            (*pb - 0.5 * *pa).abs().max_element() <= 1e-5 * pa.max_element(),
            "pixel {i}: {pa} with albedo 0.5, {pb} with 0.25"
        );
    }
    let out = dir.path("bad.exr");
    let bad = lumis([
        OsStr::new("render"),
        xml.as_os_str(),
        OsStr::new("-D"),
        OsStr::new("albedo=dark"),
        OsStr::new("-o"),
        out.as_os_str(),
    ]);
    expect_error(&bad, &["scene.xml:", "dark"]);
    let json = dir.scene(8, 8);
    let bad = lumis([
        OsStr::new("render"),
        json.as_os_str(),
        OsStr::new("--spp"),
        OsStr::new("1"),
        OsStr::new("-D"),
        OsStr::new("albedo=0.25"),
        OsStr::new("-o"),
        out.as_os_str(),
    ]);
    expect_error(&bad, &["scene_8x8.json", "-D albedo=0.25", ".xml"]);
}
