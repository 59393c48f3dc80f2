//! Export of shapes, the inverse of [`super::shape`]:
//!
//! * a quad is a `rectangle` whose `to_world` maps [-1, 1]² onto it (x = edge_u / 2,
//!   y = edge_v / 2, z = the unit normal), with the translation nudged by ulps until the
//!   importer's `to_world · (-1, -1, 0)` is the corner to the last bit ([`rectangle_matrix`]);
//! * a box is its six faces as rectangles, in [`box_faces`] order: exactly the six quads lumis
//!   builds for it (Mitsuba's `cube` would import as 12 triangles with other uv and lights);
//! * a sphere is `center` + `radius` (no `to_world`: the importer's radius is then exact), or,
//!   with a `pole` or `u_axis`, a `to_world` = [r·u, r·(pole × u), r·pole, center] (Mitsuba's
//!   texture frame);
//! * a cylinder is `p0`, `p1`, `radius` and `flip_normals` where its u axis is Mitsuba's
//!   default, else a `to_world` = [r·u, r·(ẑ × u), p1 − p0, p0] of the unit tube (whose frame
//!   is the identity);
//! * a disk is a `disk` with `to_world` = [r·a, r·b, n, center] for a right-handed orthonormal
//!   (a, b, n), axis-aligned where n is, so that r and n come back exact; a = its `u_axis`, or
//!   for a textured disk without one the first tangent of the normal's frame, so that Mitsuba's
//!   texture coordinates are lumis';
//! * a mesh from an `.obj`, `.ply` or `.serialized` file names the file with its `to_world`
//!   (row-major `matrix`); a glTF mesh, inline triangles and a polygon (triangulated as lumis
//!   triangulates it) are written to a binary PLY beside the XML. A mesh without vertex normals
//!   gets `face_normals` true: lumis shades it flat, where Mitsuba would smooth it; one whose
//!   normals lumis computed (`recompute_normals`) gets `face_normals` false, and Mitsuba
//!   computes the same.
//!
//! A textured material or emission on a shape whose texture coordinates Mitsuba defines
//! otherwise than lumis (polygon, triangles, a mesh without uv) is an error, as the importer
//! refuses the same.

use super::export::{ExportCtx, Xml, file_name, matrix_value, num, vec3};
use super::export_bsdf::{color_value, is_textured, texture_xml};
use crate::geometry::polygon;
use crate::scene::build::box_faces;
use crate::scene::desc::{GeometryDesc, SceneDesc, ShapeDesc};
use crate::scene::error::SceneError;
use crate::scene::mesh::MeshData;
use glam::{DMat3, DMat4, DVec3, DVec4};

/// Writes shape `s` of `desc` (one or more `<shape>` elements).
pub(crate) fn shape(
    ctx: &mut ExportCtx,
    x: &mut Xml,
    desc: &SceneDesc,
    s: &ShapeDesc,
) -> Result<(), SceneError> {
    let path = &s.json_path;
    let material = s.material.map(|i| &desc.materials[i]);
    let textured = material.is_some_and(|m| is_textured(m, &desc.materials))
        || s.emission_texture
            .as_ref()
            .is_some_and(|t| t.texture.reads_uv());
    let no_uv = |what: &str| -> Result<(), SceneError> {
        if textured {
            return Err(SceneError::new(
                path.clone(),
                format!(
                    "a textured {what} cannot be exported: Mitsuba gives it other texture \
                     coordinates than lumis"
                ),
            ));
        }
        Ok(())
    };
    match &s.geometry {
        GeometryDesc::Quad {
            corner,
            edge_u,
            edge_v,
        } => {
            x.open("shape", &[("type", "rectangle")]);
            matrix(x, "to_world", &rectangle_matrix(*corner, *edge_u, *edge_v));
            attachments(ctx, x, desc, s)?;
        }
        GeometryDesc::Box {
            min,
            max,
            rotate_y_deg,
            translate,
        } => {
            for [c, eu, ev] in box_faces(*min, *max, *rotate_y_deg, *translate) {
                x.open("shape", &[("type", "rectangle")]);
                matrix(x, "to_world", &rectangle_matrix(c, eu, ev));
                attachments(ctx, x, desc, s)?;
            }
        }
        GeometryDesc::Sphere {
            center,
            radius,
            pole,
            u_axis,
        } => {
            x.open("shape", &[("type", "sphere")]);
            if pole.is_none() && u_axis.is_none() {
                // Mitsuba's sphere in the world's axes, as lumis' default.
                x.leaf("point", &[("name", "center"), ("value", &vec3(*center))]);
                x.leaf("float", &[("name", "radius"), ("value", &num(*radius))]);
            } else {
                let z = pole.unwrap_or(DVec3::Z).normalize();
                let u = u_axis.unwrap_or(DVec3::X);
                let u = (u - z * z.dot(u)).normalize();
                let m = DMat4::from_cols(
                    (u * *radius).extend(0.0),
                    (z.cross(u) * *radius).extend(0.0),
                    (z * *radius).extend(0.0),
                    center.extend(1.0),
                );
                matrix(x, "to_world", &m);
            }
            attachments(ctx, x, desc, s)?;
        }
        GeometryDesc::Cylinder {
            p0,
            p1,
            radius,
            u_axis,
            flip_normals,
        } => {
            x.open("shape", &[("type", "cylinder")]);
            match u_axis {
                None => {
                    x.leaf("point", &[("name", "p0"), ("value", &vec3(*p0))]);
                    x.leaf("point", &[("name", "p1"), ("value", &vec3(*p1))]);
                    x.leaf("float", &[("name", "radius"), ("value", &num(*radius))]);
                }
                Some(u) => {
                    let axis = *p1 - *p0;
                    let z = axis.normalize();
                    let u = (*u - z * z.dot(*u)).normalize();
                    let m = DMat4::from_cols(
                        (u * *radius).extend(0.0),
                        (z.cross(u) * *radius).extend(0.0),
                        axis.extend(0.0),
                        p0.extend(1.0),
                    );
                    matrix(x, "to_world", &m);
                }
            }
            if *flip_normals {
                x.leaf("boolean", &[("name", "flip_normals"), ("value", "true")]);
            }
            attachments(ctx, x, desc, s)?;
        }
        GeometryDesc::Disk {
            center,
            normal,
            radius,
            u_axis,
        } => {
            // With a texture, the frame whose x axis is where φ = 0 (the normal's own frame by
            // default, lumis' `Frame::from_normal`); without, any (`disk_matrix`).
            let axes = match u_axis {
                Some(u) => {
                    let u = (*u - *normal * normal.dot(*u)).normalize();
                    Some((u, normal.cross(u)))
                }
                None if textured => Some(super::transform::coordinate_system(*normal)),
                None => None,
            };
            let m = match axes {
                Some((a, b)) => DMat4::from_cols(
                    (a * *radius).extend(0.0),
                    (b * *radius).extend(0.0),
                    normal.extend(0.0),
                    center.extend(1.0),
                ),
                None => disk_matrix(*center, *normal, *radius),
            };
            x.open("shape", &[("type", "disk")]);
            matrix(x, "to_world", &m);
            attachments(ctx, x, desc, s)?;
        }
        GeometryDesc::Polygon { vertices } => {
            no_uv("polygon")?;
            let mesh = MeshData {
                positions: vertices.iter().map(|p| p.as_vec3()).collect(),
                indices: polygon::triangulate(vertices)
                    .iter()
                    .map(|t| t.map(|i| i as u32))
                    .collect(),
                normals: None,
                uvs: None,
                attributes: Vec::new(),
            };
            ply_shape(ctx, x, desc, s, mesh, DMat4::IDENTITY)?;
        }
        GeometryDesc::Triangles { positions, indices } => {
            no_uv("triangle list")?;
            let mesh = MeshData {
                positions: positions.iter().map(|p| p.as_vec3()).collect(),
                indices: indices.clone(),
                normals: None,
                uvs: None,
                attributes: Vec::new(),
            };
            ply_shape(ctx, x, desc, s, mesh, DMat4::IDENTITY)?;
        }
        GeometryDesc::Mesh {
            file,
            shape_index,
            to_world,
            face_normals,
            mesh,
            ..
        } => {
            if mesh.uvs.is_none() {
                no_uv("mesh without texture coordinates")?;
            }
            let ext = file
                .extension()
                .and_then(|e| e.to_str())
                .map(str::to_ascii_lowercase)
                .unwrap_or_default();
            match ext.as_str() {
                "obj" | "ply" | "serialized" => {
                    x.open("shape", &[("type", &ext)]);
                    x.leaf(
                        "string",
                        &[
                            ("name", "filename"),
                            ("value", &file_name(file, &ctx.folder)),
                        ],
                    );
                    if ext == "serialized" {
                        x.leaf(
                            "integer",
                            &[("name", "shape_index"), ("value", &shape_index.to_string())],
                        );
                    }
                    let flat = *face_normals || mesh.normals.is_none();
                    x.leaf(
                        "boolean",
                        &[("name", "face_normals"), ("value", &flat.to_string())],
                    );
                    matrix(x, "to_world", to_world);
                    attachments(ctx, x, desc, s)?;
                }
                _ => {
                    let mut m = (**mesh).clone();
                    if *face_normals {
                        m.normals = None;
                    }
                    ply_shape(ctx, x, desc, s, m, *to_world)?;
                }
            }
        }
    }
    Ok(())
}

/// A `ply` shape for `mesh`, written beside the XML as `STEM_shapes_N.ply`.
fn ply_shape(
    ctx: &mut ExportCtx,
    x: &mut Xml,
    desc: &SceneDesc,
    s: &ShapeDesc,
    mesh: MeshData,
    to_world: DMat4,
) -> Result<(), SceneError> {
    let tag: String = s
        .json_path
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    let name = format!("{}_{}.ply", ctx.stem, tag.trim_matches('_'));
    let file = ctx.folder.join(&name);
    if ctx.meshes.iter().any(|(p, _)| *p == file) {
        return Err(SceneError::new(
            s.json_path.clone(),
            format!("two shapes would write the same mesh file {name}"),
        ));
    }
    x.open("shape", &[("type", "ply")]);
    x.leaf("string", &[("name", "filename"), ("value", &name)]);
    let flat = mesh.normals.is_none();
    x.leaf(
        "boolean",
        &[("name", "face_normals"), ("value", &flat.to_string())],
    );
    if to_world != DMat4::IDENTITY {
        matrix(x, "to_world", &to_world);
    }
    ctx.meshes.push((file, mesh));
    attachments(ctx, x, desc, s)
}

/// The shape's BSDF (a `<ref>` to its material; black one-sided diffuse for none, which only an
/// emitter may leave out: Mitsuba's default is grey) and area emitter, then `</shape>`.
fn attachments(
    ctx: &mut ExportCtx,
    x: &mut Xml,
    desc: &SceneDesc,
    s: &ShapeDesc,
) -> Result<(), SceneError> {
    let emits = s.emission_texture.is_some() || s.emission != DVec3::ZERO;
    match s.material {
        Some(i) => {
            let id = ctx.bsdfs.use_material(&desc.materials, i);
            x.leaf("ref", &[("id", &id)]);
        }
        None if emits => {}
        None => {
            x.open("bsdf", &[("type", "diffuse")]);
            color_value(x, "reflectance", DVec3::ZERO);
            x.close("bsdf");
        }
    }
    if emits {
        x.open("emitter", &[("type", "area")]);
        match &s.emission_texture {
            Some(t) => texture_xml(
                x,
                "radiance",
                t,
                false,
                &ctx.folder,
                &format!("{}.emission", s.json_path),
            )?,
            None => color_value(x, "radiance", s.emission),
        }
        x.close("emitter");
    }
    x.close("shape");
    Ok(())
}

/// `<transform name=…><matrix value="16 numbers, row by row"/></transform>`.
fn matrix(x: &mut Xml, name: &str, m: &DMat4) {
    x.open("transform", &[("name", name)]);
    x.leaf("matrix", &[("value", &matrix_value(m))]);
    x.close("transform");
}

/// The rectangle `to_world` whose image of [-1, 1]² is the quad, such that the importer's
/// `to_world · (-1, -1, 0)` (computed as it computes it) is `corner` exactly and
/// `to_world · (2, 0, 0)`, `· (0, 2, 0)` are the edges (halving is exact).
pub(crate) fn rectangle_matrix(corner: DVec3, edge_u: DVec3, edge_v: DVec3) -> DMat4 {
    let n = edge_u.cross(edge_v).normalize();
    let (x, y) = (edge_u * 0.5, edge_v * 0.5);
    let mut t = corner + x + y;
    let m = |t: DVec3| {
        DMat4::from_cols(
            x.extend(0.0),
            y.extend(0.0),
            n.extend(0.0),
            DVec4::new(t.x, t.y, t.z, 1.0),
        )
    };
    let at = DVec3::new(-1.0, -1.0, 0.0);
    for axis in 0..3 {
        // The corner as a function of t[axis] is monotone: step towards it one ulp at a time
        // (after a first correction), up to a bound; rounding can rarely leave it one ulp off.
        let err = m(t).transform_point3(at)[axis] - corner[axis];
        t[axis] -= err;
        for _ in 0..64 {
            let got = m(t).transform_point3(at)[axis];
            if got == corner[axis] {
                break;
            }
            t[axis] = if got < corner[axis] {
                t[axis].next_up()
            } else {
                t[axis].next_down()
            };
        }
    }
    m(t)
}

/// A disk's `to_world`: Mitsuba's unit disk at z = 0 facing +z, scaled by `radius` in its plane.
fn disk_matrix(center: DVec3, normal: DVec3, radius: f64) -> DMat4 {
    let (a, b) = match axis_perpendicular(normal) {
        Some(a) => (a, normal.cross(a)),
        None => super::transform::coordinate_system(normal),
    };
    // Right-handed, so that the importer's normal (inverse transpose · z) is +normal.
    let b = if DMat3::from_cols(a, b, normal).determinant() < 0.0 {
        -b
    } else {
        b
    };
    DMat4::from_cols(
        (a * radius).extend(0.0),
        (b * radius).extend(0.0),
        normal.extend(0.0),
        center.extend(1.0),
    )
}

/// For an axis-aligned unit `n`, the next axis (a unit vector perpendicular to it).
fn axis_perpendicular(n: DVec3) -> Option<DVec3> {
    let axes = [DVec3::X, DVec3::Y, DVec3::Z];
    let i = axes.iter().position(|a| n.abs() == *a)?;
    Some(axes[(i + 1) % 3])
}
