//! Runs the χ² test on one sampler of the suite and writes its histograms, like Nori's warptest:
//!
//! ```sh
//! cargo run --release -p lumis-renderer --example warptest -- NAME [OUT.png] [SAMPLES] [SEED]
//! cargo run --release -p lumis-renderer --example warptest -- list
//! ```
//!
//! Prints the test's summary and the cells that contribute most to the statistic; the PNG shows
//! observed | expected | residual `(O − E)/√E` (red above, blue below, saturating at 4σ), with
//! φ to the right and θ down from the domain's axis (see `lumis::stats::domain`).

use lumis::stats::suite::{all_cases, case_by_name};
use lumis::stats::{ChiSquareTest, write_histogram_png};
use std::path::PathBuf;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(name) = args.first() else {
        eprintln!("usage: warptest NAME|list [OUT.png] [SAMPLES] [SEED]");
        std::process::exit(2);
    };
    if name == "list" {
        for c in all_cases() {
            println!("{}", c.name);
        }
        return;
    }
    let Some(case) = case_by_name(name) else {
        eprintln!("no sampler named '{name}' (try `warptest list`)");
        std::process::exit(2);
    };
    let out = PathBuf::from(args.get(1).map_or("warptest.png", String::as_str));
    let samples = args
        .get(2)
        .map_or(1_000_000, |s| s.parse().expect("SAMPLES"));
    let seed = args.get(3).map_or(0, |s| s.parse().expect("SEED"));

    let mut test = ChiSquareTest::new(&case.sampler)
        .samples(samples)
        .seed(seed);
    let r = test.run();
    println!(
        "{name}: {} samples, {} × {} cells",
        samples, test.res_theta, test.res_phi
    );
    println!("domain: {:?}", test.current_domain());
    println!("{r}");
    println!(
        "{:>5} {:>5} {:>10} {:>10} {:>9}",
        "row", "col", "observed", "expected", "(O-E)²/E"
    );
    for (row, col, o, e) in test.worst_cells(12) {
        println!(
            "{row:5} {col:5} {o:10.0} {e:10.1} {:9.2}",
            (o - e).powi(2) / e
        );
    }
    write_histogram_png(&test, &out).unwrap_or_else(|e| panic!("{e}"));
    println!("wrote {}", out.display());
}
