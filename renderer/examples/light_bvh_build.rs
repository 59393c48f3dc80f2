//! Times building the light BVH (`LightBvh::new`) over an emitting UV sphere of about N
//! triangles (default 1,000,000) and prints the time, the node count and a descent's cost.
//! `cargo run --release -p lumis-renderer --example light_bvh_build -- [N]`

use glam::Vec3;
use lumis::geometry::primitive::NONE;
use lumis::lights::{Light, LightBvh, TriangleLight};
use std::time::Instant;

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .map_or(1_000_000, |a| a.parse().expect("N: a number of triangles"));
    // A UV sphere of `rings` × `segments` quads, two triangles each, normals outwards.
    let rings = ((n / 2) as f64).sqrt() as usize;
    let segments = n / 2 / rings.max(1);
    let at = |i: usize, j: usize| {
        let th = std::f32::consts::PI * i as f32 / rings as f32;
        let ph = std::f32::consts::TAU * j as f32 / segments as f32;
        Vec3::new(th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos())
    };
    let mut lights = Vec::with_capacity(2 * rings * segments);
    for i in 0..rings {
        for j in 0..segments {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            for v in [[a, b, c], [a, c, d]] {
                let cr = (v[1] - v[0]).cross(v[2] - v[0]);
                if cr.length() > 0.0 {
                    lights.push(Light::Triangle(TriangleLight {
                        v,
                        n: cr.normalize(),
                        area: 0.5 * cr.length(),
                        le: Vec3::ONE,
                        attr: NONE,
                        texture: NONE,
                    }));
                }
            }
        }
    }
    let t = Instant::now();
    let bvh = LightBvh::new(&lights).expect("the sphere emits");
    let build = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let mut rng = lumis::rng::Rng::new(1, 0, 0);
    let queries = 100_000;
    let mut chosen = 0;
    for _ in 0..queries {
        let p = 3.0 * Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) - 1.5;
        chosen += bvh.sample(p, Vec3::ZERO, rng.next_f32()).is_some() as usize;
    }
    let per = t.elapsed().as_secs_f64() / queries as f64;
    println!(
        "{} triangles: build {build:.3} s, {} nodes, sample {:.2} µs ({chosen} of {queries} chose)",
        lights.len(),
        bvh.nodes().len(),
        per * 1e6
    );
}
