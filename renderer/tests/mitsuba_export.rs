//! The Mitsuba 3 exporter (`renderer/src/scene/mitsuba/export*.rs`) round-trips: for every
//! scene in `tests/data/scenes/` and a scene with every material, texture and shape kind the
//! exporter maps, JSON → export → import (`load_scene_with` on the written XML) builds a scene
//! that renders bit for bit like the JSON's (a few samples per pixel, same seed, every pixel
//! compared exactly). Two mappings cannot be exact: a plastic in lumis' coupling, which Mitsuba
//! does not have, goes out as Mitsuba's GGX plastic and comes back as that, so it is compared
//! with that plastic; and an emitting polygon becomes a PLY of its
//! triangles, whose light lumis samples per triangle rather than as one polygon; those scenes
//! are compared exactly against the JSON with its polygons as lumis' own triangulation, and
//! `analytic_polygon` also by the block z-test against the unchanged JSON. Wrong mappings
//! (swapped film size, flipped normals, Mitsuba's default exterior index, unswapped
//! checkerboard colours in a scalar slot) are shown to be detected. Nothing runs Mitsuba.

mod common;

use glam::DVec3;
use lumis::engine::Progressive;
use lumis::integrator::Settings;
use lumis::scene::desc::{LightDesc, LookAt};
use lumis::scene::mitsuba::export::{ExportOptions, write_export};
use lumis::scene::{
    BackgroundDesc, GeometryDesc, MaterialDesc, PlasticModel, ProjectionDesc, Scene, SceneDesc,
    load_scene, load_scene_with, parse_scene_in,
};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Samples per pixel of each comparison render, and its seed.
const SPP: u32 = 4;
const SEED: u32 = 7;

/// A temporary folder, removed when dropped.
struct Dir(PathBuf);

impl Dir {
    fn new(name: &str) -> Dir {
        let d = std::env::temp_dir().join(format!("lumis-export-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        Dir(d)
    }
}

impl Drop for Dir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Renders `desc` with lumis' default settings (`rr_depth` from a Mitsuba file if given).
fn render(desc: &SceneDesc, rr_depth: Option<u32>) -> Progressive {
    let scene = Arc::new(Scene::from_desc(desc).unwrap_or_else(|e| panic!("{e}")));
    let mut settings = Settings::default();
    if let Some(rr) = rr_depth {
        settings.rr_depth = rr;
    }
    common::render(&scene, settings, SPP, SEED)
}

/// Exports `desc` into `dir/NAME.xml` and imports it back.
fn round_trip(desc: &SceneDesc, dir: &Dir, name: &str) -> (PathBuf, lumis::scene::LoadedScene) {
    let xml = dir.0.join(format!("{name}.xml"));
    write_export(desc, &xml, &ExportOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    (xml.clone(), reimport(&xml))
}

fn reimport(xml: &Path) -> lumis::scene::LoadedScene {
    load_scene_with(xml, &[]).unwrap_or_else(|e| {
        let text = std::fs::read_to_string(xml).unwrap_or_default();
        panic!("{e}\n{text}")
    })
}

/// `None` when the two renders agree in every pixel and channel, else what differs.
fn difference(a: &Progressive, b: &Progressive) -> Option<String> {
    let (fa, fb) = (a.film(), b.film());
    if (fa.width, fa.height) != (fb.width, fb.height) {
        return Some(format!(
            "size {}×{} vs {}×{}",
            fa.width, fa.height, fb.width, fb.height
        ));
    }
    let (ma, mb) = (fa.mean(), fb.mean());
    let differing: Vec<usize> = (0..ma.len()).filter(|&i| ma[i] != mb[i]).collect();
    let &first = differing.first()?;
    Some(format!(
        "{} of {} pixels differ, first ({}, {}): {:?} vs {:?}",
        differing.len(),
        ma.len(),
        first as u32 % fa.width,
        first as u32 / fa.width,
        ma[first],
        mb[first]
    ))
}

/// `desc` as the exact comparisons expect it back: every polygon replaced by the triangles lumis
/// builds for it, and the camera in Mitsuba's `lookat` frame (`to` at unit distance, `up`
/// orthonormalised): the same camera, but lumis' f32 camera basis (`normalize(forward × up)`)
/// can differ in the last bit between an up hint and its orthonormalised version, and Mitsuba's
/// sensor keeps only the frame. `every_camera_comes_back_as_the_same_view` checks the frame.
fn canonical(desc: &SceneDesc) -> SceneDesc {
    let mut d = desc.clone();
    let c = &mut d.camera;
    let dir = (c.to - c.from).normalize();
    let left = c.up.cross(dir).normalize();
    c.up = dir.cross(left);
    c.to = c.from + dir;
    // The lights' frames come back the same way (the `lookat` of their `to_world`); a
    // direction is normalised once more by the importer and once more by the scene parser.
    for l in &mut d.lights {
        match l {
            LightDesc::Spot { frame, .. } | LightDesc::Projector { frame, .. } => {
                let dir = (frame.to - frame.from).normalize();
                let left = frame.up.cross(dir).normalize();
                frame.up = dir.cross(left);
                frame.to = frame.from + dir;
            }
            LightDesc::Directional { direction, .. } => {
                *direction = direction.normalize().normalize();
            }
            LightDesc::Point { .. } => {}
        }
    }
    for s in &mut d.shapes {
        if let GeometryDesc::Polygon { vertices } = &s.geometry {
            let indices = lumis::geometry::polygon::triangulate(vertices)
                .iter()
                .map(|t| t.map(|i| i as u32))
                .collect();
            s.geometry = GeometryDesc::Triangles {
                positions: vertices.clone(),
                indices,
            };
        }
    }
    // Mitsuba has no plastic in lumis' coupling: one goes out as Mitsuba's GGX plastic and
    // comes back as that (docs/mitsuba.md, Export).
    for m in &mut d.materials {
        if let MaterialDesc::Plastic { model, .. } = &mut m.material
            && *model == PlasticModel::Lumis
        {
            *model = PlasticModel::Mitsuba {
                distribution: lumis::materials::Distribution::Ggx,
                nonlinear: false,
            };
        }
    }
    d
}

/// Exports, imports and compares `desc` exactly (polygons as triangles), panicking on a
/// difference.
fn assert_round_trip(desc: &SceneDesc, name: &str) {
    let dir = Dir::new(name);
    let (_, back) = round_trip(desc, &dir, name);
    assert_same_view(desc, &back.desc, name);
    assert_same_lights(desc, &back.desc, name);
    let expected = render(&canonical(desc), None);
    let got = render(&back.desc, back.rr_depth);
    if let Some(d) = difference(&expected, &got) {
        panic!("{name}: the exported scene renders differently: {d}");
    }
}

/// The imported camera is the original's view: the same eye, view direction, image up
/// (orthonormalised), field of view and size, to 1e-12.
fn assert_same_view(desc: &SceneDesc, back: &SceneDesc, name: &str) {
    let (a, b) = (&canonical(desc).camera, &back.camera);
    let close =
        |u: DVec3, v: DVec3| (u - v).abs().max_element() <= 1e-12 * u.abs().max_element().max(1.0);
    assert!(
        close(a.from, b.from) && close(a.to, b.to) && close(a.up, b.up),
        "{name}: camera {a:?} came back as {b:?}"
    );
    // The projection's kind and numbers (field of view, lens, film size).
    let numbers = |p: ProjectionDesc| match p {
        ProjectionDesc::Perspective { vfov_deg } => (0, vec![vfov_deg]),
        ProjectionDesc::ThinLens {
            vfov_deg,
            aperture_radius,
            focus_distance,
        } => (1, vec![vfov_deg, aperture_radius, focus_distance]),
        ProjectionDesc::Orthographic { view_size } => (2, view_size.to_vec()),
    };
    let ((ka, na), (kb, nb)) = (numbers(a.projection), numbers(b.projection));
    assert!(
        ka == kb
            && na
                .iter()
                .zip(&nb)
                .all(|(x, y)| (x - y).abs() <= 1e-12 * x.abs()),
        "{name}: {a:?} vs {b:?}"
    );
    assert_eq!((a.width, a.height), (b.width, b.height), "{name}");
    assert_eq!(a.principal_point_offset, b.principal_point_offset, "{name}");
}

/// The imported lights are the original's, in order: frames and directions as [`canonical`]
/// gives them to 1e-12 (as the camera's), every other number and texture exactly.
fn assert_same_lights(desc: &SceneDesc, back: &SceneDesc, name: &str) {
    let want = canonical(desc).lights;
    assert_eq!(want.len(), back.lights.len(), "{name}: {:?}", back.lights);
    let close =
        |u: DVec3, v: DVec3| (u - v).abs().max_element() <= 1e-12 * u.abs().max_element().max(1.0);
    let same_frame =
        |a: &LookAt, b: &LookAt| close(a.from, b.from) && close(a.to, b.to) && close(a.up, b.up);
    for (i, (a, b)) in want.iter().zip(&back.lights).enumerate() {
        // The frames (and a direction) to the tolerance, then the rest exactly.
        let mut b = b.clone();
        let ok = match (a, &mut b) {
            (LightDesc::Spot { frame: fa, .. }, LightDesc::Spot { frame: fb, .. })
            | (LightDesc::Projector { frame: fa, .. }, LightDesc::Projector { frame: fb, .. }) => {
                let ok = same_frame(fa, fb);
                *fb = *fa;
                ok
            }
            (
                LightDesc::Directional { direction: da, .. },
                LightDesc::Directional { direction: db, .. },
            ) => {
                let ok = close(*da, *db);
                *db = *da;
                ok
            }
            _ => true,
        };
        assert!(
            ok && *a == b,
            "{name}: lights[{i}] {a:?} came back as {:?}",
            back.lights[i]
        );
    }
}

fn scenes_dir() -> PathBuf {
    common::data_dir().join("scenes")
}

#[test]
fn every_stored_scene_round_trips_bit_for_bit() {
    let mut names: Vec<String> = std::fs::read_dir(scenes_dir())
        .unwrap()
        .filter_map(|e| {
            let p = e.unwrap().path();
            (p.extension()? == "json").then(|| p.file_stem().unwrap().to_string_lossy().into())
        })
        .collect();
    names.sort();
    assert!(names.len() >= 7, "{names:?}");
    for name in names {
        let desc = load_scene(&scenes_dir().join(format!("{name}.json")))
            .unwrap_or_else(|e| panic!("{e}"));
        assert_round_trip(&desc, &name);
    }
}

/// A textured sphere and disk turned by their own frames (`pole`, `u_axis`) export as Mitsuba
/// `to_world` matrices whose columns are those frames and come back as the same frames to
/// 1e-12 (not bit for bit: the importer divides the columns by their length, the radius).
#[test]
fn turned_texture_frames_round_trip() {
    let json = r#"{
      "camera": {"from": [0, 2, -5], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40,
                 "width": 8, "height": 8},
      "materials": {"checker": {"type": "diffuse", "albedo": {"type": "checkerboard"}}},
      "shapes": [
        {"type": "sphere", "center": [-1.2, 0.3, -2.4], "radius": 0.3, "pole": [0.3, 1, 0],
         "u_axis": [1, 0, 0.5], "material": "checker"},
        {"type": "disk", "center": [2.2, 0.02, -0.6], "normal": [0, 1, 0.1], "radius": 0.4,
         "u_axis": [1, 0, 1], "material": "checker"}
      ]
    }"#;
    let desc = parse_scene_in(json, &scenes_dir()).unwrap_or_else(|e| panic!("{e}"));
    let dir = Dir::new("texture_frames");
    let (_, back) = round_trip(&desc, &dir, "texture_frames");
    let close = |a: DVec3, b: DVec3| (a - b).abs().max_element() < 1e-12;
    let perpendicular = |u: DVec3, n: DVec3| (u - n * n.dot(u)).normalize();
    let GeometryDesc::Sphere {
        pole: Some(pole),
        u_axis: Some(u),
        radius,
        ..
    } = back.desc.shapes[0].geometry
    else {
        panic!("{:?}", back.desc.shapes[0].geometry)
    };
    let z = DVec3::new(0.3, 1.0, 0.0).normalize();
    let want_u = perpendicular(DVec3::new(1.0, 0.0, 0.5), z);
    assert!(close(pole, z) && close(u, want_u) && (radius - 0.3).abs() < 1e-12);
    let GeometryDesc::Disk {
        normal,
        u_axis: Some(u),
        ..
    } = back.desc.shapes[1].geometry
    else {
        panic!("{:?}", back.desc.shapes[1].geometry)
    };
    let n = DVec3::new(0.0, 1.0, 0.1).normalize();
    assert!(close(normal, n) && close(u, perpendicular(DVec3::new(1.0, 0.0, 1.0), n)));
}

/// An environment map turned by a general rotation and then about +y exports as one `to_world`
/// (the matrix, then the turn) and comes back as the same rotation to 1e-12, as the background's
/// `rotation` (issue 38, item 1).
#[test]
fn an_envmap_rotation_round_trips() {
    use glam::DMat3;
    let mut desc = load_scene(&scenes_dir().join("envmap_objects.json")).unwrap();
    let tilt = DMat3::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 0.9);
    let BackgroundDesc::Envmap(e) = &mut desc.background else {
        panic!("envmap_objects has an envmap")
    };
    e.rotation = Some(tilt);
    let want = DMat3::from_rotation_y(e.rotate_y_deg.to_radians()) * tilt;
    let dir = Dir::new("envmap_rotation");
    let (_, back) = round_trip(&desc, &dir, "envmap_rotation");
    let BackgroundDesc::Envmap(b) = &back.desc.background else {
        panic!("the envmap came back as {:?}", back.desc.background)
    };
    let got = DMat3::from_rotation_y(b.rotate_y_deg.to_radians()) * b.rotation.unwrap();
    let off = (got - want)
        .to_cols_array()
        .iter()
        .fold(0.0f64, |a, x| a.max(x.abs()));
    assert!(off < 1e-12, "{got} against {want}: {off:e}");
}

/// A thin lens and an orthographic camera go out as Mitsuba's `thinlens` and `orthographic`
/// (the film's size as a scale, the near plane behind `from`) and come back as the same view,
/// rendering the same image bit for bit; so does a perspective camera's principal point
/// offset, which the other two cannot take. Catches a film size off by the aspect (the importer
/// divides the height by it) and a near plane not undone.
#[test]
fn thin_lens_and_orthographic_cameras_round_trip() {
    let base = load_scene(&scenes_dir().join("analytic_disk.json")).unwrap();
    let dist = (base.camera.to - base.camera.from).length();
    for (name, projection) in [
        (
            "thinlens",
            ProjectionDesc::ThinLens {
                vfov_deg: base.camera.vfov_deg().unwrap(),
                aperture_radius: 0.05 * dist,
                focus_distance: 0.8 * dist,
            },
        ),
        (
            "orthographic",
            ProjectionDesc::Orthographic {
                view_size: [0.9 * dist, 0.6 * dist],
            },
        ),
    ] {
        let mut desc = base.clone();
        desc.camera.projection = projection;
        assert_round_trip(&desc, &format!("camera_{name}"));
        // Mitsuba's principal point offset belongs to its perspective camera only.
        desc.camera.principal_point_offset = [0.1, 0.0];
        let dir = Dir::new(&format!("camera_{name}_offset"));
        let err = write_export(&desc, &dir.0.join("s.xml"), &ExportOptions::default()).unwrap_err();
        assert!(
            err.to_string().contains("camera.principal_point_offset"),
            "{err}"
        );
    }
    let mut desc = base.clone();
    desc.camera.principal_point_offset = [0.2, -0.15];
    assert_round_trip(&desc, "camera_principal_point");
}

/// A scene with every material kind, both texture kinds in colour and scalar slots (uv scale
/// and offset, wrap, raw), a textured emission, boxes, cylinders (a textured one and a flipped
/// anisotropic one with its own u axis), a textured sphere, one-sided materials, a shape without a material, a
/// constant background and every light kind (a point, a textured and a plain spot, a
/// directional, a textured projector whose field of view was given vertically and a constant
/// one).
fn kitchen_sink() -> SceneDesc {
    let json = r#"{
      "camera": {"from": [0.3, 1.2, -4], "to": [0, 0.4, 0], "up": [0, 1, 0.1],
                 "vfov_deg": 42, "width": 72, "height": 48},
      "max_depth": 6,
      "background": [0.05, 0.06, 0.08],
      "materials": {
        "checker": {"type": "diffuse", "albedo": {"type": "checkerboard", "color0": [0.8, 0.7, 0.1],
                    "color1": 0.2, "uv_scale": [4, 3], "uv_offset": [0.1, 0.25]}},
        "image": {"type": "diffuse", "albedo": {"type": "bitmap", "file": "textured_mesh_albedo.png",
                  "wrap": "mirror", "uv_scale": [2, 2]}},
        "raw": {"type": "diffuse", "albedo": {"type": "bitmap", "file": "textured_mesh_albedo.png",
                "raw": true, "wrap": "clamp"}, "two_sided": false},
        "brushed": {"type": "conductor", "eta": [0.2, 0.9, 1.1], "k": [3.9, 2.4, 2.2],
                    "alpha": {"type": "checkerboard", "color0": 0.05, "color1": 0.4,
                              "uv_scale": [5, 5]}},
        "mirror": {"type": "conductor", "alpha": 0, "reflectance": [0.9, 0.8, 0.6]},
        "tinted": {"type": "conductor", "alpha": 0.3,
                   "reflectance": {"type": "checkerboard", "color0": [0.9, 0.2, 0.2], "color1": 0.7}},
        "plastic": {"type": "plastic", "albedo": [0.2, 0.4, 0.7], "alpha": 0.2, "ior": 1.45,
                    "specular": [0.9, 0.9, 0.8]},
        "glossy": {"type": "plastic", "albedo": {"type": "checkerboard", "color0": 0.6, "color1": 0.1},
                   "alpha": 0, "ior": 1.6, "specular": [1, 1, 1], "two_sided": false},
        "glass": {"type": "dielectric", "ior": 1.5, "alpha": 0},
        "carbon": {"type": "conductor", "eta": [0.2, 0.9, 1.1], "k": [3.9, 2.4, 2.2],
                   "specular": [0.9, 0.8, 0.7], "distribution": "beckmann",
                   "alpha": [{"type": "checkerboard", "color0": 0.05, "color1": 0.3,
                              "uv_scale": [4, 4]}, 0.2]},
        "varnish": {"type": "plastic", "model": "mitsuba", "distribution": "beckmann",
                    "nonlinear": true, "albedo": [0.6, 0.4, 0.2], "alpha": 0.15, "ior": 1.5},
        "frosted": {"type": "dielectric", "ior": 1.33,
                    "alpha": {"type": "bitmap", "file": "textured_mesh_albedo.png"}},
        "bumpy": {"type": "plastic", "albedo": [0.5, 0.3, 0.2], "alpha": 0.2, "ior": 1.5,
                  "model": "mitsuba", "two_sided": false,
                  "normal_map": {"texture": {"type": "bitmap", "file": "textured_mesh_albedo.png",
                                 "raw": true, "uv_scale": [3, 2]}, "shadowing": false}},
        "tilted": {"type": "diffuse", "albedo": [0.6, 0.6, 0.5],
                   "normal_map": {"texture": [0.65, 0.4, 0.9], "flip_invalid_normals": false}},
        "dented": {"type": "diffuse", "albedo": [0.5, 0.6, 0.6],
                   "bump_map": {"texture": {"type": "bitmap", "file": "textured_mesh_albedo.png",
                                "raw": true, "uv_scale": [2, 2]}, "scale": -0.004,
                                "shadowing": false}},
        "sheet": {"type": "thin_dielectric", "ior": 1.33},
        "card": {"type": "two_sided", "front": "tinted", "back": "glossy"},
        "blend": {"type": "mix", "materials": ["plastic", "tinted"],
                  "weight": {"type": "checkerboard", "color0": 0.2, "color1": 0.9, "uv_scale": [3, 2]}}
      },
      "shapes": [
        {"type": "quad", "corner": [-3, 0, -3], "edge_u": [6, 0, 0], "edge_v": [0, 0, 6],
         "material": "checker"},
        {"type": "quad", "corner": [-3, 0, 3], "edge_u": [6, 0, 0], "edge_v": [0, 4, 0],
         "material": "image"},
        {"type": "quad", "corner": [-1.3, 2.7, -0.4], "edge_u": [0.9, 0.1, 0.3],
         "edge_v": [0.2, -0.1, 0.7], "emission": {"type": "checkerboard", "color0": [9, 8, 7],
         "color1": 2, "uv_scale": [2, 1]}},
        {"type": "box", "min": [-0.4, 0, -0.4], "max": [0.4, 0.7, 0.4], "rotate_y_deg": 27.5,
         "translate": [-1.4, 0, 0.6], "material": "brushed"},
        {"type": "box", "min": [0, 0, 0], "max": [0.5, 0.5, 0.5], "translate": [1.1, 0, -0.6],
         "material": "frosted"},
        {"type": "quad", "corner": [0.6, 0.05, 1.0], "edge_u": [0.8, 0, 0.2],
         "edge_v": [0, 1.1, 0], "material": "raw"},
        {"type": "sphere", "center": [0.2, 0.45, 0.1], "radius": 0.45, "material": "glass"},
        {"type": "sphere", "center": [-0.5, 0.25, -1.0], "radius": 0.25, "material": "plastic"},
        {"type": "sphere", "center": [1.6, 0.3, 0.8], "radius": 0.3, "material": "mirror"},
        {"type": "box", "min": [-2.2, 0, 1.5], "max": [-1.6, 1.2, 2.1], "material": "tinted"},
        {"type": "box", "min": [1.8, 0, -1.8], "max": [2.4, 0.6, -1.2], "material": "glossy"},
        {"type": "disk", "center": [2.0, 2.5, 0.5], "normal": [-0.3, -0.9, -0.2], "radius": 0.4,
         "emission": [6, 6, 5]},
        {"type": "disk", "center": [-2.5, 0.01, -1.5], "normal": [0, 1, 0], "radius": 0.5},
        {"type": "triangles", "positions": [[-2, 0, -2], [-1.5, 0, -2], [-1.8, 0.8, -1.9]],
         "indices": [[0, 1, 2]], "material": "varnish"},
        {"type": "quad", "corner": [-2.9, 0, 2.0], "edge_u": [0.8, 0, 0], "edge_v": [0, 0.8, 0],
         "material": "carbon"},
        {"type": "cylinder", "p0": [-0.9, 0, 1.2], "p1": [-0.9, 0.9, 1.2], "radius": 0.3,
         "material": "checker"},
        {"type": "cylinder", "p0": [0.9, 0.3, -2.2], "p1": [1.9, 0.5, -2.0], "radius": 0.25,
         "u_axis": [0, 1, 0.2], "flip_normals": true, "material": "carbon"},
        {"type": "sphere", "center": [2.6, 0.3, 2.4], "radius": 0.3, "material": "image"},
        {"type": "sphere", "center": [-2.4, 0.35, 0.4], "radius": 0.35, "material": "bumpy"},
        {"type": "quad", "corner": [2.2, 0, -3], "edge_u": [0.8, 0, 0], "edge_v": [0, 1, 0.1],
         "material": "tilted"},
        {"type": "quad", "corner": [-3, 0, -3], "edge_u": [0.8, 0, 0], "edge_v": [0, 1, 0.1],
         "material": "dented"},
        {"type": "quad", "corner": [-0.6, 0.2, -2.5], "edge_u": [1.2, 0, 0.1],
         "edge_v": [0, 1.2, 0], "material": "sheet"},
        {"type": "quad", "corner": [0.9, 0, -1.6], "edge_u": [0.3, 0, 0.6],
         "edge_v": [0, 0.9, 0], "material": "card"},
        {"type": "sphere", "center": [-1.0, 0.3, -1.8], "radius": 0.3, "material": "blend"}
      ],
      "lights": [
        {"type": "point", "position": [1.5, 2.0, -1.0], "intensity": [2, 1.5, 1]},
        {"type": "spot", "from": [-1, 2.5, -2], "to": [0, 0, 0.5], "up": [0, 1, 0],
         "intensity": [4, 4, 3.5], "cutoff_angle_deg": 35, "beam_width_deg": 20,
         "texture": {"type": "bitmap", "file": "textured_mesh_albedo.png", "uv_scale": [2, 1]}},
        {"type": "spot", "from": [2, 3, 1], "to": [1.6, 0, 0.8], "up": [0.3, 0.2, 1],
         "intensity": [3, 2, 1], "cutoff_angle_deg": 50},
        {"type": "directional", "direction": [0.3, -1, 0.4], "irradiance": [0.5, 0.45, 0.4]},
        {"type": "projector", "from": [0.5, 2, -3], "to": [0, 0.5, 3], "up": [0.1, 1, 0],
         "fov_deg": 30, "fov_axis": "y", "scale": 2,
         "irradiance": {"type": "bitmap", "file": "textured_mesh_albedo.png"}},
        {"type": "projector", "from": [-2, 1.5, -1], "to": [0, 0.3, 2.5],
         "fov_deg": 25, "irradiance": [1, 0.5, 0.25], "scale": 0.5}
      ]
    }"#;
    parse_scene_in(json, &scenes_dir()).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn every_material_texture_and_shape_kind_round_trips_bit_for_bit() {
    assert_round_trip(&kitchen_sink(), "kitchen_sink");
}

/// Opacities go out as Mitsuba's `mask` around everything else (a constant on a one-sided
/// diffuse, a bitmap on a bump-mapped two-sided diffuse) and come back the same, rendering the
/// same image bit for bit, at unlimited depth; at a finite `max_depth` the export is refused by
/// path (Mitsuba spends a bounce on each pass through a mask).
#[test]
fn masks_round_trip_at_unlimited_depth() {
    let mut desc = kitchen_sink();
    desc.max_depth = -1;
    let bitmap = desc
        .materials
        .iter()
        .find(|m| m.name == "frosted")
        .and_then(|m| m.textures.alpha.clone())
        .expect("a scalar bitmap");
    for m in desc.materials.iter_mut() {
        match m.name.as_str() {
            "raw" => {
                m.opacity = Some(lumis::scene::TextureDesc {
                    texture: lumis::textures::Texture::Constant(glam::Vec3::splat(0.6)),
                })
            }
            "dented" => m.opacity = Some(bitmap.clone()),
            _ => {}
        }
    }
    assert_round_trip(&desc, "masks");
    let dir = Dir::new("masks_back");
    let (_, back) = round_trip(&desc, &dir, "masks_back");
    for name in ["raw", "dented"] {
        let find = |d: &SceneDesc| d.materials.iter().find(|m| m.name == name).cloned();
        assert_eq!(
            find(&back.desc).unwrap().opacity,
            find(&desc).unwrap().opacity,
            "{name}"
        );
    }
    desc.max_depth = 6;
    let dir = Dir::new("masks_depth");
    let err = write_export(&desc, &dir.0.join("s.xml"), &ExportOptions::default()).unwrap_err();
    assert!(err.to_string().contains("materials.raw.opacity"), "{err}");
}

/// Mitsuba's `mesh_attribute` textures (`tests/data/mitsuba/xml_mesh_attribute.xml`: vertex and
/// face attributes of a PLY file without texture coordinates, a scaled 8-bit one, a scalar one as
/// α) go out as `mesh_attribute` on the same file and come back rendering the same image, bit
/// for bit.
#[test]
fn mesh_attribute_textures_round_trip() {
    let xml = common::data_dir()
        .join("mitsuba")
        .join("xml_mesh_attribute.xml");
    let m = lumis::scene::mitsuba::load(&xml, &[]).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(m.desc.mesh_attributes.len(), 3);
    assert_round_trip(&m.desc, "mesh_attribute");
}

/// The principled reference scene (every lobe, textured scalars and base colour, a transmitting
/// sphere, non-default sampling rates) goes out as Mitsuba's `principled` and comes back as the
/// same materials, rendering the same image bit for bit.
#[test]
fn principled_round_trips() {
    let xml = common::data_dir()
        .join("mitsuba")
        .join("xml_principled.xml");
    let m = lumis::scene::mitsuba::load(&xml, &[]).unwrap_or_else(|e| panic!("{e}"));
    assert_round_trip(&m.desc, "principled");
    let dir = Dir::new("principled_back");
    let (_, back) = round_trip(&m.desc, &dir, "principled_back");
    let kinds =
        |d: &SceneDesc| -> Vec<_> { d.materials.iter().map(|x| x.material.clone()).collect() };
    assert_eq!(kinds(&m.desc), kinds(&back.desc));
}

/// The thin principled reference scene (every lobe, textured base colour, diff_trans, η and
/// spec_trans, every sampling rate) goes out as Mitsuba's `principledthin` and comes back as the
/// same materials, rendering the same image bit for bit.
#[test]
fn principledthin_round_trips() {
    let xml = common::data_dir()
        .join("mitsuba")
        .join("xml_principledthin.xml");
    let m = lumis::scene::mitsuba::load(&xml, &[]).unwrap_or_else(|e| panic!("{e}"));
    assert_round_trip(&m.desc, "principledthin");
    let dir = Dir::new("principledthin_back");
    let (_, back) = round_trip(&m.desc, &dir, "principledthin_back");
    let kinds =
        |d: &SceneDesc| -> Vec<_> { d.materials.iter().map(|x| x.material.clone()).collect() };
    assert_eq!(kinds(&m.desc), kinds(&back.desc));
}

/// A mix of model mitsuba with a delta lobe (a smooth conductor beside a rough plastic) goes out
/// as a blendbsdf and comes back as the same mix of model mitsuba (the importer gives it the
/// model for its delta lobe), rendering the same image bit for bit.
#[test]
fn a_mix_of_model_mitsuba_round_trips() {
    let json = r#"{"camera": {"from": [0, 1, -3], "to": [0, 0.5, 0], "up": [0, 1, 0],
            "vfov_deg": 40, "width": 24, "height": 16},
        "background": [0.3, 0.3, 0.3],
        "materials": {
            "coat": {"type": "plastic", "albedo": [0.2, 0.3, 0.6], "alpha": 0.25,
                     "model": "mitsuba", "two_sided": false},
            "mirror": {"type": "conductor", "alpha": 0, "reflectance": [0.9, 0.8, 0.5],
                       "two_sided": false},
            "m": {"type": "mix", "materials": ["coat", "mirror"], "weight": 0.4,
                  "model": "mitsuba"}},
        "shapes": [{"type": "sphere", "center": [0, 0.5, 0], "radius": 0.5, "material": "m"},
                   {"type": "quad", "corner": [-0.5, 2, -0.5], "edge_u": [1, 0, 0],
                    "edge_v": [0, 0, 1], "emission": [5, 5, 5]}]}"#;
    let desc = parse_scene_in(json, &scenes_dir()).unwrap_or_else(|e| panic!("{e}"));
    assert_round_trip(&desc, "blend_delta");
    let dir = Dir::new("blend_delta_back");
    let (_, back) = round_trip(&desc, &dir, "blend_delta_back");
    let mix = back
        .desc
        .materials
        .iter()
        .find_map(|m| m.mix.as_ref())
        .unwrap();
    assert!(mix.mitsuba, "the model came back");
}

/// A gaussian pixel filter goes out as Mitsuba's `gaussian` rfilter and comes back as the same
/// filter (the same image, bit for bit); a radius other than Mitsuba's 4σ is refused by path.
#[test]
fn a_gaussian_filter_round_trips_and_another_radius_is_refused() {
    let mut desc = kitchen_sink();
    desc.camera.filter = lumis::scene::FilterDesc::Gaussian {
        stddev: 0.5,
        radius: 2.0,
    };
    assert_round_trip(&desc, "gaussian_filter");
    let dir = Dir::new("gaussian_filter_back");
    let (_, back) = round_trip(&desc, &dir, "gaussian_filter_back");
    assert_eq!(back.desc.camera.filter, desc.camera.filter);
    desc.camera.filter = lumis::scene::FilterDesc::Gaussian {
        stddev: 0.5,
        radius: 3.0,
    };
    let dir = Dir::new("gaussian_radius");
    let err = write_export(&desc, &dir.0.join("s.xml"), &ExportOptions::default()).unwrap_err();
    assert!(err.to_string().contains("camera.filter.radius"), "{err}");
}

/// A tent goes out as Mitsuba's `tent` with its radius and comes back the same, rendering the
/// same image bit for bit.
#[test]
fn a_tent_filter_round_trips() {
    let mut desc = kitchen_sink();
    desc.camera.filter = lumis::scene::FilterDesc::Tent { radius: 1.75 };
    assert_round_trip(&desc, "tent_filter");
    let dir = Dir::new("tent_filter_back");
    let (_, back) = round_trip(&desc, &dir, "tent_filter_back");
    assert_eq!(back.desc.camera.filter, desc.camera.filter);
}

/// The filters with negative lobes go out as Mitsuba's `lanczos` (lobes), `mitchell` (B, C) and
/// `catmullrom`, and come back the same, rendering the same image bit for bit.
#[test]
fn signed_filters_round_trip() {
    use lumis::scene::FilterDesc;
    for (filter, name) in [
        (FilterDesc::Lanczos { lobes: 4 }, "lanczos_filter"),
        (
            FilterDesc::Mitchell { b: 0.25, c: 0.375 },
            "mitchell_filter",
        ),
        (FilterDesc::CatmullRom, "catmullrom_filter"),
    ] {
        let mut desc = kitchen_sink();
        desc.camera.filter = filter;
        assert_round_trip(&desc, name);
        let dir = Dir::new(&format!("{name}_back"));
        let (_, back) = round_trip(&desc, &dir, &format!("{name}_back"));
        assert_eq!(back.desc.camera.filter, filter);
    }
}

/// The block z-test at family-wise α = 0.01 (seeds 1 and 2, 64 spp each, 8×8 blocks): the
/// exported `analytic_polygon`, whose emitting polygon becomes a triangle mesh, renders like
/// the JSON with its polygon light. Detects a wrong triangulation or winding of the PLY.
#[test]
fn an_emitting_polygon_renders_like_its_exported_triangles() {
    let desc = load_scene(&scenes_dir().join("analytic_polygon.json")).unwrap();
    let dir = Dir::new("polygon");
    let (_, back) = round_trip(&desc, &dir, "analytic_polygon");
    let scene = |d: &SceneDesc| Arc::new(Scene::from_desc(d).unwrap());
    let a = common::render(&scene(&desc), Settings::default(), 64, 1);
    let b = common::render(&scene(&back.desc), Settings::default(), 64, 2);
    common::assert_unbiased(
        "exported analytic_polygon",
        &common::renders_z_test(&a, &b, 8, 0.01),
    );
}

/// Applies `edit` to the exported XML of `desc` and asserts that the edited scene renders
/// differently: the exact comparison catches that wrong mapping.
fn assert_detected(desc: &SceneDesc, name: &str, edit: impl Fn(&str) -> String) {
    let dir = Dir::new(name);
    let (xml, _) = round_trip(desc, &dir, name);
    let text = std::fs::read_to_string(&xml).unwrap();
    let edited = edit(&text);
    assert_ne!(edited, text, "{name}: the edit changed nothing");
    std::fs::write(&xml, edited).unwrap();
    let back = reimport(&xml);
    let expected = render(&canonical(desc), None);
    let got = render(&back.desc, back.rr_depth);
    assert!(
        difference(&expected, &got).is_some(),
        "{name}: a wrong mapping rendered identically"
    );
}

#[test]
fn wrong_mappings_are_detected() {
    let veach = load_scene(&scenes_dir().join("veach_mis.json")).unwrap();
    // Film width and height swapped.
    assert_detected(&veach, "swapped_size", |t| {
        t.replace("\"width\" value=\"320\"", "\"width\" value=\"180\"")
            .replacen("\"height\" value=\"180\"", "\"height\" value=\"320\"", 1)
    });
    // A rectangle with its normal flipped (its edges swapped on import).
    assert_detected(&veach, "flipped", |t| {
        t.replacen(
            "<shape type=\"rectangle\">",
            "<shape type=\"rectangle\">\n<boolean name=\"flip_normals\" value=\"true\"/>",
            1,
        )
    });
    let sink = kitchen_sink();
    // Mitsuba's default exterior (air, 1.000277) instead of lumis' vacuum.
    assert_detected(&sink, "ext_ior", |t| {
        t.replace("<float name=\"ext_ior\" value=\"1.0\"/>", "")
    });
    // The brushed conductor's scalar checkerboard without its colour swap.
    assert_detected(&sink, "checker_swap", |t| {
        t.replacen(
            "<rgb name=\"color0\" value=\"0.4 0.4 0.4\"/>",
            "<rgb name=\"color0\" value=\"0.05 0.05 0.05\"/>",
            1,
        )
        .replacen(
            "<rgb name=\"color1\" value=\"0.05 0.05 0.05\"/>",
            "<rgb name=\"color1\" value=\"0.4 0.4 0.4\"/>",
            1,
        )
    });
    // The textured projector's horizontal field of view read as the vertical one (its image is
    // twice as wide as high).
    assert_detected(&sink, "projector_fov_axis", |t| {
        t.replacen(
            "<string name=\"fov_axis\" value=\"x\"/>",
            "<string name=\"fov_axis\" value=\"y\"/>",
            1,
        )
    });
    // The directional light reversed.
    assert_detected(&sink, "directional_reversed", |t| {
        let key = "<vector name=\"direction\" value=\"";
        let start = t.find(key).unwrap() + key.len();
        let end = start + t[start..].find('"').unwrap();
        let reversed: Vec<String> = t[start..end]
            .split(' ')
            .map(|v| format!("{:?}", -v.parse::<f64>().unwrap()))
            .collect();
        format!("{}{}{}", &t[..start], reversed.join(" "), &t[end..])
    });
}

#[test]
fn what_mitsuba_cannot_take_is_an_error_naming_the_json_path() {
    let folder = scenes_dir();
    let base = |materials: &str, shapes: &str| {
        format!(
            r#"{{"camera": {{"from": [0, 0, -3], "to": [0, 0, 0], "up": [0, 1, 0],
                "vfov_deg": 40, "width": 8, "height": 8}},
               "materials": {{{materials}}}, "shapes": [{shapes}]}}"#
        )
    };
    let cases = [
        // Mitsuba's blendbsdf weighs a delta lobe against the other part, which only a mix of
        // model mitsuba does.
        (
            base(
                r#""a": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]},
                   "b": {"type": "conductor", "alpha": 0, "reflectance": [1, 1, 1]},
                   "m": {"type": "mix", "materials": ["a", "b"], "weight": 0.5}"#,
                r#"{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}"#,
            ),
            "materials.m",
            "a mix of `b`, which has a delta lobe, cannot be exported",
        ),
        // A mix's textured weight reads texture coordinates, which Mitsuba gives a polygon
        // otherwise.
        (
            base(
                r#""a": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]},
                   "b": {"type": "diffuse", "albedo": [0.1, 0.1, 0.1]},
                   "m": {"type": "mix", "materials": ["a", "b"],
                         "weight": {"type": "checkerboard"}}"#,
                r#"{"type": "polygon", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
                    "material": "m"}"#,
            ),
            "shapes[0]",
            "textured polygon",
        ),
        (
            base(
                r#""t": {"type": "diffuse", "albedo": {"type": "checkerboard"}}"#,
                r#"{"type": "polygon", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
                    "material": "t"}"#,
            ),
            "shapes[0]",
            "textured polygon",
        ),
        (
            base(
                r#""p": {"type": "plastic", "albedo": [0.5, 0.5, 0.5],
                         "alpha": {"type": "checkerboard"}}"#,
                r#"{"type": "quad", "corner": [0, 0, 0], "edge_u": [1, 0, 0],
                    "edge_v": [0, 1, 0], "material": "p"}"#,
            ),
            "materials.p.alpha",
            "plastic",
        ),
        (
            base(
                r#""s": {"type": "diffuse", "albedo": {"type": "bitmap",
                         "file": "textured_mesh_albedo.png", "scale": 0.5}}"#,
                r#"{"type": "quad", "corner": [0, 0, 0], "edge_u": [1, 0, 0],
                    "edge_v": [0, 1, 0], "material": "s"}"#,
            ),
            "materials.s",
            "scale",
        ),
    ];
    // A light's bitmap with a `scale`, which Mitsuba's bitmap does not have.
    let spot = r#"{"camera": {"from": [0, 0, -3], "to": [0, 0, 0], "up": [0, 1, 0],
                    "vfov_deg": 40, "width": 8, "height": 8}, "shapes": [],
                   "lights": [{"type": "point", "position": [0, 1, 0], "intensity": [1, 1, 1]},
                              {"type": "spot", "from": [0, 1, 0], "to": [0, 0, 0],
                               "up": [0, 0, 1], "intensity": [1, 1, 1], "texture": {"type": "bitmap",
                               "file": "textured_mesh_albedo.png", "scale": 0.5}}]}"#;
    let cases = cases
        .into_iter()
        .chain([(spot.to_owned(), "lights[1].texture", "scale")]);
    let dir = Dir::new("errors");
    for (json, path, words) in cases {
        let desc = parse_scene_in(&json, &folder).unwrap_or_else(|e| panic!("{e}\n{json}"));
        let xml = dir.0.join("e.xml");
        let e = write_export(&desc, &xml, &ExportOptions::default())
            .expect_err("an inexpressible scene was exported");
        assert_eq!(e.path, path, "{e}");
        assert!(e.message.contains(words), "{e}");
        assert!(!xml.exists(), "nothing is written for a refused scene");
    }
}

/// The exporter's nudged rectangle transform gives the importer back every quad (random, seed
/// 3) as lumis builds it: edges exact in `f64`, the corner exact in `f32` (what the quad is built
/// from) and within an ulp of the translation in `f64`. Exact `f64` is impossible where `|translation| > |corner|`
/// leaves the importer's `translation + (−x − y)` no representable translation that sums to
/// the corner (the nudge gets every other one exact).
#[test]
fn quad_corners_come_back_exactly() {
    let mut rng = lumis::rng::Rng::new(3, 0, 0);
    let mut r = || (rng.next_f32() as f64 - 0.5) * 10.0 + rng.next_f32() as f64 * 1e-7;
    let mut shapes = Vec::new();
    let mut quads = Vec::new();
    for _ in 0..200 {
        let (c, u, v) = (
            DVec3::new(r(), r(), r()),
            DVec3::new(r(), r(), r()),
            DVec3::new(r(), r(), r()),
        );
        quads.push((c, u, v));
        shapes.push(format!(
            r#"{{"type": "quad", "corner": {:?}, "edge_u": {:?}, "edge_v": {:?}}}"#,
            c.to_array(),
            u.to_array(),
            v.to_array()
        ));
    }
    let json = format!(
        r#"{{"camera": {{"from": [0, 0, -30], "to": [0, 0, 0], "up": [0, 1, 0],
            "vfov_deg": 40, "width": 8, "height": 8}}, "shapes": [{}]}}"#,
        shapes.join(",")
    );
    let desc = parse_scene_in(&json, Path::new("")).unwrap();
    let dir = Dir::new("corners");
    let (_, back) = round_trip(&desc, &dir, "corners");
    assert_eq!(back.desc.shapes.len(), quads.len());
    let mut exact = 0;
    for (s, (c, u, v)) in back.desc.shapes.iter().zip(quads) {
        let GeometryDesc::Quad {
            corner,
            edge_u,
            edge_v,
        } = &s.geometry
        else {
            panic!("{:?}", s.geometry)
        };
        assert_eq!((*edge_u, *edge_v), (u, v), "{}", s.json_path);
        assert_eq!(corner.as_vec3(), c.as_vec3(), "{}", s.json_path);
        for i in 0..3 {
            let (a, b) = (corner[i], c[i]);
            let ulp_t = f64::EPSILON * (c[i].abs() + u[i].abs() + v[i].abs());
            assert!((a - b).abs() <= ulp_t, "{}", s.json_path);
        }
        exact += usize::from(*corner == c);
    }
    println!("{exact} of 200 corners exact in f64");
}

/// A `gltf_pbr` material has no Mitsuba BSDF (Mitsuba's principled is Burley's model, not
/// glTF's): the export is refused at the material's path, naming why, even inside a mix.
#[test]
fn a_gltf_pbr_material_is_refused_by_name() {
    let mut desc = kitchen_sink();
    let m = desc
        .materials
        .iter_mut()
        .find(|m| m.parts().is_none() && !m.material.transmits())
        .expect("a reflecting material");
    let name = m.name.clone();
    m.material = lumis::scene::MaterialDesc::GltfPbr(Default::default());
    m.textures = Default::default();
    let dir = Dir::new("gltf_pbr_refused");
    let err = write_export(&desc, &dir.0.join("s.xml"), &ExportOptions::default()).unwrap_err();
    let err = err.to_string();
    assert!(err.contains("materials") && err.contains(&name), "{err}");
    assert!(
        err.contains("gltf_pbr material cannot be exported"),
        "{err}"
    );
}
