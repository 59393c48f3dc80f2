//! Vertex attributes of mesh triangles: shading normals and texture coordinates, stored once per
//! vertex (as the file has them, normals already in world space) and found from a hit's
//! barycentrics, and the named vertex and face attributes that `mesh_attribute` textures read
//! ([`MeshAttributes::named`]). Triangles without attributes (the JSON shapes, `face_normals`
//! meshes without UVs) have none stored and cost nothing.
//!
//! Conventions (Mitsuba 3's, so that references agree):
//! - **UVs** follow the image-row convention of textures (`v = 0` is the top row): glTF and PLY
//!   coordinates as stored, OBJ's `v` flipped at load. A triangle without UVs gets its
//!   barycentrics `(b1, b2)`.
//! - **Shading normals** are the interpolated vertex normals, normalised, turned to the geometric
//!   normal's side where a file's normals disagree with its winding (the geometric normal, from
//!   the winding, is what the format defines as the outside). Where the interpolation vanishes
//!   or is not finite, the geometric normal is used.
//!
//! WGSL twin: `geometry/mesh_attributes.wgsl`.

use super::primitive::NONE;
use glam::{Vec2, Vec3};

/// Flag of [`AttrMesh::flags`]: the mesh has vertex normals.
pub const HAS_NORMALS: u32 = 1;
/// Flag of [`AttrMesh::flags`]: the mesh has texture coordinates.
pub const HAS_UVS: u32 = 2;

/// Where one mesh's vertex attributes start.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AttrMesh {
    /// Index of its vertex 0 in [`MeshAttributes::normals`] (if [`HAS_NORMALS`]).
    pub normal_base: u32,
    /// Index of its vertex 0 in [`MeshAttributes::uvs`] (if [`HAS_UVS`]).
    pub uv_base: u32,
    /// [`HAS_NORMALS`] | [`HAS_UVS`].
    pub flags: u32,
    /// Index of its entry for slot 0 in [`MeshAttributes::named_slots`] (one entry per slot
    /// follows), or [`NONE`] where the scene's textures read no named attribute.
    pub named: u32,
}

/// Where one mesh's values of one named attribute (a texture slot) start.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NamedSlot {
    /// Index of its vertex 0's or face 0's value in [`MeshAttributes::named_values`]; [`NONE`]
    /// where the mesh lacks the attribute.
    pub base: u32,
    /// The attribute record of the mesh's face 0: a mesh with named attributes has one record
    /// per face, in file order, so face `k`'s is `first_triangle + k`.
    pub first_triangle: u32,
    /// One value per face (`face_…`), not per vertex.
    pub per_face: bool,
}

/// One triangle's vertices in its mesh (16 bytes a triangle: the attributes themselves are
/// stored per vertex).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AttrTriangle {
    /// Its vertices' indices within the mesh.
    pub v: [u32; 3],
    /// Index into [`MeshAttributes::meshes`].
    pub mesh: u32,
}

/// The attributes of every triangle that has some; a primitive's `attr` indexes `triangles`.
#[derive(Clone, Debug, Default)]
pub struct MeshAttributes {
    /// Unit world-space vertex normals.
    pub normals: Vec<Vec3>,
    /// Vertex texture coordinates.
    pub uvs: Vec<Vec2>,
    /// Per mesh with attributes.
    pub meshes: Vec<AttrMesh>,
    /// Per attributed triangle.
    pub triangles: Vec<AttrTriangle>,
    /// Per mesh with named attributes, one entry per slot.
    pub named_slots: Vec<NamedSlot>,
    /// The named attributes' values (one component stored in all three).
    pub named_values: Vec<Vec3>,
}

impl MeshAttributes {
    /// True if no triangle has attributes.
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// True if some triangle has shading normals.
    pub fn has_normals(&self) -> bool {
        !self.normals.is_empty()
    }

    /// The shading normal at barycentrics `b = (b1, b2)` of triangle `attr` with geometric normal
    /// `ng`, or `None` where the triangle has no vertex normals (`attr` may be [`NONE`]).
    #[inline]
    pub fn shading_normal(&self, attr: u32, b: Vec2, ng: Vec3) -> Option<Vec3> {
        if attr == NONE {
            return None;
        }
        let tri = &self.triangles[attr as usize];
        let mesh = &self.meshes[tri.mesh as usize];
        if mesh.flags & HAS_NORMALS == 0 {
            return None;
        }
        let [n0, n1, n2] = tri.v.map(|i| self.normals[(mesh.normal_base + i) as usize]);
        Some(interpolate_normal([n0, n1, n2], b, ng))
    }

    /// The vertex texture coordinates of triangle `attr`, where it has UVs.
    #[inline]
    pub fn triangle_uvs(&self, attr: u32) -> Option<[Vec2; 3]> {
        if attr == NONE {
            return None;
        }
        let tri = &self.triangles[attr as usize];
        let mesh = &self.meshes[tri.mesh as usize];
        if mesh.flags & HAS_UVS == 0 {
            return None;
        }
        Some(tri.v.map(|i| self.uvs[(mesh.uv_base + i) as usize]))
    }

    /// The value of named attribute `slot` at barycentrics `b = (b1, b2)` of triangle `attr`: a
    /// vertex attribute interpolated as Mitsuba's `Mesh::eval_attribute`, a face attribute the
    /// face's; black where the triangle's mesh lacks it (or `attr` is [`NONE`]).
    #[inline]
    pub fn named(&self, slot: u32, attr: u32, b: Vec2) -> Vec3 {
        if attr == NONE {
            return Vec3::ZERO;
        }
        let tri = &self.triangles[attr as usize];
        let mesh = &self.meshes[tri.mesh as usize];
        if mesh.named == NONE {
            return Vec3::ZERO;
        }
        let s = &self.named_slots[(mesh.named + slot) as usize];
        if s.base == NONE {
            Vec3::ZERO
        } else if s.per_face {
            self.named_values[(s.base + attr - s.first_triangle) as usize]
        } else {
            let [v0, v1, v2] = tri.v.map(|i| self.named_values[(s.base + i) as usize]);
            (1.0 - b.x - b.y) * v0 + b.x * v1 + b.y * v2
        }
    }

    /// The texture coordinates at barycentrics `b = (b1, b2)` of triangle `attr`: interpolated
    /// where it has UVs, else `b` itself (also for `attr` = [`NONE`]).
    #[inline]
    pub fn uv(&self, attr: u32, b: Vec2) -> Vec2 {
        match self.triangle_uvs(attr) {
            Some([t0, t1, t2]) => (1.0 - b.x - b.y) * t0 + b.x * t1 + b.y * t2,
            None => b,
        }
    }
}

/// `normalize((1−b1−b2)·n0 + b1·n1 + b2·n2)`, turned to `ng`'s side; `ng` where that is not a
/// direction.
#[inline]
pub fn interpolate_normal(n: [Vec3; 3], b: Vec2, ng: Vec3) -> Vec3 {
    let sum = (1.0 - b.x - b.y) * n[0] + b.x * n[1] + b.y * n[2];
    let len2 = sum.length_squared();
    if !(len2 > 1e-20 && len2.is_finite()) {
        return ng;
    }
    let ns = sum / len2.sqrt();
    if ns.dot(ng) < 0.0 { -ns } else { ns }
}

/// The world-space normal transform of an affine `to_world`: the inverse transpose of its linear
/// part (normals stay perpendicular to surfaces under non-uniform scaling).
pub fn normal_matrix(to_world: glam::DMat4) -> glam::DMat3 {
    glam::DMat3::from_mat4(to_world).inverse().transpose()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn one_triangle(normals: Option<[Vec3; 3]>, uvs: Option<[Vec2; 3]>) -> MeshAttributes {
        let mut a = MeshAttributes::default();
        let mut flags = 0;
        if let Some(n) = normals {
            a.normals.extend(n.map(Vec3::normalize));
            flags |= HAS_NORMALS;
        }
        if let Some(t) = uvs {
            a.uvs.extend(t);
            flags |= HAS_UVS;
        }
        a.meshes.push(AttrMesh {
            normal_base: 0,
            uv_base: 0,
            flags,
            named: NONE,
        });
        a.triangles.push(AttrTriangle {
            v: [0, 1, 2],
            mesh: 0,
        });
        a
    }

    #[test]
    fn normals_interpolate_with_the_hit_barycentrics() {
        let a = one_triangle(Some([Vec3::X, Vec3::Y, Vec3::Z]), None);
        let ng = Vec3::ONE.normalize();
        // At each vertex its own normal, at the centroid their normalised mean.
        assert_eq!(a.shading_normal(0, Vec2::ZERO, ng), Some(Vec3::X));
        assert_eq!(a.shading_normal(0, Vec2::X, ng), Some(Vec3::Y));
        assert_eq!(a.shading_normal(0, Vec2::Y, ng), Some(Vec3::Z));
        let c = a.shading_normal(0, Vec2::splat(1.0 / 3.0), ng).unwrap();
        assert!((c - ng).length() < 1e-6);
        // No normals: none; no attributes at all: none.
        assert_eq!(
            one_triangle(None, None).shading_normal(0, Vec2::X, ng),
            None
        );
        assert_eq!(a.shading_normal(NONE, Vec2::X, ng), None);
    }

    #[test]
    fn shading_normals_turn_to_the_geometric_side_and_fall_back_to_it() {
        let a = one_triangle(Some([-Vec3::Z, -Vec3::Z, -Vec3::Z]), None);
        assert_eq!(a.shading_normal(0, Vec2::X, Vec3::Z), Some(Vec3::Z));
        // Opposite normals cancel at the midpoint: the geometric normal.
        let n = [Vec3::X, -Vec3::X, Vec3::X];
        assert_eq!(interpolate_normal(n, Vec2::new(0.5, 0.0), Vec3::Z), Vec3::Z);
        let nan = [Vec3::NAN, Vec3::X, Vec3::X];
        assert_eq!(
            interpolate_normal(nan, Vec2::new(0.5, 0.0), Vec3::Z),
            Vec3::Z
        );
    }

    #[test]
    fn uvs_interpolate_or_are_the_barycentrics() {
        let t = [
            Vec2::new(0.0, 1.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(0.5, 0.0),
        ];
        let a = one_triangle(None, Some(t));
        assert_eq!(a.uv(0, Vec2::ZERO), t[0]);
        assert_eq!(a.uv(0, Vec2::X), t[1]);
        assert_eq!(a.uv(0, Vec2::Y), t[2]);
        let b = Vec2::new(0.25, 0.5);
        assert!((a.uv(0, b) - (0.25 * t[0] + 0.25 * t[1] + 0.5 * t[2])).length() < 1e-7);
        assert_eq!(one_triangle(Some([Vec3::Z; 3]), None).uv(0, b), b);
        assert_eq!(a.uv(NONE, b), b);
    }

    #[test]
    fn named_attributes_interpolate_per_vertex_and_are_constant_per_face() {
        let mut a = one_triangle(None, None);
        // Slot 0: a vertex attribute; slot 1: a face attribute; slot 2: missing.
        a.named_values = vec![Vec3::X, Vec3::Y, Vec3::Z, Vec3::new(0.1, 0.2, 0.3)];
        a.meshes[0].named = 0;
        a.named_slots = vec![
            NamedSlot {
                base: 0,
                first_triangle: 0,
                per_face: false,
            },
            NamedSlot {
                base: 3,
                first_triangle: 0,
                per_face: true,
            },
            NamedSlot {
                base: NONE,
                first_triangle: 0,
                per_face: false,
            },
        ];
        let b = Vec2::new(0.25, 0.5);
        assert_eq!(a.named(0, 0, Vec2::ZERO), Vec3::X);
        assert_eq!(a.named(0, 0, Vec2::X), Vec3::Y);
        assert_eq!(a.named(0, 0, Vec2::Y), Vec3::Z);
        assert!((a.named(0, 0, b) - Vec3::new(0.25, 0.25, 0.5)).length() < 1e-7);
        assert_eq!(a.named(1, 0, b), Vec3::new(0.1, 0.2, 0.3));
        assert_eq!(a.named(2, 0, b), Vec3::ZERO);
        assert_eq!(a.named(0, NONE, b), Vec3::ZERO);
        // A second face of the mesh reads the next face value.
        a.triangles.push(AttrTriangle {
            v: [2, 1, 0],
            mesh: 0,
        });
        a.named_values.push(Vec3::ONE);
        assert_eq!(a.named(1, 1, b), Vec3::ONE);
        assert_eq!(a.named(0, 1, Vec2::ZERO), Vec3::Z);
    }

    #[test]
    fn normal_matrix_keeps_normals_perpendicular_under_non_uniform_scale() {
        let m = glam::DMat4::from_scale_rotation_translation(
            glam::DVec3::new(1.0, 4.0, 0.5),
            glam::DQuat::from_rotation_x(0.3),
            glam::DVec3::new(1.0, 2.0, 3.0),
        );
        let tangent = glam::DVec3::new(1.0, 1.0, 0.0);
        let normal = glam::DVec3::new(1.0, -1.0, 0.0);
        let t = m.transform_vector3(tangent);
        let n = normal_matrix(m) * normal;
        assert!(t.dot(n).abs() < 1e-12 * t.length() * n.length());
        assert!(
            (m.transform_vector3(normal)).dot(t).abs() > 0.1,
            "the plain matrix would fail"
        );
    }
}
