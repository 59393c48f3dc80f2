//! Instances at scale (issue 42 item 3): a Mitsuba scene of 10⁴ `instance`s of one `shapegroup`
//! (a 320-triangle PLY sphere), generated here, imports (lumis flattens instances into the
//! scene) with every instance sharing the one mesh read from the file, its BVH holds every
//! flattened triangle exactly once, the peak heap over the import and build stays within
//! [`MAX_BYTES_PER_TRIANGLE`] per flattened triangle, and it renders on the CPU to a finite,
//! non-black image.
//!
//! The memory bound is a deterministic count (this binary's global allocator counts the heap),
//! not a timing. What this catches: the mesh file read, or its data copied, once per instance;
//! a second copy of the primitives; a triangle dropped from or duplicated in the BVH. The import
//! and build times are printed (`cargo test --release -p lumis-renderer --test instances_scale
//! -- --nocapture`), for docs/performance.md, not asserted.

mod common;

use lumis::alloc_count::{CountingAllocator, live_bytes, peak_bytes, reset_peak};
use lumis::engine::Progressive;
use lumis::integrator::Settings;
use lumis::scene::Scene;
use lumis::scene::desc::GeometryDesc;
use std::fmt::Write as _;
use std::sync::Arc;
use std::time::Instant;

/// Instances (a 100 × 100 grid).
const INSTANCES: usize = 10_000;
/// Triangles of `tests/data/mitsuba/attribute_sphere.ply`.
const MESH_TRIANGLES: usize = 320;
/// The bound: peak heap over the baseline during import + build, per flattened triangle: the
/// one-mesh bound of `mesh_scale.rs` (measured 2026-12-07: 158.5 B, the importer's JSON and
/// the 10⁴ shape descriptions included; a copy of the mesh per instance, 19 KB with its
/// attributes, would add 60 B).
const MAX_BYTES_PER_TRIANGLE: f64 = 200.0;

#[global_allocator]
static ALLOCATOR: CountingAllocator = CountingAllocator;

/// The scene: the grid of instances (each turned about y by its index and scaled) on a floor,
/// lit by a rectangle, seen from above, 32×32 pixels.
fn scene_xml(ply: &str) -> String {
    let mut s = String::from(
        r#"<scene version="3.0.0">
    <sensor type="perspective">
        <float name="fov" value="50"/>
        <transform name="to_world"><lookat origin="0, 60, -70" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="32"/><integer name="height" value="32"/>
            <rfilter type="box"/></film>
    </sensor>
    <bsdf type="diffuse" id="grey"><rgb name="reflectance" value="0.5, 0.5, 0.5"/></bsdf>
    <shape type="rectangle">
        <transform name="to_world"><scale value="80"/><rotate x="1" angle="-90"/></transform>
        <ref id="grey"/>
    </shape>
    <shape type="rectangle">
        <transform name="to_world"><scale value="20"/><rotate x="1" angle="90"/><translate y="40"/></transform>
        <emitter type="area"><rgb name="radiance" value="4, 4, 4"/></emitter>
    </shape>
"#,
    );
    writeln!(
        s,
        r#"    <shape type="shapegroup" id="g">
        <shape type="ply"><string name="filename" value="{ply}"/>
            <bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.4, 0.2"/></bsdf></shape>
    </shape>"#
    )
    .unwrap();
    for i in 0..INSTANCES {
        let (x, z) = ((i % 100) as f64 - 49.5, (i / 100) as f64 - 49.5);
        let scale = 0.3 + 0.1 * (i % 3) as f64;
        writeln!(
            s,
            r#"    <shape type="instance"><ref id="g"/><transform name="to_world"><scale value="{scale}"/><rotate y="1" angle="{}"/><translate x="{x}" y="0.5" z="{z}"/></transform></shape>"#,
            i % 360
        )
        .unwrap();
    }
    s + "</scene>\n"
}

#[test]
fn ten_thousand_instances_share_their_mesh_within_the_memory_bound_and_render() {
    let dir = std::env::temp_dir().join(format!("lumis-instances-scale-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let ply = common::data_dir()
        .join("mitsuba")
        .join("attribute_sphere.ply");
    let xml = dir.join("instances.xml");
    std::fs::write(&xml, scene_xml(&ply.to_string_lossy())).unwrap();

    let baseline = reset_peak();
    let start = Instant::now();
    let imported = lumis::scene::mitsuba::load(&xml, &[]).unwrap_or_else(|e| panic!("{e}"));
    let import_s = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let scene = Scene::from_desc(&imported.desc).unwrap_or_else(|e| panic!("{e}"));
    let build_s = start.elapsed().as_secs_f64();
    let peak = peak_bytes() - baseline;
    std::fs::remove_dir_all(&dir).unwrap();

    // Every instance holds the one mesh the file gave.
    let meshes: Vec<_> = imported
        .desc
        .shapes
        .iter()
        .filter_map(|s| match &s.geometry {
            GeometryDesc::Mesh { mesh, .. } => Some(mesh.clone()),
            _ => None,
        })
        .collect();
    assert_eq!(meshes.len(), INSTANCES);
    assert!(
        meshes.iter().all(|m| Arc::ptr_eq(m, &meshes[0])),
        "a mesh copied per instance"
    );
    drop(meshes);
    drop(imported);

    let triangles = INSTANCES * MESH_TRIANGLES;
    let kept = live_bytes() - baseline;
    let per_triangle = peak as f64 / triangles as f64;
    eprintln!(
        "{INSTANCES} instances, {triangles} triangles: import {import_s:.2} s, build \
         {build_s:.2} s; peak heap {:.1} MB ({per_triangle:.1} B per triangle), the scene keeps \
         {:.1} MB ({:.1} B per triangle)",
        peak as f64 / 1e6,
        kept as f64 / 1e6,
        kept as f64 / triangles as f64
    );
    // The instances' triangles and the two rectangles' four.
    assert_eq!(scene.accel.primitives().len(), triangles + 4);

    let mut render = Progressive::new(Arc::new(scene), Settings::default(), 1);
    assert!(render.render_pass(2));
    let film = render.film();
    assert_eq!(film.nonfinite, 0, "non-finite samples");
    let image = film.mean();
    let lit = image.iter().filter(|p| p.max_element() > 0.0).count();
    assert!(
        lit > image.len() / 2,
        "only {lit} of {} pixels lit",
        image.len()
    );
    assert!(
        per_triangle < MAX_BYTES_PER_TRIANGLE,
        "peak heap {per_triangle:.1} B per triangle, at most {MAX_BYTES_PER_TRIANGLE} allowed"
    );
}
