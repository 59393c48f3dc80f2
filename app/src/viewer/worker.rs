//! The render thread. The UI hands it a [`Job`] (scene description, one lane per strategy shown)
//! and never waits for it: the thread builds the scene, renders reduced-resolution previews and
//! then full passes, and publishes an [`Output`] the UI copies each frame. A new job cancels the
//! running pass through the engines' cancel flags, so a restart takes effect at once.

use super::convergence::{CurvePoint, ErrorSource, film_error, pixel_errors};
use super::gpu_display::LiveImage;
use super::params::Pacing;
use super::preview::{preview_factors, render_preview};
use glam::Vec3;
use lumis::engine::{AnyProgressive, Backend};
use lumis::gpu::GpuContext;
use lumis::integrator::Settings;
use lumis::scene::{Scene, SceneDesc};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// Passes aim at this duration: short enough that the image updates several times a second,
/// long enough that scheduling and publishing stay negligible.
const TARGET_PASS: Duration = Duration::from_millis(120);

/// A GPU lane shown straight from its accumulation buffer is read back (for the error, the
/// curve and false colour) at most this often, not after every pass.
const READBACK_EVERY: Duration = Duration::from_millis(500);

/// One independent accumulation: a strategy and its settings.
#[derive(Clone, Debug, PartialEq)]
pub struct LaneSpec {
    /// Name shown above the pane (the strategy).
    pub label: String,
    /// Estimator settings.
    pub settings: Settings,
    /// Where this lane renders (a wipe may put CPU and GPU side by side).
    pub backend: Backend,
}

/// Everything the render thread needs for one accumulation run.
#[derive(Clone)]
pub struct Job {
    /// The scene as edited in the UI.
    pub desc: Arc<SceneDesc>,
    /// Bumped by the UI on every edit of `desc`; tells whether `scene` still matches it.
    pub desc_version: u64,
    /// The scene already built from this `desc_version`, when only settings changed.
    pub scene: Option<Arc<Scene>>,
    /// The lanes, rendered side by side.
    pub lanes: Vec<LaneSpec>,
    /// Random seed of every lane.
    pub seed: u32,
    /// Stop each lane at this many samples per pixel (0: never).
    pub spp_limit: u32,
    /// How lanes share render time.
    pub pacing: Pacing,
    /// With [`Pacing::EqualError`]: stop each lane when its relMSE reaches this.
    pub target_relmse: f64,
    /// The window's wgpu device, when it has one: GPU lanes then render on it and are shown
    /// from their accumulation buffers without a readback per pass.
    pub gpu: Option<Arc<GpuContext>>,
    /// Reference image for the error, same size as the film.
    pub reference: Option<Arc<Vec<Vec3>>>,
}

/// What one lane shows now.
#[derive(Clone, Debug)]
pub struct LaneView {
    /// Strategy name.
    pub label: String,
    /// The estimator settings this lane renders with.
    pub settings: Settings,
    /// Size of `pixels` (smaller than the film while `preview`).
    pub width: u32,
    /// Size of `pixels`.
    pub height: u32,
    /// Whether `pixels` is a reduced-resolution preview.
    pub preview: bool,
    /// The current mean, linear RGB.
    pub pixels: Arc<Vec<Vec3>>,
    /// Per pixel and channel, the variance of the mean (`s²/n` from the film's Σx and Σx²;
    /// infinite below 2 samples, empty for previews): the inspector's standard error.
    pub variance: Arc<Vec<Vec3>>,
    /// Per-pixel relative error (NaN where unknown; empty for previews).
    pub errors: Arc<Vec<f32>>,
    /// Per pixel, the mean contribution of each technique (camera, light samples, BSDF
    /// samples, control variate: [`lumis::integrator::Technique::ALL`]) for the technique map;
    /// empty for previews and GPU lanes (their kernels do not record it).
    pub techniques: Arc<Vec<[Vec3; 4]>>,
    /// Samples per pixel of `pixels` (a GPU lane shown live may be further: see `live`).
    pub spp: u32,
    /// A GPU lane's accumulation buffer, to show without a readback (only when the job had the
    /// window's device).
    pub live: Option<LiveImage>,
    /// Non-finite samples discarded.
    pub nonfinite: u64,
    /// Render time spent on this lane.
    pub render_seconds: f64,
    /// Samples (pixels × spp) per second of render time.
    pub samples_per_second: f64,
    /// Current error and where it comes from.
    pub error: Option<(f64, ErrorSource)>,
    /// Error against render time.
    pub curve: Vec<CurvePoint>,
    /// The spp limit is reached, or (equal-error pacing) the target error.
    pub done: bool,
    /// Equal-error pacing: the render time (s) and spp at which the lane's relMSE first reached
    /// the target.
    pub reached: Option<(f64, u32)>,
}

/// What the render thread has published.
#[derive(Clone, Default)]
pub struct Output {
    /// The job this belongs to (see [`Worker::submit`]).
    pub generation: u64,
    /// Bumped on every publication, so the UI can tell when to upload new textures.
    pub version: u64,
    /// The `desc_version` the scene was built from.
    pub desc_version: u64,
    /// The scene being rendered.
    pub scene: Option<Arc<Scene>>,
    /// Why the job could not start (shown in the window).
    pub error: Option<String>,
    /// One view per lane.
    pub lanes: Vec<LaneView>,
    /// Time from [`Worker::submit`] to the job's first image.
    pub first_image: Option<Duration>,
}

#[derive(Default)]
struct Control {
    pending: Option<(u64, Job, Instant)>,
    cancel_flags: Vec<Arc<AtomicBool>>,
    shutdown: bool,
}

struct Shared {
    control: Mutex<Control>,
    wake: Condvar,
    /// Set with every new job; previews poll it (the engines have their own flags).
    interrupt: AtomicBool,
    output: Mutex<Output>,
    repaint: Mutex<Option<egui::Context>>,
}

/// Locks, ignoring poisoning: a panicked render thread must not take the UI down with it.
fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

/// The UI's handle on the render thread.
pub struct Worker {
    shared: Arc<Shared>,
    thread: Option<JoinHandle<()>>,
    generation: u64,
}

impl Worker {
    /// Starts the render thread with `threads` rendering threads (0: all cores).
    pub fn new(threads: usize) -> Worker {
        let shared = Arc::new(Shared {
            control: Mutex::new(Control::default()),
            wake: Condvar::new(),
            interrupt: AtomicBool::new(false),
            output: Mutex::new(Output::default()),
            repaint: Mutex::new(None),
        });
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .thread_name(|i| format!("lumis-render-{i}"))
            .build()
            .expect("cannot start the render threads");
        let s = shared.clone();
        let thread = std::thread::Builder::new()
            .name("lumis-worker".into())
            .spawn(move || pool.install(|| run(&s)))
            .expect("cannot start the render thread");
        Worker {
            shared,
            thread: Some(thread),
            generation: 0,
        }
    }

    /// Asks for a repaint of `ctx` whenever something new is published.
    pub fn set_repaint(&self, ctx: &egui::Context) {
        let mut r = lock(&self.shared.repaint);
        if r.is_none() {
            *r = Some(ctx.clone());
        }
    }

    /// Replaces whatever is rendering by `job`, cancelling the running pass. Returns the job's
    /// generation number.
    pub fn submit(&mut self, job: Job) -> u64 {
        self.generation += 1;
        let mut c = lock(&self.shared.control);
        c.pending = Some((self.generation, job, Instant::now()));
        for f in &c.cancel_flags {
            f.store(true, Ordering::Relaxed);
        }
        self.shared.interrupt.store(true, Ordering::Relaxed);
        self.shared.wake.notify_all();
        self.generation
    }

    /// The generation of the last submitted job.
    pub fn generation(&self) -> u64 {
        self.generation
    }

    /// A copy of the latest output (cheap: images are shared).
    pub fn output(&self) -> Output {
        lock(&self.shared.output).clone()
    }

    /// The latest output's version, without copying it.
    pub fn version(&self) -> u64 {
        lock(&self.shared.output).version
    }
}

impl Drop for Worker {
    fn drop(&mut self) {
        {
            let mut c = lock(&self.shared.control);
            c.shutdown = true;
            for f in &c.cancel_flags {
                f.store(true, Ordering::Relaxed);
            }
            self.shared.interrupt.store(true, Ordering::Relaxed);
            self.shared.wake.notify_all();
        }
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

struct Lane {
    render: AnyProgressive,
    /// When the film was last read back (GPU lanes shown live read back only now and then).
    last_readback: Option<Instant>,
    /// The previews render outside the engine, so they need the settings too.
    settings: Settings,
    time: Duration,
    pass: u32,
    view: LaneView,
}

struct Running {
    generation: u64,
    submitted: Instant,
    desc: Arc<SceneDesc>,
    scene: Arc<Scene>,
    lanes: Vec<Lane>,
    previews: Vec<u32>,
    seed: u32,
    spp_limit: u32,
    pacing: Pacing,
    target_relmse: f64,
    reference: Option<Arc<Vec<Vec3>>>,
    /// GPU lanes are shown from their buffers (the job came with the window's device).
    live: bool,
}

impl Running {
    fn idle(&self) -> bool {
        self.previews.is_empty() && self.lanes.iter().all(|l| l.view.done)
    }
}

fn run(shared: &Shared) {
    let mut running: Option<Running> = None;
    // The GPU device outlives jobs: creating one costs tens of milliseconds.
    let mut gpu = None;
    loop {
        let job = {
            let mut c = lock(&shared.control);
            loop {
                if c.shutdown {
                    return;
                }
                if let Some(p) = c.pending.take() {
                    shared.interrupt.store(false, Ordering::Relaxed);
                    break Some(p);
                }
                if running.as_ref().is_some_and(|r| !r.idle()) {
                    break None;
                }
                c = shared.wake.wait(c).unwrap_or_else(|e| e.into_inner());
            }
        };
        if let Some((generation, job, submitted)) = job {
            running = start(shared, generation, job, submitted, &mut gpu);
        } else if let Some(r) = running.as_mut() {
            step(shared, r);
        }
    }
}

/// Builds the scene and the lanes; publishes the error instead when that fails.
fn start(
    shared: &Shared,
    generation: u64,
    job: Job,
    submitted: Instant,
    gpu: &mut Option<Arc<GpuContext>>,
) -> Option<Running> {
    let fail = |message: String| {
        let mut o = lock(&shared.output);
        *o = Output {
            generation,
            version: o.version + 1,
            desc_version: job.desc_version,
            error: Some(message),
            ..Output::default()
        };
        drop(o);
        request_repaint(shared);
        None
    };
    let scene = match &job.scene {
        Some(s) => s.clone(),
        None => match Scene::from_desc(&job.desc) {
            Ok(s) => Arc::new(s),
            Err(e) => return fail(e.to_string()),
        },
    };
    if let Some(g) = &job.gpu {
        *gpu = Some(g.clone());
    }
    let mut lanes = Vec::new();
    for spec in &job.lanes {
        let mut render = match AnyProgressive::with_device(
            spec.backend,
            scene.clone(),
            spec.settings,
            job.seed,
            gpu,
        ) {
            Ok(r) => r,
            Err(e) => return fail(e.to_string()),
        };
        // Always recorded on the CPU (a few adds per contribution), so that switching the
        // panes to the technique map is a display change, not a restart.
        render.enable_technique_map();
        lanes.push(Lane {
            render,
            last_readback: None,
            settings: spec.settings,
            time: Duration::ZERO,
            pass: 1,
            view: empty_view(spec),
        });
    }
    {
        // Registered under the lock so that a job submitted meanwhile cancels these lanes too.
        let mut c = lock(&shared.control);
        c.cancel_flags = lanes
            .iter()
            .filter_map(|l| l.render.cancel_flag())
            .collect();
        if c.pending.is_some() {
            for f in &c.cancel_flags {
                f.store(true, Ordering::Relaxed);
            }
        }
    }
    let mut o = lock(&shared.output);
    *o = Output {
        generation,
        version: o.version + 1,
        desc_version: job.desc_version,
        scene: Some(scene.clone()),
        error: None,
        lanes: lanes.iter().map(|l| l.view.clone()).collect(),
        first_image: None,
    };
    drop(o);
    Some(Running {
        generation,
        submitted,
        previews: preview_factors(scene.camera.width, scene.camera.height),
        desc: job.desc,
        scene,
        lanes,
        seed: job.seed,
        spp_limit: job.spp_limit,
        pacing: job.pacing,
        target_relmse: job.target_relmse,
        reference: job.reference,
        live: job.gpu.is_some(),
    })
}

fn empty_view(spec: &LaneSpec) -> LaneView {
    LaneView {
        settings: spec.settings,
        ..empty_lane_view(&spec.label)
    }
}

/// A lane with nothing rendered yet.
pub(crate) fn empty_lane_view(label: &str) -> LaneView {
    LaneView {
        label: label.into(),
        settings: Settings::default(),
        width: 0,
        height: 0,
        preview: true,
        pixels: Arc::new(Vec::new()),
        variance: Arc::new(Vec::new()),
        errors: Arc::new(Vec::new()),
        techniques: Arc::new(Vec::new()),
        spp: 0,
        live: None,
        nonfinite: 0,
        render_seconds: 0.0,
        samples_per_second: 0.0,
        error: None,
        curve: Vec::new(),
        done: false,
        reached: None,
    }
}

/// Renders one preview level for every lane, or one full pass of the lane whose turn it is.
fn step(shared: &Shared, r: &mut Running) {
    if !r.previews.is_empty() {
        let factor = r.previews.remove(0);
        for i in 0..r.lanes.len() {
            let settings = r.lanes[i].settings;
            let Some(img) = render_preview(
                &r.scene,
                &r.desc.camera,
                &settings,
                factor,
                r.seed,
                &shared.interrupt,
            ) else {
                return;
            };
            let v = &mut r.lanes[i].view;
            v.width = img.width;
            v.height = img.height;
            v.pixels = Arc::new(img.pixels);
            publish(shared, r, i);
        }
        return;
    }
    let Some(i) = next_lane(r) else { return };
    let max_spp = r.lanes.iter().map(|l| l.render.spp()).max().unwrap_or(0);
    let lane = &mut r.lanes[i];
    let spp = lane.render.spp();
    let mut n = lane.pass;
    // Equal samples: a lane that is behind catches up to the leader before running ahead.
    if r.pacing == Pacing::EqualSamples && spp < max_spp {
        n = n.min(max_spp - spp);
    }
    if r.spp_limit > 0 {
        n = n.min(r.spp_limit.saturating_sub(spp)).max(1);
    }
    let t = Instant::now();
    if !lane.render.render_pass(n) {
        return;
    }
    let dt = t.elapsed();
    lane.time += dt;
    let scale = TARGET_PASS.as_secs_f64() / dt.as_secs_f64().max(1e-6);
    lane.pass = ((n as f64 * scale).clamp(1.0, 1024.0) as u32).min(n.saturating_mul(4));
    let spp = lane.render.spp();
    let done = r.spp_limit > 0 && spp >= r.spp_limit;
    let v = &mut lane.view;
    v.done = done;
    v.render_seconds = lane.time.as_secs_f64();
    if r.live
        && let Some(acc) = lane.render.accumulation()
    {
        v.live = Some(LiveImage {
            buffer: acc.buffer.clone(),
            plane_size: acc.plane_size,
            width: acc.width,
            height: acc.height,
            spp: acc.spp,
        });
        v.samples_per_second =
            spp as f64 * acc.width as f64 * acc.height as f64 / v.render_seconds.max(1e-9);
    }
    // Equal-error pacing reads every pass back, so that a lane stops at the pass that reaches
    // the target, not up to half a second later.
    let due = v.live.is_none()
        || done
        || r.pacing == Pacing::EqualError
        || lane
            .last_readback
            .is_none_or(|t| t.elapsed() >= READBACK_EVERY);
    if due {
        lane.last_readback = Some(Instant::now());
        let reference = r.reference.as_deref().map(|v| v.as_slice());
        if let Err(e) = update_view(lane, reference) {
            publish_error(shared, r.generation, e);
            r.lanes.clear();
            return;
        }
        if r.pacing == Pacing::EqualError
            && let Some(at) = super::equal_error::reached(&lane.view, r.target_relmse)
        {
            lane.view.reached = Some(at);
            lane.view.done = true;
        }
    }
    publish(shared, r, i);
}

/// Which lane renders next: the one with the least render time (equal time or error) or the
/// fewest samples (equal samples); ties go to the leftmost.
fn next_lane(r: &Running) -> Option<usize> {
    let candidates = r.lanes.iter().enumerate().filter(|(_, l)| !l.view.done);
    if r.pacing != Pacing::EqualSamples {
        candidates.min_by_key(|(_, l)| l.time).map(|(i, _)| i)
    } else {
        candidates
            .min_by_key(|(_, l)| l.render.spp())
            .map(|(i, _)| i)
    }
}

/// Reads the film and updates the image, the error and the curve.
fn update_view(lane: &mut Lane, reference: Option<&[Vec3]>) -> Result<(), String> {
    let film = lane.render.film().map_err(|e| e.to_string())?;
    let film = film.as_ref();
    let mean = film.mean();
    let v = &mut lane.view;
    v.error = film_error(film, &mean, reference);
    v.errors = Arc::new(pixel_errors(film, &mean, reference));
    v.variance = Arc::new(variance_of_mean(film));
    v.techniques = Arc::new(lane.render.technique_means());
    v.width = film.width;
    v.height = film.height;
    v.preview = false;
    v.pixels = Arc::new(mean);
    v.spp = film.spp;
    v.nonfinite = film.nonfinite;
    v.render_seconds = lane.time.as_secs_f64();
    v.samples_per_second =
        film.spp as f64 * film.width as f64 * film.height as f64 / v.render_seconds.max(1e-9);
    if let Some((e, _)) = v.error {
        v.curve.push(CurvePoint {
            seconds: v.render_seconds,
            spp: film.spp,
            relmse: e,
        });
    }
    Ok(())
}

/// [`lumis::engine::Film::variance_of_mean`] in `f32`, one `Vec3` a pixel, computed in one pass
/// over the film (the inspector's standard errors; the film itself stays with the engine).
fn variance_of_mean(film: &lumis::engine::Film) -> Vec<Vec3> {
    let n = film.spp as f64;
    film.pixels
        .iter()
        .map(|p| {
            if n < 2.0 {
                return Vec3::INFINITY;
            }
            let v: [f32; 3] = std::array::from_fn(|c| {
                let mean = p.sum[c] / n;
                (((p.sum_sq[c] - n * mean * mean) / (n - 1.0)).max(0.0) / n) as f32
            });
            Vec3::from(v)
        })
        .collect()
}

fn publish_error(shared: &Shared, generation: u64, e: String) {
    let mut o = lock(&shared.output);
    if o.generation == generation {
        o.version += 1;
        o.error = Some(e);
    }
    drop(o);
    request_repaint(shared);
}

fn publish(shared: &Shared, r: &Running, lane: usize) {
    let mut o = lock(&shared.output);
    if o.generation != r.generation {
        return;
    }
    o.version += 1;
    o.lanes[lane] = r.lanes[lane].view.clone();
    if o.first_image.is_none() {
        o.first_image = Some(r.submitted.elapsed());
    }
    drop(o);
    request_repaint(shared);
}

fn request_repaint(shared: &Shared) {
    if let Some(ctx) = lock(&shared.repaint).as_ref() {
        ctx.request_repaint();
    }
}
