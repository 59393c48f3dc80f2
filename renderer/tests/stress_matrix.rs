//! Numerical stress matrix (issue 7): small renders of generated scenes at the edges of what the
//! renderer must handle, with every strategy and both light-sampling methods, seeded.
//!
//! Axes: roughness α ∈ {0, 1e-4, 1e-3, 0.01, 0.5, 1} on conductors (complex Fresnel and tint) and
//! plastic; camera and lights 0.01° above a surface; lights touching or cutting through surfaces;
//! tiny lights (1e-8 of the scene's area) and a light far larger than the scene; emission 1e-6 and
//! 1e6; scene scales 1e-4 to 1e6; coplanar overlapping quads; boxes 1e-6 thick; shading points on
//! a light; every light shape (quad, triangle, concave polygon, disk, sphere) in the geometric
//! cases.
//!
//! Every render must have zero non-finite pixels and zero discarded non-finite samples (any
//! discard is a bug to find, not noise). Where a closed form or an exact relation exists it is
//! checked too:
//! - **emission scaling** is exact: with throughput-based Russian roulette and power-based light
//!   selection, the same seed draws the same paths, so the image at emission `k·L` is `k` times
//!   the image at `L` up to f32 rounding (relative 1e-4);
//! - **scale invariance**: the closed emissive box of albedo 0.5 renders `L/(1−a) = 2L` at every
//!   scale from 1e-4 to 1e6 (a z-test on the image mean, Šidák-corrected over every comparison in
//!   this file, family-wise α = 0.01), which catches light leaking through corners at any scale.

mod common;

use common::{METHODS, STRATEGIES, build, render};
use lumis::engine::Progressive;
use lumis::integrator::Settings;
use lumis::metrics::{normal_two_sided_critical, sidak};
use lumis::scene::Scene;
use std::sync::Arc;

/// Image size (square) and samples per pixel of a stress render.
const SIZE: u32 = 24;
const SPP: u32 = 16;

/// Settings for one cell of the matrix.
fn all_settings() -> Vec<Settings> {
    STRATEGIES
        .into_iter()
        .flat_map(|strategy| {
            METHODS.into_iter().map(move |light_sampling| Settings {
                strategy,
                light_sampling,
                ..Settings::default()
            })
        })
        .collect()
}

/// A room at scale `s`: a floor (material `floor`), a back wall, a sphere and a box resting on the
/// floor (materials `ball` and `block`), `lights` (JSON shape objects, already scaled), seen by
/// `camera` (a JSON camera object). Materials come from `materials` (a JSON object body).
fn room(s: f64, materials: &str, lights: &[String], camera: &str, extra: &[String]) -> String {
    let v = |x: f64, y: f64, z: f64| format!("[{}, {}, {}]", x * s, y * s, z * s);
    let mut shapes = vec![
        format!(
            r#"{{"type": "quad", "corner": {}, "edge_u": {}, "edge_v": {}, "material": "floor"}}"#,
            v(-1.0, 0.0, -1.0),
            v(0.0, 0.0, 2.0),
            v(2.0, 0.0, 0.0)
        ),
        format!(
            r#"{{"type": "quad", "corner": {}, "edge_u": {}, "edge_v": {}, "material": "floor"}}"#,
            v(-1.0, 0.0, 1.0),
            v(0.0, 2.0, 0.0),
            v(2.0, 0.0, 0.0)
        ),
        format!(
            r#"{{"type": "sphere", "center": {}, "radius": {}, "material": "ball"}}"#,
            v(0.4, 0.3, 0.2),
            0.3 * s
        ),
        format!(
            r#"{{"type": "box", "min": {}, "max": {}, "rotate_y_deg": 20, "material": "block"}}"#,
            v(-0.7, 0.0, -0.2),
            v(-0.2, 0.5, 0.3)
        ),
    ];
    shapes.extend(lights.iter().cloned());
    shapes.extend(extra.iter().cloned());
    format!(
        r#"{{"camera": {camera}, "materials": {{{materials}}}, "shapes": [{}]}}"#,
        shapes.join(", ")
    )
}

/// The default camera of a room at scale `s`.
fn camera(s: f64) -> String {
    format!(
        r#"{{"from": [0, {}, {}], "to": [0, {}, 0], "up": [0, 1, 0], "vfov_deg": 50, "width": {SIZE}, "height": {SIZE}}}"#,
        1.0 * s,
        -3.0 * s,
        0.4 * s
    )
}

/// Diffuse materials for every slot, plus an `emitter` material for lights.
const DIFFUSE: &str = r#""floor": {"type": "diffuse", "albedo": [0.7, 0.7, 0.7]},
    "ball": {"type": "diffuse", "albedo": [0.6, 0.3, 0.2]},
    "block": {"type": "diffuse", "albedo": [0.2, 0.5, 0.7]},
    "emitter": {"type": "diffuse", "albedo": [0.8, 0.8, 0.8]}"#;

/// The light shapes, centred at `c` (scale `s` applied by the caller) with size `r`, facing along
/// `n` (unit), emitting `le`: quad, triangle, concave star polygon, disk, sphere.
fn light_shapes(c: [f64; 3], n: [f64; 3], r: f64, le: f64) -> Vec<(String, String)> {
    // An orthonormal frame (u, w) of the plane with normal n, so that u × w = n.
    let helper = if n[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let norm = |a: [f64; 3]| {
        let l = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
        [a[0] / l, a[1] / l, a[2] / l]
    };
    let u = norm(cross(helper, n));
    let w = cross(n, u);
    let at = |x: f64, y: f64| {
        format!(
            "[{}, {}, {}]",
            c[0] + r * (x * u[0] + y * w[0]),
            c[1] + r * (x * u[1] + y * w[1]),
            c[2] + r * (x * u[2] + y * w[2])
        )
    };
    let vec = |a: [f64; 3], k: f64| format!("[{}, {}, {}]", a[0] * k, a[1] * k, a[2] * k);
    let e = format!(r#""material": "emitter", "emission": [{le}, {le}, {le}]"#);
    let star: Vec<String> = (0..10)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / 10.0;
            let rr = if i % 2 == 0 { 1.0 } else { 0.4 };
            at(rr * a.cos(), rr * a.sin())
        })
        .collect();
    vec![
        (
            "quad".into(),
            format!(
                r#"{{"type": "quad", "corner": {}, "edge_u": {}, "edge_v": {}, {e}}}"#,
                at(-1.0, -1.0),
                vec(u, 2.0 * r),
                vec(w, 2.0 * r)
            ),
        ),
        (
            "triangle".into(),
            format!(
                r#"{{"type": "triangles", "positions": [{}, {}, {}], "indices": [[0, 1, 2]], {e}}}"#,
                at(-1.0, -1.0),
                at(1.0, -1.0),
                at(0.0, 1.0)
            ),
        ),
        (
            "star".into(),
            format!(
                r#"{{"type": "polygon", "vertices": [{}], {e}}}"#,
                star.join(", ")
            ),
        ),
        (
            "disk".into(),
            format!(
                r#"{{"type": "disk", "center": {}, "normal": {}, "radius": {r}, {e}}}"#,
                vec(c, 1.0),
                vec(n, 1.0)
            ),
        ),
        (
            "sphere".into(),
            format!(
                r#"{{"type": "sphere", "center": {}, "radius": {r}, {e}}}"#,
                vec(c, 1.0)
            ),
        ),
    ]
}

/// The usual light: 0.25 wide, 1.5 above the floor, facing down, at scale `s`.
fn ceiling_lights(s: f64, le: f64) -> Vec<(String, String)> {
    light_shapes([0.0, 1.5 * s, 0.0], [0.0, -1.0, 0.0], 0.25 * s, le)
}

/// One stress scene.
struct Case {
    name: String,
    json: String,
}

fn case(name: impl Into<String>, json: String) -> Case {
    Case {
        name: name.into(),
        json,
    }
}

/// Materials for the roughness axis: a complex-Fresnel conductor floor, a tinted conductor ball
/// and a plastic block, all at roughness `alpha`.
fn rough_materials(alpha: f64) -> String {
    format!(
        r#""floor": {{"type": "conductor", "alpha": {alpha}, "eta": [0.2, 0.92, 1.1], "k": [3.9, 2.45, 2.14]}},
    "ball": {{"type": "conductor", "alpha": {alpha}, "reflectance": [0.9, 0.8, 0.6]}},
    "block": {{"type": "plastic", "alpha": {alpha}, "albedo": [0.3, 0.5, 0.7], "ior": 1.5}},
    "emitter": {{"type": "plastic", "alpha": {alpha}, "albedo": [0.8, 0.8, 0.8], "ior": 1.9}}"#
    )
}

/// Every scene of the matrix except the exact-relation checks.
fn stress_cases() -> Vec<Case> {
    let mut cases = Vec::new();
    let quad = |lights: Vec<(String, String)>| vec![lights[0].1.clone()];
    let all = |lights: Vec<(String, String)>| -> Vec<(String, Vec<String>)> {
        lights.into_iter().map(|(n, j)| (n, vec![j])).collect()
    };

    // Roughness, with every light shape so that every light meets every lobe width.
    for alpha in [0.0, 1e-4, 1e-3, 0.01, 0.5, 1.0] {
        let lights: Vec<String> = ceiling_lights(1.0, 5.0).into_iter().map(|l| l.1).collect();
        // Spread the five lights so they do not overlap.
        let spread: Vec<String> = lights
            .iter()
            .enumerate()
            .map(|(i, l)| shift_x(l, (i as f64 - 2.0) * 0.6))
            .collect();
        cases.push(case(
            format!("alpha {alpha}"),
            room(1.0, &rough_materials(alpha), &spread, &camera(1.0), &[]),
        ));
    }

    // A camera 0.01° above the floor, looking along it.
    let grazing = 0.01f64.to_radians().tan();
    let cam = format!(
        r#"{{"from": [0, {}, -0.99], "to": [0, 0, 1], "up": [0, 1, 0], "vfov_deg": 30, "width": {SIZE}, "height": {SIZE}}}"#,
        2.0 * grazing
    );
    for (shape, lights) in all(ceiling_lights(1.0, 5.0)) {
        cases.push(case(
            format!("grazing camera, {shape} light"),
            room(1.0, DIFFUSE, &lights, &cam, &[]),
        ));
    }

    // Lights 0.01° off the floor's plane: lying just above it and facing almost along it.
    let tilt = [0.0, grazing.sin(), grazing.cos()];
    for (shape, lights) in all(light_shapes([0.0, 0.3, -0.5], tilt, 0.25, 5.0)) {
        cases.push(case(
            format!("grazing {shape} light"),
            room(1.0, DIFFUSE, &lights, &camera(1.0), &[]),
        ));
    }
    for (shape, lights) in all(light_shapes([0.0, 1e-3, 0.0], [0.0, 1.0, 0.0], 0.25, 5.0)) {
        cases.push(case(
            format!("{shape} light 1e-3 above the floor, facing up"),
            room(1.0, DIFFUSE, &lights, &camera(1.0), &[]),
        ));
    }

    // Lights touching and cutting through the floor and the wall.
    for (shape, lights) in all(light_shapes([0.0, 0.0, 0.0], [0.0, 0.0, -1.0], 0.3, 5.0)) {
        cases.push(case(
            format!("{shape} light cut by the floor"),
            room(1.0, DIFFUSE, &lights, &camera(1.0), &[]),
        ));
    }
    for (shape, lights) in all(light_shapes([0.0, 0.5, 1.0], [0.0, -1.0, 0.0], 0.3, 5.0)) {
        cases.push(case(
            format!("{shape} light cut by the wall"),
            room(1.0, DIFFUSE, &lights, &camera(1.0), &[]),
        ));
    }

    // Tiny lights (area ~1e-8 of the room's 4 square units) and one far larger than the scene.
    for (shape, lights) in all(light_shapes([0.0, 1.0, 0.0], [0.0, -1.0, 0.0], 1e-4, 1e8)) {
        cases.push(case(
            format!("tiny {shape} light"),
            room(1.0, DIFFUSE, &lights, &camera(1.0), &[]),
        ));
    }
    for (shape, lights) in all(light_shapes([0.0, 3.0, 0.0], [0.0, -1.0, 0.0], 100.0, 1.0)) {
        cases.push(case(
            format!("huge {shape} light"),
            room(1.0, DIFFUSE, &lights, &camera(1.0), &[]),
        ));
    }

    // Scene scales from 1e-4 to 1e6, with rough materials at a mid roughness.
    for s in [1e-4, 1e-2, 1e2, 1e4, 1e6] {
        cases.push(case(
            format!("scale {s}"),
            room(
                s,
                &rough_materials(0.2),
                &quad(ceiling_lights(s, 5.0)),
                &camera(s),
                &[],
            ),
        ));
    }

    // Coplanar overlapping quads (one of them emitting), and boxes 1e-6 thick.
    let overlap = vec![
        r#"{"type": "quad", "corner": [-0.5, 0, -0.5], "edge_u": [0, 0, 1], "edge_v": [1, 0, 0], "material": "ball"}"#.to_string(),
        r#"{"type": "quad", "corner": [-0.2, 0, -0.7], "edge_u": [0, 0, 1], "edge_v": [1, 0, 0], "material": "emitter", "emission": [2, 2, 2]}"#.to_string(),
    ];
    cases.push(case(
        "coplanar overlapping quads",
        room(
            1.0,
            DIFFUSE,
            &quad(ceiling_lights(1.0, 5.0)),
            &camera(1.0),
            &overlap,
        ),
    ));
    let thin = vec![
        r#"{"type": "box", "min": [-0.5, 0.2, -0.5], "max": [0.5, 0.200001, 0.5], "material": "block"}"#.to_string(),
        r#"{"type": "box", "min": [0.5, 0, -0.6], "max": [0.500001, 0.8, 0.6], "rotate_y_deg": 30, "material": "ball"}"#.to_string(),
    ];
    cases.push(case(
        "boxes 1e-6 thick",
        room(
            1.0,
            DIFFUSE,
            &quad(ceiling_lights(1.0, 5.0)),
            &camera(1.0),
            &thin,
        ),
    ));

    // Shading points on a light: the camera looks at the lights' backs and fronts, whose own
    // material reflects the other lights and themselves.
    let on_light: Vec<String> = light_shapes([0.0, 0.6, 0.3], [0.0, 0.0, -1.0], 0.5, 3.0)
        .into_iter()
        .enumerate()
        .map(|(i, (_, j))| shift_x(&j, (i as f64 - 2.0) * 0.35))
        .collect();
    cases.push(case(
        "shading points on lights",
        room(1.0, &rough_materials(0.3), &on_light, &camera(1.0), &[]),
    ));
    cases
}

/// Moves every `[x, y, z]` point of a light's JSON by `dx` along x (direction fields excepted).
fn shift_x(json: &str, dx: f64) -> String {
    let mut v: serde_json::Value = serde_json::from_str(json).unwrap();
    let obj = v.as_object_mut().unwrap();
    let shift = |p: &mut serde_json::Value| {
        let x = p[0].as_f64().unwrap();
        p[0] = (x + dx).into();
    };
    for key in ["corner", "center"] {
        if let Some(p) = obj.get_mut(key) {
            shift(p);
        }
    }
    for key in ["positions", "vertices"] {
        if let Some(list) = obj.get_mut(key) {
            list.as_array_mut().unwrap().iter_mut().for_each(shift);
        }
    }
    v.to_string()
}

/// Renders `scene` with `settings` and checks that no sample or pixel is non-finite; returns the
/// render.
fn render_finite(name: &str, scene: &Arc<Scene>, settings: Settings, seed: u32) -> Progressive {
    let r = render(scene, settings, SPP, seed);
    let film = r.film();
    assert_eq!(
        film.nonfinite, 0,
        "{name} {settings:?}: {} non-finite samples discarded",
        film.nonfinite
    );
    let bad = film.mean().iter().filter(|p| !p.is_finite()).count();
    assert_eq!(bad, 0, "{name} {settings:?}: {bad} non-finite pixels");
    r
}

#[test]
fn stress_scenes_never_produce_non_finite_values() {
    let cases = stress_cases();
    let settings = all_settings();
    let mut renders = 0;
    for (i, c) in cases.iter().enumerate() {
        let scene = build(&c.json);
        let mut lit = false;
        for (k, s) in settings.iter().enumerate() {
            let r = render_finite(&c.name, &scene, *s, (100 * i + k) as u32);
            lit |= r.film().mean().iter().any(|p| p.max_element() > 0.0);
            renders += 1;
        }
        // Every scene has a visible, lit surface: a black image would be a silent failure.
        assert!(lit, "{}: every render is black", c.name);
    }
    eprintln!(
        "{} scenes × {} settings = {renders} renders of {SIZE}×{SIZE} at {SPP} spp",
        cases.len(),
        settings.len()
    );
}

/// Emission 1e-6 and 1e6 against 1: the same seed gives the same paths, so the images are in exact
/// proportion (up to f32 rounding of the radiance sums).
#[test]
fn emission_scales_exactly() {
    let scene_at = |le: f64| {
        let lights: Vec<String> = ceiling_lights(1.0, le)
            .into_iter()
            .enumerate()
            .map(|(i, (_, j))| shift_x(&j, (i as f64 - 2.0) * 0.6))
            .collect();
        build(&room(
            1.0,
            &rough_materials(0.3),
            &lights,
            &camera(1.0),
            &[],
        ))
    };
    let base = scene_at(1.0);
    for k in [1e-6, 1e6] {
        let scaled = scene_at(k);
        for (i, s) in all_settings().into_iter().enumerate() {
            let a = render_finite("emission 1", &base, s, 7 + i as u32);
            let b = render_finite(&format!("emission {k}"), &scaled, s, 7 + i as u32);
            let (a, b) = (a.film().mean(), b.film().mean());
            let peak = a.iter().map(|p| p.max_element()).fold(0.0f32, f32::max);
            assert!(peak > 0.0, "{s:?}: black image");
            for (p, (x, y)) in a.iter().zip(&b).enumerate() {
                let diff = (*y / k as f32 - *x).abs().max_element();
                assert!(
                    diff <= 1e-4 * peak,
                    "{s:?} emission {k}: pixel {p} is {y} instead of {}",
                    *x * k as f32
                );
            }
        }
    }
}

/// Scales of the closed-box check.
const BOX_SCALES: [f64; 6] = [1e-4, 1e-2, 1.0, 1e2, 1e4, 1e6];

/// The closed emissive box (albedo 0.5, emission 1, unlimited depth) renders exactly 2 at every
/// scale: light leaking through corners or edges at some scale shows as a deficit.
#[test]
fn closed_box_is_exact_at_every_scale() {
    let settings = all_settings();
    let comparisons = BOX_SCALES.len() * settings.len();
    let critical = normal_two_sided_critical(sidak(0.01, comparisons));
    for (i, s) in BOX_SCALES.into_iter().enumerate() {
        let scene = build(&closed_box(s));
        for (k, st) in settings.iter().enumerate() {
            let r = render(&scene, *st, 64, (1000 + 10 * i + k) as u32);
            let film = r.film();
            assert_eq!(film.nonfinite, 0, "scale {s} {st:?}: non-finite samples");
            // Grey box: channel 0 stands for all three.
            let n = film.mean().len() as f64;
            let mean = film.mean().iter().map(|p| p.x as f64).sum::<f64>() / n;
            let var = film.variance_of_mean().iter().map(|v| v[0]).sum::<f64>() / (n * n);
            let z = (mean - 2.0) / var.sqrt().max(1e-12);
            assert!(
                z.abs() < critical,
                "scale {s} {st:?}: mean {mean} instead of 2 (z = {z:.2}, critical {critical:.2})"
            );
        }
    }
}

/// The cube `[−s, s]³` of six inward-facing quads, diffuse albedo 0.5, emission 1, camera inside.
fn closed_box(s: f64) -> String {
    let faces = [
        ([-1, -1, -1], [0, 2, 0], [0, 0, 2]),
        ([1, -1, -1], [0, 0, 2], [0, 2, 0]),
        ([-1, -1, -1], [0, 0, 2], [2, 0, 0]),
        ([-1, 1, -1], [2, 0, 0], [0, 0, 2]),
        ([-1, -1, -1], [2, 0, 0], [0, 2, 0]),
        ([-1, -1, 1], [0, 2, 0], [2, 0, 0]),
    ];
    let v = |a: [i32; 3]| {
        format!(
            "[{}, {}, {}]",
            a[0] as f64 * s,
            a[1] as f64 * s,
            a[2] as f64 * s
        )
    };
    let shapes: Vec<String> = faces
        .iter()
        .map(|&(c, u, w)| {
            format!(
                r#"{{"type": "quad", "corner": {}, "edge_u": {}, "edge_v": {}, "material": "wall", "emission": [1, 1, 1]}}"#,
                v(c),
                v(u),
                v(w)
            )
        })
        .collect();
    format!(
        r#"{{"camera": {{"from": [{}, {}, {}], "to": [{}, {}, {}], "up": [0, 1, 0], "vfov_deg": 100, "width": 16, "height": 16}},
  "max_depth": -1,
  "materials": {{"wall": {{"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}}}},
  "shapes": [{}]}}"#,
        0.1 * s,
        0.05 * s,
        -0.2 * s,
        s,
        0.8 * s,
        0.9 * s,
        shapes.join(", ")
    )
}
