//! Command-line arguments.

use clap::{Args, Parser, Subcommand, ValueEnum};
use lumis::integrator::{Heuristic, Settings, Strategy};
use lumis::lights::{LightSampling, LightSelection};
use lumis::sampler::SamplerKind;
use lumis_app::image_size::ImageSize;
use std::path::PathBuf;

/// lumis: an interactive, progressive, physically based path tracer.
#[derive(Parser, Debug)]
#[command(name = "lumis", version, about)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// Subcommands.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Render a scene headless to an image file.
    Render(RenderArgs),
    /// Print the relMSE and RMSE of an image against a reference.
    Compare(CompareArgs),
    /// Measure error against render time for each strategy; write the curves as CSV (and a plot).
    Bench(BenchArgs),
    /// Open the interactive viewer (renders headless to a PNG when there is no display).
    View(ViewArgs),
    /// Combine part files from `render --sample-range` into one, exactly.
    Merge(MergeArgs),
    /// Write a scene as a Mitsuba 3 XML scene (meshes as PLY files beside it).
    Export(ExportArgs),
}

/// Direct-lighting strategy names.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum StrategyArg {
    /// Next-event estimation only.
    Light,
    /// BSDF sampling only.
    Bsdf,
    /// One-sample mixture of light and BSDF sampling with weight --mix-weight.
    Mixture,
    /// Light + BSDF sampling with multiple importance sampling.
    Mis,
    /// Light + BSDF sampling with optimal MIS weights learnt per pixel from its earlier samples
    /// (first vertex; power heuristic deeper). Not with --sample-range parts after sample 0.
    MisOptimal,
}

/// MIS heuristics.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum HeuristicArg {
    /// Balance heuristic.
    Balance,
    /// Power heuristic (exponent 2).
    Power,
}

/// Light sampling methods.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightSamplingArg {
    /// Uniform by area; an environment map uniformly over the sphere.
    Area,
    /// Uniform by solid angle where the shape allows it (spherical triangles, rectangles and
    /// ellipses of disks; cones of spheres); an environment map by importance.
    SolidAngle,
    /// Solid angle, warped towards the receiver's cos θ for triangles, quads and polygons
    /// (Hart et al. 2020).
    SolidAngleCosine,
    /// Per light and shading point: by area where a triangle, quad, polygon or disk looks small,
    /// by solid angle elsewhere (a polygon's triangle picked by its estimated solid angle).
    Adaptive,
    /// Triangles, quads and polygons in proportion to the receiver's cos θ over the part above
    /// its horizon (Peters 2021); by solid angle where too small or grazing to do so accurately.
    ProjectedSolidAngle,
}

/// Light selection rules (`lumis::lights::LightSelection`).
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightSelectionArg {
    /// In proportion to emitted power.
    Power,
    /// By importance at the receiver (power, distance, orientation) in a light BVH.
    Bvh,
}

/// Samplers (`lumis::sampler`).
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SamplerArg {
    /// Independent uniforms (a PCG stream per pixel sample).
    Independent,
    /// Owen-scrambled Sobol points, pixels in Morton order (either backend).
    Sobol,
}

impl From<LightSamplingArg> for LightSampling {
    fn from(a: LightSamplingArg) -> LightSampling {
        match a {
            LightSamplingArg::Area => LightSampling::Area,
            LightSamplingArg::SolidAngle => LightSampling::SolidAngle,
            LightSamplingArg::SolidAngleCosine => LightSampling::SolidAngleCosine,
            LightSamplingArg::Adaptive => LightSampling::Adaptive,
            LightSamplingArg::ProjectedSolidAngle => LightSampling::ProjectedSolidAngle,
        }
    }
}

/// Estimator options shared by every command that renders.
#[derive(Args, Debug, Clone)]
pub struct EstimatorArgs {
    /// Direct-lighting strategy.
    #[arg(long, value_enum, default_value = "mis")]
    pub strategy: StrategyArg,
    /// Everything else about the estimator.
    #[command(flatten)]
    pub options: EstimatorOptions,
}

impl EstimatorArgs {
    /// The renderer settings these options describe.
    pub fn settings(&self) -> anyhow::Result<Settings> {
        self.options.settings(self.strategy)
    }
}

/// The estimator options besides the strategy, so that `bench` can apply them to several
/// strategies in one run.
#[derive(Args, Debug, Clone)]
pub struct EstimatorOptions {
    /// Probability of light sampling in the `mixture` strategy, in [0, 1].
    #[arg(long, default_value_t = 0.5)]
    pub mix_weight: f32,
    /// MIS heuristic for the `mis` strategy.
    #[arg(long, value_enum, default_value = "power")]
    pub heuristic: HeuristicArg,
    /// How points on lights are chosen.
    #[arg(long, value_enum, default_value = "solid-angle")]
    pub light_sampling: LightSamplingArg,
    /// How next-event estimation chooses a light.
    #[arg(long, value_enum, default_value = "power")]
    pub light_selection: LightSelectionArg,
    /// Override the scene's max_depth (-1 = unlimited).
    #[arg(long, allow_negative_numbers = true)]
    pub max_depth: Option<i32>,
    /// Where the random numbers come from (either backend). Sobol by default: it wins at equal
    /// time on the shared scenes from 16 spp on (docs/performance.md, "Sobol sampler").
    #[arg(long, value_enum, default_value = "sobol")]
    pub sampler: SamplerArg,
}

impl EstimatorOptions {
    /// The renderer settings for `strategy` with these options.
    pub fn settings(&self, strategy: StrategyArg) -> anyhow::Result<Settings> {
        if !(0.0..=1.0).contains(&self.mix_weight) {
            anyhow::bail!("--mix-weight must be in [0, 1], got {}", self.mix_weight);
        }
        if let Some(d) = self.max_depth
            && (d == 0 || d < -1)
        {
            anyhow::bail!("--max-depth must be -1 or at least 1, got {d}");
        }
        let heuristic = match self.heuristic {
            HeuristicArg::Balance => Heuristic::Balance,
            HeuristicArg::Power => Heuristic::Power,
        };
        let strategy = match strategy {
            StrategyArg::Light => Strategy::Light,
            StrategyArg::Bsdf => Strategy::Bsdf,
            StrategyArg::Mixture => Strategy::Mixture {
                light_weight: self.mix_weight,
            },
            StrategyArg::Mis => Strategy::Mis { heuristic },
            StrategyArg::MisOptimal => Strategy::MisOptimal,
        };
        let light_sampling = LightSampling::from(self.light_sampling);
        let light_selection = match self.light_selection {
            LightSelectionArg::Power => LightSelection::Power,
            LightSelectionArg::Bvh => LightSelection::Bvh,
        };
        Ok(Settings {
            strategy,
            light_sampling,
            light_selection,
            max_depth: self.max_depth,
            sampler: match self.sampler {
                SamplerArg::Independent => SamplerKind::Independent,
                SamplerArg::Sobol => SamplerKind::Sobol,
            },
            ..Settings::default()
        })
    }
}

/// `lumis render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    /// Scene file (JSON, a mesh file, or a Mitsuba 3 scene `.xml`).
    pub scene: PathBuf,
    /// A parameter of a Mitsuba XML scene, `-D NAME=VALUE`: replaces `$NAME` in the file,
    /// overriding its `<default>` (as `mitsuba -D`); repeatable. Only for `.xml` scenes.
    #[arg(short = 'D', value_name = "NAME=VALUE", value_parser = parse_define)]
    pub define: Vec<(String, String)>,
    /// A model file opened on its own (.obj, .ply, .gltf, .glb, .serialized) is shown without
    /// the studio (its grey ground and studio lights): under a white environment of radiance 1,
    /// as before issue 43. Nothing changes for scene files.
    #[arg(long)]
    pub no_studio: bool,
    /// Samples per pixel (default for a Mitsuba scene: its sampler's `sample_count`; required
    /// otherwise, unless --sample-range is given). In a Mitsuba scene it is also the value of
    /// `$spp`, as `-D spp=N` would be, but no error where the scene has no `$spp`.
    #[arg(long)]
    pub spp: Option<u32>,
    /// Render only the sample indices START..END (END excluded) of the full render, instead of
    /// --spp, and write a part file (.exr) for `lumis merge`.
    #[arg(long, value_name = "START..END", conflicts_with = "spp", value_parser = parse_sample_range)]
    pub sample_range: Option<std::ops::Range<u32>>,
    /// Random seed.
    #[arg(long, default_value_t = 0)]
    pub seed: u32,
    /// Estimator options.
    #[command(flatten)]
    pub estimator: EstimatorArgs,
    /// Where to render.
    #[arg(long, value_enum, default_value = "cpu")]
    pub backend: BackendArg,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// The image size (the scene's by default).
    #[command(flatten)]
    pub size: ImageSize,
    /// Stop after this many seconds even if --spp is not reached.
    #[arg(long)]
    pub time_limit: Option<f64>,
    /// Exposure in stops for PNG output.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub exposure: f32,
    /// Output image: .exr or .pfm (linear float RGB) or .png (sRGB).
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
}

/// `-D`'s value, `NAME=VALUE` (the name is checked when the scene is read).
fn parse_define(text: &str) -> Result<(String, String), String> {
    match text.split_once('=') {
        Some((name, value)) if !name.is_empty() => Ok((name.to_owned(), value.to_owned())),
        _ => Err(format!("`{text}` is not NAME=VALUE")),
    }
}

/// What the viewer's panes show (`lumis_app::viewer::tonemap::Content`).
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShowArg {
    /// The image.
    Image,
    /// The per-pixel relative error in false colour.
    Error,
    /// The signed difference in false colour.
    Difference,
    /// Where light samples and where BSDF samples carry the direct light (CPU lanes).
    TechniqueMap,
}

/// A `--compare` pane: `STRATEGY` or `STRATEGY@LIGHT_SAMPLING`.
fn parse_compare_pane(text: &str) -> Result<(StrategyArg, Option<LightSamplingArg>), String> {
    let (strategy, method) = match text.split_once('@') {
        Some((s, m)) => (s, Some(m)),
        None => (text, None),
    };
    let strategy = StrategyArg::from_str(strategy, false)?;
    let method = method
        .map(|m| LightSamplingArg::from_str(m, false))
        .transpose()?;
    Ok((strategy, method))
}

/// A `--wipe` side.
fn parse_wipe_side(text: &str) -> Result<lumis_app::viewer::wipe::WipeSide, String> {
    lumis_app::viewer::wipe::WipeSide::parse(text)
}

/// `--inspect`'s value, `X,Y`.
fn parse_pixel(text: &str) -> Result<(u32, u32), String> {
    let bad = || format!("`{text}` is not X,Y (two pixel numbers)");
    let (x, y) = text.split_once(',').ok_or_else(bad)?;
    Ok((
        x.trim().parse().map_err(|_| bad())?,
        y.trim().parse().map_err(|_| bad())?,
    ))
}

/// `--window-size`'s value, `WIDTHxHEIGHT`, each 200 to 16384.
fn parse_window_size(text: &str) -> Result<[f32; 2], String> {
    let bad = || format!("`{text}` is not WIDTHxHEIGHT (200 to 16384 each)");
    let (w, h) = text.split_once('x').ok_or_else(bad)?;
    let parse = |v: &str| {
        v.trim()
            .parse::<u32>()
            .ok()
            .filter(|v| (200..=16384).contains(v))
            .ok_or_else(bad)
    };
    Ok([parse(w)? as f32, parse(h)? as f32])
}

/// `--sample-range`'s value, `START..END` (END excluded), non-empty.
fn parse_sample_range(text: &str) -> Result<std::ops::Range<u32>, String> {
    lumis_app::part_file::parse_range(text)
}

/// `lumis export`.
#[derive(Args, Debug)]
pub struct ExportArgs {
    /// Scene file (JSON, a mesh file, or a Mitsuba 3 scene `.xml`).
    pub scene: PathBuf,
    /// A parameter of a Mitsuba XML scene, `-D NAME=VALUE` (as for `render`).
    #[arg(short = 'D', value_name = "NAME=VALUE", value_parser = parse_define)]
    pub define: Vec<(String, String)>,
    /// A model file opened on its own (.obj, .ply, .gltf, .glb, .serialized) is shown without
    /// the studio (its grey ground and studio lights): under a white environment of radiance 1,
    /// as before issue 43. Nothing changes for scene files.
    #[arg(long)]
    pub no_studio: bool,
    /// The sampler's `sample_count` to write (default: the scene's, if it names one, else none:
    /// Mitsuba's 4).
    #[arg(long)]
    pub spp: Option<u32>,
    /// Output Mitsuba scene (.xml); PLY files go beside it, named after their shapes.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
}

/// `lumis merge`.
#[derive(Args, Debug)]
pub struct MergeArgs {
    /// Part files written by `lumis render --sample-range` (or by `lumis merge`), of one scene,
    /// seed and estimator, with disjoint sample ranges.
    #[arg(required = true)]
    pub parts: Vec<PathBuf>,
    /// Output part file (.exr): the mean of all their samples, and the sums to merge it again.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
}

/// `lumis compare`.
#[derive(Args, Debug)]
pub struct CompareArgs {
    /// Image to judge (EXR or PFM).
    pub image: PathBuf,
    /// Reference image (EXR or PFM).
    pub reference: PathBuf,
}

/// Where `render`, `bench` and `view` render.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum BackendArg {
    /// The multi-threaded CPU engine.
    Cpu,
    /// The GPU engine (wgpu compute; Mesa's lavapipe where there is no GPU).
    Gpu,
}

/// `lumis bench`.
#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Scene file (JSON, a mesh file, or a Mitsuba 3 scene `.xml`).
    pub scene: PathBuf,
    /// A parameter of a Mitsuba XML scene, `-D NAME=VALUE`: replaces `$NAME` in the file,
    /// overriding its `<default>` (as `mitsuba -D`); repeatable. Only for `.xml` scenes.
    #[arg(short = 'D', value_name = "NAME=VALUE", value_parser = parse_define)]
    pub define: Vec<(String, String)>,
    /// A model file opened on its own (.obj, .ply, .gltf, .glb, .serialized) is shown without
    /// the studio (its grey ground and studio lights): under a white environment of radiance 1,
    /// as before issue 43. Nothing changes for scene files.
    #[arg(long)]
    pub no_studio: bool,

    /// Reference image (EXR or PFM) of the same size; without it the error is estimated from two
    /// independent half images.
    #[arg(long)]
    pub reference: Option<PathBuf>,
    /// Strategies to measure, comma-separated.
    #[arg(
        long,
        value_enum,
        value_delimiter = ',',
        default_value = "light,bsdf,mixture,mis"
    )]
    pub strategies: Vec<StrategyArg>,
    /// Where to render.
    #[arg(long, value_enum, default_value = "cpu")]
    pub backend: BackendArg,
    /// Render time per strategy: checkpoints at 1, 2, 4, … spp (from 2 without --reference) until
    /// this many seconds of rendering are spent (the default, 10 s, when --spp-list is not given
    /// either); the last doubling can take the total to about twice the budget.
    #[arg(long, conflicts_with = "spp_list")]
    pub seconds: Option<f64>,
    /// Checkpoints in samples per pixel, comma-separated and increasing, instead of --seconds.
    #[arg(long, value_delimiter = ',')]
    pub spp_list: Vec<u32>,
    /// Random seed.
    #[arg(long, default_value_t = 0)]
    pub seed: u32,
    /// Estimator options (--mix-weight applies to `mixture`, --heuristic to `mis`).
    #[command(flatten)]
    pub estimator: EstimatorOptions,
    /// Threads and image size.
    #[command(flatten)]
    pub film: FilmOptions,
    /// Output CSV: strategy,seconds,spp,samples_per_second,relmse,rmse,efficiency,error_source.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    /// Also plot relMSE against seconds (log-log) to this PNG.
    #[arg(long)]
    pub plot: Option<PathBuf>,
}

/// Threads and image size, shared by `bench` and `view`.
#[derive(Args, Debug)]
pub struct FilmOptions {
    /// Rendering threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// The image size (the scene's by default).
    #[command(flatten)]
    pub size: ImageSize,
}

/// `lumis view`.
#[derive(Args, Debug)]
pub struct ViewArgs {
    /// Scene file (JSON, a mesh file, or a Mitsuba 3 scene `.xml`) [default: the seed Cornell
    /// box, assets/seed_cornell.json].
    pub scene: Option<PathBuf>,
    /// A parameter of a Mitsuba XML scene, `-D NAME=VALUE`: replaces `$NAME` in the file,
    /// overriding its `<default>` (as `mitsuba -D`); repeatable. Only for `.xml` scenes.
    #[arg(short = 'D', value_name = "NAME=VALUE", value_parser = parse_define)]
    pub define: Vec<(String, String)>,
    /// A model file opened on its own (.obj, .ply, .gltf, .glb, .serialized) is shown without
    /// the studio (its grey ground and studio lights): under a white environment of radiance 1,
    /// as before issue 43. Nothing changes for scene files.
    #[arg(long)]
    pub no_studio: bool,

    /// Reference image (EXR or PFM, the film's size) for the error; without it the error is
    /// estimated from two independent half images.
    #[arg(long)]
    pub reference: Option<PathBuf>,
    /// Strategy of the single view.
    #[arg(long, value_enum, default_value = "mis")]
    pub strategy: StrategyArg,
    /// Where to render (switchable live in the window).
    #[arg(long, value_enum, default_value = "cpu")]
    pub backend: BackendArg,
    /// Estimator options.
    #[command(flatten)]
    pub estimator: EstimatorOptions,
    /// Open the comparison view with these 2 or 3 panes side by side (comma-separated), each
    /// `STRATEGY` or `STRATEGY@LIGHT_SAMPLING` (a light-sampling method of its own), e.g.
    /// `light,bsdf,mis` or `mis@solid-angle,mis@projected-solid-angle`.
    #[arg(long, value_delimiter = ',', value_parser = parse_compare_pane)]
    pub compare: Vec<(StrategyArg, Option<LightSamplingArg>)>,
    /// Open the wipe: two sides in one image split by a divider, each `STRATEGY`,
    /// `STRATEGY:cpu`, `STRATEGY:gpu` or `reference` (comma-separated), e.g. `light,mis`,
    /// `mis:cpu,mis:gpu` or `mis,reference`.
    #[arg(long, value_delimiter = ',', value_parser = parse_wipe_side, conflicts_with = "compare")]
    pub wipe: Vec<lumis_app::viewer::wipe::WipeSide>,
    /// Where the wipe's divider starts, 0 (left) to 1 (right).
    #[arg(long, default_value_t = 0.5)]
    pub wipe_position: f32,
    /// Compare at equal render time instead of equal samples per pixel.
    #[arg(long, conflicts_with = "equal_error")]
    pub equal_time: bool,
    /// Stop each pane when its relMSE reaches this (equal-error comparison: the times to this
    /// error are reported).
    #[arg(long, value_name = "RELMSE")]
    pub equal_error: Option<f64>,
    /// What the panes show: the image, the per-pixel relative error, the signed difference
    /// (A − B in the wipe, else against the reference or the first pane), or the technique map
    /// (where light samples and where BSDF samples carry the direct light; CPU lanes).
    #[arg(long, value_enum, default_value = "image")]
    pub show: ShowArg,
    /// The pixel the inspector shows at first, `X,Y` [default: the image centre].
    #[arg(long, value_parser = parse_pixel)]
    pub inspect: Option<(u32, u32)>,
    /// The window's size in points, `WIDTHxHEIGHT`.
    #[arg(long, default_value = "1400x900", value_parser = parse_window_size)]
    pub window_size: [f32; 2],
    /// Stop accumulating at this many samples per pixel (0: never).
    #[arg(long, default_value_t = 0)]
    pub spp_limit: u32,
    /// Random seed.
    #[arg(long, default_value_t = 0)]
    pub seed: u32,
    /// Threads and image size.
    #[command(flatten)]
    pub film: FilmOptions,
    /// Initial exposure in stops.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub exposure: f32,
    /// Folder for screenshots (Ctrl+S or F12): lumis-NNNN*.png/.exr/.csv.
    #[arg(long, default_value = ".")]
    pub screenshot_dir: PathBuf,
    /// Take a screenshot as soon as every pane has this many samples per pixel.
    #[arg(long)]
    pub screenshot_after: Option<u32>,
    /// Close the window after the --screenshot-after screenshot is saved.
    #[arg(long, requires = "screenshot_after")]
    pub exit_after_screenshot: bool,
    /// Print the time from every restart to its first image on stderr.
    #[arg(long)]
    pub log_latency: bool,
    /// Without a display: the PNG to write [default: SCENE_NAME.png].
    #[arg(short = 'o', long = "output")]
    pub output: Option<PathBuf>,
    /// Without a display: samples per pixel when no --spp-limit is given.
    #[arg(long, default_value_t = 64)]
    pub headless_spp: u32,
}

impl BackendArg {
    /// The renderer's backend.
    pub fn backend(self) -> lumis::engine::Backend {
        match self {
            BackendArg::Cpu => lumis::engine::Backend::Cpu,
            BackendArg::Gpu => lumis::engine::Backend::Gpu,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `--compare` panes: a strategy alone, or with a light-sampling method of its own; an
    /// unknown name on either side is an error naming it.
    #[test]
    fn compare_panes_parse() {
        assert_eq!(parse_compare_pane("mis"), Ok((StrategyArg::Mis, None)));
        assert_eq!(
            parse_compare_pane("light@projected-solid-angle"),
            Ok((
                StrategyArg::Light,
                Some(LightSamplingArg::ProjectedSolidAngle)
            ))
        );
        assert!(parse_compare_pane("mis@nope").unwrap_err().contains("nope"));
        assert!(
            parse_compare_pane("nope@area")
                .unwrap_err()
                .contains("nope")
        );
    }
}
