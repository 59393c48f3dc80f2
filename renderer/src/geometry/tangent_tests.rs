//! Tests of `tangent.rs`: ∂p/∂u moves along +u and keeps v (checked from the definition, not the
//! formula), the frame's orthonormality and first axis, and the fallbacks.

use super::*;
use crate::geometry::disk::Disk;
use crate::geometry::mesh_attributes::{AttrMesh, AttrTriangle, HAS_UVS};
use crate::geometry::primitive::NONE;
use crate::geometry::sphere::Sphere;
use crate::rng::Rng;
use glam::{Vec2, Vec3};

fn hit(p: Vec3, n: Vec3) -> SurfaceHit {
    SurfaceHit {
        t: 1.0,
        p,
        p_error: Vec3::ZERO,
        n,
        prim: 0,
        b: Vec2::ZERO,
    }
}

fn prim(shape: Shape, attr: u32) -> Primitive {
    Primitive {
        shape,
        material: 0,
        light: NONE,
        attr,
    }
}

/// The attributes of one triangle (`attr` 0) with texture coordinates `uvs`.
fn one_triangle(uvs: [Vec2; 3]) -> MeshAttributes {
    MeshAttributes {
        normals: Vec::new(),
        uvs: uvs.to_vec(),
        meshes: vec![AttrMesh {
            normal_base: 0,
            uv_base: 0,
            flags: HAS_UVS,
            named: NONE,
        }],
        triangles: vec![AttrTriangle {
            v: [0, 1, 2],
            mesh: 0,
        }],
        ..MeshAttributes::default()
    }
}

/// The move of p on triangle `v` under the barycentric step (db1, db2) that moves its texture
/// coordinates `uvs` by `duv`: the definition of ∂p/∂u (`duv` = (1, 0)) and ∂p/∂v ((0, 1));
/// `None` where the UV map is nearly degenerate.
fn p_step(v: [Vec3; 3], uvs: [Vec2; 3], duv: Vec2) -> Option<Vec3> {
    let m = glam::Mat2::from_cols(uvs[1] - uvs[0], uvs[2] - uvs[0]);
    if m.determinant().abs() < 1e-3 {
        return None;
    }
    let db = m.inverse() * duv;
    Some(db.x * (v[1] - v[0]) + db.y * (v[2] - v[0]))
}

#[test]
fn a_triangles_dp_du_moves_along_u_only() {
    let mut r = Rng::new(3, 0, 0);
    let mut rv = || Vec3::new(r.next_f32(), r.next_f32(), r.next_f32()) * 2.0 - 1.0;
    for _ in 0..200 {
        let v = [rv(), rv(), rv()];
        let uvs = [rv().truncate(), rv().truncate(), rv().truncate()];
        let attrs = one_triangle(uvs);
        let Some(shape) = Shape::triangle(v) else {
            continue;
        };
        let n = match shape {
            Shape::Triangle { n, .. } => n,
            _ => unreachable!(),
        };
        let d = dp_du(&prim(shape, 0), &attrs, &hit(v[0], n));
        let Some(want) = p_step(v, uvs, Vec2::X) else {
            continue;
        };
        assert!(
            (d - want).length() <= 1e-3 * want.length().max(1.0),
            "{d} vs {want}"
        );
        // Without UVs: the first edge.
        let none = dp_du(&prim(shape, NONE), &attrs, &hit(v[0], n));
        assert_eq!(none, v[1] - v[0]);
    }
}

/// Both partials from the definition: the barycentric step that moves the UVs by (0, 1) moves
/// p by ∂p/∂v; ∂p/∂u is `dp_du`'s bit for bit; without UVs the two edges; analytic shapes none.
#[test]
fn a_triangles_dp_dv_moves_along_v_only() {
    let mut r = Rng::new(4, 0, 0);
    let mut rv = || Vec3::new(r.next_f32(), r.next_f32(), r.next_f32()) * 2.0 - 1.0;
    let mut checked = 0;
    for _ in 0..200 {
        let v = [rv(), rv(), rv()];
        let uvs = [rv().truncate(), rv().truncate(), rv().truncate()];
        let attrs = one_triangle(uvs);
        let Some(shape) = Shape::triangle(v) else {
            continue;
        };
        let Shape::Triangle { n, .. } = shape else {
            unreachable!()
        };
        let h = hit(v[0], n);
        let (du, dv) = dp_duv(&prim(shape, 0), &attrs, &h).unwrap();
        assert_eq!(du, dp_du(&prim(shape, 0), &attrs, &h));
        let Some(want) = p_step(v, uvs, Vec2::Y) else {
            continue;
        };
        assert!(
            (dv - want).length() <= 1e-3 * want.length().max(1.0),
            "{dv} vs {want}"
        );
        checked += 1;
        let none = dp_duv(&prim(shape, NONE), &attrs, &h).unwrap();
        assert_eq!(none, (v[1] - v[0], v[2] - v[0]));
    }
    assert!(checked > 100, "{checked}");
    let sphere = Shape::Sphere(Sphere::new(Vec3::ZERO, 1.0));
    assert_eq!(
        dp_duv(
            &prim(sphere, NONE),
            &one_triangle([Vec2::ZERO; 3]),
            &hit(Vec3::Z, Vec3::Z)
        ),
        None
    );
}

#[test]
fn a_degenerate_uv_map_falls_back_to_the_normals_frame() {
    let v = [Vec3::ZERO, Vec3::X, Vec3::Y];
    let attrs = one_triangle([Vec2::ZERO, Vec2::ONE, Vec2::splat(2.0)]);
    let shape = Shape::triangle(v).unwrap();
    let d = dp_du(&prim(shape, 0), &attrs, &hit(Vec3::ZERO, Vec3::Z));
    assert_eq!(d, Frame::from_normal(Vec3::Z).s);
}

#[test]
fn spheres_turn_about_z_and_disks_point_outward() {
    let s = Sphere::new(Vec3::new(1.0, 2.0, 3.0), 2.0);
    let p = s.center + Vec3::new(1.2, -1.6, 0.0);
    let d = dp_du(
        &prim(Shape::Sphere(s), NONE),
        &MeshAttributes::default(),
        &hit(p, Vec3::Z),
    );
    assert!(d.dot(p - s.center).abs() < 1e-6 && d.z == 0.0 && d.length() > 1.0);
    // Counter-clockwise seen from +z, as Mitsuba's φ grows.
    assert!((p - s.center).cross(d).z > 0.0);
    let disk = Disk::new(Vec3::ZERO, Vec3::Y, 1.0);
    let q = Vec3::new(0.3, 0.0, -0.4);
    let d = dp_du(
        &prim(Shape::Disk(disk), NONE),
        &MeshAttributes::default(),
        &hit(q, Vec3::Y),
    );
    assert_eq!(d, q);
    // A sphere whose pole is turned to +x (Mitsuba's `to_world` rotation): about +x.
    let turned = Sphere {
        pole: Vec3::X,
        u_axis: Vec3::Y,
        ..s
    };
    let p = s.center + Vec3::new(0.5, 1.2, -1.6);
    let d = dp_du(
        &prim(Shape::Sphere(turned), NONE),
        &MeshAttributes::default(),
        &hit(p, (p - s.center).normalize()),
    );
    assert!(d.x == 0.0 && d.dot(p - s.center).abs() < 1e-6 && d.length() > 1.0);
    assert!((p - s.center).cross(d).x > 0.0);
}

#[test]
fn the_tangent_frame_is_orthonormal_along_the_projected_tangent() {
    let mut r = Rng::new(4, 0, 0);
    for _ in 0..1000 {
        let n = crate::sampling::sphere::sample_uniform_sphere(r.next_2d());
        let t = Vec3::new(r.next_f32(), r.next_f32(), r.next_f32()) * 2.0 - 1.0;
        let f = tangent_frame(n, t);
        for (a, b) in [(f.s, f.t), (f.t, f.n), (f.s, f.n)] {
            assert!(a.dot(b).abs() < 1e-5);
        }
        for a in [f.s, f.t] {
            assert!((a.length() - 1.0).abs() < 1e-5);
        }
        assert!(f.n == n && f.s.dot(t) >= 0.0 && f.s.cross(t - n * n.dot(t)).length() < 1e-4);
    }
    // Nothing left after projection: the frame of the normal.
    let n = Vec3::new(0.0, 0.6, 0.8);
    for t in [Vec3::ZERO, n * 3.0] {
        let f = tangent_frame(n, t);
        let g = Frame::from_normal(n);
        assert_eq!((f.s, f.t, f.n), (g.s, g.t, g.n));
    }
}
