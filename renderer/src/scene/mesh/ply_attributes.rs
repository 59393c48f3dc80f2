//! Mitsuba's named PLY attributes (`vertex_color`, `face_{prefix}`, …): which properties of an
//! element form which attribute, by Mitsuba 3.9.1's `find_other_fields` and its quirks, and how
//! their values convert. Part of [`super`] (the reader calls [`attribute_sources`] per element
//! and [`attribute_vec`] per vertex or face), in a file of its own for its length.

use super::*;

/// The postfix sequences of Mitsuba's attribute runs, by position in the run (row) and
/// sequence (column: `x y z w`, `r g b a`, `0 1 2 3`, `1 2 3 4`).
const POSTFIXES: [&[u8; 4]; 4] = [b"xr01", b"yg12", b"zb23", b"wa34"];

/// A named attribute an element holds: Mitsuba's name and the properties of its components
/// (1 or 3; 4 for `r g b a`), in order.
#[derive(Debug)]
pub(super) struct AttributeSource {
    pub(super) name: String,
    pub(super) properties: Vec<usize>,
}

/// An element's attributes, and where the first of them is in [`MeshData::attributes`].
pub(super) struct Attributes {
    pub(super) sources: Vec<AttributeSource>,
    pub(super) first: usize,
}

/// One field of an element as Mitsuba's PLY loader names it, with the property a scalar comes
/// from (`None` for the parts of a list).
struct Field {
    name: String,
    property: Option<usize>,
}

/// Mitsuba's fields of `element`: a scalar is one field; a list is four (`{name}.count`, `i0`,
/// `i1`, `i2`, as its header parser lays out the three indices of a triangle).
fn mitsuba_fields(element: &Element) -> Vec<Field> {
    let mut fields = Vec::with_capacity(element.properties.len());
    for (k, p) in element.properties.iter().enumerate() {
        match p.kind {
            Kind::Scalar(_) => fields.push(Field {
                name: p.name.clone(),
                property: Some(k),
            }),
            Kind::List { .. } => {
                fields.push(Field {
                    name: format!("{}.count", p.name),
                    property: None,
                });
                for i in ["i0", "i1", "i2"] {
                    fields.push(Field {
                        name: i.to_owned(),
                        property: None,
                    });
                }
            }
        }
    }
    fields
}

/// The property of the first field named `name` (as Mitsuba's `Struct` finds it).
fn field_property(fields: &[Field], name: &str) -> Option<usize> {
    fields
        .iter()
        .find(|f| f.name == name)
        .and_then(|f| f.property)
}

/// Renames the first field named `from` to `to`, as Mitsuba does before it looks for
/// attributes.
fn rename(fields: &mut [Field], from: &str, to: &str) {
    if let Some(f) = fields.iter_mut().find(|f| f.name == from) {
        f.name = to.to_owned();
    }
}

/// The attributes of the `vertex` or `face` element (`kind`), as Mitsuba 3.9.1's PLY loader
/// finds them (`find_other_fields` in its `ply.h`), over the fields it names after its own
/// renaming (`texture_u`/`s` → `u`, `red` → `r`, `alpha` → `a`, …). Its reserved names (and so
/// skipped here): `x y z nx ny nz u v` in a vertex, the index list in a face, `r g b a` in both.
/// Its loop has quirks that decide which attributes survive, kept here on purpose:
/// - a property without `_` or with a postfix longer than one byte ends the current run;
/// - a run of 2 or 4 components is dropped, and its prefix may start a run again later;
/// - a run whose postfix sequence breaks is dropped together with every following property
///   whose name starts with the prefix, and the property after those too; the run count is
///   then left at 1, so the next run starts counting at 2 (its names are looked up by the
///   counted positions, see [`Run::flush`]);
/// - a prefix already kept skips every following property whose name starts with it, and the
///   property after those;
/// - a property whose postfix cannot start a run (`q`, `5`, …) is skipped and leaves the count;
/// - a fifth property in a run (which Mitsuba reads past its table) breaks the sequence.
pub(super) fn attribute_sources(element: &Element, kind: AttributeKind) -> Vec<AttributeSource> {
    let mut fields = mitsuba_fields(element);
    let has = |fields: &[Field], names: &[&str]| {
        names.iter().all(|n| fields.iter().any(|f| f.name == *n))
    };
    let (kind, mut reserved) = match kind {
        AttributeKind::Vertex => {
            if !has(&fields, &["u", "v"]) {
                for [u, v] in [["texture_u", "texture_v"], ["s", "t"]] {
                    if has(&fields, &[u, v]) {
                        rename(&mut fields, u, "u");
                        rename(&mut fields, v, "v");
                        break;
                    }
                }
            }
            ("vertex", vec!["x", "y", "z", "nx", "ny", "nz", "u", "v"])
        }
        AttributeKind::Face => (
            "face",
            vec![
                "vertex_index.count",
                "vertex_indices.count",
                "i0",
                "i1",
                "i2",
            ],
        ),
    };
    let mut sources = Vec::new();
    if !has(&fields, &["r", "g", "b"]) && has(&fields, &["red", "green", "blue"]) {
        for (from, to) in [("red", "r"), ("green", "g"), ("blue", "b"), ("alpha", "a")] {
            rename(&mut fields, from, to);
        }
    }
    if has(&fields, &["r", "g", "b"]) {
        let names: &[&str] = if has(&fields, &["a"]) {
            &["r", "g", "b", "a"]
        } else {
            &["r", "g", "b"]
        };
        // Names without `.` are never parts of a list: every one is a scalar.
        if let Some(properties) = names.iter().map(|n| field_property(&fields, n)).collect() {
            sources.push(AttributeSource {
                name: format!("{kind}_color"),
                properties,
            });
        }
    }
    reserved.extend(["r", "g", "b", "a"]);

    let mut run = Run::default();
    let mut kept: Vec<String> = Vec::new();
    let n = fields.len();
    let mut i = 0;
    while i < n {
        let name = fields[i].name.as_str();
        i += 1;
        if reserved.contains(&name) {
            continue;
        }
        let Some((prefix, postfix)) = name.rsplit_once('_').filter(|(_, p)| p.len() == 1) else {
            if run.reading {
                run.flush(&fields, kind, &mut kept, &mut sources);
            }
            continue;
        };
        if run.reading && prefix != run.prefix {
            run.flush(&fields, kind, &mut kept, &mut sources);
        }
        // Passes the current field, every following one whose name starts with `prefix`, and
        // one more (Mitsuba's loop steps past the field that ended the skipping).
        let skip_run = |i: &mut usize| {
            *i -= 1;
            while *i < n && fields[*i].name.starts_with(prefix) {
                *i += 1;
            }
            *i += 1;
        };
        let c = postfix.as_bytes()[0];
        if !run.reading {
            if kept.iter().any(|p| p == prefix) {
                skip_run(&mut i);
                continue;
            }
            let Some(sequence) = POSTFIXES[0].iter().position(|&p| p == c) else {
                continue;
            };
            // `count` may be 1 here, left over from a broken run (Mitsuba's quirk).
            (run.prefix, run.sequence, run.reading) = (prefix.to_owned(), sequence, true);
        } else if POSTFIXES.get(run.count).map(|p| p[run.sequence]) != Some(c) {
            run = Run::default();
            skip_run(&mut i);
            // Mitsuba counts this field although the run is gone: the count stays at 1.
        }
        run.count += 1;
    }
    if run.reading {
        run.flush(&fields, kind, &mut kept, &mut sources);
    }
    sources
}

/// The run of properties `attribute_sources` is reading.
#[derive(Default)]
struct Run {
    prefix: String,
    /// The column of [`POSTFIXES`].
    sequence: usize,
    /// Properties counted (Mitsuba's `current_postfix_level_index`).
    count: usize,
    reading: bool,
}

impl Run {
    /// Ends the run and starts afresh. A run of 1 or 3 components marks its prefix as seen and
    /// becomes attribute `{kind}_{prefix}` (`…_color` for `r g b a`), unless the element lacks
    /// one of the names at the counted positions or the attribute name is taken (the `color`
    /// of `r g b` and `color_0 …`): Mitsuba refuses such a file, lumis drops the attribute.
    fn flush(
        &mut self,
        fields: &[Field],
        kind: &str,
        kept: &mut Vec<String>,
        sources: &mut Vec<AttributeSource>,
    ) {
        let run = std::mem::take(self);
        if run.count != 1 && run.count != 3 {
            return;
        }
        let properties: Option<Vec<usize>> = (0..run.count)
            .map(|l| {
                let c = char::from(POSTFIXES[l][run.sequence]);
                field_property(fields, &format!("{}_{c}", run.prefix))
            })
            .collect();
        let color = if run.sequence == 1 { "_color" } else { "" };
        let name = format!("{kind}_{}{color}", run.prefix);
        if let Some(properties) = properties
            && !sources.iter().any(|s| s.name == name)
        {
            sources.push(AttributeSource { name, properties });
        }
        kept.push(run.prefix);
    }
}

/// The value of attribute component `property` of `element`, read as `raw`: a float or a
/// `uchar` as stored, another integer divided by its type's maximum and sRGB-decoded. Mitsuba
/// 3.9.1's PLY header parser marks integer properties `Normalized | Gamma` by the test
/// `Int8 <= type <= UInt64` on struct-jit's type numbers, in which `UInt8` comes before `Int8`:
/// `uchar` escapes it (checked with Mitsuba: a `uchar` 89 reads 89).
fn attribute_value(element: &Element, property: usize, raw: f64) -> Result<f32, String> {
    let p = &element.properties[property];
    let value = match p.kind {
        Kind::Scalar(Scalar::U8) => raw,
        Kind::Scalar(t) => match t.int_range() {
            Some((_, max)) => srgb_to_linear(raw / max as f64),
            None => raw,
        },
        Kind::List { .. } => raw,
    };
    finite(&p.name, value)
}

/// The sRGB transfer function's inverse (an encoded value to linear), as Mitsuba's converter
/// applies it (the linear segment also below 0, for normalized signed integers).
fn srgb_to_linear(s: f64) -> f64 {
    if s <= 0.04045 {
        s / 12.92
    } else {
        ((s + 0.055) / 1.055).powf(2.4)
    }
}

/// One value of `source` for the current element, from its properties' `values`.
pub(super) fn attribute_vec(
    element: &Element,
    source: &AttributeSource,
    values: &[f64],
) -> Result<Vec3, String> {
    let mut c = [0.0f32; 4];
    for (slot, &k) in c.iter_mut().zip(&source.properties) {
        *slot = attribute_value(element, k, values[k])?;
    }
    Ok(if source.properties.len() == 1 {
        Vec3::splat(c[0])
    } else {
        Vec3::new(c[0], c[1], c[2])
    })
}
