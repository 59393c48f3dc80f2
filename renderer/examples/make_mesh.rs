//! Writes a UV sphere of at least `--triangles N` triangles, with vertex normals and texture
//! coordinates, as a mesh file: binary little-endian PLY by default, or `--format ply-ascii`,
//! `ply-be`, `obj`. For the scale test (a 1M-triangle PLY made at test time, not committed) and
//! the tessellated-sphere test.
//!
//! The sphere is [`lumis::scene::mesh::uv_sphere::UvSphere`] (its doc says how it is made):
//! `--bumps A` (0 ≤ A < 1, default 0) displaces it, with exact normals, at frequency
//! `--frequency` (default 8). `--no-normals` and `--no-uvs` leave those out. There is no
//! randomness: the file is a function of the arguments.
//!
//! `--load FILE` instead reads FILE with lumis's mesh reader and prints the time it took, the
//! size of the result and the peak heap while reading. `--scene SCENE.json` loads a scene (e.g.
//! one with a `mesh` shape of that file) and prints, each with its peak heap over what was live
//! before: the parse (reading the mesh files) and the build ([`Scene::from_desc`]) times, the
//! BVH build alone ([`Accel::new`] over the scene's primitives), a surface-area estimate of the
//! BVH's cost per ray, and its ray throughput on one thread in Mrays/s (closest hit and
//! unblocked any hit, for about 2^18 camera rays through a grid in each pixel and as many rays
//! from uniform points in uniform directions). Heap is counted by this example's global
//! allocator.
//!
//! `cargo run --release -p lumis-renderer --example make_mesh -- --triangles 1000000 /tmp/sphere_1m.ply`
//! `cargo run --release -p lumis-renderer --example make_mesh -- --triangles 20000 --bumps 0.05 --format obj /tmp/bumpy.obj`
//! `cargo run --release -p lumis-renderer --example make_mesh -- --load /tmp/sphere_1m.ply`
//! `cargo run --release -p lumis-renderer --example make_mesh -- --scene /tmp/sphere_1m.json`

use glam::{Vec2, Vec3};
use lumis::alloc_count::{CountingAllocator, peak_bytes, reset_peak};
use lumis::geometry::{Accel, Ray};
use lumis::rng::Rng;
use lumis::sampling::sample_uniform_sphere;
use lumis::scene::mesh::uv_sphere::UvSphere;
use lumis::scene::mesh::{load_mesh, obj, ply};
use lumis::scene::{Scene, load_scene};
use std::path::{Path, PathBuf};
use std::time::Instant;

const USAGE: &str = "usage: make_mesh [--triangles N] [--bumps A] [--frequency K] \
[--format ply|ply-ascii|ply-be|obj] [--no-normals] [--no-uvs] OUT
       make_mesh --load FILE
       make_mesh --scene SCENE.json";

#[global_allocator]
static ALLOCATOR: CountingAllocator = CountingAllocator;

/// Runs `f`, returning its result, its seconds and its peak heap over what was live before.
fn measured<T>(f: impl FnOnce() -> T) -> (T, f64, usize) {
    let before = reset_peak();
    let start = Instant::now();
    let out = f();
    let seconds = start.elapsed().as_secs_f64();
    (out, seconds, peak_bytes() - before)
}

/// What to do.
enum Task {
    /// Write a sphere.
    Write(UvSphere, Format, PathBuf),
    /// Read a mesh file.
    Load(PathBuf),
    /// Load and measure a scene.
    Scene(PathBuf),
}

/// The file format to write.
enum Format {
    Ply(ply::Encoding),
    Obj,
}

/// Parses the command line: a sphere to write and where, or a file to load.
fn parse() -> Result<Task, String> {
    let mut sphere = UvSphere::new(1000);
    let mut format = Format::Ply(ply::Encoding::BinaryLittleEndian);
    let mut out = None;
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        let mut value = |name: &str| args.next().ok_or(format!("{name} needs a value"));
        match arg.as_str() {
            "--triangles" => {
                sphere.triangles = value("--triangles")?
                    .parse()
                    .map_err(|e| format!("--triangles: {e}"))?
            }
            "--bumps" => {
                sphere.bumps = value("--bumps")?
                    .parse()
                    .map_err(|e| format!("--bumps: {e}"))?;
                if !(0.0..1.0).contains(&sphere.bumps) {
                    return Err("--bumps must be in [0, 1)".into());
                }
            }
            "--frequency" => {
                sphere.frequency = value("--frequency")?
                    .parse()
                    .map_err(|e| format!("--frequency: {e}"))?
            }
            "--format" => {
                format = match value("--format")?.as_str() {
                    "ply" => Format::Ply(ply::Encoding::BinaryLittleEndian),
                    "ply-be" => Format::Ply(ply::Encoding::BinaryBigEndian),
                    "ply-ascii" => Format::Ply(ply::Encoding::Ascii),
                    "obj" => Format::Obj,
                    other => return Err(format!("unknown format '{other}'")),
                }
            }
            "--no-normals" => sphere.normals = false,
            "--no-uvs" => sphere.uvs = false,
            "--load" => return Ok(Task::Load(PathBuf::from(value("--load")?))),
            "--scene" => return Ok(Task::Scene(PathBuf::from(value("--scene")?))),
            _ if arg.starts_with("--") => return Err(format!("unknown option {arg}")),
            _ => out = Some(PathBuf::from(arg)),
        }
    }
    let out = out.ok_or("no output file given")?;
    Ok(Task::Write(sphere, format, out))
}

/// Writes `sphere` to `out`.
fn write(sphere: &UvSphere, format: Format, out: &Path) {
    let start = Instant::now();
    let mesh = sphere.mesh();
    let made = start.elapsed();
    let written = match format {
        Format::Ply(encoding) => ply::write(out, &mesh, encoding),
        Format::Obj => obj::write(out, &mesh),
    };
    written.unwrap_or_else(|e| fail(format!("{}: {e}", out.display())));
    eprintln!(
        "{}: {} triangles, {} vertices (made in {:.3} s, written in {:.3} s)",
        out.display(),
        mesh.indices.len(),
        mesh.positions.len(),
        made.as_secs_f64(),
        (start.elapsed() - made).as_secs_f64()
    );
}

/// Reads `file` and says how long it took and how large the result is.
fn load(file: &Path) {
    let (mesh, seconds, peak) = measured(|| load_mesh(file));
    let mesh = mesh.unwrap_or_else(|e| fail(e));
    let bytes = mesh.positions.capacity() * size_of::<Vec3>()
        + mesh.indices.capacity() * size_of::<[u32; 3]>()
        + mesh
            .normals
            .as_ref()
            .map_or(0, |n| n.capacity() * size_of::<Vec3>())
        + mesh
            .uvs
            .as_ref()
            .map_or(0, |u| u.capacity() * size_of::<Vec2>());
    let per_tri = |b: usize| b as f64 / mesh.indices.len().max(1) as f64;
    println!(
        "{}: {} triangles, {} vertices, normals {}, uvs {}; read in {seconds:.3} s; \
         MeshData {:.1} MB ({:.1} B per triangle), peak heap {:.1} MB ({:.1} B per triangle)",
        file.display(),
        mesh.indices.len(),
        mesh.positions.len(),
        mesh.normals.is_some(),
        mesh.uvs.is_some(),
        bytes as f64 / 1e6,
        per_tri(bytes),
        peak as f64 / 1e6,
        per_tri(peak)
    );
}

/// Loads the scene `file` and prints its load and build figures and its BVH's ray throughput.
fn scene(file: &Path) {
    let (desc, parse_s, parse_peak) = measured(|| load_scene(file));
    let desc = desc.unwrap_or_else(|e| fail(e));
    let (scene, build_s, build_peak) = measured(|| Scene::from_desc(&desc));
    let scene = scene.unwrap_or_else(|e| fail(e));
    drop(desc);
    let prims = scene.accel.primitives().len();
    let per_prim = |b: usize| b as f64 / prims as f64;
    println!(
        "{}: {prims} primitives; parse {parse_s:.3} s (peak heap {:.1} B per primitive), \
         build {build_s:.3} s (peak heap over the parsed scene {:.1} B per primitive)",
        file.display(),
        per_prim(parse_peak),
        per_prim(build_peak)
    );
    let copy = scene.accel.primitives().to_vec();
    let (_, bvh_s, bvh_peak) = measured(|| Accel::new(copy));
    println!(
        "BVH alone: {bvh_s:.3} s, peak heap {:.1} B per primitive over its input",
        per_prim(bvh_peak)
    );
    if let Some(bvh) = scene.accel.cwbvh() {
        let (nodes, prims) = surface_area_costs(bvh);
        println!(
            "BVH: {} nodes; a ray through its box meets on average {nodes:.2} nodes and \
             {prims:.2} primitives' boxes (surface-area estimate)",
            bvh.nodes.len()
        );
    }
    let camera = &scene.camera;
    // About 2^18 camera rays: a grid of rays in each pixel.
    let grid = ((1u32 << 18) as f64 / (camera.width * camera.height) as f64)
        .sqrt()
        .max(1.0) as u32;
    let coherent: Vec<Ray> = (0..camera.height * grid)
        .flat_map(|y| (0..camera.width * grid).map(move |x| (x, y)))
        .map(|(x, y)| {
            let at = |i: u32| (i as f32 + 0.5) / grid as f32;
            camera.ray(at(x), at(y))
        })
        .collect();
    let (lo, hi) = scene.accel.bounds();
    let incoherent: Vec<Ray> = (0..coherent.len() as u32)
        .map(|i| {
            let mut rng = Rng::new(7, i, 0);
            let o = lo + (hi - lo) * Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
            let d = sample_uniform_sphere(Vec2::new(rng.next_f32(), rng.next_f32()));
            Ray::new(o, d)
        })
        .collect();
    for (name, rays) in [("camera", &coherent), ("random", &incoherent)] {
        // Shadow rays that reach just short of the closest hit: nothing blocks them, so the whole
        // traversal runs.
        let shadow: Vec<Ray> = rays
            .iter()
            .map(|r| match scene.accel.intersect(r) {
                Some(hit) => Ray {
                    t_max: hit.t * 0.999,
                    ..*r
                },
                None => *r,
            })
            .collect();
        let closest = mrays_per_second(rays, |r| scene.accel.intersect(r).is_some());
        let any = mrays_per_second(&shadow, |r| scene.accel.occluded(r));
        println!(
            "{name} rays ({}): closest hit {closest:.2} Mrays/s, unblocked any hit {any:.2} \
             Mrays/s (one thread)",
            rays.len()
        );
    }
}

/// The surface-area estimates of the nodes and leaf primitives a random line through the root's
/// box meets (`Σ area(node) / area(root)` over internal nodes, `Σ count · area(leaf) /
/// area(root)` over leaves): a measure of the tree's quality that does not depend on timing.
fn surface_area_costs(bvh: &obvhs::cwbvh::CwBvh) -> (f64, f64) {
    let root = bvh.total_aabb.half_area() as f64;
    let (mut nodes, mut prims) = (0.0, 0.0);
    let mut todo = vec![(0usize, root)];
    while let Some((i, area)) = todo.pop() {
        nodes += area / root;
        let node = &bvh.nodes[i];
        for s in 0..8 {
            if node.is_child_empty(s) {
                continue;
            }
            let child = node.child_aabb(s).half_area() as f64;
            if node.is_leaf(s) {
                prims += node.child_primitives(s).1 as f64 * child / root;
            } else {
                todo.push((node.child_node_index(s) as usize, child));
            }
        }
    }
    (nodes, prims)
}

/// Rays per second through `query`, in millions: the best of 5 rounds, the one least disturbed
/// by other work on the machine.
fn mrays_per_second(rays: &[Ray], query: impl Fn(&Ray) -> bool) -> f64 {
    let best = (0..5)
        .map(|_| {
            let start = Instant::now();
            let n = rays
                .iter()
                .filter(|r| query(std::hint::black_box(r)))
                .count();
            std::hint::black_box(n);
            start.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min);
    rays.len() as f64 / best / 1e6
}

fn fail(e: impl std::fmt::Display) -> ! {
    eprintln!("make_mesh: {e}");
    std::process::exit(1);
}

fn main() {
    let task = parse().unwrap_or_else(|e| {
        eprintln!("make_mesh: {e}\n{USAGE}");
        std::process::exit(2);
    });
    match task {
        Task::Write(sphere, format, out) => write(&sphere, format, &out),
        Task::Load(file) => load(&file),
        Task::Scene(file) => scene(&file),
    }
}
