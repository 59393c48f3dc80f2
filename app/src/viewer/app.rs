//! The viewer's state and its frame loop: the scene being edited, the parameters, the display
//! state (zoom, wipe divider, inspected pixel), the render thread's latest output, and the
//! actions every control ends in (restart, load, save). The panels are drawn by `controls`,
//! `panes_controls`, `selection`, `image_area`, `inspector` and `plot`.

use super::ViewerOptions;
use super::edit::LightEdit;
use super::gpu_display::GpuDisplay;
use super::params::RenderParams;
use super::screenshot;
use super::textures::TextureCache;
use super::tonemap::Display;
use super::worker::{Job, Output, Worker};
use super::zoom::ImageView;
use crate::scene_file::load_scene_warning as load_scene;
use glam::Vec3;
use lumis::gpu::GpuContext;
use lumis::image_io::Image;
use lumis::scene::{CameraDesc, SceneDesc};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// The viewer. Fields are public so that the UI tests can check what each control changed.
pub struct ViewerApp {
    /// Estimator and comparison parameters.
    pub params: RenderParams,
    /// Exposure and what the panes show (no restart needed).
    pub display: Display,
    /// The zoom and pan all panes share (display only).
    pub view: ImageView,
    /// In the comparison, the one pane shown alone at full size (display only).
    pub solo: Option<usize>,
    /// The wipe divider, 0 (left edge) to 1 (right edge) of the pane (display only).
    pub wipe_position: f32,
    /// The pixel the inspector shows (the last hovered; `None`: the image centre).
    pub inspect: Option<(u32, u32)>,
    /// The inspected pixel stays put while the mouse moves (Ctrl+click, or `--inspect`).
    pub inspect_pinned: bool,
    /// Whether the pixel inspector panel is open.
    pub show_inspector: bool,
    /// The convergence plot shows efficiency, 1/(relMSE · t), instead of relMSE.
    pub plot_efficiency: bool,
    /// The scene file shown, if any loaded.
    pub scene_path: Option<PathBuf>,
    /// The scene as edited.
    pub desc: Option<SceneDesc>,
    /// Bumped on every edit of `desc`.
    pub desc_version: u64,
    /// The camera the scene file had, for "reset camera".
    pub home_camera: Option<CameraDesc>,
    /// Selected material (index into `desc.materials`).
    pub selected_material: Option<usize>,
    /// Normal maps switched off in the material controls, by material index, kept to switch
    /// them back on.
    pub normal_maps_off: std::collections::HashMap<usize, lumis::scene::desc::NormalMapDesc>,
    /// Alpha masks (opacities) switched off in the material controls, by material index, kept
    /// to switch them back on.
    pub masks_off: std::collections::HashMap<usize, lumis::scene::TextureDesc>,
    /// Selected light and its editor state.
    pub light: Option<LightEdit>,
    /// Selected delta light (index into `desc.lights`) for the delta-light controls.
    pub selected_delta_light: Option<usize>,
    /// Reference image (same size as the film) for the error, and its file.
    pub reference: Option<(PathBuf, Arc<Vec<Vec3>>)>,
    /// Last error to show in the window (load failures, save failures).
    pub error: Option<String>,
    /// Last status message (saved files, …).
    pub status: Option<String>,
    /// Number of accumulation restarts so far.
    pub restarts: u64,
    /// Time from the last restart to its first image.
    pub last_latency: Option<Duration>,
    /// Files written by the last screenshot.
    pub last_saved: Vec<PathBuf>,
    /// Where each pane's whole image was drawn in the last frame (points; clipped to its cell,
    /// larger than it when zoomed in).
    pub pane_rects: Vec<egui::Rect>,
    /// Each pane's cell in the last frame (points).
    pub pane_cells: Vec<egui::Rect>,
    /// Text of the scene path field.
    pub path_field: String,
    /// Text of the reference path field.
    pub reference_field: String,
    pub(crate) options: ViewerOptions,
    pub(crate) worker: Worker,
    pub(crate) output: Output,
    pub(crate) textures: TextureCache,
    /// Whether a real window (not a test harness) draws this, so window captures arrive.
    pub(crate) in_window: bool,
    auto_shot_done: bool,
    window_shot: Option<PathBuf>,
    /// Filled by eframe's screenshot callback (on its own schedule, hence the mutex).
    window_capture: Arc<Mutex<Option<Arc<egui::ColorImage>>>>,
    logged_generation: u64,
    /// The window's wgpu device as a GPU backend context: GPU lanes render on it.
    window_gpu: Option<Arc<GpuContext>>,
    /// Draws GPU lanes straight from their accumulation buffers.
    pub(crate) gpu_display: Option<GpuDisplay>,
}

impl ViewerApp {
    /// A viewer on `options.scene` (a load error is shown in the window).
    pub fn new(options: ViewerOptions) -> ViewerApp {
        let params = options.params.clone();
        let mut app = ViewerApp {
            params,
            display: Display {
                exposure: options.exposure,
                content: options.content,
            },
            view: ImageView::default(),
            solo: None,
            wipe_position: options.wipe_position,
            inspect: options.inspect,
            inspect_pinned: options.inspect.is_some(),
            show_inspector: true,
            plot_efficiency: false,
            scene_path: None,
            desc: None,
            desc_version: 0,
            home_camera: None,
            selected_material: None,
            normal_maps_off: Default::default(),
            masks_off: Default::default(),
            light: None,
            selected_delta_light: None,
            reference: None,
            error: None,
            status: None,
            restarts: 0,
            last_latency: None,
            last_saved: Vec::new(),
            pane_rects: Vec::new(),
            pane_cells: Vec::new(),
            path_field: options.scene.display().to_string(),
            reference_field: String::new(),
            worker: Worker::new(options.threads),
            output: Output::default(),
            textures: TextureCache::default(),
            in_window: false,
            auto_shot_done: false,
            window_shot: None,
            window_capture: Arc::default(),
            logged_generation: 0,
            window_gpu: None,
            gpu_display: None,
            options,
        };
        app.load_scene(&app.options.scene.clone());
        if let Some(r) = app.options.reference.clone() {
            app.reference_field = r.display().to_string();
            app.load_reference(&r);
        }
        app
    }

    /// Loads a scene file; on failure the error is shown and the current scene stays.
    pub fn load_scene(&mut self, path: &Path) {
        self.path_field = path.display().to_string();
        match load_scene(path) {
            Ok(mut desc) => {
                if let Err(e) = self.options.size.apply(&mut desc.camera) {
                    self.error = Some(e);
                    return;
                }
                self.home_camera = Some(desc.camera.clone());
                self.desc = Some(desc);
                self.scene_path = Some(path.to_path_buf());
                self.selected_material = None;
                self.normal_maps_off.clear();
                self.masks_off.clear();
                self.light = None;
                self.selected_delta_light = None;
                self.error = None;
                // Another image: fit it, and inspect its centre unless a pixel is pinned there.
                self.view.zoom = super::zoom::Zoom::Fit;
                if !self.inspect_pinned {
                    self.inspect = None;
                }
                // A reference of another scene no longer applies.
                self.reference = None;
                self.scene_changed();
            }
            Err(e) => self.error = Some(one_line(&e.to_string())),
        }
    }

    /// Loads a reference image (EXR or PFM) of the film's size.
    pub fn load_reference(&mut self, path: &Path) {
        let size = self
            .desc
            .as_ref()
            .map(|d| (d.camera.width, d.camera.height));
        match Image::read(path) {
            Ok(img) if Some((img.width, img.height)) == size => {
                self.reference = Some((path.to_path_buf(), Arc::new(img.data)));
                self.error = None;
                self.restart();
            }
            Ok(img) => {
                self.error = Some(format!(
                    "{}: the reference is {}x{} but the film is {}",
                    path.display(),
                    img.width,
                    img.height,
                    size.map_or("not loaded".into(), |(w, h)| format!("{w}x{h}"))
                ))
            }
            Err(e) => self.error = Some(one_line(&e.to_string())),
        }
    }

    /// Drops the reference; errors are estimated from the half images again.
    pub fn clear_reference(&mut self) {
        self.reference = None;
        self.restart();
    }

    /// Call after every edit of `desc`: the scene is rebuilt and accumulation restarts.
    pub fn scene_changed(&mut self) {
        self.desc_version += 1;
        self.restart();
    }

    /// Restarts accumulation with the current scene and parameters.
    pub fn restart(&mut self) {
        let Some(desc) = &self.desc else { return };
        // Settings-only changes reuse the scene the render thread already built.
        let scene = (self.output.desc_version == self.desc_version)
            .then(|| self.output.scene.clone())
            .flatten();
        let job = Job {
            desc: Arc::new(desc.clone()),
            desc_version: self.desc_version,
            scene,
            lanes: self.params.lanes(),
            seed: self.options.seed,
            spp_limit: self.params.spp_limit,
            pacing: self.params.pacing,
            target_relmse: self.params.target_relmse,
            gpu: self.window_gpu.clone(),
            reference: self.reference.as_ref().map(|(_, r)| r.clone()),
        };
        self.worker.submit(job);
        self.restarts += 1;
        self.auto_shot_done = false;
    }

    /// Shares the window's wgpu device (eframe's) with the GPU backend, so that GPU lanes are
    /// drawn from their accumulation buffers with no readback per frame. Restarts, so a GPU
    /// render already running on a device of its own moves onto the window's.
    pub fn attach_window_device(&mut self, state: &eframe::egui_wgpu::RenderState) {
        super::surface_race::survive_configure_races(&state.device);
        self.window_gpu = Some(GpuContext::from_device(
            state.device.clone(),
            state.queue.clone(),
            state.adapter.get_info(),
        ));
        self.gpu_display = Some(GpuDisplay::new(state));
        self.restart();
    }

    /// The render thread's latest output, as of the start of this frame.
    pub fn output(&self) -> &Output {
        &self.output
    }

    /// Waits (up to `timeout`) until the render thread has published output for the latest
    /// restart that satisfies `done`. For tests and headless use; the UI never waits.
    pub fn wait_for(&mut self, timeout: Duration, done: impl Fn(&Output) -> bool) -> bool {
        let end = std::time::Instant::now() + timeout;
        loop {
            self.output = self.worker.output();
            if self.output.generation == self.worker.generation() && done(&self.output) {
                return true;
            }
            if std::time::Instant::now() > end {
                return false;
            }
            std::thread::sleep(Duration::from_millis(5));
        }
    }

    /// Saves PNG/EXR per pane and the error CSV (and, in a window, a window capture).
    pub fn save_screenshot(&mut self, ctx: &egui::Context) {
        let dir = self.options.screenshot_dir.clone();
        let lanes = match self.current_lanes() {
            Ok(l) => l,
            Err(e) => {
                self.error = Some(e);
                return;
            }
        };
        match screenshot::save(&dir, &lanes, self.display) {
            Ok((stem, files)) => {
                self.status = Some(format!(
                    "saved {}",
                    files
                        .iter()
                        .map(|f| f.display().to_string())
                        .collect::<Vec<_>>()
                        .join(", ")
                ));
                self.last_saved = files;
                if self.in_window {
                    self.window_shot = Some(stem);
                    let slot = self.window_capture.clone();
                    let repaint = ctx.clone();
                    ctx.request_screenshot(move |image| {
                        *slot.lock().unwrap_or_else(|e| e.into_inner()) = Some(image);
                        repaint.request_repaint();
                    });
                } else if self.options.exit_after_screenshot {
                    ctx.send_viewport_cmd(egui::ViewportCommand::Close);
                }
            }
            Err(e) => self.error = Some(e),
        }
    }

    /// Saves the camera's view into the scene file.
    pub fn save_camera(&mut self) {
        let (Some(path), Some(desc)) = (&self.scene_path, &self.desc) else {
            return;
        };
        match super::camera::save_camera(path, &desc.camera) {
            Ok(()) => self.status = Some(format!("camera saved to {}", path.display())),
            Err(e) => self.error = Some(e),
        }
    }

    /// Puts the camera back where the scene file had it.
    pub fn reset_camera(&mut self) {
        if let (Some(desc), Some(home)) = (&mut self.desc, &self.home_camera) {
            desc.camera = home.clone();
            self.scene_changed();
        }
    }

    /// Draws one frame of the whole viewer into `ui`.
    pub fn show(&mut self, ui: &mut egui::Ui) {
        let ctx = ui.ctx().clone();
        self.worker.set_repaint(&ctx);
        self.output = self.worker.output();
        self.log_latency();
        self.handle_input(&ctx);
        self.top_bar(ui);
        self.controls_panel(ui);
        self.stats_panel(ui);
        self.inspector_panel(ui);
        self.central(ui);
        self.auto_screenshot(&ctx);
    }

    fn log_latency(&mut self) {
        let o = &self.output;
        if o.generation == self.worker.generation()
            && o.generation != self.logged_generation
            && let Some(t) = o.first_image
        {
            self.logged_generation = o.generation;
            self.last_latency = Some(t);
            if self.options.log_latency {
                eprintln!(
                    "lumis view: first image {:.1} ms after restart",
                    t.as_secs_f64() * 1e3
                );
            }
        }
    }

    fn handle_input(&mut self, ctx: &egui::Context) {
        use egui::{Key, KeyboardShortcut, Modifiers};
        let save = ctx.input_mut(|i| {
            i.consume_shortcut(&KeyboardShortcut::new(Modifiers::COMMAND, Key::S))
                || i.consume_key(Modifiers::NONE, Key::F12)
        });
        if save {
            self.save_screenshot(ctx);
        }
        self.view_keys(ctx);
        let capture = self
            .window_capture
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .take();
        if let Some(image) = capture
            && let Some(stem) = self.window_shot.take()
        {
            match screenshot::save_window(&stem, &image) {
                Ok(p) => self.last_saved.push(p),
                Err(e) => self.error = Some(e),
            }
            if self.options.exit_after_screenshot {
                ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            }
        }
        let dropped: Vec<PathBuf> = ctx.input(|i| {
            i.raw
                .dropped_files
                .iter()
                .map(|f| f.path().to_path_buf())
                .collect()
        });
        for path in dropped {
            let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
            if matches!(ext.to_ascii_lowercase().as_str(), "exr" | "pfm") {
                self.reference_field = path.display().to_string();
                self.load_reference(&path);
            } else {
                self.load_scene(&path);
            }
        }
    }

    /// `--screenshot-after N`: once every pane has N samples, save as the shortcut would.
    fn auto_screenshot(&mut self, ctx: &egui::Context) {
        let Some(n) = self.options.screenshot_after else {
            return;
        };
        let o = &self.output;
        let ready = !self.auto_shot_done
            && o.generation == self.worker.generation()
            && !o.lanes.is_empty()
            && o.lanes.iter().all(|l| !l.preview && l.spp >= n);
        if ready {
            self.auto_shot_done = true;
            self.save_screenshot(ctx);
        }
    }

    /// The lanes with what is on screen now: a GPU lane drawn from its buffer is read back
    /// here, so a screenshot holds the samples shown, not the last periodic readback's.
    fn current_lanes(&self) -> Result<Vec<super::worker::LaneView>, String> {
        let mut lanes = self.output.lanes.clone();
        for l in &mut lanes {
            let (Some(live), Some(ctx)) = (&l.live, &self.window_gpu) else {
                continue;
            };
            if live.spp == l.spp {
                continue;
            }
            let bytes = ctx
                .read_buffer(&live.buffer, live.plane_size)
                .map_err(|e| e.to_string())?;
            let mean: &[[f32; 4]] = bytemuck::cast_slice(&bytes);
            l.pixels = Arc::new(mean.iter().map(|m| Vec3::new(m[0], m[1], m[2])).collect());
            l.spp = live.spp;
            l.width = live.width;
            l.height = live.height;
        }
        Ok(lanes)
    }
}

/// The first line of a message, for one-line display.
pub(crate) fn one_line(s: &str) -> String {
    s.lines().map(str::trim).collect::<Vec<_>>().join(" ")
}
