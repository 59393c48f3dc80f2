//! Delta lights (point, spot, …) under a BSDF-only strategy: `render` and `bench` say in one
//! stderr line that their light is missing, and say nothing for strategies that sample lights.

use super::*;

/// A diffuse floor seen from above, lit only by a point light and a green spot.
const DELTA_SCENE: &str = r#"{
  "camera": {"from": [0, 5, 0.001], "to": [0, 0, 0], "up": [0, 0, 1], "vfov_deg": 60,
             "width": 32, "height": 32},
  "materials": {"floor": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
  "shapes": [{"type": "quad", "corner": [-10, 0, -10], "edge_u": [0, 0, 20], "edge_v": [20, 0, 0],
              "material": "floor"}],
  "lights": [
    {"type": "point", "position": [0, 2, 0], "intensity": [4, 4, 4]},
    {"type": "spot", "from": [1, 2, 0], "to": [1, 0, 0], "up": [0, 0, 1], "intensity": [0, 8, 0],
     "cutoff_angle_deg": 30}
  ]
}
"#;

/// `lumis render` of `scene` with `opts`: asserts success, returns stderr and the image.
fn render_stderr(dir: &TempDir, scene: &Path, name: &str, opts: &[&str]) -> (String, Image) {
    let out = dir.path(name);
    let mut args: Vec<&OsStr> = vec!["render".as_ref(), scene.as_os_str()];
    args.extend(opts.iter().map(OsStr::new));
    args.extend([
        "--spp".as_ref(),
        "2".as_ref(),
        "-o".as_ref(),
        out.as_os_str(),
    ]);
    let output = lumis(&args);
    let stderr = text(&output.stderr);
    assert!(output.status.success(), "{opts:?}: {stderr}");
    (stderr, read(&out))
}

/// The note's line, checked: one line on stderr naming both lights and the strategies to use.
fn assert_note(stderr: &str, missing_from: &str) {
    let lines: Vec<&str> = stderr.lines().collect();
    assert_eq!(lines.len(), 1, "{stderr}");
    let line = lines[0];
    for needle in [
        "note: BSDF sampling alone never finds the scene's 2 delta lights (point, spot)",
        &format!("their light is missing from {missing_from}"),
        "use light, mis, mixture (with a weight above 0) or mis-optimal",
    ] {
        assert!(line.contains(needle), "{line:?} lacks {needle:?}");
    }
}

#[test]
fn bsdf_only_render_says_the_delta_lights_are_missing() {
    let dir = TempDir::new("delta-render");
    let scene = dir.write("delta.json", DELTA_SCENE);
    // BSDF sampling alone: the note, and indeed a black image (nothing else emits).
    let (stderr, img) = render_stderr(&dir, &scene, "bsdf.exr", &["--strategy", "bsdf"]);
    assert_note(&stderr, "this image");
    assert!(
        !check_pixels(&img, 32, 32),
        "BSDF sampling found a delta light"
    );
    // A mixture that never picks light sampling is BSDF sampling alone too.
    let opts = ["--strategy", "mixture", "--mix-weight", "0"];
    let (stderr, _) = render_stderr(&dir, &scene, "mix0.exr", &opts);
    assert_note(&stderr, "this image");
    // Strategies that sample lights find them: no note, and a lit image.
    for (name, opts) in [
        ("mis.exr", &["--strategy", "mis"][..]),
        ("light.exr", &["--strategy", "light"]),
        ("mix.exr", &["--strategy", "mixture", "--mix-weight", "0.5"]),
    ] {
        let (stderr, img) = render_stderr(&dir, &scene, name, opts);
        assert!(stderr.is_empty(), "{opts:?}: {stderr}");
        assert!(check_pixels(&img, 32, 32), "{opts:?}: black image");
    }
    // Without delta lights, BSDF sampling says nothing.
    let plain = dir.scene(8, 8);
    let (stderr, _) = render_stderr(&dir, &plain, "plain.exr", &["--strategy", "bsdf"]);
    assert!(stderr.is_empty(), "{stderr}");
}

#[test]
fn bench_says_which_curves_miss_the_delta_lights() {
    let dir = TempDir::new("delta-bench");
    let scene = dir.write("delta.json", DELTA_SCENE);
    let csv = dir.path("curves.csv");
    let run = |strategies: &str| {
        let output = lumis([
            "bench".as_ref(),
            scene.as_os_str(),
            "--strategies".as_ref(),
            strategies.as_ref(),
            "--spp-list".as_ref(),
            "2".as_ref(),
            "-o".as_ref(),
            csv.as_os_str(),
        ]);
        let stderr = text(&output.stderr);
        assert!(output.status.success(), "{strategies}: {stderr}");
        stderr
    };
    assert_note(&run("light,bsdf,mis"), "the bsdf curve");
    assert!(run("light,mis").is_empty());
}
