//! Loading a scene file for a command: the description, with its warnings (dropped degenerate
//! triangles, vertex normals not used, …) printed to stderr, so they are never lost.

use lumis::scene::{SceneDesc, SceneError, load_scene};
use std::path::Path;

/// [`load_scene`], printing each warning as `warning: FILE: …` on stderr.
pub fn load_scene_warning(path: &Path) -> Result<SceneDesc, SceneError> {
    let desc = load_scene(path)?;
    for w in &desc.warnings {
        eprintln!("warning: {}: {w}", path.display());
    }
    Ok(desc)
}
