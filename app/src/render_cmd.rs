//! `lumis render` and `lumis compare`.

use crate::cli::{BackendArg, CompareArgs, RenderArgs, StrategyArg};
use anyhow::{Context, bail};
use indicatif::{ProgressBar, ProgressStyle};
use lumis::engine::{AnyProgressive, Progressive};
use lumis::image_io::Image;
use lumis::metrics::{relmse, rmse};
use lumis::scene::Scene;
use lumis_app::delta_lights::{self, missed_delta_lights};
use lumis_app::part_file::{Part, Provenance, format_ranges};
use std::sync::Arc;
use std::time::Instant;

/// Renders a scene headless and writes the image.
pub fn render(args: &RenderArgs) -> anyhow::Result<()> {
    let mut settings = args.estimator.settings()?;
    if args.spp == Some(0) {
        bail!("--spp must be at least 1");
    }
    check_output_extension(&args.output)?;
    if args.sample_range.is_some() {
        check_part_options(args)?;
    }
    check_output_dir(&args.output)?;
    lumis_app::scene_file::set_studio(!args.no_studio);
    lumis_app::scene_file::set_defines(&args.scene, args.define.clone(), args.spp);
    let loaded = lumis_app::scene_file::load_scene_file(&args.scene)?;
    // clap allows at most one of --spp and --sample-range; a Mitsuba scene names a default.
    let (first, spp) = match (&args.sample_range, args.spp.or(loaded.spp)) {
        (Some(r), _) => (r.start, r.end - r.start),
        (None, Some(spp)) => (0, spp),
        (None, None) => bail!("--spp is required (the scene names no sample count)"),
    };
    if let Some(rr) = loaded.rr_depth {
        settings.rr_depth = rr;
    }
    let mut desc = loaded.desc;
    args.size
        .apply(&mut desc.camera)
        .map_err(|e| anyhow::anyhow!(e))?;
    let scene = Arc::new(Scene::from_desc(&desc).map_err(|e| e.in_file(&args.scene))?);
    let missed = missed_delta_lights(settings.strategy, &scene);
    if let Some(note) = delta_lights::note(&missed, "this image") {
        eprintln!("{note}");
    }
    let pool = thread_pool(args.threads)?;
    let mut render = match args.sample_range {
        Some(_) => AnyProgressive::Cpu(Progressive::with_first_sample(
            scene, settings, args.seed, first,
        )),
        None => AnyProgressive::new(args.backend.backend(), scene, settings, args.seed)?,
    };
    let bar = ProgressBar::new(spp as u64);
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} spp  {elapsed_precise} (eta {eta})")
            .expect("valid progress template"),
    );
    let start = Instant::now();
    let mut pass = 1u32;
    while render.spp() < spp {
        // The time limit never stops the first pass: a 0-spp image would be silently black.
        if let Some(limit) = args.time_limit
            && render.spp() > 0
            && start.elapsed().as_secs_f64() >= limit
        {
            break;
        }
        let n = pass.min(spp - render.spp());
        let t = Instant::now();
        pool.install(|| render.render_pass(n));
        bar.set_position(render.spp() as u64);
        // Aim for passes of about a quarter second: responsive to the time limit, cheap to schedule.
        let dt = t.elapsed().as_secs_f64().max(1e-6);
        pass = ((n as f64 * 0.25 / dt).clamp(1.0, 4096.0)) as u32;
        if let Some(limit) = args.time_limit {
            let left = limit - start.elapsed().as_secs_f64();
            pass = pass.min(((left / dt) * n as f64).max(1.0) as u32);
        }
    }
    let seconds = start.elapsed().as_secs_f64();
    bar.finish_and_clear();
    let film = render.film()?;
    // A time limit can end a part early: it holds (and says) only the samples rendered.
    let rendered = first..first + film.spp;
    if args.sample_range.is_some() {
        let provenance = Provenance::new(&args.scene, args.seed, &settings)?;
        Part {
            film: film.clone().into_owned(),
            samples: vec![rendered.clone()],
            provenance,
        }
        .write(&args.output)?;
    } else {
        let img = Image {
            width: film.width,
            height: film.height,
            data: film.mean(),
        };
        img.write(&args.output, args.exposure)?;
    }
    let total = film.spp as f64 * film.width as f64 * film.height as f64;
    let range = match args.sample_range {
        Some(_) => format!(
            " samples={}",
            format_ranges(std::slice::from_ref(&rendered))
        ),
        None => String::new(),
    };
    println!(
        "spp={} seconds={:.3} samples_per_second={:.4e} nonfinite={}{range}",
        film.spp,
        seconds,
        total / seconds,
        film.nonfinite
    );
    Ok(())
}

/// What `--sample-range` needs besides a valid range: the CPU backend, whose film holds the
/// exact f64 sums, and an EXR output to hold them.
fn check_part_options(args: &RenderArgs) -> anyhow::Result<()> {
    if args.backend == BackendArg::Gpu {
        bail!(
            "--sample-range needs --backend cpu: the GPU accumulates f32 running means from \
             sample 0, which cannot start at an offset or merge exactly"
        );
    }
    let ext = args.output.extension().and_then(|e| e.to_str());
    if !ext.is_some_and(|e| e.eq_ignore_ascii_case("exr")) {
        bail!(
            "{}: --sample-range writes a part file, which must end in .exr",
            args.output.display()
        );
    }
    if let Some(range) = &args.sample_range
        && range.start > 0
        && args.estimator.strategy == StrategyArg::MisOptimal
    {
        bail!(
            "--strategy mis-optimal learns each pixel's weights from its samples before the \
             range, which a part starting at sample {} does not render: a mis-optimal part must \
             start at 0 (render 0..{} as one part), or use another strategy",
            range.start,
            range.end
        );
    }
    Ok(())
}

/// Fails before rendering, not after, when `path` could never be written because its directory
/// is missing.
pub(crate) fn check_output_dir(path: &std::path::Path) -> anyhow::Result<()> {
    if let Some(dir) = path.parent()
        && !dir.as_os_str().is_empty()
        && !dir.is_dir()
    {
        bail!(
            "{}: the directory {} does not exist",
            path.display(),
            dir.display()
        );
    }
    Ok(())
}

/// The worker pool for `--threads` (`None`: all cores).
pub(crate) fn thread_pool(threads: Option<usize>) -> anyhow::Result<rayon::ThreadPool> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .build()
        .context("starting worker threads")
}

fn check_output_extension(path: &std::path::Path) -> anyhow::Result<()> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    if !matches!(ext.as_str(), "exr" | "pfm" | "png") {
        bail!("{}: output must end in .exr, .pfm or .png", path.display());
    }
    Ok(())
}

/// Prints the relMSE and RMSE of an image against a reference.
pub fn compare(args: &CompareArgs) -> anyhow::Result<()> {
    let img = Image::read(&args.image)?;
    let reference = Image::read(&args.reference)?;
    if (img.width, img.height) != (reference.width, reference.height) {
        bail!(
            "{} is {}x{} but {} is {}x{}",
            args.image.display(),
            img.width,
            img.height,
            args.reference.display(),
            reference.width,
            reference.height
        );
    }
    println!(
        "relmse={:.6e} rmse={:.6e}",
        relmse(&img.data, &reference.data),
        rmse(&img.data, &reference.data)
    );
    Ok(())
}
