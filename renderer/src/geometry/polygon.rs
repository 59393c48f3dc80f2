//! Planar polygons: the Newell normal, validation (planar, simple, non-degenerate) and
//! ear-clipping triangulation.
//!
//! Everything here is `f64` and runs once at scene load, so it favours robustness and clear
//! errors over speed (O(n²) in the vertex count).
//!
//! All tolerances are relative to the polygon's *size*, the diagonal of its bounding box, so the
//! same polygon validates identically whether it is 1e-3 or 1e5 units across.

use glam::{DVec2, DVec3};
use std::fmt;

/// Largest allowed distance of a vertex from the best-fit plane, as a fraction of the size.
///
/// Why 1e-4: scene files are written by hand or by scripts that round coordinates to 6–10
/// significant digits, which moves vertices by ≲1e-6 of the size; a typo or a genuinely bent
/// polygon moves them by ≳1e-2. A vertex 1e-4·size off the plane tilts the fan triangles by
/// ~1e-4 rad, which changes their projected area (and hence emitted power and light pdfs) by ~1e-8:
/// invisible. So 1e-4 accepts every honest file and rejects every real mistake.
pub const PLANARITY_TOLERANCE: f64 = 1e-4;

/// Relative tolerance for "zero": two vertices closer than this (× size) coincide, and a
/// polygon whose area is below this (× size²) has zero area. Far above f64 rounding (~1e-16),
/// far below any intentional feature.
const DEGENERATE_TOLERANCE: f64 = 1e-10;

/// Orientation tests in the normalised 2D projection (coordinates of order 1) treat values
/// below this as zero, so touching edges count as touching despite rounding.
const ORIENT_EPS: f64 = 1e-12;

/// Why a vertex list is not a valid polygon.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PolygonError {
    /// Fewer than three vertices.
    TooFewVertices,
    /// The vertices are collinear (or the polygon otherwise encloses no area).
    ZeroArea,
    /// Some vertex lies farther than the tolerance from the best-fit plane.
    NonPlanar {
        /// The largest distance of a vertex from the best-fit plane, in scene units.
        max_distance: f64,
    },
    /// Two edges cross, touch or overlap; edge `i` runs from vertex `i` to vertex `i + 1`.
    SelfIntersecting {
        /// The two offending edges, smaller index first.
        edges: (usize, usize),
    },
    /// This vertex coincides with an earlier one.
    RepeatedVertex(usize),
}

impl fmt::Display for PolygonError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            PolygonError::TooFewVertices => write!(f, "a polygon needs at least 3 vertices"),
            PolygonError::ZeroArea => {
                write!(f, "the polygon has zero area (its vertices are collinear)")
            }
            PolygonError::NonPlanar { max_distance } => write!(
                f,
                "the polygon is not planar: a vertex lies {max_distance:e} from the best-fit \
                 plane (allowed: {PLANARITY_TOLERANCE:e} of the polygon's size)"
            ),
            PolygonError::SelfIntersecting { edges: (a, b) } => write!(
                f,
                "the polygon is not simple: edge {a} and edge {b} intersect or touch \
                 (edge i runs from vertex i to vertex i+1)"
            ),
            PolygonError::RepeatedVertex(i) => {
                write!(f, "vertex {i} coincides with an earlier vertex")
            }
        }
    }
}

impl std::error::Error for PolygonError {}

/// The Newell normal: the sum of the cross products of consecutive vertices. It points along the
/// right-hand-rule normal of the vertex order and its length is twice the area of a planar
/// polygon; for a non-planar one it is the normal of the best-fit plane.
pub fn newell_normal(v: &[DVec3]) -> DVec3 {
    let Some(&origin) = v.first() else {
        return DVec3::ZERO;
    };
    // Relative to the first vertex: the sum is translation invariant, and subtracting first
    // keeps full precision for small polygons far from the origin.
    (1..v.len().saturating_sub(1))
        .map(|i| (v[i] - origin).cross(v[i + 1] - origin))
        .sum()
}

/// Checks that `v` is a planar, simple polygon with distinct vertices and non-zero area, and
/// returns its unit normal (right-hand rule). Coordinates must be finite.
pub fn validate_polygon(v: &[DVec3]) -> Result<DVec3, PolygonError> {
    let n = v.len();
    if n < 3 {
        return Err(PolygonError::TooFewVertices);
    }
    let size = polygon_size(v);
    for j in 1..n {
        if v[..j]
            .iter()
            .any(|&p| p.distance(v[j]) <= DEGENERATE_TOLERANCE * size)
        {
            return Err(PolygonError::RepeatedVertex(j));
        }
    }
    let newell = newell_normal(v);
    let zero_area = newell.length() <= DEGENERATE_TOLERANCE * size * size;
    // A bow-tie can have zero *signed* area; find a plane from one fan triangle instead, so it is
    // reported as self-intersecting rather than as zero-area.
    let plane_normal = if zero_area {
        let fan = (1..n - 1)
            .map(|i| (v[i] - v[0]).cross(v[i + 1] - v[0]))
            .max_by(|a, b| a.length_squared().total_cmp(&b.length_squared()))
            .unwrap_or(DVec3::ZERO);
        if fan.length() <= DEGENERATE_TOLERANCE * size * size {
            return Err(PolygonError::ZeroArea);
        }
        fan.normalize()
    } else {
        newell.normalize()
    };

    let centroid = v.iter().sum::<DVec3>() / n as f64;
    let max_distance = v
        .iter()
        .map(|&p| (p - centroid).dot(plane_normal).abs())
        .fold(0.0, f64::max);
    if max_distance > PLANARITY_TOLERANCE * size {
        return Err(PolygonError::NonPlanar { max_distance });
    }

    let p = project(v, plane_normal);
    check_simple(&p)?;
    if zero_area {
        // Unreachable for a truly simple polygon, kept as a guard.
        return Err(PolygonError::ZeroArea);
    }
    Ok(plane_normal)
}

/// Splits a valid (see [`validate_polygon`]) polygon into `n - 2` or fewer triangles of vertex
/// indices, each wound like the polygon so its right-hand normal equals the polygon's. Handles
/// concave polygons and collinear vertices; prefers well-shaped ears to avoid slivers.
pub fn triangulate(v: &[DVec3]) -> Vec<[usize; 3]> {
    let normal = newell_normal(v);
    if v.len() < 3 || normal == DVec3::ZERO {
        return Vec::new();
    }
    // Projected onto a basis with u × w = normal, the polygon runs counter-clockwise.
    let p = project(v, normal.normalize());
    let mut ring: Vec<usize> = (0..v.len()).collect();
    let mut ears: Vec<Option<f64>> = (0..ring.len()).map(|k| ear_quality(&p, &ring, k)).collect();
    let mut triangles = Vec::with_capacity(v.len() - 2);
    while ring.len() > 3 {
        let m = ring.len();
        let best = (0..m)
            .filter_map(|k| ears[k].map(|q| (k, q)))
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(k, _)| k);
        let k = match best {
            Some(k) => {
                triangles.push([ring[(k + m - 1) % m], ring[k], ring[(k + 1) % m]]);
                k
            }
            // No ear: only possible through rounding on collinear runs. Drop a flat vertex (it
            // adds no area); failing that, clip the most convex one, so the loop always ends.
            None => match (0..m).find(|&k| corner(&p, &ring, k).abs() <= ORIENT_EPS) {
                Some(k) => k,
                None => {
                    let k = (0..m)
                        .max_by(|&a, &b| corner(&p, &ring, a).total_cmp(&corner(&p, &ring, b)))
                        .unwrap_or(0);
                    triangles.push([ring[(k + m - 1) % m], ring[k], ring[(k + 1) % m]]);
                    k
                }
            },
        };
        ring.remove(k);
        ears.remove(k);
        // Only the two neighbours of the clipped vertex change their ear status.
        let m = ring.len();
        let (before, after) = ((k + m - 1) % m, k % m);
        ears[before] = ear_quality(&p, &ring, before);
        ears[after] = ear_quality(&p, &ring, after);
    }
    if orient(p[ring[0]], p[ring[1]], p[ring[2]]) > ORIENT_EPS {
        triangles.push([ring[0], ring[1], ring[2]]);
    }
    triangles
}

/// The diagonal of the bounding box: the length scale for all tolerances.
fn polygon_size(v: &[DVec3]) -> f64 {
    let lo = v.iter().fold(DVec3::INFINITY, |a, &b| a.min(b));
    let hi = v.iter().fold(DVec3::NEG_INFINITY, |a, &b| a.max(b));
    (hi - lo).length()
}

/// Projects onto the plane with unit normal `normal`, in a right-handed 2D basis, centred on the
/// centroid and scaled by the size so coordinates are of order 1 (making `ORIENT_EPS` relative).
fn project(v: &[DVec3], normal: DVec3) -> Vec<DVec2> {
    let u = normal.any_orthonormal_vector();
    let w = normal.cross(u);
    let centroid = v.iter().sum::<DVec3>() / v.len() as f64;
    let scale = 1.0 / polygon_size(v);
    v.iter()
        .map(|&q| DVec2::new((q - centroid).dot(u), (q - centroid).dot(w)) * scale)
        .collect()
}

/// Twice the signed area of triangle `abc`: positive when counter-clockwise.
fn orient(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    (b - a).perp_dot(c - a)
}

/// Sign of `orient` with a dead zone around zero.
fn orient_sign(a: DVec2, b: DVec2, c: DVec2) -> i32 {
    let o = orient(a, b, c);
    if o > ORIENT_EPS {
        1
    } else if o < -ORIENT_EPS {
        -1
    } else {
        0
    }
}

/// Whether `q`, known to be collinear with `a` and `b`, lies within the segment's bounds.
fn within(a: DVec2, b: DVec2, q: DVec2) -> bool {
    let lo = a.min(b) - DVec2::splat(ORIENT_EPS);
    let hi = a.max(b) + DVec2::splat(ORIENT_EPS);
    q.cmpge(lo).all() && q.cmple(hi).all()
}

/// Whether the closed segments `ab` and `cd` share any point.
fn segments_meet(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> bool {
    let (d1, d2) = (orient_sign(c, d, a), orient_sign(c, d, b));
    let (d3, d4) = (orient_sign(a, b, c), orient_sign(a, b, d));
    if d1 * d2 < 0 && d3 * d4 < 0 {
        return true;
    }
    (d1 == 0 && within(c, d, a))
        || (d2 == 0 && within(c, d, b))
        || (d3 == 0 && within(a, b, c))
        || (d4 == 0 && within(a, b, d))
}

/// Non-adjacent edges must not meet; adjacent edges must not fold back onto each other.
fn check_simple(p: &[DVec2]) -> Result<(), PolygonError> {
    let n = p.len();
    let edge = |i: usize| (p[i], p[(i + 1) % n]);
    for i in 0..n {
        // Adjacent edges i-1 and i share vertex i; they overlap if collinear and pointing back.
        let (prev, here, next) = (p[(i + n - 1) % n], p[i], p[(i + 1) % n]);
        if orient_sign(prev, here, next) == 0 && (prev - here).dot(next - here) > 0.0 {
            let pair = ((i + n - 1) % n, i);
            return Err(PolygonError::SelfIntersecting {
                edges: (pair.0.min(pair.1), pair.0.max(pair.1)),
            });
        }
    }
    for i in 0..n {
        for j in i + 2..n {
            if i == 0 && j == n - 1 {
                continue; // adjacent through the wrap-around
            }
            let ((a, b), (c, d)) = (edge(i), edge(j));
            if segments_meet(a, b, c, d) {
                return Err(PolygonError::SelfIntersecting { edges: (i, j) });
            }
        }
    }
    Ok(())
}

/// Turn at ring position `k` (positive = convex in a counter-clockwise ring).
fn corner(p: &[DVec2], ring: &[usize], k: usize) -> f64 {
    let m = ring.len();
    orient(p[ring[(k + m - 1) % m]], p[ring[k]], p[ring[(k + 1) % m]])
}

/// `Some(quality)` if ring position `k` is an ear: strictly convex, and no other remaining vertex
/// inside or on its triangle. Quality is 4√3·area / Σ edge² (1 for equilateral, → 0 for slivers).
fn ear_quality(p: &[DVec2], ring: &[usize], k: usize) -> Option<f64> {
    let m = ring.len();
    let (ia, ib, ic) = (ring[(k + m - 1) % m], ring[k], ring[(k + 1) % m]);
    let (a, b, c) = (p[ia], p[ib], p[ic]);
    let twice_area = orient(a, b, c);
    if twice_area <= ORIENT_EPS {
        return None;
    }
    let blocked = ring
        .iter()
        .filter(|&&i| i != ia && i != ib && i != ic)
        .any(|&i| {
            let q = p[i];
            orient(a, b, q) >= -ORIENT_EPS
                && orient(b, c, q) >= -ORIENT_EPS
                && orient(c, a, q) >= -ORIENT_EPS
        });
    if blocked {
        return None;
    }
    let edges2 = (b - a).length_squared() + (c - b).length_squared() + (a - c).length_squared();
    Some(2.0 * 3f64.sqrt() * twice_area / edges2)
}

#[cfg(test)]
mod tests;
