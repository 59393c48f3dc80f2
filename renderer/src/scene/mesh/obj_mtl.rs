//! The `.mtl` reader of [`super`] (an OBJ file opened on its own): each material's statements
//! that lumis maps, checked, and the keywords of the rest, for the warning.
//!
//! lumis reads `.mtl` text itself rather than through `tobj::load_mtl_buf`, which panics on a
//! colour of fewer than three numbers (`Kd 0.5`, which the MTL spec allows), reports no line,
//! accepts NaN, and keeps unknown statements in a map that loses their order.
//!
//! Keywords are matched without regard to case (exporters write `map_kd` as often as
//! `map_Kd`). Statements before the first `newmtl` belong to no material and are skipped;
//! `#` starts a comment at the start of a word. The values lumis uses are checked: `Kd`, `Ks`
//! and `Ke` (one number, meaning three equal ones, or three), `Ns`, `Ni`, `d` (with an optional
//! `-halo`, not rendered), `Tr` (one number each), `illum` (a whole number), `map_Kd` (options,
//! then a file name that may hold spaces). A value that does not parse, or is NaN or infinite,
//! is an error naming the `.mtl` file, the line and the material. `Ka` and `map_Ka` (ambient
//! light, which a path tracer has no use for) are skipped silently; every other statement is
//! kept by keyword for the warning.

use crate::scene::mesh::MeshError;
use std::path::Path;

/// One `newmtl` block: what lumis maps, as written (clamping is the mapping's).
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct MtlMaterial {
    pub(super) name: String,
    pub(super) kd: Option<[f64; 3]>,
    pub(super) ks: Option<[f64; 3]>,
    pub(super) ke: Option<[f64; 3]>,
    pub(super) ns: Option<f64>,
    pub(super) ni: Option<f64>,
    pub(super) d: Option<f64>,
    pub(super) tr: Option<f64>,
    pub(super) illum: Option<u32>,
    /// `map_Kd`'s file name as written (relative to the `.mtl` file's folder).
    pub(super) map_kd: Option<String>,
    /// What lumis does not render, each once, in file order: keywords (`map_Bump`), texture
    /// options (`map_Kd -s`), colour forms (`Kd spectral`), `illum 4`.
    pub(super) unrendered: Vec<String>,
}

/// At most this many things are named per material; then `…` (a longer list helps nobody, and
/// a file of many keywords must not take quadratic time).
const MAX_UNRENDERED: usize = 20;

impl MtlMaterial {
    /// Names `what` in the warning, once.
    pub(super) fn unrendered(&mut self, what: impl Into<String>) {
        let what = what.into();
        if self.unrendered.len() > MAX_UNRENDERED || self.unrendered.contains(&what) {
            return;
        }
        if self.unrendered.len() == MAX_UNRENDERED {
            self.unrendered.push("…".into());
        } else {
            self.unrendered.push(what);
        }
    }
}

/// The options of a texture statement and how many values each takes (at most; `-o`, `-s`,
/// `-t` take one to three numbers, `-mm` two).
const TEXTURE_OPTIONS: [(&str, usize); 13] = [
    ("-blendu", 1),
    ("-blendv", 1),
    ("-boost", 1),
    ("-bm", 1),
    ("-cc", 1),
    ("-clamp", 1),
    ("-imfchan", 1),
    ("-mm", 2),
    ("-o", 3),
    ("-s", 3),
    ("-t", 3),
    ("-texres", 1),
    ("-type", 1),
];

/// Reads the `.mtl` text of `file` (named in errors).
pub(super) fn parse(file: &Path, text: &str) -> Result<Vec<MtlMaterial>, MeshError> {
    let mut materials: Vec<MtlMaterial> = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let fail = |name: &str, m: String| {
            MeshError::at(
                file,
                &format!("line {}", i + 1),
                format!("material '{name}': {m}"),
            )
        };
        let line = line.trim();
        let Some(keyword) = line.split_whitespace().next() else {
            continue;
        };
        if keyword.starts_with('#') {
            continue;
        }
        // Everything after the keyword, as written (names and file names may hold spaces).
        let rest = line[keyword.len()..].trim();
        let key = keyword.to_ascii_lowercase();
        if key == "newmtl" {
            if rest.is_empty() {
                return Err(MeshError::at(
                    file,
                    &format!("line {}", i + 1),
                    "newmtl without a name",
                ));
            }
            materials.push(MtlMaterial {
                name: rest.to_owned(),
                ..Default::default()
            });
            continue;
        }
        let Some(m) = materials.last_mut() else {
            continue;
        };
        let values: Vec<&str> = rest
            .split_whitespace()
            .take_while(|w| !w.starts_with('#'))
            .collect();
        statement(m, keyword, &key, rest, &values).map_err(|e| fail(&m.name, e))?;
    }
    Ok(materials)
}

/// Reads one statement into `m`: `keyword` as written, `key` in lower case, `rest` the text
/// after it, `values` its words up to a comment.
fn statement(
    m: &mut MtlMaterial,
    keyword: &str,
    key: &str,
    rest: &str,
    values: &[&str],
) -> Result<(), String> {
    match key {
        "kd" => m.kd = colour(m, keyword, values)?.or(m.kd),
        "ks" => m.ks = colour(m, keyword, values)?.or(m.ks),
        "ke" => m.ke = colour(m, keyword, values)?.or(m.ke),
        "ns" => m.ns = Some(one_number(keyword, values)?),
        "ni" => m.ni = Some(one_number(keyword, values)?),
        "d" => {
            let values = match values {
                ["-halo", rest @ ..] => {
                    m.unrendered("d -halo");
                    rest
                }
                _ => values,
            };
            m.d = Some(one_number(keyword, values)?);
        }
        "tr" => m.tr = Some(one_number(keyword, values)?),
        "illum" => {
            let [v] = values else {
                return Err(format!("'{keyword}' needs one whole number"));
            };
            let illum: u32 = v
                .parse()
                .map_err(|_| format!("{keyword}: '{v}' is not a whole number"))?;
            // 0 to 2 are colour and highlight, which the mapping reads; 3 and up add
            // ray-traced reflection, refraction or glass, which it does not render as such.
            if illum > 2 {
                m.unrendered(format!("illum {illum}"));
            }
            m.illum = Some(illum);
        }
        "map_kd" => m.map_kd = Some(texture_file(m, keyword, rest)?),
        "ka" | "map_ka" => {}
        // The transmission filter: white (what many exporters write for every material) filters
        // nothing, so naming it would be a warning that changes nothing.
        "tf" => {
            if colour(m, keyword, values)?.is_some_and(|c| c != [1.0; 3]) {
                m.unrendered(keyword);
            }
        }
        _ => m.unrendered(keyword),
    }
    Ok(())
}

/// A colour statement's value: `r` (grey) or `r g b`; `None` for the forms lumis does not read
/// (`spectral`, `xyz`), which are named for the warning.
fn colour(m: &mut MtlMaterial, keyword: &str, values: &[&str]) -> Result<Option<[f64; 3]>, String> {
    if let Some(form) = values
        .first()
        .filter(|w| w.eq_ignore_ascii_case("spectral") || w.eq_ignore_ascii_case("xyz"))
    {
        m.unrendered(format!("{keyword} {form}"));
        return Ok(None);
    }
    let v = values
        .iter()
        .map(|w| number(keyword, w))
        .collect::<Result<Vec<_>, _>>()?;
    match *v.as_slice() {
        [g] => Ok(Some([g; 3])),
        [r, g, b] => Ok(Some([r, g, b])),
        _ => Err(format!(
            "'{keyword}' needs 1 or 3 numbers, found {}",
            v.len()
        )),
    }
}

/// The one number of a statement.
fn one_number(keyword: &str, values: &[&str]) -> Result<f64, String> {
    match values {
        [v] => number(keyword, v),
        _ => Err(format!(
            "'{keyword}' needs one number, found {}",
            values.len()
        )),
    }
}

/// One finite number of statement `keyword`, or why not.
fn number(keyword: &str, word: &str) -> Result<f64, String> {
    let v: f64 = word
        .parse()
        .map_err(|_| format!("{keyword}: '{word}' is not a number"))?;
    if v.is_nan() {
        Err(format!("{keyword} is NaN"))
    } else if v.is_infinite() {
        Err(format!("{keyword} is infinite"))
    } else {
        Ok(v)
    }
}

/// The file name of a texture statement after its options (each option is named for the
/// warning: lumis does not apply them).
fn texture_file(m: &mut MtlMaterial, keyword: &str, rest: &str) -> Result<String, String> {
    let mut rest = rest;
    loop {
        let word = rest.split_whitespace().next().unwrap_or("");
        let Some(&(option, most)) = TEXTURE_OPTIONS
            .iter()
            .find(|(o, _)| word.eq_ignore_ascii_case(o))
        else {
            break;
        };
        m.unrendered(format!("{keyword} {option}"));
        rest = rest[word.len()..].trim_start();
        // The first value is taken whatever it is; the options of several numbers take up to
        // `most`, as long as they are numbers.
        for k in 0..most {
            let Some(value) = rest.split_whitespace().next() else {
                break;
            };
            if k > 0 && value.parse::<f64>().is_err() {
                break;
            }
            rest = rest[value.len()..].trim_start();
        }
    }
    if rest.is_empty() {
        return Err(format!("'{keyword}' without a file name"));
    }
    Ok(rest.to_owned())
}
