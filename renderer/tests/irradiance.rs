//! Irradiance from every light shape, estimated by light sampling, against closed forms.
//!
//! For a triangle, a parallelogram (quad), a convex hexagon, a concave five-pointed star polygon, a
//! disk and a sphere, each a one-sided emitter of radiance `L`, tilted and moved off the axes, we
//! take [`POINTS`] random receivers in front of the emitting side (heights from 0.02 to 20 light
//! sizes, laterally over and beside the light) with random normals, and estimate
//! `E = ∫ L·max(0, n·ω) dω` as the mean of `L·max(0, n·wi)/pdf` over [`SAMPLES`] samples of
//! `Light::sample` (area and solid-angle sampling, and for the polygonal lights projected solid
//! angle with the receiver's normal; a `None` sample counts 0).
//!
//! Projected-solid-angle sampling has zero variance here wherever it does not fall back to solid
//! angle (every sample's estimate is `L·Ω⊥`): its standard error is rounding, so the comparison is
//! one of its f32 Ω⊥ with the f64 closed form, within the relative slack below.
//!
//! Closed forms (f64, from the f32 geometry the light holds):
//! - polygons, triangles, quads: Lambert's formula `E = L/2 · |Σ_i γ_i n·(r_i × r_{i+1})/|r_i × r_{i+1}||`
//!   (γ_i the angle between the unit directions r_i, r_{i+1} to consecutive vertices). It is a contour
//!   integral, exact for concave polygons too.
//! - disk: the same contour integral, `E = L/2 · |∮ n·(r × dr)/|r|²|`, by the trapezoidal rule with
//!   4096 nodes (exponentially convergent for this smooth periodic integrand; checked against the
//!   on-axis closed form `πL r²/(r² + d²)`).
//! - sphere: `E = πL (r/d)² cos θ`, θ between `n` and the direction to the centre.
//!
//! For these, the normal is drawn (uniformly, by rejection) so that the whole light is above the
//! receiver's horizon, where `max(0, ·)` is inactive. In addition, [`CLIPPED`] points per polygonal
//! light and for the disk have normals for which the light straddles the horizon: the polygon is
//! clipped by the receiver's tangent plane (Sutherland–Hodgman; the collinear edges it may add along
//! the plane for the concave star cancel in the contour integral) and Lambert's formula is applied
//! to the clipped polygon; the disk's contour becomes the arc above the plane (composite Simpson)
//! and the chord along it (Lambert's exact term for a straight edge), checked against a clipped
//! 4096-gon. With solid-angle sampling the disk is sampled through its spherical ellipse (issue
//! 20) wherever that is at least `MIN_ELLIPSE_SOLID_ANGLE` (heights up to ~4 here), by area
//! beyond.
//!
//! **Test:** per point and method, two-sided z-test with the standard error computed from the
//! samples, family-wise α = 0.01 over all [`N_TESTS`] comparisons in this file (Šidák), plus a
//! relative slack of 1e-5 of E for f32 rounding. Everything is seeded.

use glam::{DVec3, Vec2};
use lumis::lights::{Light, LightSampling};
use lumis::metrics::{normal_two_sided_critical, sidak};
use lumis::rng::Rng;
use lumis::scene::{Scene, parse_scene};
use rayon::prelude::*;
use std::f64::consts::PI;

/// Receivers with the whole light above the horizon, per light.
const POINTS: usize = 50;
/// Extra receivers with the light straddling the horizon, per polygonal light and for the disk.
const CLIPPED: usize = 10;
/// Light samples per receiver and method.
const SAMPLES: u32 = 50_000;
const METHODS: [LightSampling; 3] = [
    LightSampling::Area,
    LightSampling::SolidAngle,
    LightSampling::ProjectedSolidAngle,
];
/// The first this many of [`METHODS`] run on the round lights too (projected solid angle is
/// solid angle there).
const ROUND_METHODS: usize = 2;
/// Polygonal lights (triangle, quad, hexagon, star); with the disk they are also seen straddling
/// the horizon, the sphere is not.
const N_POLYGONAL: usize = 4;
/// Every comparison in this file: the polygons with every method, the disk (also clipped) and
/// the sphere with the first [`ROUND_METHODS`].
const N_TESTS: usize = METHODS.len() * N_POLYGONAL * (POINTS + CLIPPED)
    + ROUND_METHODS * ((POINTS + CLIPPED) + POINTS);
/// Emitted radiance.
const LE: f64 = 1.5;

fn critical() -> f64 {
    normal_two_sided_critical(sidak(0.01, N_TESTS))
}

/// The placement of every light: a rotation about a skew axis, then a translation.
fn place(p: DVec3) -> DVec3 {
    let q = glam::DQuat::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 0.7);
    q * p + DVec3::new(0.3, -0.2, 0.5)
}

fn place_dir(d: DVec3) -> DVec3 {
    place(d) - place(DVec3::ZERO)
}

/// Rounds to what the renderer stores (f32).
fn f32r(p: DVec3) -> DVec3 {
    p.as_vec3().as_dvec3()
}

fn jv(p: DVec3) -> String {
    format!("[{:?}, {:?}, {:?}]", p.x, p.y, p.z)
}

fn build_light(shape_json: &str) -> Light {
    let json = format!(
        r#"{{
  "camera": {{"from": [0, 0, -10], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40, "width": 4, "height": 4}},
  "shapes": [{shape_json}]
}}"#
    );
    let desc = parse_scene(&json).unwrap_or_else(|e| panic!("{e}\n{json}"));
    let scene = Scene::from_desc(&desc).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.lights.len(), 1);
    scene.lights[0].clone()
}

/// The emitter's geometry as the closed forms see it.
#[derive(Clone, Debug)]
enum Geometry {
    /// Vertices (in order, wound so that the right-hand-rule normal is the emitting side).
    Polygon(Vec<DVec3>),
    Disk {
        c: DVec3,
        n: DVec3,
        r: f64,
    },
    Sphere {
        c: DVec3,
        r: f64,
    },
}

struct Case {
    name: &'static str,
    light: Light,
    geometry: Geometry,
}

fn polygon_case(name: &'static str, local: &[[f64; 2]], json_kind: &str) -> Case {
    let world: Vec<DVec3> = local
        .iter()
        .map(|p| place(DVec3::new(p[0], p[1], 0.0)))
        .collect();
    let shape = match json_kind {
        "triangles" => format!(
            r#"{{"type": "triangles", "positions": [{}], "indices": [[0, 1, 2]], "emission": [{LE}, {LE}, {LE}]}}"#,
            world.iter().map(|p| jv(*p)).collect::<Vec<_>>().join(", ")
        ),
        "quad" => format!(
            r#"{{"type": "quad", "corner": {}, "edge_u": {}, "edge_v": {}, "emission": [{LE}, {LE}, {LE}]}}"#,
            jv(world[0]),
            jv(world[1] - world[0]),
            jv(world[3] - world[0]),
        ),
        _ => format!(
            r#"{{"type": "polygon", "vertices": [{}], "emission": [{LE}, {LE}, {LE}]}}"#,
            world.iter().map(|p| jv(*p)).collect::<Vec<_>>().join(", ")
        ),
    };
    let light = build_light(&shape);
    // The geometry the light holds, in f32.
    let vertices: Vec<DVec3> = match &light {
        Light::Triangle(l) => l.v.iter().map(|v| v.as_dvec3()).collect(),
        Light::Quad(_) => {
            // Corner + edges as parsed (f32), the fourth vertex as their sum.
            let (c, u, v) = (
                f32r(world[0]),
                f32r(world[1] - world[0]),
                f32r(world[3] - world[0]),
            );
            vec![c, c + u, c + u + v, c + v]
        }
        Light::Polygon(l) => l.vertices.iter().map(|v| v.as_dvec3()).collect(),
        other => panic!("{name}: unexpected light {other:?}"),
    };
    Case {
        name,
        light,
        geometry: Geometry::Polygon(vertices),
    }
}

fn cases() -> Vec<Case> {
    let hexagon = [
        [0.5, 0.0],
        [0.3, 0.45],
        [-0.2, 0.5],
        [-0.55, 0.1],
        [-0.35, -0.4],
        [0.2, -0.45],
    ];
    let star: Vec<[f64; 2]> = (0..10)
        .map(|i| {
            let a = PI / 2.0 + i as f64 * PI / 5.0;
            let r = if i % 2 == 0 { 0.6 } else { 0.24 };
            [r * a.cos(), r * a.sin()]
        })
        .collect();
    let disk_c = place(DVec3::ZERO);
    let disk_n = place_dir(DVec3::Z);
    let disk = build_light(&format!(
        r#"{{"type": "disk", "center": {}, "normal": {}, "radius": 0.5, "emission": [{LE}, {LE}, {LE}]}}"#,
        jv(disk_c),
        jv(disk_n)
    ));
    let Light::Disk(d) = &disk else {
        panic!("not a disk")
    };
    let disk_geometry = Geometry::Disk {
        c: d.disk.center.as_dvec3(),
        n: d.disk.n.as_dvec3().normalize(),
        r: d.disk.radius as f64,
    };
    let sphere = build_light(&format!(
        r#"{{"type": "sphere", "center": {}, "radius": 0.5, "emission": [{LE}, {LE}, {LE}]}}"#,
        jv(disk_c)
    ));
    let Light::Sphere(s) = &sphere else {
        panic!("not a sphere")
    };
    let sphere_geometry = Geometry::Sphere {
        c: s.sphere.center.as_dvec3(),
        r: s.sphere.radius as f64,
    };
    vec![
        polygon_case(
            "triangle",
            &[[-0.4, -0.3], [0.5, -0.2], [0.1, 0.6]],
            "triangles",
        ),
        polygon_case(
            "quad",
            &[[-0.5, -0.4], [0.5, -0.4], [0.8, 0.4], [-0.2, 0.4]],
            "quad",
        ),
        polygon_case("hexagon", &hexagon, "polygon"),
        polygon_case("star", &star, "polygon"),
        Case {
            name: "disk",
            light: disk,
            geometry: disk_geometry,
        },
        Case {
            name: "sphere",
            light: sphere,
            geometry: sphere_geometry,
        },
    ]
}

/// Lambert's formula: irradiance from a uniform polygon (any simple polygon, any orientation)
/// wholly above the horizon of `(p, n)`.
fn lambert(p: DVec3, n: DVec3, vertices: &[DVec3]) -> f64 {
    let dirs: Vec<DVec3> = vertices.iter().map(|v| (*v - p).normalize()).collect();
    let mut sum = 0.0;
    for i in 0..dirs.len() {
        let (a, b) = (dirs[i], dirs[(i + 1) % dirs.len()]);
        let c = a.cross(b);
        let len = c.length();
        if len == 0.0 {
            continue;
        }
        let gamma = len.atan2(a.dot(b));
        sum += gamma * n.dot(c) / len;
    }
    0.5 * LE * sum.abs()
}

/// Sutherland–Hodgman: the part of the polygon with `n·(x − p) ≥ 0`.
fn clip(p: DVec3, n: DVec3, vertices: &[DVec3]) -> Vec<DVec3> {
    let mut out = Vec::new();
    let k = vertices.len();
    for i in 0..k {
        let (a, b) = (vertices[i], vertices[(i + 1) % k]);
        let (da, db) = (n.dot(a - p), n.dot(b - p));
        if da >= 0.0 {
            out.push(a);
        }
        if (da >= 0.0) != (db >= 0.0) {
            let t = da / (da - db);
            out.push(a + t * (b - a));
        }
    }
    out
}

/// The disk's contour integral by the trapezoidal rule.
fn disk_irradiance(p: DVec3, n: DVec3, c: DVec3, nd: DVec3, r: f64) -> f64 {
    const M: usize = 4096;
    let e1 = nd.any_orthonormal_vector();
    let e2 = nd.cross(e1);
    let mut sum = 0.0;
    for i in 0..M {
        let t = 2.0 * PI * i as f64 / M as f64;
        let (s, co) = t.sin_cos();
        let x = c + r * (co * e1 + s * e2) - p;
        let dx = r * (-s * e1 + co * e2);
        sum += n.dot(x.cross(dx)) / x.length_squared();
    }
    0.5 * LE * (sum * 2.0 * PI / M as f64).abs()
}

/// The contour integral of the part of the disk above the plane through `p` with normal `n`:
/// the arc with `n·(x − p) ≥ 0` by composite Simpson (smooth, not periodic), closed by the chord
/// along the plane with Lambert's exact term for a straight edge. The whole disk where the plane
/// misses it; 0 where the disk is wholly below.
fn clipped_disk_irradiance(p: DVec3, n: DVec3, c: DVec3, nd: DVec3, r: f64) -> f64 {
    const M: usize = 20_000;
    let e1 = nd.any_orthonormal_vector();
    let e2 = nd.cross(e1);
    // n·(x(t) − p) = m + r·k·cos(t − t0) on the rim x(t) = c + r(cos t e1 + sin t e2).
    let (a, b) = (n.dot(e1), n.dot(e2));
    let (m, k, t0) = (n.dot(c - p), a.hypot(b), b.atan2(a));
    let ratio = -m / (r * k);
    if ratio <= -1.0 {
        return disk_irradiance(p, n, c, nd, r);
    }
    if ratio >= 1.0 {
        return 0.0;
    }
    let delta = ratio.acos();
    let rim = |t: f64| c + r * (t.cos() * e1 + t.sin() * e2) - p;
    let f = |t: f64| {
        let x = rim(t);
        let dx = r * (-t.sin() * e1 + t.cos() * e2);
        n.dot(x.cross(dx)) / x.length_squared()
    };
    let (lo, hi) = (t0 - delta, t0 + delta);
    let h = (hi - lo) / M as f64;
    let mut arc = f(lo) + f(hi);
    for i in 1..M {
        arc += f(lo + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    arc *= h / 3.0;
    // The chord from the arc's end back to its start.
    let (from, to) = (rim(hi), rim(lo));
    let cross = from.cross(to);
    let chord = cross.length().atan2(from.dot(to)) * n.dot(cross) / cross.length();
    0.5 * LE * (arc + chord).abs()
}

/// A receiver: position, normal, closed-form irradiance, and whether the light is clipped.
#[derive(Clone, Copy, Debug)]
struct Receiver {
    p: DVec3,
    n: DVec3,
    e: f64,
    clipped: bool,
}

fn uniform_dir(rng: &mut Rng) -> DVec3 {
    let u = rng.next_2d();
    let z = 1.0 - 2.0 * u.x as f64;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y as f64;
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// Smallest and largest `n·(x − p)/|x − p|` over the light.
fn horizon_range(g: &Geometry, p: DVec3, n: DVec3) -> (f64, f64) {
    match g {
        Geometry::Polygon(v) => v.iter().fold((f64::MAX, f64::MIN), |(lo, hi), x| {
            let c = n.dot((*x - p).normalize());
            (lo.min(c), hi.max(c))
        }),
        Geometry::Disk { c, n: nd, r } => {
            // Extremes of n·(x − p) over the rim: n·(c − p) ± r·|n − (n·nd) nd|.
            let tang = (n - n.dot(*nd) * *nd).length();
            let mid = n.dot(*c - p);
            let scale = (*c - p).length() + r;
            ((mid - r * tang) / scale, (mid + r * tang) / scale)
        }
        Geometry::Sphere { c, r } => {
            let d = (*c - p).length();
            let mid = n.dot(*c - p);
            ((mid - r) / d, (mid + r) / d)
        }
    }
}

fn receivers(case: &Case, index: usize) -> Vec<Receiver> {
    let (centre, axis) = match &case.geometry {
        Geometry::Polygon(_) | Geometry::Disk { .. } => (place(DVec3::ZERO), place_dir(DVec3::Z)),
        Geometry::Sphere { c, .. } => (*c, place_dir(DVec3::Z)),
    };
    let tangent_u = place_dir(DVec3::X);
    let tangent_v = place_dir(DVec3::Y);
    let clipped_count = if matches!(case.geometry, Geometry::Polygon(_) | Geometry::Disk { .. }) {
        CLIPPED
    } else {
        0
    };
    let mut out = Vec::new();
    let mut rng = Rng::new(7, index as u32, 0);
    while out.len() < POINTS + clipped_count {
        let want_clipped = out.len() >= POINTS;
        // Height log-uniform in [0.02, 20]; lateral offset over or beside the light.
        let h = 0.02 * 1000f64.powf(rng.next_f32() as f64);
        let spread = 0.6 + 0.5 * h;
        let (x, y) = (
            (2.0 * rng.next_f32() as f64 - 1.0) * spread,
            (2.0 * rng.next_f32() as f64 - 1.0) * spread,
        );
        let p = match case.geometry {
            Geometry::Sphere { r, .. } => {
                // Anywhere outside the sphere: a random direction, distance r·(1.05 … 40).
                let d = r * (1.05 + 40f64.powf(rng.next_f32() as f64) - 1.0);
                centre + d * uniform_dir(&mut rng)
            }
            _ => centre + x * tangent_u + y * tangent_v + h * axis,
        };
        let p = f32r(p);
        let mut found = None;
        for _ in 0..1000 {
            let n = uniform_dir(&mut rng);
            let (lo, hi) = horizon_range(&case.geometry, p, n);
            let ok = if want_clipped {
                lo < -0.05 && hi > 0.05
            } else {
                lo > 1e-3
            };
            if ok {
                found = Some(n);
                break;
            }
        }
        let Some(n) = found else { continue };
        let n = f32r(n).normalize();
        let e = match &case.geometry {
            Geometry::Polygon(v) if want_clipped => lambert(p, n, &clip(p, n, v)),
            Geometry::Polygon(v) => lambert(p, n, v),
            Geometry::Disk { c, n: nd, r } if want_clipped => {
                clipped_disk_irradiance(p, n, *c, *nd, *r)
            }
            Geometry::Disk { c, n: nd, r } => disk_irradiance(p, n, *c, *nd, *r),
            Geometry::Sphere { c, r } => {
                let d = *c - p;
                PI * LE * (r * r / d.length_squared()) * n.dot(d.normalize())
            }
        };
        out.push(Receiver {
            p,
            n,
            e,
            clipped: want_clipped,
        });
    }
    out
}

/// Mean and standard error of `L·max(0, n·wi)/pdf`.
fn estimate(light: &Light, r: &Receiver, method: LightSampling, seed: u32) -> (f64, f64) {
    let mut rng = Rng::new(seed, 0x5eed, 1);
    let (p, n) = (r.p.as_vec3(), r.n.as_vec3());
    let (mut sum, mut sum_sq) = (0.0f64, 0.0f64);
    for _ in 0..SAMPLES {
        let u = Vec2::new(rng.next_f32(), rng.next_f32());
        // The receiver's normal where the method reads it (the others never see one here).
        let ns = if method == LightSampling::ProjectedSolidAngle {
            n
        } else {
            glam::Vec3::ZERO
        };
        let v = match light.sample(p, ns, u, method) {
            Some(s) => {
                assert!(
                    s.pdf > 0.0 && s.pdf.is_finite() && s.wi.is_finite(),
                    "bad sample {s:?}"
                );
                (s.le.x * n.dot(s.wi).max(0.0) / s.pdf) as f64
            }
            None => 0.0,
        };
        sum += v;
        sum_sq += v * v;
    }
    let m = SAMPLES as f64;
    let mean = sum / m;
    let var = ((sum_sq - m * mean * mean) / (m - 1.0)).max(0.0);
    (mean, (var / m).sqrt())
}

#[test]
fn disk_contour_matches_on_axis_closed_form() {
    let c = DVec3::new(0.1, 0.2, 0.3);
    let nd = DVec3::new(1.0, -2.0, 0.5).normalize();
    for (r, d) in [(0.5, 0.01), (0.5, 1.0), (2.0, 30.0)] {
        let p = c + d * nd;
        let e = disk_irradiance(p, -nd, c, nd, r);
        let exact = PI * LE * r * r / (r * r + d * d);
        assert!(
            (e - exact).abs() <= 1e-12 * exact,
            "{r} {d}: {e} vs {exact}"
        );
    }
    // Lambert's formula on a regular 4096-gon inscribed in the disk agrees with the disk's
    // contour integral (to the polygon's O(1/n²) area deficit).
    let poly: Vec<DVec3> = (0..4096)
        .map(|i| {
            let t = 2.0 * PI * i as f64 / 4096.0;
            let e1 = nd.any_orthonormal_vector();
            c + 0.5 * (t.cos() * e1 + t.sin() * nd.cross(e1))
        })
        .collect();
    let p = c + 0.7 * nd;
    let a = lambert(p, -nd, &poly);
    let b = disk_irradiance(p, -nd, c, nd, 0.5);
    assert!((a - b).abs() <= 1e-5 * b, "{a} vs {b}");
    // Clipped by tilted receivers' horizons: the arc-and-chord contour agrees with the clipped
    // 4096-gon, and with the whole disk where the horizon misses it.
    let tilt = nd.any_orthonormal_vector();
    for (k, (height, lean)) in [(0.7, 1.5), (0.05, 4.0), (0.3, 0.9), (2.0, 0.1)]
        .into_iter()
        .enumerate()
    {
        let p = c + height * nd + 0.2 * tilt;
        let n = (-nd + lean * tilt.cross(nd)).normalize();
        let a = lambert(p, n, &clip(p, n, &poly));
        let b = clipped_disk_irradiance(p, n, c, nd, 0.5);
        assert!(
            (a - b).abs() <= 1e-5 * b.max(1e-3),
            "clipped {k}: {a} vs {b}"
        );
    }
}

#[test]
fn irradiance_matches_closed_forms() {
    let cases = cases();
    let mut jobs = Vec::new();
    for (ci, case) in cases.iter().enumerate() {
        for (pi, r) in receivers(case, ci).into_iter().enumerate() {
            let round = !matches!(case.geometry, Geometry::Polygon(_));
            for (mi, method) in METHODS.into_iter().enumerate() {
                if !(round && mi >= ROUND_METHODS) {
                    jobs.push((ci, pi, r, mi, method));
                }
            }
        }
    }
    assert_eq!(jobs.len(), N_TESTS);
    let zc = critical();
    let results: Vec<(String, f64, bool)> = jobs
        .par_iter()
        .map(|&(ci, pi, r, mi, method)| {
            let case = &cases[ci];
            let seed = 1000 * ci as u32 + 10 * pi as u32 + mi as u32;
            let (mean, se) = estimate(&case.light, &r, method, seed);
            let diff = mean - r.e;
            let ok = diff.abs() <= zc * se + 1e-5 * r.e;
            let z = if se > 0.0 {
                diff / se
            } else if ok {
                0.0
            } else {
                f64::INFINITY
            };
            let line = format!(
                "{} point {pi}{} {method:?}: p {:?} n {:?} E {:.6e} estimate {mean:.6e} (se {se:.2e}, z = {z:.2})",
                case.name,
                if r.clipped { " (clipped)" } else { "" },
                r.p.as_vec3(),
                r.n.as_vec3(),
                r.e
            );
            (line, z, ok)
        })
        .collect();
    let failures: Vec<&String> = results.iter().filter(|r| !r.2).map(|r| &r.0).collect();
    let worst = results
        .iter()
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
        .unwrap();
    eprintln!(
        "{} comparisons, critical |z| {zc:.2}, worst: {}",
        results.len(),
        worst.0
    );
    assert!(
        failures.is_empty(),
        "{} of {} comparisons fail (|z| > {zc:.2}):\n{}",
        failures.len(),
        results.len(),
        failures
            .iter()
            .map(|s| s.as_str())
            .collect::<Vec<_>>()
            .join("\n")
    );
}
