//! Scale (issue 17, item 8): a generated 1M-triangle binary PLY (made here, at test time, by the
//! same generator as the `make_mesh` example) loads through a scene file's `mesh` shape within
//! 200 bytes of heap per triangle at the peak of parsing and BVH building, its BVH holds every
//! triangle exactly once, and it renders on the CPU to a finite, non-black image.
//!
//! The memory bound is a deterministic count, not a timing: this test binary's global allocator
//! counts the bytes live on the heap and their peak while [`Scene::load`] runs, over what was live
//! before it. What this catches: a builder that holds a second copy of the primitives, a builder
//! temporary sized per BVH2 node kept alongside the scene's data, a `Vec` left at a doubled
//! capacity, a triangle dropped from (or duplicated in) the BVH. Load and build times are
//! reported by the `make_mesh --scene` example, not asserted here.

use lumis::alloc_count::{CountingAllocator, live_bytes, peak_bytes, reset_peak};
use lumis::engine::Progressive;
use lumis::integrator::Settings;
use lumis::scene::Scene;
use lumis::scene::mesh::ply;
use lumis::scene::mesh::uv_sphere::UvSphere;
use std::sync::Arc;

/// The bound of the issue: peak heap over the baseline during load + build, per triangle.
const MAX_BYTES_PER_TRIANGLE: f64 = 200.0;

/// Triangles in the generated mesh (at least; the sphere rounds up to whole stacks).
const TRIANGLES: usize = 1_000_000;

#[global_allocator]
static ALLOCATOR: CountingAllocator = CountingAllocator;

/// The scene: the sphere in plastic on a diffuse floor, lit by a quad, 32×32 pixels.
fn scene_json(mesh_file: &str) -> String {
    format!(
        r#"{{
  "camera": {{"from": [0, 1.2, -3.6], "to": [0, 0.1, 0], "up": [0, 1, 0], "vfov_deg": 40, "width": 32, "height": 32}},
  "materials": {{
    "floor": {{"type": "diffuse", "albedo": [0.6, 0.6, 0.6]}},
    "shiny": {{"type": "plastic", "albedo": [0.7, 0.3, 0.2], "alpha": 0.15, "ior": 1.5}}
  }},
  "shapes": [
    {{"type": "mesh", "file": "{mesh_file}", "material": "shiny"}},
    {{"type": "quad", "corner": [-4, -1, -4], "edge_u": [0, 0, 8], "edge_v": [8, 0, 0], "material": "floor"}},
    {{"type": "quad", "corner": [-1, 2.5, -2], "edge_u": [2, 0, 0], "edge_v": [0, 0, 1.5], "emission": [6, 6, 6]}}
  ]
}}"#
    )
}

/// Every primitive slot lies in exactly one leaf of the CWBVH (whose leaves index the
/// primitives directly).
fn check_leaves_cover_every_primitive(scene: &Scene) {
    let prims = scene.accel.primitives().len();
    let bvh = scene.accel.cwbvh().expect("a scene this large has a BVH");
    let mut seen = vec![0u8; prims];
    let mut todo = vec![0usize];
    while let Some(i) = todo.pop() {
        let node = &bvh.nodes[i];
        for slot in 0..8 {
            if node.is_child_empty(slot) {
                continue;
            }
            if node.is_leaf(slot) {
                let (first, count) = node.child_primitives(slot);
                for p in first..first + count {
                    seen[p as usize] += 1;
                }
            } else {
                todo.push(node.child_node_index(slot) as usize);
            }
        }
    }
    let missing = seen.iter().filter(|&&n| n == 0).count();
    let repeated = seen.iter().filter(|&&n| n > 1).count();
    assert_eq!(
        (missing, repeated),
        (0, 0),
        "primitives in no leaf, in several leaves (of {prims})"
    );
}

#[test]
fn a_million_triangle_ply_loads_within_the_memory_bound_and_renders() {
    let dir = std::env::temp_dir().join(format!("lumis-mesh-scale-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let sphere = UvSphere::new(TRIANGLES);
    let triangles = sphere.triangle_count();
    ply::write(
        &dir.join("sphere.ply"),
        &sphere.mesh(),
        ply::Encoding::BinaryLittleEndian,
    )
    .unwrap();
    let scene_path = dir.join("scene.json");
    std::fs::write(&scene_path, scene_json("sphere.ply")).unwrap();

    let baseline = reset_peak();
    let scene = Scene::load(&scene_path).unwrap_or_else(|e| panic!("{e}"));
    let peak = peak_bytes() - baseline;
    let kept = live_bytes() - baseline;
    std::fs::remove_dir_all(&dir).unwrap();
    let per_triangle = peak as f64 / triangles as f64;
    eprintln!(
        "{triangles} triangles: peak heap during load + build {:.1} MB ({per_triangle:.1} B per \
         triangle), the scene keeps {:.1} MB ({:.1} B per triangle)",
        peak as f64 / 1e6,
        kept as f64 / 1e6,
        kept as f64 / triangles as f64
    );

    // The sphere's triangles and the two quads' four.
    assert_eq!(scene.accel.primitives().len(), triangles + 4);
    check_leaves_cover_every_primitive(&scene);

    let mut render = Progressive::new(Arc::new(scene), Settings::default(), 1);
    assert!(render.render_pass(4));
    let film = render.film();
    assert_eq!(film.nonfinite, 0, "non-finite samples");
    let image = film.mean();
    assert!(image.iter().all(|p| p.is_finite()), "non-finite pixels");
    let lit = image.iter().filter(|p| p.max_element() > 0.0).count();
    assert!(
        lit > image.len() / 2,
        "only {lit} of {} pixels are not black",
        image.len()
    );

    assert!(
        per_triangle < MAX_BYTES_PER_TRIANGLE,
        "peak heap {per_triangle:.1} B per triangle, at most {MAX_BYTES_PER_TRIANGLE} allowed"
    );
}
