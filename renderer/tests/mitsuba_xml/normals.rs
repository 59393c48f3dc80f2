//! Vertex normals of a mesh file without them, as Mitsuba computes them (a part of
//! `renderer/tests/mitsuba_xml.rs`): the world-space normals lumis shades an imported mesh with
//! equal the ones Mitsuba 3.9.1 computes for the same file and `to_world` (a non-uniform
//! scale, so that computing them before the transform would differ), printed by
//! `tools/mitsuba_grammar_check.py` (case 10). `face_normals` keeps the mesh flat.

use super::*;
use lumis::geometry::mesh_attributes::normal_matrix;

/// An irregular fan of six triangles around vertex 0 (`tools/mitsuba_grammar_check.py`).
pub const FAN_OBJ: &str = "v 0 0 0.3\nv 1 0 0\nv 0.2 1.1 0.1\nv -0.9 0.4 -0.2\nv -0.3 -1 0.4\n\
v 0.8 -0.7 -0.5\nf 1 2 3\nf 1 3 4\nf 1 4 5\nf 1 5 6\nf 1 6 2\nf 2 6 3\n";

/// Mitsuba 3.9.1's `vertex_normals_buffer()` for [`FAN_OBJ`] under `to_world` = scale (2, 1,
/// 0.5) · rotate 30° about z.
const MITSUBA: [[f64; 3]; 6] = [
    [-0.0015653, 0.0443966, 0.9990128],
    [0.7194243, 0.6683013, 0.1892140],
    [-0.0676687, 0.0896550, 0.9936715],
    [-0.1265089, -0.0017343, 0.9919640],
    [0.0922813, 0.0924212, 0.9914345],
    [0.3520594, 0.0905120, 0.9315911],
];

#[test]
fn smooth_normals_are_mitsubas() {
    let dir = Dir::new("normals");
    dir.write("fan.obj", FAN_OBJ);
    let shape = |extra: &str| {
        format!(
            r#"<shape type="obj"><string name="filename" value="fan.obj"/>{extra}
    <transform name="to_world"><rotate z="1" angle="30"/><scale x="2" y="1" z="0.5"/></transform></shape>"#
        )
    };
    let m = ok(&dir, &shape(""));
    let GeometryDesc::Mesh {
        to_world,
        mesh,
        recompute_normals,
        ..
    } = &m.desc.shapes[0].geometry
    else {
        panic!("not a mesh");
    };
    assert!(recompute_normals);
    let nm = normal_matrix(*to_world);
    let normals = mesh.normals.as_ref().expect("computed normals");
    for (i, (n, want)) in normals.iter().zip(MITSUBA).enumerate() {
        let world = (nm * n.as_dvec3()).normalize();
        let err = (world - DVec3::from(want)).length();
        assert!(err < 2e-6, "vertex {i}: lumis {world}, Mitsuba {want:?}");
    }
    assert!(m.desc.warnings.is_empty(), "{:?}", m.desc.warnings);
    // face_normals = true: flat, as Mitsuba shades it.
    let m = ok(
        &dir,
        &shape(r#"<boolean name="face_normals" value="true"/>"#),
    );
    let GeometryDesc::Mesh { mesh, .. } = &m.desc.shapes[0].geometry else {
        panic!("not a mesh");
    };
    assert!(mesh.normals.is_none());
}
