//! Bad input and unwritable outputs: one `lumis: ` line naming the file, the JSON path or the
//! option, never a panic.

use super::*;

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
