//! `<transform>`: `translate`, `rotate` (axis and angle in degrees), `scale`, `matrix` and
//! `lookat`, each applied after the ones before it (`T = op · T`, Mitsuba 3.9.1's
//! `parse_transform_node`), in double precision.

use super::values::{parse_number, tokens};
use super::xml::{Element, Pos};
use crate::scene::error::SceneError;
use glam::{DMat4, DVec3, DVec4};

/// The composition of `el`'s children.
pub fn parse_transform(el: &Element) -> Result<DMat4, SceneError> {
    let mut m = DMat4::IDENTITY;
    for op in &el.children {
        if let Some(c) = op.children.first() {
            return Err(c.pos.error(format!("<{}> has no child elements", op.tag)));
        }
        let step = match op.tag.as_str() {
            "translate" => DMat4::from_translation(xyz(op, 0.0)?),
            "scale" => DMat4::from_scale(xyz(op, 1.0)?),
            "rotate" => rotate(op)?,
            "matrix" => matrix(op)?,
            "lookat" => look_at(op)?,
            other => {
                return Err(op.pos.error(format!(
                    "unexpected <{other}> inside <transform> (expected translate, rotate, \
                     scale, matrix or lookat)"
                )));
            }
        };
        m = step * m;
        if !m.is_finite() {
            return Err(op.pos.error("the transform is not finite"));
        }
    }
    Ok(m)
}

/// `value="a"` (all three), `value="x y z"`, or the attributes `x`, `y`, `z` (`missing` where
/// not given); `angle` is allowed for `rotate`.
fn xyz(op: &Element, missing: f64) -> Result<DVec3, SceneError> {
    let allowed: &[&str] = if op.tag == "rotate" {
        &["value", "x", "y", "z", "angle"]
    } else {
        &["value", "x", "y", "z"]
    };
    op.only_attrs(allowed)?;
    if let Some(a) = op.attr("value") {
        if let Some(b) = ["x", "y", "z"].iter().find_map(|k| op.attr(k)) {
            return Err(b
                .pos
                .error("give either `value` or `x`, `y`, `z`, not both"));
        }
        let t = tokens(&a.value);
        return match t.len() {
            1 => Ok(DVec3::splat(parse_number(t[0], &a.pos)?)),
            3 => Ok(DVec3::new(
                parse_number(t[0], &a.pos)?,
                parse_number(t[1], &a.pos)?,
                parse_number(t[2], &a.pos)?,
            )),
            n => Err(a.pos.error(format!("expected 1 or 3 numbers, found {n}"))),
        };
    }
    let mut v = DVec3::splat(missing);
    for (i, key) in ["x", "y", "z"].iter().enumerate() {
        if let Some(a) = op.attr(key) {
            v[i] = parse_number(&a.value, &a.pos)?;
        }
    }
    Ok(v)
}

/// A rotation by `angle` degrees about `axis` (right-handed). As in Mitsuba (drjit's `rotate`),
/// the axis is used as given, not normalised: give a unit axis.
pub fn rotation(axis: DVec3, angle_deg: f64) -> DMat4 {
    let (s, c) = angle_deg.to_radians().sin_cos();
    let a = axis;
    let k = 1.0 - c;
    // Rows of R = c·I + (1 − c)·a·aᵀ + s·[a]×.
    let rows = [
        [
            a.x * a.x * k + c,
            a.x * a.y * k - a.z * s,
            a.x * a.z * k + a.y * s,
        ],
        [
            a.y * a.x * k + a.z * s,
            a.y * a.y * k + c,
            a.y * a.z * k - a.x * s,
        ],
        [
            a.z * a.x * k - a.y * s,
            a.z * a.y * k + a.x * s,
            a.z * a.z * k + c,
        ],
    ];
    from_rows3(rows, DVec3::ZERO)
}

fn rotate(op: &Element) -> Result<DMat4, SceneError> {
    let axis = xyz(op, 0.0)?;
    let angle = op.required("angle")?;
    if axis == DVec3::ZERO {
        return Err(op.pos.error("the rotation axis is zero"));
    }
    Ok(rotation(axis, parse_number(&angle.value, &angle.pos)?))
}

/// `matrix value="…"`: 16 numbers (4×4) or 9 (3×3, no translation), row by row; the last row
/// of a 4×4 must be `0 0 0 1` (Mitsuba keeps only affine transforms).
fn matrix(op: &Element) -> Result<DMat4, SceneError> {
    op.only_attrs(&["value"])?;
    let a = op.required("value")?;
    let t = tokens(&a.value);
    let n = match t.len() {
        16 => 4,
        9 => 3,
        len => {
            return Err(a.pos.error(format!(
                "a matrix has 16 numbers (4×4) or 9 (3×3), found {len}"
            )));
        }
    };
    let mut m = [[0.0f64; 4]; 4];
    m[3][3] = 1.0;
    for i in 0..n {
        for j in 0..n {
            m[i][j] = parse_number(t[i * n + j], &a.pos)?;
        }
    }
    if m[3] != [0.0, 0.0, 0.0, 1.0] {
        return Err(a
            .pos
            .error("the last row must be 0 0 0 1: Mitsuba keeps only affine transforms"));
    }
    Ok(DMat4::from_cols_array_2d(&m).transpose())
}

/// `lookat origin target [up]`: camera space's +z towards `target`, +y up, +x to the left
/// (Mitsuba's `look_at`); without `up`, Mitsuba's `coordinate_system` picks one.
fn look_at(op: &Element) -> Result<DMat4, SceneError> {
    op.only_attrs(&["origin", "target", "up"])?;
    let vec = |key: &str| -> Result<DVec3, SceneError> {
        let a = op.required(key)?;
        let t = tokens(&a.value);
        if t.len() != 3 {
            return Err(a
                .pos
                .error(format!("expected 3 numbers, found {}", t.len())));
        }
        Ok(DVec3::new(
            parse_number(t[0], &a.pos)?,
            parse_number(t[1], &a.pos)?,
            parse_number(t[2], &a.pos)?,
        ))
    };
    let (origin, target) = (vec("origin")?, vec("target")?);
    let mut up = match op.attr("up") {
        Some(_) => vec("up")?,
        None => DVec3::ZERO,
    };
    let dir = (target - origin).normalize();
    if up == DVec3::ZERO {
        up = coordinate_system(dir).0;
    }
    let left = up.cross(dir).normalize();
    let new_up = dir.cross(left);
    let m = DMat4::from_cols(
        left.extend(0.0),
        new_up.extend(0.0),
        dir.extend(0.0),
        DVec4::new(origin.x, origin.y, origin.z, 1.0),
    );
    if !m.is_finite() {
        return Err(invalid_look_at(&op.pos));
    }
    Ok(m)
}

fn invalid_look_at(pos: &Pos) -> SceneError {
    pos.error("invalid lookat: `origin` equals `target`, or `up` is parallel to the view direction")
}

/// Two unit vectors completing `n` to an orthonormal basis (Duff et al. 2017, the construction
/// Mitsuba's `coordinate_system` uses).
pub fn coordinate_system(n: DVec3) -> (DVec3, DVec3) {
    let sign = 1f64.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        DVec3::new(n.x * n.x * a * sign + 1.0, b * sign, -n.x * sign),
        DVec3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

/// The affine matrix with 3×3 part `rows` and translation `t`.
pub fn from_rows3(rows: [[f64; 3]; 3], t: DVec3) -> DMat4 {
    DMat4::from_cols(
        DVec4::new(rows[0][0], rows[1][0], rows[2][0], 0.0),
        DVec4::new(rows[0][1], rows[1][1], rows[2][1], 0.0),
        DVec4::new(rows[0][2], rows[1][2], rows[2][2], 0.0),
        t.extend(1.0),
    )
}

/// `m` as the scene format's `to_world`: 4 rows of 4 numbers.
pub fn rows_json(m: &DMat4) -> serde_json::Value {
    serde_json::json!(m.transpose().to_cols_array_2d())
}
