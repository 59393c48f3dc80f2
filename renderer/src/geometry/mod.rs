//! Geometry: rays, the shapes that can be hit, robust ray offsets, and the BVH.

pub mod bvh;
pub mod bvh_build;
pub mod cylinder;
pub mod disk;
pub mod mesh_attributes;
pub mod polygon;
pub mod primitive;
pub mod ray;
pub mod sphere;
pub mod tangent;
pub mod triangle;
pub mod wide_bvh;

pub use bvh::Accel;
pub use primitive::{Primitive, Shape, ShapeHit};
pub use ray::{Ray, SurfaceHit};
