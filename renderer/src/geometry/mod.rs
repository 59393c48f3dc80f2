//! Geometry.
pub mod polygon;
