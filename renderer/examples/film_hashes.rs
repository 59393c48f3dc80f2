//! Prints a hash of the film of a fixed set of renders, on the CPU and on the GPU (lavapipe where
//! there is no GPU): the check that a restructuring step keeps every image bit for bit (issue 35).
//! Run it before and after the step and compare the output with `diff`.
//!
//! `cargo run --release -p lumis-renderer --example film_hashes [cpu|gpu|both] > hashes.txt`
//!
//! The set: every scene in `tests/data/scenes` and `tests/data/mitsuba` and the default scenes in
//! `assets/`, each under every strategy, at 2 samples per pixel with seed 7; on `seed_cornell`
//! and `veach_mis` also every light-sampling method, the light BVH and the Sobol sampler. A hash
//! covers each pixel's sums (f64 bits), the sample count and the non-finite count.

use lumis::engine::{Film, Progressive};
use lumis::gpu::{GpuContext, GpuProgressive};
use lumis::integrator::{Heuristic, Settings, Strategy};
use lumis::lights::{LightSampling, LightSelection};
use lumis::sampler::SamplerKind;
use lumis::scene::Scene;
use std::hash::Hasher;
use std::path::{Path, PathBuf};
use std::sync::Arc;

const SPP: u32 = 2;
const SEED: u32 = 7;

fn scenes(root: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for dir in ["tests/data/scenes", "tests/data/mitsuba", "assets"] {
        let mut files: Vec<PathBuf> = std::fs::read_dir(root.join(dir))
            .unwrap_or_else(|e| panic!("{dir}: {e}"))
            .map(|e| e.unwrap().path())
            .filter(|p| matches!(p.extension().and_then(|e| e.to_str()), Some("json" | "xml")))
            .collect();
        files.sort();
        out.extend(files);
    }
    out
}

fn strategies() -> Vec<Strategy> {
    vec![
        Strategy::Light,
        Strategy::Bsdf,
        Strategy::Mixture { light_weight: 0.5 },
        Strategy::Mis {
            heuristic: Heuristic::Balance,
        },
        Strategy::Mis {
            heuristic: Heuristic::Power,
        },
        Strategy::MisOptimal,
    ]
}

/// The settings each scene is rendered with, named.
fn configs(scene_name: &str) -> Vec<(String, Settings)> {
    let mut out: Vec<(String, Settings)> = strategies()
        .into_iter()
        .map(|s| {
            let settings = Settings {
                strategy: s,
                ..Settings::default()
            };
            (format!("{s:?}"), settings)
        })
        .collect();
    if matches!(scene_name, "seed_cornell" | "veach_mis") {
        for m in [
            LightSampling::Area,
            LightSampling::SolidAngleCosine,
            LightSampling::Adaptive,
            LightSampling::ProjectedSolidAngle,
        ] {
            let settings = Settings {
                light_sampling: m,
                ..Settings::default()
            };
            out.push((format!("Mis/{m:?}"), settings));
        }
        let bvh = Settings {
            light_selection: LightSelection::Bvh,
            ..Settings::default()
        };
        out.push(("Mis/Bvh".into(), bvh));
        let sobol = Settings {
            sampler: SamplerKind::Sobol,
            ..Settings::default()
        };
        out.push(("Mis/Sobol".into(), sobol));
    }
    out
}

fn film_hash(film: &Film) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    h.write_u32(film.width);
    h.write_u32(film.height);
    h.write_u32(film.spp);
    h.write_u64(film.nonfinite);
    for p in &film.pixels {
        for v in p.sum.iter().chain(&p.sum_sq).chain(&p.sum_even) {
            h.write_u64(v.to_bits());
        }
    }
    h.finish()
}

fn main() {
    let which = std::env::args().nth(1).unwrap_or_else(|| "both".into());
    let (cpu, gpu) = match which.as_str() {
        "cpu" => (true, false),
        "gpu" => (false, true),
        "both" => (true, true),
        other => panic!("usage: film_hashes [cpu|gpu|both], not {other}"),
    };
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let ctx = if gpu {
        Some(GpuContext::new().unwrap_or_else(|e| panic!("{e}")))
    } else {
        None
    };
    for path in scenes(&root) {
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let rel = path.strip_prefix(&root).unwrap().display().to_string();
        let scene = Arc::new(Scene::load(&path).unwrap_or_else(|e| panic!("{e}")));
        for (label, settings) in configs(&name) {
            if cpu {
                let mut r = Progressive::new(scene.clone(), settings, SEED);
                assert!(r.render_pass(SPP));
                println!("cpu {rel} {label} {:016x}", film_hash(r.film()));
            }
            if let Some(ctx) = &ctx {
                let mut r =
                    GpuProgressive::with_context(ctx.clone(), scene.clone(), settings, SEED)
                        .unwrap_or_else(|e| panic!("{rel}: {e}"));
                r.render_pass(SPP);
                let film = r.film().unwrap_or_else(|e| panic!("{e}"));
                println!("gpu {rel} {label} {:016x}", film_hash(&film));
            }
        }
    }
}
