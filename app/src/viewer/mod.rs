//! `lumis view`: the interactive viewer. The image converges live while every control restarts
//! accumulation at once; strategies can be compared side by side or in a wipe, pixel by pixel,
//! with a live convergence plot and predictions of the time to a target error.
//!
//! * [`app`]: state, actions and the frame loop; [`params`], the settings the panels edit;
//!   [`controls`], [`menus`], [`panes_controls`], [`selection`], [`delta_light`], [`environment`],
//!   [`plot`] and [`inspector`] draw its panels.
//! * [`image_area`]: the panes, in the [`layout`] grid that shows them largest, at the shared
//!   [`zoom`]; the [`wipe`]; mouse [`gesture`]s and [`keys`]; the false-colour [`legend`];
//!   [`textures`], uploaded only when they change.
//! * [`worker`]: the render thread (never blocks the UI) with reduced-resolution [`preview`]s;
//!   it renders on either engine through [`lumis::engine::AnyProgressive`].
//! * [`gpu_display`]: the GPU lane's tonemapping on the window's device, without readback;
//!   [`surface_race`]: the one wgpu surface error that is survived.
//! * [`edit`], [`light_shape`], [`pick`], [`camera`]: edits of the scene description.
//! * [`convergence`], [`prediction`], [`equal_error`], [`tonemap`], [`screenshot`]: error
//!   estimates and their 1/t fits, equal-error stops, display, saved files.
//! * [`headless`]: the render without a display.

pub mod app;
pub mod camera;
pub mod controls;
pub mod convergence;
pub mod delta_light;
pub mod edit;
pub mod environment;
pub mod equal_error;
pub mod gesture;
pub mod gpu_display;
pub mod headless;
pub mod image_area;
pub mod inspector;
pub mod keys;
pub mod layout;
pub mod legend;
pub mod lens;
pub mod light_shape;
pub mod menus;
pub mod panes_controls;
pub mod params;
pub mod pick;
pub mod plot;
pub mod prediction;
pub mod preview;
pub mod screenshot;
pub mod selection;
pub mod surface_race;
pub mod textures;
pub mod tonemap;
pub mod wipe;
pub mod worker;
pub mod zoom;

use crate::image_size::ImageSize;
pub use app::ViewerApp;
use params::RenderParams;
use std::path::PathBuf;

/// How the viewer starts.
#[derive(Clone, Debug)]
pub struct ViewerOptions {
    /// Scene file to open.
    pub scene: PathBuf,
    /// Reference image (EXR/PFM) to measure the error against.
    pub reference: Option<PathBuf>,
    /// Initial estimator and comparison parameters.
    pub params: RenderParams,
    /// Random seed of every lane.
    pub seed: u32,
    /// Rendering threads (0: all cores).
    pub threads: usize,
    /// The image size (`--width`, `--height`, `--resolution-scale`; the scene's by default).
    pub size: ImageSize,
    /// Initial exposure in stops.
    pub exposure: f32,
    /// Where screenshots go.
    pub screenshot_dir: PathBuf,
    /// Save a screenshot as soon as every pane has this many samples per pixel.
    pub screenshot_after: Option<u32>,
    /// Close the window once that screenshot is saved.
    pub exit_after_screenshot: bool,
    /// Print the time from each restart to its first image on stderr.
    pub log_latency: bool,
    /// Without a display: the PNG to write (default: the scene's name in the current folder).
    pub headless_output: Option<PathBuf>,
    /// Without a display: samples per pixel (when no spp limit is set).
    pub headless_spp: u32,
    /// What the panes show at first.
    pub content: tonemap::Content,
    /// The pixel the inspector shows at first (default: the image centre).
    pub inspect: Option<(u32, u32)>,
    /// The window's inner size in points.
    pub window_size: [f32; 2],
    /// Where the wipe's divider starts, 0 (left) to 1 (right).
    pub wipe_position: f32,
}

impl Default for ViewerOptions {
    fn default() -> ViewerOptions {
        ViewerOptions {
            scene: PathBuf::from("assets/seed_cornell.json"),
            reference: None,
            params: RenderParams::default(),
            seed: 0,
            threads: 0,
            size: ImageSize::default(),
            exposure: 0.0,
            screenshot_dir: PathBuf::from("."),
            screenshot_after: None,
            exit_after_screenshot: false,
            log_latency: false,
            headless_output: None,
            headless_spp: 64,
            content: tonemap::Content::Image,
            inspect: None,
            window_size: [1400.0, 900.0],
            wipe_position: 0.5,
        }
    }
}

/// Whether a window could open at all: X11 or Wayland is named in the environment.
pub fn has_display() -> bool {
    ["DISPLAY", "WAYLAND_DISPLAY"]
        .iter()
        .any(|v| std::env::var_os(v).is_some_and(|s| !s.is_empty()))
}

/// Opens the viewer window; without a display, or when the window cannot open, renders headless
/// instead (with a one-line notice on stderr saying why). Never a panic.
pub fn run(options: ViewerOptions) -> anyhow::Result<()> {
    if !has_display() {
        return headless::render(
            &options,
            "no display (DISPLAY and WAYLAND_DISPLAY are unset)",
        );
    }
    let native = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title("lumis")
            .with_inner_size(options.window_size)
            .with_drag_and_drop(true),
        wgpu_options: window_wgpu_options(),
        ..Default::default()
    };
    // Some platform failures surface as panics inside winit or the graphics setup; the default
    // hook would print a multi-line report before we could turn it into one line. It is back
    // in place once the window is open, so that later panics report normally.
    let options_for_headless = options.clone();
    let opened = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let flag = opened.clone();
    std::panic::set_hook(Box::new(|_| {}));
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(move || {
        eframe::run_native(
            "lumis",
            native,
            Box::new(move |_cc| {
                drop(std::panic::take_hook());
                flag.store(true, std::sync::atomic::Ordering::Relaxed);
                let mut app = ViewerApp::new(options);
                app.in_window = true;
                Ok(Box::new(Window(app, false)))
            }),
        )
    }));
    drop(std::panic::take_hook());
    let opened = opened.load(std::sync::atomic::Ordering::Relaxed);
    let message = match result {
        Ok(Ok(())) => return Ok(()),
        Ok(Err(e)) => app::one_line(&e.to_string()),
        Err(p) => app::one_line(
            p.downcast_ref::<String>()
                .map(String::as_str)
                .or_else(|| p.downcast_ref::<&str>().copied())
                .unwrap_or("unknown error"),
        ),
    };
    if opened {
        anyhow::bail!("the viewer failed: {message}");
    }
    // A display is named but unusable (no X server behind DISPLAY, no GL or Vulkan driver):
    // do what the no-display case does rather than fail.
    headless::render(
        &options_for_headless,
        &format!("cannot open a window ({message})"),
    )
}

/// eframe's wgpu setup, asking for the adapter's own limits: the defaults allow 8 storage
/// buffers and (on the GL fallback) no compute at all, too little for the GPU backend, which
/// renders on the window's device.
fn window_wgpu_options() -> eframe::egui_wgpu::WgpuConfiguration {
    use eframe::egui_wgpu::{WgpuConfiguration, WgpuSetup, WgpuSetupCreateNew};
    WgpuConfiguration {
        wgpu_setup: WgpuSetup::CreateNew(WgpuSetupCreateNew {
            device_descriptor: std::sync::Arc::new(|adapter: &eframe::wgpu::Adapter| {
                eframe::wgpu::DeviceDescriptor {
                    label: Some("lumis viewer"),
                    required_limits: adapter.limits(),
                    ..Default::default()
                }
            }),
            ..WgpuSetupCreateNew::without_display_handle()
        }),
        ..Default::default()
    }
}

/// The viewer as an eframe application.
/// The second field: whether the window's wgpu device has been handed to the viewer.
struct Window(ViewerApp, bool);

impl eframe::App for Window {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        if !self.1 {
            self.1 = true;
            if let Some(state) = frame.wgpu_render_state() {
                self.0.attach_window_device(state);
            }
        }
        self.0.show(ui);
    }
}
