//! Vertex normals for a mesh file that has none, as Mitsuba 3.9.1 computes them
//! (`Mesh::recompute_vertex_normals`, after Thürmer and Wüthrich, "Computing Vertex Normals from
//! Polygonal Facets", JGT 1998): each triangle's unit normal, weighted by the triangle's angle
//! at the vertex, summed and normalised. Angle weights make the normal independent of how a
//! face is split into triangles (a cube's corner gets (1, 1, 1)/√3 whatever its diagonals).
//! Mitsuba computes them after `to_world`, so the callers pass world positions. Mitsuba works
//! in single precision, lumis in double: the normals agree to about 1e-7.

use glam::DVec3;

/// The normals of `positions` (world space) for `triangles`, and the number of vertices no
/// triangle of positive area touches: those get Mitsuba's placeholder (1, 0, 0).
pub fn angle_weighted(positions: &[DVec3], triangles: &[[u32; 3]]) -> (Vec<DVec3>, usize) {
    let mut sums = vec![DVec3::ZERO; positions.len()];
    for tri in triangles {
        let v = tri.map(|i| positions[i as usize]);
        let Some(n) = (v[1] - v[0]).cross(v[2] - v[0]).try_normalize() else {
            continue;
        };
        for k in 0..3 {
            let (a, b) = (v[(k + 1) % 3] - v[k], v[(k + 2) % 3] - v[k]);
            // atan2 of |a×b| and a·b: the angle, accurate also near 0 and π (Mitsuba's
            // `unit_angle` is its equivalent for unit vectors).
            let angle = a.cross(b).length().atan2(a.dot(b));
            sums[tri[k] as usize] += n * angle;
        }
    }
    let mut invalid = 0;
    let normals = sums
        .into_iter()
        .map(|s| {
            s.try_normalize().unwrap_or_else(|| {
                invalid += 1;
                DVec3::X
            })
        })
        .collect();
    (normals, invalid)
}

#[cfg(test)]
mod tests {
    use super::angle_weighted;
    use glam::DVec3;

    /// A unit cube's corner at the origin, its three faces split along either diagonal in two
    /// mixed ways (one face with two triangles at the corner, two faces with one, and the other
    /// way round): angle weights give the corner (1, 1, 1)/√3 for both; plain or area weights
    /// would tilt it towards the face with two triangles.
    #[test]
    fn a_cube_corner_is_the_diagonal_whatever_the_split() {
        let p = |x, y, z| DVec3::new(x, y, z);
        let positions = vec![
            p(0., 0., 0.),
            p(1., 0., 0.),
            p(0., 1., 0.),
            p(0., 0., 1.),
            p(1., 1., 0.),
            p(0., 1., 1.),
            p(1., 0., 1.),
        ];
        // Faces z = 0, x = 0 and y = 0 (outward normals −z, −x, −y), each split through the
        // corner (two triangles there) or across it (one).
        let z_through = [[0, 2, 4], [0, 4, 1]];
        let z_across = [[0, 2, 1], [1, 2, 4]];
        let x_through = [[0, 3, 5], [0, 5, 2]];
        let x_across = [[0, 3, 2], [2, 3, 5]];
        let y_through = [[0, 1, 6], [0, 6, 3]];
        let y_across = [[0, 1, 3], [1, 6, 3]];
        let splits = [
            [z_through, x_across, y_across].concat(),
            [z_across, x_through, y_through].concat(),
        ];
        for tris in &splits {
            let (n, invalid) = angle_weighted(&positions, tris);
            assert!(
                (n[0] + DVec3::ONE / 3f64.sqrt()).length() < 1e-12,
                "{}",
                n[0]
            );
            assert_eq!(invalid, 0);
        }
    }

    #[test]
    fn coplanar_triangles_keep_the_face_normal_and_lonely_vertices_get_x() {
        let positions = vec![
            DVec3::new(0., 0., 2.),
            DVec3::new(3., 0., 2.),
            DVec3::new(3., 1., 2.),
            DVec3::new(0., 1., 2.),
            DVec3::new(9., 9., 9.),
        ];
        let (n, invalid) = angle_weighted(&positions, &[[0, 1, 2], [0, 2, 3], [4, 4, 4]]);
        for v in &n[..4] {
            assert!((*v - DVec3::Z).length() < 1e-15, "{v}");
        }
        assert_eq!((n[4], invalid), (DVec3::X, 1));
    }
}
