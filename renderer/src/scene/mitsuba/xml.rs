//! The Mitsuba 3 XML document: files read with `roxmltree`, `<default>` parameters and `$name`
//! substitution (overridable by `-D name=value`), `<path>` and `<include>` through Mitsuba's
//! file resolver (cycles refused), `<alias>` and the `id` index that `<ref>` resolves against.
//! The result is one owned element tree in which every element and attribute knows its file,
//! line, column and element path, for messages.
//!
//! Mitsuba 3.9.1's rules (`src/core/parser.cpp`) are followed: parameters are substituted in
//! document order, longest name first, `\$` escapes a dollar sign, an undefined `$name` is an
//! error, a `<default>` never overrides a parameter already set (a `-D` or an earlier default),
//! and a `-D` parameter that no attribute uses is an error. An included file whose root is a
//! `<scene>` contributes its children; any other root element is inserted as one child.
//!
//! File names, as Mitsuba 3.9.1 resolves them (each rule checked against Mitsuba itself,
//! `renderer/tests/mitsuba_xml/grammar.rs`): every file is read with a search list of folders,
//! its own folder first, then the list of the file that included it as it was at the
//! `<include>`. A `<path value>` (only a child of the root) is resolved through that list, must
//! exist, and goes to the front of it: newest first. An `<include filename>` is resolved through
//! the including file's list. The file names inside objects (meshes, textures, environment
//! maps) are resolved when the scene is built, through the *main* file's final list: its
//! `<path>`s newest first (wherever they stand in the file), then its folder; a `<path>` or the
//! folder of an included file does not count. A `<spectrum filename>`, read while parsing, is
//! resolved through the main file's list as it is at that point. A name found nowhere is taken
//! as it is, relative to the working directory, as Mitsuba does.

use crate::scene::error::SceneError;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Mitsuba's limit on nested includes (`ParserConfig::max_include_depth`).
const MAX_INCLUDE_DEPTH: usize = 15;

/// Where an element or attribute is: its file, line and column (1-based) and its element path
/// within that file (`scene/shape[2]/bsdf/rgb@value`; an index, counted from 1 as in XPath, is
/// written where the parent has several children of that tag).
#[derive(Clone, Debug, PartialEq)]
pub struct Pos {
    /// The XML file.
    pub file: Arc<PathBuf>,
    /// Line, from 1.
    pub line: u32,
    /// Column, from 1.
    pub col: u32,
    /// Element path within the file.
    pub path: String,
}

impl Pos {
    /// `file:line:col: element path`, the prefix of every message about this place.
    pub fn describe(&self) -> String {
        format!(
            "{}:{}:{}: {}",
            self.file.display(),
            self.line,
            self.col,
            self.path
        )
    }

    /// An error at this place.
    pub fn error(&self, message: impl Into<String>) -> SceneError {
        SceneError::new(self.describe(), message)
    }
}

/// One attribute, after `$name` substitution.
#[derive(Clone, Debug)]
pub struct Attr {
    /// Its name.
    pub name: String,
    /// Its value.
    pub value: String,
    /// Where it is (the path ends in `@name`).
    pub pos: Pos,
}

/// One element of the document, after substitution and with includes spliced in.
#[derive(Clone, Debug)]
pub struct Element {
    /// The tag name (`shape`, `float`, …).
    pub tag: String,
    /// Its attributes in document order.
    pub attrs: Vec<Attr>,
    /// Its child elements (comments and text dropped).
    pub children: Vec<Element>,
    /// Where it is.
    pub pos: Pos,
}

impl Element {
    /// The attribute `name`, if present.
    pub fn attr(&self, name: &str) -> Option<&Attr> {
        self.attrs.iter().find(|a| a.name == name)
    }

    /// The value of attribute `name`, if present.
    pub fn value(&self, name: &str) -> Option<&str> {
        self.attr(name).map(|a| a.value.as_str())
    }

    /// The required attribute `name`, or an error naming the element.
    pub fn required(&self, name: &str) -> Result<&Attr, SceneError> {
        self.attr(name).ok_or_else(|| {
            self.pos
                .error(format!("<{}> needs the attribute `{name}`", self.tag))
        })
    }

    /// Where attribute `name` is, or the element when it has none.
    pub fn pos_of(&self, name: &str) -> &Pos {
        self.attr(name).map_or(&self.pos, |a| &a.pos)
    }

    /// Fails on any attribute outside `allowed` (Mitsuba's `check_attributes`).
    pub fn only_attrs(&self, allowed: &[&str]) -> Result<(), SceneError> {
        match self
            .attrs
            .iter()
            .find(|a| !allowed.contains(&a.name.as_str()))
        {
            None => Ok(()),
            Some(a) => Err(a.pos.error(format!(
                "unexpected attribute `{}` in <{}> (allowed: {})",
                a.name,
                self.tag,
                allowed.join(", ")
            ))),
        }
    }
}

/// A whole document: the root `<scene>` with every include spliced in.
#[derive(Debug)]
pub struct Document {
    /// The root element.
    pub root: Element,
    /// The file that was opened.
    pub file: PathBuf,
    /// The main file's search list after reading it (its `<path>`s newest first, then its
    /// folder), through which the objects' file names are resolved ([`resolve`]).
    pub search: Vec<PathBuf>,
}

impl Document {
    /// Every element with an `id`, and every `<alias>`'s new name, for `<ref id>`. Visited in
    /// document order as Mitsuba does: an alias's source must be defined before it and its new
    /// name must not be taken; a repeated id is an error naming both places.
    pub fn ids(&self) -> Result<HashMap<&str, &Element>, SceneError> {
        let mut ids: HashMap<&str, &Element> = HashMap::new();
        let mut stack = vec![&self.root];
        while let Some(el) = stack.pop() {
            stack.extend(el.children.iter().rev());
            if el.tag == "alias" {
                let (id, alias) = (el.required("id")?, el.required("as")?);
                let Some(&target) = ids.get(id.value.as_str()) else {
                    return Err(id.pos.error(format!(
                        "alias of `{}`, which is not defined before this point",
                        id.value
                    )));
                };
                if let Some(prev) = ids.insert(alias.value.as_str(), target) {
                    return Err(alias.pos.error(format!(
                        "alias `{}` is already the id of the object at {}",
                        alias.value,
                        prev.pos.describe()
                    )));
                }
                continue;
            }
            // Objects have ids; a <ref>'s `id` names one.
            if let Some(id) = el.attr("id").filter(|_| el.tag != "ref")
                && let Some(prev) = ids.insert(id.value.as_str(), el)
            {
                return Err(id.pos.error(format!(
                    "duplicate id `{}` (first defined at {})",
                    id.value,
                    prev.pos.describe()
                )));
            }
        }
        Ok(ids)
    }
}

/// `name` through a search list: the first folder that has it, else `name` as it is (relative
/// to the working directory), as Mitsuba's `FileResolver::resolve`.
pub fn resolve(name: &Path, search: &[PathBuf]) -> PathBuf {
    if name.is_absolute() {
        return name.to_owned();
    }
    search
        .iter()
        .map(|dir| dir.join(name))
        .find(|p| p.exists())
        .unwrap_or_else(|| name.to_owned())
}

/// A `$name` parameter: from the command line (`-D`) or a `<default>`.
struct Param {
    /// `$name`.
    key: String,
    value: String,
    /// Whether any attribute used it (only `-D` parameters must be used).
    used: bool,
}

/// The command line's parameters for a Mitsuba scene.
#[derive(Clone, Debug, Default)]
pub struct Params {
    /// `-D name=value`: replaces `$name`, overriding a `<default>`; each must be used (Mitsuba
    /// refuses unused parameters).
    pub defines: Vec<(String, String)>,
    /// `--spp N`: the value of `$spp` where the scene has one (overriding its `<default>`, as
    /// `-D spp=N` would), unused without error: how Mitsuba's gallery renders are given their
    /// sample count. A `-D spp` takes precedence.
    pub spp: Option<u32>,
}

/// Reads `path` and everything it includes, with the command line's parameters.
pub fn load(path: &Path, params: &Params) -> Result<Document, SceneError> {
    let mut loader = Loader {
        params: Vec::new(),
        stack: Vec::new(),
        search: Vec::new(),
    };
    for (name, value) in &params.defines {
        if !is_param_name(name) {
            return Err(SceneError::new(
                "",
                format!("-D {name}={value}: a parameter name is letters, digits and `_`"),
            )
            .in_file(path));
        }
        loader.add_param(name, value, false);
    }
    if let Some(spp) = params.spp {
        loader.add_param("spp", &spp.to_string(), true);
    }
    // The top file gives its root element (only included scenes contribute children).
    let (elements, search) = loader.load_file(path, None)?;
    let root = elements
        .into_iter()
        .next()
        .ok_or_else(|| SceneError::new("", "the file has no root element").in_file(path))?;
    if root.tag != "scene" {
        return Err(root.pos.error(format!(
            "the root element must be <scene>, found <{}>",
            root.tag
        )));
    }
    if let Some(p) = loader.params.iter().find(|p| !p.used) {
        return Err(SceneError::new(
            "",
            format!(
                "-D {}={}: the scene uses no parameter `{}` (Mitsuba refuses unused parameters too)",
                &p.key[1..],
                p.value,
                &p.key[1..]
            ),
        )
        .in_file(path));
    }
    Ok(Document {
        root,
        file: path.to_owned(),
        search,
    })
}

/// Whether `name` can follow a `$` (Mitsuba stops a name at the first other character).
fn is_param_name(name: &str) -> bool {
    !name.is_empty() && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

struct Loader {
    /// Sorted longest key first, so that `$ab` is replaced before `$a`.
    params: Vec<Param>,
    /// The files being read, outermost first (canonical paths), to refuse cyclic includes.
    stack: Vec<PathBuf>,
    /// The search list of each file being read, outermost first (the module's rules).
    search: Vec<Vec<PathBuf>>,
}

impl Loader {
    fn add_param(&mut self, name: &str, value: &str, used: bool) {
        let key = format!("${name}");
        if self.params.iter().any(|p| p.key == key) {
            return;
        }
        let at = self
            .params
            .iter()
            .position(|p| p.key.len() < key.len())
            .unwrap_or(self.params.len());
        self.params.insert(
            at,
            Param {
                key,
                value: value.to_owned(),
                used,
            },
        );
    }

    /// `value` with every parameter substituted; an undefined `$name` is an error at `pos`.
    fn substitute(&mut self, value: &str, pos: &Pos) -> Result<String, SceneError> {
        if !value.contains('$') {
            return Ok(value.to_owned());
        }
        let mut out = value.to_owned();
        for p in &mut self.params {
            let mut from = 0;
            while let Some(i) = out[from..].find(&p.key).map(|i| i + from) {
                if i > 0 && out.as_bytes()[i - 1] == b'\\' {
                    from = i + p.key.len();
                } else {
                    out.replace_range(i..i + p.key.len(), &p.value);
                    p.used = true;
                    from = i + p.value.len();
                }
            }
        }
        let bytes = out.as_bytes();
        for (i, &b) in bytes.iter().enumerate() {
            if b == b'$' && (i == 0 || bytes[i - 1] != b'\\') {
                let name: String = out[i + 1..]
                    .chars()
                    .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                    .collect();
                let spp = if name == "spp" { ", or --spp" } else { "" };
                return Err(pos.error(format!(
                    "undefined parameter `${name}` (define it with <default name=\"{name}\" \
                     value=\"…\"/> or -D {name}=…{spp})"
                )));
            }
        }
        Ok(out.replace("\\$", "$"))
    }

    /// The elements `path` contributes (its root, or for an included `<scene>` its children)
    /// and its search list after reading it. `include` is the `<include>` element that names
    /// it (for messages), if any.
    fn load_file(
        &mut self,
        path: &Path,
        include: Option<&Pos>,
    ) -> Result<(Vec<Element>, Vec<PathBuf>), SceneError> {
        let at_include = |msg: String| match include {
            Some(pos) => pos.error(msg),
            None => SceneError::new("", msg).in_file(path),
        };
        let canonical = std::fs::canonicalize(path).map_err(|e| match include {
            Some(_) => at_include(format!(
                "cannot read the included file {}: {e}",
                path.display()
            )),
            None => at_include(format!("cannot read the scene file: {e}")),
        })?;
        if let Some(first) = self.stack.iter().position(|p| *p == canonical) {
            let chain: Vec<String> = self.stack[first..]
                .iter()
                .chain([&canonical])
                .map(|p| p.display().to_string())
                .collect();
            return Err(at_include(format!(
                "cyclic include: {}",
                chain.join(" includes ")
            )));
        }
        if self.stack.len() > MAX_INCLUDE_DEPTH {
            return Err(at_include(format!(
                "includes nested more than {MAX_INCLUDE_DEPTH} deep (Mitsuba's limit)"
            )));
        }
        let text = std::fs::read_to_string(path)
            .map_err(|e| at_include(format!("cannot read {}: {e}", path.display())))?;
        let file = Arc::new(path.to_owned());
        let doc = roxmltree::Document::parse(&text).map_err(|e| {
            let p = e.pos();
            SceneError::new(
                format!("{}:{}:{}", path.display(), p.row, p.col),
                format!("XML syntax error: {e}"),
            )
        })?;
        let root = doc.root_element();
        let root_pos = pos_of(
            &doc,
            &file,
            root.range().start,
            root.tag_name().name().into(),
        );
        let version = root.attribute("version").ok_or_else(|| {
            root_pos.error(format!(
                "<{}> needs the attribute `version` (the Mitsuba scene format version)",
                root.tag_name().name()
            ))
        })?;
        check_version(version, &root_pos)?;
        // Its own folder, then the includer's list as it is now.
        let mut search = vec![path.parent().unwrap_or(Path::new("")).to_owned()];
        search.extend(self.search.last().into_iter().flatten().cloned());
        self.stack.push(canonical);
        self.search.push(search);
        let result = self.element(&doc, &file, root, root.tag_name().name().to_owned());
        self.stack.pop();
        let search = self.search.pop().unwrap_or_default();
        let root = result?;
        let elements = match (include, root.tag.as_str()) {
            (Some(_), "scene") => root.children,
            _ => vec![root],
        };
        Ok((elements, search))
    }

    /// One element and its subtree (includes expanded in place) at element path `path`.
    /// `<default>` and `<include>` elements take effect here and leave no element behind; they
    /// come back as an empty list, everything else as one element.
    fn element(
        &mut self,
        doc: &roxmltree::Document,
        file: &Arc<PathBuf>,
        node: roxmltree::Node,
        path: String,
    ) -> Result<Element, SceneError> {
        let pos = pos_of(doc, file, node.range().start, path.clone());
        let mut attrs = Vec::new();
        for a in node.attributes() {
            if a.namespace().is_some() {
                continue;
            }
            let apos = pos_of(doc, file, a.range().start, format!("{path}@{}", a.name()));
            let value = self.substitute(a.value(), &apos)?;
            attrs.push(Attr {
                name: a.name().to_owned(),
                value,
                pos: apos,
            });
        }
        if node.tag_name().name() == "spectrum"
            && let Some(a) = attrs.iter_mut().find(|a| a.name == "filename")
        {
            // Read while parsing, through the main file's list as it is at this point.
            let main = self.search.first().expect("a file is being read");
            a.value = resolve(Path::new(&a.value), main)
                .to_string_lossy()
                .into_owned();
        }
        let mut el = Element {
            tag: node.tag_name().name().to_owned(),
            attrs,
            children: Vec::new(),
            pos,
        };
        // Element paths index repeated tags among siblings, counted in the file as written.
        let kids: Vec<roxmltree::Node> = node.children().filter(|n| n.is_element()).collect();
        let mut seen: HashMap<&str, usize> = HashMap::new();
        for child in &kids {
            let tag = child.tag_name().name();
            let total = kids.iter().filter(|k| k.tag_name().name() == tag).count();
            let n = seen.entry(tag).or_insert(0);
            *n += 1;
            let child_path = if total > 1 {
                format!("{path}/{tag}[{n}]")
            } else {
                format!("{path}/{tag}")
            };
            match tag {
                "default" => self.default(doc, file, *child, child_path)?,
                "path" => {
                    let el = self.element(doc, file, *child, child_path)?;
                    if node.parent_element().is_some() {
                        return Err(el.pos.error(
                            "<path> can only be a child of the root element (as in Mitsuba)",
                        ));
                    }
                    self.path(&el)?;
                }
                "include" => {
                    let inc = self.element(doc, file, *child, child_path)?;
                    el.children.extend(self.include(&inc)?);
                }
                _ => el
                    .children
                    .push(self.element(doc, file, *child, child_path)?),
            }
        }
        Ok(el)
    }

    /// `<default name value>`: a parameter unless one of that name is already set.
    fn default(
        &mut self,
        doc: &roxmltree::Document,
        file: &Arc<PathBuf>,
        node: roxmltree::Node,
        path: String,
    ) -> Result<(), SceneError> {
        let el = self.element(doc, file, node, path)?;
        el.only_attrs(&["name", "value"])?;
        let name = el.required("name")?;
        let value = el.required("value")?;
        if !is_param_name(&name.value) {
            return Err(name.pos.error(format!(
                "`{}` is not a parameter name (letters, digits and `_`)",
                name.value
            )));
        }
        if let Some(c) = el.children.first() {
            return Err(c.pos.error("<default> has no child elements"));
        }
        // Defaults count as used: only -D parameters must be used.
        self.add_param(&name.value, &value.value, true);
        Ok(())
    }

    /// `<path value>`: a folder, resolved through the current file's search list, put first in
    /// that list.
    fn path(&mut self, el: &Element) -> Result<(), SceneError> {
        el.only_attrs(&["value"])?;
        let value = el.required("value")?;
        if let Some(c) = el.children.first() {
            return Err(c.pos.error("<path> has no child elements"));
        }
        let search = self.search.last_mut().expect("a file is being read");
        let dir = resolve(Path::new(&value.value), search);
        if !dir.is_dir() {
            return Err(value.pos.error(format!(
                "<path>: no folder `{}` (searched: {})",
                value.value,
                describe_search(search)
            )));
        }
        search.insert(0, dir);
        Ok(())
    }

    /// `<include filename [name]>`: the file's elements; the name is resolved through the
    /// including file's search list.
    fn include(&mut self, inc: &Element) -> Result<Vec<Element>, SceneError> {
        inc.only_attrs(&["filename", "name"])?;
        let name = inc.required("filename")?;
        let search = self.search.last().expect("a file is being read");
        let target = resolve(Path::new(&name.value), search);
        let (mut elements, _) = self.load_file(&target, Some(&name.pos))?;
        if let [single] = elements.as_mut_slice()
            && single.tag != "scene"
        {
            // The root's version is the file's; as a child it is an ordinary object.
            single.attrs.retain(|a| a.name != "version");
            if let Some(prop) = inc.attr("name") {
                single.attrs.retain(|a| a.name != "name");
                single.attrs.push(prop.clone());
            }
        }
        Ok(elements)
    }
}

/// A search list for messages: the folders, newest first, then the working directory.
pub fn describe_search(search: &[PathBuf]) -> String {
    let mut dirs: Vec<String> = search
        .iter()
        .map(|d| match d.as_os_str().is_empty() {
            true => "./".to_owned(),
            false => format!("{}/", d.display()),
        })
        .collect();
    dirs.push("the working directory".to_owned());
    dirs.join(", ")
}

/// A file position as a [`Pos`].
fn pos_of(doc: &roxmltree::Document, file: &Arc<PathBuf>, byte: usize, path: String) -> Pos {
    let p = doc.text_pos_at(byte);
    Pos {
        file: file.clone(),
        line: p.row,
        col: p.col,
        path,
    }
}

/// The root's `version="major.minor.patch"`: Mitsuba 3 reads 2.x and later as they are (older
/// files it upgrades, renaming camelCase properties; lumis does not).
fn check_version(version: &str, pos: &Pos) -> Result<(), SceneError> {
    let parts: Vec<Option<u32>> = version.split('.').map(|p| p.trim().parse().ok()).collect();
    if parts.len() != 3 || parts.iter().any(Option::is_none) {
        return Err(pos.error(format!(
            "invalid version `{version}` (expected major.minor.patch, e.g. 3.0.0)"
        )));
    }
    if parts[0] < Some(2) {
        return Err(pos.error(format!(
            "version {version}: scenes of Mitsuba 0.x (before 2.0.0) are not supported; \
             Mitsuba 3 upgrades them on loading, lumis does not"
        )));
    }
    Ok(())
}
