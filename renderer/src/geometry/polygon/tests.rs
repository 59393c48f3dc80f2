//! Tests of polygon validation and triangulation.

use super::*;

fn xy(points: &[(f64, f64)]) -> Vec<DVec3> {
    points.iter().map(|&(x, y)| DVec3::new(x, y, 0.0)).collect()
}

/// Places 2D points on a tilted plane at `offset`, scaled by `scale`.
fn tilted(points: &[(f64, f64)], scale: f64, offset: DVec3) -> Vec<DVec3> {
    let u = DVec3::new(1.0, 2.0, 2.0) / 3.0;
    let w = DVec3::new(2.0, 1.0, -2.0) / 3.0;
    points
        .iter()
        .map(|&(x, y)| offset + (u * x + w * y) * scale)
        .collect()
}

fn area(v: &[DVec3]) -> f64 {
    newell_normal(v).length() / 2.0
}

/// Triangulates, then checks count, area sum, winding and index validity.
fn check_triangulation(v: &[DVec3]) {
    let normal = validate_polygon(v).expect("valid polygon");
    let tris = triangulate(v);
    assert!(tris.len() <= v.len() - 2, "{} triangles", tris.len());
    let mut sum = 0.0;
    for t in &tris {
        assert!(t.iter().all(|&i| i < v.len()));
        let n = (v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]);
        assert!(n.length() > 0.0, "degenerate triangle {t:?}");
        assert!(
            n.normalize().dot(normal) > 1.0 - 1e-9,
            "triangle {t:?} flipped"
        );
        sum += n.length() / 2.0;
    }
    let expected = area(v);
    assert!(
        (sum - expected).abs() <= 1e-9 * expected,
        "{sum} vs {expected}"
    );
}

const L_SHAPE: [(f64, f64); 6] = [(0., 0.), (2., 0.), (2., 1.), (1., 1.), (1., 2.), (0., 2.)];
const COMB: [(f64, f64); 10] = [
    (0., 0.),
    (5., 0.),
    (5., 3.),
    (4., 3.),
    (4., 1.),
    (3., 1.),
    (3., 3.),
    (2., 3.),
    (2., 1.),
    (0., 1.),
];

fn star(points: usize) -> Vec<(f64, f64)> {
    (0..2 * points)
        .map(|i| {
            let r = if i % 2 == 0 { 1.0 } else { 0.4 };
            let a = std::f64::consts::PI * i as f64 / points as f64;
            (r * a.cos(), r * a.sin())
        })
        .collect()
}

#[test]
fn newell_length_is_twice_area() {
    let square = xy(&[(0., 0.), (2., 0.), (2., 2.), (0., 2.)]);
    assert_eq!(newell_normal(&square), DVec3::new(0.0, 0.0, 8.0));
    let reversed: Vec<_> = square.iter().rev().copied().collect();
    assert_eq!(newell_normal(&reversed), DVec3::new(0.0, 0.0, -8.0));
}

#[test]
fn convex_hexagon() {
    let hex: Vec<_> = (0..6)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / 6.0;
            (a.cos(), a.sin())
        })
        .collect();
    let v = tilted(&hex, 1.0, DVec3::new(0.3, 2.0, 0.2));
    check_triangulation(&v);
    assert!((area(&v) - 1.5 * 3f64.sqrt()).abs() < 1e-12);
}

#[test]
fn seed_cornell_hexagon_faces_down() {
    let v = [[400., 554., 250.], [400., 554., 350.], [300., 554., 400.]]
        .into_iter()
        .chain([[200., 554., 350.], [200., 554., 250.], [300., 554., 200.]])
        .map(DVec3::from)
        .collect::<Vec<_>>();
    assert_eq!(validate_polygon(&v), Ok(DVec3::new(0.0, -1.0, 0.0)));
    check_triangulation(&v);
}

#[test]
fn concave_shapes() {
    check_triangulation(&xy(&L_SHAPE));
    check_triangulation(&xy(&COMB));
    check_triangulation(&xy(&star(5)));
    check_triangulation(&tilted(&star(7), 3.0, DVec3::new(-4.0, 1.0, 9.0)));
}

#[test]
fn collinear_vertices() {
    // A square with extra points along two sides, and a triangle with a crowded base.
    check_triangulation(&xy(&[
        (0., 0.),
        (1., 0.),
        (2., 0.),
        (3., 0.),
        (3., 3.),
        (0., 3.),
    ]));
    let base: Vec<_> = (0..=8)
        .map(|i| (i as f64, 0.0))
        .chain([(4.0, 1.0)])
        .collect();
    check_triangulation(&xy(&base));
    // Concave with a collinear run passing a reflex vertex.
    check_triangulation(&xy(&[
        (0., 0.),
        (2., 0.),
        (2., 1.),
        (1., 1.),
        (1., 2.),
        (0., 2.),
        (0., 1.),
    ]));
}

#[test]
fn clockwise_and_counter_clockwise() {
    let ccw = xy(&L_SHAPE);
    let cw: Vec<_> = ccw.iter().rev().copied().collect();
    assert_eq!(validate_polygon(&ccw), Ok(DVec3::Z));
    assert_eq!(validate_polygon(&cw), Ok(-DVec3::Z));
    check_triangulation(&ccw);
    check_triangulation(&cw);
    let star_cw: Vec<_> = xy(&star(6)).into_iter().rev().collect();
    check_triangulation(&star_cw);
}

#[test]
fn large_and_tiny_coordinates() {
    for (scale, offset) in [(1e5, DVec3::splat(3e5)), (1e-3, DVec3::splat(2e-3))] {
        check_triangulation(&tilted(&COMB, scale, offset));
        check_triangulation(&tilted(&star(5), scale, offset));
        // The tolerance scales too: the same relative bend is rejected at both scales.
        let mut bent = tilted(&L_SHAPE, scale, offset);
        bent[3] += DVec3::new(2.0, -2.0, 1.0) / 3.0 * (1e-3 * scale);
        assert!(matches!(
            validate_polygon(&bent),
            Err(PolygonError::NonPlanar { .. })
        ));
        let mut slightly = tilted(&L_SHAPE, scale, offset);
        slightly[3] += DVec3::new(2.0, -2.0, 1.0) / 3.0 * (1e-6 * scale);
        assert!(validate_polygon(&slightly).is_ok());
    }
}

#[test]
fn random_star_shaped_polygons() {
    // Star-shaped around the origin with random radii: always simple, often very concave.
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for n in 3..60 {
        let points: Vec<_> = (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU * (i as f64 + 0.8 * next()) / n as f64;
                let r = 0.05 + next();
                (r * a.cos(), r * a.sin())
            })
            .collect();
        check_triangulation(&tilted(&points, 10.0, DVec3::new(1.0, -2.0, 3.0)));
    }
}

#[test]
fn rejects_non_planar() {
    let mut v = xy(&[(0., 0.), (1., 0.), (1., 1.), (0., 1.)]);
    v[2].z = 0.1;
    let Err(PolygonError::NonPlanar { max_distance }) = validate_polygon(&v) else {
        panic!("accepted a bent quad");
    };
    assert!(max_distance > 0.02 && max_distance < 0.1, "{max_distance}");
}

#[test]
fn rejects_self_intersection() {
    let bow_tie = xy(&[(0., 0.), (1., 1.), (1., 0.), (0., 1.)]);
    assert_eq!(
        validate_polygon(&bow_tie),
        Err(PolygonError::SelfIntersecting { edges: (0, 2) })
    );
    // Asymmetric bow-tie: non-zero signed area, still crossing.
    let skew = xy(&[(0., 0.), (2., 1.), (2., 0.), (0., 3.)]);
    assert!(matches!(
        validate_polygon(&skew),
        Err(PolygonError::SelfIntersecting { .. })
    ));
    // A vertex touching a non-adjacent edge.
    let touch = xy(&[(0., 0.), (2., 0.), (2., 2.), (1., 0.), (0., 2.)]);
    assert!(matches!(
        validate_polygon(&touch),
        Err(PolygonError::SelfIntersecting { .. })
    ));
    // An edge folding back onto the previous one (a zero-width spike).
    let spike = xy(&[(0., 0.), (2., 0.), (2., 2.), (3., 2.), (1., 2.), (0., 2.)]);
    assert_eq!(
        validate_polygon(&spike),
        Err(PolygonError::SelfIntersecting { edges: (2, 3) })
    );
}

#[test]
fn rejects_degenerate() {
    assert_eq!(
        validate_polygon(&xy(&[(0., 0.), (1., 0.)])),
        Err(PolygonError::TooFewVertices)
    );
    let line = xy(&[(0., 0.), (1., 0.), (3., 0.)]);
    assert_eq!(validate_polygon(&line), Err(PolygonError::ZeroArea));
    let repeated = xy(&[(0., 0.), (1., 0.), (1., 0.), (0., 1.)]);
    assert_eq!(
        validate_polygon(&repeated),
        Err(PolygonError::RepeatedVertex(2))
    );
    let closed = xy(&[(0., 0.), (1., 0.), (0., 1.), (0., 0.)]);
    assert_eq!(
        validate_polygon(&closed),
        Err(PolygonError::RepeatedVertex(3))
    );
}

#[test]
fn messages_are_readable() {
    let msg = PolygonError::SelfIntersecting { edges: (0, 2) }.to_string();
    assert!(msg.contains("edge 0 and edge 2"), "{msg}");
    let msg = PolygonError::NonPlanar { max_distance: 0.05 }.to_string();
    assert!(msg.contains("not planar") && msg.contains("5e-2"), "{msg}");
}
