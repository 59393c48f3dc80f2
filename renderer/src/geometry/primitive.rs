//! A primitive: one hittable shape with its material and, if it emits, its light.
//! WGSL twin: `geometry/primitive.wgsl`.

use super::cylinder::Cylinder;
use super::disk::Disk;
use super::ray::{Ray, SurfaceHit};
use super::sphere::Sphere;
use super::triangle::{TriangleRay, intersect_triangle_prepared, triangle_normal, triangle_point};
use glam::Vec3;

/// Marks "no light" / "no material".
pub const NONE: u32 = u32::MAX;

/// A candidate hit found by [`Shape::intersect_t`]: its ray parameter and, for triangles, the
/// barycentrics, kept so that the closest hit's record needs no second triangle test.
#[derive(Clone, Copy, Debug)]
pub struct ShapeHit {
    /// Ray parameter.
    pub t: f32,
    /// Barycentrics of a triangle hit (unused for the analytic shapes).
    pub b: [f32; 3],
}

/// The shapes the BVH holds. Quads, polygons and boxes are triangulated; disks, spheres and
/// cylinders stay analytic.
#[derive(Clone, Copy, Debug)]
pub enum Shape {
    /// A flat triangle with its right-hand-rule normal.
    Triangle {
        /// Vertices.
        v: [Vec3; 3],
        /// Unit normal.
        n: Vec3,
    },
    /// A disk.
    Disk(Disk),
    /// A sphere.
    Sphere(Sphere),
    /// A cylinder (Mitsuba's open tube).
    Cylinder(Cylinder),
}

impl Shape {
    /// A triangle shape, or `None` if it is degenerate.
    pub fn triangle(v: [Vec3; 3]) -> Option<Shape> {
        triangle_normal(&v).map(|n| Shape::Triangle { v, n })
    }

    /// Axis-aligned bounds.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        match self {
            Shape::Triangle { v, .. } => (v[0].min(v[1]).min(v[2]), v[0].max(v[1]).max(v[2])),
            Shape::Disk(d) => d.bounds(),
            Shape::Sphere(s) => (s.center - s.radius, s.center + s.radius),
            Shape::Cylinder(c) => c.bounds(),
        }
    }

    /// The nearest hit in `(0, ray.t_max)`; `tri` is `ray` prepared for triangles.
    #[inline(always)]
    pub fn intersect_t(&self, ray: &Ray, tri: &TriangleRay) -> Option<ShapeHit> {
        match self {
            Shape::Triangle { v, .. } => {
                intersect_triangle_prepared(tri, v, ray.t_max).map(|h| ShapeHit { t: h.t, b: h.b })
            }
            Shape::Disk(d) => d.intersect(ray).map(|t| ShapeHit { t, b: [0.0; 3] }),
            Shape::Sphere(s) => s.intersect(ray).map(|t| ShapeHit { t, b: [0.0; 3] }),
            Shape::Cylinder(c) => c.intersect(ray).map(|t| ShapeHit { t, b: [0.0; 3] }),
        }
    }

    /// The next hit in `(after, ray.t_max)` beyond a hit at `after` that a mask let the ray pass
    /// ([`crate::materials::mask`]): a sphere's or cylinder's far side; none for the flat shapes,
    /// which a ray meets once.
    #[inline]
    pub fn intersect_t_beyond(&self, ray: &Ray, after: f32) -> Option<ShapeHit> {
        let t = match self {
            Shape::Triangle { .. } | Shape::Disk(_) => None,
            Shape::Sphere(s) => s.intersect_beyond(ray, after),
            Shape::Cylinder(c) => c.intersect_beyond(ray, after),
        };
        t.map(|t| ShapeHit { t, b: [0.0; 3] })
    }

    /// Full hit record for `hit` (found by [`Shape::intersect_t`] on the same ray).
    pub fn surface_hit(&self, ray: &Ray, hit: ShapeHit, prim: u32) -> SurfaceHit {
        let t = hit.t;
        match self {
            Shape::Triangle { v, n } => {
                let (p, p_error) = triangle_point(v, hit.b);
                SurfaceHit {
                    t,
                    p,
                    p_error,
                    n: *n,
                    prim,
                    b: glam::Vec2::new(hit.b[1], hit.b[2]),
                }
            }
            Shape::Disk(d) => {
                let (p, p_error) = d.surface_point(ray, t);
                SurfaceHit {
                    t,
                    p,
                    p_error,
                    n: d.n,
                    prim,
                    b: glam::Vec2::ZERO,
                }
            }
            Shape::Sphere(s) => {
                let (p, p_error, n) = s.surface_point(ray, t);
                SurfaceHit {
                    t,
                    p,
                    p_error,
                    n,
                    prim,
                    b: glam::Vec2::ZERO,
                }
            }
            Shape::Cylinder(c) => {
                let (p, p_error, n) = c.surface_point(ray, t);
                SurfaceHit {
                    t,
                    p,
                    p_error,
                    n,
                    prim,
                    b: glam::Vec2::ZERO,
                }
            }
        }
    }
}

/// A shape with its material index and light index ([`NONE`] if it does not emit).
#[derive(Clone, Copy, Debug)]
pub struct Primitive {
    /// Geometry.
    pub shape: Shape,
    /// Index into the scene's materials.
    pub material: u32,
    /// Index into the scene's lights, or [`NONE`].
    pub light: u32,
    /// Index of the triangle's vertex attributes (shading normals, UVs) in the scene's
    /// [`MeshAttributes`](super::mesh_attributes::MeshAttributes), or [`NONE`].
    pub attr: u32,
}

// One primitive per 64-byte cache line: the traversal reads them in its inner loop, so a shape
// grows only within a triangle's 48 bytes (a sphere keeps two axes of its frame, not three).
const _: () = assert!(std::mem::size_of::<Primitive>() == 64);

impl obvhs::Boundable for Primitive {
    fn aabb(&self) -> obvhs::aabb::Aabb {
        // Widened by the rounding of the analytic shapes' bounds, so the box holds every hit.
        let (lo, hi) = self.shape.bounds();
        let pad = super::ray::gamma(3) * lo.abs().max(hi.abs());
        obvhs::aabb::Aabb::new((lo - pad).into(), (hi + pad).into())
    }
}
