//! Shapes given by vertex lists: `polygon` and `triangles`.

use super::desc::GeometryDesc;
use super::error::SceneError;
use super::walk::{Obj, array, integer, vec3};
use crate::geometry::polygon::{PolygonError, validate_polygon};
use glam::DVec3;

/// A triangle whose |cross product| is below this fraction of its longest edge squared has zero
/// area: far above f64 rounding, far below any real sliver.
pub(crate) const DEGENERATE_TRIANGLE: f64 = 1e-10;

/// At most this many dropped triangles are listed by index in a warning.
const LISTED_DROPS: usize = 5;

/// A `polygon`: at least 3 vertices forming a planar, simple, non-degenerate polygon.
pub(crate) fn polygon(obj: &Obj) -> Result<GeometryDesc, SceneError> {
    let path = obj.at("vertices");
    let vertices = array(obj.req("vertices")?, &path)?
        .iter()
        .enumerate()
        .map(|(j, v)| vec3(v, &format!("{path}[{j}]")))
        .collect::<Result<Vec<_>, _>>()?;
    match validate_polygon(&vertices) {
        Ok(_) => Ok(GeometryDesc::Polygon { vertices }),
        Err(e @ PolygonError::RepeatedVertex(j)) => {
            Err(SceneError::new(format!("{path}[{j}]"), e.to_string()))
        }
        Err(e) => Err(SceneError::new(path, e.to_string())),
    }
}

/// Whether a triangle has zero area by the format's rule: |cross product| at most
/// [`DEGENERATE_TRIANGLE`] times its longest edge squared (`triangles` and `mesh` alike).
pub(crate) fn has_zero_area([a, b, c]: [DVec3; 3]) -> bool {
    let longest2 = (b - a)
        .length_squared()
        .max((c - b).length_squared())
        .max((a - c).length_squared());
    let area2 = (b - a).cross(c - a).length();
    // Written so that a NaN area also counts as zero.
    area2.partial_cmp(&(DEGENERATE_TRIANGLE * longest2)) != Some(std::cmp::Ordering::Greater)
}

/// `dropped N zero-area triangle(s): …`, listing at most [`LISTED_DROPS`] of them, each as
/// `label` writes it.
pub(crate) fn dropped_list(dropped: &[usize], label: impl Fn(usize) -> String) -> String {
    let list: Vec<String> = dropped
        .iter()
        .take(LISTED_DROPS)
        .map(|&t| label(t))
        .collect();
    let more = if dropped.len() > LISTED_DROPS {
        ", …"
    } else {
        ""
    };
    format!(
        "dropped {} zero-area triangle(s): {}{more}",
        dropped.len(),
        list.join(", ")
    )
}

/// A `triangles` mesh: indices in range; zero-area triangles are an error when the shape emits
/// (`emits`), otherwise dropped with a warning.
pub(crate) fn triangles(
    obj: &Obj,
    emits: bool,
    warnings: &mut Vec<String>,
) -> Result<GeometryDesc, SceneError> {
    let ppath = obj.at("positions");
    let positions = array(obj.req("positions")?, &ppath)?
        .iter()
        .enumerate()
        .map(|(j, v)| vec3(v, &format!("{ppath}[{j}]")))
        .collect::<Result<Vec<_>, _>>()?;
    let ipath = obj.at("indices");
    let mut indices = Vec::new();
    let mut dropped = Vec::new();
    for (t, tri) in array(obj.req("indices")?, &ipath)?.iter().enumerate() {
        let tpath = format!("{ipath}[{t}]");
        let items = array(tri, &tpath)?;
        if items.len() != 3 {
            let msg = format!("expected 3 vertex indices, found {}", items.len());
            return Err(SceneError::new(tpath, msg));
        }
        let mut idx = [0u32; 3];
        for (c, item) in items.iter().enumerate() {
            let cpath = format!("{tpath}[{c}]");
            let i = integer(item, &cpath, 0, u32::MAX as i64)? as u32;
            if i as usize >= positions.len() {
                let n = positions.len();
                let msg = format!("index {i} is out of range: there are {n} positions");
                return Err(SceneError::new(cpath, msg));
            }
            idx[c] = i;
        }
        if !has_zero_area(idx.map(|i| positions[i as usize])) {
            indices.push(idx);
        } else if emits {
            // A zero-area light has an infinite area-sampling pdf: refuse rather than guess.
            return Err(SceneError::new(
                tpath,
                format!(
                    "triangle {idx:?} has zero area, which is not allowed in an emitting shape"
                ),
            ));
        } else {
            dropped.push(t);
        }
    }
    if !dropped.is_empty() {
        let list = dropped_list(&dropped, |t| format!("[{t}]"));
        warnings.push(format!("{ipath}: {list}"));
    }
    if indices.is_empty() {
        warnings.push(format!("{}: the mesh has no triangles", obj.path));
    }
    Ok(GeometryDesc::Triangles { positions, indices })
}

#[cfg(test)]
mod tests {
    use crate::scene::desc::GeometryDesc;
    use crate::scene::parse::parse_scene_value;
    use crate::scene::tests::{expect_err, with};
    use serde_json::{Value, json};

    #[test]
    fn concave_polygon_parses() {
        // A 5-pointed star, counter-clockwise seen from +z, off the axes.
        let star: Vec<Value> = (0..10)
            .map(|i| {
                let (r, a) = (
                    if i % 2 == 0 { 2.0 } else { 0.8 },
                    i as f64 * 0.2 * std::f64::consts::PI,
                );
                json!([3.0 + r * a.cos(), -1.0 + r * a.sin(), 7.5])
            })
            .collect();
        let s = with(
            1,
            json!({"type": "polygon", "vertices": star, "emission": [1, 1, 1]}),
        );
        let d = parse_scene_value(&s).unwrap();
        let GeometryDesc::Polygon { vertices } = &d.shapes[1].geometry else {
            panic!()
        };
        assert_eq!(vertices.len(), 10);
    }

    #[test]
    fn invalid_polygons() {
        let p = |v: Value| {
            with(
                1,
                json!({"type": "polygon", "vertices": v, "emission": [1, 1, 1]}),
            )
        };
        let bent = json!([[0, 0, 0], [1, 0, 0], [1, 1, 0.1], [0, 1, 0]]);
        expect_err(&p(bent), "shapes[1].vertices", "not planar");
        let bow_tie = json!([[0, 0, 0], [1, 1, 0], [1, 0, 0], [0, 1, 0]]);
        expect_err(
            &p(bow_tie),
            "shapes[1].vertices",
            "edge 0 and edge 2 intersect",
        );
        let line = json!([[0, 0, 0], [1, 1, 1], [2, 2, 2]]);
        expect_err(&p(line), "shapes[1].vertices", "zero area");
        let repeated = json!([[0, 0, 0], [1, 0, 0], [1, 0, 0], [0, 1, 0]]);
        expect_err(
            &p(repeated),
            "shapes[1].vertices[2]",
            "coincides with an earlier vertex",
        );
        expect_err(
            &p(json!([[0, 0, 0], [1, 0, 0]])),
            "shapes[1].vertices",
            "at least 3",
        );
        expect_err(
            &p(json!([[0, 0, 0], [1, 0], [0, 1, 0]])),
            "shapes[1].vertices[1]",
            "found 2",
        );
    }

    #[test]
    fn triangle_index_rules() {
        let t = |idx: Value, emission: [f64; 3]| {
            let pos = json!([[0, 0, 0], [1, 0, 0], [0, 1, 0], [2, 0, 0]]);
            with(
                2,
                json!({"type": "triangles", "positions": pos, "indices": idx, "emission": emission}),
            )
        };
        let lit = [1.0, 1.0, 1.0];
        expect_err(
            &t(json!([[0, 1, 2], [0, 1, 4]]), lit),
            "shapes[2].indices[1][2]",
            "index 4 is out of range: there are 4",
        );
        expect_err(
            &t(json!([[0, -1, 2]]), lit),
            "shapes[2].indices[0][1]",
            "out of range",
        );
        expect_err(
            &t(json!([[0, 1, 2, 3]]), lit),
            "shapes[2].indices[0]",
            "expected 3 vertex indices, found 4",
        );
        expect_err(
            &t(json!([[0, 1.5, 2]]), lit),
            "shapes[2].indices[0][1]",
            "expected an integer",
        );
        // Collinear (0, 1, 3) and repeated (2, 2, 0): fatal for a light ...
        let degenerate = json!([[0, 1, 2], [0, 1, 3], [2, 2, 0]]);
        expect_err(
            &t(degenerate.clone(), lit),
            "shapes[2].indices[1]",
            "zero area",
        );
        // ... dropped with a warning otherwise.
        let d = parse_scene_value(&t(degenerate, [0.0; 3])).unwrap();
        let GeometryDesc::Triangles { indices, .. } = &d.shapes[2].geometry else {
            panic!()
        };
        assert_eq!(indices, &vec![[0, 1, 2]]);
        assert_eq!(
            d.warnings,
            ["shapes[2].indices: dropped 2 zero-area triangle(s): [1], [2]"]
        );
    }
}
