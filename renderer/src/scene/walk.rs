//! Reading a `serde_json::Value` by hand, so that every error names its JSON path: typed
//! accessors on an object that knows where it is, and a strict parser that rejects duplicate keys.

use super::error::SceneError;
use glam::DVec3;
use serde::de::{self, DeserializeSeed, Deserializer, MapAccess, SeqAccess, Visitor};
use serde_json::{Map, Number, Value};
use std::cell::RefCell;
use std::fmt;

/// Parses JSON text, rejecting duplicate keys (which `serde_json::Value` would silently collapse,
/// e.g. two materials of the same name). Errors carry line and column and, because a number like
/// `1e999` (the only way to write a non-finite number) or a truncated file is otherwise hard to
/// find, the JSON path of the value being read.
pub(crate) fn parse_json(text: &str) -> Result<Value, SceneError> {
    let at = RefCell::new(Vec::new());
    let mut de = serde_json::Deserializer::from_str(text);
    let value = StrictSeed(&at)
        .deserialize(&mut de)
        .and_then(|Strict(v)| de.end().map(|()| v));
    value.map_err(|e| {
        let what = match e.classify() {
            serde_json::error::Category::Data => "invalid JSON",
            _ => "JSON syntax error",
        };
        // serde_json's message already ends in "at line L column C"; say so even when it doesn't.
        let msg = e.to_string();
        let msg = if msg.contains(" line ") {
            msg
        } else {
            format!("{msg} at line {} column {}", e.line(), e.column())
        };
        // On an error the stack is left as it was where reading stopped.
        let path = at.borrow().iter().fold(String::new(), |p, seg| match seg {
            Seg::Key(k) => join(&p, k),
            Seg::Index(i) => format!("{p}[{i}]"),
        });
        SceneError::new(path, format!("{what}: {msg}"))
    })
}

/// One step of a JSON path.
enum Seg {
    Key(String),
    Index(usize),
}

/// A `Value` built by [`StrictSeed`].
struct Strict(Value);

/// Deserializes a [`Strict`] value, keeping in `.0` the path of the value being read.
#[derive(Clone, Copy)]
struct StrictSeed<'a>(&'a RefCell<Vec<Seg>>);

impl<'de> DeserializeSeed<'de> for StrictSeed<'_> {
    type Value = Strict;

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<Strict, D::Error> {
        d.deserialize_any(self)
    }
}

impl StrictSeed<'_> {
    /// Reads one nested value at `seg`; the segment stays on the stack if that fails.
    fn nested<T, E>(self, seg: Seg, read: impl FnOnce(Self) -> Result<T, E>) -> Result<T, E> {
        self.0.borrow_mut().push(seg);
        let value = read(self)?;
        self.0.borrow_mut().pop();
        Ok(value)
    }
}

impl<'de> Visitor<'de> for StrictSeed<'_> {
    type Value = Strict;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("any JSON value")
    }
    fn visit_unit<E>(self) -> Result<Strict, E> {
        Ok(Strict(Value::Null))
    }
    fn visit_bool<E>(self, b: bool) -> Result<Strict, E> {
        Ok(Strict(Value::Bool(b)))
    }
    fn visit_i64<E>(self, i: i64) -> Result<Strict, E> {
        Ok(Strict(Value::from(i)))
    }
    fn visit_u64<E>(self, u: u64) -> Result<Strict, E> {
        Ok(Strict(Value::from(u)))
    }
    fn visit_f64<E: de::Error>(self, x: f64) -> Result<Strict, E> {
        Number::from_f64(x)
            .map(|n| Strict(Value::Number(n)))
            .ok_or_else(|| E::custom("number is not finite"))
    }
    fn visit_str<E>(self, s: &str) -> Result<Strict, E> {
        Ok(Strict(Value::String(s.to_owned())))
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Strict, A::Error> {
        let mut items = Vec::new();
        while let Some(Strict(v)) =
            self.nested(Seg::Index(items.len()), |s| seq.next_element_seed(s))?
        {
            items.push(v);
        }
        Ok(Strict(Value::Array(items)))
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Strict, A::Error> {
        let mut obj = Map::new();
        while let Some(key) = map.next_key::<String>()? {
            if obj.contains_key(&key) {
                self.0.borrow_mut().push(Seg::Key(key.clone()));
                return Err(de::Error::custom(format!("duplicate key `{key}`")));
            }
            let Strict(v) = self.nested(Seg::Key(key.clone()), |s| map.next_value_seed(s))?;
            obj.insert(key, v);
        }
        Ok(Strict(Value::Object(obj)))
    }
}

/// `parent.key`, or just `key` at the root. A key that is empty or holds anything but letters,
/// digits, `_` and `-` is written as a JSON string (`materials."red.metal"`, `""`), so that every
/// path is unambiguous and non-empty.
pub(crate) fn join(parent: &str, key: &str) -> String {
    let plain = !key.is_empty()
        && key
            .chars()
            .all(|c| c.is_alphanumeric() || c == '_' || c == '-');
    let key = if plain {
        key.to_owned()
    } else {
        Value::String(key.to_owned()).to_string()
    };
    if parent.is_empty() {
        key
    } else {
        format!("{parent}.{key}")
    }
}

/// A JSON type name for messages.
fn kind(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
    }
}

fn wrong_type(v: &Value, path: &str, expected: &str) -> SceneError {
    SceneError::new(path, format!("expected {expected}, found {}", kind(v)))
}

/// A number that is finite also in single precision, which the renderer computes in: a larger
/// one would become infinite there.
pub(crate) fn number(v: &Value, path: &str) -> Result<f64, SceneError> {
    let x = v.as_f64().ok_or_else(|| wrong_type(v, path, "a number"))?;
    if !x.is_finite() {
        return Err(SceneError::new(path, format!("number {x} is not finite")));
    }
    if x.abs() > f32::MAX as f64 {
        return Err(SceneError::new(
            path,
            format!(
                "number {x:e} is out of range: numbers must lie within ±3.4e38 (single precision)"
            ),
        ));
    }
    Ok(x)
}

/// An integer in `[lo, hi]`; integral floats like `256.0` are accepted (scripts write those).
pub(crate) fn integer(v: &Value, path: &str, lo: i64, hi: i64) -> Result<i64, SceneError> {
    let x = number(v, path)?;
    if x.fract() != 0.0 {
        return Err(SceneError::new(
            path,
            format!("expected an integer, found {x}"),
        ));
    }
    if x < lo as f64 || x > hi as f64 {
        return Err(SceneError::new(
            path,
            format!("{x} is out of range [{lo}, {hi}]"),
        ));
    }
    Ok(x as i64)
}

/// An array, for element-wise reading with paths `path[i]`.
pub(crate) fn array<'a>(v: &'a Value, path: &str) -> Result<&'a [Value], SceneError> {
    v.as_array()
        .map(Vec::as_slice)
        .ok_or_else(|| wrong_type(v, path, "an array"))
}

/// `[x, y, z]` of finite numbers.
pub(crate) fn vec3(v: &Value, path: &str) -> Result<DVec3, SceneError> {
    let items = array(v, path).map_err(|_| wrong_type(v, path, "an array of 3 numbers"))?;
    if items.len() != 3 {
        let n = items.len();
        return Err(SceneError::new(
            path,
            format!("expected 3 numbers, found {n}"),
        ));
    }
    let c = |i: usize| number(&items[i], &format!("{path}[{i}]"));
    Ok(DVec3::new(c(0)?, c(1)?, c(2)?))
}

/// Checks every component of `v` against `ok`, naming the first bad one as `path[i]`.
pub(crate) fn check_components(
    v: DVec3,
    path: &str,
    ok: impl Fn(f64) -> bool,
    rule: &str,
) -> Result<DVec3, SceneError> {
    match v.to_array().iter().position(|&x| !ok(x)) {
        Some(i) => Err(SceneError::new(
            format!("{path}[{i}]"),
            format!("{} {rule}", v[i]),
        )),
        None => Ok(v),
    }
}

/// A JSON object that knows its path.
pub(crate) struct Obj<'a> {
    map: &'a Map<String, Value>,
    /// JSON path of the object itself.
    pub path: String,
}

impl<'a> Obj<'a> {
    /// `v` as an object, or a type error at `path`.
    pub fn new(v: &'a Value, path: impl Into<String>) -> Result<Obj<'a>, SceneError> {
        let path = path.into();
        match v {
            Value::Object(map) => Ok(Obj { map, path }),
            _ => Err(wrong_type(v, &path, "an object")),
        }
    }

    /// The underlying map.
    pub fn map(&self) -> &'a Map<String, Value> {
        self.map
    }

    /// Path of a member.
    pub fn at(&self, key: &str) -> String {
        join(&self.path, key)
    }

    /// Rejects any key not in `allowed`; `comment` and `name` are also allowed when `annotated`
    /// (root, materials, shapes).
    pub fn only_keys(&self, allowed: &[&str], annotated: bool) -> Result<(), SceneError> {
        let extra: &[&str] = if annotated { &["comment", "name"] } else { &[] };
        for (key, value) in self.map {
            if key == "name" && annotated && !value.is_string() {
                return Err(wrong_type(value, &self.at(key), "a string"));
            }
            if !allowed.contains(&key.as_str()) && !extra.contains(&key.as_str()) {
                let mut all: Vec<&str> = allowed.to_vec();
                all.extend(extra);
                let list = all.join(", ");
                return Err(SceneError::new(
                    self.at(key),
                    format!("unknown key `{key}` (allowed here: {list})"),
                ));
            }
        }
        Ok(())
    }

    /// An optional member.
    pub fn get(&self, key: &str) -> Option<&'a Value> {
        self.map.get(key)
    }

    /// A required member.
    pub fn req(&self, key: &str) -> Result<&'a Value, SceneError> {
        self.map
            .get(key)
            .ok_or_else(|| SceneError::new(self.at(key), format!("missing required key `{key}`")))
    }

    /// A required finite number.
    pub fn number(&self, key: &str) -> Result<f64, SceneError> {
        number(self.req(key)?, &self.at(key))
    }

    /// An optional finite number.
    pub fn opt_number(&self, key: &str) -> Result<Option<f64>, SceneError> {
        self.get(key).map(|v| number(v, &self.at(key))).transpose()
    }

    /// A required vector.
    pub fn vec3(&self, key: &str) -> Result<DVec3, SceneError> {
        vec3(self.req(key)?, &self.at(key))
    }

    /// An optional vector.
    pub fn opt_vec3(&self, key: &str) -> Result<Option<DVec3>, SceneError> {
        self.get(key).map(|v| vec3(v, &self.at(key))).transpose()
    }

    /// A required string.
    pub fn string(&self, key: &str) -> Result<&'a str, SceneError> {
        let v = self.req(key)?;
        v.as_str()
            .ok_or_else(|| wrong_type(v, &self.at(key), "a string"))
    }

    /// An optional boolean.
    pub fn opt_bool(&self, key: &str) -> Result<Option<bool>, SceneError> {
        self.get(key)
            .map(|v| {
                v.as_bool()
                    .ok_or_else(|| wrong_type(v, &self.at(key), "true or false"))
            })
            .transpose()
    }
}
