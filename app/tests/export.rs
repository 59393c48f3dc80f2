//! End-to-end tests of `lumis export`: a JSON scene with inline triangles becomes a Mitsuba XML
//! file and a PLY beside it, named after the shape, which `lumis render` then renders to the
//! same pixels as the JSON (same seed and spp; the camera's up is orthogonal to its view, which
//! Mitsuba's lookat frame keeps bit for bit, renderer/tests/mitsuba_export.rs `canonical`); a scene the exporter cannot express fails with
//! one `lumis: ` line naming the file and the JSON path, and writes nothing.

use lumis::image_io::Image;
use std::path::PathBuf;
use std::process::{Command, Output};

/// A temporary directory, removed when dropped.
struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> TempDir {
        let dir =
            std::env::temp_dir().join(format!("lumis-export-cli-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("create temp dir");
        TempDir(dir)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn lumis(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lumis"))
        .args(args)
        .output()
        .expect("run lumis")
}

/// A floor quad, a triangle and a downward quad light; `extra` goes into `materials`.
fn scene(material: &str, extra: &str) -> String {
    format!(
        r#"{{
  "camera": {{"from": [0, 1, -3], "to": [0, 1, 0], "up": [0, 1, 0], "vfov_deg": 70,
              "width": 20, "height": 14}},
  "max_depth": 3,
  "materials": {{"floor": {{"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}}{extra}}},
  "shapes": [
    {{"type": "quad", "corner": [-2, 0, -2], "edge_u": [0, 0, 4], "edge_v": [4, 0, 0],
      "material": "floor"}},
    {{"type": "triangles", "positions": [[-0.5, 0, 0], [0.5, 0, 0], [0, 0.8, 0.2]],
      "indices": [[0, 2, 1]], "material": "{material}"}},
    {{"type": "quad", "corner": [-0.5, 2, -0.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1],
      "emission": [4, 4, 4]}}
  ]
}}"#
    )
}

#[test]
fn export_writes_xml_and_ply_that_render_like_the_json() {
    let dir = TempDir::new("ok");
    let json = dir.0.join("scene.json");
    std::fs::write(&json, scene("floor", "")).unwrap();
    let xml = dir.0.join("out.xml");
    let out = lumis(&[
        "export",
        json.to_str().unwrap(),
        "-o",
        xml.to_str().unwrap(),
        "--spp",
        "3",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let ply = dir.0.join("out_shapes_1.ply");
    assert!(ply.is_file(), "no {}", ply.display());
    let text = std::fs::read_to_string(&xml).unwrap();
    assert!(text.contains("out_shapes_1.ply") && text.contains("\"sample_count\" value=\"3\""));
    let render = |scene: &PathBuf, image: &str, spp: &[&str]| {
        let path = dir.0.join(image);
        let mut args = vec![
            "render",
            scene.to_str().unwrap(),
            "-o",
            path.to_str().unwrap(),
        ];
        args.extend(spp);
        let out = lumis(&args);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        Image::read(&path).unwrap()
    };
    let a = render(&json, "a.exr", &["--spp", "3"]);
    // The XML's sample_count is the default spp.
    let b = render(&xml, "b.exr", &[]);
    assert_eq!((a.width, a.height), (b.width, b.height));
    assert!(a.data == b.data, "the exported scene renders differently");
}

#[test]
fn an_inexpressible_scene_is_one_error_line_and_writes_nothing() {
    let dir = TempDir::new("err");
    let json = dir.0.join("mix.json");
    // A mix with a delta lobe: Mitsuba's blendbsdf would weigh it differently (docs/mitsuba.md).
    let mix = r#", "mirror": {"type": "conductor", "alpha": 0, "reflectance": [0.9, 0.9, 0.9]},
        "m": {"type": "mix", "materials": ["floor", "mirror"], "weight": 0.5}"#;
    std::fs::write(&json, scene("m", mix)).unwrap();
    let xml = dir.0.join("out.xml");
    let out = lumis(&[
        "export",
        json.to_str().unwrap(),
        "-o",
        xml.to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(
        err.starts_with("lumis: ") && err.contains("mix.json") && err.contains("materials.m"),
        "{err}"
    );
    assert!(!xml.exists() && !dir.0.join("out_shapes_1.ply").exists());
    // The output must be .xml.
    let out = lumis(&[
        "export",
        json.to_str().unwrap(),
        "-o",
        dir.0.join("x.json").to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains(".xml"));
}
