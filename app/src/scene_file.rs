//! Loading a scene file for a command: the description, with its warnings (dropped degenerate
//! triangles, vertex normals not used, …) printed to stderr, so they are never lost, and the
//! command line's parameters (`-D name=value`, and `--spp` as `$spp`) for the Mitsuba scene it
//! names.

use lumis::scene::mitsuba::Params;
use lumis::scene::{LoadedScene, ModelOptions, SceneDesc, SceneError, load_scene_options};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, Ordering};

/// The command line's scene and its parameters.
static DEFINES: OnceLock<(PathBuf, Params)> = OnceLock::new();

/// Sets the `-D name=value` parameters and the `--spp` of the command line's scene `scene`
/// (once per process): every later load of that file gets them, and loads of other files (the
/// viewer's open and drop) get none.
pub fn set_defines(scene: &Path, defines: Vec<(String, String)>, spp: Option<u32>) {
    // A second call (tests running several commands) keeps the first.
    let _ = DEFINES.set((scene.to_owned(), Params { defines, spp }));
}

/// Whether a model file opened on its own gets the studio (`--no-studio` turns it off; the
/// viewer's toggle flips it and reloads).
static STUDIO: AtomicBool = AtomicBool::new(true);

/// Sets whether models opened on their own get the studio (every later load).
pub fn set_studio(on: bool) {
    STUDIO.store(on, Ordering::Relaxed);
}

/// Whether models opened on their own get the studio.
pub fn studio() -> bool {
    STUDIO.load(Ordering::Relaxed)
}

/// [`load_scene_file`]'s description.
pub fn load_scene_warning(path: &Path) -> Result<SceneDesc, SceneError> {
    Ok(load_scene_file(path)?.desc)
}

/// [`load_scene_options`] with the parameters set for `path` by [`set_defines`] and the studio
/// as [`set_studio`] left it, printing each warning as `warning: FILE: …` on stderr.
pub fn load_scene_file(path: &Path) -> Result<LoadedScene, SceneError> {
    let none = Params::default();
    let params = match DEFINES.get() {
        Some((scene, p)) if scene == path => p,
        _ => &none,
    };
    let model = ModelOptions { studio: studio() };
    let loaded = load_scene_options(path, params, model)?;
    for w in &loaded.desc.warnings {
        eprintln!("warning: {}: {w}", path.display());
    }
    Ok(loaded)
}
