//! The document grammar as Mitsuba 3.9.1 parses it (a part of `renderer/tests/mitsuba_xml.rs`;
//! issue 37 item 1): file resolution through `<path>` and `<include>`, `<alias>`, objects
//! declared at the top level and referenced by id, the integrators lumis maps, and `--spp` as
//! `$spp`. Each expectation is Mitsuba's own answer on the same case, printed by
//! `tools/mitsuba_grammar_check.py` (which builds these cases and loads them with Mitsuba 3.9.1;
//! its output is quoted in docs/mitsuba.md). Each mesh is a triangle whose size names its
//! folder, as in that tool.

use super::*;
use lumis::scene::mitsuba::Params;

/// The meshes of the resolution cases, by file, with the triangle size that names each.
const MESHES: [(&str, f64); 6] = [
    ("m.obj", 1.0),
    ("sub/m.obj", 2.0),
    ("other/m.obj", 3.0),
    ("inc/m.obj", 4.0),
    ("inc/deep/m.obj", 5.0),
    ("inc/only_inc.obj", 6.0),
];

fn meshes(dir: &Dir) {
    for (name, size) in MESHES {
        dir.write(
            name,
            &format!("v 0 0 0\nv {size} 0 0\nv 0 {size} 0\nf 1 2 3\n"),
        );
    }
}

fn xml(body: &str) -> String {
    format!("<scene version=\"3.0.0\">\n{body}\n</scene>\n")
}

fn obj(filename: &str) -> String {
    format!(r#"<shape type="obj"><string name="filename" value="{filename}"/></shape>"#)
}

/// The triangle size of each mesh shape of `m`, in order: which file it was read from.
fn sizes(m: &Imported) -> Vec<f64> {
    m.desc
        .shapes
        .iter()
        .map(|s| match &s.geometry {
            GeometryDesc::Mesh { mesh, .. } => mesh
                .positions
                .iter()
                .map(|p| p.x as f64)
                .fold(0.0, f64::max),
            other => panic!("not a mesh: {other:?}"),
        })
        .collect()
}

fn load(dir: &Dir, file: &str, text: &str) -> Result<Imported, SceneError> {
    let path = dir.write(file, text);
    mitsuba::load(&path, &[])
}

#[test]
fn paths_and_includes_resolve_files_as_mitsuba_does() {
    let dir = Dir::new("grammar-paths");
    meshes(&dir);
    // Case 1: the main file's <path>s newest first, wherever they stand (`other`, given last,
    // wins for every shape, the first one included); the included file's <path> and folder do
    // not count; its nested include is found in its own folder (inc/b.xml, not b.xml).
    dir.write(
        "inc/a.xml",
        &xml(&format!(
            "<path value=\"deep\"/>\n{}\n<include filename=\"b.xml\"/>",
            obj("m.obj")
        )),
    );
    dir.write("inc/b.xml", &xml(&obj("m.obj")));
    dir.write("b.xml", &xml(r#"<shape type="sphere"/>"#));
    let case1 = format!(
        "<path value=\"sub\"/>\n{SENSOR}\n{}\n<include filename=\"inc/a.xml\"/>\n<path value=\"other\"/>",
        obj("m.obj")
    );
    let m = load(&dir, "case1.xml", &xml(&case1)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        sizes(&m),
        [3.0, 3.0, 3.0],
        "Mitsuba: main 3, in_a 3, in_inc_b 3"
    );
    // The JSON names the files relative to the main file's folder.
    assert_eq!(m.json["shapes"][0]["file"], "other/m.obj");
    // Case 2: without <path>, the main folder; a file only beside the included file is not
    // found (Mitsuba: "file not found", at the included file's shape).
    dir.write("inc/c.xml", &xml(&obj("m.obj")));
    let m = load(
        &dir,
        "case2.xml",
        &xml(&format!("{SENSOR}\n<include filename=\"inc/c.xml\"/>")),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(sizes(&m), [1.0]);
    dir.write("inc/d.xml", &xml(&format!("\n{}", obj("only_inc.obj"))));
    let e = load(
        &dir,
        "case2b.xml",
        &xml(&format!("{SENSOR}\n<include filename=\"inc/d.xml\"/>")),
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("d.xml:3:") && e.contains("only_inc.obj"), "{e}");
    // Case 3: <path> only under the root, and its folder must exist.
    let e = load(
        &dir,
        "case3.xml",
        &xml(r#"<shape type="sphere"><path value="sub"/></shape>"#),
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("case3.xml:2:") && e.contains("child of the root"),
        "{e}"
    );
    let e = load(&dir, "case3b.xml", &xml(r#"<path value="nowhere"/>"#))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("case3b.xml:2:") && e.contains("no folder `nowhere`"),
        "{e}"
    );
}

#[test]
fn spectrum_files_resolve_through_the_main_file() {
    // Case 4: a spectrum file named in an included file is the main folder's (0.9), not the
    // one beside the included file (0.1).
    let dir = Dir::new("grammar-spectrum");
    dir.write("s.spd", "400 0.9\n700 0.9\n");
    dir.write("inc/s.spd", "400 0.1\n700 0.1\n");
    dir.write(
        "inc/spec.xml",
        &xml(r#"<bsdf type="diffuse" id="sp"><spectrum name="reflectance" filename="s.spd"/></bsdf>"#),
    );
    let m = ok(
        &dir,
        r#"<include filename="inc/spec.xml"/>
<shape type="sphere"><ref id="sp"/></shape>"#,
    );
    let albedo = &m.json["materials"]["sp"]["albedo"];
    let g = albedo[1].as_f64().unwrap();
    assert!(
        (g - 0.899781).abs() < 2e-3,
        "Mitsuba: 0.895808 0.899781 0.895418; lumis {albedo}"
    );
}

#[test]
fn aliases_follow_document_order() {
    let dir = Dir::new("grammar-alias");
    // Case 5c: an alias inside an object names the same object.
    let m = ok(
        &dir,
        r#"<bsdf type="diffuse" id="white"><rgb name="reflectance" value="0.25"/></bsdf>
<shape type="sphere"><alias id="white" as="w3"/><ref id="w3"/></shape>"#,
    );
    assert_eq!(m.json["shapes"][0]["material"], "white");
    // Case 5a: the source must be defined before the alias; 5b: the new name must be free.
    refused(
        &dir,
        r#"<alias id="white" as="w2"/>
<bsdf type="diffuse" id="white"/>"#,
        "<alias",
        "scene/alias@id",
        "not defined before this point",
    );
    refused(
        &dir,
        r#"<bsdf type="diffuse" id="white"/>
<bsdf type="conductor" id="c"/>
<alias id="white" as="c"/>"#,
        "<alias",
        "scene/alias@as",
        "already the id of",
    );
}

#[test]
fn top_level_declarations_are_taken_where_referenced() {
    let dir = Dir::new("grammar-declarations");
    let area = r#"<emitter type="area" id="a"><rgb name="radiance" value="2"/></emitter>"#;
    // Case 6a: an area emitter at the top level, referenced by a shape: one emitter.
    let m = ok(
        &dir,
        &format!("{area}\n<shape type=\"sphere\"><ref id=\"a\"/></shape>"),
    );
    assert_eq!(m.desc.shapes.len(), 1);
    assert_eq!(m.desc.shapes[0].emission, DVec3::splat(2.0));
    assert!(m.desc.warnings.is_empty(), "{:?}", m.desc.warnings);
    // 6b: referenced by none, it emits nothing (Mitsuba: no emitter), with a warning.
    let m = ok(&dir, &format!("{area}\n<shape type=\"sphere\"/>"));
    assert_eq!(m.desc.shapes[0].emission, DVec3::ZERO);
    assert!(
        m.desc.warnings.iter().any(|w| w.contains("no shape takes")),
        "{:?}",
        m.desc.warnings
    );
    // 6c: referenced by two shapes, refused as Mitsuba refuses it.
    refused(
        &dir,
        &format!(
            "{area}\n<shape type=\"sphere\"><ref id=\"a\"/></shape>\n<shape type=\"sphere\" id=\"second\"><ref id=\"a\"/></shape>"
        ),
        "id=\"second\"",
        "scene/shape[2]/ref",
        "already attached to the shape at",
    );
    // Case 7: a sampler declared at the top level and referenced by the sensor.
    let text = xml(
        r#"<sampler type="independent" id="smp"><integer name="sample_count" value="7"/></sampler>
<sensor type="perspective"><ref id="smp"/><film type="hdrfilm"><integer name="width" value="8"/>
<integer name="height" value="8"/></film></sensor>"#,
    );
    let m = import(&dir, &text, &[]).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(m.spp, 7);
}

/// `body` with the standard sensor and a sphere, imported; the integrator is in `body`.
fn with_integrator(dir: &Dir, body: &str) -> Result<Imported, SceneError> {
    import(
        dir,
        &scene(&format!("{body}\n<shape type=\"sphere\"/>")),
        &[],
    )
}

#[test]
fn integrators_map_with_mitsubas_defaults() {
    let dir = Dir::new("grammar-integrators");
    let depth = |body: &str| {
        let m = with_integrator(&dir, body).unwrap_or_else(|e| panic!("{e}"));
        (m.desc.max_depth, m.rr_depth, m.desc.hide_emitters)
    };
    // Case 8: Mitsuba's defaults (max_depth −1 for path and ptracer, 6 for the prb family).
    assert_eq!(depth(r#"<integrator type="path"/>"#), (-1, Some(5), false));
    assert_eq!(
        depth(r#"<integrator type="ptracer"/>"#),
        (-1, Some(5), false)
    );
    for ty in ["prb", "prb_basic", "prb_projective"] {
        assert_eq!(
            depth(&format!("<integrator type=\"{ty}\"/>")),
            (6, Some(5), false),
            "{ty}"
        );
    }
    // Gradient-only parameters change no image; direct_projective fixes its depth at 2.
    assert_eq!(
        depth(
            r#"<integrator type="prb_projective"><integer name="sppc" value="4"/>
<string name="guiding" value="grid"/><integer name="max_depth" value="3"/></integrator>"#
        ),
        (3, Some(5), false)
    );
    assert_eq!(
        depth(
            r#"<integrator type="direct_projective"><integer name="max_depth" value="5"/></integrator>"#
        ),
        (2, None, false)
    );
    // moment renders its nested integrator.
    assert_eq!(
        depth(
            r#"<integrator type="moment"><integrator type="path"><integer name="max_depth" value="3"/></integrator></integrator>"#
        ),
        (3, Some(5), false)
    );
    assert_eq!(
        depth(
            r#"<integrator type="direct"><boolean name="hide_emitters" value="true"/></integrator>"#
        ),
        (2, None, true)
    );
    let e = with_integrator(
        &dir,
        r#"<integrator type="moment"><integrator type="path"/><integrator type="direct"/></integrator>"#,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("scene/integrator/integrator[2]") && e.contains("renders one"),
        "{e}"
    );
    // ptracer cannot see through a delta BSDF: refused where the scene has one.
    let e = import(
        &dir,
        &scene(
            r#"<integrator type="ptracer"/>
<shape type="sphere"><bsdf type="dielectric" id="glass"/></shape>"#,
        ),
        &[],
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("scene/integrator") && e.contains("`glass`") && e.contains("particle tracer"),
        "{e}"
    );
    // Nor through a mask, whose camera connections stop at it.
    let e = import(
        &dir,
        &scene(
            r#"<integrator type="ptracer"/>
<shape type="sphere"><bsdf type="mask" id="leaf"><bsdf type="diffuse"/></bsdf></shape>"#,
        ),
        &[],
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("scene/integrator") && e.contains("`leaf`") && e.contains("a mask"),
        "{e}"
    );
}

#[test]
fn spp_option_gives_the_spp_parameter() {
    let dir = Dir::new("grammar-spp");
    let text = xml(&format!(
        "<default name=\"spp\" value=\"14\"/>\n{}",
        SENSOR.replace(
            "<film",
            "<sampler type=\"independent\"><integer name=\"sample_count\" value=\"$spp\"/></sampler><film"
        )
    ));
    let path = dir.write("scene.xml", &text);
    let load = |defines: &[(&str, &str)], spp| {
        let params = Params {
            defines: defines
                .iter()
                .map(|(a, b)| (a.to_string(), b.to_string()))
                .collect(),
            spp,
        };
        mitsuba::load_params(&path, &params)
            .unwrap_or_else(|e| panic!("{e}"))
            .spp
    };
    // Case 9: as Mitsuba's spp=3 over a default of 14; -D spp takes precedence.
    assert_eq!(load(&[], None), 14);
    assert_eq!(load(&[], Some(3)), 3);
    assert_eq!(load(&[("spp", "5")], Some(3)), 5);
    // A scene without $spp takes --spp without complaint (lumis' option, not a -D).
    let other = dir.write("plain.xml", &scene(""));
    let params = Params {
        defines: Vec::new(),
        spp: Some(3),
    };
    assert!(mitsuba::load_params(&other, &params).is_ok());
    // Undefined, the error says how to give it.
    let bare = dir.write(
        "bare.xml",
        &xml(&SENSOR.replace(
            "<film",
            "<sampler type=\"independent\"><integer name=\"sample_count\" value=\"$spp\"/></sampler><film",
        )),
    );
    let e = mitsuba::load(&bare, &[]).unwrap_err().to_string();
    assert!(
        e.contains("undefined parameter `$spp`") && e.contains("--spp"),
        "{e}"
    );
}
