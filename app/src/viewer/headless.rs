//! `lumis view` without a display: render what the window would have shown to PNG files, so that
//! the first command of the README works on a server or in CI.

use super::ViewerOptions;
use crate::scene_file::load_scene_warning as load_scene;
use lumis::engine::AnyProgressive;
use lumis::image_io::Image;
use lumis::scene::Scene;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

/// Renders every lane of `options` and writes each as a PNG, after one line on stderr saying
/// `why` there is no window (printed once the scene has loaded, so that a scene error stays the
/// only line).
pub fn render(options: &ViewerOptions, why: &str) -> anyhow::Result<()> {
    let mut desc = load_scene(&options.scene)?;
    options
        .size
        .apply(&mut desc.camera)
        .map_err(|e| anyhow::anyhow!(e))?;
    let scene = Arc::new(Scene::from_desc(&desc).map_err(|e| e.in_file(&options.scene))?);
    let lanes = options.params.lanes();
    let spp = match options.params.spp_limit {
        0 => options.headless_spp.max(1),
        n => n,
    };
    let base = options.headless_output.clone().unwrap_or_else(|| {
        let stem = options
            .scene
            .file_stem()
            .map_or("lumis".into(), |s| s.to_string_lossy().into_owned());
        PathBuf::from(format!("{stem}.png"))
    });
    let outputs: Vec<PathBuf> = if lanes.len() == 1 {
        vec![base.clone()]
    } else {
        let stem = base.with_extension("");
        lanes
            .iter()
            .map(|l| {
                PathBuf::from(format!(
                    "{}-{}.png",
                    stem.display(),
                    l.label.replace(' ', "_")
                ))
            })
            .collect()
    };
    eprintln!(
        "lumis view: {why}; rendering {spp} spp headless to {}",
        outputs
            .iter()
            .map(|p| p.display().to_string())
            .collect::<Vec<_>>()
            .join(", ")
    );
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(options.threads)
        .build()?;
    let mut gpu = None;
    for (lane, out) in lanes.iter().zip(&outputs) {
        let mut r = AnyProgressive::with_device(
            lane.backend,
            scene.clone(),
            lane.settings,
            options.seed,
            &mut gpu,
        )?;
        let start = Instant::now();
        // Passes of a few samples so that a huge spp budget still uses every thread evenly.
        while r.spp() < spp {
            let n = (spp - r.spp()).min(8);
            pool.install(|| r.render_pass(n));
        }
        let seconds = start.elapsed().as_secs_f64();
        let film = r.film().map_err(anyhow::Error::msg)?;
        Image {
            width: film.width,
            height: film.height,
            data: film.mean(),
        }
        .write(out, options.exposure)?;
        println!(
            "{}: spp={} seconds={seconds:.3} nonfinite={} -> {}",
            lane.label,
            film.spp,
            film.nonfinite,
            out.display()
        );
    }
    Ok(())
}
