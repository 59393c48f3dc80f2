//! Light sampling throughput per shape (triangle, polygon, quad, disk, sphere) and method (area,
//! solid angle, cosine-warped, adaptive, projected solid angle): `Light::sample` from a fixed set of shading points, the first visible surface
//! point of each pixel of a 64×48 view of `assets/plastic_lights.json`, which has one light of each
//! shape (the polygon is a concave 10-vertex star). Points behind a one-sided light are kept: the
//! integrator pays for those calls too. Throughput is in samples.
//!
//! Disks sample their spherical ellipse (issue 20) under `SolidAngle` (and `SolidAngleCosine`,
//! the same for disks, so not measured again) and `Adaptive` where it is large enough, by area
//! elsewhere; `light_pdf/disk/*` measures the MIS pdf of a point on the disk, which for the
//! ellipse builds it and evaluates its solid angle (one `R_F` and one `R_J`) per call. The share
//! of calls that use the ellipse is printed once.
//!
//! `cargo bench -p lumis-renderer --bench lights`

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::{Vec2, Vec3};
use lumis::lights::{Light, LightSampling};
use lumis::rng::Rng;
use lumis::scene::Scene;
use std::hint::black_box;
use std::path::Path;

/// Shading points are taken on this grid of the camera's view.
const GRID: (u32, u32) = (64, 48);

/// One call's inputs.
struct Input {
    p: Vec3,
    /// The hit's geometric normal, facing the camera (the receiver normal of the cosine warp and
    /// of projected-solid-angle sampling).
    ns: Vec3,
    u: Vec2,
}

fn load_scene() -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/plastic_lights.json");
    Scene::load(&path).expect("plastic_lights.json loads")
}

/// The first hit of a camera ray through each grid cell, with a fixed random pair each.
fn inputs(scene: &Scene) -> Vec<Input> {
    let cam = &scene.camera;
    let (sx, sy) = (
        cam.width as f32 / GRID.0 as f32,
        cam.height as f32 / GRID.1 as f32,
    );
    let mut out = Vec::new();
    for y in 0..GRID.1 {
        for x in 0..GRID.0 {
            let ray = cam.ray((x as f32 + 0.5) * sx, (y as f32 + 0.5) * sy);
            if let Some(hit) = scene.accel.intersect(&ray) {
                let mut rng = Rng::new(5, y * GRID.0 + x, 0);
                let ns = if hit.n.dot(ray.d) < 0.0 {
                    hit.n
                } else {
                    -hit.n
                };
                out.push(Input {
                    p: hit.p,
                    ns,
                    u: rng.next_2d(),
                });
            }
        }
    }
    out
}

/// The scene's first light of each shape.
fn lights(scene: &Scene) -> Vec<(&'static str, &Light)> {
    // Area lights only: the others are not shapes.
    let kind = |l: &Light| (!l.is_infinite() && !l.is_delta()).then(|| l.kind_name());
    let mut out: Vec<(&'static str, &Light)> = Vec::new();
    for l in &scene.lights {
        if let Some(k) = kind(l)
            && !out.iter().any(|(name, _)| *name == k)
        {
            out.push((k, l));
        }
    }
    assert_eq!(
        out.len(),
        5,
        "plastic_lights.json has one light of every shape"
    );
    out
}

fn light_sampling(c: &mut Criterion) {
    let scene = load_scene();
    let inputs = inputs(&scene);
    let mut group = c.benchmark_group("light_sample");
    group.throughput(Throughput::Elements(inputs.len() as u64));
    for (shape, light) in lights(&scene) {
        for (method_name, method) in [
            ("area", LightSampling::Area),
            ("solid_angle", LightSampling::SolidAngle),
            ("solid_angle_cosine", LightSampling::SolidAngleCosine),
            ("adaptive", LightSampling::Adaptive),
            ("projected_solid_angle", LightSampling::ProjectedSolidAngle),
        ] {
            // The cosine warp does not change disks; spheres are neither warped, adaptive nor
            // projected.
            let planar_only = matches!(
                method,
                LightSampling::SolidAngleCosine
                    | LightSampling::Adaptive
                    | LightSampling::ProjectedSolidAngle
            );
            if (shape == "disk" && method == LightSampling::SolidAngleCosine)
                || (shape == "sphere" && planar_only)
            {
                continue;
            }
            group.bench_function(format!("{shape}/{method_name}"), |b| {
                b.iter(|| {
                    inputs.iter().fold(0.0f32, |acc, x| {
                        match light.sample(black_box(x.p), x.ns, x.u, method) {
                            Some(s) => acc + s.pdf,
                            None => acc,
                        }
                    })
                })
            });
        }
    }
    group.finish();
}

/// The MIS pdf of the disk light at its centre from every shading point, by area and by the
/// spherical ellipse.
fn disk_pdf(c: &mut Criterion) {
    let scene = load_scene();
    let inputs = inputs(&scene);
    let (_, light) = lights(&scene)
        .into_iter()
        .find(|(k, _)| *k == "disk")
        .expect("a disk");
    let Light::Disk(d) = light else {
        unreachable!("a disk")
    };
    let (y, ny) = (d.disk.center, d.disk.n);
    let ellipse = inputs
        .iter()
        .filter(|x| lumis::sampling::SphericalEllipse::new(x.p, y, ny, d.disk.radius).is_some())
        .count();
    eprintln!(
        "disk: {ellipse} of {} shading points sample the spherical ellipse",
        inputs.len()
    );
    let mut group = c.benchmark_group("light_pdf");
    group.throughput(Throughput::Elements(inputs.len() as u64));
    for (method_name, method) in [
        ("area", LightSampling::Area),
        ("solid_angle", LightSampling::SolidAngle),
    ] {
        group.bench_function(format!("disk/{method_name}"), |b| {
            b.iter(|| {
                inputs.iter().fold(0.0f32, |acc, x| {
                    let wi = (y - x.p).normalize();
                    acc + light.pdf(black_box(x.p), x.ns, wi, y, ny, method)
                })
            })
        });
    }
    group.finish();
}

criterion_group!(benches, light_sampling, disk_pdf);
criterion_main!(benches);
