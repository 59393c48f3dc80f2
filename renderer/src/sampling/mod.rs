//! Pure sampling routines: each warp from `[0,1)ⁿ` comes with its pdf and its inverse.

pub mod bilinear;
pub mod cone;
pub mod discrete;
pub mod disk;
pub mod elliptic;
pub mod hemisphere;
pub mod piecewise2d;
pub mod projected_solid_angle;
pub mod sphere;
pub mod spherical_ellipse;
pub mod spherical_rectangle;
pub mod spherical_triangle;
pub mod triangle;

#[cfg(test)]
mod testing;

pub use bilinear::*;
pub use cone::*;
pub use discrete::DiscreteDistribution;
pub use disk::*;
pub use hemisphere::*;
pub use piecewise2d::Piecewise2D;
pub use projected_solid_angle::ProjectedPolygon;
pub use sphere::*;
pub use spherical_ellipse::{MAX_ELLIPSE_SOLID_ANGLE, MIN_ELLIPSE_SOLID_ANGLE, SphericalEllipse};
pub use spherical_rectangle::SphericalRectangle;
pub use spherical_triangle::*;
pub use triangle::*;

/// The largest f32 below 1: sample values are kept in `[0, 1)`.
pub const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;
