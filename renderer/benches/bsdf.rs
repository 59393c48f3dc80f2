//! BSDF throughput: `eval`, `pdf` and `sample` of the diffuse, GGX conductor (α 0.05 and 0.5) and
//! plastic materials through the `Material` enum, as the integrator calls them, over a fixed set of
//! local-frame directions and random numbers. Throughput is in calls. Also the rough plastic's
//! coat-albedo table build (`CoatAlbedo::new`), which the viewer's roughness slider repeats per
//! change: its budget is 10 ms (one 60 Hz frame minus the render's share).
//!
//! `cargo bench -p lumis-renderer --bench bsdf`

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::{Vec2, Vec3};
use lumis::materials::coat_albedo::CoatAlbedo;
use lumis::materials::{Conductor, ConductorFresnel, Diffuse, Material, Microfacet, Plastic};
use lumis::rng::Rng;
use lumis::sampling::sample_uniform_hemisphere;
use std::hint::black_box;

/// Inputs per iteration: enough to average over directions, small enough to stay in L1/L2.
const N: u32 = 4096;

/// One call's inputs: viewer and light directions in the local frame (upper hemisphere), and the
/// random numbers `sample` takes.
struct Input {
    wo: Vec3,
    wi: Vec3,
    u_lobe: f32,
    u: Vec2,
}

fn inputs() -> Vec<Input> {
    (0..N)
        .map(|i| {
            let mut rng = Rng::new(11, i, 0);
            Input {
                wo: sample_uniform_hemisphere(rng.next_2d()),
                wi: sample_uniform_hemisphere(rng.next_2d()),
                u_lobe: rng.next_f32(),
                u: rng.next_2d(),
            }
        })
        .collect()
}

fn materials() -> Vec<(&'static str, Material)> {
    // Copper's complex IOR at roughly R, G, B wavelengths: the costlier Fresnel of the two forms.
    let copper = ConductorFresnel::Complex {
        eta: Vec3::new(0.200, 0.924, 1.102),
        k: Vec3::new(3.912, 2.452, 2.142),
        tint: Vec3::ONE,
    };
    vec![
        (
            "diffuse",
            Material::Diffuse(Diffuse {
                albedo: Vec3::splat(0.7),
            }),
        ),
        (
            "conductor_a0.05",
            Material::Conductor(Conductor {
                microfacet: Microfacet::ggx(0.05),
                fresnel: copper,
            }),
        ),
        (
            "conductor_a0.5",
            Material::Conductor(Conductor {
                microfacet: Microfacet::ggx(0.5),
                fresnel: copper,
            }),
        ),
        (
            "plastic_a0.2",
            Material::Plastic(Plastic::new(Vec3::new(0.7, 0.1, 0.1), 0.2, 1.5, Vec3::ONE)),
        ),
    ]
}

fn bsdf(c: &mut Criterion) {
    let inputs = inputs();
    let mut group = c.benchmark_group("bsdf");
    group.throughput(Throughput::Elements(inputs.len() as u64));
    for (name, m) in materials() {
        group.bench_function(format!("eval/{name}"), |b| {
            b.iter(|| {
                inputs
                    .iter()
                    .fold(Vec3::ZERO, |acc, x| acc + m.eval(black_box(x.wo), x.wi))
            })
        });
        group.bench_function(format!("pdf/{name}"), |b| {
            b.iter(|| {
                inputs
                    .iter()
                    .map(|x| m.pdf(black_box(x.wo), x.wi))
                    .sum::<f32>()
            })
        });
        group.bench_function(format!("sample/{name}"), |b| {
            b.iter(|| {
                inputs.iter().fold(Vec3::ZERO, |acc, x| {
                    match m.sample(black_box(x.wo), x.u_lobe, x.u) {
                        Some(s) => acc + s.weight,
                        None => acc,
                    }
                })
            })
        });
    }
    group.finish();
}

/// One table build per iteration, at a few rough coats (a smooth one, α ≈ 0, skips the quadrature
/// and is not measured).
fn coat_albedo(c: &mut Criterion) {
    let mut group = c.benchmark_group("coat_albedo");
    for alpha in [0.05f32, 0.3, 1.0] {
        group.bench_function(format!("new/a{alpha}"), |b| {
            b.iter(|| CoatAlbedo::new(black_box(alpha), black_box(0.04)))
        });
    }
    group.finish();
}

criterion_group!(benches, bsdf, coat_albedo);
criterion_main!(benches);
