//! The Mitsuba importer's textures and refusals (a part of `renderer/tests/mitsuba_xml.rs`): every
//! unsupported feature, and every error the JSON validation finds, is one error naming the
//! file, line and element path.

use super::*;

#[test]
fn textures_map_with_their_options() {
    let dir = Dir::new("textures");
    let img = lumis::image_io::Image {
        width: 2,
        height: 2,
        data: vec![glam::Vec3::new(0.2, 0.4, 0.6); 4],
    };
    img.write(&dir.0.join("wood.png"), 0.0).unwrap();
    let body = r#"<shape type="rectangle"><bsdf type="diffuse" id="wood">
    <texture name="reflectance" type="bitmap"><string name="filename" value="wood.png"/>
        <string name="wrap_mode" value="mirror"/><boolean name="raw" value="true"/>
        <transform name="to_uv"><scale x="4" y="2"/><translate x="0.5" y="0.25"/></transform>
    </texture></bsdf></shape>
<shape type="rectangle"><bsdf type="roughconductor" id="checked"><string name="distribution" value="ggx"/>
    <texture name="alpha" type="checkerboard"><float name="color0" value="0.1"/><float name="color1" value="0.3"/></texture>
</bsdf></shape>"#;
    let m = ok(&dir, body);
    // to_uv: u' = 4u + 0.5, v' = 2v + 0.25; Mitsuba's eval_1 swaps a checkerboard's colours.
    let want = expected(
        &dir,
        json!({
            "materials": {
                "wood": {"type": "diffuse", "two_sided": false, "albedo": {
                    "type": "bitmap", "file": "wood.png", "wrap": "mirror", "raw": true,
                    "uv_scale": [4, 2], "uv_offset": [0.5, 0.25]}},
                "checked": {"type": "conductor", "two_sided": false, "reflectance": [1, 1, 1],
                    "alpha": {"type": "checkerboard", "color0": 0.3, "color1": 0.1}},
            },
            "shapes": [
                {"type": "quad", "corner": [-1, -1, 0], "edge_u": [2, 0, 0], "edge_v": [0, 2, 0], "material": "wood"},
                {"type": "quad", "corner": [-1, -1, 0], "edge_u": [2, 0, 0], "edge_v": [0, 2, 0], "material": "checked"},
            ],
        }),
    );
    assert_same(&m.desc, &want);
    refused(
        &dir,
        &body.replace(
            "\"mirror\"/>",
            "\"mirror\"/><string name=\"filter_type\" value=\"nearest\"/>",
        ),
        "nearest",
        "texture/string[3]@value",
        "filter_type `nearest` is not supported",
    );
    refused(
        &dir,
        &body.replace(
            "<translate x=\"0.5\" y=\"0.25\"/>",
            "<rotate z=\"1\" angle=\"10\"/>",
        ),
        "to_uv",
        "texture/transform",
        "to_uv rotates or shears",
    );
    // A textured sphere's uv follow its object frame, which a non-uniform scale does not give.
    refused(
        &dir,
        r#"<shape type="sphere"><ref id="wood"/><transform name="to_world"><scale x="2"/></transform></shape>
<bsdf type="diffuse" id="wood"><texture name="reflectance" type="checkerboard"/></bsdf>"#,
        "scale x",
        "scene/shape/transform",
        "a textured or anisotropic sphere needs a to_world of a rotation and a uniform scale",
    );
    // A flipped disk's φ would run the other way about its normal than lumis' disk lets it.
    refused(
        &dir,
        r#"<shape type="disk"><ref id="wood"/><boolean name="flip_normals" value="true"/></shape>
<bsdf type="diffuse" id="wood"><texture name="reflectance" type="checkerboard"/></bsdf>"#,
        "<shape type=\"disk\">",
        "scene/shape",
        "a textured flipped disk is not supported",
    );
}

/// An error the JSON validation finds is reported at the XML element it came from.
#[test]
fn json_validation_errors_name_the_xml() {
    let dir = Dir::new("validation");
    refused(
        &dir,
        r#"<shape type="sphere"><bsdf type="diffuse"><rgb name="reflectance" value="0.5 1.5 0.5"/></bsdf></shape>"#,
        "1.5",
        "scene/shape/bsdf/rgb@value",
        "is outside [0, 1]",
    );
    refused(
        &dir,
        r#"<shape type="sphere"><float name="radius" value="0"/></shape>"#,
        "value=\"0\"",
        "scene/shape/float@value",
        "radius must be positive",
    );
    refused(
        &dir,
        r#"<integrator type="path"><integer name="max_depth" value="0"/></integrator>"#,
        "max_depth",
        "scene/integrator/integer@value",
        "0 is not allowed",
    );
}

/// Mitsuba's `normalmap` becomes its material's `normal_map`: the nested BSDF as it maps alone,
/// the texture with its options, the two flags (defaults true); a constant `rgb` too.
#[test]
fn a_normalmap_maps_onto_the_materials_normal_map() {
    let dir = Dir::new("normalmap");
    let img = lumis::image_io::Image {
        width: 2,
        height: 2,
        data: vec![glam::Vec3::new(0.6, 0.4, 0.9); 4],
    };
    img.write(&dir.0.join("n.png"), 0.0).unwrap();
    let plastic =
        r#"<bsdf type="roughplastic"><rgb name="diffuse_reflectance" value="0.3 0.2 0.1"/></bsdf>"#;
    let body = format!(
        r#"<shape type="rectangle"><bsdf type="normalmap" id="bumpy">
    <texture name="normalmap" type="bitmap"><string name="filename" value="n.png"/>
        <boolean name="raw" value="true"/></texture>
    <boolean name="use_shadowing_function" value="false"/>{plastic}</bsdf></shape>
<shape type="rectangle"><bsdf type="normalmap" id="flat"><rgb name="normalmap" value="0.5 0.6 1"/>
    <boolean name="flip_invalid_normals" value="false"/><bsdf type="diffuse"/></bsdf></shape>"#
    );
    let m = ok(&dir, &body).desc;
    let alone = ok(
        &dir,
        &format!(
            r#"<shape type="rectangle">{}</shape>"#,
            plastic.replace("<bsdf ", r#"<bsdf id="bumpy" "#)
        ),
    )
    .desc;
    let get =
        |d: &SceneDesc, name: &str| d.materials.iter().find(|m| m.name == name).unwrap().clone();
    let (bumpy, flat) = (get(&m, "bumpy"), get(&m, "flat"));
    assert_eq!(bumpy.material, get(&alone, "bumpy").material);
    assert!(!bumpy.two_sided);
    let map = bumpy.normal_map.expect("bumpy has a normal map");
    assert!(map.flip_invalid_normals && !map.shadowing);
    let lumis::textures::Texture::Bitmap(b) = &map.texture.texture else {
        panic!("{:?}", map.texture)
    };
    assert!(b.raw && b.file.ends_with("n.png"));
    let map = flat.normal_map.expect("flat has a normal map");
    assert!(!map.flip_invalid_normals && map.shadowing);
    assert_eq!(
        map.texture.texture,
        lumis::textures::Texture::Constant(glam::Vec3::new(0.5, 0.6, 1.0))
    );
}

/// Mitsuba's `bumpmap` becomes its material's `bump_map`: its one texture (whatever its name)
/// with its options, `scale`, the two flags; around a `twosided`, without a texture or on a
/// sphere (lumis has no ∂p/∂v there) it is refused where it is written.
#[test]
fn a_bumpmap_maps_onto_the_materials_bump_map() {
    let dir = Dir::new("bumpmap");
    let img = lumis::image_io::Image {
        width: 2,
        height: 2,
        data: vec![
            glam::Vec3::splat(0.2),
            glam::Vec3::splat(0.7),
            glam::Vec3::ONE,
            glam::Vec3::ZERO,
        ],
    };
    img.write(&dir.0.join("h.png"), 0.0).unwrap();
    let tex = r#"<texture name="tiles" type="bitmap"><string name="filename" value="h.png"/>
        <boolean name="raw" value="true"/></texture>"#;
    let body = format!(
        r#"<shape type="rectangle"><bsdf type="twosided" id="dented"><bsdf type="bumpmap">{tex}
    <float name="scale" value="0.02"/><boolean name="use_shadowing_function" value="false"/>
    <bsdf type="diffuse"/></bsdf></bsdf></shape>"#
    );
    let m = ok(&dir, &body).desc;
    let dented = m.materials.iter().find(|m| m.name == "dented").unwrap();
    assert!(dented.two_sided);
    let map = dented.normal_map.as_ref().expect("a bump map");
    assert!(map.flip_invalid_normals && !map.shadowing);
    assert_eq!(map.height_scale, Some(0.02));
    let lumis::textures::Texture::Bitmap(b) = &map.texture.texture else {
        panic!("{:?}", map.texture)
    };
    assert!(b.raw && b.file.ends_with("h.png"));
    refused(
        &dir,
        &format!(
            r#"<shape type="rectangle"><bsdf type="bumpmap">{tex}<bsdf type="twosided"><bsdf type="diffuse"/></bsdf></bsdf></shape>"#
        ),
        "bumpmap",
        "scene/shape/bsdf",
        "a bumpmap around a twosided BSDF is not supported",
    );
    refused(
        &dir,
        r#"<shape type="rectangle"><bsdf type="bumpmap"><bsdf type="diffuse"/></bsdf></shape>"#,
        "bumpmap",
        "scene/shape/bsdf",
        "a bumpmap needs exactly one nested <texture>",
    );
    refused(
        &dir,
        &format!(
            r#"<shape type="sphere"><bsdf type="bumpmap">{tex}<bsdf type="diffuse"/></bsdf></shape>"#
        ),
        "<shape type=\"sphere",
        "scene/shape",
        "bump map on a sphere",
    );
}

/// Every unsupported feature is refused with its file, line and element path.
#[test]
fn refusals_name_file_line_and_element() {
    let dir = Dir::new("refusals");
    let cases: [(&str, &str, &str, &str); 31] = [
        (
            r#"<emitter type="sunsky"/>"#,
            "sunsky",
            "scene/emitter",
            "emitter type `sunsky` is not supported",
        ),
        (
            r#"<emitter type="directionalarea"/>"#,
            "directionalarea",
            "scene/emitter",
            "no directional area lights",
        ),
        (
            r#"<shape type="sphere"><emitter type="spot"/></shape>"#,
            "spot",
            "scene/shape/emitter",
            "a `spot` emitter cannot be attached to a shape",
        ),
        (
            r#"<shape type="sphere"><bsdf type="bumpmap"/></shape>"#,
            "bumpmap",
            "scene/shape/bsdf",
            "a bumpmap needs a nested <bsdf>",
        ),
        (
            r#"<shape type="sphere"><bsdf type="normalmap"/></shape>"#,
            "normalmap",
            "scene/shape/bsdf",
            "a normalmap needs a nested <bsdf>",
        ),
        (
            r#"<shape type="sphere"><bsdf type="normalmap"><bsdf type="diffuse"/></bsdf></shape>"#,
            "normalmap",
            "scene/shape/bsdf",
            "a normalmap needs its `normalmap` texture",
        ),
        (
            r#"<shape type="sphere"><bsdf type="normalmap"><rgb name="normalmap" value="0.5 0.5 1"/><bsdf type="null"/></bsdf></shape>"#,
            "normalmap",
            "scene/shape/bsdf",
            "nothing to shade",
        ),
        (
            r#"<shape type="sphere"><bsdf type="normalmap"><rgb name="normalmap" value="0.5 0.5 1"/><bsdf type="twosided"><bsdf type="diffuse"/></bsdf></bsdf></shape>"#,
            "\"normalmap\"",
            "scene/shape/bsdf",
            "a normalmap around a twosided BSDF is not supported",
        ),
        (
            r#"<shape type="sphere"><bsdf type="normalmap"><rgb name="normalmap" value="0.5 0.5 1"/><bsdf type="normalmap"><rgb name="normalmap" value="0.5 0.5 1"/><bsdf type="diffuse"/></bsdf></bsdf></shape>"#,
            "<bsdf type=\"normalmap\"><rgb name=\"normalmap\" value=\"0.5 0.5 1\"/><bsdf type=\"diffuse",
            "scene/shape/bsdf/bsdf",
            "one normalmap or bumpmap, around its BSDF or its twosided",
        ),
        (
            r#"<shape type="sphere"><bsdf type="normalmap"><rgb name="normalmap" value="0.5 0.5 1"/><float name="strength" value="2"/><bsdf type="diffuse"/></bsdf></shape>"#,
            "strength",
            "scene/shape/bsdf/float",
            "property `strength` (a float) is not supported in <bsdf type=\"normalmap\">",
        ),
        (
            r#"<shape type="sphere"><bsdf type="blendbsdf"/></shape>"#,
            "blendbsdf",
            "scene/shape/bsdf",
            "a blendbsdf needs two nested <bsdf>, it has 0",
        ),
        (
            r#"<shape type="sphere"><bsdf type="twosided"><bsdf type="principledthin"/></bsdf></shape>"#,
            "principledthin",
            "scene/shape/bsdf/bsdf",
            "a `principledthin` cannot be nested in twosided (Mitsuba refuses",
        ),
        (
            r#"<shape type="sphere"><bsdf type="velvet"/></shape>"#,
            "velvet",
            "scene/shape/bsdf",
            "BSDF type `velvet` is not supported; lumis maps",
        ),
        (
            r#"<shape type="sphere"><bsdf type="mask"><bsdf type="mask"><bsdf type="diffuse"/></bsdf></bsdf></shape>"#,
            "<bsdf type=\"mask\"><bsdf type=\"mask",
            "scene/shape/bsdf/bsdf",
            "BSDF type `mask` is not supported here (a material has one mask)",
        ),
        (
            r#"<shape type="sphere"><bsdf type="roughplastic"><float name="alpha_u" value="0.1"/><float name="alpha_v" value="0.3"/></bsdf></shape>"#,
            "roughplastic",
            "scene/shape/bsdf",
            "anisotropic alpha_u, alpha_v are not supported in roughplastic",
        ),
        (
            r#"<shape type="sphere"><bsdf type="conductor"><string name="material" value="Au"/><texture type="checkerboard" name="specular_reflectance"/></bsdf></shape>"#,
            "<texture",
            "scene/shape/bsdf/texture",
            "textured specular_reflectance together with eta and k",
        ),
        (
            r#"<shape type="cube"><bsdf type="roughconductor"><float name="alpha_u" value="0.1"/><float name="alpha_v" value="0.3"/></bsdf></shape>"#,
            "<shape",
            "scene/shape",
            "anisotropic BSDF on a cube",
        ),
        (
            r#"<shape type="obj"><string name="filename" value="x.obj"/><bsdf type="roughplastic"><float name="alpha_u" value="0.1"/><texture type="checkerboard" name="alpha_v"/></bsdf></shape>"#,
            "roughplastic",
            "scene/shape/bsdf",
            "textured alpha_u and alpha_v are not supported in roughplastic",
        ),
        (
            r#"<shape type="sphere"><bsdf type="roughconductor"><string name="distribution" value="phong"/></bsdf></shape>"#,
            "phong",
            "scene/shape/bsdf/string@value",
            "unknown distribution `phong`",
        ),
        (
            r#"<shape type="sphere"><bsdf type="diffuse"><rgb name="reflectanse" value="1"/></bsdf></shape>"#,
            "reflectanse",
            "scene/shape/bsdf/rgb",
            "property `reflectanse` (an rgb) is not supported",
        ),
        (
            r#"<shape type="cylinder"><emitter type="area"/></shape>"#,
            "cylinder",
            "scene/shape",
            "an emitting cylinder is not supported",
        ),
        (
            r#"<shape type="cylinder"><transform name="to_world"><scale x="2"/></transform></shape>"#,
            "scale x",
            "scene/shape/transform",
            "an elliptic",
        ),
        (
            r#"<shape type="cylinder"><transform name="to_world"><scale z="-1"/></transform></shape>"#,
            "scale z",
            "scene/shape/transform",
            "a mirroring to_world (negative determinant) on a cylinder",
        ),
        (
            r#"<shape type="cylinder"><float name="radius" value="0"/></shape>"#,
            "cylinder",
            "scene/shape",
            "a cylinder needs a positive radius",
        ),
        (
            r#"<shape type="sphere"><medium type="homogeneous" name="interior"/></shape>"#,
            "homogeneous",
            "scene/shape/medium",
            "out of scope: participating media",
        ),
        (
            r#"<integrator type="volpath"/>"#,
            "volpath",
            "scene/integrator",
            "<integrator type=\"volpath\"> is out of scope: participating media",
        ),
        (
            r#"<shape type="sphere"><transform name="to_world"><matrix value="1 2 3"/></transform></shape>"#,
            "matrix",
            "transform/matrix@value",
            "a matrix has 16 numbers",
        ),
        (
            r#"<shape type="sphere"><transform name="to_world"><rotate angle="3"/></transform></shape>"#,
            "rotate",
            "transform/rotate",
            "rotation axis is zero",
        ),
        (
            r#"<shape type="sphere"><transform name="to_world"><translate x="1"/><lookat origin="0 0 0" target="0 0 0"/></transform></shape>"#,
            "lookat origin=\"0 0 0\"",
            "transform/lookat",
            "invalid lookat",
        ),
        (
            r#"<shape type="sphere"><bsdf type="diffuse"><spectrum name="reflectance" value="500:0.2, 400:0.1"/></bsdf></shape>"#,
            "400:0.1",
            "spectrum@value",
            "wavelengths must increase",
        ),
        (
            r#"<shape type="sphere"><bsdf type="plastic"><float name="int_ior" value="1.5"/><string name="ext_ior" value="unobtainium"/></bsdf></shape>"#,
            "unobtainium",
            "string@value",
            "unknown index of refraction `unobtainium`",
        ),
    ];
    for (body, marker, path, fragment) in cases {
        refused(&dir, body, marker, path, fragment);
    }
    // The sensor, film and filter, in their own scenes.
    let sensor = |film: &str| {
        format!(
            "<scene version=\"3.0.0\">\n<sensor type=\"perspective\">\n<float name=\"fov\" value=\"30\"/>\n{film}\n</sensor>\n</scene>"
        )
    };
    let film_cases = [
        (
            r#"<film type="hdrfilm"><rfilter type="mitchell"><float name="A" value="0.3"/></rfilter></film>"#,
            4,
            "scene/sensor/film/rfilter/float",
            "property `A` (a float) is not supported",
        ),
        (
            r#"<film type="hdrfilm"><rfilter type="lanczos"><integer name="lobes" value="0"/></rfilter></film>"#,
            4,
            "scene/sensor/film/rfilter/integer",
            "lobes 0 must be in [1, 16]",
        ),
        (
            r#"<film type="hdrfilm"><rfilter type="sinc"/></film>"#,
            4,
            "scene/sensor/film/rfilter",
            "reconstruction filter `sinc` is not supported",
        ),
        (
            r#"<film type="hdrfilm"><rfilter type="tent"><float name="radius" value="-1"/></rfilter></film>"#,
            4,
            "scene/sensor/film/rfilter/float",
            "radius -1 must be in (0, 16]",
        ),
        ("", 2, "scene/sensor", "the sensor has no <film>"),
        (
            r#"<film type="hdrfilm"><integer name="crop_width" value="3"/><rfilter type="box"/></film>"#,
            4,
            "scene/sensor/film",
            "crop window",
        ),
        (
            r#"<film type="specfilm"><rfilter type="box"/></film>"#,
            4,
            "scene/sensor/film",
            "film type `specfilm`",
        ),
        (
            r#"<film type="hdrfilm"><rfilter type="box"/></film><transform name="to_world"><scale x="-1"/></transform>"#,
            4,
            "scene/sensor/transform",
            "mirrors the image",
        ),
        (
            r#"<film type="hdrfilm"><rfilter type="box"/></film><transform name="to_world"><scale x="2"/></transform>"#,
            4,
            "scene/sensor/transform",
            "scale factor",
        ),
    ];
    for (film, line, path, fragment) in film_cases {
        let text = sensor(film);
        let e = import(&dir, &text, &[]).unwrap_err().to_string();
        assert!(
            e.contains(&format!("scene.xml:{line}:")) && e.contains(path) && e.contains(fragment),
            "{film}: {e}"
        );
    }
    let tele = "<scene version=\"3.0.0\">\n<sensor type=\"telecentric\"/></scene>";
    let e = import(&dir, tele, &[]).unwrap_err().to_string();
    assert!(
        e.contains("scene.xml:2:") && e.contains("telecentric"),
        "{e}"
    );
    // The thin lens and the orthographic camera: their own bad input, at its line.
    let film = "<film type=\"hdrfilm\"><rfilter type=\"box\"/></film>";
    let camera = |ty: &str, body: &str| {
        format!(
            "<scene version=\"3.0.0\">\n<sensor type=\"{ty}\">\n{body}\n{film}</sensor>\n</scene>"
        )
    };
    for (ty, body, line, fragment) in [
        (
            "thinlens",
            "<float name=\"fov\" value=\"30\"/>",
            2,
            "needs `aperture_radius`",
        ),
        (
            "thinlens",
            "<float name=\"aperture_radius\" value=\"0.1\"/><transform name=\"to_world\"><scale value=\"2\"/></transform>",
            3,
            "scale factor",
        ),
        (
            "orthographic",
            "<transform name=\"to_world\"><matrix value=\"1 0.5 0 0 0 1 0 0 0 0 1 0 0 0 0 1\"/></transform>",
            3,
            "shears or flattens",
        ),
        (
            "orthographic",
            "<transform name=\"to_world\"><scale x=\"-1\"/></transform>",
            3,
            "mirrors the image",
        ),
        (
            "orthographic",
            "<float name=\"near_clip\" value=\"0\"/>",
            3,
            "near_clip must be > 0",
        ),
        (
            "orthographic",
            "<float name=\"fov\" value=\"30\"/>",
            3,
            "fov",
        ),
    ] {
        let e = import(&dir, &camera(ty, body), &[])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains(&format!("scene.xml:{line}:")) && e.contains(fragment),
            "{ty} {body}: {e}"
        );
    }
    // Document-level problems.
    let e = import(
        &dir,
        "<scene version=\"3.0.0\">\n  <shape type='sphere'>\n</scene>",
        &[],
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("scene.xml:3:") && e.contains("XML syntax error"),
        "{e}"
    );
    let e = import(&dir, "<scene>\n</scene>", &[])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("scene.xml:1:1: scene") && e.contains("`version`"),
        "{e}"
    );
    let e = import(&dir, "<scene version=\"0.6.0\"/>", &[])
        .unwrap_err()
        .to_string();
    assert!(e.contains("Mitsuba 0.x"), "{e}");
    let e = import(&dir, "<scene version=\"3.0.0\"/>", &[])
        .unwrap_err()
        .to_string();
    assert!(e.contains("no <sensor>"), "{e}");
    let e = import(&dir, &scene("<volume type=\"grid\"/>"), &[])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("scene.xml:8:1: scene/volume") && e.contains("out of scope"),
        "{e}"
    );
    // -D applies to .xml only.
    let json = common::data_dir().join("scenes/analytic_disk.json");
    let e = lumis::scene::load_scene_with(&json, &[("a".into(), "1".into())]).unwrap_err();
    assert!(
        e.to_string().contains("Mitsuba XML scenes (.xml) only"),
        "{e}"
    );
}

/// Exactly the plugins the brief puts out of scope are refused as such, wherever they appear, with
/// the file, line, element path, "out of scope" and the reason (issue 37, item 3); a plugin lumis
/// merely lacks is not (it says "not supported").
#[test]
fn out_of_scope_plugins_are_refused_with_their_reason() {
    let dir = Dir::new("out_of_scope");
    let sphere = |inner: &str| format!(r#"<shape type="sphere">{inner}</shape>"#);
    let cases = [
        (
            sphere(r#"<bsdf type="pplastic"/>"#),
            "pplastic",
            "scene/shape/bsdf",
            "polarization",
        ),
        (
            sphere(r#"<bsdf type="polarizer"/>"#),
            "polarizer",
            "scene/shape/bsdf",
            "polarization",
        ),
        (
            sphere(r#"<bsdf type="measured_polarized"/>"#),
            "measured_polarized",
            "scene/shape/bsdf",
            "polarization",
        ),
        (
            r#"<integrator type="stokes"/>"#.into(),
            "stokes",
            "scene/integrator",
            "polarization",
        ),
        (
            r#"<medium type="homogeneous"/>"#.into(),
            "homogeneous",
            "scene/medium",
            "media",
        ),
        (r#"<phase type="hg"/>"#.into(), "hg", "scene/phase", "media"),
        (
            sphere(r#"<bsdf type="diffuse"><texture type="volume" name="reflectance"/></bsdf>"#),
            "volume",
            "scene/shape/bsdf/texture",
            "media",
        ),
        (
            r#"<integrator type="volpathmis"/>"#.into(),
            "volpathmis",
            "scene/integrator",
            "media",
        ),
        (
            r#"<integrator type="prbvolpath"/>"#.into(),
            "prbvolpath",
            "scene/integrator",
            "media",
        ),
        (
            r#"<shape type="bsplinecurve"/>"#.into(),
            "bsplinecurve",
            "scene/shape",
            "curves and hair",
        ),
        (
            r#"<shape type="linearcurve"/>"#.into(),
            "linearcurve",
            "scene/shape",
            "curves and hair",
        ),
        (
            sphere(r#"<bsdf type="hair"/>"#),
            "hair",
            "scene/shape/bsdf",
            "curves and hair",
        ),
        (
            r#"<shape type="sdfgrid"/>"#.into(),
            "sdfgrid",
            "scene/shape",
            "sdfgrid",
        ),
        (
            sphere(r#"<bsdf type="measured"/>"#),
            "measured",
            "scene/shape/bsdf",
            "measured BSDFs",
        ),
        (
            r#"<integrator type="aov"/>"#.into(),
            "aov",
            "scene/integrator",
            "AOVs",
        ),
        (
            r#"<integrator type="depth"/>"#.into(),
            "depth",
            "scene/integrator",
            "depths",
        ),
    ];
    for (body, marker, path, why) in &cases {
        let msg = refused(&dir, body, marker, path, why);
        assert!(msg.contains("is out of scope"), "{msg}");
    }
    // Not out of scope: lumis lacks it (another issue's work), and says so differently.
    let msg = refused(
        &dir,
        r#"<shape type="ellipsoids"/>"#,
        "ellipsoids",
        "scene/shape",
        "is not supported",
    );
    assert!(!msg.contains("out of scope"), "{msg}");
}

/// Mitsuba's `instance` of a `shapegroup` is flattened: an instance renders the scene its
/// group's shapes would, each placed by the instance's `to_world` after its own, bit for bit;
/// an unused group renders nothing; what lumis cannot flatten exactly (a shear, a non-uniform
/// scale, a mirror) and what Mitsuba refuses (an emitter in a group, a nested group, an
/// instance of something else) are located errors.
#[test]
fn instances_are_flattened_and_their_refusals_located() {
    let dir = Dir::new("instances");
    let floor = r#"<shape type="rectangle"><transform name="to_world"><scale value="4"/>
        <rotate x="1" angle="-90"/></transform></shape>
<shape type="rectangle"><transform name="to_world"><rotate x="1" angle="90"/>
        <translate y="3"/></transform><emitter type="area"><rgb name="radiance" value="5"/></emitter></shape>"#;
    let group = r#"<shape type="shapegroup" id="g">
    <shape type="sphere"><float name="radius" value="0.3"/><point name="center" x="0.5" y="0" z="0"/></shape>
    <shape type="cube"><transform name="to_world"><scale value="0.2"/><rotate x="1" angle="30"/></transform></shape>
</shape>"#;
    let place =
        "<scale value=\"1.5\"/><rotate y=\"1\" angle=\"70\"/><translate x=\"0.2\" y=\"0.6\"/>";
    let instanced = ok(
        &dir,
        &format!(
            "{floor}\n{group}\n<shape type=\"instance\"><ref id=\"g\"/><transform name=\"to_world\">{place}</transform></shape>"
        ),
    );
    let explicit = ok(
        &dir,
        &format!(
            "{floor}\n<shape type=\"sphere\"><float name=\"radius\" value=\"0.3\"/><point name=\"center\" x=\"0.5\" y=\"0\" z=\"0\"/><transform name=\"to_world\">{place}</transform></shape>\n\
             <shape type=\"cube\"><transform name=\"to_world\"><scale value=\"0.2\"/><rotate x=\"1\" angle=\"30\"/>{place}</transform></shape>"
        ),
    );
    assert_eq!(instanced.desc.shapes.len(), 4);
    // The same shapes, to rounding (the instance's matrix multiplies the group's after it is
    // built; Mitsuba's transform list builds one product in another order).
    fn close(a: &Value, b: &Value, at: &str) {
        match (a, b) {
            (Value::Number(x), Value::Number(y)) => {
                let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
                assert!((x - y).abs() <= 1e-12 * (1.0 + x.abs()), "{at}: {x} vs {y}");
            }
            (Value::Array(x), Value::Array(y)) => {
                assert_eq!(x.len(), y.len(), "{at}");
                for (i, (x, y)) in x.iter().zip(y).enumerate() {
                    close(x, y, &format!("{at}[{i}]"));
                }
            }
            (Value::Object(x), Value::Object(y)) => {
                assert_eq!(
                    x.keys().collect::<Vec<_>>(),
                    y.keys().collect::<Vec<_>>(),
                    "{at}"
                );
                for (k, x) in x {
                    close(x, &y[k], &format!("{at}.{k}"));
                }
            }
            _ => assert_eq!(a, b, "{at}"),
        }
    }
    close(
        &instanced.json["shapes"],
        &explicit.json["shapes"],
        "shapes",
    );
    // A group no instance names adds nothing.
    assert_eq!(ok(&dir, &format!("{floor}\n{group}")).desc.shapes.len(), 2);

    let instance = |to_world: &str| {
        format!(
            "{group}\n<shape type=\"instance\"><ref id=\"g\"/><transform name=\"to_world\">{to_world}</transform></shape>"
        )
    };
    for bad in [
        r#"<scale x="1" y="2" z="1"/>"#,
        r#"<scale x="-1" y="1" z="1"/>"#,
        r#"<matrix value="1 0.5 0 0  0 1 0 0  0 0 1 0  0 0 0 1"/>"#,
    ] {
        refused(
            &dir,
            &instance(bad),
            "type=\"instance\"",
            "scene/shape",
            "a rotation, a uniform scale",
        );
    }
    refused(
        &dir,
        r#"<shape type="shapegroup" id="g"><shape type="sphere"><emitter type="area"/></shape></shape>
<shape type="instance"><ref id="g"/></shape>"#,
        "<emitter",
        "emitter",
        "does not instance emitters",
    );
    refused(
        &dir,
        r#"<shape type="shapegroup" id="h"><shape type="sphere"/></shape>
<shape type="shapegroup" id="g"><ref id="h"/></shape>
<shape type="instance"><ref id="g"/></shape>"#,
        "id=\"h\"",
        "scene/shape",
        "inside a shapegroup",
    );
    refused(
        &dir,
        r#"<shape type="instance"><ref id="nope"/></shape>"#,
        "nope",
        "scene/shape/ref",
        "no object has the id `nope`",
    );
    refused(
        &dir,
        r#"<shape type="sphere" id="s"/>
<shape type="instance"><ref id="s"/></shape>"#,
        "id=\"s\"",
        "scene/shape",
        "names a shapegroup",
    );
}

/// `hdrfilm`'s `sample_border = true` with a gaussian filter (explicit, or Mitsuba's default when
/// the film has no `<rfilter>`) is refused at the boolean's line: Mitsuba then samples outside
/// the film too, so its edge pixels see the whole filter, where lumis renormalises it on the film
/// (the image would differ near the border). `false`, and `true` with a box (whose samples never
/// leave the film), import. Catches the importer ignoring the flag (deliberate bug tried:
/// `film.bool("sample_border", false)` read as `false` always: the first case was accepted).
#[test]
fn sample_border_with_a_gaussian_is_refused() {
    let dir = Dir::new("sample_border");
    let sensor = |border: &str, filter: &str| {
        format!(
            "<scene version=\"3.0.0\">\n<sensor type=\"perspective\">\n<float name=\"fov\" value=\"30\"/>\n<film type=\"hdrfilm\">\n<boolean name=\"sample_border\" value=\"{border}\"/>\n{filter}</film>\n</sensor>\n</scene>"
        )
    };
    for filter in ["<rfilter type=\"gaussian\"/>\n", ""] {
        let e = import(&dir, &sensor("true", filter), &[])
            .err()
            .unwrap_or_else(|| panic!("sample_border true accepted with {filter:?}"))
            .to_string();
        assert!(
            e.contains("scene.xml:5:")
                && e.contains("scene/sensor/film/boolean")
                && e.contains("sample_border = true is not supported with a gaussian filter")
                && !e.contains('\n'),
            "{filter:?}: {e}"
        );
    }
    for (border, filter) in [
        ("false", "<rfilter type=\"gaussian\"/>\n"),
        ("false", ""),
        ("true", "<rfilter type=\"box\"/>\n"),
    ] {
        import(&dir, &sensor(border, filter), &[])
            .unwrap_or_else(|e| panic!("sample_border {border} with {filter:?}: {e}"));
    }
}
