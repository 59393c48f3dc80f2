//! Tests of the light BVH: its pmf is a distribution, `sample` and `pmf` agree bit for bit,
//! choices follow the pmf (χ²), and the edge cases (one light, no power, lights at infinity).

use super::*;
use crate::rng::Rng;
use crate::scene::Scene;
use crate::stats::gamma::chi2_sf;
use crate::stats::selected_lights::{scattered_lights_scene, several_lights_scene};

fn random_receiver(rng: &mut Rng) -> (Vec3, Vec3) {
    let r3 = |rng: &mut Rng| Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
    let p = 10.0 * r3(rng) - 5.0;
    // Every fourth receiver has no normal.
    let n = if rng.next_f32() < 0.25 {
        Vec3::ZERO
    } else {
        (2.0 * r3(rng) - 1.0).normalize_or(Vec3::Z)
    };
    (p, n)
}

fn bvh(scene: &Scene) -> &LightBvh {
    scene.light_bvh.as_ref().expect("a light BVH")
}

/// The leaf masses of a full traversal of the tree at `(p, n)` (the branch probabilities of
/// every interior node, by recursion instead of bit trails) and the mass lost at dead ends
/// (nodes whose children both have importance 0, where `sample` returns `None`).
fn traverse(b: &LightBvh, p: Vec3, n: Vec3, lights: usize) -> (Vec<f64>, f64) {
    fn go(b: &LightBvh, k: usize, mass: f64, p: Vec3, n: Vec3, out: &mut Vec<f64>, dead: &mut f64) {
        let node = &b.nodes()[k];
        if node.leaf {
            if k == 0 && !positive(node.bounds.importance(p, n)) {
                *dead += mass;
            } else {
                out[node.child_or_light as usize] += mass;
            }
            return;
        }
        let c1 = node.child_or_light as usize;
        let w0 = b.nodes()[k + 1].bounds.importance(p, n) as f64;
        let w1 = b.nodes()[c1].bounds.importance(p, n) as f64;
        if (w0 + w1).partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            *dead += mass;
            return;
        }
        go(b, k + 1, mass * w0 / (w0 + w1), p, n, out, dead);
        go(b, c1, mass * w1 / (w0 + w1), p, n, out, dead);
    }
    let mut out = vec![0.0; lights];
    let mut dead = 0.0;
    let p_inf = b.infinite().len() as f64 / (b.infinite().len() as f64 + 1.0);
    for &i in b.infinite() {
        out[i as usize] = p_inf / b.infinite().len() as f64;
    }
    go(b, 0, 1.0 - p_inf, p, n, &mut out, &mut dead);
    (out, dead)
}

/// At 200 random receivers of a 200-light scene with a background (seed 7), pmf(p, n, i) is
/// the mass an independent traversal of the tree gives light i (relative 1e-4: f32 products
/// down ~10 levels against f64), and Σ_i pmf + the dead-end mass = 1 (the pmf is the
/// distribution `sample` draws from, its missing mass exactly where `sample` returns `None`).
/// Catches a branch probability that is not normalised and a trail that leads to the wrong
/// leaf (one light's mass counted twice, another's not at all).
#[test]
fn pmf_is_the_trees_distribution() {
    let scene = scattered_lights_scene(200, 7, true);
    let b = bvh(&scene);
    let mut rng = Rng::new(7, 1, 0);
    let mut max_dead = 0.0f64;
    for _ in 0..200 {
        let (p, n) = random_receiver(&mut rng);
        let (mass, dead) = traverse(b, p, n, scene.lights.len());
        let mut sum = dead;
        for (i, &m) in mass.iter().enumerate() {
            let pmf = b.pmf(p, n, i) as f64;
            assert!(
                (pmf - m).abs() <= 1e-4 * m,
                "light {i}: pmf {pmf}, tree {m} at {p}, {n}"
            );
            sum += pmf;
        }
        assert!(
            (sum - 1.0).abs() < 1e-4,
            "Σ pmf + dead = {sum} at p {p}, n {n}"
        );
        max_dead = max_dead.max(dead);
    }
    eprintln!("largest dead-end mass {max_dead}");
}

/// `sample`'s pmf is `pmf(p, n, i)` of the light it returns, bit for bit, at 20 000 random
/// receivers and uniforms (seed 11) on scenes with and without a background. Catches any
/// difference in how the two compute the branch probabilities (a term only one of them has).
#[test]
fn sample_pmf_is_pmf_bitwise() {
    for background in [false, true] {
        let scene = scattered_lights_scene(300, 11, background);
        let b = bvh(&scene);
        let mut rng = Rng::new(11, 2, 0);
        let mut some = 0;
        for _ in 0..20_000 {
            let (p, n) = random_receiver(&mut rng);
            let u = rng.next_f32();
            if let Some((i, pmf)) = b.sample(p, n, u) {
                assert!(pmf > 0.0);
                assert_eq!(
                    pmf.to_bits(),
                    b.pmf(p, n, i).to_bits(),
                    "light {i} at {p}, {n}"
                );
                some += 1;
            }
        }
        assert!(some > 15_000, "only {some} choices");
    }
}

/// The frequencies of 200 000 choices at a fixed receiver (the origin, normal +z, seed 13)
/// match the pmf: Pearson χ² over the lights with positive pmf (expected counts ≥ 5; the rest
/// pooled), rejected at α = 1e-3. Catches a descent whose rescaled uniform is not uniform (a
/// wrong rescale skews the choices below the first level) and pmfs the choices do not follow.
#[test]
fn choices_follow_the_pmf() {
    for (scene, name) in [
        (several_lights_scene(true), "several"),
        (scattered_lights_scene(60, 13, false), "scattered"),
    ] {
        let b = bvh(&scene);
        let (p, n) = (Vec3::ZERO, Vec3::Z);
        let samples = 200_000;
        let mut counts = vec![0u64; scene.lights.len()];
        let mut rng = Rng::new(13, 3, 0);
        for _ in 0..samples {
            if let Some((i, _)) = b.sample(p, n, rng.next_f32()) {
                counts[i] += 1;
            }
        }
        let (mut chi2, mut dof, mut pooled_obs, mut pooled_exp) = (0.0, 0usize, 0.0, 0.0);
        for (i, &c) in counts.iter().enumerate() {
            let e = samples as f64 * b.pmf(p, n, i) as f64;
            if e == 0.0 {
                assert_eq!(c, 0, "{name}: light {i} of pmf 0 chosen");
            } else if e < 5.0 {
                pooled_obs += c as f64;
                pooled_exp += e;
            } else {
                chi2 += (c as f64 - e).powi(2) / e;
                dof += 1;
            }
        }
        if pooled_exp > 0.0 {
            chi2 += (pooled_obs - pooled_exp).powi(2) / pooled_exp;
            dof += 1;
        }
        let p_value = chi2_sf(chi2, (dof - 1) as f64);
        assert!(
            p_value > 1e-3,
            "{name}: χ² = {chi2}, dof {}, p = {p_value}",
            dof - 1
        );
    }
}

/// A lone light is the root leaf: chosen with probability 1 where it can reach the receiver,
/// never (and pmf 0) where it faces away, as pbrt-v4 treats the root leaf.
#[test]
fn single_light() {
    let scene = Scene::from_json_str(
        r#"{"camera": {"from": [0, -5, 0], "to": [0, 0, 0], "up": [0, 0, 1], "vfov_deg": 40,
            "width": 2, "height": 2},
            "shapes": [{"type": "quad", "corner": [-0.5, -0.5, 1], "edge_u": [0, 1, 0],
            "edge_v": [1, 0, 0], "emission": [1, 1, 1]}]}"#,
    )
    .unwrap();
    let b = bvh(&scene);
    assert_eq!(b.nodes().len(), 1);
    let below = Vec3::new(0.0, 0.0, -1.0);
    assert_eq!(b.sample(below, Vec3::Z, 0.7), Some((0, 1.0)));
    assert_eq!(b.pmf(below, Vec3::Z, 0), 1.0);
    let above = Vec3::new(0.0, 0.0, 3.0);
    assert_eq!(b.sample(above, Vec3::Z, 0.7), None);
    assert_eq!(b.pmf(above, Vec3::Z, 0), 0.0);
}

/// A black emitter is left out (pmf 0, never chosen) beside one with power; a scene whose only
/// emitter is black has no BVH, as it has no power sampler.
#[test]
fn zero_power_light() {
    let quad = |z: f32, e: f32| {
        format!(
            r#"{{"type": "quad", "corner": [-0.5, -0.5, {z}], "edge_u": [0, 1, 0],
            "edge_v": [1, 0, 0], "emission": [{e}, {e}, {e}]}}"#
        )
    };
    let scene_of = |shapes: &str| {
        Scene::from_json_str(&format!(
            r#"{{"camera": {{"from": [0, -5, 0], "to": [0, 0, 0], "up": [0, 0, 1],
            "vfov_deg": 40, "width": 2, "height": 2}}, "shapes": [{shapes}]}}"#
        ))
    };
    // The scene builder drops black emitters, so the lights are made here.
    let quad_light = |z: f32, e: f32| {
        let q = super::super::QuadLight::new(
            Vec3::new(-0.5, -0.5, z),
            Vec3::Y,
            Vec3::X,
            Vec3::splat(e),
        );
        Light::Quad(q.expect("a quad"))
    };
    let lights = [quad_light(1.0, 0.0), quad_light(2.0, 1.0)];
    let b = LightBvh::new(&lights).unwrap();
    let (p, n) = (Vec3::ZERO, Vec3::Z);
    let black = 0;
    assert_eq!(b.pmf(p, n, black), 0.0);
    assert_eq!(b.trail(black), None);
    for k in 0..100 {
        let (i, pmf) = b.sample(p, n, k as f32 / 100.0).unwrap();
        assert_ne!(i, black);
        assert_eq!(pmf, 1.0);
    }
    let dark = scene_of(&quad(1.0, 0.0)).unwrap();
    assert!(dark.light_bvh.is_none() && dark.light_sampler.is_none());
}

/// With a background beside finite lights, the background is chosen with probability 1/2
/// (n_inf / (n_inf + 1)) wherever the receiver is, for u below 1/2 exactly, and the finite
/// lights share the other half.
#[test]
fn infinite_and_finite_mix() {
    let scene = several_lights_scene(true);
    let b = bvh(&scene);
    let bg = scene.background_light.unwrap() as usize;
    assert_eq!(b.infinite(), &[bg as u32]);
    let (p, n) = (Vec3::new(0.1, 0.2, 0.3), Vec3::Z);
    assert_eq!(b.pmf(p, n, bg), 0.5);
    assert_eq!(b.sample(p, n, 0.49), Some((bg, 0.5)));
    let (i, _) = b.sample(p, n, 0.51).unwrap();
    assert_ne!(i, bg);
    let finite: f32 = (0..scene.lights.len())
        .filter(|&i| i != bg)
        .map(|i| b.pmf(p, n, i))
        .sum();
    assert!((finite - 0.5).abs() < 1e-6, "{finite}");
}

/// The tree orders its choices by the receiver: next to one of many equal lights, that light is
/// far likelier than under power selection (which gives each 1/n); catches an importance that
/// ignores distance.
#[test]
fn nearby_light_is_preferred() {
    let scene = scattered_lights_scene(400, 17, false);
    let b = bvh(&scene);
    let Light::Quad(q) = &scene.lights[0] else {
        panic!("light 0 is a quad");
    };
    let c = q.corner + 0.5 * (q.edge_u + q.edge_v);
    let p = c + 0.05 * q.n;
    let power = scene.light_sampler.as_ref().unwrap().pmf(0);
    let near = b.pmf(p, -q.n, 0);
    assert!(near > 4.0 * power, "pmf {near} against power's {power}");
}

/// Every light's trail leads from the root to its own leaf (500 lights, seed 19); catches a
/// trail bit set at the wrong depth or for the wrong child.
#[test]
fn trails_lead_to_their_leaves() {
    let scene = scattered_lights_scene(500, 19, false);
    let b = bvh(&scene);
    for i in 0..scene.lights.len() {
        let mut t = b.trail(i).expect("every light has power");
        let mut k = 0;
        while !b.nodes()[k].leaf {
            k = if t & 1 == 0 {
                k + 1
            } else {
                b.nodes()[k].child_or_light as usize
            };
            t >>= 1;
        }
        assert_eq!(b.nodes()[k].child_or_light as usize, i);
    }
}
