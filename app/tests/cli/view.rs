//! `lumis view` without a display: a headless render, and its one-line errors.

use super::*;

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
