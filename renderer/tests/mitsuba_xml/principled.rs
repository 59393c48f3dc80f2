//! The Mitsuba importer's `principled` (a part of `renderer/tests/mitsuba_xml.rs`): its keys
//! copied for the scene format, which applies Mitsuba's defaults and rules, and its refusals.

use super::*;

#[test]
fn principled_maps_key_for_key() {
    let dir = Dir::new("principled");
    let body = r#"<shape type="sphere"><bsdf type="principled" id="plain"/></shape>
<shape type="sphere"><bsdf type="principled" id="full">
    <rgb name="base_color" value="0.8 0.4 0.2"/><float name="roughness" value="0.3"/>
    <float name="anisotropic" value="0.5"/><float name="metallic" value="0.7"/>
    <float name="spec_tint" value="0.4"/><float name="sheen" value="0.3"/>
    <float name="sheen_tint" value="0.2"/><float name="flatness" value="0.1"/>
    <float name="clearcoat" value="0.6"/><float name="clearcoat_gloss" value="0.3"/>
    <float name="specular" value="0.6"/><float name="main_specular_sampling_rate" value="0.5"/>
    <float name="clearcoat_sampling_rate" value="2"/>
    <float name="diffuse_reflectance_sampling_rate" value="3"/></bsdf></shape>
<shape type="sphere"><bsdf type="principled" id="glassy"><float name="spec_trans" value="0.8"/>
    <float name="eta" value="1.33"/>
    <texture name="roughness" type="checkerboard"><float name="color0" value="0.1"/><float name="color1" value="0.3"/></texture>
</bsdf></shape>
<shape type="sphere"><bsdf type="twosided" id="both"><bsdf type="principled"><float name="spec_trans" value="0"/></bsdf></bsdf></shape>"#;
    let m = ok(&dir, body);
    let want = expected(
        &dir,
        json!({
            "materials": {
                "plain": {"type": "principled", "two_sided": false},
                "full": {"type": "principled", "base_color": [0.8, 0.4, 0.2], "roughness": 0.3,
                         "anisotropic": 0.5, "metallic": 0.7, "spec_tint": 0.4, "sheen": 0.3,
                         "sheen_tint": 0.2, "flatness": 0.1, "clearcoat": 0.6,
                         "clearcoat_gloss": 0.3, "specular": 0.6,
                         "main_specular_sampling_rate": 0.5, "clearcoat_sampling_rate": 2,
                         "diffuse_reflectance_sampling_rate": 3, "two_sided": false},
                // Transmitting: no sides. Mitsuba's eval_1 swaps a checkerboard's colours.
                "glassy": {"type": "principled", "spec_trans": 0.8, "eta": 1.33,
                           "roughness": {"type": "checkerboard", "color0": 0.3, "color1": 0.1}},
                // spec_trans 0 is no transmission (Mitsuba's flag): twosided takes it.
                "both": {"type": "principled", "spec_trans": 0, "two_sided": true},
            },
            "shapes": unit_spheres(&["plain", "full", "glassy", "both"]),
        }),
    );
    assert_same(&m.desc, &want);
    assert!(m.desc.warnings.is_empty(), "{:?}", m.desc.warnings);
}

#[test]
fn principled_refusals_are_located() {
    let dir = Dir::new("principled_refusals");
    refused(
        &dir,
        r#"<shape type="sphere"><bsdf type="twosided"><bsdf type="principled"><float name="spec_trans" value="0.5"/></bsdf></bsdf></shape>"#,
        "<bsdf type=\"principled",
        "scene/shape/bsdf/bsdf",
        "cannot be nested in twosided",
    );
    refused(
        &dir,
        r#"<shape type="sphere"><bsdf type="principled"><float name="eta" value="1.5"/><float name="specular" value="0.5"/></bsdf></shape>"#,
        "name=\"specular",
        "scene/shape/bsdf/float",
        "give eta or specular, not both",
    );
    refused(
        &dir,
        r#"<shape type="sphere"><bsdf type="principled"><float name="metallic" value="1.5"/></bsdf></shape>"#,
        "name=\"metallic",
        "scene/shape/bsdf/float",
        "metallic 1.5 is outside [0, 1]",
    );
    refused(
        &dir,
        r#"<shape type="sphere"><bsdf type="principled"><float name="diff_trans" value="0.5"/></bsdf></shape>"#,
        "diff_trans",
        "scene/shape/bsdf/float",
        "diff_trans",
    );
}

/// `principledthin`: every key copied (a textured η and diff_trans included), no sides (it
/// transmits; Mitsuba refuses it inside twosided: `refusals.rs`).
#[test]
fn principledthin_maps_key_for_key() {
    let dir = Dir::new("principledthin");
    let body = r#"<shape type="sphere"><bsdf type="principledthin" id="plain"/></shape>
<shape type="sphere"><bsdf type="principledthin" id="full">
    <rgb name="base_color" value="0.3 0.7 0.2"/><float name="roughness" value="0.3"/>
    <float name="anisotropic" value="0.5"/><float name="spec_trans" value="0.4"/>
    <float name="spec_tint" value="0.4"/><float name="sheen" value="0.3"/>
    <float name="sheen_tint" value="0.2"/><float name="flatness" value="0.1"/>
    <float name="diff_trans" value="1.5"/><float name="eta" value="1.33"/>
    <float name="specular_reflectance_sampling_rate" value="0.5"/>
    <float name="specular_transmittance_sampling_rate" value="2"/>
    <float name="diffuse_reflectance_sampling_rate" value="3"/>
    <float name="diffuse_transmittance_sampling_rate" value="0.7"/></bsdf></shape>
<shape type="sphere"><bsdf type="principledthin" id="textured">
    <texture name="eta" type="checkerboard"><float name="color0" value="1.2"/><float name="color1" value="1.8"/></texture>
    <texture name="diff_trans" type="checkerboard"><float name="color0" value="0.4"/><float name="color1" value="1.6"/></texture>
</bsdf></shape>"#;
    let m = ok(&dir, body);
    let want = expected(
        &dir,
        json!({
            "materials": {
                "plain": {"type": "principled_thin"},
                "full": {"type": "principled_thin", "base_color": [0.3, 0.7, 0.2],
                         "roughness": 0.3, "anisotropic": 0.5, "spec_trans": 0.4,
                         "spec_tint": 0.4, "sheen": 0.3, "sheen_tint": 0.2, "flatness": 0.1,
                         "diff_trans": 1.5, "eta": 1.33,
                         "specular_reflectance_sampling_rate": 0.5,
                         "specular_transmittance_sampling_rate": 2,
                         "diffuse_reflectance_sampling_rate": 3,
                         "diffuse_transmittance_sampling_rate": 0.7},
                // Mitsuba's eval_1 swaps a checkerboard's colours.
                "textured": {"type": "principled_thin",
                             "eta": {"type": "checkerboard", "color0": 1.8, "color1": 1.2},
                             "diff_trans": {"type": "checkerboard", "color0": 1.6, "color1": 0.4}},
            },
            "shapes": unit_spheres(&["plain", "full", "textured"]),
        }),
    );
    assert_same(&m.desc, &want);
    assert!(m.desc.warnings.is_empty(), "{:?}", m.desc.warnings);
}

#[test]
fn principledthin_refusals_are_located() {
    let dir = Dir::new("principledthin_refusals");
    refused(
        &dir,
        r#"<shape type="sphere"><bsdf type="principledthin"><float name="metallic" value="0.5"/></bsdf></shape>"#,
        "metallic",
        "scene/shape/bsdf/float",
        "metallic",
    );
    refused(
        &dir,
        r#"<shape type="sphere"><bsdf type="principledthin"><float name="diff_trans" value="2.5"/></bsdf></shape>"#,
        "name=\"diff_trans",
        "scene/shape/bsdf/float",
        "diff_trans 2.5 is outside [0, 2]",
    );
}
