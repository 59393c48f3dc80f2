//! Self-intersection (pbrt-v4's `Triangle.Reintersect`, extended to disks, spheres and
//! cylinders): a ray
//! spawned from a hit point never hits the surface it leaves, for random shapes at random
//! positions and scales from 1e-4 to 1e6, and a shadow ray between points on two surfaces is never
//! blocked by either end. Seeded; every failure prints the shape and the ray.

use glam::Vec3;
use lumis::geometry::cylinder::Cylinder;
use lumis::geometry::disk::Disk;
use lumis::geometry::ray::{spawn_ray, spawn_ray_to};
use lumis::geometry::sphere::Sphere;
use lumis::geometry::triangle::TriangleRay;
use lumis::geometry::{Ray, Shape, ShapeHit, SurfaceHit};
use lumis::math::Frame;
use lumis::rng::Rng;
use lumis::sampling::sphere::sample_uniform_sphere;

/// Shapes per kind, and rays spawned from one hit point on each.
const SHAPES: u32 = 2000;
const RAYS_PER_HIT: u32 = 64;

/// `10^u` for `u` uniform in `[lo, hi)`.
fn log_uniform(rng: &mut Rng, lo: f32, hi: f32) -> f32 {
    10f32.powf(lo + (hi - lo) * rng.next_f32())
}

fn random_dir(rng: &mut Rng) -> Vec3 {
    sample_uniform_sphere(rng.next_2d())
}

/// Whether `t` is the far root of `ray` against `s`, solved in f64 (the ray starts inside, so the
/// near root is negative). Near-tangent chords are ill-conditioned in f32 (`r² − |l|²` cancels),
/// so this only asks that the hit be on the far half of the chord, nowhere near the origin, where
/// a self-hit would be.
fn is_far_side(s: &Sphere, ray: &Ray, t: f32) -> bool {
    let f = (ray.o - s.center).as_dvec3();
    let d = ray.d.as_dvec3();
    let (a, b, c) = (d.dot(d), f.dot(d), f.dot(f) - (s.radius as f64).powi(2));
    let disc = b * b - a * c;
    if c >= 0.0 || disc < 0.0 {
        return false;
    }
    let t_far = (-b + disc.sqrt()) / a;
    (t as f64 - t_far).abs() <= 0.5 * t_far
}

/// [`is_far_side`] for a cylinder's tube: the same question about the ray projected onto the
/// plane perpendicular to the axis.
fn is_far_side_of_tube(c: &Cylinder, ray: &Ray, t: f32) -> bool {
    let z = c.axis.as_dvec3().normalize();
    let flat = |v: glam::DVec3| v - z * z.dot(v);
    let f = flat((ray.o - c.p0).as_dvec3());
    let d = flat(ray.d.as_dvec3());
    let (a, b, cc) = (d.dot(d), f.dot(d), f.dot(f) - (c.radius as f64).powi(2));
    let disc = b * b - a * cc;
    if cc >= 0.0 || disc < 0.0 || a == 0.0 {
        return false;
    }
    let t_far = (-b + disc.sqrt()) / a;
    (t as f64 - t_far).abs() <= 0.5 * t_far
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    Triangle,
    Disk,
    Sphere,
    Cylinder,
}

/// A random shape of `kind` around a random position, with its size, or `None` if degenerate.
fn random_shape(kind: Kind, rng: &mut Rng) -> Option<(Shape, f32)> {
    let size = log_uniform(rng, -4.0, 6.0);
    // Positions up to 1e6 away from the origin, so the size can be far below the position's ulp.
    let center = random_dir(rng) * log_uniform(rng, -4.0, 6.0);
    let shape = match kind {
        Kind::Triangle => Shape::triangle([
            center + size * random_dir(rng),
            center + size * random_dir(rng),
            center + size * random_dir(rng),
        ])?,
        Kind::Disk => Shape::Disk(Disk::new(center, random_dir(rng), size)),
        Kind::Sphere => Shape::Sphere(Sphere::new(center, size)),
        Kind::Cylinder => {
            // At least 2⁻¹⁴ of its distance from the origin (about a thousand ulps of its
            // position): a narrower tube is narrower than the rounding of its own hit points
            // across it, which may put a point beside the wall where it curves away, out of
            // reach of any offset along the normal (a case seen at radius 1e-3, 1e4 away).
            let size = size.max(center.length() * 2f32.powi(-14));
            let axis = random_dir(rng) * size * (0.2 + 4.0 * rng.next_f32());
            Shape::Cylinder(Cylinder {
                p0: center,
                axis,
                u_axis: Frame::from_normal(axis.normalize()).s,
                radius: size * (0.05 + rng.next_f32()),
                flip: rng.next_f32() < 0.5,
            })
        }
    };
    Some((shape, size))
}

/// A random point on `shape` (not uniform by area; that does not matter here).
fn random_point(shape: &Shape, rng: &mut Rng) -> Vec3 {
    match shape {
        Shape::Triangle { v, .. } => {
            let (mut a, mut b) = (rng.next_f32(), rng.next_f32());
            if a + b > 1.0 {
                (a, b) = (1.0 - a, 1.0 - b);
            }
            v[0] + a * (v[1] - v[0]) + b * (v[2] - v[0])
        }
        Shape::Disk(d) => {
            let f = Frame::from_normal(d.n);
            let r = d.radius * rng.next_f32().sqrt();
            let phi = std::f32::consts::TAU * rng.next_f32();
            d.center + f.to_world(Vec3::new(r * phi.cos(), r * phi.sin(), 0.0))
        }
        Shape::Sphere(s) => s.center + s.radius * random_dir(rng),
        Shape::Cylinder(c) => {
            let f = Frame::from_normal(c.axis.normalize());
            let phi = std::f32::consts::TAU * rng.next_f32();
            let radial = f.to_world(Vec3::new(phi.cos(), phi.sin(), 0.0)) * c.radius;
            c.p0 + c.axis * rng.next_f32() + radial
        }
    }
}

fn intersect(shape: &Shape, ray: &Ray) -> Option<ShapeHit> {
    shape.intersect_t(ray, &TriangleRay::new(ray))
}

/// Hits `shape` with a ray aimed from outside at a random point on it.
fn random_hit(shape: &Shape, size: f32, rng: &mut Rng) -> Option<SurfaceHit> {
    let target = random_point(shape, rng);
    let origin = target + random_dir(rng) * size * (0.5 + 10.0 * rng.next_f32());
    let ray = Ray::new(origin, (target - origin).normalize());
    intersect(shape, &ray).map(|h| shape.surface_hit(&ray, h, 0))
}

/// How many hits and spawned rays a run tested, and how many hit points could not be made.
#[derive(Default, Debug)]
struct Counts {
    hits: u32,
    rays: u32,
    shadow_rays: u32,
    no_hit: u32,
}

fn check_kind(kind: Kind, seed: u32) -> Counts {
    let mut counts = Counts::default();
    for i in 0..SHAPES {
        let mut rng = Rng::new(seed, i, 0);
        let Some((shape, size)) = random_shape(kind, &mut rng) else {
            continue;
        };
        let Some(hit) = random_hit(&shape, size, &mut rng) else {
            counts.no_hit += 1;
            continue;
        };
        counts.hits += 1;
        for _ in 0..RAYS_PER_HIT {
            let w = random_dir(&mut rng);
            let ray = spawn_ray(hit.p, hit.p_error, hit.n, w);
            counts.rays += 1;
            let Some(t) = intersect(&shape, &ray).map(|h| h.t) else {
                continue;
            };
            // Only a sphere or a tube can be hit again, on its far side, by a ray heading
            // inwards (a flipped tube's normal points inwards).
            let far_side = match shape {
                Shape::Sphere(s) if w.dot(hit.n) < 0.0 => is_far_side(&s, &ray, t),
                Shape::Cylinder(c) if (w.dot(hit.n) < 0.0) != c.flip => {
                    is_far_side_of_tube(&c, &ray, t)
                }
                _ => false,
            };
            assert!(
                far_side,
                "{kind:?} {i}: ray {ray:?} from {hit:?} re-hit {shape:?} at t = {t}"
            );
        }
        // Shadow rays between this hit and a hit on a second shape of the same kind.
        let Some((other, other_size)) = random_shape(kind, &mut rng) else {
            continue;
        };
        let Some(to) = random_hit(&other, other_size, &mut rng) else {
            continue;
        };
        let d = to.p - hit.p;
        // A sphere legitimately blocks a segment that leaves it inwards; skip those. A tube
        // blocks segments through its inside too, and the two of them may cross: only segments
        // that leave outwards and arrive from outside, with the flip undone.
        let outward = |s: &Shape, n: Vec3| match s {
            Shape::Cylinder(c) if c.flip => -n,
            _ => n,
        };
        if matches!(kind, Kind::Sphere | Kind::Cylinder)
            && (d.dot(outward(&shape, hit.n)) <= 0.0 || d.dot(outward(&other, to.n)) >= 0.0)
        {
            continue;
        }
        let ray = spawn_ray_to(hit.p, hit.p_error, hit.n, to.p, to.p_error, to.n);
        counts.shadow_rays += 1;
        for (end, s) in [("origin", &shape), ("target", &other)] {
            assert!(
                intersect(s, &ray).is_none(),
                "{kind:?} {i}: shadow ray {ray:?} from {hit:?} to {to:?} blocked by its {end} {s:?}"
            );
        }
    }
    eprintln!("{kind:?}: {counts:?}");
    // Aimed rays practically always hit; a low count would mean the test tests little.
    assert!(
        counts.hits > SHAPES * 9 / 10,
        "{kind:?}: only {} of {SHAPES} aimed rays hit",
        counts.hits
    );
    counts
}

#[test]
fn triangles_never_reintersect() {
    check_kind(Kind::Triangle, 1);
}

#[test]
fn disks_never_reintersect() {
    check_kind(Kind::Disk, 2);
}

#[test]
fn spheres_never_reintersect() {
    check_kind(Kind::Sphere, 3);
}

#[test]
fn cylinders_never_reintersect() {
    check_kind(Kind::Cylinder, 4);
}
