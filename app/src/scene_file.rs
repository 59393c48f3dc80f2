//! Loading a scene file for a command: the description, with its warnings (dropped degenerate
//! triangles, vertex normals not used, …) printed to stderr, so they are never lost, and the
//! command line's `-D name=value` parameters for the Mitsuba scene it names.

use lumis::scene::{LoadedScene, SceneDesc, SceneError, load_scene_with};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// The command line's scene and its `-D` parameters.
static DEFINES: OnceLock<(PathBuf, Vec<(String, String)>)> = OnceLock::new();

/// Sets the `-D name=value` parameters of the command line's scene `scene` (once per process):
/// every later load of that file gets them, and loads of other files (the viewer's open and
/// drop) get none.
pub fn set_defines(scene: &Path, defines: Vec<(String, String)>) {
    // A second call (tests running several commands) keeps the first.
    let _ = DEFINES.set((scene.to_owned(), defines));
}

/// [`load_scene_file`]'s description.
pub fn load_scene_warning(path: &Path) -> Result<SceneDesc, SceneError> {
    Ok(load_scene_file(path)?.desc)
}

/// [`load_scene_with`] with the parameters set for `path` by [`set_defines`], printing each
/// warning as `warning: FILE: …` on stderr.
pub fn load_scene_file(path: &Path) -> Result<LoadedScene, SceneError> {
    let defines = match DEFINES.get() {
        Some((scene, d)) if scene == path => d.as_slice(),
        _ => &[],
    };
    let loaded = load_scene_with(path, defines)?;
    for w in &loaded.desc.warnings {
        eprintln!("warning: {}: {w}", path.display());
    }
    Ok(loaded)
}
