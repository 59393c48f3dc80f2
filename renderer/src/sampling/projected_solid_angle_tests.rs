//! Tests of [`super`]: the projected solid angle against f64 and against a Monte Carlo estimate,
//! samples inside the polygon with the density `cos θ / Ω⊥` (through the inverse, which the χ²
//! suite checks independently), round trips, Newton's convergence within its cap, and the
//! degenerate configurations.

use super::*;
use crate::math::Frame;
use crate::rng::Rng;
use crate::sampling::testing::check_fractions;
use glam::DVec3;

/// Lambert's formula in f64 for the f32 polygon `w` clipped to z ≥ 0 (the reference).
fn lambert64(w: &[Vec3]) -> f64 {
    let w: Vec<DVec3> = w.iter().map(|x| x.as_dvec3()).collect();
    let mut c = Vec::new();
    for (i, &a) in w.iter().enumerate() {
        let b = w[(i + 1) % w.len()];
        if a.z >= 0.0 {
            c.push(a);
        }
        if (a.z > 0.0 && b.z < 0.0) || (a.z < 0.0 && b.z > 0.0) {
            let x = a + a.z / (a.z - b.z) * (b - a);
            c.push(DVec3::new(x.x, x.y, 0.0));
        }
    }
    let mut sum = 0.0;
    for (i, &a) in c.iter().enumerate() {
        let (a, b) = (a.normalize(), c[(i + 1) % c.len()].normalize());
        let m = a.cross(b);
        if m.length() > 0.0 {
            sum += 0.5 * m.length().atan2(a.dot(b)) * m.z / m.length();
        }
    }
    sum.abs()
}

/// A random convex polygon (triangle or parallelogram) in the local frame: centre direction with
/// `z ∈ [zmin, 1]`, distance log-uniform in [0.3, 300], size log-uniform in [0.01, 3], its plane
/// tilted up to 85° from facing the origin.
fn random_polygon(r: &mut Rng, zmin: f32) -> Vec<Vec3> {
    let u = r.next_2d();
    let z = zmin + (1.0 - zmin) * u.x;
    let phi = std::f32::consts::TAU * u.y;
    let s = (1.0 - z * z).max(0.0).sqrt();
    let dir = Vec3::new(s * phi.cos(), s * phi.sin(), z);
    let dist = 0.3 * 1000f32.powf(r.next_f32());
    let size = 0.01 * 300f32.powf(r.next_f32());
    let tilt = 85f32.to_radians() * r.next_f32();
    let f = Frame::from_normal(-dir);
    let spin = std::f32::consts::TAU * r.next_f32();
    let n = (f.n * tilt.cos() + (f.s * spin.cos() + f.t * spin.sin()) * tilt.sin()).normalize();
    let g = Frame::from_normal(n);
    let c = dir * dist;
    let at = |x: f32, y: f32| c + size * (g.s * x + g.t * y);
    if r.next_f32() < 0.5 {
        vec![at(1.0, 0.0), at(-0.5, 0.8), at(-0.4, -0.9)]
    } else {
        let sk = r.next_f32() - 0.5;
        vec![
            at(-1.0, -0.6),
            at(1.0, -0.6),
            at(1.0 + sk, 0.6),
            at(-1.0 + sk, 0.6),
        ]
    }
}

/// Whether unit `w` is in the convex spherical polygon `v` (counter-clockwise about +z), within
/// `tol` radians.
fn inside(v: &[Vec3], w: Vec3, tol: f32) -> bool {
    (0..v.len()).all(|i| {
        let m = v[i].cross(v[(i + 1) % v.len()]).normalize_or_zero();
        m.dot(w) >= -tol
    })
}

/// Hand-made cases: zenith inside, zenith on an edge and at a vertex, an edge on the horizon,
/// half below the horizon, a huge light just above the receiver, a thin radial sliver.
fn special_cases() -> Vec<(&'static str, Vec<Vec3>)> {
    let v = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
    vec![
        (
            "zenith_inside",
            vec![v(-1.0, -1.0, 1.0), v(1.0, -1.0, 1.0), v(0.0, 1.0, 1.0)],
        ),
        (
            "zenith_on_edge",
            vec![v(-1.0, 0.0, 1.0), v(1.0, 0.0, 1.0), v(0.0, 1.0, 1.0)],
        ),
        (
            "zenith_at_vertex",
            vec![v(0.0, 0.0, 1.0), v(1.0, 0.0, 1.0), v(0.0, 1.0, 1.0)],
        ),
        (
            "horizon_edge",
            vec![v(1.0, -1.0, 0.0), v(1.0, 1.0, 0.0), v(1.0, 0.0, 1.0)],
        ),
        (
            "straddling",
            vec![
                v(2.0, -1.0, -1.0),
                v(2.0, 1.0, -1.0),
                v(2.0, 1.0, 1.0),
                v(2.0, -1.0, 1.0),
            ],
        ),
        (
            "huge_close",
            vec![
                v(-50.0, -50.0, 0.01),
                v(50.0, -50.0, 0.01),
                v(50.0, 50.0, 0.01),
                v(-50.0, 50.0, 0.01),
            ],
        ),
        (
            "radial_sliver",
            vec![v(0.1, 0.0, 1.0), v(3.0, 0.02, 1.0), v(3.0, -0.02, 1.0)],
        ),
    ]
}

/// Every configuration of the tests: the special cases and 3000 random polygons (a third of
/// them with centres down to 0.3 below the horizon).
fn configs() -> Vec<Vec<Vec3>> {
    let mut r = Rng::new(41, 0, 0);
    let mut out: Vec<Vec<Vec3>> = special_cases().into_iter().map(|c| c.1).collect();
    for i in 0..3000 {
        out.push(random_polygon(&mut r, if i % 3 == 0 { -0.3 } else { 0.0 }));
    }
    out
}

/// Ω⊥ against Lambert's formula in f64, by condition number `Σ|S_e|/Ω⊥`: relative error at most
/// 3e-7 × the condition number over 3000 random polygons (most of them small or far, so that a
/// quarter or more is well conditioned) and the special cases, and below 1e-5 wherever
/// [`ProjectedPolygon::well_conditioned`] (the fallback's purpose). Measured: the error grows
/// about linearly with the condition number, at most 2.2e-7 × it (printed).
#[test]
fn area_matches_f64_lambert() {
    let mut worst_ratio = 0.0f64;
    let mut worst_conditioned = 0.0f64;
    let (mut kept, mut total) = (0, 0);
    for w in configs() {
        let exact = lambert64(&w);
        let Some(p) = ProjectedPolygon::new(&w) else {
            assert!(exact < 1e-12, "{w:?}: None but Ω⊥ = {exact}");
            continue;
        };
        total += 1;
        let err = (p.area() as f64 - exact).abs() / exact;
        let cond = (p.abs_sum() / p.area()) as f64;
        assert!(
            err <= 3e-7 * cond,
            "{w:?}: error {err:.2e} at condition {cond:.1}"
        );
        worst_ratio = worst_ratio.max(err / cond);
        if p.well_conditioned() {
            kept += 1;
            worst_conditioned = worst_conditioned.max(err);
        }
    }
    eprintln!(
        "Ω⊥: worst error/condition {worst_ratio:.2e}; {kept} of {total} well conditioned, worst \
         error there {worst_conditioned:.2e}"
    );
    assert!(worst_conditioned < 1e-5);
    assert!(kept > total / 4);
}

/// Ω⊥ against an independent estimate: the fraction of cosine-distributed directions that hit
/// the (unclipped) polygon, times π, within 5 standard errors, for the special cases.
#[test]
fn area_matches_cosine_monte_carlo() {
    for (name, w) in special_cases() {
        let p = ProjectedPolygon::new(&w).unwrap();
        // The polygon seen from the origin (either winding): directions inside it.
        let dirs: Vec<Vec3> = w.iter().map(|x| x.normalize()).collect();
        let sign = if dirs[0].cross(dirs[1]).dot(dirs[2]) > 0.0 {
            1.0
        } else {
            -1.0
        };
        let hits = |d: Vec3| {
            (0..dirs.len()).all(|i| sign * dirs[i].cross(dirs[(i + 1) % dirs.len()]).dot(d) >= 0.0)
        };
        let mut r = Rng::new(5, 0, 0);
        let n = 400_000;
        let count = (0..n)
            .filter(|_| hits(crate::sampling::sample_cosine_hemisphere(r.next_2d())))
            .count();
        let f = count as f64 / n as f64;
        let (est, se) = (
            std::f64::consts::PI * f,
            std::f64::consts::PI * (f * (1.0 - f) / n as f64).sqrt(),
        );
        let got = p.area() as f64;
        assert!(
            (got - est).abs() <= 5.0 * se + 1e-6,
            "{name}: {got} vs {est} ± {se}"
        );
    }
}

/// Samples land inside the clipped polygon, above the horizon, with unit length; their `u`
/// round-trips through [`ProjectedPolygon::invert`]; and the inverse maps them to uniform points
/// (4×4 grid within 5σ), i.e. the samples have the density `cos θ / Ω⊥`, for every special case
/// and 300 well-conditioned random polygons.
/// Mutant tried (by hand): `u.y²` in place of `u.y` in `Wedge::lift` fails it; the same
/// mutant fails 16 of the 20 projected-solid-angle cases of the χ² suite (all but the three far
/// lights, which fall back to solid angle, and the star half below the horizon).
#[test]
fn samples_are_inside_uniform_and_round_trip() {
    let mut cases: Vec<Vec<Vec3>> = special_cases().into_iter().map(|c| c.1).collect();
    cases.extend(
        configs()
            .into_iter()
            .filter(|w| ProjectedPolygon::new(w).is_some_and(|p| p.well_conditioned()))
            .take(300),
    );
    let mut worst = 0.0f32;
    for (k, w) in cases.iter().enumerate() {
        let p = ProjectedPolygon::new(w).unwrap();
        let mut r = Rng::new(9, k as u32, 0);
        let mut counts = [0u32; 16];
        let n = 4000;
        for _ in 0..n {
            let u = r.next_2d();
            let d = p.sample(u);
            assert!((d.length() - 1.0).abs() < 1e-5, "{w:?}: |{d}| ≠ 1");
            assert!(d.z >= 0.0, "{w:?}: {d} below the horizon");
            assert!(inside(p.vertices(), d, 1e-5), "{w:?} {u}: {d} outside");
            let back = p
                .invert(d)
                .unwrap_or_else(|| panic!("{w:?}: {d} not invertible"));
            // u.y is ill-conditioned where the inner and outer arcs nearly meet (r² differences).
            worst = worst.max((back.x - u.x).abs());
            let c = (back * 4.0).as_uvec2().min(glam::UVec2::splat(3));
            counts[(c.y * 4 + c.x) as usize] += 1;
        }
        check_fractions(&counts, &[1.0 / 16.0; 16]);
    }
    eprintln!("worst |Δu.x| in round trips: {worst:.2e}");
    assert!(worst < 1e-3);
}

/// Newton's iteration reaches the target within its cap on well-conditioned polygons: the
/// sampled azimuth's distribution function differs from `u.x` by at most 4e-6 × the condition
/// number `Σ|S_e|/Ω⊥` (the noise of evaluating it: the arcs' points carry their normals'
/// rounding; measured worst printed), so by at most 2.6e-4 under [`MAX_CONDITION`]. Where the
/// polygon is well conditioned (condition below 8) the iteration stops by its tolerance, short
/// of the cap; the histogram of steps taken is printed.
#[test]
fn newton_converges_within_the_cap() {
    let (mut worst, mut worst_scaled) = (0.0f32, 0.0f32);
    let mut calm = [0u64; NEWTON_STEPS as usize];
    for (k, w) in configs().iter().enumerate() {
        let Some(p) = ProjectedPolygon::new(w).filter(|p| p.well_conditioned()) else {
            continue;
        };
        if p.contains_zenith() {
            continue;
        }
        let cond = p.abs_sum() / p.area();
        let mut r = Rng::new(10, k as u32, 0);
        for _ in 0..20 {
            let u = r.next_2d();
            let (d, steps) = p.sample_steps(u);
            let back = p.invert(d).unwrap();
            worst = worst.max((back.x - u.x).abs());
            worst_scaled = worst_scaled.max((back.x - u.x).abs() / cond);
            if cond < 8.0 {
                // Calls reaching step k + 1, for every k below the steps taken.
                calm[..steps as usize].iter_mut().for_each(|c| *c += 1);
            }
        }
    }
    eprintln!(
        "worst |C(φ)/Ω⊥ − u.x|: {worst:.2e}, {worst_scaled:.2e} × the condition number; calls \
         reaching each Newton step where the condition is below 8: {calm:?}"
    );
    assert!(worst_scaled < 4e-6, "{worst_scaled}");
    assert!(
        calm[0] > 0 && calm[NEWTON_STEPS as usize - 1] == 0,
        "{calm:?}"
    );
}

/// Degenerate inputs: entirely below the horizon, touching it at an edge or a vertex only,
/// coincident vertices; tiny and grazing polygons are ill-conditioned.
#[test]
fn degenerate_cases() {
    let v = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
    assert!(
        ProjectedPolygon::new(&[v(1.0, 0.0, -1.0), v(0.0, 1.0, -1.0), v(0.0, 0.0, -1.0)]).is_none()
    );
    assert!(
        ProjectedPolygon::new(&[v(1.0, 0.0, 0.0), v(0.0, 1.0, 0.0), v(0.0, 0.0, -1.0)]).is_none()
    );
    assert!(
        ProjectedPolygon::new(&[v(1.0, 0.0, 0.0), v(0.0, 1.0, -1.0), v(0.0, 0.0, -1.0)]).is_none()
    );
    assert!(
        ProjectedPolygon::new(&[v(1.0, 0.0, 1.0), v(1.0, 0.0, 1.0), v(0.0, 1.0, 1.0)]).is_none()
    );
    // 1e-4 wide at distance 1, 60° from the zenith.
    let tiny = [
        v(0.866, 0.0, 0.5),
        v(0.866, 1e-4, 0.5),
        v(0.866, 0.0, 0.5001),
    ];
    let p = ProjectedPolygon::new(&tiny).unwrap();
    assert!(!p.well_conditioned(), "{p:?}");
    // A sizeable light 0.2° above the horizon.
    let grazing = [v(5.0, -1.0, 0.01), v(5.0, 1.0, 0.01), v(5.0, 0.0, 0.03)];
    let p = ProjectedPolygon::new(&grazing).unwrap();
    assert!(!p.well_conditioned(), "{p:?}");
    // Both windings give the same polygon.
    let a = ProjectedPolygon::new(&special_cases()[0].1).unwrap();
    let mut rev = special_cases()[0].1.clone();
    rev.reverse();
    let b = ProjectedPolygon::new(&rev).unwrap();
    assert!((a.area() - b.area()).abs() <= 1e-6 * a.area());
}
