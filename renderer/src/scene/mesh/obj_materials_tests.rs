//! Tests of an OBJ file opened on its own: grouping by material, the `.mtl` mapping rule of
//! docs/scene-format.md ("OBJ materials"), the warnings and the errors, on small texts through
//! `load_obj_model_bytes` (and once through files).

use super::*;
use crate::scene::mesh::ply::tests::test_dir;
use glam::{Vec2, Vec3};

/// The OBJ's path in these tests: its folder is `models`.
fn obj_path() -> PathBuf {
    PathBuf::from("models/car.obj")
}

/// `obj` with the `.mtl` files `mtls` (paths relative to the OBJ's folder).
fn read(obj: &str, mtls: &[(&str, &str)]) -> Result<ObjModel, MeshError> {
    let mtls: Vec<(PathBuf, Vec<u8>)> = mtls
        .iter()
        .map(|(name, text)| (Path::new("models").join(name), text.as_bytes().to_vec()))
        .collect();
    let supply = |p: &Path| mtls.iter().find(|(q, _)| q == p).map(|(_, b)| b.clone());
    load_obj_model_bytes(&obj_path(), obj.as_bytes(), &supply)
}

fn model(obj: &str, mtls: &[(&str, &str)]) -> ObjModel {
    read(obj, mtls).unwrap_or_else(|e| panic!("{e}"))
}

const SQUARE: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

/// One material `name` with `body` (its statements) on the square's one triangle, mapped.
fn one(name: &str, body: &str) -> (ObjMaterial, Vec<String>) {
    let obj = format!("mtllib car.mtl\n{SQUARE}usemtl {name}\nf 1 2 3\n");
    let mtl = format!("newmtl {name}\n{body}");
    let m = model(&obj, &[("car.mtl", &mtl)]);
    assert_eq!(m.groups.len(), 1);
    assert_eq!(m.groups[0].material, Some(0));
    (m.materials[0].clone(), m.warnings)
}

fn json_of(body: &str) -> Value {
    one("M", body).0.json
}

/// Catches faces grouped by model (tobj splits at every `g` and material change) instead of by
/// material, a group order other than first use, unknown names not joining the default group,
/// and materials listed that no face uses.
#[test]
fn faces_are_grouped_by_material_in_order_of_first_use() {
    let obj = format!(
        "mtllib car.mtl\n{SQUARE}v 2 0 0\nv 2 1 0\n\
         f 1 2 3\n\
         usemtl Paint\nf 2 5 6\n\
         g glass\nusemtl Glass\nf 1 3 4\n\
         g body\nusemtl Paint\nf 2 6 3\nusemtl Nowhere\nf 4 3 6\n"
    );
    let mtl = "newmtl Glass\nKd 0 0 1\nnewmtl Paint\nKd 1 0 0\nnewmtl Unused\nKd 0 1 0\n";
    let m = model(&obj, &[("car.mtl", mtl)]);
    let summary: Vec<(Option<&str>, usize)> = m
        .groups
        .iter()
        .map(|g| {
            let name = g.material.map(|k| m.materials[k].name.as_str());
            (name, g.mesh.indices.len())
        })
        .collect();
    assert_eq!(summary, [(None, 2), (Some("Paint"), 2), (Some("Glass"), 1)]);
    assert_eq!(m.materials.len(), 2);
    // Each group has only the vertices its faces use, numbered in first-use order.
    let paint = &m.groups[1].mesh;
    let p = |x: f32, y: f32| Vec3::new(x, y, 0.0);
    assert_eq!(
        paint.positions,
        [
            p(1.0, 0.0),
            p(2.0, 0.0),
            p(2.0, 1.0),
            p(1.0, 0.0),
            p(2.0, 1.0),
            p(1.0, 1.0)
        ]
    );
    assert_eq!(paint.indices, [[0, 1, 2], [3, 4, 5]]);
    assert_eq!(
        m.warnings,
        [
            "usemtl names a material no .mtl file defines: 'Nowhere' (line 17) (its faces get \
          lumis' default material)"
        ]
    );
}

/// Catches normals or texture coordinates decided over the whole file rather than per group,
/// and a lost `1 − v` flip.
#[test]
fn normals_and_texture_coordinates_are_kept_per_group() {
    let obj = format!(
        "mtllib car.mtl\n{SQUARE}vt 0.25 0.75\nvn 0 0 1\n\
         usemtl A\nf 1/1/1 2/1/1 3/1/1\nusemtl B\nf 1 3 4\n"
    );
    let m = model(&obj, &[("car.mtl", "newmtl A\nnewmtl B\n")]);
    let (a, b) = (&m.groups[0].mesh, &m.groups[1].mesh);
    assert_eq!(a.normals, Some(vec![Vec3::Z; 3]));
    assert_eq!(a.uvs, Some(vec![Vec2::new(0.25, 0.25); 3]));
    assert_eq!((b.normals.as_ref(), b.uvs.as_ref()), (None, None));
    // The plain reader sees one mesh, and so none of them.
    let merged = super::super::obj::load_bytes(&obj_path(), obj.as_bytes()).unwrap();
    assert_eq!((merged.normals, merged.uvs), (None, None));
}

/// A `usemtl` before the `mtllib` line still finds its material (every library is read before
/// the faces are grouped); a name defined twice takes its last definition; an `mtllib` of two
/// files reads both.
#[test]
fn every_library_is_read_before_grouping() {
    let obj = format!("usemtl Late\n{SQUARE}f 1 2 3\nmtllib a.mtl b.mtl\nusemtl Twice\nf 1 3 4\n");
    let m = model(
        &obj,
        &[
            (
                "a.mtl",
                "newmtl Late\nKd 0.1 0.1 0.1\nnewmtl Twice\nKd 0.2 0.2 0.2\n",
            ),
            ("b.mtl", "newmtl Twice\nKd 0.3 0.3 0.3\n"),
        ],
    );
    assert!(m.warnings.is_empty(), "{:?}", m.warnings);
    let albedo: Vec<&Value> = m.materials.iter().map(|x| &x.json["albedo"]).collect();
    assert_eq!(albedo, [&json!([0.1, 0.1, 0.1]), &json!([0.3, 0.3, 0.3])]);
}

#[test]
fn kd_is_the_albedo_grey_when_missing_and_clamped() {
    assert_eq!(
        json_of("Kd 0.2 0.4 0.6\n"),
        json!({"type": "diffuse", "albedo": [0.2, 0.4, 0.6]})
    );
    assert_eq!(json_of("Kd 0.3\n")["albedo"], json!([0.3, 0.3, 0.3]));
    assert_eq!(json_of("illum 2\n")["albedo"], json!([0.8, 0.8, 0.8]));
    let (m, warnings) = one("Hot", "Kd 1.5 -0.1 0.5\n");
    assert_eq!(m.json["albedo"], json!([1.0, 0.0, 0.5]));
    assert_eq!(
        warnings,
        ["lumis does not render these .mtl statements: mtl 'Hot': Kd (clamped)"]
    );
}

/// The texture's path is the `.mtl`'s folder joined to the name as written (options skipped,
/// spaces kept, `\` turned to `/`), and Kd, where given, its scale.
#[test]
fn map_kd_is_a_bitmap_relative_to_the_obj_scaled_by_kd() {
    let obj = format!("mtllib mats/lib.mtl\n{SQUARE}usemtl A\nf 1 2 3\nusemtl B\nf 1 3 4\n");
    let mtl = "newmtl A\nKd 0.5 0.25 1\nmap_Kd tex\\wood.png\n\
               newmtl B\nmap_kd -s 2 2 -o 0.1 0.2 -clamp on tex/old wood.png\n";
    let m = model(&obj, &[("mats/lib.mtl", mtl)]);
    assert_eq!(
        m.materials[0].json["albedo"],
        json!({"type": "bitmap", "file": "mats/tex/wood.png", "scale": [0.5, 0.25, 1.0]})
    );
    assert_eq!(
        m.materials[1].json["albedo"],
        json!({"type": "bitmap", "file": "mats/tex/old wood.png"})
    );
    assert_eq!(
        m.warnings,
        [
            "lumis does not render these .mtl statements: mtl 'B': map_kd -s, map_kd -o, \
          map_kd -clamp"
        ]
    );
}

/// Ks makes a plastic unless illum is 0 or 1; α follows Walter et al.'s √(2/(Ns + 2)) within
/// [0.001, 1]; `ior` is Ni within (1, 10], else 1.5.
#[test]
fn ks_makes_a_plastic_with_alpha_from_ns_and_ior_from_ni() {
    let plastic = json_of("Kd 0.1 0.2 0.3\nKs 0.5 0.5 0.5\nNs 98\nNi 1.33\n");
    assert_eq!(
        plastic,
        json!({"type": "plastic", "albedo": [0.1, 0.2, 0.3], "alpha": 0.02f64.sqrt(),
               "ior": 1.33})
    );
    let cases = [
        ("Ks 0 0 0.01\n", Some((1.0, 1.5))),
        ("Ks 1 1 1\nNs 1e9\nNi 12\n", Some((0.001, 1.5))),
        ("Ks 1 1 1\nNs 0\nNi 1\n", Some((1.0, 1.5))),
        ("Ks 1 1 1\nNs 6\nNi 10\n", Some((0.5, 10.0))),
        ("Ks 1 1 1\nillum 3\n", Some((1.0, 1.5))),
        ("Ks 1 1 1\nillum 1\n", None),
        ("Ks 1 1 1\nillum 0\n", None),
        ("Ks 0 0 0\nNs 100\n", None),
        ("Ks -1 0 0\n", None),
    ];
    for (body, expected) in cases {
        let j = json_of(body);
        match expected {
            Some((alpha, ior)) => {
                assert_eq!(j["type"], "plastic", "{body}");
                assert_eq!(
                    (j["alpha"].as_f64(), j["ior"].as_f64()),
                    (Some(alpha), Some(ior)),
                    "{body}"
                );
            }
            None => assert_eq!(j["type"], "diffuse", "{body}"),
        }
    }
}

/// d below 1 is the opacity; without d, 1 − Tr; d wins over Tr; opaque values give none.
#[test]
fn d_or_tr_is_the_opacity() {
    let cases = [
        ("d 0.25\n", Some(0.25)),
        ("d 1\n", None),
        ("Tr 0.25\n", Some(0.75)),
        ("Tr 0\n", None),
        ("d 0.5\nTr 0.9\n", Some(0.5)),
        ("Tr 0.9\nd 1\n", None),
        ("d -halo 0.5\n", Some(0.5)),
    ];
    for (body, expected) in cases {
        assert_eq!(json_of(body)["opacity"].as_f64(), expected, "{body}");
    }
    let (_, warnings) = one("Ghost", "d -halo 0.5\nd 1.5\n");
    assert_eq!(
        warnings,
        ["lumis does not render these .mtl statements: mtl 'Ghost': d -halo, d (clamped)"]
    );
}

/// A positive Ke is the emission; an emitter's opacity is dropped and named.
#[test]
fn ke_is_the_emission_and_an_emitter_is_not_masked() {
    assert_eq!(one("Lamp", "Ke 2 3 0\n").0.emission, Some([2.0, 3.0, 0.0]));
    assert_eq!(one("Dark", "Ke 0 0 0\n").0.emission, None);
    let (m, warnings) = one("Lamp", "Ke 4 4 4\nd 0.5\n");
    assert_eq!(m.emission, Some([4.0; 3]));
    assert_eq!(m.json.get("opacity"), None);
    assert_eq!(
        warnings,
        [
            "lumis does not render these .mtl statements: mtl 'Lamp': d (an emitting material \
          cannot be masked)"
        ]
    );
}

/// One warning for everything not rendered: by material, each keyword once, in file order;
/// `Ka` and `map_Ka` are not named (ambient light means nothing to a path tracer), nor a white
/// `Tf` (it filters nothing); materials no face uses are not named.
#[test]
fn unrendered_statements_are_one_warning_each_named_once() {
    let obj = format!("mtllib car.mtl\n{SQUARE}usemtl Body\nf 1 2 3\nusemtl Glass\nf 1 3 4\n");
    let mtl = "newmtl Body\nKa 1 1 1\nmap_Ka amb.png\nmap_Bump -bm 0.5 n.png\nmap_Ks s.png\n\
               bump n.png\nmap_Bump n2.png\nKd spectral red.rfl\nillum 2\n\
               Tf 1 1 1\n\
               newmtl Glass\nTf 1 0.5 1\nillum 7\nPr 0.5\n\
               newmtl Unused\nrefl -type sphere r.png\n";
    let m = model(&obj, &[("car.mtl", mtl)]);
    assert_eq!(
        m.warnings,
        [
            "lumis does not render these .mtl statements: mtl 'Body': map_Bump, map_Ks, bump, \
          Kd spectral; mtl 'Glass': Tf, illum 7, Pr"
        ]
    );
    assert_eq!(m.materials[0].json["albedo"], json!([0.8, 0.8, 0.8]));
}

#[test]
fn a_missing_library_is_a_warning_and_the_default_material() {
    let obj = format!("mtllib gone.mtl\n{SQUARE}usemtl Paint\nf 1 2 3\n");
    let m = model(&obj, &[]);
    assert_eq!(m.groups[0].material, None);
    assert!(m.materials.is_empty());
    assert_eq!(
        m.warnings,
        [
            "cannot read the material library models/gone.mtl (line 1) (its materials get \
             lumis' default material)",
            "usemtl names a material no .mtl file defines: 'Paint' (line 6) (its faces get \
             lumis' default material)",
        ]
    );
}

/// Values lumis uses must parse and be finite; the error names the `.mtl`, the line and the
/// material. Catches a NaN passed on into the JSON (where serde_json writes it as null).
#[test]
fn bad_values_name_the_library_line_and_material() {
    let cases = [
        ("Kd nan 0 0\n", "line 2: material 'Body': Kd is NaN"),
        ("Ks 1 inf 1\n", "line 2: material 'Body': Ks is infinite"),
        ("Ke 1e400\n", "line 2: material 'Body': Ke is infinite"),
        (
            "Kd 0.5 0.5\n",
            "line 2: material 'Body': 'Kd' needs 1 or 3 numbers, found 2",
        ),
        (
            "Kd\n",
            "line 2: material 'Body': 'Kd' needs 1 or 3 numbers, found 0",
        ),
        ("Ns x\n", "line 2: material 'Body': Ns: 'x' is not a number"),
        (
            "d 0.5 0.5\n",
            "line 2: material 'Body': 'd' needs one number, found 2",
        ),
        (
            "illum 2.5\n",
            "line 2: material 'Body': illum: '2.5' is not a whole number",
        ),
        (
            "map_Kd -s 2 2\n",
            "line 2: material 'Body': 'map_Kd' without a file name",
        ),
        ("newmtl\n", "line 2: newmtl without a name"),
    ];
    for (body, expected) in cases {
        let obj = format!("mtllib car.mtl\n{SQUARE}usemtl Body\nf 1 2 3\n");
        let mtl = format!("newmtl Body\n{body}");
        let err = read(&obj, &[("car.mtl", &mtl)]).expect_err(body).0;
        assert_eq!(err, format!("models/car.mtl {expected}"), "{body}");
    }
}

/// The OBJ's own errors are `obj.rs`'s, word for word.
#[test]
fn the_objs_errors_are_the_plain_readers() {
    for text in [format!("{SQUARE}f 1 2 9\n"), "v 0 0 0\n".to_owned()] {
        let plain = super::super::obj::load_bytes(&obj_path(), text.as_bytes()).unwrap_err();
        assert_eq!(read(&text, &[]).unwrap_err(), plain);
    }
}

/// The file entry reads the `.mtl` beside the OBJ, as the bytes entry does with it supplied.
#[test]
fn load_obj_model_reads_the_files() {
    let dir = test_dir().join("obj_model");
    std::fs::create_dir_all(dir.join("mats")).unwrap();
    let obj = format!("mtllib mats/m.mtl\n{SQUARE}usemtl A\nf 1 2 3 4\n");
    let mtl = "newmtl A\nKd 0.1 0.2 0.3\nKs 1 1 1\nNs 18\nmap_Kd a.png\n";
    std::fs::write(dir.join("car.obj"), &obj).unwrap();
    std::fs::write(dir.join("mats/m.mtl"), mtl).unwrap();
    let from_file = load_obj_model(&dir.join("car.obj")).unwrap();
    let supply = |p: &Path| (p == dir.join("mats/m.mtl")).then(|| mtl.as_bytes().to_vec());
    let from_bytes = load_obj_model_bytes(&dir.join("car.obj"), obj.as_bytes(), &supply).unwrap();
    assert_eq!(from_file, from_bytes);
    assert_eq!(from_file.materials[0].json["alpha"], json!(0.1f64.sqrt()));
    assert_eq!(from_file.materials[0].json["albedo"]["file"], "mats/a.png");
    std::fs::remove_file(dir.join("mats/m.mtl")).unwrap();
    let without = load_obj_model(&dir.join("car.obj")).unwrap();
    assert_eq!(without.groups[0].material, None);
    assert_eq!(without.warnings.len(), 2);
}

/// Found by `renderer/tests/mesh_mutations/`: a warning quotes the file's words (a `usemtl`
/// name, a keyword), which may hold a line break other than `\n`; it must stay one line.
#[test]
fn warnings_are_one_line_whatever_they_quote() {
    let obj =
        format!("mtllib car.mtl\n{SQUARE}usemtl b\u{b}lue\nf 1 2 3\nusemtl A\u{85}B\nf 1 3 4\n");
    let m = model(&obj, &[("car.mtl", "newmtl A\u{85}B\nmap_Ks s.png\n")]);
    assert_eq!(
        m.warnings,
        [
            r"usemtl names a material no .mtl file defines: 'b\u{b}lue' (line 6) (its faces get lumis' default material)",
            r"lumis does not render these .mtl statements: mtl 'A\u{85}B': map_Ks",
        ]
    );
}

/// A warning names at most ten things, then how many more; missing libraries are one warning,
/// each named once however often the OBJ names it.
#[test]
fn warnings_name_at_most_ten_things() {
    let mut obj = format!("mtllib a.mtl\nmtllib b.mtl\nmtllib a.mtl\n{SQUARE}");
    for k in 0..12 {
        obj += &format!("usemtl m{k}\nf 1 2 3\n");
    }
    let m = model(&obj, &[]);
    let names: Vec<String> = (0..10)
        .map(|k| format!("'m{k}' (line {})", 8 + 2 * k))
        .collect();
    assert_eq!(
        m.warnings,
        [
            "cannot read the material library models/a.mtl (line 1), models/b.mtl (line 2) \
             (its materials get lumis' default material)"
                .to_owned(),
            format!(
                "usemtl names a material no .mtl file defines: {}, and 2 more (its faces get \
                 lumis' default material)",
                names.join(", ")
            ),
        ]
    );
}

/// The mapped materials are materials the scene front end accepts and a scene builds with, with
/// their textures, opacity and emission: catches a key lumis does not know, a value out of its
/// range, or an opacity left on an emitter's material (which the build refuses).
#[test]
fn mapped_materials_pass_the_scene_front_end() {
    let dir = test_dir().join("obj_scene");
    std::fs::create_dir_all(dir.join("mats/tex")).unwrap();
    image::RgbImage::from_pixel(2, 2, image::Rgb([200, 100, 50]))
        .save(dir.join("mats/tex/wood.png"))
        .unwrap();
    let obj = format!(
        "mtllib mats/lib.mtl\n{SQUARE}vt 0 0\nusemtl Wood\nf 1/1 2/1 3/1\nusemtl Glass\nf 1 3 4\n\
         usemtl Lamp\nf 2 3 4\nusemtl Plain\nf 1 2 4\n"
    );
    let mtl = "newmtl Wood\nKd 0.9 0.8 0.7\nKs 0.04 0.04 0.04\nNs 250\nNi 1.45\nd 0.75\n\
               map_Kd -s 2 2 tex\\wood.png\n\
               newmtl Glass\nKd 0.2 0.3 0.4\nTr 0.6\nillum 1\n\
               newmtl Lamp\nKe 10 8 6\nKd 0.5\nd 0.5\n\
               newmtl Plain\nKd 2 2 2\nKs 1 1 1\n";
    std::fs::write(dir.join("car.obj"), &obj).unwrap();
    std::fs::write(dir.join("mats/lib.mtl"), mtl).unwrap();
    let m = load_obj_model(&dir.join("car.obj")).unwrap();
    assert_eq!(m.materials.len(), 4);
    let mut materials = serde_json::Map::new();
    let mut shapes = Vec::new();
    for (k, group) in m.groups.iter().enumerate() {
        let material = &m.materials[group.material.unwrap()];
        materials.insert(format!("m{k}"), material.json.clone());
        let positions: Vec<[f32; 3]> = group.mesh.positions.iter().map(|p| p.to_array()).collect();
        let mut shape = json!({"type": "triangles", "positions": positions,
                               "indices": group.mesh.indices, "material": format!("m{k}")});
        if let Some(e) = material.emission {
            shape["emission"] = json!(e);
        }
        shapes.push(shape);
    }
    let scene = json!({
        "camera": {"from": [0.5, 0.5, 3], "to": [0.5, 0.5, 0], "up": [0, 1, 0], "vfov_deg": 30,
                   "width": 8, "height": 8},
        "materials": materials,
        "shapes": shapes,
    });
    let desc = crate::scene::parse::parse_scene_value_in(&scene, &dir)
        .unwrap_or_else(|e| panic!("{e}\n{scene:#}"));
    crate::scene::Scene::from_desc(&desc).unwrap_or_else(|e| panic!("{e}\n{scene:#}"));
}
