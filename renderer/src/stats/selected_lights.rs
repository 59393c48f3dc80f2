//! Adapter: light selection composed with light sampling, as next-event estimation draws a
//! direction (one uniform chooses the light, two sample it), with the density of any direction
//! `Σ_l pmf(l | p, n) · pdf_l(w)` over every light the ray from `p` crosses (occlusion ignored:
//! the sampler does not trace shadow rays either). Also the scenes of several lights the light
//! selection tests use.

use super::sampler::{DirectionSample, DirectionalSampler};
use crate::geometry::ray::{Ray, spawn_ray};
use crate::lights::{LightSampling, LightSelection};
use crate::rng::Rng;
use crate::scene::{Scene, parse_scene};
use glam::{Vec2, Vec3};
use serde_json::{Value, json};
use std::sync::Arc;

/// `scene.select_light` then `scene.sample_light` from `p` (shading normal `ns`) as a
/// direction sampler.
#[derive(Clone)]
pub struct SelectedLightDirections {
    /// The lights (and nothing else: every surface is a light here).
    pub scene: Arc<Scene>,
    /// The selection rule.
    pub selection: LightSelection,
    /// The receiver.
    pub p: Vec3,
    /// The receiver's shading normal (zero: none).
    pub ns: Vec3,
    /// How each light is sampled.
    pub method: LightSampling,
}

impl DirectionalSampler for SelectedLightDirections {
    fn sample(&self, u1: f32, u: Vec2) -> Option<DirectionSample> {
        let (i, pmf) = self
            .scene
            .select_light(self.selection, self.p, self.ns, u1)?;
        let s = self
            .scene
            .sample_light(i, self.p, self.ns, u, self.method)?;
        // The chosen light's share from the sampler's own pmf, the other lights' from
        // `light_pmf`: the harness compares this with `pdf`, which checks the sampler's pmf
        // against `light_pmf` (the lights at infinity share every direction with the others).
        Some(DirectionSample {
            w: s.wi,
            pdf: pmf * s.pdf + self.density(s.wi, Some(i)),
            delta: false,
        })
    }

    fn pdf(&self, w: Vec3) -> f32 {
        self.density(w, None)
    }
}

impl SelectedLightDirections {
    /// `Σ_l pmf(l) · pdf_l(w)` over the lights but `skip`.
    fn density(&self, w: Vec3, skip: Option<usize>) -> f32 {
        let scene = &self.scene;
        let mut pdf = 0.0;
        for (i, l) in scene.lights.iter().enumerate() {
            if l.is_infinite() && Some(i) != skip {
                let pmf = scene.light_pmf(self.selection, self.p, self.ns, i);
                pdf += pmf * l.pdf(self.p, self.ns, w, Vec3::ZERO, Vec3::ZERO, self.method);
            }
        }
        // Every light the ray crosses, front-facing (one-sided lights sample only from there).
        let mut ray = Ray::new(self.p, w);
        // A ray crosses each primitive at most twice (spheres); more means it is stuck.
        for _ in 0..2 * scene.accel.primitives().len() + 1 {
            let Some(hit) = scene.accel.intersect(&ray) else {
                break;
            };
            let light = scene.accel.primitives()[hit.prim as usize].light;
            if light != crate::geometry::primitive::NONE && Some(light as usize) != skip {
                let l = &scene.lights[light as usize];
                if l.radiance(hit.n, w) != Vec3::ZERO {
                    let pmf = scene.light_pmf(self.selection, self.p, self.ns, light as usize);
                    pdf += pmf * l.pdf(self.p, self.ns, w, hit.p, hit.n, self.method);
                }
            }
            ray = spawn_ray(hit.p, hit.p_error, hit.n, w);
        }
        pdf
    }
}

fn v(p: Vec3) -> Value {
    json!([p.x, p.y, p.z])
}

/// A quad centred at `c` facing `n` with side `size`, emitting `e`.
fn quad(c: Vec3, n: Vec3, size: f32, e: f32) -> Value {
    let f = crate::math::Frame::from_normal(n.normalize());
    let (u, w) = (size * f.s, size * f.t);
    json!({"type": "quad", "corner": v(c - 0.5 * u - 0.5 * w), "edge_u": v(u), "edge_v": v(w),
        "emission": [e, e, e]})
}

fn scene_of(shapes: Vec<Value>, background: Option<f32>) -> Arc<Scene> {
    let mut scene = json!({
        "camera": {"from": [0, -5, 0], "to": [0, 0, 0], "up": [0, 0, 1], "vfov_deg": 40,
            "width": 2, "height": 2},
        "shapes": shapes,
    });
    if let Some(b) = background {
        scene["background"] = json!([b, b, b]);
    }
    let desc = parse_scene(&scene.to_string()).unwrap_or_else(|e| panic!("{e}"));
    Arc::new(Scene::from_desc(&desc).unwrap_or_else(|e| panic!("{e}")))
}

/// Five lights about a receiver at the origin with normal +z, of different kinds, sizes,
/// powers, orientations and distances: a small bright quad overhead, a large dim disk far off
/// to the side and tilted, a sphere, a triangle facing away (never sampled: the BVH's
/// orientation bound gives it no share, power selection wastes its share), and a quad below the
/// receiver's plane facing it (only a transmitting receiver sees it; its share shows whether
/// the normal term is |cos|). With `background`, a constant background too.
pub fn several_lights_scene(background: bool) -> Arc<Scene> {
    let disk_n = Vec3::new(1.0, 0.2, -0.4).normalize();
    let shapes = vec![
        quad(Vec3::new(0.3, 0.2, 1.5), -Vec3::Z, 0.6, 8.0),
        json!({"type": "disk", "center": [-6.0, 1.0, 3.0], "normal": v(disk_n), "radius": 2.0,
            "emission": [0.5, 0.5, 0.5]}),
        json!({"type": "sphere", "center": [1.5, -2.0, 1.0], "radius": 0.5,
            "emission": [2.0, 2.0, 2.0]}),
        json!({"type": "triangles", "positions": [[2.0, 2.0, 0.2], [3.0, 2.5, 0.4],
            [2.5, 3.0, 0.3]], "indices": [[0, 2, 1]], "emission": [3.0, 3.0, 3.0]}),
        quad(Vec3::new(0.0, 0.5, -1.5), Vec3::Z, 1.0, 1.0),
    ];
    scene_of(shapes, background.then_some(0.05))
}

/// `n` emitters (quads, disks, spheres, triangles, in turn) scattered in `[−4, 4]³` with random
/// sizes, orientations and radiances, seeded by `seed`; with a constant background when
/// `background`. A many-light scene for the selection tests and the GPU parity.
pub fn scattered_lights_scene(n: usize, seed: u32, background: bool) -> Arc<Scene> {
    let mut rng = Rng::new(seed, 0, 0);
    let r3 = |rng: &mut Rng| Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
    let shapes = (0..n)
        .map(|k| {
            let c = 8.0 * r3(&mut rng) - 4.0;
            let dir = (2.0 * r3(&mut rng) - 1.0).normalize_or(Vec3::Z);
            let size = 0.05 + 0.5 * rng.next_f32();
            let e = 0.1 + 4.0 * rng.next_f32();
            match k % 4 {
                0 => quad(c, dir, size, e),
                1 => json!({"type": "disk", "center": v(c), "normal": v(dir), "radius": size,
                    "emission": [e, e, e]}),
                2 => json!({"type": "sphere", "center": v(c), "radius": 0.5 * size,
                    "emission": [e, e, e]}),
                _ => {
                    let f = crate::math::Frame::from_normal(dir);
                    let (a, b) = (c + size * f.s, c + size * f.t);
                    json!({"type": "triangles", "positions": [v(c), v(a), v(b)],
                        "indices": [[0, 1, 2]], "emission": [e, e, e]})
                }
            }
        })
        .collect();
    scene_of(shapes, background.then_some(0.2))
}
