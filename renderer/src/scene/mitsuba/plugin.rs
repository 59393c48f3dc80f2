//! One Mitsuba object (`<bsdf type="diffuse">`, `<shape>`, …) with its typed properties: the
//! property elements (`float`, `integer`, `boolean`, `string`, `rgb`, `spectrum`, `point`,
//! `vector`, `transform`) and child objects (nested or `<ref>`), parsed once with their
//! positions. Every property read is marked; [`Plugin::finish`] refuses any that was not, as
//! Mitsuba refuses unreferenced properties, so a misspelt or unsupported parameter never
//! disappears silently.

use super::transform::parse_transform;
use super::values::{Spectrum, parse_number, parse_spectrum, parse_triple};
use super::xml::{Element, Pos};
use crate::scene::error::SceneError;
use glam::{DMat4, DVec3};
use std::cell::Cell;
use std::collections::HashMap;

/// The tags that create objects, Mitsuba's `ObjectType`s.
pub const OBJECT_TAGS: [&str; 14] = [
    "scene",
    "bsdf",
    "shape",
    "emitter",
    "sensor",
    "film",
    "rfilter",
    "sampler",
    "integrator",
    "texture",
    "medium",
    "phase",
    "volume",
    "spectrum",
];

/// A property's value.
#[derive(Clone, Debug)]
pub enum Value<'a> {
    /// `<float>`.
    Float(f64),
    /// `<integer>`.
    Int(i64),
    /// `<boolean>`.
    Bool(bool),
    /// `<string>`.
    Str(&'a str),
    /// `<rgb>`.
    Rgb(DVec3),
    /// `<spectrum value|filename>` (a `<spectrum type=…>` is an object).
    Spectrum(Spectrum),
    /// `<point>` or `<vector>`.
    Vector(DVec3),
    /// `<transform>`, composed.
    Transform(DMat4),
    /// A nested object or the target of a `<ref>`.
    Object(&'a Element),
}

impl Value<'_> {
    /// The kind of value, for messages.
    fn kind(&self) -> &'static str {
        match self {
            Value::Float(_) => "a float",
            Value::Int(_) => "an integer",
            Value::Bool(_) => "a boolean",
            Value::Str(_) => "a string",
            Value::Rgb(_) => "an rgb",
            Value::Spectrum(_) => "a spectrum",
            Value::Vector(_) => "a point or vector",
            Value::Transform(_) => "a transform",
            Value::Object(_) => "an object",
        }
    }
}

/// One property: its name (`_arg_N` for unnamed objects, as in Mitsuba), value and element.
#[derive(Debug)]
pub struct Prop<'a> {
    /// The `name` attribute, or `_arg_N`.
    pub name: String,
    /// The value.
    pub value: Value<'a>,
    /// The property element (for a `<ref>`, the `<ref>` itself).
    pub el: &'a Element,
    used: Cell<bool>,
}

/// An object and its properties.
#[derive(Debug)]
pub struct Plugin<'a> {
    /// The object's element.
    pub el: &'a Element,
    /// Its `type` (`"scene"` for the root).
    pub ty: &'a str,
    props: Vec<Prop<'a>>,
}

impl<'a> Plugin<'a> {
    /// Reads `el`'s properties; `<ref id>` resolves through `ids`.
    pub fn new(
        el: &'a Element,
        ids: &HashMap<&str, &'a Element>,
    ) -> Result<Plugin<'a>, SceneError> {
        // Out of scope first: such a file gets that reason, not a missing-feature message.
        super::scope::check(el)?;
        let ty = match el.tag.as_str() {
            "scene" => {
                el.only_attrs(&["version", "type", "id", "name"])?;
                "scene"
            }
            _ => {
                el.only_attrs(&["type", "id", "name"])?;
                el.required("type")?.value.as_str()
            }
        };
        let mut props: Vec<Prop<'a>> = Vec::new();
        let mut args = 0;
        for child in &el.children {
            // An alias names an object (`Document::ids`); it is no property.
            if child.tag == "alias" {
                child.only_attrs(&["id", "as"])?;
                continue;
            }
            let (name, value) = property(child, ids, &mut args)?;
            if let Some(prev) = props.iter().find(|p| p.name == name) {
                return Err(child.pos.error(format!(
                    "property `{name}` is given twice (first at {})",
                    prev.el.pos.describe()
                )));
            }
            props.push(Prop {
                name,
                value,
                el: child,
                used: Cell::new(false),
            });
        }
        Ok(Plugin { el, ty, props })
    }

    /// Where the object is.
    pub fn pos(&self) -> &Pos {
        &self.el.pos
    }

    /// `<tag type="ty">`, for messages.
    pub fn what(&self) -> String {
        format!("<{} type=\"{}\">", self.el.tag, self.ty)
    }

    /// An error about the object.
    pub fn error(&self, message: impl Into<String>) -> SceneError {
        self.el.pos.error(message)
    }

    /// The property `name`, marked as read.
    pub fn get(&self, name: &str) -> Option<&Prop<'a>> {
        let p = self.props.iter().find(|p| p.name == name)?;
        p.used.set(true);
        Some(p)
    }

    /// Whether the property `name` is given (without reading it).
    pub fn has(&self, name: &str) -> bool {
        self.props.iter().any(|p| p.name == name)
    }

    /// Marks `names` as read: parameters Mitsuba knows that do not change lumis' image.
    pub fn ignore(&self, names: &[&str]) {
        for n in names {
            self.get(n);
        }
    }

    /// A float (an integer is accepted), or `default`.
    pub fn float(&self, name: &str, default: f64) -> Result<f64, SceneError> {
        match self.get(name) {
            None => Ok(default),
            Some(p) => match p.value {
                Value::Float(x) => Ok(x),
                Value::Int(i) => Ok(i as f64),
                _ => Err(p.wrong_type("a float")),
            },
        }
    }

    /// An integer, or `default`.
    pub fn int(&self, name: &str, default: i64) -> Result<i64, SceneError> {
        match self.get(name) {
            None => Ok(default),
            Some(p) => match p.value {
                Value::Int(i) => Ok(i),
                _ => Err(p.wrong_type("an integer")),
            },
        }
    }

    /// A boolean, or `default`.
    pub fn bool(&self, name: &str, default: bool) -> Result<bool, SceneError> {
        match self.get(name) {
            None => Ok(default),
            Some(p) => match p.value {
                Value::Bool(b) => Ok(b),
                _ => Err(p.wrong_type("a boolean")),
            },
        }
    }

    /// A string, or `None`.
    pub fn string(&self, name: &str) -> Result<Option<(&'a str, &Prop<'a>)>, SceneError> {
        match self.get(name) {
            None => Ok(None),
            Some(p) => match p.value {
                Value::Str(s) => Ok(Some((s, p))),
                _ => Err(p.wrong_type("a string")),
            },
        }
    }

    /// A point or vector, or `default`.
    pub fn vector(&self, name: &str, default: DVec3) -> Result<DVec3, SceneError> {
        match self.get(name) {
            None => Ok(default),
            Some(p) => match p.value {
                Value::Vector(v) => Ok(v),
                _ => Err(p.wrong_type("a point")),
            },
        }
    }

    /// A transform, or `None`.
    pub fn transform(&self, name: &str) -> Result<Option<(DMat4, &Prop<'a>)>, SceneError> {
        match self.get(name) {
            None => Ok(None),
            Some(p) => match p.value {
                Value::Transform(m) => Ok(Some((m, p))),
                _ => Err(p.wrong_type("a transform")),
            },
        }
    }

    /// The child objects with tag `tag`, in document order, marked as read.
    pub fn objects(&self, tag: &str) -> Vec<&Prop<'a>> {
        self.props
            .iter()
            .filter(|p| matches!(p.value, Value::Object(e) if e.tag == tag))
            .inspect(|p| p.used.set(true))
            .collect()
    }

    /// At most one child object with tag `tag` (Mitsuba: a shape has one BSDF, one emitter).
    pub fn object(&self, tag: &str) -> Result<Option<&Prop<'a>>, SceneError> {
        let all = self.objects(tag);
        match all.as_slice() {
            [] => Ok(None),
            [one] => Ok(Some(one)),
            [_, second, ..] => Err(second
                .el
                .pos
                .error(format!("{} has more than one <{tag}>", self.what()))),
        }
    }

    /// Fails on the first property that was not read: unknown to Mitsuba, or a parameter whose
    /// effect lumis does not have. `reads` lists the parameters this object does read.
    pub fn finish(&self, reads: &str) -> Result<(), SceneError> {
        match self.props.iter().find(|p| !p.used.get()) {
            None => Ok(()),
            Some(p) => {
                let what = match &p.value {
                    Value::Object(e) => format!("<{}>", e.tag),
                    v => format!("property `{}` ({})", p.name, v.kind()),
                };
                Err(p.el.pos.error(format!(
                    "{what} is not supported in {} (lumis reads: {reads})",
                    self.what()
                )))
            }
        }
    }
}

impl<'a> Prop<'a> {
    /// Where the value is: the `value` attribute if there is one, else the element.
    pub fn pos(&self) -> &Pos {
        self.el.pos_of("value")
    }

    /// An error about this property's value.
    pub fn error(&self, message: impl Into<String>) -> SceneError {
        self.pos().error(message)
    }

    /// The error for a value of the wrong kind.
    pub fn wrong_type(&self, expected: &str) -> SceneError {
        self.el.pos.error(format!(
            "`{}` must be {expected}, found {}",
            self.name,
            self.value.kind()
        ))
    }

    /// The object, if the value is one.
    pub fn object(&self) -> Option<&'a Element> {
        match self.value {
            Value::Object(e) => Some(e),
            _ => None,
        }
    }
}

/// A property element's name and value; objects without a name are `_arg_N`.
fn property<'a>(
    el: &'a Element,
    ids: &HashMap<&str, &'a Element>,
    args: &mut usize,
) -> Result<(String, Value<'a>), SceneError> {
    let tag = el.tag.as_str();
    let is_object = OBJECT_TAGS.contains(&tag) && (tag != "spectrum" || el.attr("type").is_some());
    if is_object || tag == "ref" {
        let name = match el.value("name") {
            Some(n) => n.to_owned(),
            None => {
                *args += 1;
                format!("_arg_{}", *args - 1)
            }
        };
        if tag == "ref" {
            el.only_attrs(&["id", "name"])?;
            let id = el.required("id")?;
            let target = ids
                .get(id.value.as_str())
                .ok_or_else(|| id.pos.error(format!("no object has the id `{}`", id.value)))?;
            return Ok((name, Value::Object(target)));
        }
        if tag == "scene" {
            return Err(el.pos.error("a <scene> cannot be nested in another object"));
        }
        return Ok((name, Value::Object(el)));
    }
    let name = || -> Result<String, SceneError> { Ok(el.required("name")?.value.clone()) };
    let no_children = || match el.children.first() {
        Some(c) if tag != "transform" => Err(c
            .pos
            .error(format!("<{}> cannot have child elements", el.tag))),
        _ => Ok(()),
    };
    no_children()?;
    let value = |key: &str| -> Result<&'a super::xml::Attr, SceneError> { el.required(key) };
    let v = match tag {
        "float" => {
            el.only_attrs(&["name", "value"])?;
            let a = value("value")?;
            Value::Float(parse_number(&a.value, &a.pos)?)
        }
        "integer" => {
            el.only_attrs(&["name", "value"])?;
            let a = value("value")?;
            Value::Int(
                a.value
                    .trim()
                    .parse()
                    .map_err(|_| a.pos.error(format!("`{}` is not an integer", a.value)))?,
            )
        }
        "boolean" => {
            el.only_attrs(&["name", "value"])?;
            let a = value("value")?;
            Value::Bool(match a.value.to_ascii_lowercase().as_str() {
                "true" => true,
                "false" => false,
                _ => {
                    return Err(a
                        .pos
                        .error(format!("`{}` is not a boolean (true or false)", a.value)));
                }
            })
        }
        "string" => {
            el.only_attrs(&["name", "value"])?;
            Value::Str(value("value")?.value.as_str())
        }
        "rgb" => {
            el.only_attrs(&["name", "value"])?;
            let a = value("value")?;
            Value::Rgb(parse_triple(&a.value, &a.pos, true)?)
        }
        "spectrum" => {
            el.only_attrs(&["name", "value", "filename"])?;
            Value::Spectrum(parse_spectrum(el)?)
        }
        "point" | "vector" => Value::Vector(point(el)?),
        "transform" => {
            el.only_attrs(&["name"])?;
            Value::Transform(parse_transform(el)?)
        }
        "lookat" | "translate" | "rotate" | "scale" | "matrix" => {
            return Err(el
                .pos
                .error(format!("<{tag}> can only appear inside a <transform>")));
        }
        _ => {
            return Err(el.pos.error(format!("unknown element <{tag}>")));
        }
    };
    Ok((name()?, v))
}

/// `<point>`/`<vector>`: `value="x y z"` (or one value for all three), or `x`, `y`, `z`.
fn point(el: &Element) -> Result<DVec3, SceneError> {
    el.only_attrs(&["name", "value", "x", "y", "z"])?;
    if let Some(a) = el.attr("value") {
        if let Some(b) = ["x", "y", "z"].iter().find_map(|k| el.attr(k)) {
            return Err(b
                .pos
                .error("give either `value` or `x`, `y`, `z`, not both"));
        }
        return parse_triple(&a.value, &a.pos, true);
    }
    let mut v = DVec3::ZERO;
    for (i, key) in ["x", "y", "z"].iter().enumerate() {
        let a = el.required(key)?;
        v[i] = parse_number(&a.value, &a.pos)?;
    }
    Ok(v)
}
