//! Writes a UV sphere of at least `--triangles N` triangles, with vertex normals and texture
//! coordinates, as a mesh file: binary little-endian PLY by default, or `--format ply-ascii`,
//! `ply-be`, `obj`. For the scale test (a 1M-triangle PLY made at test time, not committed) and
//! the tessellated-sphere test.
//!
//! The sphere has `s` stacks and `2s` segments, `s` the smallest with `4s(s − 1) ≥ N` triangles
//! (`(s + 1)(2s + 1)` vertices: the seam and the poles are repeated so that the texture
//! coordinates are continuous): vertex `(i, j)` is at polar angle `θ = πi/s` from +y and azimuth
//! `φ = 2πj/(2s)`, direction `d = (sin θ cos φ, cos θ, −sin θ sin φ)`, texture coordinates
//! `(j/2s, 1 − i/s)`. Triangles wind counter-clockwise seen from outside (the right-hand rule
//! gives the outward normal); the degenerate halves of the quads at the poles are left out.
//!
//! `--bumps A` (0 ≤ A < 1, default 0) displaces the radius to `r = 1 + A·sin(kx)·sin(ky)·sin(kz)`
//! (`k` = `--frequency`, default 8) and gives the exact normals of that surface,
//! `normalize(d − ∇ₛr / r)`; with `A = 0` it is the unit sphere with normals `d`. `--no-normals`
//! and `--no-uvs` leave those out. There is no randomness: the file is a function of the
//! arguments.
//!
//! `--load FILE` instead reads FILE with lumis's mesh reader and prints the time it took and the
//! size of the result (for peak memory, run it under `/usr/bin/time -v`).
//!
//! `cargo run --release -p lumis-renderer --example make_mesh -- --triangles 1000000 /tmp/sphere_1m.ply`
//! `cargo run --release -p lumis-renderer --example make_mesh -- --triangles 20000 --bumps 0.05 --format obj /tmp/bumpy.obj`
//! `cargo run --release -p lumis-renderer --example make_mesh -- --load /tmp/sphere_1m.ply`

use glam::{DVec3, Vec2, Vec3};
use lumis::scene::mesh::{MeshData, load_mesh, obj, ply};
use std::f64::consts::PI;
use std::path::PathBuf;
use std::time::Instant;

const USAGE: &str = "usage: make_mesh [--triangles N] [--bumps A] [--frequency K] \
[--format ply|ply-ascii|ply-be|obj] [--no-normals] [--no-uvs] OUT\n       make_mesh --load FILE";

/// What to write.
struct Sphere {
    triangles: usize,
    bumps: f64,
    frequency: f64,
    normals: bool,
    uvs: bool,
}

/// The file format to write.
enum Format {
    Ply(ply::Encoding),
    Obj,
}

impl Sphere {
    /// The smallest stack count giving at least `self.triangles` triangles.
    fn stacks(&self) -> usize {
        let mut s = 2;
        while 4 * s * (s - 1) < self.triangles {
            s += 1;
        }
        s
    }

    /// The mesh (see the module doc).
    fn mesh(&self) -> MeshData {
        let s = self.stacks();
        let segments = 2 * s;
        let columns = segments + 1;
        let vertices = (s + 1) * columns;
        let mut positions = Vec::with_capacity(vertices);
        let mut normals = Vec::with_capacity(if self.normals { vertices } else { 0 });
        let mut uvs = Vec::with_capacity(if self.uvs { vertices } else { 0 });
        let azimuth: Vec<(f64, f64)> = (0..columns)
            .map(|j| (2.0 * PI * j as f64 / segments as f64).sin_cos())
            .collect();
        for i in 0..=s {
            let (sin_t, cos_t) = (PI * i as f64 / s as f64).sin_cos();
            for (j, &(sin_p, cos_p)) in azimuth.iter().enumerate() {
                let d = DVec3::new(sin_t * cos_p, cos_t, -sin_t * sin_p);
                let (p, n) = self.displaced(d);
                positions.push(p.as_vec3());
                if self.normals {
                    normals.push(n.as_vec3());
                }
                if self.uvs {
                    uvs.push(Vec2::new(
                        j as f32 / segments as f32,
                        1.0 - i as f32 / s as f32,
                    ));
                }
            }
        }
        let mut indices = Vec::with_capacity(4 * s * (s - 1));
        let at = |i: usize, j: usize| (i * columns + j) as u32;
        for i in 0..s {
            for j in 0..segments {
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                if i + 1 < s {
                    indices.push([a, b, c]);
                }
                if i > 0 {
                    indices.push([a, c, d]);
                }
            }
        }
        MeshData {
            positions,
            indices,
            normals: self.normals.then_some(normals),
            uvs: self.uvs.then_some(uvs),
        }
    }

    /// The point of the surface in direction `d` (unit) and its unit normal.
    fn displaced(&self, d: DVec3) -> (DVec3, DVec3) {
        if self.bumps == 0.0 {
            return (d, d);
        }
        let k = self.frequency;
        let (s, c) = (
            DVec3::new((k * d.x).sin(), (k * d.y).sin(), (k * d.z).sin()),
            DVec3::new((k * d.x).cos(), (k * d.y).cos(), (k * d.z).cos()),
        );
        let r = 1.0 + self.bumps * s.x * s.y * s.z;
        let grad = self.bumps * k * DVec3::new(c.x * s.y * s.z, s.x * c.y * s.z, s.x * s.y * c.z);
        // Only the part of the gradient along the sphere tilts the surface.
        let tangential = grad - grad.dot(d) * d;
        (r * d, (d - tangential / r).normalize())
    }
}

/// Parses the command line: a sphere to write and where, or a file to load.
fn parse() -> Result<Result<(Sphere, Format, PathBuf), PathBuf>, String> {
    let mut sphere = Sphere {
        triangles: 1000,
        bumps: 0.0,
        frequency: 8.0,
        normals: true,
        uvs: true,
    };
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
            "--load" => return Ok(Err(PathBuf::from(value("--load")?))),
            _ if arg.starts_with("--") => return Err(format!("unknown option {arg}")),
            _ => out = Some(PathBuf::from(arg)),
        }
    }
    let out = out.ok_or("no output file given")?;
    Ok(Ok((sphere, format, out)))
}

fn main() {
    let task = parse().unwrap_or_else(|e| {
        eprintln!("make_mesh: {e}\n{USAGE}");
        std::process::exit(2);
    });
    match task {
        Ok((sphere, format, out)) => {
            let start = Instant::now();
            let mesh = sphere.mesh();
            let made = start.elapsed();
            let written = match format {
                Format::Ply(encoding) => ply::write(&out, &mesh, encoding),
                Format::Obj => obj::write(&out, &mesh),
            };
            written.unwrap_or_else(|e| {
                eprintln!("make_mesh: {}: {e}", out.display());
                std::process::exit(1);
            });
            eprintln!(
                "{}: {} triangles, {} vertices (made in {:.3} s, written in {:.3} s)",
                out.display(),
                mesh.indices.len(),
                mesh.positions.len(),
                made.as_secs_f64(),
                (start.elapsed() - made).as_secs_f64()
            );
        }
        Err(file) => {
            let start = Instant::now();
            let mesh = load_mesh(&file).unwrap_or_else(|e| {
                eprintln!("make_mesh: {e}");
                std::process::exit(1);
            });
            let seconds = start.elapsed().as_secs_f64();
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
            println!(
                "{}: {} triangles, {} vertices, normals {}, uvs {}; read in {seconds:.3} s; \
                 MeshData {:.1} MB ({:.1} bytes per triangle)",
                file.display(),
                mesh.indices.len(),
                mesh.positions.len(),
                mesh.normals.is_some(),
                mesh.uvs.is_some(),
                bytes as f64 / 1e6,
                bytes as f64 / mesh.indices.len().max(1) as f64
            );
        }
    }
}
