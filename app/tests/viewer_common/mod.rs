//! Helpers shared by the viewer's UI tests (`viewer_ui.rs`, `viewer_instrument.rs`): a harness
//! on a scene, waiting for the render thread, and driving sliders and menus through AccessKit.
#![allow(dead_code)]

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use lumis_app::viewer::{ViewerApp, ViewerOptions};
use std::path::PathBuf;
use std::time::Duration;

pub const WAIT: Duration = Duration::from_secs(60);

pub fn asset(name: &str) -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../assets")).join(name)
}

pub fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("lumis-viewer-ui-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The viewer on `scene` at `size`×`size` pixels, in a harness big enough for every panel.
pub fn harness(scene: &str, size: u32, dir: PathBuf) -> Harness<'static, ViewerApp> {
    harness_at(asset(scene), size, dir)
}

/// [`harness`] on a scene file anywhere.
pub fn harness_at(scene: PathBuf, size: u32, dir: PathBuf) -> Harness<'static, ViewerApp> {
    let app = ViewerApp::new(ViewerOptions {
        scene,
        size: lumis_app::image_size::ImageSize {
            width: Some(size),
            height: Some(size),
            resolution_scale: None,
        },
        screenshot_dir: dir,
        ..ViewerOptions::default()
    });
    let mut h = Harness::builder()
        .with_size([1200.0, 1400.0])
        .build_ui_state(|ui, app: &mut ViewerApp| app.show(ui), app);
    settle(&mut h);
    h
}

/// Renders until every lane has `spp` samples, then checks that moving a control with `act`
/// restarts: a new generation whose curves start from scratch. Returns the app for checks.
pub fn assert_restarts(
    h: &mut Harness<'static, ViewerApp>,
    what: &str,
    act: impl FnOnce(&mut Harness<'static, ViewerApp>),
) {
    assert!(
        h.state_mut()
            .wait_for(WAIT, |o| o.lanes.iter().all(|l| l.spp >= 32)),
        "{what}: no accumulation before the change"
    );
    let restarts = h.state().restarts;
    act(h);
    h.run_steps(2);
    assert!(h.state().restarts > restarts, "{what}: no restart");
    assert!(
        h.state_mut().wait_for(WAIT, |o| !o.lanes.is_empty()
            && o.lanes.iter().all(|l| !l.curve.is_empty())),
        "{what}: no image after the restart"
    );
    for l in &h.state().output().lanes {
        // Pass sizes at most quadruple, so a fresh film's first error point is at ≤ 5 spp; a
        // film that kept accumulating would start at ≥ 32.
        assert!(
            l.curve[0].spp <= 5,
            "{what}: accumulation did not restart ({:?})",
            l.curve[0]
        );
    }
}

pub fn set_slider(h: &mut Harness<'static, ViewerApp>, label: &str, v: f64) {
    h.get_by_role_and_label(Role::Slider, label)
        .set_value_accesskit(v);
}

pub fn pick_combo(h: &mut Harness<'static, ViewerApp>, combo: &str, option: &str) {
    h.get_by_label(combo).click();
    h.run_steps(2);
    h.get_by_label(option).click();
}

/// Waits until the render thread has built and rendered the current description.
pub fn wait_for_current_scene(h: &mut Harness<'static, ViewerApp>, what: &str) {
    let version = h.state().desc_version;
    assert!(
        h.state_mut().wait_for(WAIT, |o| o.desc_version == version
            && o.scene.is_some()
            && !o.lanes.is_empty()
            && o.lanes.iter().all(|l| !l.preview && l.spp >= 8)),
        "{what}: the render thread did not render the current scene"
    );
    h.run_steps(1);
}

/// A harness of `size` points on a viewer started with `options`.
pub fn harness_with(options: ViewerOptions, size: [f32; 2]) -> Harness<'static, ViewerApp> {
    let mut h = Harness::builder().with_size(size).build_ui_state(
        |ui, app: &mut ViewerApp| app.show(ui),
        ViewerApp::new(options),
    );
    settle(&mut h);
    h
}

/// Runs the first frames, then waits until the render thread has published its lanes and draws
/// one more frame: the panes (and `pane_rects`) exist only once the lanes do, which on a slow
/// machine is later than the first two frames.
pub fn settle(h: &mut Harness<'static, ViewerApp>) {
    h.run_steps(2);
    if h.state().desc.is_some() {
        h.state_mut()
            .wait_for(WAIT, |o| !o.lanes.is_empty() || o.error.is_some());
        h.run_steps(1);
    }
}

/// Presses the mouse `button` at `from`, moves to `to` in `steps` and releases it.
pub fn drag(
    h: &mut Harness<'static, ViewerApp>,
    button: egui::PointerButton,
    from: egui::Pos2,
    to: egui::Pos2,
    steps: usize,
) {
    h.event(egui::Event::PointerMoved(from));
    h.run_steps(1);
    let press = |h: &mut Harness<'static, ViewerApp>, pos, pressed| {
        h.event(egui::Event::PointerButton {
            pos,
            button,
            pressed,
            modifiers: egui::Modifiers::NONE,
        });
        h.run_steps(1);
    };
    press(h, from, true);
    for k in 1..=steps {
        h.event(egui::Event::PointerMoved(
            from + (to - from) * (k as f32 / steps as f32),
        ));
        h.run_steps(1);
    }
    press(h, to, false);
}
