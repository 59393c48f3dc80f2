//! Shapes: `obj`, `ply`, `serialized` (lumis' `mesh`), `rectangle` (a `quad`), `cube`
//! (`triangles`), `disk`, `sphere` and `cylinder`, with `to_world`, `flip_normals` and
//! `face_normals`, their BSDF and area emitter.
//!
//! Mitsuba's rectangle is `to_world` of [-1, 1]² at z = 0 with normal +z and `uv` = the
//! position in [0, 1]², which is lumis' quad from `to_world(-1, -1, 0)` with edges
//! `to_world(2, 0, 0)` and `to_world(0, 2, 0)` (u along the first edge, normal `edge_u × edge_v`).
//! Its cube is `to_world` of [-1, 1]³ with outward normals; its disk the unit disk at z = 0
//! facing +z; its sphere `to_world · translate(center) · scale(radius)` of the unit sphere; its
//! cylinder `to_world · translate(p0) · to_frame(p1 − p0) · scale(r, r, |p1 − p0|)` of the unit
//! tube around [0, 1] on z, whose x axis is where `u = 0`.
//! A shape without a BSDF gets Mitsuba's default, a one-sided diffuse of reflectance 0.5 (0 if
//! it emits); a `null` BSDF without an emitter is invisible and is left out.

use super::bsdf::material;
use super::emitter::area;
use super::plugin::Plugin;
use super::transform::rows_json;
use super::{Ctx, target};
use crate::scene::error::SceneError;
use glam::{DMat3, DMat4, DVec3, DVec4};
use serde_json::{Value as Json, json};

/// Name of the material standing in for Mitsuba's default BSDF.
const DEFAULT_MATERIAL: &str = "mitsuba_default_diffuse";

/// The scene format's shape for `s`, to go at `shapes[index]`; `None` when it is invisible.
pub fn shape(ctx: &mut Ctx, s: &Plugin, index: usize) -> Result<Option<Json>, SceneError> {
    placed(ctx, s, index, &DMat4::IDENTITY)
}

/// Mitsuba's `instance` of a `shapegroup`, flattened into the scene: each shape of the group
/// placed by the instance's `to_world` after its own, to go at `shapes[index..]`, with where
/// each was declared. lumis has no instancing of its own (a flattened instance costs what its
/// shapes cost, docs/mitsuba.md), so the instance's `to_world` must be a similarity (a rotation,
/// a uniform scale and a translation): under it a flattened sphere, disk or cylinder stays one
/// and a mesh's recomputed normals are Mitsuba's, which computes them in the group's space.
/// Mitsuba's own refusals are kept: one shapegroup per instance, no nested groups or instances,
/// no emitters in a group.
pub fn instance(
    ctx: &mut Ctx,
    s: &Plugin,
    index: usize,
) -> Result<Vec<(Json, super::xml::Pos)>, SceneError> {
    let outer = match s.transform("to_world")? {
        None => DMat4::IDENTITY,
        Some((m, p)) => {
            let m3 = DMat3::from_mat4(m);
            let det = m3.determinant();
            let scale = det.cbrt();
            let r = m3 / scale;
            let orthonormal = (r.transpose() * r - DMat3::IDENTITY)
                .to_cols_array()
                .iter()
                .all(|x| x.abs() < 1e-6);
            if !(det > 0.0 && orthonormal) {
                return Err(p.el.pos.error(
                    "an instance's to_world must be a rotation, a uniform scale and a \
                     translation: lumis flattens instances into the scene, and a flattened \
                     sphere, disk or cylinder cannot follow a shear, a non-uniform scale or a \
                     mirror as Mitsuba's instance does",
                ));
            }
            m
        }
    };
    let groups = s.objects("shape");
    let [group] = groups.as_slice() else {
        return Err(s.error("an instance names exactly one shapegroup (as in Mitsuba)"));
    };
    let group = ctx.plugin(target(group))?;
    if group.ty != "shapegroup" {
        return Err(group.error(format!(
            "an instance names a shapegroup, not a `{}` (as in Mitsuba)",
            group.ty
        )));
    }
    s.finish("to_world, one shapegroup")?;
    let mut out = Vec::new();
    for child in group.objects("shape") {
        let c = ctx.plugin(target(child))?;
        if matches!(c.ty, "shapegroup" | "instance") {
            return Err(c.error(
                "a shapegroup inside a shapegroup, or an instance in one, is not allowed (nor \
                 in Mitsuba)",
            ));
        }
        if let Some(e) = c.objects("emitter").first() {
            return Err(e.el.pos.error(
                "an emitter in a shapegroup is not allowed (Mitsuba does not instance emitters)",
            ));
        }
        if let Some(obj) = placed(ctx, &c, index + out.len(), &outer)? {
            out.push((obj, c.pos().clone()));
        }
    }
    group.finish("shapes (the group's)")?;
    Ok(out)
}

/// [`shape`] with the shape's `to_world` applied after `outer` (an instance's).
fn placed(
    ctx: &mut Ctx,
    s: &Plugin,
    index: usize,
    outer: &DMat4,
) -> Result<Option<Json>, SceneError> {
    let path = format!("shapes[{index}]");
    ctx.origin(&path, s.pos());
    if let Some(medium) = s.objects("medium").first() {
        return Err(medium
            .el
            .pos
            .error("media (interior/exterior) are not supported"));
    }
    if let Some(p) = s.objects("sensor").first() {
        return Err(p
            .el
            .pos
            .error("a sensor attached to a shape is not supported"));
    }
    let emission = match s.object("emitter")? {
        Some(p) => {
            let e = ctx.plugin(target(p))?;
            // Mitsuba: "an endpoint can only be attached to a single shape".
            if let Some(first) = ctx.area_owners.insert(e.el as *const _, s.pos().clone()) {
                return Err(p.el.pos.error(format!(
                    "this area emitter is already attached to the shape at {} (Mitsuba \
                     attaches an emitter to one shape)",
                    first.describe()
                )));
            }
            Some(area(ctx, &e, &format!("{path}.emission"))?)
        }
        None => None,
    };
    let mat = match s.object("bsdf")? {
        Some(p) => {
            let el = target(p);
            ctx.origin(&format!("{path}.material"), &p.el.pos);
            match material(ctx, el)? {
                Some(name) => Some(name),
                None if emission.is_some() => {
                    return Err(p.el.pos.error(
                        "an emitting shape with a null BSDF is not supported: lumis' surfaces \
                         always block rays",
                    ));
                }
                None => {
                    s.ignore(&SHAPE_PROPERTIES);
                    return Ok(None);
                }
            }
        }
        // Mitsuba's default; black (lumis' "no material") when the shape emits.
        None if emission.is_some() => None,
        None => {
            ctx.materials.entry(DEFAULT_MATERIAL).or_insert_with(
                || json!({"type": "diffuse", "albedo": [0.5, 0.5, 0.5], "two_sided": false}),
            );
            Some(DEFAULT_MATERIAL.to_owned())
        }
    };
    let textured = emission.as_ref().is_some_and(Json::is_object)
        || mat.as_ref().is_some_and(|m| {
            ctx.materials
                .get(m)
                .and_then(Json::as_object)
                .is_some_and(|o| o.values().any(Json::is_object))
        });
    let flip = s.bool("flip_normals", false)?;
    let (to_world, tpos) = match s.transform("to_world")? {
        Some((m, p)) => {
            ctx.origin(&format!("{path}.to_world"), &p.el.pos);
            (*outer * m, p.el.pos.clone())
        }
        None => (*outer, s.pos().clone()),
    };
    // Importance of silhouettes for differentiable rendering only.
    s.ignore(&["silhouette_sampling_weight"]);
    // [α_u, α_v]: the BSDF follows the surface's ∂p/∂u (`geometry/tangent.rs`).
    let anisotropic = mat.as_ref().is_some_and(|m| {
        ctx.materials
            .get(m)
            .and_then(|o| o.get("alpha"))
            .is_some_and(Json::is_array)
    });
    let no_uv = |what: &str| -> Result<(), SceneError> {
        if textured {
            return Err(s.error(format!(
                "a textured {what} is not supported: lumis gives it no texture coordinates \
                 like Mitsuba's"
            )));
        }
        if anisotropic {
            return Err(s.error(format!(
                "an anisotropic BSDF on a {what} is not supported: lumis gives it no surface \
                 tangents like Mitsuba's"
            )));
        }
        Ok(())
    };
    let mirror = DMat3::from_mat4(to_world).determinant() < 0.0;
    if mirror && matches!(s.ty, "rectangle" | "cube" | "disk") {
        return Err(tpos.error(format!(
            "a mirroring to_world (negative determinant) on a {} is not supported: its \
             geometric and shading normals would disagree",
            s.ty
        )));
    }
    let mut obj = match s.ty {
        "obj" | "ply" | "serialized" => {
            let (file, fp) = s
                .string("filename")?
                .ok_or_else(|| s.error(format!("a `{}` shape needs `filename`", s.ty)))?;
            ctx.origin(&format!("{path}.file"), fp.pos());
            let file = ctx.resolve_file(file);
            if flip {
                return Err(s.get("flip_normals").map_or_else(
                    || s.error("flip_normals"),
                    |p| p.error("flip_normals = true is not supported on mesh files"),
                ));
            }
            let flip_default = s.ty == "obj";
            if s.ty != "serialized" && s.bool("flip_tex_coords", flip_default)? != flip_default {
                return Err(s.get("flip_tex_coords").map_or_else(
                    || s.error("flip_tex_coords"),
                    |p| {
                        p.error(format!(
                            "flip_tex_coords = {} is not supported (lumis reads {} texture \
                             coordinates as Mitsuba does by default)",
                            !flip_default, s.ty
                        ))
                    },
                ));
            }
            let mut m = json!({
                "type": "mesh", "file": file, "to_world": rows_json(&to_world),
                "face_normals": s.bool("face_normals", false)?,
                // Mitsuba computes smooth normals where the file has none.
                "recompute_normals": true,
            });
            if s.ty == "serialized" {
                let index = s.int("shape_index", 0)?;
                if let Some(p) = s.get("shape_index") {
                    ctx.origin(&format!("{path}.shape_index"), p.pos());
                }
                m["shape_index"] = json!(index);
            }
            m
        }
        "rectangle" => {
            if flip {
                no_uv("flipped rectangle")?;
            }
            let corner = to_world.transform_point3(DVec3::new(-1.0, -1.0, 0.0));
            let mut eu = to_world.transform_vector3(DVec3::new(2.0, 0.0, 0.0));
            let mut ev = to_world.transform_vector3(DVec3::new(0.0, 2.0, 0.0));
            if flip {
                std::mem::swap(&mut eu, &mut ev);
            }
            ctx.origin(&format!("{path}.edge_u"), &tpos);
            ctx.origin(&format!("{path}.edge_v"), &tpos);
            json!({"type": "quad", "corner": corner.to_array(), "edge_u": eu.to_array(),
                   "edge_v": ev.to_array()})
        }
        "cube" => {
            no_uv("cube")?;
            let (positions, indices) = cube(&to_world, flip);
            json!({"type": "triangles", "positions": positions, "indices": indices})
        }
        "disk" => {
            if flip {
                no_uv("flipped disk")?;
            }
            let m = DMat3::from_mat4(to_world);
            let (du, dv) = (m.x_axis, m.y_axis);
            let r = du.length();
            if (dv.length() - r).abs() > 1e-6 * r || du.dot(dv).abs() > 1e-6 * r * r {
                return Err(tpos.error(
                    "the disk's to_world makes it an ellipse, which lumis' disk cannot be",
                ));
            }
            // Normals transform by the inverse transpose.
            let mut n = m.inverse().transpose() * DVec3::Z;
            if flip {
                n = -n;
            }
            ctx.origin(&format!("{path}.radius"), &tpos);
            let mut d = json!({"type": "disk", "center": to_world.w_axis.truncate().to_array(),
                               "normal": n.to_array(), "radius": r});
            // Mitsuba's φ = 0 at its object x axis (what else only a texture sees).
            if textured {
                ctx.origin(&format!("{path}.u_axis"), &tpos);
                d["u_axis"] = json!((du / r).to_array());
            }
            d
        }
        "sphere" => {
            let center = s.vector("center", DVec3::ZERO)?;
            let radius = s.float("radius", 1.0)?;
            if let Some(p) = s.get("radius") {
                ctx.origin(&format!("{path}.radius"), p.pos());
            }
            let m = to_world
                * DMat4::from_translation(center)
                * DMat4::from_scale(DVec3::splat(radius));
            let m3 = DMat3::from_mat4(m);
            let r = m3.x_axis.length();
            let lengths = [m3.y_axis.length(), m3.z_axis.length()];
            if lengths.iter().any(|l| (l - r).abs() > 1e-6 * r)
                || m3.x_axis.dot(m3.y_axis).abs() > 1e-6 * r * r
            {
                ctx.warnings.push(format!(
                    "{}: the sphere's to_world scales non-uniformly; like Mitsuba, lumis \
                     renders a sphere of radius |to_world · x| = {r}",
                    tpos.describe()
                ));
            }
            if flip != (m3.determinant() < 0.0) {
                return Err(s.error(
                    "a sphere with inward normals (flip_normals, or a negative scale) is not \
                     supported: lumis' spheres face outward",
                ));
            }
            let mut sphere =
                json!({"type": "sphere", "center": m.w_axis.truncate().to_array(), "radius": r});
            // Mitsuba's texture frame is its object frame (what else only a texture or an
            // anisotropic BSDF sees); a non-uniform scale leaves no frame to give.
            let (x, z) = (m3.x_axis / r, m3.z_axis / r);
            if (textured || anisotropic) && (x != DVec3::X || z != DVec3::Z) {
                if let Err(e) = crate::scene::parse_background::proper_rotation(m3 / r) {
                    return Err(tpos.error(format!(
                        "a textured or anisotropic sphere needs a to_world of a rotation and a \
                         uniform scale (its texture frame): {e}"
                    )));
                }
                ctx.origin(&format!("{path}.pole"), &tpos);
                ctx.origin(&format!("{path}.u_axis"), &tpos);
                sphere["pole"] = json!(z.to_array());
                sphere["u_axis"] = json!(x.to_array());
            }
            sphere
        }
        "cylinder" => cylinder(ctx, s, &path, &to_world, &tpos, flip, emission.is_some())?,
        other => {
            return Err(s.error(format!(
                "shape type `{other}` is not supported; lumis maps obj, ply, serialized, \
                 rectangle, cube, disk, sphere and cylinder, and instances of shapegroups"
            )));
        }
    };
    s.finish(
        "filename, to_world, face_normals, flip_normals (not on meshes or spheres), shape_index \
         (serialized), center and radius (sphere), p0, p1 and radius (cylinder), one bsdf, one \
         area emitter",
    )?;
    if let Some(name) = mat {
        obj["material"] = json!(name);
    }
    if let Some(e) = emission {
        obj["emission"] = e;
    }
    Ok(Some(obj))
}

/// Mitsuba's cylinder as lumis' (`p0`, `p1`, `radius` read here): its object-to-world matrix
/// maps the unit tube's axis [0, 1]·z to the segment and its x axis to `u_axis`. Refused, each
/// with its position: an emitting cylinder (lumis has no cylinder light), one whose `to_world`
/// mirrors it (Mitsuba's normals would then point inward by its cross product, lumis' by its
/// radius vector) or makes it elliptic or slanted (shear or unequal x and y scales: Mitsuba
/// only warns and renders an elliptic tube with a circle's area).
fn cylinder(
    ctx: &mut Ctx,
    s: &Plugin,
    path: &str,
    to_world: &DMat4,
    tpos: &super::xml::Pos,
    flip: bool,
    emits: bool,
) -> Result<Json, SceneError> {
    if emits {
        return Err(s.error(
            "an emitting cylinder is not supported: lumis has no cylinder light (use a mesh)",
        ));
    }
    let radius = s.float("radius", 1.0)?;
    let p0 = s.vector("p0", DVec3::ZERO)?;
    let p1 = s.vector("p1", DVec3::Z)?;
    for key in ["radius", "p0", "p1"] {
        if let Some(p) = s.get(key) {
            ctx.origin(&format!("{path}.{key}"), p.pos());
        }
    }
    let d = p1 - p0;
    let length = d.length();
    if !(radius > 0.0 && length > 0.0) {
        return Err(s.error(format!(
            "a cylinder needs a positive radius and p1 ≠ p0 (radius {radius}, height {length})"
        )));
    }
    let z = d / length;
    let (x, y) = super::transform::coordinate_system(z);
    let frame = DMat4::from_cols(x.extend(0.0), y.extend(0.0), z.extend(0.0), DVec4::W);
    let m = *to_world
        * DMat4::from_translation(p0)
        * frame
        * DMat4::from_scale(DVec3::new(radius, radius, length));
    let m3 = DMat3::from_mat4(m);
    let (ex, ey, axis) = (m3.x_axis, m3.y_axis, m3.z_axis);
    let r = ex.length();
    let h = axis.length();
    let round = 1e-6;
    if m3.determinant() < 0.0 {
        return Err(tpos.error(
            "a mirroring to_world (negative determinant) on a cylinder is not supported: \
             Mitsuba's normals would point inward",
        ));
    }
    if (ey.length() - r).abs() > round * r
        || ex.dot(ey).abs() > round * r * r
        || ex.dot(axis).abs() > round * r * h
        || ey.dot(axis).abs() > round * r * h
    {
        return Err(tpos.error(
            "the cylinder's to_world shears it or scales its x and y differently (an elliptic \
             or slanted tube), which lumis' cylinder cannot be",
        ));
    }
    ctx.origin(&format!("{path}.u_axis"), tpos);
    let p0w = m.w_axis.truncate();
    let mut c = json!({
        "type": "cylinder", "p0": p0w.to_array(), "p1": (p0w + axis).to_array(),
        "radius": r, "u_axis": (ex / r).to_array(),
    });
    if flip {
        c["flip_normals"] = json!(true);
    }
    Ok(c)
}

/// Every property a shape may have (an invisible shape's are read without effect).
const SHAPE_PROPERTIES: [&str; 11] = [
    "filename",
    "to_world",
    "face_normals",
    "flip_normals",
    "flip_tex_coords",
    "shape_index",
    "center",
    "radius",
    "p0",
    "p1",
    "silhouette_sampling_weight",
];

/// The 8 corners of `to_world([-1, 1]³)` and its 12 triangles, wound outward (inward with
/// `flip`).
fn cube(to_world: &DMat4, flip: bool) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let positions: Vec<[f64; 3]> = (0..8)
        .map(|i| {
            let c = |bit: u32| if i & bit != 0 { 1.0 } else { -1.0 };
            to_world
                .transform_point3(DVec3::new(c(1), c(2), c(4)))
                .to_array()
        })
        .collect();
    // Each face as corners in counter-clockwise order seen from outside.
    let faces: [[u32; 4]; 6] = [
        [1, 3, 7, 5], // +x
        [0, 4, 6, 2], // -x
        [2, 6, 7, 3], // +y
        [0, 1, 5, 4], // -y
        [4, 5, 7, 6], // +z
        [0, 2, 3, 1], // -z
    ];
    let mut indices = Vec::with_capacity(12);
    for [a, b, c, d] in faces {
        for t in [[a, b, c], [a, c, d]] {
            indices.push(if flip { [t[0], t[2], t[1]] } else { t });
        }
    }
    (positions, indices)
}
