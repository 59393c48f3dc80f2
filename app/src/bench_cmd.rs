//! `lumis bench`: error against render time for each direct-lighting strategy, as CSV and an
//! optional log-log plot.
//!
//! Each strategy renders progressively from an empty film; at geometric checkpoints (1, 2, 4, … spp,
//! or `--spp-list`) it records the render seconds so far (error computation excluded), the spp, and
//! the relMSE and RMSE against `--reference`, or, without one, their estimates from the two
//! independent half images the film keeps.

use crate::cli::BenchArgs;
use crate::render_cmd::{check_output_dir, thread_pool};
use anyhow::{Context, anyhow, bail};
use lumis::engine::AnyProgressive;
use lumis::image_io::Image;
use lumis::integrator::{Heuristic, Settings, Strategy};
use lumis::metrics::{relmse, rmse};
use lumis::scene::Scene;
use lumis_app::delta_lights::{self, missed_delta_lights};
use lumis_app::image_size::ImageSize;
use std::fmt::Write as _;
use std::path::Path;
use std::sync::Arc;
use std::time::Instant;

/// Time budget per strategy when neither `--seconds` nor `--spp-list` is given.
const DEFAULT_SECONDS: f64 = 10.0;

/// The CSV header, also the column order of [`Checkpoint::csv_row`].
const CSV_HEADER: &str =
    "strategy,seconds,spp,samples_per_second,relmse,rmse,efficiency,error_source";

/// When to record a checkpoint.
enum Schedule {
    /// Double the spp until this many render seconds are spent.
    Seconds(f64),
    /// Exactly these spp, increasing.
    List(Vec<u32>),
}

/// Where the error numbers come from.
#[derive(Clone, Copy, PartialEq, Eq)]
enum ErrorSource {
    Reference,
    HalfBuffer,
}

impl ErrorSource {
    fn name(self) -> &'static str {
        match self {
            ErrorSource::Reference => "reference",
            ErrorSource::HalfBuffer => "half-buffer",
        }
    }
}

/// One measured point of one strategy's curve.
struct Checkpoint {
    seconds: f64,
    spp: u32,
    samples_per_second: f64,
    relmse: f64,
    rmse: f64,
}

impl Checkpoint {
    /// Error reduction per second: `1 / (relMSE · seconds)`, constant for an unbiased estimator
    /// whose error falls as 1/time, so strategies compare by it directly.
    fn efficiency(&self) -> f64 {
        1.0 / (self.relmse * self.seconds)
    }

    fn csv_row(&self, strategy: &str, source: ErrorSource) -> String {
        format!(
            "{strategy},{:.6},{},{:.6e},{:.6e},{:.6e},{:.6e},{}",
            self.seconds,
            self.spp,
            self.samples_per_second,
            self.relmse,
            self.rmse,
            self.efficiency(),
            source.name()
        )
    }
}

/// One strategy's measured curve.
struct Curve {
    settings: Settings,
    points: Vec<Checkpoint>,
}

impl Curve {
    fn name(&self) -> &'static str {
        self.settings.strategy.name()
    }

    /// The strategy with its parameter, for the plot's legend.
    fn label(&self) -> String {
        match self.settings.strategy {
            Strategy::Mixture { light_weight } => format!("mixture (w = {light_weight})"),
            Strategy::Mis { heuristic } => format!(
                "mis ({})",
                match heuristic {
                    Heuristic::Balance => "balance",
                    Heuristic::Power => "power",
                }
            ),
            Strategy::MisOptimal => "mis (optimal weights)".to_owned(),
            s => s.name().to_owned(),
        }
    }
}

/// Runs the benchmark and writes the CSV (and the plot).
pub fn bench(args: &BenchArgs) -> anyhow::Result<()> {
    // Every usage problem is reported before any rendering starts.
    let mut settings: Vec<Settings> = Vec::new();
    for (i, &s) in args.strategies.iter().enumerate() {
        let these = args.estimator.settings(s)?;
        if args.strategies[..i].contains(&s) {
            bail!("--strategies lists {} twice", these.strategy.name());
        }
        settings.push(these);
    }
    let source = if args.reference.is_some() {
        ErrorSource::Reference
    } else {
        ErrorSource::HalfBuffer
    };
    let schedule = schedule(args, source)?;
    check_output_dir(&args.output)?;
    if let Some(plot) = &args.plot {
        let ext = plot.extension().and_then(|e| e.to_str()).unwrap_or("");
        if !ext.eq_ignore_ascii_case("png") {
            bail!("{}: --plot must end in .png", plot.display());
        }
        check_output_dir(plot)?;
    }

    lumis_app::scene_file::set_studio(!args.no_studio);

    lumis_app::scene_file::set_defines(&args.scene, args.define.clone(), None);
    let (scene, rr_depth) = load_scene(&args.scene, &args.film.size)?;
    let scene = Arc::new(scene);
    bsdf_only_note(&settings, &scene);
    if let Some(rr) = rr_depth {
        settings.iter_mut().for_each(|s| s.rr_depth = rr);
    }
    let (width, height) = (scene.camera.width, scene.camera.height);
    let reference = match &args.reference {
        Some(path) => {
            let img = Image::read(path)?;
            if (img.width, img.height) != (width, height) {
                bail!(
                    "{} is {}x{} but the scene {} renders {}x{}",
                    path.display(),
                    img.width,
                    img.height,
                    args.scene.display(),
                    width,
                    height
                );
            }
            Some(img.data)
        }
        None => {
            println!(
                "no --reference: relmse and rmse are half-buffer estimates (the squared difference \
                 of two independent half images estimates the variance of the mean), not errors \
                 against a reference"
            );
            None
        }
    };
    let pool = thread_pool(args.film.threads)?;

    let mut curves = Vec::new();
    for &settings in &settings {
        // The GPU program is compiled here, before the timed passes.
        let mut render =
            AnyProgressive::new(args.backend.backend(), scene.clone(), settings, args.seed)?;
        let mut seconds = 0.0f64;
        let mut points = Vec::new();
        let mut next = match &schedule {
            Schedule::Seconds(_) => match source {
                // Two half images need at least one sample each.
                ErrorSource::HalfBuffer => 2,
                ErrorSource::Reference => 1,
            },
            Schedule::List(list) => list[0],
        };
        loop {
            let n = next - render.spp();
            // Only the render is timed: the error below is measurement, not work a user waits for.
            let t = Instant::now();
            pool.install(|| render.render_pass(n));
            seconds += t.elapsed().as_secs_f64();

            let film = render.film()?;
            let film = &film;
            let (relmse, rmse) = match &reference {
                Some(r) => {
                    let mean = film.mean();
                    (relmse(&mean, r), rmse(&mean, r))
                }
                None => film.half_buffer_error(),
            };
            let samples = film.spp as f64 * width as f64 * height as f64;
            let point = Checkpoint {
                seconds,
                spp: film.spp,
                samples_per_second: samples / seconds.max(1e-9),
                relmse,
                rmse,
            };
            println!(
                "strategy={} spp={} seconds={:.4} samples_per_second={:.4e} relmse={:.4e} \
                 rmse={:.4e} efficiency={:.4e}",
                settings.strategy.name(),
                point.spp,
                point.seconds,
                point.samples_per_second,
                point.relmse,
                point.rmse,
                point.efficiency()
            );
            points.push(point);

            next = match &schedule {
                Schedule::Seconds(budget) => {
                    if seconds >= *budget {
                        break;
                    }
                    match next.checked_mul(2) {
                        Some(n) => n,
                        None => break,
                    }
                }
                Schedule::List(list) => match list.get(points.len()) {
                    Some(&n) => n,
                    None => break,
                },
            };
        }
        curves.push(Curve { settings, points });
    }

    let mut csv = String::new();
    writeln!(csv, "{CSV_HEADER}")?;
    for c in &curves {
        for p in &c.points {
            writeln!(csv, "{}", p.csv_row(c.name(), source))?;
        }
    }
    std::fs::write(&args.output, csv)
        .with_context(|| format!("{}: cannot write", args.output.display()))?;
    if let Some(path) = &args.plot {
        let title = format!(
            "{}: relMSE vs render time ({}); dashed: constant efficiency 1/(relMSE·s)",
            args.scene
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default(),
            match source {
                ErrorSource::Reference => "against the reference",
                ErrorSource::HalfBuffer => "half-buffer estimate",
            }
        );
        plot(&curves, &title, path)?;
    }
    Ok(())
}

/// The checkpoint schedule from `--seconds` / `--spp-list`, validated.
fn schedule(args: &BenchArgs, source: ErrorSource) -> anyhow::Result<Schedule> {
    if args.spp_list.is_empty() {
        let seconds = args.seconds.unwrap_or(DEFAULT_SECONDS);
        if !(seconds.is_finite() && seconds > 0.0) {
            bail!("--seconds must be a positive number, got {seconds}");
        }
        return Ok(Schedule::Seconds(seconds));
    }
    let list = &args.spp_list;
    if list[0] == 0 || list.windows(2).any(|w| w[0] >= w[1]) {
        bail!(
            "--spp-list must be increasing and at least 1, got {}",
            list.iter()
                .map(u32::to_string)
                .collect::<Vec<_>>()
                .join(",")
        );
    }
    if source == ErrorSource::HalfBuffer && list[0] < 2 {
        bail!(
            "--spp-list starts at 1, but without --reference the error is estimated from two half \
             images, which needs at least 2 spp"
        );
    }
    Ok(Schedule::List(list.clone()))
}

/// Says on stderr, in one line, when a benchmarked strategy samples BSDFs only and so never
/// finds the scene's delta lights: its curve then measures an image without their light.
fn bsdf_only_note(settings: &[Settings], scene: &Scene) {
    let mut missed = Vec::new();
    let mut names = Vec::new();
    for s in settings {
        let these = missed_delta_lights(s.strategy, scene);
        if !these.is_empty() {
            missed = these;
            names.push(s.strategy.name());
        }
    }
    let curves = match names.as_slice() {
        [one] => format!("the {one} curve"),
        many => format!("the {} curves", many.join(" and ")),
    };
    if let Some(note) = delta_lights::note(&missed, &curves) {
        eprintln!("{note}");
    }
}

/// Loads the scene at the image size asked for (a smaller image benchmarks faster), and the
/// Russian roulette depth a Mitsuba scene sets.
fn load_scene(path: &Path, size: &ImageSize) -> anyhow::Result<(Scene, Option<u32>)> {
    size.of(1, 1).map_err(|e| anyhow!(e))?;
    let loaded = lumis_app::scene_file::load_scene_file(path)?;
    let mut desc = loaded.desc;
    size.apply(&mut desc.camera).map_err(|e| anyhow!(e))?;
    Ok((
        Scene::from_desc(&desc).map_err(|e| e.in_file(path))?,
        loaded.rr_depth,
    ))
}

/// Plot size in pixels.
const PLOT_SIZE: (u32, u32) = (1024, 640);

/// Okabe–Ito colours (distinguishable with colour-blindness), one per strategy.
const COLOURS: [(u8, u8, u8); 6] = [
    (213, 94, 0),
    (0, 114, 178),
    (0, 158, 115),
    (204, 121, 167),
    (230, 159, 0),
    (86, 180, 233),
];

/// Draws relMSE against seconds on log-log axes, one line per strategy, each labelled with its
/// efficiency at its last checkpoint, and writes it as a PNG.
fn plot(curves: &[Curve], title: &str, path: &Path) -> anyhow::Result<()> {
    use plotters::prelude::*;

    // ab_glyph draws no text without a registered font; the embedded one keeps the plot free of
    // system font libraries.
    plotters::style::register_font("sans-serif", FontStyle::Normal, dejavu::sans::regular())
        .map_err(|_| anyhow!("the embedded plot font is invalid"))?;

    // Log axes cannot show zero or non-finite values (e.g. relMSE 0 against a black reference).
    let plottable = |p: &&Checkpoint| {
        p.seconds.is_finite() && p.seconds > 0.0 && p.relmse.is_finite() && p.relmse > 0.0
    };
    let range = |f: fn(&Checkpoint) -> f64| {
        let (lo, hi) = curves
            .iter()
            .flat_map(|c| c.points.iter().filter(plottable))
            .map(f)
            .fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
                (lo.min(v), hi.max(v))
            });
        if lo.is_finite() {
            // Whole decades: plotters labels a log axis only from its first power of ten on, and
            // this also keeps a single point from giving an empty range.
            // Widened by a hair so rounding cannot drop the end decades' labels.
            10f64.powf(lo.log10().floor()) * (1.0 - 1e-9)
                ..10f64.powf((hi.log10() + 1e-9).ceil()) * (1.0 + 1e-9)
        } else {
            1e-3..1.0
        }
    };
    let (xs, ys) = (range(|p| p.seconds), range(|p| p.relmse));

    let (w, h) = PLOT_SIZE;
    let mut buffer = vec![0u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buffer, PLOT_SIZE).into_drawing_area();
        let draw_err = |e: &dyn std::fmt::Display| anyhow!("drawing the plot: {e}");
        root.fill(&WHITE).map_err(|e| draw_err(&e))?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 19))
            .margin(16)
            .x_label_area_size(48)
            .y_label_area_size(80)
            .build_cartesian_2d(xs.clone().log_scale(), ys.clone().log_scale())
            .map_err(|e| draw_err(&e))?;
        chart
            .configure_mesh()
            .x_desc("render time (s)")
            .y_desc("relMSE")
            // Enough key points for a grid line at every 1…9 × 10ⁿ, labelled at 1, 2 and 5 only.
            .x_labels(60)
            .y_labels(60)
            .x_label_formatter(&log_tick)
            .y_label_formatter(&log_tick)
            // The key points already give every grid line; plotters' extra light lines would
            // crowd into grey bands on log axes.
            .light_line_style(TRANSPARENT)
            .bold_line_style(BLACK.mix(0.12))
            .label_style(("sans-serif", 15))
            .axis_desc_style(("sans-serif", 17))
            .draw()
            .map_err(|e| draw_err(&e))?;
        for (i, c) in curves.iter().enumerate() {
            let (r, g, b) = COLOURS[i % COLOURS.len()];
            let colour = RGBColor(r, g, b);
            let points: Vec<(f64, f64)> = c
                .points
                .iter()
                .filter(plottable)
                .map(|p| (p.seconds, p.relmse))
                .collect();
            let label = match c.points.last() {
                Some(p) => format!(
                    "{}: efficiency {} at {} spp",
                    c.label(),
                    short_number(p.efficiency()),
                    p.spp
                ),
                None => c.label(),
            };
            chart
                .draw_series(LineSeries::new(
                    points.iter().copied(),
                    colour.stroke_width(2),
                ))
                .map_err(|e| draw_err(&e))?
                .label(label)
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 24, y)], colour.stroke_width(2))
                });
            // The line of constant efficiency through the last checkpoint (slope −1 in log-log):
            // a curve below another strategy's line beats that strategy's final efficiency.
            if let Some(last) = c.points.last().filter(|p| plottable(p)) {
                let k = last.relmse * last.seconds;
                let x0 = xs.start.max(k / ys.end);
                let x1 = xs.end.min(k / ys.start);
                if x0 < x1 {
                    chart
                        .draw_series(DashedLineSeries::new(
                            [(x0, k / x0), (x1, k / x1)],
                            6,
                            5,
                            colour.mix(0.45).stroke_width(1),
                        ))
                        .map_err(|e| draw_err(&e))?;
                }
            }
            chart
                .draw_series(points.iter().map(|&p| Circle::new(p, 3, colour.filled())))
                .map_err(|e| draw_err(&e))?;
        }
        chart
            .configure_series_labels()
            .label_font(("sans-serif", 15))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(|e| draw_err(&e))?;
        root.present().map_err(|e| draw_err(&e))?;
    }
    image::save_buffer(path, &buffer, w, h, image::ExtendedColorType::Rgb8)
        .with_context(|| format!("{}: cannot write", path.display()))?;
    Ok(())
}

/// The label of a log-axis key point: only 1, 2 and 5 × 10ⁿ are labelled, to keep them apart.
fn log_tick(v: &f64) -> String {
    // The nudge keeps an exact power of ten that rounds just below itself in its own decade.
    let mantissa = v / 10f64.powf((v.log10() + 1e-9).floor());
    if [1.0, 2.0, 5.0].iter().any(|m| (mantissa - m).abs() < 1e-6) {
        short_number(*v)
    } else {
        String::new()
    }
}

/// A compact tick or legend number with at most 3 significant digits: `0.25`, `47`, `3.1e-4`.
fn short_number(v: f64) -> String {
    let a = v.abs();
    let trim = |s: String| -> String {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_owned()
        } else {
            s
        }
    };
    if a == 0.0 || !v.is_finite() {
        format!("{v}")
    } else if (0.01..10_000.0).contains(&a) {
        let decimals = (2 - a.log10().floor() as i32).max(0) as usize;
        trim(format!("{v:.decimals$}"))
    } else {
        let s = format!("{v:.2e}");
        let (mantissa, exp) = s.split_once('e').expect("exponent format");
        format!("{}e{exp}", trim(mantissa.to_owned()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_numbers() {
        assert_eq!(short_number(0.25), "0.25");
        assert_eq!(short_number(47.044), "47");
        assert_eq!(short_number(0.02), "0.02");
        assert_eq!(short_number(300.0), "300");
        assert_eq!(short_number(0.00031), "3.1e-4");
        assert_eq!(short_number(123456.0), "1.23e5");
        assert_eq!(short_number(1e5), "1e5");
    }
}
