//! Scene files other than JSON through the command line: warnings, a model file on its own, XML
//! scenes with their defaults and `-D` overrides.

use super::*;

/// A scene's warnings (here a dropped zero-area triangle, which leaves its shape empty) reach
/// stderr, one line each, and the render still succeeds.
#[test]
fn scene_warnings_are_printed() {
    let dir = TempDir::new("warnings");
    let json = scene_json(8, 8).replace(
        r#""shapes": ["#,
        r#""shapes": [
    {"type": "triangles", "positions": [[0, 0, 0], [1, 0, 0], [2, 0, 0]], "indices": [[0, 1, 2]],
     "material": "floor"},"#,
    );
    let scene = dir.path("warn.json");
    std::fs::write(&scene, json).unwrap();
    let out = dir.path("warn.exr");
    let output = lumis([
        "render".as_ref(),
        scene.as_os_str(),
        "--spp".as_ref(),
        "1".as_ref(),
        "-o".as_ref(),
        out.as_os_str(),
    ]);
    let stderr = text(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    let lines: Vec<&str> = stderr.lines().collect();
    assert_eq!(lines.len(), 2, "{stderr}");
    assert!(
        lines
            .iter()
            .all(|l| l.starts_with("warning: ") && l.contains("warn.json")),
        "{stderr}"
    );
    assert!(
        lines[0].contains("dropped 1 zero-area triangle"),
        "{stderr}"
    );
    assert!(lines[1].contains("no triangles"), "{stderr}");
}

/// A mesh file renders on its own (`scene/model.rs`): a convex tetrahedron (diffuse 0.8) under the
/// white environment (1) that `--no-studio` gives. With BSDF sampling every sample is exact (a
/// ray leaving a convex object escapes to the environment: 0.8 × 1), so every pixel lies between
/// 0.8 (the model) and 1 (the environment), and the model fills part of the frame. Without the
/// flag the studio's grey ground fills the background (the image's bottom corners, below the
/// model, are far darker than 1): the flag reaches the scene.
#[test]
fn a_model_file_renders_on_its_own() {
    let dir = TempDir::new("model");
    let obj = dir.path("tet.obj");
    std::fs::write(
        &obj,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    )
    .unwrap();
    let out = dir.path("tet.exr");
    let stats = render(
        &obj,
        &out,
        &["--spp", "4", "--strategy", "bsdf", "--no-studio"],
    );
    assert_eq!(stats.nonfinite, 0);
    let img = read(&out);
    assert_eq!((img.width, img.height), (640, 480));
    let lum: Vec<f32> = img.data.iter().map(|p| (p.x + p.y + p.z) / 3.0).collect();
    // A ray leaving a point on an edge between two faces, offset along one face's normal, can
    // hit the neighbouring face next to the edge (measured: one sample of 1.2M, at pixel
    // (447, 319)); so a few pixels may fall below 0.8, never above 1.
    let outside = lum
        .iter()
        .filter(|&&x| !(0.8 - 1e-4..=1.0 + 1e-4).contains(&x))
        .count();
    assert!(outside <= 30, "{outside} pixels outside [0.8, 1]");
    assert!(lum.iter().all(|&x| x <= 1.0 + 1e-4));
    let model = lum.iter().filter(|&&x| x < 0.81).count() as f32 / lum.len() as f32;
    assert!(
        (0.05..0.9).contains(&model),
        "the model covers {model} of the frame"
    );

    let studio = dir.path("tet_studio.exr");
    render(&obj, &studio, &["--spp", "2", "--resolution-scale", "0.1"]);
    let img = read(&studio);
    let (w, h) = (img.width as usize, img.height as usize);
    for corner in [img.data[(h - 1) * w], img.data[h * w - 1]] {
        assert!(
            corner.max_element() < 0.5,
            "{corner}: not the studio's ground"
        );
    }
}

/// A Mitsuba XML scene with `<default>` parameters: a twosided diffuse floor of reflectance
/// `$albedo` under a downward rectangle light the camera does not see, direct light only
/// (`max_depth` 2), `$spp` samples.
const XML_SCENE: &str = r#"<scene version="3.0.0">
    <default name="albedo" value="0.5"/>
    <default name="spp" value="4"/>
    <integrator type="path"><integer name="max_depth" value="2"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="50"/>
        <transform name="to_world"><lookat origin="0, 1, -3" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
        <film type="hdrfilm">
            <integer name="width" value="16"/><integer name="height" value="12"/>
            <rfilter type="box"/>
        </film>
    </sensor>
    <shape type="rectangle">
        <transform name="to_world"><scale value="3"/><rotate x="1" angle="-90"/></transform>
        <bsdf type="twosided">
            <bsdf type="diffuse"><rgb name="reflectance" value="$albedo"/></bsdf>
        </bsdf>
    </shape>
    <shape type="rectangle">
        <transform name="to_world"><scale value="0.5"/><rotate x="1" angle="90"/><translate y="2"/></transform>
        <emitter type="area"><rgb name="radiance" value="10"/></emitter>
    </shape>
</scene>
"#;

/// `lumis render scene.xml` reads Mitsuba XML by its extension, takes the spp of its sampler,
/// and `-D name=value` overrides its `<default>`s as Mitsuba's `-D` does: `-D albedo=0.25` halves
/// every pixel (same seed, the same draws: direct light is linear in the floor's albedo), `-D
/// spp=8` renders 8 samples; `-D` with a JSON scene, and a value that is not a number, are one
/// error naming the file (and the XML line). Catches `-D` ignored, applied to the wrong file,
/// or the XML's spp not used.
#[test]
fn xml_scenes_render_with_their_defaults_and_d_overrides() {
    let dir = TempDir::new("xml");
    let xml = dir.write("scene.xml", XML_SCENE);
    let (a, b, c) = (dir.path("a.exr"), dir.path("b.exr"), dir.path("c.exr"));
    assert_eq!(render(&xml, &a, &["--seed", "3"]).spp, 4);
    assert_eq!(
        render(&xml, &b, &["--seed", "3", "-D", "albedo=0.25"]).spp,
        4
    );
    assert_eq!(render(&xml, &c, &["-D", "spp=8"]).spp, 8);
    let (a, b) = (read(&a), read(&b));
    assert!(check_pixels(&a, 16, 12));
    for (i, (pa, pb)) in a.data.iter().zip(&b.data).enumerate() {
        assert!(
            (*pb - 0.5 * *pa).abs().max_element() <= 1e-5 * pa.max_element(),
            "pixel {i}: {pa} with albedo 0.5, {pb} with 0.25"
        );
    }
    let out = dir.path("bad.exr");
    let bad = lumis([
        OsStr::new("render"),
        xml.as_os_str(),
        OsStr::new("-D"),
        OsStr::new("albedo=dark"),
        OsStr::new("-o"),
        out.as_os_str(),
    ]);
    expect_error(&bad, &["scene.xml:", "dark"]);
    let json = dir.scene(8, 8);
    let bad = lumis([
        OsStr::new("render"),
        json.as_os_str(),
        OsStr::new("--spp"),
        OsStr::new("1"),
        OsStr::new("-D"),
        OsStr::new("albedo=0.25"),
        OsStr::new("-o"),
        out.as_os_str(),
    ]);
    expect_error(&bad, &["scene_8x8.json", "-D albedo=0.25", ".xml"]);
}

/// `--width`, `--height` and `--resolution-scale` (issue 37 item 4) size the image of every
/// scene format alike: a Mitsuba XML scene (16 × 12), a JSON scene (8 × 8) and a model file
/// (640 × 480); one of width and height given alone keeps the aspect ratio; a bad scale and a
/// scale with a width are one-line errors. The field of view and filter staying the scene's is
/// `ImageSize::apply`'s unit test. Catches an option ignored by one format or command.
#[test]
fn image_size_options_size_every_scene_format() {
    let dir = TempDir::new("image-size");
    let xml = dir.write("scene.xml", XML_SCENE);
    let json = dir.scene(8, 8);
    let obj = dir.write(
        "tet.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    );
    let cases: [(&Path, &[&str], (u32, u32)); 6] = [
        (&xml, &["--resolution-scale", "0.5"], (8, 6)),
        (&xml, &["--width", "8"], (8, 6)),
        (&xml, &["--height", "3"], (4, 3)),
        (&xml, &["--width", "5", "--height", "7"], (5, 7)),
        (&json, &["--spp", "1", "--resolution-scale", "2"], (16, 16)),
        (
            &obj,
            &["--spp", "1", "--resolution-scale", "0.05"],
            (32, 24),
        ),
    ];
    for (i, (scene, opts, (w, h))) in cases.iter().enumerate() {
        let out = dir.path(&format!("{i}.exr"));
        render(scene, &out, opts);
        let img = read(&out);
        assert!(check_pixels(&img, *w, *h), "case {i}: black image");
    }
    let out = dir.path("bad.exr");
    for (opts, needle) in [
        (
            &["--resolution-scale", "0"][..],
            "--resolution-scale 0 must be a positive number",
        ),
        (
            &["--resolution-scale", "0.5", "--width", "4"][..],
            "cannot be used with",
        ),
    ] {
        let mut args = vec![OsStr::new("render"), xml.as_os_str()];
        args.extend(opts.iter().map(OsStr::new));
        args.extend([OsStr::new("-o"), out.as_os_str()]);
        expect_error(&lumis(&args), &[needle]);
    }
}
