//! End-to-end tests of the `lumis` binary: `render` to every output format, determinism, every
//! estimator option, the time limit, `compare`, and the one-line `lumis: ` error contract.
//!
//! One module per subcommand (`render.rs`, `compare.rs`, `bench.rs`, `view.rs`), bad input in
//! `errors.rs` and other scene formats in `scenes.rs`; the shared helpers are here.
//!
//! Each test renders a tiny scene (16×16, a diffuse quad under a quad light, max_depth 2) with a
//! few samples per pixel into its own temporary directory.

use lumis::image_io::Image;
use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::Instant;

mod bench;
mod compare;
mod delta_lights;
mod errors;
mod render;
mod scenes;
mod view;

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
