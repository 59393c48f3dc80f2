//! The mesh attribute texture: Mitsuba 3.9.1's `mesh_attribute` plugin. Its value at a point of
//! a mesh triangle is the mesh's attribute `name` there, times `scale`: a `vertex_…` attribute
//! interpolated by the point's barycentrics, a `face_…` attribute constant over the triangle.
//! A one-component attribute reads the same in R, G and B (Mitsuba broadcasts it), and a scalar
//! slot reads that component (the luminance of a grey value is the value).
//!
//! The values are the shape's, not the texture's: one texture serves every mesh that carries the
//! attribute (the scene front end checks that each shape using the material carries it, with
//! values in the slot's range), so a lookup needs the hit's triangle ([`TexPoint`]); the scene
//! keeps each mesh's values in [`crate::geometry::mesh_attributes::MeshAttributes`], found by the
//! attribute's `slot`.
//!
//! WGSL twin: `textures/mod.wgsl` (`TEXTURE_MESH_ATTRIBUTE`) and `geometry/mesh_attributes.wgsl`.

use super::TexPoint;
use crate::geometry::primitive::NONE;
use glam::Vec3;

/// A texture that reads a mesh attribute.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshAttributeTexture {
    /// The attribute's name, `vertex_…` or `face_…` (Mitsuba's rule: any other start is an
    /// error).
    pub name: String,
    /// Multiplies the attribute (Mitsuba's `scale`, default 1).
    pub scale: f32,
    /// Which of the scene's attribute names this is
    /// ([`crate::scene::desc::SceneDesc::mesh_attributes`]), set by the front end once the
    /// shapes are known; [`NONE`] before.
    pub slot: u32,
    /// The mean and the per-channel largest value over the meshes that carry it (times
    /// `scale`; vertex values averaged as they are, not by area): what display and light power
    /// read. Zero before the front end binds it.
    pub mean: Vec3,
    /// See `mean`.
    pub max: Vec3,
}

impl MeshAttributeTexture {
    /// An unbound texture of attribute `name` times `scale`.
    pub fn new(name: &str, scale: f32) -> MeshAttributeTexture {
        MeshAttributeTexture {
            name: name.to_owned(),
            scale,
            slot: NONE,
            mean: Vec3::ZERO,
            max: Vec3::ZERO,
        }
    }

    /// The value at `at`: black off a mesh triangle that carries the attribute (never met in
    /// a scene the front end accepted).
    #[inline]
    pub fn eval(&self, at: TexPoint) -> Vec3 {
        match at.mesh {
            Some(m) => m.attributes.named(self.slot, m.attr, m.b) * self.scale,
            None => Vec3::ZERO,
        }
    }
}

/// Whether `name` can name a mesh attribute (Mitsuba's check: it starts with `vertex_` or
/// `face_`).
pub fn is_attribute_name(name: &str) -> bool {
    name.starts_with("vertex_") || name.starts_with("face_")
}
