//! The GPU backend in the viewer draws its image straight from the accumulation buffer: the
//! viewer gets a real wgpu render state (as eframe gives it in a window; here egui_kittest's
//! offscreen renderer on the same adapter), renders on that device, and the frame egui paints
//! must show the accumulated mean through the display shader: the pane's pixels are compared
//! with the CPU tonemapping of the same samples, read back once the spp limit stops the render.
//!
//! Runs on lavapipe without a GPU; `LUMIS_SKIP_GPU_TESTS=1` skips it where no adapter exists.

use eframe::egui_wgpu;
use eframe::wgpu;
use egui_kittest::Harness;
use lumis::engine::Backend;
use lumis_app::viewer::tonemap::srgb8;
use lumis_app::viewer::{ViewerApp, ViewerOptions};
use std::sync::Arc;
use std::time::Duration;

const SPP: u32 = 8;

/// egui_kittest's offscreen render state, with the adapter's own limits (the path tracer binds
/// more storage buffers than wgpu's defaults allow), as the viewer asks of eframe.
fn render_state() -> egui_wgpu::RenderState {
    let egui_wgpu::WgpuSetup::CreateNew(mut setup) = egui_kittest::wgpu::default_wgpu_setup()
    else {
        unreachable!("kittest creates its own device")
    };
    setup.device_descriptor = Arc::new(|adapter: &wgpu::Adapter| wgpu::DeviceDescriptor {
        label: Some("lumis test"),
        required_limits: adapter.limits(),
        ..Default::default()
    });
    egui_kittest::wgpu::create_render_state(
        egui_wgpu::WgpuSetup::CreateNew(setup),
        egui_wgpu::RendererOptions::PREDICTABLE,
    )
}

/// Mean sRGB byte per channel over the screen pixels of `region` (inside the pane at `pane`,
/// pixels): as shown in `img`, and as expected, by sampling the CPU-tonemapped image at each
/// screen pixel's centre nearest-neighbour (what the pane's sampler does to a magnified texture).
fn means(
    img: &image::RgbaImage,
    pane: egui::Rect,
    region: egui::Rect,
    tonemapped: &[[u8; 3]],
    size: u32,
) -> ([f64; 3], [f64; 3]) {
    let (mut shown, mut want, mut n) = ([0.0; 3], [0.0; 3], 0.0);
    for y in region.min.y.ceil() as u32..region.max.y.floor() as u32 {
        for x in region.min.x.ceil() as u32..region.max.x.floor() as u32 {
            let p = img.get_pixel(x, y).0;
            let u = (x as f64 + 0.5 - pane.min.x as f64) / pane.width() as f64 * size as f64;
            let v = (y as f64 + 0.5 - pane.min.y as f64) / pane.height() as f64 * size as f64;
            let (tx, ty) = (
                (u.floor() as i64).clamp(0, size as i64 - 1),
                (v.floor() as i64).clamp(0, size as i64 - 1),
            );
            let t = tonemapped[(ty * size as i64 + tx) as usize];
            for k in 0..3 {
                shown[k] += p[k] as f64;
                want[k] += t[k] as f64;
            }
            n += 1.0;
        }
    }
    (shown.map(|v| v / n), want.map(|v| v / n))
}

#[test]
fn gpu_lanes_are_drawn_from_the_accumulation_buffer() {
    if std::env::var_os("LUMIS_SKIP_GPU_TESTS").is_some() {
        eprintln!("LUMIS_SKIP_GPU_TESTS is set: skipping a GPU test");
        return;
    }
    let size = 64;
    let state = render_state();
    let mut app = ViewerApp::new(ViewerOptions {
        scene: concat!(env!("CARGO_MANIFEST_DIR"), "/../assets/seed_cornell.json").into(),
        size: lumis_app::image_size::ImageSize {
            width: Some(size),
            height: Some(size),
            resolution_scale: None,
        },
        ..ViewerOptions::default()
    });
    app.params.backend = Backend::Gpu;
    app.params.spp_limit = SPP;
    app.attach_window_device(&state);
    let mut h = Harness::builder()
        .with_size([1000.0, 900.0])
        .renderer(egui_kittest::wgpu::WgpuTestRenderer::from_render_state(
            state,
        ))
        .build_ui_state(|ui, app: &mut ViewerApp| app.show(ui), app);
    assert!(
        h.state_mut()
            .wait_for(Duration::from_secs(120), |o| o.error.is_some()
                || o.lanes.iter().all(|l| l.done)),
        "the GPU render did not reach {SPP} spp"
    );
    assert_eq!(h.state().output().error, None);
    h.run_steps(2);
    let lane = h.state().output().lanes[0].clone();
    let live = lane
        .live
        .clone()
        .expect("a GPU lane on the window's device is shown live");
    // At the limit the last pass was read back, so `pixels` holds exactly the buffer's samples.
    assert_eq!((live.spp, lane.spp), (SPP, SPP));
    let rect = h.state().pane_rects[0];
    assert!(rect.width() > 2.0 * size as f32, "pane {rect:?}");

    for exposure in [0.0f32, 1.5] {
        h.state_mut().display.exposure = exposure;
        h.run_steps(2);
        let img = h.render().expect("render the frame");
        let ppp = img.width() as f32 / 1000.0;
        let px = egui::Rect::from_min_max(
            (rect.min.to_vec2() * ppp).to_pos2(),
            (rect.max.to_vec2() * ppp).to_pos2(),
        );
        // The whole pane and its quadrants: a black, stale, mis-exposed or transposed image
        // fails by tens of units; the GPU's filter and rounding stay within one.
        let gain = 2f32.powf(exposure);
        let tonemapped: Vec<[u8; 3]> = lane.pixels.iter().map(|&c| srgb8(c, gain)).collect();
        let mut regions = vec![px];
        for (i, j) in [(0.0, 0.0), (0.5, 0.0), (0.0, 0.5), (0.5, 0.5)] {
            regions.push(egui::Rect::from_min_size(
                px.lerp_inside(egui::vec2(i, j)),
                px.size() * 0.5,
            ));
        }
        for r in regions {
            let (shown, want) = means(&img, px, r, &tonemapped, size);
            for c in 0..3 {
                assert!(
                    (shown[c] - want[c]).abs() < 1.0,
                    "exposure {exposure}, region {r:?}, channel {c}: shown {shown:?}, expected {want:?}"
                );
            }
        }
    }
}
