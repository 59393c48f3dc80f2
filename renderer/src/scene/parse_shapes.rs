//! The `shapes` list: each shape's geometry, material reference and emission.

use super::desc::{GeometryDesc, NamedMaterial, ShapeDesc};
use super::error::SceneError;
use super::parse::check_radiance;
use super::parse_mesh::{DEGENERATE_TRIANGLE, polygon, triangles};
use super::parse_mesh_file::mesh;
use super::parse_texture::{TextureLoader, TextureUse, texture_at};
use super::walk::Obj;
use glam::DVec3;
use serde_json::Value;
use std::path::Path;

/// Every shape, in file order; degenerate non-emitting triangles are dropped into `warnings`.
/// `mesh` files are relative to `folder`; emission textures come from `loader`.
pub(crate) fn parse_shapes(
    items: &[Value],
    materials: &[NamedMaterial],
    folder: &Path,
    loader: &mut TextureLoader,
    warnings: &mut Vec<String>,
) -> Result<Vec<ShapeDesc>, SceneError> {
    items
        .iter()
        .enumerate()
        .map(|(i, v)| {
            parse_shape(
                &Obj::new(v, format!("shapes[{i}]"))?,
                materials,
                folder,
                loader,
                warnings,
            )
        })
        .collect()
}

fn parse_shape(
    obj: &Obj,
    materials: &[NamedMaterial],
    folder: &Path,
    loader: &mut TextureLoader,
    warnings: &mut Vec<String>,
) -> Result<ShapeDesc, SceneError> {
    let kind = obj.string("type")?;
    let fields: &[&str] = match kind {
        "quad" => &["corner", "edge_u", "edge_v"],
        "polygon" => &["vertices"],
        "triangles" => &["positions", "indices"],
        "disk" => &["center", "normal", "radius", "u_axis"],
        "sphere" => &["center", "radius", "pole", "u_axis"],
        "cylinder" => &["p0", "p1", "radius", "u_axis", "flip_normals"],
        "box" => &["min", "max", "rotate_y_deg", "translate"],
        "mesh" => &[
            "file",
            "shape_index",
            "to_world",
            "face_normals",
            "recompute_normals",
        ],
        other => {
            return Err(SceneError::new(
                obj.at("type"),
                format!(
                    "unknown shape type `{other}` \
                     (expected quad, polygon, triangles, mesh, disk, sphere, cylinder or box)"
                ),
            ));
        }
    };
    let mut allowed = vec!["type", "material", "emission"];
    allowed.extend(fields);
    obj.only_keys(&allowed, true)?;

    let material = match obj.get("material") {
        None => None,
        Some(_) => Some(material_index(obj, materials)?),
    };
    // A texture's texels are checked as it loads; its mean stands in for the constant.
    let emission_texture = texture_at(obj, "emission", TextureUse::Emission, loader)?;
    let emission = match &emission_texture {
        Some(t) => t.mean_color(),
        None => obj.opt_vec3("emission")?.unwrap_or(DVec3::ZERO),
    };
    check_radiance(emission, &obj.at("emission"))?;
    let emits = emission != DVec3::ZERO
        || emission_texture
            .as_ref()
            .is_some_and(|t| t.texture.max().max_element() > 0.0);

    let geometry = match kind {
        "quad" => quad(obj)?,
        "polygon" => polygon(obj)?,
        "triangles" => triangles(obj, emits, warnings)?,
        "mesh" => mesh(obj, folder, loader, emits, warnings)?,
        "disk" => {
            let normal = obj.vec3("normal")?;
            if normal == DVec3::ZERO {
                return Err(SceneError::new(obj.at("normal"), "zero-length normal"));
            }
            let (center, radius) = (obj.vec3("center")?, radius(obj)?);
            GeometryDesc::Disk {
                center,
                normal: unit(normal),
                radius,
                u_axis: u_axis(obj, normal, "normal")?,
            }
        }
        "sphere" => {
            let pole = obj.opt_vec3("pole")?;
            if pole == Some(DVec3::ZERO) {
                return Err(SceneError::new(obj.at("pole"), "zero-length pole"));
            }
            GeometryDesc::Sphere {
                center: obj.vec3("center")?,
                radius: radius(obj)?,
                pole,
                u_axis: u_axis(obj, pole.unwrap_or(DVec3::Z), "pole")?,
            }
        }
        "cylinder" => cylinder(obj, emits)?,
        _ => boxed(obj)?,
    };
    let analytic = matches!(
        geometry,
        GeometryDesc::Disk { .. } | GeometryDesc::Sphere { .. } | GeometryDesc::Cylinder { .. }
    );
    if analytic && material.is_some_and(|m| bump_mapped(materials, m, 0)) {
        let msg = format!(
            "a bump map on a {kind}: lumis has ∂p/∂v only for triangles (meshes, quads, \
             polygons, boxes), and a bump map needs both partials"
        );
        return Err(SceneError::new(obj.at("material"), msg));
    }
    Ok(ShapeDesc {
        geometry,
        material,
        emission,
        emission_texture,
        json_path: obj.path.clone(),
    })
}

/// Whether material `m`, or one a mix may choose through it, has a bump map (mix chains were
/// checked for cycles with the materials; `depth` bounds the walk all the same).
fn bump_mapped(materials: &[NamedMaterial], m: usize, depth: usize) -> bool {
    let named = &materials[m];
    match &named.mix {
        Some(mix) if depth < materials.len() => mix
            .materials
            .iter()
            .any(|&c| bump_mapped(materials, c, depth + 1)),
        Some(_) => false,
        None => named
            .normal_map
            .as_ref()
            .is_some_and(|n| n.height_scale.is_some()),
    }
}

fn material_index(obj: &Obj, materials: &[NamedMaterial]) -> Result<usize, SceneError> {
    let name = obj.string("material")?;
    materials
        .iter()
        .position(|m| m.name == name)
        .ok_or_else(|| {
            let known: Vec<&str> = materials.iter().map(|m| m.name.as_str()).collect();
            let known = if known.is_empty() {
                "no materials are defined".to_owned()
            } else {
                format!("defined: {}", known.join(", "))
            };
            SceneError::new(
                obj.at("material"),
                format!("unknown material `{name}` ({known})"),
            )
        })
}

/// `v / |v|` for any non-zero `v`, but unchanged when `v` is already unit to rounding, so that
/// normalising is idempotent and a saved and reloaded scene compares equal.
pub(crate) fn unit(v: DVec3) -> DVec3 {
    let len = v.length();
    if (len - 1.0).abs() <= 4.0 * f64::EPSILON {
        v
    } else {
        // Scaled by the largest component first: the length of `[1e-300, 0, 0]` underflows to 0
        // (a NaN normal) and that of `[1e300, 1e300, 0]` overflows.
        let v = v / v.abs().max_element();
        v / v.length()
    }
}

fn radius(obj: &Obj) -> Result<f64, SceneError> {
    let r = obj.number("radius")?;
    if r <= 0.0 {
        return Err(SceneError::new(
            obj.at("radius"),
            format!("radius must be positive, found {r}"),
        ));
    }
    Ok(r)
}

/// The optional `u_axis` of an analytic shape: where its texture coordinates' φ = 0 lies, which
/// must not be zero or along `axis` (the shape's `what`: its normal, pole or axis).
fn u_axis(obj: &Obj, axis: DVec3, what: &str) -> Result<Option<DVec3>, SceneError> {
    let u = obj.opt_vec3("u_axis")?;
    if let Some(u) = u
        && u.cross(axis).length() <= 1e-6 * u.length() * axis.length()
    {
        return Err(SceneError::new(
            obj.at("u_axis"),
            format!("u_axis is zero or parallel to the shape's {what}"),
        ));
    }
    Ok(u)
}

fn cylinder(obj: &Obj, emits: bool) -> Result<GeometryDesc, SceneError> {
    if emits {
        return Err(SceneError::new(
            obj.at("emission"),
            "a cylinder cannot emit: lumis has no cylinder light (use a mesh)",
        ));
    }
    let (p0, p1, radius) = (obj.vec3("p0")?, obj.vec3("p1")?, radius(obj)?);
    let axis = p1 - p0;
    if axis == DVec3::ZERO {
        return Err(SceneError::new(
            obj.at("p1"),
            "p1 equals p0: the cylinder has no height",
        ));
    }
    Ok(GeometryDesc::Cylinder {
        p0,
        p1,
        radius,
        u_axis: u_axis(obj, axis, "axis p1 − p0")?,
        flip_normals: obj.opt_bool("flip_normals")?.unwrap_or(false),
    })
}

fn quad(obj: &Obj) -> Result<GeometryDesc, SceneError> {
    let (corner, edge_u, edge_v) = (
        obj.vec3("corner")?,
        obj.vec3("edge_u")?,
        obj.vec3("edge_v")?,
    );
    for (key, edge) in [("edge_u", edge_u), ("edge_v", edge_v)] {
        if edge == DVec3::ZERO {
            return Err(SceneError::new(
                obj.at(key),
                "zero-length edge: the quad has no area",
            ));
        }
    }
    if edge_u.cross(edge_v).length() <= DEGENERATE_TRIANGLE * edge_u.length() * edge_v.length() {
        return Err(SceneError::new(
            obj.at("edge_v"),
            "`edge_v` is parallel to `edge_u`: the quad has no area",
        ));
    }
    Ok(GeometryDesc::Quad {
        corner,
        edge_u,
        edge_v,
    })
}

fn boxed(obj: &Obj) -> Result<GeometryDesc, SceneError> {
    let (min, max) = (obj.vec3("min")?, obj.vec3("max")?);
    if let Some(axis) = (0..3).find(|&a| min[a] >= max[a]) {
        let name = ["x", "y", "z"][axis];
        return Err(SceneError::new(
            obj.at("max"),
            format!(
                "max must exceed min on every axis, but on {name}: max {} ≤ min {}",
                max[axis], min[axis]
            ),
        ));
    }
    let rotate_y_deg = obj.opt_number("rotate_y_deg")?.unwrap_or(0.0);
    let translate = obj.opt_vec3("translate")?.unwrap_or(DVec3::ZERO);
    Ok(GeometryDesc::Box {
        min,
        max,
        rotate_y_deg,
        translate,
    })
}

#[cfg(test)]
mod tests {
    use crate::scene::desc::GeometryDesc;
    use crate::scene::parse::parse_scene_value;
    use crate::scene::tests::{base, expect_err, with};
    use glam::DVec3;
    use serde_json::json;

    #[test]
    fn every_shape_type_parses() {
        let d = parse_scene_value(&base()).unwrap();
        assert!(d.warnings.is_empty(), "{:?}", d.warnings);
        assert_eq!(d.shapes.len(), 6);
        assert_eq!(d.shapes[5].json_path, "shapes[5]");
        assert_eq!(d.shapes[0].material, Some(3)); // "white", the last in name order
        assert!(
            matches!(&d.shapes[1].geometry, GeometryDesc::Polygon { vertices } if vertices.len() == 6)
        );
        assert_eq!(d.shapes[1].emission, DVec3::splat(4.0));
        let GeometryDesc::Disk { normal, .. } = d.shapes[3].geometry else {
            panic!()
        };
        assert_eq!(normal, DVec3::new(0.0, -1.0, 0.0)); // normalised from [0, -2, 0]
        let GeometryDesc::Box {
            rotate_y_deg,
            translate,
            ..
        } = d.shapes[5].geometry
        else {
            panic!()
        };
        assert_eq!((rotate_y_deg, translate), (0.0, DVec3::ZERO));
    }

    #[test]
    fn structure_rules() {
        let s = with(4, json!({"type": "cone", "center": [0, 0, 0], "radius": 1}));
        expect_err(&s, "shapes[4].type", "unknown shape type `cone`");
        let s = with(4, json!({"center": [0, 0, 0], "radius": 1}));
        expect_err(&s, "shapes[4].type", "missing required key `type`");
        let s = with(
            4,
            json!({"type": "sphere", "center": [0, 0, 0], "radius": 1, "normal": [0, 1, 0]}),
        );
        expect_err(&s, "shapes[4].normal", "unknown key `normal`");
        let s = with(4, json!({"type": "sphere", "center": [0, 0, 0]}));
        expect_err(&s, "shapes[4].radius", "missing required key `radius`");
        let s = with(
            4,
            json!({"type": "sphere", "center": [0, 0, 0], "radius": 1, "comment": "x", "name": "s"}),
        );
        assert!(parse_scene_value(&s).is_ok());
        let s = with(4, json!("sphere"));
        expect_err(&s, "shapes[4]", "expected an object, found a string");
    }

    /// The cylinder's keys, its defaults, the description written back, and each bad input as
    /// one error at its key.
    #[test]
    fn cylinder_keys_and_errors() {
        let c = json!({"type": "cylinder", "p0": [0, 0, 0], "p1": [0, 2, 0], "radius": 0.5,
                       "u_axis": [1, 1, 0], "flip_normals": true});
        let d = parse_scene_value(&with(4, c.clone())).unwrap();
        let GeometryDesc::Cylinder {
            p1,
            radius,
            u_axis,
            flip_normals,
            ..
        } = d.shapes[4].geometry
        else {
            panic!("{:?}", d.shapes[4].geometry)
        };
        assert_eq!((p1, radius), (DVec3::new(0.0, 2.0, 0.0), 0.5));
        assert_eq!(
            (u_axis, flip_normals),
            (Some(DVec3::new(1.0, 1.0, 0.0)), true)
        );
        let again = parse_scene_value(&d.to_json()).unwrap();
        assert_eq!(again.shapes[4].geometry, d.shapes[4].geometry);
        let plain = json!({"type": "cylinder", "p0": [0, 0, 0], "p1": [0, 0, 1], "radius": 1});
        let d = parse_scene_value(&with(4, plain)).unwrap();
        assert!(matches!(
            d.shapes[4].geometry,
            GeometryDesc::Cylinder {
                u_axis: None,
                flip_normals: false,
                ..
            }
        ));
        let bad = |key: &str, value: serde_json::Value| {
            let mut c = c.clone();
            c[key] = value;
            with(4, c)
        };
        expect_err(
            &bad("radius", json!(0)),
            "shapes[4].radius",
            "must be positive",
        );
        expect_err(&bad("p1", json!([0, 0, 0])), "shapes[4].p1", "no height");
        expect_err(
            &bad("u_axis", json!([0, -3, 0])),
            "shapes[4].u_axis",
            "parallel to the shape's axis p1 − p0",
        );
        expect_err(
            &bad("emission", json!([1, 1, 1])),
            "shapes[4].emission",
            "a cylinder cannot emit",
        );
    }

    /// A sphere's `pole` and `u_axis` and a disk's `u_axis` (version 3): kept as given, written
    /// back, and refused where they leave no frame.
    #[test]
    fn sphere_and_disk_texture_frames() {
        let sphere = json!({"type": "sphere", "center": [0, 0, 0], "radius": 1,
                            "pole": [0, 1, 0], "u_axis": [1, 0, 1]});
        let disk = json!({"type": "disk", "center": [0, 0, 0], "normal": [0, 1, 0], "radius": 1,
                          "u_axis": [0, 0, 2]});
        for shape in [&sphere, &disk] {
            let d = parse_scene_value(&with(4, shape.clone())).unwrap();
            let again = parse_scene_value(&d.to_json()).unwrap();
            assert_eq!(again.shapes[4].geometry, d.shapes[4].geometry);
        }
        let d = parse_scene_value(&with(4, sphere.clone())).unwrap();
        assert!(matches!(
            d.shapes[4].geometry,
            GeometryDesc::Sphere {
                pole: Some(p),
                u_axis: Some(u),
                ..
            } if p == DVec3::Y && u == DVec3::new(1.0, 0.0, 1.0)
        ));
        let mut bad = sphere.clone();
        bad["u_axis"] = json!([0, -2, 0]);
        expect_err(
            &with(4, bad),
            "shapes[4].u_axis",
            "parallel to the shape's pole",
        );
        let mut bad = sphere.clone();
        bad["pole"] = json!([0, 0, 0]);
        expect_err(&with(4, bad), "shapes[4].pole", "zero-length pole");
        let mut bad = disk.clone();
        bad["u_axis"] = json!([0, 3, 0]);
        expect_err(
            &with(4, bad),
            "shapes[4].u_axis",
            "parallel to the shape's normal",
        );
    }

    #[test]
    fn unknown_material_name() {
        let s = with(
            4,
            json!({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "gold"}),
        );
        expect_err(
            &s,
            "shapes[4].material",
            "unknown material `gold` (defined: copper, metal",
        );
        let s = with(
            4,
            json!({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": 3}),
        );
        expect_err(&s, "shapes[4].material", "expected a string");
    }

    #[test]
    fn negative_emission() {
        let s = with(
            4,
            json!({"type": "sphere", "center": [0, 0, 0], "radius": 1, "emission": [1, 1, -1]}),
        );
        expect_err(&s, "shapes[4].emission[2]", "negative");
    }

    #[test]
    fn radius_must_be_positive() {
        for r in [0.0, -1.0] {
            let s = with(
                4,
                json!({"type": "sphere", "center": [0, 0, 0], "radius": r}),
            );
            expect_err(&s, "shapes[4].radius", "radius must be positive");
            let s = with(
                3,
                json!({"type": "disk", "center": [0, 0, 0], "normal": [0, 1, 0], "radius": r}),
            );
            expect_err(&s, "shapes[3].radius", "radius must be positive");
        }
    }

    #[test]
    fn zero_length_disk_normal() {
        let s = with(
            3,
            json!({"type": "disk", "center": [0, 0, 0], "normal": [0, 0, 0], "radius": 1}),
        );
        expect_err(&s, "shapes[3].normal", "zero-length normal");
    }

    #[test]
    fn degenerate_quad() {
        let q = |u: [f64; 3], v: [f64; 3]| {
            with(
                0,
                json!({"type": "quad", "corner": [0, 0, 0], "edge_u": u, "edge_v": v}),
            )
        };
        expect_err(
            &q([0., 0., 0.], [1., 0., 0.]),
            "shapes[0].edge_u",
            "zero-length edge",
        );
        expect_err(
            &q([1., 0., 0.], [-3., 0., 0.]),
            "shapes[0].edge_v",
            "parallel",
        );
    }

    #[test]
    fn box_needs_min_below_max() {
        let s = with(
            5,
            json!({"type": "box", "min": [0, 2, 0], "max": [1, 2, 1]}),
        );
        expect_err(&s, "shapes[5].max", "on y: max 2 ≤ min 2");
        let s = with(
            5,
            json!({"type": "box", "min": [0, 0, 0], "max": [1, 1, 1], "rotate_y_deg": "10"}),
        );
        expect_err(&s, "shapes[5].rotate_y_deg", "expected a number");
    }
}
