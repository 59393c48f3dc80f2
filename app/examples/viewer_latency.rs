//! Slider-to-image latency of the viewer: applies the edits the controls make (roughness,
//! mixture weight, light shape, camera orbit, strategy) to a running viewer, exactly as the
//! controls do, and reports the time from each change to the first new image the render thread
//! publishes (what the next frame shows; a reduced-resolution preview) and, in the last column,
//! the median time to the first full-resolution image (1 spp; including a ≤ 5 ms poll).
//! Accumulation is running when each change arrives.
//!
//! `cargo run --release -p lumis-app --example viewer_latency -- [SCENE] [SIZE] [REPEATS] [cpu|gpu]`
//! (default: the seed Cornell box at 512×512, 20 repeats of each edit, the CPU backend).

use lumis_app::viewer::edit;
use lumis_app::viewer::light_shape::LightShape;
use lumis_app::viewer::params::StrategyKind;
use lumis_app::viewer::{ViewerApp, ViewerOptions, camera};
use std::path::PathBuf;
use std::time::{Duration, Instant};

const WAIT: Duration = Duration::from_secs(60);

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let scene = args.first().map_or_else(
        || {
            PathBuf::from(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../assets/seed_cornell.json"
            ))
        },
        PathBuf::from,
    );
    let size: u32 = args.get(1).map_or(512, |s| s.parse().expect("SIZE"));
    let repeats: usize = args.get(2).map_or(20, |s| s.parse().expect("REPEATS"));
    let backend = match args.get(3).map(String::as_str) {
        None | Some("cpu") => lumis::engine::Backend::Cpu,
        Some("gpu") => lumis::engine::Backend::Gpu,
        Some(b) => panic!("backend {b}: cpu or gpu"),
    };
    let mut app = ViewerApp::new(ViewerOptions {
        scene,
        size: lumis_app::image_size::ImageSize {
            width: Some(size),
            height: Some(size),
            resolution_scale: None,
        },
        ..ViewerOptions::default()
    });
    app.params.backend = backend;
    app.restart();
    if let Some(e) = &app.error {
        eprintln!("{e}");
        std::process::exit(1);
    }
    let desc = app.desc.clone().expect("scene loaded");
    let rough = desc
        .materials
        .iter()
        .position(|m| edit::alpha(&m.material).is_some());
    let light = desc
        .shapes
        .iter()
        .position(|s| s.emission.max_element() > 0.0);

    type Edit = Box<dyn Fn(&mut ViewerApp, usize)>;
    let mut edits: Vec<(&str, Edit)> = vec![
        (
            "mixture weight",
            Box::new(|a, k| {
                a.params.mix_weight = 0.25 + 0.5 * (k % 2) as f32;
                a.restart();
            }),
        ),
        (
            "strategy",
            Box::new(|a, k| {
                a.params.strategy = StrategyKind::ALL[k % 4];
                a.restart();
            }),
        ),
        (
            "camera orbit",
            Box::new(|a, _| {
                camera::orbit(&mut a.desc.as_mut().unwrap().camera, 3.0, 1.0);
                a.scene_changed();
            }),
        ),
    ];
    if let Some(i) = rough {
        edits.push((
            "roughness",
            Box::new(move |a, k| {
                let m = &mut a.desc.as_mut().unwrap().materials[i].material;
                edit::set_alpha(m, 0.1 + 0.02 * (k % 20) as f64);
                a.scene_changed();
            }),
        ));
    }
    if let Some(s) = light {
        app.select_light(Some(s));
        if app.light.as_ref().and_then(|l| l.planar_shape()).is_some() {
            edits.push((
                "light sides",
                Box::new(|a, k| {
                    let shape = LightShape::from_slider(3 + (k as u32 * 7) % 63);
                    a.light.as_mut().unwrap().set_shape(shape);
                    a.light_changed();
                }),
            ));
        }
    }

    println!(
        "{size}x{size}, {} rendering threads; ms from change to first image (render thread's clock)",
        rayon::current_num_threads()
    );
    println!(
        "{:<16} {:>8} {:>8} {:>8} {:>12}",
        "edit", "median", "p90", "max", "full-res med"
    );
    let mut all = Vec::new();
    for (name, apply) in &edits {
        let (mut times, mut full) = (Vec::new(), Vec::new());
        for k in 0..repeats {
            // Let the previous change reach full-resolution passes, so each change interrupts
            // a running accumulation as a slider drag would.
            assert!(app.wait_for(WAIT, |o| o.lanes.iter().all(|l| !l.preview && l.spp >= 1)));
            std::thread::sleep(Duration::from_millis(50));
            let t = Instant::now();
            apply(&mut app, k);
            assert!(app.wait_for(WAIT, |o| o.first_image.is_some()));
            let worker = app.output().first_image.unwrap();
            // The poll adds up to 5 ms; the render thread's own clock is the measurement.
            times.push(worker.as_secs_f64() * 1e3);
            assert!(app.wait_for(WAIT, |o| o.lanes.iter().all(|l| !l.preview)));
            full.push(t.elapsed().as_secs_f64() * 1e3);
        }
        full.sort_by(f64::total_cmp);
        times.sort_by(f64::total_cmp);
        let q = |p: f64| times[((times.len() - 1) as f64 * p).round() as usize];
        println!(
            "{name:<16} {:>8.1} {:>8.1} {:>8.1} {:>12.0}",
            q(0.5),
            q(0.9),
            times[times.len() - 1],
            full[full.len() / 2]
        );
        all.extend(times);
    }
    all.sort_by(f64::total_cmp);
    let q = |p: f64| all[((all.len() - 1) as f64 * p).round() as usize];
    println!(
        "{:<16} {:>8.1} {:>8.1} {:>8.1}",
        "all",
        q(0.5),
        q(0.9),
        all[all.len() - 1]
    );
}
