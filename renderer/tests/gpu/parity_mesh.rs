//! Mesh vertex attributes on the GPU (issue 17, item 7): the WGSL twins of
//! `MeshAttributes::shading_normal` and `MeshAttributes::uv` (`geometry/mesh_attributes.wgsl`) against the
//! Rust functions on many (attr, b) inputs, degenerate ones included; hit barycentrics and
//! primitives' attribute indices against the CPU's; and a mesh with vertex normals rendered on
//! the GPU against the CPU's render, by the block z-test of `renderer/tests/gpu/images.rs` and by the same
//! random streams giving the same image.
//!
//! Tolerances. Vulkan rounds f32 addition, subtraction and multiplication correctly but lets a
//! compiler fuse a product into an addition (FMA), sums a `dot` in any order, and allows 2.5 ulp
//! for a division and about 3 for a square root. The interpolated sum `w0·n0 + b1·n1 + b2·n2`
//! therefore agrees to 2·3u·Σ|wᵢ||nᵢ| per component (u = 2⁻²⁴, both sides' rounding), and the
//! normalised result to that over |sum| plus the normalisation's ≈ 8u on each side: a relative
//! tolerance of 16u and a conditioning term 8u·κ, κ = Σ|wᵢ||nᵢ| / |sum| (1 for equal normals,
//! large where they nearly cancel). Everything else (the fallbacks, NONE, the flags, whether a
//! normal is found) must agree exactly.

use crate::gpu_common;
use glam::{Vec2, Vec3};
use gpu_common::images::{cpu_render, decide_gpu_vs_cpu, gpu_render};
use gpu_common::{Compare, context};
use lumis::geometry::Ray;
use lumis::geometry::mesh_attributes::{
    AttrMesh, AttrTriangle, HAS_NORMALS, HAS_UVS, MeshAttributes,
};
use lumis::geometry::primitive::NONE;
use lumis::gpu::GpuScene;
use lumis::gpu::kernel::run_snippet;
use lumis::integrator::{Heuristic, Settings, Strategy};
use lumis::lights::LightSampling;
use lumis::rng::Rng;
use lumis::sampling::sample_uniform_sphere;
use lumis::scene::mesh::{MeshData, obj};
use lumis::scene::{Scene, parse_scene};
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

/// f32's unit roundoff, 2⁻²⁴.
const U: f32 = f32::EPSILON / 2.0;

/// Relative tolerance of a shading normal or UV (module doc).
const RTOL: f32 = 16.0 * U;

fn f4(v: Vec3, w: f32) -> [f32; 4] {
    [v.x, v.y, v.z, w]
}

fn run(gpu: &GpuScene, body: &str, inputs: &[[f32; 4]], ins: usize, outs: usize) -> Vec<[f32; 4]> {
    run_snippet(gpu, &Settings::default(), body, inputs, ins, outs)
        .unwrap_or_else(|e| panic!("{e}"))
}

fn unit(r: &mut Rng) -> Vec3 {
    sample_uniform_sphere(r.next_2d())
}

/// Barycentrics (b1, b2) of item `k`: the vertices and an edge midpoint in turn, else uniform in
/// the triangle.
fn barycentrics(k: usize, r: &mut Rng) -> Vec2 {
    match k % 16 {
        0 => Vec2::ZERO,
        1 => Vec2::X,
        2 => Vec2::Y,
        3 => Vec2::new(0.5, 0.0),
        4 => Vec2::new(0.5, 0.5),
        _ => {
            let u = r.next_2d();
            if u.x + u.y > 1.0 {
                Vec2::new(1.0 - u.x, 1.0 - u.y)
            } else {
                u
            }
        }
    }
}

/// Vertices `VERTS` per mesh; mesh 0 normals and UVs, 1 normals only (with the special vertices
/// of [`special_normals`] first), 2 UVs only, 3 neither.
const VERTS: u32 = 64;

/// Normals that cancel or are no direction: opposite pairs (X, −X: cancel exactly at b = (½, 0)
/// with v = [0, 1, 0]), zero, tiny (squared length 1e-24, under the 1e-20 floor), huge (squared
/// length overflows), NaN, infinite, and one not of unit length.
fn special_normals() -> Vec<Vec3> {
    vec![
        Vec3::X,
        -Vec3::X,
        Vec3::ZERO,
        Vec3::splat(1e-12),
        Vec3::splat(1e30),
        Vec3::new(f32::NAN, 0.0, 1.0),
        Vec3::new(f32::INFINITY, 0.0, 0.0),
        Vec3::new(0.0, 3.0, 4.0),
    ]
}

/// Hand-made attributes exercising every branch of `shading_normal` and `uv`.
fn synthetic_attributes(r: &mut Rng) -> MeshAttributes {
    let mut a = MeshAttributes::default();
    let flags = [HAS_NORMALS | HAS_UVS, HAS_NORMALS, HAS_UVS, 0];
    for (m, &f) in flags.iter().enumerate() {
        a.meshes.push(AttrMesh {
            normal_base: a.normals.len() as u32,
            uv_base: a.uvs.len() as u32,
            flags: f,
            named: lumis::geometry::primitive::NONE,
        });
        if f & HAS_NORMALS != 0 {
            let mut n: Vec<Vec3> = if m == 1 {
                special_normals()
            } else {
                Vec::new()
            };
            while n.len() < VERTS as usize {
                n.push(unit(r));
            }
            a.normals.extend(n);
        }
        if f & HAS_UVS != 0 {
            a.uvs.extend((0..VERTS).map(|_| r.next_2d() * 4.0 - 1.0));
        }
        // Triangles: every pair of special vertices with a random third, then random ones.
        let mut tris: Vec<[u32; 3]> = Vec::new();
        if m == 1 {
            let s = special_normals().len() as u32;
            for i in 0..s {
                for j in 0..s {
                    tris.push([i, j, s + (i * s + j) % (VERTS - s)]);
                }
            }
            tris.push([0, 1, 0]);
        }
        while tris.len() < 200 {
            let mut v = || (r.next_f32() * VERTS as f32) as u32 % VERTS;
            tris.push([v(), v(), v()]);
        }
        a.triangles
            .extend(tris.into_iter().map(|v| AttrTriangle { v, mesh: m as u32 }));
    }
    a
}

/// `shading_normal`'s interpolated sum Σ wᵢnᵢ (in f64) and its conditioning
/// κ = Σ|wᵢ||nᵢ| / |Σ wᵢnᵢ|, for a triangle with vertex normals.
fn interpolation(a: &MeshAttributes, attr: u32, b: Vec2) -> (glam::DVec3, f64) {
    let t = &a.triangles[attr as usize];
    let base = a.meshes[t.mesh as usize].normal_base;
    let n = t.v.map(|i| a.normals[(base + i) as usize].as_dvec3());
    let w = [1.0 - b.x - b.y, b.x, b.y].map(f64::from);
    let sum: glam::DVec3 = (0..3).map(|i| w[i] * n[i]).sum();
    let abs: f64 = (0..3).map(|i| w[i].abs() * n[i].abs().max_element()).sum();
    (sum, abs / sum.length())
}

/// Same for `uv`, per component.
fn uv_conditioning(a: &MeshAttributes, attr: u32, b: Vec2) -> f32 {
    let t = &a.triangles[attr as usize];
    let base = a.meshes[t.mesh as usize].uv_base;
    let w = [1.0 - b.x - b.y, b.x, b.y];
    (0..3)
        .map(|i| w[i].abs() * a.uvs[(base + t.v[i]) as usize].abs().max_element())
        .sum()
}

/// The WGSL item body: inputs (bits of attr, b1, b2, _), (ng, _); outputs (shading normal, found),
/// (uv, _, _).
const ATTR_BODY: &str = "let a = inp(0u);
    let attr = bitcast<u32>(a.x);
    let s = shading_normal(attr, a.yz, inp(1u).xyz);
    outp(0u, vec4f(s.n, select(0.0, 1.0, s.found)));
    outp(1u, vec4f(mesh_uv(attr, a.yz), 0.0, 0.0));";

/// `shading_normal` and `uv` on 16k (attr, b, ng): random triangles of the four kinds of mesh,
/// every pair of degenerate normals, NONE; ng sometimes exactly opposite to the interpolated
/// normal (so it must be turned) and sometimes perpendicular to it.
#[test]
fn shading_normals_and_uvs_match() {
    let Some(ctx) = context() else {
        return;
    };
    let mut r = Rng::new(17, 7, 0);
    let mut scene = Scene::from_desc(&parse_scene(LIT_QUAD).unwrap()).unwrap();
    scene.attributes = synthetic_attributes(&mut r);
    let scene = Arc::new(scene);
    let gpu = GpuScene::new(ctx, scene.clone()).unwrap();
    let a = &scene.attributes;
    let n_tris = a.triangles.len() as u32;
    // The special triangles of mesh 1 (after mesh 0's 200) at every special barycentric point
    // and a few random ones, then random triangles; one item in 32 NONE.
    let special = special_normals().len() as u32;
    let special = 200..200 + special * special + 1;
    let mut items = Vec::new();
    for k in 0..16384 {
        let (attr, b) = if k < 8 * special.len() {
            (special.start + (k / 8) as u32, barycentrics(k % 8, &mut r))
        } else if k % 32 == 31 {
            (NONE, barycentrics(k, &mut r))
        } else {
            let t = (r.next_f32() * n_tris as f32) as u32 % n_tris;
            (t, barycentrics(k, &mut r))
        };
        let mut ng = unit(&mut r);
        if attr != NONE
            && k % 5 == 0
            && let Some(ns) = a.shading_normal(attr, b, ng)
        {
            // ng opposite to the normal (turned from one side to the other), or (k % 10 == 5)
            // perpendicular to it.
            ng = if k % 10 == 0 {
                -ns
            } else {
                ns.any_orthonormal_vector()
            };
        }
        items.push((attr, b, ng));
    }
    let inputs: Vec<[f32; 4]> = items
        .iter()
        .flat_map(|&(attr, b, ng)| [[f32::from_bits(attr), b.x, b.y, 0.0], f4(ng, 0.0)])
        .collect();
    let out = run(&gpu, ATTR_BODY, &inputs, 2, 2);
    let mut normal = Compare::new("shading normal", RTOL, 0.0);
    let mut found = Compare::new("normal found", 0.0, 0.0);
    let mut fallback = Compare::new("geometric fallback", 0.0, 0.0);
    let mut uv = Compare::new("uv", RTOL, 0.0);
    let (mut with_normal, mut exact, mut fallbacks, mut turned, mut ambiguous) = (0, 0, 0, 0, 0);
    for (&(attr, b, ng), o) in items.iter().zip(out.chunks(2)) {
        let what = format!("attr {attr} b {b} ng {ng}");
        let want = a.shading_normal(attr, b, ng);
        found.scalar(o[0][3], want.is_some() as u32 as f32, &what);
        let got = Vec3::new(o[0][0], o[0][1], o[0][2]);
        let Some(mut w) = want else {
            fallback.v3(o[0], ng, &format!("{what}: no normal, ng"));
            compare_uv(&mut uv, a, attr, b, o[1], &what);
            continue;
        };
        with_normal += 1;
        if got.to_array().map(f32::to_bits) == w.to_array().map(f32::to_bits) {
            exact += 1;
        }
        let (sum, kappa) = interpolation(a, attr, b);
        let len2 = sum.length_squared();
        let borderline = (1e-21..1e-19).contains(&len2) || (1e37..1e39).contains(&len2);
        assert!(
            !borderline,
            "{what}: squared length {len2:e} near a threshold"
        );
        if !(len2 > 1e-20 && len2 < f32::MAX as f64) {
            // Not a direction (tiny, overflowing or NaN, far from the thresholds): the geometric
            // fallback, exactly ng on both sides.
            fallbacks += 1;
            assert_eq!(w, ng, "{what}: the CPU's fallback");
            fallback.v3(o[0], ng, &what);
        } else {
            // Which way an interpolation nearly perpendicular to ng is turned is decided by the
            // sign of a dot product that rounding may flip: either is right there.
            let raw = (sum / sum.length()).as_vec3();
            if raw.dot(ng).abs() <= 4.0 * RTOL * kappa as f32 {
                ambiguous += 1;
                if got.dot(w) < 0.0 {
                    w = -w;
                }
            } else if raw.dot(ng) < 0.0 {
                turned += 1;
            }
            normal.v3_conditioned(o[0], w, 8.0 * U * kappa as f32, &what);
        }
        compare_uv(&mut uv, a, attr, b, o[1], &what);
    }
    eprintln!(
        "{} items: {with_normal} with a normal ({exact} bit-exact), {fallbacks} geometric \
         fallbacks, {turned} turned to ng's side, {ambiguous} nearly perpendicular to ng",
        items.len()
    );
    assert!(
        fallbacks >= 100,
        "the degenerate cases were not reached: {fallbacks}"
    );
    assert!(turned >= 1000, "few normals turned: {turned}");
    found.finish(0);
    fallback.finish(0);
    normal.finish(0);
    uv.finish(0);
}

/// Compares a GPU UV with `MeshAttributes::uv`: Σ wᵢtᵢ agrees to 2·3u·Σ|wᵢ||tᵢ| (module doc),
/// `b` itself exactly.
fn compare_uv(uv: &mut Compare, a: &MeshAttributes, attr: u32, b: Vec2, got: [f32; 4], what: &str) {
    let want = a.uv(attr, b);
    let extra = if attr == NONE
        || a.meshes[a.triangles[attr as usize].mesh as usize].flags & HAS_UVS == 0
    {
        0.0
    } else {
        6.0 * U * uv_conditioning(a, attr, b)
    };
    uv.scalar_conditioned(got[0], want.x, extra, what);
    uv.scalar_conditioned(got[1], want.y, extra, what);
}

/// A lit quad and a disk: a scene for kernels whose attributes a test replaces.
const LIT_QUAD: &str = r#"{
  "camera": {"from": [0, 1, -3], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40, "width": 4, "height": 4},
  "shapes": [
    {"type": "quad", "corner": [-1, 0, -1], "edge_u": [0, 0, 2], "edge_v": [2, 0, 0]},
    {"type": "disk", "center": [0, 2, 0], "normal": [0, -1, 0], "radius": 0.5, "emission": [4, 4, 4]}
  ]
}"#;

/// A UV sphere of `rings` × `segments` quads (split in two triangles) around the origin, radius
/// 1, wound outward, with its exact unit normals as vertex normals and (segment, ring) fractions
/// as UVs.
fn smooth_sphere(rings: u32, segments: u32) -> MeshData {
    let mut m = MeshData {
        normals: Some(Vec::new()),
        uvs: Some(Vec::new()),
        ..MeshData::default()
    };
    for i in 0..=rings {
        let theta = std::f32::consts::PI * i as f32 / rings as f32;
        for j in 0..=segments {
            let phi = std::f32::consts::TAU * j as f32 / segments as f32;
            let p = Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            );
            m.positions.push(p);
            m.normals.as_mut().unwrap().push(p.normalize());
            m.uvs.as_mut().unwrap().push(Vec2::new(
                j as f32 / segments as f32,
                i as f32 / rings as f32,
            ));
        }
    }
    let at = |i: u32, j: u32| i * (segments + 1) + j;
    for i in 0..rings {
        for j in 0..segments {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            for t in [[a, b, c], [a, c, d]] {
                let p = t.map(|k| m.positions[k as usize]);
                let n = (p[1] - p[0]).cross(p[2] - p[0]);
                if n.length() < 1e-7 {
                    continue; // the poles' collapsed triangles
                }
                // Outward by the right-hand rule.
                m.indices.push(if n.dot(p[0] + p[1] + p[2]) > 0.0 {
                    t
                } else {
                    [t[0], t[2], t[1]]
                });
            }
        }
    }
    m
}

/// A fresh path in this process's scratch folder (tests run in parallel: one file per call).
fn scratch(ext: &str) -> PathBuf {
    static N: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!("lumis-gpu-mesh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(format!("{}.{ext}", N.fetch_add(1, Ordering::Relaxed)))
}

/// A coarse smooth sphere (10 × 20, its facets obvious without shading normals) of plastic on a
/// diffuse floor under a quad light, seen from slightly above, `size` pixels square.
fn sphere_scene(size: u32) -> Arc<Scene> {
    let file = scratch("obj");
    obj::write(&file, &smooth_sphere(10, 20)).unwrap();
    let json = format!(
        r#"{{
  "camera": {{"from": [0, 1.2, -3.6], "to": [0, 0.1, 0], "up": [0, 1, 0], "vfov_deg": 40, "width": {size}, "height": {size}}},
  "materials": {{
    "floor": {{"type": "diffuse", "albedo": [0.6, 0.6, 0.6]}},
    "shiny": {{"type": "plastic", "albedo": [0.7, 0.3, 0.2], "alpha": 0.15, "ior": 1.5}}
  }},
  "shapes": [
    {{"type": "mesh", "file": "{}", "material": "shiny"}},
    {{"type": "quad", "corner": [-4, -1, -4], "edge_u": [0, 0, 8], "edge_v": [8, 0, 0], "material": "floor"}},
    {{"type": "quad", "corner": [-1, 2.5, -2], "edge_u": [2, 0, 0], "edge_v": [0, 0, 1.5], "emission": [6, 6, 6]}}
  ]
}}"#,
        file.display()
    );
    let scene = Scene::from_desc(&parse_scene(&json).unwrap_or_else(|e| panic!("{e}")))
        .unwrap_or_else(|e| panic!("{e}"));
    std::fs::remove_file(&file).unwrap();
    assert!(scene.attributes.has_normals());
    Arc::new(scene)
}

/// The attribute index of every primitive (a triangle's d.w) and, for rays at the smooth sphere
/// and the floor, the hit's primitive, barycentrics, shading normal and UV, against the CPU's.
/// Barycentrics to 1e-6 absolute (both sides compute them with the same watertight test, the GPU
/// once more for the closest hit; `bvh_queries_match_the_cpu` holds t and p to 1e-5).
#[test]
fn hit_barycentrics_and_attributes_match_the_cpu() {
    let Some(ctx) = context() else {
        return;
    };
    let scene = sphere_scene(8);
    let gpu = GpuScene::new(ctx, scene.clone()).unwrap();
    let prims = scene.accel.primitives();
    let inputs: Vec<[f32; 4]> = (0..prims.len() as u32)
        .map(|i| [f32::from_bits(i), 0.0, 0.0, 0.0])
        .collect();
    let out = run(
        &gpu,
        "outp(0u, vec4f(bitcast<f32>(prim_attr(prims[bitcast<u32>(inp(0u).x)])), 0.0, 0.0, 0.0));",
        &inputs,
        1,
        1,
    );
    let with_attr = prims.iter().filter(|p| p.attr != NONE).count();
    for (p, o) in prims.iter().zip(&out) {
        assert_eq!(o[0].to_bits(), p.attr, "a primitive's attribute index");
    }
    assert!(with_attr > 300, "{with_attr}");

    let mut r = Rng::new(17, 8, 0);
    let rays: Vec<Ray> = (0..8192)
        .map(|_| {
            let o = Vec3::new(r.next_f32() * 6.0 - 3.0, r.next_f32() * 3.0, -4.0);
            let target = unit(&mut r) * 1.1 * r.next_f32();
            Ray::new(o, (target - o).normalize())
        })
        .collect();
    let inputs: Vec<[f32; 4]> = rays
        .iter()
        .flat_map(|r| [f4(r.o, r.t_max), f4(r.d, 0.0)])
        .collect();
    let out = run(
        &gpu,
        "let h = scene_intersect(Ray(inp(0u).xyz, inp(1u).xyz, inp(0u).w));
         var attr = NONE;
         var s = ShadingNormal(false, vec3f(0.0));
         var uv = vec2f(0.0);
         if h.prim != NONE {
             attr = prim_attr(prims[h.prim]);
             s = shading_normal(attr, h.b, h.n);
             uv = mesh_uv(attr, h.b);
         }
         outp(0u, vec4f(h.b, bitcast<f32>(h.prim), bitcast<f32>(attr)));
         outp(1u, vec4f(s.n, select(0.0, 1.0, s.found)));
         outp(2u, vec4f(uv, 0.0, 0.0));",
        &inputs,
        2,
        3,
    );
    let mut bary = Compare::new("barycentrics", 0.0, 1e-6);
    let mut normal = Compare::new("shading normal at a hit", RTOL, 0.0);
    let mut uv = Compare::new("uv at a hit", RTOL, 0.0);
    let mut smooth_hits = 0;
    for (ray, o) in rays.iter().zip(out.chunks(3)) {
        let Some(h) = scene.accel.intersect(ray) else {
            assert_eq!(o[0][2].to_bits(), NONE, "a miss");
            continue;
        };
        assert_eq!(o[0][2].to_bits(), h.prim, "the hit primitive");
        let attr = prims[h.prim as usize].attr;
        assert_eq!(o[0][3].to_bits(), attr, "the hit's attribute index");
        bary.scalar(o[0][0], h.b.x, "b1");
        bary.scalar(o[0][1], h.b.y, "b2");
        let a = &scene.attributes;
        let want = a.shading_normal(attr, h.b, h.n);
        assert_eq!(o[1][3] == 1.0, want.is_some(), "normal found");
        if let Some(w) = want {
            smooth_hits += 1;
            // The barycentrics' own difference (≤ 1e-6) moves the normal by at most
            // 1e-6·|nᵢ − n₀| ≤ 2e-6 before normalising; the sphere's normals never cancel.
            normal.v3_conditioned(o[1], w, 4e-6, "n");
        }
        // UVs of the sphere are within [0, 1]: the barycentrics' 1e-6 moves them by ≤ 2e-6.
        let want_uv = a.uv(attr, h.b);
        uv.scalar_conditioned(o[2][0], want_uv.x, 4e-6, "u");
        uv.scalar_conditioned(o[2][1], want_uv.y, 4e-6, "v");
    }
    assert!(smooth_hits > 2000, "{smooth_hits} hits on the sphere");
    bary.finish(0);
    normal.finish(0);
    uv.finish(0);
}

fn settings(strategy: Strategy) -> Settings {
    Settings {
        strategy,
        light_sampling: LightSampling::SolidAngle,
        ..Settings::default()
    }
}

/// The smooth sphere rendered on the GPU agrees with the CPU's render by the block z-test of
/// `gpu/images.rs` (family-wise α = 0.01), 32 spp each, with light sampling and with MIS. Blocks of
/// 8×8 pixels of the 64×64 image, as a facet is a few pixels wide: measured on lavapipe, a GPU
/// that ignores the shading normal (shades the facets flat) fails 14 and 13 of 192 blocks
/// (16×16 blocks: 1 and 0 of 48), while the correct GPU stays within worst |z| 3.06 over 9
/// seeds × both strategies (critical 4.04).
#[test]
fn gpu_smooth_sphere_matches_the_cpu() {
    let scene = sphere_scene(64);
    let mut failures = Vec::new();
    for (i, strategy) in [
        Strategy::Light,
        Strategy::Mis {
            heuristic: Heuristic::Power,
        },
    ]
    .into_iter()
    .enumerate()
    {
        let s = settings(strategy);
        let what = format!("gpu smooth sphere {strategy:?} vs cpu");
        let Some(decision) = decide_gpu_vs_cpu(&what, &scene, s, 32, 4000 + i as u32, 8) else {
            return;
        };
        if let Err(msg) = decision {
            failures.push(msg);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A 2×2-quad sheet in the plane y = 0, x and z in [−1, 1], geometric normal +y, whose vertex
/// normals lean 30° to 70° towards `side`·x: far enough from the geometric normal that many
/// directions lie above one of the two and below the other.
fn leaning_sheet(side: f32) -> MeshData {
    let mut m = MeshData {
        normals: Some(Vec::new()),
        ..MeshData::default()
    };
    for i in 0..3 {
        for j in 0..3 {
            m.positions
                .push(Vec3::new(j as f32 - 1.0, 0.0, i as f32 - 1.0));
            let lean = (30.0 + 5.0 * (3 * i + j) as f32).to_radians();
            let n = Vec3::new(side * lean.sin(), lean.cos(), 0.0);
            m.normals.as_mut().unwrap().push(n);
        }
    }
    for i in 0..2u32 {
        for j in 0..2u32 {
            let (a, b) = (3 * i + j, 3 * i + j + 1);
            let (c, d) = (3 * (i + 1) + j + 1, 3 * (i + 1) + j);
            for t in [[a, b, c], [a, c, d]] {
                let p = t.map(|k| m.positions[k as usize]);
                let up = (p[1] - p[0]).cross(p[2] - p[0]).y > 0.0;
                m.indices.push(if up { t } else { [t[0], t[2], t[1]] });
            }
        }
    }
    m
}

/// The shading-normal rule's cases, each in view, from a camera at a grazing 20° from −x: a glass
/// sheet of [`leaning_sheet`] leaning away from it (the viewing direction is above the geometric
/// plane and below the shading one; glass is never flipped, so the rule must end those paths), and
/// a two-sided diffuse one leaning towards it (paths from the floor meet its underside, where the
/// shading normal flips with the geometric one), lit from above and by a sphere light below the
/// sheets' plane on the −x side (its directions are above the leaning normals and below the
/// geometric one: light that must not leak through, by light sampling or by BSDF sampling), over
/// a diffuse floor.
fn rule_scene(size: u32) -> Arc<Scene> {
    let towards = scratch("obj");
    obj::write(&towards, &leaning_sheet(-1.0)).unwrap();
    let away = scratch("obj");
    obj::write(&away, &leaning_sheet(1.0)).unwrap();
    let sheet = |file: &PathBuf, material: &str, z: f32| {
        format!(
            r#"{{"type": "mesh", "file": "{}", "material": "{material}",
                "to_world": [[0.9, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0.45, {z}], [0, 0, 0, 1]]}}"#,
            file.display()
        )
    };
    let json = format!(
        r#"{{
  "camera": {{"from": [-3.2, 1.2, 0], "to": [0.3, 0, 0], "up": [0, 1, 0], "vfov_deg": 45, "width": {size}, "height": {size}}},
  "materials": {{
    "matte": {{"type": "diffuse", "albedo": [0.7, 0.7, 0.7], "two_sided": true}},
    "glass": {{"type": "dielectric", "ior": 1.5, "alpha": 0.0}}
  }},
  "shapes": [
    {}, {},
    {{"type": "quad", "corner": [-4, -0.7, -4], "edge_u": [0, 0, 8], "edge_v": [8, 0, 0], "material": "matte"}},
    {{"type": "quad", "corner": [-1, 3, -1], "edge_u": [2, 0, 0], "edge_v": [0, 0, 2], "emission": [3, 3, 3]}},
    {{"type": "sphere", "center": [-2.2, -0.35, -0.5], "radius": 0.3, "emission": [20, 20, 20]}}
  ]
}}"#,
        sheet(&towards, "matte", -0.5),
        sheet(&away, "glass", 0.5)
    );
    let scene = Scene::from_desc(&parse_scene(&json).unwrap_or_else(|e| panic!("{e}")))
        .unwrap_or_else(|e| panic!("{e}"));
    std::fs::remove_file(&towards).unwrap();
    std::fs::remove_file(&away).unwrap();
    assert!(scene.attributes.has_normals());
    Arc::new(scene)
}

/// Pixels of a same-seed GPU render (`spp` samples) of `scene` that differ from the CPU's by more
/// than 1e-3 (relative), and the relMSE between the two, per strategy.
fn same_seed_divergence(scene: &Arc<Scene>, spp: u32) -> Option<Vec<(Strategy, usize, f64)>> {
    let mut rows = Vec::new();
    for (i, strategy) in [
        Strategy::Light,
        Strategy::Bsdf,
        Strategy::Mixture { light_weight: 0.5 },
        Strategy::Mis {
            heuristic: Heuristic::Power,
        },
    ]
    .into_iter()
    .enumerate()
    {
        let mut s = settings(strategy);
        if i % 2 == 1 {
            s.light_sampling = LightSampling::Area;
        }
        let gpu = gpu_render(scene, s, spp, 11)?;
        assert_eq!(gpu.nonfinite, 0, "{strategy:?}: non-finite samples");
        let cpu = cpu_render(scene, s, spp, 11);
        let (g, c) = (gpu.mean(), cpu.mean());
        let diverged = g
            .iter()
            .zip(&c)
            .filter(|(a, b)| (**a - **b).abs().max_element() > 1e-3 * (1.0 + b.max_element()))
            .count();
        rows.push((strategy, diverged, lumis::metrics::relmse(&g, &c)));
    }
    Some(rows)
}

/// Same seed, same samples: the GPU's images of the smooth sphere and of the rule's scene are the
/// CPU's up to rounding (a path diverges only where the two sides' roundings take different
/// branches), with every strategy; the bound of `gpu/images.rs` (at most 1 pixel in 1000
/// diverged, relMSE < 1e-5). Stronger than the z-test, and what sees the shading-normal rule:
/// measured on lavapipe, no pixel diverges (relMSE ≤ 4e-11), while with light sampling alone
/// already, of the rule scene's 4096 pixels, 354 diverge without the rule's check of the viewing
/// direction, 342 without that of the light sample, 115 without that of the BSDF sample and 435
/// when the shading normal does not flip with a two-sided surface's geometric one; ignoring the
/// shading normal altogether, 1902 of the sphere's.
#[test]
fn same_seed_gives_the_cpu_image() {
    let mut worst = 0.0f64;
    for (name, scene) in [
        ("smooth sphere", sphere_scene(64)),
        ("rule scene", rule_scene(64)),
    ] {
        let Some(rows) = same_seed_divergence(&scene, 4) else {
            return;
        };
        let pixels = (scene.camera.width * scene.camera.height) as usize;
        for (strategy, diverged, e) in rows {
            eprintln!(
                "{name} {strategy:?}: relMSE {e:.2e}, {diverged} of {pixels} pixels diverged"
            );
            assert!(
                diverged * 1000 <= pixels,
                "{name} {strategy:?}: {diverged} of {pixels} pixels differ from the CPU's"
            );
            worst = worst.max(e);
        }
    }
    assert!(worst < 1e-5, "relMSE against the CPU up to {worst:e}");
}
