//! `lumis bench`: the curves it writes, their error against a reference, its time budget and
//! its option errors.

use super::*;

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
