//! `lumis compare`: the metrics it prints and its errors.

use super::*;

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
