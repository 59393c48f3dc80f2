//! The one error type of scene loading: what is wrong, where in the JSON, in which file.

use std::fmt;
use std::path::PathBuf;

/// A scene file that cannot be loaded, with the JSON path of the problem.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneError {
    /// JSON path of the offending value, e.g. `shapes[3].vertices` or
    /// `materials.red.albedo[1]`; empty for problems with the file as a whole (I/O, JSON syntax).
    pub path: String,
    /// What is wrong, in words for the scene's author.
    pub message: String,
    /// The file, when the scene came from one.
    pub file: Option<PathBuf>,
}

impl SceneError {
    /// An error at `path` (no file yet: [`crate::scene::load_scene`] adds it). Control
    /// characters are escaped, so that a key or name from the file written with `\n` cannot
    /// break the message over several lines.
    pub fn new(path: impl Into<String>, message: impl Into<String>) -> SceneError {
        SceneError {
            path: one_line(path.into()),
            message: one_line(message.into()),
            file: None,
        }
    }

    /// The same error, attributed to `file`.
    pub fn in_file(mut self, file: impl Into<PathBuf>) -> SceneError {
        self.file = Some(file.into());
        self
    }
}

/// Whether `c` would end or disturb a line of terminal output.
fn breaks_line(c: char) -> bool {
    c.is_control() || c == '\u{2028}' || c == '\u{2029}'
}

/// `s` with every line-breaking character written as its Rust escape (`\n`, `\u{1b}`).
fn one_line(s: String) -> String {
    if !s.chars().any(breaks_line) {
        return s;
    }
    s.chars()
        .map(|c| {
            if breaks_line(c) {
                c.escape_default().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(file) = &self.file {
            // File names may hold newlines too.
            write!(f, "{}: ", one_line(file.display().to_string()))?;
        }
        if !self.path.is_empty() {
            write!(f, "{}: ", self.path)?;
        }
        f.write_str(&self.message)
    }
}

impl std::error::Error for SceneError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_names_file_and_path() {
        let e = SceneError::new("shapes[3].vertices", "not planar");
        assert_eq!(e.to_string(), "shapes[3].vertices: not planar");
        let e = e.in_file("scenes/a.json");
        assert_eq!(
            e.to_string(),
            "scenes/a.json: shapes[3].vertices: not planar"
        );
        assert_eq!(SceneError::new("", "bad JSON").to_string(), "bad JSON");
    }

    #[test]
    fn control_characters_are_escaped() {
        let e =
            SceneError::new("materials.a\nb", "unknown key `a\nb\r\u{2028}`").in_file("x\ny.json");
        assert_eq!(
            e.to_string(),
            "x\\ny.json: materials.a\\nb: unknown key `a\\nb\\r\\u{2028}`"
        );
    }
}
