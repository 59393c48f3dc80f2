//! Renders a converged reference of a scene with lumis's own MIS estimator and writes the mean
//! (`OUT.exr`) and the per-pixel variance of that mean (`OUT.var.exr`), in the layout of the
//! independent references in `tests/data/refs/`. Used for scenes the independent renderer cannot
//! render (the `plastic` material): they test that all strategies agree with MIS.
//!
//! `cargo run --release -p lumis-renderer --example make_reference -- SCENE.json SPP SEED OUT`

use lumis::engine::Progressive;
use lumis::image_io::Image;
use lumis::integrator::Settings;
use lumis::scene::Scene;
use std::path::Path;
use std::sync::Arc;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() != 5 {
        eprintln!("usage: make_reference SCENE.json SPP SEED OUT (writes OUT.exr and OUT.var.exr)");
        std::process::exit(2);
    }
    let scene = Arc::new(Scene::load(Path::new(&args[1])).unwrap_or_else(|e| panic!("{e}")));
    let spp: u32 = args[2].parse().expect("SPP");
    let seed: u32 = args[3].parse().expect("SEED");
    let mut render = Progressive::new(scene, Settings::default(), seed);
    while render.film().spp < spp {
        render.render_pass(16.min(spp - render.film().spp));
        eprint!("\r{}/{spp} spp", render.film().spp);
    }
    eprintln!();
    let film = render.film();
    assert_eq!(film.nonfinite, 0, "non-finite samples");
    let (width, height) = (film.width, film.height);
    Image {
        width,
        height,
        data: film.mean(),
    }
    .write(Path::new(&format!("{}.exr", args[4])), 0.0)
    .unwrap();
    let var = film
        .variance_of_mean()
        .iter()
        .map(|v| glam::Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32))
        .collect();
    Image {
        width,
        height,
        data: var,
    }
    .write(Path::new(&format!("{}.var.exr", args[4])), 0.0)
    .unwrap();
}
