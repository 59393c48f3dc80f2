// Temporary investigation tool (not committed): block means of K independent renders.
use lumis::engine::Progressive;
use lumis::image_io::Image;
use lumis::integrator::{Heuristic, Settings, Strategy};
use lumis::scene::Scene;
use std::sync::Arc;
fn main() {
    let a: Vec<String> = std::env::args().collect();
    let scene = Arc::new(Scene::load(std::path::Path::new(&a[1])).unwrap());
    let reference = Image::read(std::path::Path::new(&a[7])).unwrap();
    let strategy = match a[2].as_str() {
        "light" => Strategy::Light,
        "bsdf" => Strategy::Bsdf,
        "mix" => Strategy::Mixture { light_weight: 0.5 },
        _ => Strategy::Mis {
            heuristic: Heuristic::Power,
        },
    };
    let spp: u32 = a[3].parse().unwrap();
    let k: u32 = a[4].parse().unwrap();
    let (bx, by): (u32, u32) = (a[5].parse().unwrap(), a[6].parse().unwrap());
    let w = scene.camera.width;
    let block = |img: &[glam::Vec3]| {
        let mut s = glam::DVec3::ZERO;
        let mut n = 0.0;
        for y in by..(by + 32).min(scene.camera.height) {
            for x in bx..(bx + 32).min(w) {
                s += img[(y * w + x) as usize].as_dvec3();
                n += 1.0;
            }
        }
        s / n
    };
    println!("reference {:?}", block(&reference.data));
    let mut means = vec![];
    for seed in 0..k {
        let mut r = Progressive::new(
            scene.clone(),
            Settings {
                strategy,
                light_sampling: if a[8] == "area" {
                    lumis::lights::LightSampling::Area
                } else {
                    lumis::lights::LightSampling::SolidAngle
                },
                ..Settings::default()
            },
            500 + seed,
        );
        r.render_pass(spp);
        let m = block(&r.film().mean());
        let var = r.film().variance_of_mean();
        let mut v = 0.0;
        let mut n = 0.0;
        for y in by..(by + 32).min(scene.camera.height) {
            for x in bx..(bx + 32).min(w) {
                v += var[(y * w + x) as usize][0];
                n += 1.0;
            }
        }
        println!("seed {seed}: {:?} sd_est(R) {:.5}", m, (v / (n * n)).sqrt());
        means.push(m);
    }
    let mean = means.iter().fold(glam::DVec3::ZERO, |a, b| a + *b) / k as f64;
    let var = means
        .iter()
        .fold(glam::DVec3::ZERO, |a, b| a + (*b - mean) * (*b - mean))
        / (k as f64 - 1.0);
    println!(
        "mean {:?} sd_of_mean {:?} rel {:?}",
        mean,
        (var / k as f64).powf(0.5),
        mean / block(&reference.data) - 1.0
    );
}
