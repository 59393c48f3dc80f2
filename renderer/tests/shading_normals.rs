//! Shading normals (issue 17, docs/shading-normals.md), end to end on the CPU.
//!
//! - **A smooth mesh sphere converges to the analytic sphere.** A UV sphere of
//!   [`TRIANGLES`] triangles with exact vertex normals (`scene::mesh::uv_sphere`, written as a
//!   binary PLY at test time) and the analytic sphere, both rough plastic under a quad light and a constant sky, are
//!   rendered with every strategy; each mesh render is compared with an analytic MIS render of
//!   [`REF_SPP`] spp by the block z-test (8×8 blocks, both variances), family-wise α = 0.01
//!   Šidák-corrected over blocks, channels and the five strategies. The inscribed polyhedron lies
//!   within 1 − cos(π/96) ≈ 5e-4 of the sphere (0.013 pixels at this zoom), and the interpolated
//!   normals within the same order of the true ones, far below what the test resolves.
//! - **Power:** the same mesh with every vertex normal turned by [`TILT_DEG`] about +y must fail
//!   the same test: shading normals off by that angle are caught (measured: 5° fails 25 of 192
//!   blocks, worst |z| 8.2; 3° fails 2, |z| 4.9; 2° passes, |z| 3.4). Flat shading of this mesh is
//!   not (its facet normals lie within 1.9° of the sphere's, and alternate in sign, so 8×8 blocks
//!   average them out); it is rendered and its result printed.
//! - **The furnace keeps with shading normals.** A closed box of 12 inward triangles whose
//!   vertex normals equal their face normals, every face diffuse (albedo a) and emitting L, seen
//!   from inside: every pixel is L/(1 − a) at unlimited depth. This runs the whole shading-normal
//!   path (attribute lookup, interpolation, the frame, the side rule) where it must change nothing:
//!   a side rule that rejected valid directions, or a frame off the normal, loses energy. The image
//!   mean per channel is compared with the closed form for every strategy and light-sampling
//!   method, z-test at family-wise α = 0.01 (Šidák over all comparisons), except light-only
//!   sampling by area: in a closed box it has infinite variance (renderer/tests/furnace.rs explains why),
//!   so its sample variance understates the error (here z = −3.66 at 256 spp, the same with and
//!   without vertex normals: the image is bit-identical either way).
//!
//! The sphere's light is large (4 × 4 at height 3) because BSDF-only sampling of a small light
//! is heavy-tailed: with a 1.5 × 1.5 light, the analytic sphere's own BSDF render failed against
//! its MIS render at a silhouette pixel whose few light hits left the sample variance too small.
//!
//! Seeds are fixed (in the calls below).

mod common;

use common::{METHODS, STRATEGIES, STRATEGIES_AND_OPTIMAL, Tally, render};
use lumis::engine::Progressive;
use lumis::integrator::{Heuristic, Settings, Strategy};
use lumis::lights::LightSampling;
use lumis::metrics::{BlockTest, normal_two_sided_critical, sidak};
use lumis::scene::mesh::MeshData;
use lumis::scene::mesh::ply::{self, Encoding};
use lumis::scene::mesh::uv_sphere::UvSphere;
use lumis::scene::{Scene, parse_scene_in};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Triangles of the tessellated sphere: 48 stacks of 96 segments.
const TRIANGLES: usize = 4 * 48 * 47;
/// Image size (square), samples per pixel of the compared renders and of the reference.
const SIZE: u32 = 64;
const SPP: u32 = 256;
const REF_SPP: u32 = 1024;
/// The power check's rotation of every shading normal, in degrees (see the file comment).
const TILT_DEG: f32 = 5.0;

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("lumis-shading-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The sphere scene with `sphere` as its one shape (JSON), built in `folder`.
fn sphere_scene(folder: &Path, sphere: &str) -> Arc<Scene> {
    let json = format!(
        r#"{{
  "camera": {{"from": [0, 0.6, -4], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 35,
             "width": {SIZE}, "height": {SIZE}}},
  "max_depth": -1,
  "background": [0.2, 0.2, 0.25],
  "materials": {{
    "glossy": {{"type": "plastic", "albedo": [0.6, 0.35, 0.2], "alpha": 0.15, "ior": 1.5}}
  }},
  "shapes": [
    {sphere},
    {{"type": "quad", "corner": [-3, 3, -3], "edge_u": [4, 0, 0], "edge_v": [0, 0, 4],
      "emission": [1.5, 1.5, 1.5]}}
  ]
}}"#
    );
    let desc = parse_scene_in(&json, folder).unwrap_or_else(|e| panic!("{e}\n{json}"));
    assert!(desc.warnings.is_empty(), "{:?}", desc.warnings);
    Arc::new(Scene::from_desc(&desc).unwrap_or_else(|e| panic!("{e}")))
}

fn compare(a: &Progressive, b: &Progressive, alpha: f64) -> BlockTest {
    common::renders_z_test(a, b, 8, alpha)
}

fn mis() -> Settings {
    Settings {
        strategy: Strategy::Mis {
            heuristic: Heuristic::Power,
        },
        ..Settings::default()
    }
}

#[test]
fn smooth_mesh_sphere_converges_to_the_analytic_sphere() {
    let dir = temp_dir("sphere");
    let sphere = UvSphere::new(TRIANGLES);
    assert_eq!(sphere.stacks(), 48);
    let mesh = sphere.mesh();
    ply::write(&dir.join("sphere.ply"), &mesh, Encoding::BinaryLittleEndian).unwrap();
    let analytic = sphere_scene(
        &dir,
        r#"{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "glossy"}"#,
    );
    let smooth = sphere_scene(
        &dir,
        r#"{"type": "mesh", "file": "sphere.ply", "material": "glossy"}"#,
    );
    assert!(smooth.attributes.has_normals());
    let reference = render(&analytic, mis(), REF_SPP, 11);
    let alpha = sidak(0.01, STRATEGIES.len());
    let mut failures = Vec::new();
    for (k, strategy) in STRATEGIES.into_iter().enumerate() {
        let settings = Settings {
            strategy,
            ..Settings::default()
        };
        let r = render(&smooth, settings, SPP, 100 + k as u32);
        let what = format!("smooth mesh sphere, {strategy:?}");
        if let Err(msg) = common::check_unbiased(&what, &compare(&r, &reference, alpha)) {
            failures.push(msg);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));

    // Power: the vertex normals all turned by TILT_DEG about +y are told apart from the sphere.
    let tilt = glam::Quat::from_rotation_y(TILT_DEG.to_radians());
    let tilted_mesh = MeshData {
        normals: mesh
            .normals
            .as_ref()
            .map(|ns| ns.iter().map(|n| tilt * *n).collect()),
        ..mesh.clone()
    };
    ply::write(
        &dir.join("tilted.ply"),
        &tilted_mesh,
        Encoding::BinaryLittleEndian,
    )
    .unwrap();
    let tilted = sphere_scene(
        &dir,
        r#"{"type": "mesh", "file": "tilted.ply", "material": "glossy"}"#,
    );
    let test = compare(&render(&tilted, mis(), SPP, 200), &reference, alpha);
    assert!(
        common::check_unbiased("normals tilted (must differ)", &test).is_err(),
        "shading normals tilted by {TILT_DEG}° were not detected"
    );
    // Flat shading at this tessellation (facet normals within 1.9° of the sphere's) is printed,
    // not asserted: measured, it is not told apart (worst |z| 3.9), an error below this test's
    // resolution, as the tilt shows.
    let flat = sphere_scene(
        &dir,
        r#"{"type": "mesh", "file": "sphere.ply", "face_normals": true, "material": "glossy"}"#,
    );
    assert!(!flat.attributes.has_normals());
    let _ = common::check_unbiased(
        "flat-shaded (for information)",
        &compare(&render(&flat, mis(), SPP, 201), &reference, alpha),
    );
}

/// The closed box: 6 faces of the cube [−1, 1]³ as 12 triangles wound inwards, 4 vertices per
/// face with the face's inward normal.
fn inward_box() -> MeshData {
    use glam::Vec3;
    let mut mesh = MeshData {
        normals: Some(Vec::new()),
        ..Default::default()
    };
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            let corner = |a: f32, b: f32| {
                let mut p = Vec3::ZERO;
                p[axis] = sign;
                p[u] = a;
                p[v] = b;
                p
            };
            let base = mesh.positions.len() as u32;
            mesh.positions.extend([
                corner(-1.0, -1.0),
                corner(1.0, -1.0),
                corner(1.0, 1.0),
                corner(-1.0, 1.0),
            ]);
            let mut inward = Vec3::ZERO;
            inward[axis] = -sign;
            mesh.normals.as_mut().unwrap().extend([inward; 4]);
            // cross(e_u, e_v) points along +axis: flip the winding on the +axis face.
            let (t0, t1) = if sign > 0.0 {
                ([0, 2, 1], [0, 3, 2])
            } else {
                ([0, 1, 2], [0, 2, 3])
            };
            mesh.indices.push(t0.map(|i| base + i));
            mesh.indices.push(t1.map(|i| base + i));
        }
    }
    mesh
}

#[test]
fn closed_box_with_vertex_normals_keeps_the_furnace() {
    let dir = temp_dir("box");
    let mesh = inward_box();
    for t in &mesh.indices {
        let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
        let n = mesh.normals.as_ref().unwrap()[t[0] as usize];
        assert!((b - a).cross(c - a).dot(n) > 0.0, "winding must face in");
    }
    ply::write(&dir.join("box.ply"), &mesh, Encoding::Ascii).unwrap();
    let (albedo, le) = (0.5, 1.0);
    let fnorm = std::env::var("FACE").is_ok();
    let json = format!(
        r#"{{
  "camera": {{"from": [0.1, -0.2, 0.05], "to": [0.3, 0.1, 1], "up": [0, 1, 0], "vfov_deg": 100,
             "width": 16, "height": 16}},
  "max_depth": -1,
  "materials": {{"wall": {{"type": "diffuse", "albedo": [{albedo}, {albedo}, {albedo}]}}}},
  "shapes": [{{"type": "mesh", "file": "box.ply", "face_normals": {fnorm}, "material": "wall", "emission": [{le}, {le}, {le}]}}]
}}"#
    );
    let desc = parse_scene_in(&json, &dir).unwrap_or_else(|e| panic!("{e}"));
    let scene = Arc::new(Scene::from_desc(&desc).unwrap());
    assert!(fnorm || scene.attributes.has_normals());
    let expected = le / (1.0 - albedo);
    let comparisons = (STRATEGIES_AND_OPTIMAL.len() * METHODS.len() - 1) * 3;
    let mut tally = Tally::new(normal_two_sided_critical(sidak(0.01, comparisons)));
    for (k, strategy) in STRATEGIES_AND_OPTIMAL.into_iter().enumerate() {
        for (m, light_sampling) in METHODS.into_iter().enumerate() {
            if strategy == Strategy::Light && light_sampling == LightSampling::Area {
                continue;
            }
            let settings = Settings {
                strategy,
                light_sampling,
                ..Settings::default()
            };
            let r = render(&scene, settings, 256, (10 * k + m) as u32);
            let film = r.film();
            let (mean, var) = (film.mean(), film.variance_of_mean());
            for c in 0..3 {
                let means: Vec<f64> = mean.iter().map(|p| p[c] as f64).collect();
                let vars: Vec<f64> = var.iter().map(|v| v[c]).collect();
                assert!(means.iter().all(|m| m.is_finite()));
                let what = format!("{strategy:?} {light_sampling:?} channel {c}");
                tally.compare(&what, &means, &vars, expected);
            }
        }
    }
    tally.finish(
        "closed_box_with_vertex_normals_keeps_the_furnace",
        comparisons,
    );
}
