//! Scenes: the JSON scene format (`docs/scene-format.md`), its validation into a plain
//! [`SceneDesc`], and errors that name the JSON path of every problem.
//!
//! * [`desc`] — the validated description (f64 plain data) and its writer,
//!   [`SceneDesc::to_json`].
//! * [`parse`] — [`parse_scene`] / [`load_scene`], with materials and shapes in their own files.
//! * [`mitsuba`] — Mitsuba 3 XML scenes, translated into the JSON format ([`load_scene_with`]).
//! * [`error`] — [`SceneError`].
//! * [`build`] — the render-ready [`Scene`] (primitives in a BVH, materials, lights).

pub mod build;
pub mod desc;
pub mod error;
pub mod mesh;
pub mod mitsuba;
pub mod model;
mod model_gltf;
mod model_studio;
pub mod parse;
mod parse_background;
mod parse_composite;
pub(crate) mod parse_gltf_pbr;
mod parse_lights;
mod parse_materials;
mod parse_mesh;
mod parse_mesh_attribute;
mod parse_mesh_file;
pub(crate) mod parse_principled;
pub(crate) mod parse_principled_thin;
mod parse_shapes;
mod parse_surface_detail;
mod parse_texture;
mod select_light;
pub mod surface;
mod trace;
mod walk;

#[cfg(test)]
mod tests;

pub use build::Scene;
pub use desc::{
    BackgroundDesc, CameraDesc, EnvmapDesc, FilterDesc, FresnelDesc, GeometryDesc, LightDesc,
    LookAt, MaterialDesc, MaterialTextures, NamedMaterial, PlasticModel, ProjectionDesc, SceneDesc,
    ShapeDesc, TextureDesc,
};
pub use error::SceneError;
pub use model::ModelOptions;
pub use parse::{
    LoadedScene, load_scene, load_scene_options, load_scene_params, load_scene_with, parse_scene,
    parse_scene_in, parse_scene_value, parse_scene_value_in,
};
