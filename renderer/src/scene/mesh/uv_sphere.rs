//! A generated test mesh: a UV sphere of at least a given number of triangles, with vertex normals
//! and texture coordinates, optionally bumped. The `make_mesh` example writes it to a file; the
//! scale test (`renderer/tests/mesh_scale.rs`) makes its 1M-triangle PLY with it at test time, so no large
//! mesh is committed.
//!
//! The sphere has `s` stacks and `2s` segments, `s` the smallest with `4s(s − 1) ≥ N` triangles
//! (`(s + 1)(2s + 1)` vertices: the seam and the poles are repeated so that the texture
//! coordinates are continuous): vertex `(i, j)` is at polar angle `θ = πi/s` from +y and azimuth
//! `φ = 2πj/(2s)`, direction `d = (sin θ cos φ, cos θ, −sin θ sin φ)`, texture coordinates
//! `(j/2s, 1 − i/s)`. Triangles wind counter-clockwise seen from outside (the right-hand rule
//! gives the outward normal); the degenerate halves of the quads at the poles are left out.
//!
//! `bumps = A` (0 ≤ A < 1) displaces the radius to `r = 1 + A·sin(kx)·sin(ky)·sin(kz)`
//! (`k` = `frequency`) and gives the exact normals of that surface, `normalize(d − ∇ₛr / r)`;
//! with `A = 0` it is the unit sphere with normals `d`. There is no randomness: the mesh is a
//! function of the parameters.

use super::MeshData;
use glam::{DVec3, Vec2};
use std::f64::consts::PI;

/// The parameters of a generated sphere (see the module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UvSphere {
    /// Least number of triangles.
    pub triangles: usize,
    /// Relative amplitude `A` of the bumps, in `[0, 1)`.
    pub bumps: f64,
    /// Spatial frequency `k` of the bumps.
    pub frequency: f64,
    /// Whether the mesh has vertex normals.
    pub normals: bool,
    /// Whether the mesh has texture coordinates.
    pub uvs: bool,
}

impl UvSphere {
    /// A smooth unit sphere of at least `triangles` triangles, with normals and UVs.
    pub fn new(triangles: usize) -> UvSphere {
        UvSphere {
            triangles,
            bumps: 0.0,
            frequency: 8.0,
            normals: true,
            uvs: true,
        }
    }

    /// The smallest stack count giving at least `self.triangles` triangles.
    pub fn stacks(&self) -> usize {
        let mut s = 2;
        while 4 * s * (s - 1) < self.triangles {
            s += 1;
        }
        s
    }

    /// The number of triangles [`UvSphere::mesh`] makes: `4s(s − 1)`.
    pub fn triangle_count(&self) -> usize {
        let s = self.stacks();
        4 * s * (s - 1)
    }

    /// The mesh (see the module doc).
    pub fn mesh(&self) -> MeshData {
        let s = self.stacks();
        let segments = 2 * s;
        let columns = segments + 1;
        let vertices = (s + 1) * columns;
        let mut positions = Vec::with_capacity(vertices);
        let mut normals = Vec::with_capacity(if self.normals { vertices } else { 0 });
        let mut uvs = Vec::with_capacity(if self.uvs { vertices } else { 0 });
        let azimuth: Vec<(f64, f64)> = (0..columns)
            .map(|j| (2.0 * PI * j as f64 / segments as f64).sin_cos())
            .collect();
        for i in 0..=s {
            let (sin_t, cos_t) = (PI * i as f64 / s as f64).sin_cos();
            for (j, &(sin_p, cos_p)) in azimuth.iter().enumerate() {
                let d = DVec3::new(sin_t * cos_p, cos_t, -sin_t * sin_p);
                let (p, n) = self.displaced(d);
                positions.push(p.as_vec3());
                if self.normals {
                    normals.push(n.as_vec3());
                }
                if self.uvs {
                    uvs.push(Vec2::new(
                        j as f32 / segments as f32,
                        1.0 - i as f32 / s as f32,
                    ));
                }
            }
        }
        let mut indices = Vec::with_capacity(self.triangle_count());
        let at = |i: usize, j: usize| (i * columns + j) as u32;
        for i in 0..s {
            for j in 0..segments {
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                if i + 1 < s {
                    indices.push([a, b, c]);
                }
                if i > 0 {
                    indices.push([a, c, d]);
                }
            }
        }
        MeshData {
            positions,
            indices,
            normals: self.normals.then_some(normals),
            uvs: self.uvs.then_some(uvs),
            attributes: Vec::new(),
        }
    }

    /// The point of the surface in direction `d` (unit) and its unit normal.
    fn displaced(&self, d: DVec3) -> (DVec3, DVec3) {
        if self.bumps == 0.0 {
            return (d, d);
        }
        let k = self.frequency;
        let (s, c) = (
            DVec3::new((k * d.x).sin(), (k * d.y).sin(), (k * d.z).sin()),
            DVec3::new((k * d.x).cos(), (k * d.y).cos(), (k * d.z).cos()),
        );
        let r = 1.0 + self.bumps * s.x * s.y * s.z;
        let grad = self.bumps * k * DVec3::new(c.x * s.y * s.z, s.x * c.y * s.z, s.x * s.y * c.z);
        // Only the part of the gradient along the sphere tilts the surface.
        let tangential = grad - grad.dot(d) * d;
        (r * d, (d - tangential / r).normalize())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_winding_and_normals() {
        let sphere = UvSphere {
            bumps: 0.1,
            ..UvSphere::new(1000)
        };
        let mesh = sphere.mesh();
        let s = sphere.stacks();
        assert!(4 * s * (s - 1) >= 1000 && 4 * (s - 1) * (s - 2) < 1000);
        assert_eq!(mesh.indices.len(), sphere.triangle_count());
        assert_eq!(mesh.positions.len(), (s + 1) * (2 * s + 1));
        let normals = mesh.normals.as_ref().unwrap();
        for t in &mesh.indices {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
            let n = (b - a).cross(c - a);
            // Outward winding, and the vertex normals on the same side as the face's.
            assert!(n.dot(a + b + c) > 0.0, "{t:?}");
            assert!(t.iter().all(|&i| normals[i as usize].dot(n) > 0.0), "{t:?}");
        }
    }
}
