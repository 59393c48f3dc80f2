//! End-to-end tests of `lumis render --sample-range` and `lumis merge`: parts rendered with any
//! thread count merge into the render of all their samples within f64 rounding, in any argument
//! order and nesting, and incompatible parts or ranges are one-line errors naming the culprit.
//!
//! The bound: the one-shot film sums N non-negative f64 terms in sample order, the merge sums
//! the same terms grouped by part; each is within (N−1)·u·Σ of the exact sum (u = ε/2), so they
//! are at most (N−1)·ε·Σ apart; the tests allow N·ε·Σ (second-order terms). The variance
//! `(Σx² − (Σx)²/N) / (N(N−1))` then moves by at most (3N + 8)·ε·Σx² / (N(N−1)).

use lumis::image_io::Image;
use lumis_app::part_file::Part;
use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A temporary directory, removed when dropped (also when a test fails).
struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> TempDir {
        let dir = std::env::temp_dir().join(format!("lumis-merge-{}-{}", std::process::id(), name));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("create temp dir");
        TempDir(dir)
    }

    fn path(&self, file: &str) -> PathBuf {
        self.0.join(file)
    }

    /// A glossy sphere on a diffuse floor under a quad light, `width`×16, `max_depth` `depth`:
    /// radiance spread over decades, so that f64 sums do round.
    fn scene(&self, name: &str, width: u32, depth: u32) -> PathBuf {
        let json = format!(
            r#"{{
  "camera": {{"from": [0, 1, -3], "to": [0, 0.4, 0], "up": [0, 1, 0], "vfov_deg": 60,
              "width": {width}, "height": 16}},
  "max_depth": {depth},
  "materials": {{"floor": {{"type": "diffuse", "albedo": [0.5, 0.4, 0.3]}},
                 "gloss": {{"type": "conductor", "eta": [0.2, 0.9, 1.1], "k": [3.9, 2.4, 2.2], "alpha": 0.3}}}},
  "shapes": [
    {{"type": "quad", "corner": [-2, 0, -2], "edge_u": [0, 0, 4], "edge_v": [4, 0, 0],
      "material": "floor"}},
    {{"type": "sphere", "center": [0, 0.5, 0], "radius": 0.5, "material": "gloss"}},
    {{"type": "quad", "corner": [-0.5, 2, -0.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1],
      "emission": [5, 5, 5]}}
  ]
}}
"#
        );
        let path = self.path(name);
        std::fs::write(&path, json).expect("write scene");
        path
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Runs `lumis` with `args`.
fn lumis<S: AsRef<OsStr>>(args: &[S]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lumis"))
        .args(args)
        .output()
        .expect("run lumis")
}

/// Runs `lumis` with `args`, asserts success and returns the last stdout line.
fn ok<S: AsRef<OsStr>>(args: &[S]) -> String {
    let out = lumis(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "lumis failed: {stderr}");
    assert!(stderr.is_empty(), "lumis wrote to stderr: {stderr}");
    let stdout = String::from_utf8_lossy(&out.stdout);
    stdout.lines().last().unwrap_or("").to_owned()
}

/// Renders `scene` to `out` with `extra` options; returns the summary line.
fn render(scene: &Path, out: &Path, extra: &[&str]) -> String {
    let mut args = vec![OsStr::new("render"), scene.as_os_str()];
    args.extend(extra.iter().map(OsStr::new));
    args.extend([OsStr::new("-o"), out.as_os_str()]);
    ok(&args)
}

/// Merges `parts` into `out`; returns the summary line.
fn merge(parts: &[&Path], out: &Path) -> String {
    let mut args = vec![OsStr::new("merge")];
    args.extend(parts.iter().map(|p| p.as_os_str()));
    args.extend([OsStr::new("-o"), out.as_os_str()]);
    ok(&args)
}

fn read_part(path: &Path) -> Part {
    Part::read(path).unwrap_or_else(|e| panic!("{e:#}"))
}

/// Asserts that `merged` holds the samples of `whole` (N of them) within the bounds of the
/// module doc; returns the largest relative difference of any sum.
fn assert_same_film(merged: &Part, whole: &Part) -> f64 {
    let (m, w) = (&merged.film, &whole.film);
    assert_eq!(merged.samples, whole.samples);
    assert_eq!((m.width, m.height, m.spp), (w.width, w.height, w.spp));
    assert_eq!(m.nonfinite, w.nonfinite);
    let n = w.spp as f64;
    let eps = f64::EPSILON;
    let mut worst = 0.0f64;
    for (a, b) in m.pixels.iter().zip(&w.pixels) {
        for c in 0..3 {
            for (x, y) in [
                (a.sum[c], b.sum[c]),
                (a.sum_sq[c], b.sum_sq[c]),
                (a.sum_even[c], b.sum_even[c]),
            ] {
                assert!(y >= 0.0, "radiance sums are non-negative: {y}");
                assert!((x - y).abs() <= n * eps * y, "merged {x} vs one render {y}");
                if y > 0.0 {
                    worst = worst.max((x - y).abs() / y);
                }
            }
        }
    }
    for ((vm, vw), b) in m
        .variance_of_mean()
        .iter()
        .zip(&w.variance_of_mean())
        .zip(&w.pixels)
    {
        for c in 0..3 {
            let bound = (3.0 * n + 8.0) * eps * b.sum_sq[c] / (n * (n - 1.0));
            assert!(
                (vm[c] - vw[c]).abs() <= bound,
                "variance {} vs {} (bound {bound})",
                vm[c],
                vw[c]
            );
        }
    }
    assert!(w.pixels.iter().any(|p| p.sum[0] > 0.0), "the image is lit");
    worst
}

#[test]
fn merged_parts_equal_one_render_of_all_samples() {
    check_merged_parts_equal_one_render("equal", &[]);
}

/// The same with the Sobol sampler: its sample `s` of pixel `p` is the same point in every split
/// (`lumis::sampler`), so parts merge into the whole render exactly as with the independent one.
#[test]
fn merged_sobol_parts_equal_one_render_of_all_samples() {
    check_merged_parts_equal_one_render("equal-sobol", &["--sampler", "sobol"]);
}

/// Renders 0..8 whole and as 0..3 + 3..8 on different thread counts with the options `extra`,
/// merges, and checks the merged film against the whole one and a plain `--spp 8` render.
fn check_merged_parts_equal_one_render(name: &str, extra: &[&str]) {
    let dir = TempDir::new(name);
    let scene = dir.scene("scene.json", 24, 4);
    let with = |args: &[&'static str]| -> Vec<&str> {
        args.iter().copied().chain(extra.iter().copied()).collect()
    };
    let (one, a, b, m) = (
        dir.path("one.exr"),
        dir.path("a.exr"),
        dir.path("b.exr"),
        dir.path("m.exr"),
    );
    let line = render(
        &scene,
        &one,
        &with(&["--sample-range", "0..8", "--threads", "2"]),
    );
    assert!(line.ends_with(" samples=0..8"), "{line}");
    assert!(line.starts_with("spp=8 "), "{line}");
    render(
        &scene,
        &a,
        &with(&["--sample-range", "0..3", "--threads", "1"]),
    );
    let line = render(
        &scene,
        &b,
        &with(&["--sample-range", "3..8", "--threads", "3"]),
    );
    assert!(
        line.starts_with("spp=5 ") && line.ends_with(" samples=3..8"),
        "{line}"
    );
    let line = merge(&[&b, &a], &m);
    assert_eq!(line, "spp=8 samples=0..8 parts=2 nonfinite=0");
    let worst = assert_same_film(&read_part(&m), &read_part(&one));
    eprintln!("largest relative difference of a merged sum: {worst:.3e}");

    // The part's image is what a plain render writes, bit for bit, and any EXR reader sees it.
    let plain = dir.path("plain.exr");
    render(&scene, &plain, &with(&["--spp", "8"]));
    let read = |p: &Path| Image::read(p).unwrap();
    assert_eq!(read(&one), read(&plain));
    // The merged mean rounds to f32 from a sum within 8ε: at most one f32 step away.
    for (x, y) in read(&m).data.iter().zip(&read(&plain).data) {
        for c in 0..3 {
            let (x, y) = (x[c], y[c]);
            assert!(x.to_bits().abs_diff(y.to_bits()) <= 1, "{x} vs {y}");
        }
    }
}

#[test]
fn merge_is_independent_of_order_and_nests_across_gaps() {
    let dir = TempDir::new("order");
    let scene = dir.scene("scene.json", 16, 3);
    let part = |name: &str, range: &str| {
        let p = dir.path(name);
        render(&scene, &p, &["--sample-range", range]);
        p
    };
    let one = part("one.exr", "0..9");
    let (a, b, c) = (
        part("a.exr", "0..2"),
        part("b.exr", "2..6"),
        part("c.exr", "6..9"),
    );
    let (abc, cab) = (dir.path("abc.exr"), dir.path("cab.exr"));
    merge(&[&a, &b, &c], &abc);
    merge(&[&c, &a, &b], &cab);
    assert_eq!(
        std::fs::read(&abc).unwrap(),
        std::fs::read(&cab).unwrap(),
        "the merged file does not depend on the order of the parts"
    );
    assert_same_film(&read_part(&abc), &read_part(&one));

    // A gap is allowed and recorded; filling it later gives all the samples again.
    let ac = dir.path("ac.exr");
    assert_eq!(
        merge(&[&c, &a], &ac),
        "spp=5 samples=0..2,6..9 parts=2 nonfinite=0"
    );
    assert_eq!(read_part(&ac).samples, vec![0..2, 6..9]);
    let acb = dir.path("acb.exr");
    merge(&[&ac, &b], &acb);
    assert_same_film(&read_part(&acb), &read_part(&one));
}

/// Asserts `output` failed with one `lumis: ` line on stderr containing every needle.
fn expect_error(output: &Output, needles: &[&str]) {
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success(), "expected a failure: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    let line = stderr.trim_end_matches('\n');
    assert!(
        !line.contains('\n') && line.starts_with("lumis: "),
        "{stderr:?}"
    );
    for needle in needles {
        assert!(
            line.contains(needle),
            "{line:?} does not mention {needle:?}"
        );
    }
}

#[test]
fn merge_refuses_incompatible_parts_naming_the_file() {
    let dir = TempDir::new("refuse");
    let scene = dir.scene("scene.json", 16, 2);
    let other_scene = dir.scene("other.json", 16, 3);
    let narrow = dir.scene("narrow.json", 12, 2);
    let part = |name: &str, scene: &Path, extra: &[&str]| {
        let p = dir.path(name);
        render(scene, &p, extra);
        p
    };
    let a = part("a.exr", &scene, &["--sample-range", "0..3"]);
    let cases: [(PathBuf, &[&str]); 6] = [
        (
            part("overlap.exr", &scene, &["--sample-range", "2..5"]),
            &["overlap.exr", "samples 2..5 overlap", "a.exr's 0..3"],
        ),
        (
            part("narrow.exr", &narrow, &["--sample-range", "3..5"]),
            &["narrow.exr is 12x16 but", "a.exr is 16x16"],
        ),
        (
            part(
                "seed.exr",
                &scene,
                &["--sample-range", "3..5", "--seed", "7"],
            ),
            &["seed.exr", "seed 7 differs", "a.exr's 0"],
        ),
        (
            part("scene.exr", &other_scene, &["--sample-range", "3..5"]),
            &["scene.exr", "scene", "(other.json) differs", "(scene.json)"],
        ),
        (
            part(
                "light.exr",
                &scene,
                &["--sample-range", "3..5", "--strategy", "light"],
            ),
            &["light.exr", "settings", "Light", "differs", "a.exr's"],
        ),
        (
            part("plain.exr", &scene, &["--spp", "2"]),
            &["plain.exr", "not a lumis part file"],
        ),
    ];
    let out = dir.path("out.exr");
    for (bad, needles) in &cases {
        let args = [OsStr::new("merge"), a.as_os_str(), bad.as_os_str()];
        expect_error(
            &lumis(&[&args[..], &[OsStr::new("-o"), out.as_os_str()]].concat()),
            needles,
        );
        assert!(!out.exists(), "nothing is written when a merge is refused");
    }
    let missing = dir.path("missing.exr");
    let args = [OsStr::new("merge"), a.as_os_str(), missing.as_os_str()];
    expect_error(
        &lumis(&[&args[..], &[OsStr::new("-o"), out.as_os_str()]].concat()),
        &["missing.exr", "no such file"],
    );
    let png = dir.path("out.png");
    expect_error(
        &lumis(&[
            OsStr::new("merge"),
            a.as_os_str(),
            OsStr::new("-o"),
            png.as_os_str(),
        ]),
        &["out.png", ".exr"],
    );
}

#[test]
fn sample_range_errors_are_one_line() {
    let dir = TempDir::new("range");
    let scene = dir.scene("scene.json", 8, 2);
    let out = dir.path("out.exr");
    let run = |extra: &[&str], o: &Path| {
        let mut args = vec![OsStr::new("render"), scene.as_os_str()];
        args.extend(extra.iter().map(OsStr::new));
        args.extend([OsStr::new("-o"), o.as_os_str()]);
        lumis(&args)
    };
    for (range, needle) in [
        ("5..5", "5..5 is empty"),
        ("8..3", "8..3 is reversed"),
        ("7", "not START..END"),
        ("x..4", "not a sample index"),
        ("0..4294967296", "not a sample index"),
    ] {
        expect_error(
            &run(&["--sample-range", range], &out),
            &["--sample-range", needle],
        );
    }
    expect_error(
        &run(&["--sample-range", "0..4", "--spp", "4"], &out),
        &["--sample-range", "cannot be used with", "--spp"],
    );
    expect_error(
        &run(&["--sample-range", "0..4", "--backend", "gpu"], &out),
        &["--sample-range needs --backend cpu"],
    );
    expect_error(
        &run(&["--sample-range", "0..4"], &dir.path("out.png")),
        &["out.png", "part file", ".exr"],
    );
    // mis-optimal's weights come from the samples before the range: refused after sample 0.
    expect_error(
        &run(
            &["--sample-range", "8..16", "--strategy", "mis-optimal"],
            &out,
        ),
        &["mis-optimal", "must start at 0", "8"],
    );
    assert!(!out.exists());
    // A part from sample 0 is the render itself.
    render(
        &scene,
        &out,
        &["--sample-range", "0..2", "--strategy", "mis-optimal"],
    );
    assert!(out.exists());
}
