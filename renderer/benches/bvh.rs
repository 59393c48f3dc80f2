//! BVH throughput on `assets/seed_cornell.json`: closest hit and any hit for coherent rays (one
//! camera ray through each pixel centre, in scanline order) and incoherent rays (uniform origins
//! inside the scene's bounds, uniform directions). Throughput is in rays, so criterion's
//! `Melem/s` reads as Mrays/s.
//!
//! Any hit is measured twice: with unbounded rays, which in a closed box stop at the first blocker
//! found, and with `t_max` just short of the closest hit, which nothing blocks, so the whole
//! traversal runs, as for a shadow ray that reaches its light.
//!
//! `cargo bench -p lumis-renderer --bench bvh`

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::{Vec2, Vec3};
use lumis::geometry::Ray;
use lumis::rng::Rng;
use lumis::sampling::sample_uniform_sphere;
use lumis::scene::Scene;
use std::hint::black_box;
use std::path::Path;

fn load_cornell() -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/seed_cornell.json");
    Scene::load(&path).expect("seed_cornell.json loads")
}

/// One ray through each pixel centre, row by row.
fn camera_rays(scene: &Scene) -> Vec<Ray> {
    let (w, h) = (scene.camera.width, scene.camera.height);
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| scene.camera.ray(x as f32 + 0.5, y as f32 + 0.5))
        .collect()
}

/// `n` rays from uniform points inside the scene's bounds in uniform directions (fixed seed).
fn random_rays(scene: &Scene, n: u32) -> Vec<Ray> {
    let (lo, hi) = scene.accel.bounds();
    // Slightly inside, so no origin lies on an outer wall.
    let (lo, hi) = (lo + 0.01 * (hi - lo), hi - 0.01 * (hi - lo));
    (0..n)
        .map(|i| {
            let mut rng = Rng::new(7, i, 0);
            let o = lo + (hi - lo) * Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
            let d = sample_uniform_sphere(Vec2::new(rng.next_f32(), rng.next_f32()));
            Ray::new(o, d)
        })
        .collect()
}

/// The same rays shortened to just before their closest hit (unchanged where they miss).
fn short_of_hit(scene: &Scene, rays: &[Ray]) -> Vec<Ray> {
    rays.iter()
        .map(|r| match scene.accel.intersect(r) {
            Some(hit) => Ray {
                t_max: hit.t * 0.999,
                ..*r
            },
            None => *r,
        })
        .collect()
}

fn bvh(c: &mut Criterion) {
    let scene = load_cornell();
    let coherent = camera_rays(&scene);
    let incoherent = random_rays(&scene, coherent.len() as u32);
    let sets = [
        ("coherent", coherent.as_slice()),
        ("incoherent", incoherent.as_slice()),
    ];

    let mut group = c.benchmark_group("bvh");
    // Every iteration traces a whole set (65k rays, several ms), so fewer samples suffice.
    group.sample_size(20);
    for (name, rays) in sets {
        let shadow = short_of_hit(&scene, rays);
        group.throughput(Throughput::Elements(rays.len() as u64));
        group.bench_function(format!("closest_hit/{name}"), |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| scene.accel.intersect(black_box(r)).is_some())
                    .count()
            })
        });
        group.bench_function(format!("any_hit_unbounded/{name}"), |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| scene.accel.occluded(black_box(r)))
                    .count()
            })
        });
        group.bench_function(format!("any_hit_unblocked/{name}"), |b| {
            b.iter(|| {
                shadow
                    .iter()
                    .filter(|r| scene.accel.occluded(black_box(r)))
                    .count()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bvh);
criterion_main!(benches);
