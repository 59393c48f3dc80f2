//! `lumis view`: command-line options into the viewer's.

use crate::cli::{BackendArg, HeuristicArg, ShowArg, StrategyArg, ViewArgs};
use anyhow::bail;
use lumis::engine::Backend;
use lumis::integrator::Heuristic;
use lumis::lights::LightSampling;
use lumis_app::viewer::params::{Pacing, RenderParams, StrategyKind, ViewMode};
use lumis_app::viewer::tonemap::Content;
use lumis_app::viewer::{ViewerOptions, run};
use std::path::PathBuf;

fn kind(s: StrategyArg) -> StrategyKind {
    match s {
        StrategyArg::Light => StrategyKind::Light,
        StrategyArg::Bsdf => StrategyKind::Bsdf,
        StrategyArg::Mixture => StrategyKind::Mixture,
        StrategyArg::Mis => StrategyKind::Mis,
        StrategyArg::MisOptimal => StrategyKind::MisOptimal,
    }
}

/// The default scene: `assets/seed_cornell.json` from the current folder, else from the source
/// tree this binary was built in (so `lumis view` works from any folder of a checkout).
fn default_scene() -> PathBuf {
    let local = PathBuf::from("assets/seed_cornell.json");
    let built = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../assets/seed_cornell.json"
    ));
    if !local.exists() && built.exists() {
        built
    } else {
        local
    }
}

/// Runs the viewer.
pub fn view(args: &ViewArgs) -> anyhow::Result<()> {
    // Validates the shared options (weight, depth) exactly as `render` does.
    let settings = args.estimator.settings(args.strategy)?;
    if !args.compare.is_empty() && !(2..=3).contains(&args.compare.len()) {
        bail!(
            "--compare takes 2 or 3 strategies, got {}",
            args.compare.len()
        );
    }
    if !args.wipe.is_empty() && args.wipe.len() != 2 {
        bail!("--wipe takes 2 sides, got {}", args.wipe.len());
    }
    if !(0.0..=1.0).contains(&args.wipe_position) {
        bail!(
            "--wipe-position must be in [0, 1], got {}",
            args.wipe_position
        );
    }
    if let Some(e) = args.equal_error
        && !(e > 0.0 && e.is_finite())
    {
        bail!("--equal-error must be a positive relMSE, got {e}");
    }
    let defaults = RenderParams::default();
    let params = RenderParams {
        backend: match args.backend {
            BackendArg::Cpu => Backend::Cpu,
            BackendArg::Gpu => Backend::Gpu,
        },
        strategy: kind(args.strategy),
        mix_weight: args.estimator.mix_weight,
        heuristic: match args.estimator.heuristic {
            HeuristicArg::Balance => Heuristic::Balance,
            HeuristicArg::Power => Heuristic::Power,
        },
        light_sampling: settings.light_sampling,
        light_selection: settings.light_selection,
        max_depth: settings.max_depth,
        sampler: settings.sampler,
        spp_limit: args.spp_limit,
        view: if !args.wipe.is_empty() {
            ViewMode::Wipe
        } else if !args.compare.is_empty() {
            ViewMode::Compare
        } else {
            ViewMode::Single
        },
        compare_strategies: if args.compare.is_empty() {
            defaults.compare_strategies
        } else {
            args.compare.iter().map(|&(s, _)| kind(s)).collect()
        },
        compare_light_sampling: (args.compare.iter())
            .map(|&(_, m)| m.map(LightSampling::from))
            .collect(),
        wipe: match args.wipe[..] {
            [a, b] => [a, b],
            _ => defaults.wipe,
        },
        pacing: if args.equal_error.is_some() {
            Pacing::EqualError
        } else if args.equal_time {
            Pacing::EqualTime
        } else {
            Pacing::EqualSamples
        },
        target_relmse: args.equal_error.unwrap_or(defaults.target_relmse),
    };
    let scene = args.scene.clone().unwrap_or_else(default_scene);
    lumis_app::scene_file::set_studio(!args.no_studio);
    lumis_app::scene_file::set_defines(&scene, args.define.clone(), None);
    run(ViewerOptions {
        scene,
        reference: args.reference.clone(),
        params,
        seed: args.seed,
        threads: args.film.threads.unwrap_or(0),
        size: args.film.size,
        exposure: args.exposure,
        screenshot_dir: args.screenshot_dir.clone(),
        screenshot_after: args.screenshot_after,
        exit_after_screenshot: args.exit_after_screenshot,
        log_latency: args.log_latency,
        headless_output: args.output.clone(),
        headless_spp: args.headless_spp,
        content: match args.show {
            ShowArg::Image => Content::Image,
            ShowArg::Error => Content::RelativeError,
            ShowArg::Difference => Content::Difference,
            ShowArg::TechniqueMap => Content::TechniqueMap,
        },
        inspect: args.inspect,
        window_size: args.window_size,
        wipe_position: args.wipe_position,
    })
}
