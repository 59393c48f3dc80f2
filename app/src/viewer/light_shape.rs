//! Reshaping an area light in the scene description: a planar light is reduced to its centre,
//! orientation (normal and an in-plane axis) and area, and rebuilt as a regular polygon with any
//! number of sides, a disk, a square quad or a triangle, keeping either its area or its power.
//! Working on the description (then `Scene::from_desc`) keeps the renderer's lights untouched.

use glam::DVec3;
use lumis::geometry::polygon::newell_normal;
use lumis::scene::GeometryDesc;
use std::f64::consts::PI;

/// Most polygon sides the shape slider offers; the slider's next stop is the disk.
pub const MAX_SIDES: u32 = 64;
/// The shape slider's value for a disk.
pub const DISK_STOP: u32 = MAX_SIDES + 1;

/// The shape of a planar light.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightShape {
    /// Regular polygon (3 to [`MAX_SIDES`] sides), a `polygon` light.
    Polygon(u32),
    /// A `disk` light.
    Disk,
    /// A square `quad` light.
    Quad,
    /// An equilateral one-triangle `triangles` light.
    Triangle,
}

impl LightShape {
    /// Name shown in the shape menu.
    pub fn label(self) -> String {
        match self {
            LightShape::Polygon(n) => format!("polygon ({n} sides)"),
            LightShape::Disk => "disk".into(),
            LightShape::Quad => "quad".into(),
            LightShape::Triangle => "triangle".into(),
        }
    }

    /// Area over circumradius²: the shapes are compared at equal area or equal circumradius.
    fn area_per_r2(self) -> f64 {
        match self {
            LightShape::Polygon(n) => 0.5 * n as f64 * (2.0 * PI / n as f64).sin(),
            LightShape::Disk => PI,
            LightShape::Quad => 2.0,
            LightShape::Triangle => 0.75 * 3f64.sqrt(),
        }
    }

    /// The shape for a value of the sides slider (3…64, then the disk).
    pub fn from_slider(v: u32) -> LightShape {
        if v >= DISK_STOP {
            LightShape::Disk
        } else {
            LightShape::Polygon(v.clamp(3, MAX_SIDES))
        }
    }

    /// The sides slider's value for this shape.
    pub fn slider_value(self) -> u32 {
        match self {
            LightShape::Polygon(n) => n,
            LightShape::Disk => DISK_STOP,
            LightShape::Quad => 4,
            LightShape::Triangle => 3,
        }
    }
}

/// What a shape or size change keeps.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Keep {
    /// Shape changes keep the area (and so, with the same radiance, the power); size changes
    /// change both.
    #[default]
    Area,
    /// Shape changes keep the circumradius and size changes the area, and the radiance is
    /// rescaled so that the emitted power stays the same.
    Power,
}

/// A planar light reduced to what reshaping keeps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanarLight {
    /// Area centroid.
    pub centre: DVec3,
    /// Unit normal (the emitting side).
    pub normal: DVec3,
    /// Unit in-plane axis: the first vertex lies along it.
    pub axis: DVec3,
    /// The shape.
    pub shape: LightShape,
    /// Area.
    pub area: f64,
}

impl PlanarLight {
    /// The planar light of a shape, or `None` for spheres, boxes and meshes of several
    /// triangles.
    pub fn from_geometry(g: &GeometryDesc) -> Option<PlanarLight> {
        match g {
            GeometryDesc::Quad {
                corner,
                edge_u,
                edge_v,
            } => {
                let n = edge_u.cross(*edge_v);
                Some(PlanarLight {
                    centre: *corner + 0.5 * (*edge_u + *edge_v),
                    normal: n.normalize(),
                    axis: edge_u.normalize(),
                    shape: LightShape::Quad,
                    area: n.length(),
                })
            }
            GeometryDesc::Polygon { vertices } => {
                let shape = LightShape::Polygon((vertices.len() as u32).clamp(3, MAX_SIDES));
                Some(from_vertices(vertices, shape))
            }
            GeometryDesc::Triangles { positions, indices } if indices.len() == 1 => {
                let v = indices[0].map(|i| positions[i as usize]);
                Some(from_vertices(&v, LightShape::Triangle))
            }
            GeometryDesc::Disk {
                center,
                normal,
                radius,
                ..
            } => Some(PlanarLight {
                centre: *center,
                normal: *normal,
                axis: normal.any_orthonormal_vector(),
                shape: LightShape::Disk,
                area: PI * radius * radius,
            }),
            _ => None,
        }
    }

    /// Distance from the centre to the outermost points.
    pub fn circumradius(&self) -> f64 {
        (self.area / self.shape.area_per_r2()).sqrt()
    }

    /// This light with another shape, and the factor the radiance must be multiplied by.
    pub fn reshaped(&self, shape: LightShape, keep: Keep) -> (PlanarLight, f64) {
        match keep {
            Keep::Area => (PlanarLight { shape, ..*self }, 1.0),
            Keep::Power => {
                let r = self.circumradius();
                let area = shape.area_per_r2() * r * r;
                (
                    PlanarLight {
                        shape,
                        area,
                        ..*self
                    },
                    self.area / area,
                )
            }
        }
    }

    /// This light with another area, and the factor the radiance must be multiplied by.
    pub fn resized(&self, area: f64, keep: Keep) -> (PlanarLight, f64) {
        let scale = match keep {
            Keep::Area => 1.0,
            Keep::Power => self.area / area,
        };
        (PlanarLight { area, ..*self }, scale)
    }

    /// The shape's description: vertices counter-clockwise about the normal, so that the
    /// right-hand rule gives the same emitting side.
    pub fn geometry(&self) -> GeometryDesc {
        let r = self.circumradius();
        let u = self.axis;
        let v = self.normal.cross(u);
        let ring = |n: u32| -> Vec<DVec3> {
            (0..n)
                .map(|k| {
                    let t = 2.0 * PI * k as f64 / n as f64;
                    self.centre + r * (t.cos() * u + t.sin() * v)
                })
                .collect()
        };
        match self.shape {
            LightShape::Polygon(n) => GeometryDesc::Polygon { vertices: ring(n) },
            // The default texture frame (`LightEdit::apply` keeps a disk's own).
            LightShape::Disk => GeometryDesc::Disk {
                center: self.centre,
                normal: self.normal,
                radius: r,
                u_axis: None,
            },
            LightShape::Quad => {
                let s = self.area.sqrt();
                GeometryDesc::Quad {
                    corner: self.centre - 0.5 * s * (u + v),
                    edge_u: s * u,
                    edge_v: s * v,
                }
            }
            LightShape::Triangle => GeometryDesc::Triangles {
                positions: ring(3),
                indices: vec![[0, 1, 2]],
            },
        }
    }
}

/// Centroid, normal, axis and area of a planar polygon (concave ones too: the signed fan areas
/// of the Newell construction).
fn from_vertices(v: &[DVec3], shape: LightShape) -> PlanarLight {
    let nn = newell_normal(v);
    let normal = nn.normalize();
    let (mut weighted, mut total) = (DVec3::ZERO, 0.0);
    for i in 1..v.len() - 1 {
        let a = 0.5 * (v[i] - v[0]).cross(v[i + 1] - v[0]).dot(normal);
        weighted += a * (v[0] + v[i] + v[i + 1]) / 3.0;
        total += a;
    }
    let centre = weighted / total;
    let d = v[0] - centre;
    PlanarLight {
        centre,
        normal,
        axis: (d - d.dot(normal) * normal).normalize(),
        shape,
        area: 0.5 * nn.length(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hexagon() -> GeometryDesc {
        let ring: Vec<DVec3> = (0..6)
            .map(|k| {
                let t = k as f64 * PI / 3.0;
                DVec3::new(1.0 + t.cos(), 2.0, 3.0 + t.sin())
            })
            .collect();
        // x → z is counter-clockwise about x × z = −y (right-hand rule): a ceiling light.
        GeometryDesc::Polygon { vertices: ring }
    }

    #[test]
    fn every_shape_keeps_centre_orientation_and_area() {
        let base = PlanarLight::from_geometry(&hexagon()).unwrap();
        assert!((base.normal - DVec3::NEG_Y).length() < 1e-12);
        assert!((base.centre - DVec3::new(1.0, 2.0, 3.0)).length() < 1e-12);
        let shapes = (3..=MAX_SIDES).map(LightShape::Polygon).chain([
            LightShape::Disk,
            LightShape::Quad,
            LightShape::Triangle,
        ]);
        for shape in shapes {
            let (l, s) = base.reshaped(shape, Keep::Area);
            assert_eq!(s, 1.0);
            let back = PlanarLight::from_geometry(&l.geometry()).unwrap();
            assert!((back.centre - base.centre).length() < 1e-9, "{shape:?}");
            assert!((back.normal - base.normal).length() < 1e-9, "{shape:?}");
            assert!((back.area - base.area).abs() < 1e-9, "{shape:?}");
        }
    }

    #[test]
    fn keeping_power_scales_radiance_by_the_area_ratio() {
        let base = PlanarLight::from_geometry(&hexagon()).unwrap();
        let (disk, s) = base.reshaped(LightShape::Disk, Keep::Power);
        assert!((disk.circumradius() - base.circumradius()).abs() < 1e-12);
        assert!(
            (disk.area * s - base.area).abs() < 1e-9,
            "power = area × radiance"
        );
        let (big, s) = base.resized(4.0 * base.area, Keep::Power);
        assert!((big.area * s - base.area).abs() < 1e-9);
        assert_eq!(base.resized(2.0, Keep::Area).1, 1.0);
    }
}
