//! lumis: a progressive, physically based path tracer, on the CPU or on a GPU through wgpu.
//!
//! The crate is organised like pbrt-v4: one file per concept (each light shape, each BxDF,
//! each sampling routine), closed-set dispatch through enums and `match`. The CPU code is the
//! reference; each module with a GPU counterpart names its WGSL twin, which lives beside it with
//! the same stem (`lights/disk.rs` + `lights/disk.wgsl`). The code map is
//! `docs/architecture.md`.
//!
//! * [`scene`]: scene files (the JSON format, Mitsuba 3 XML in and out, OBJ/PLY/glTF meshes),
//!   their validation into a [`scene::SceneDesc`], and the render-ready [`scene::Scene`].
//! * [`camera`]: the pinhole camera and its pixel filter.
//! * [`geometry`]: rays, shapes, robust ray offsets and the BVH.
//! * [`sampling`]: pure warping functions with their pdfs and inverses.
//! * [`sampler`]: where a sample's random numbers come from (independent, Owen-scrambled Sobol);
//!   [`rng`]: the counter-based random streams under them.
//! * [`materials`]: BSDFs (diffuse, GGX conductor, plastic, dielectric), mixes of two and
//!   two-sided pairs.
//! * [`textures`]: constant, bitmap and checkerboard textures for material parameters and emission.
//! * [`lights`]: area lights of every shape, the constant background and environment maps, and
//!   light selection by power or through a light BVH.
//! * [`integrator`]: the path tracer and its five direct-lighting strategies.
//! * [`engine`]: the progressive, multi-threaded CPU accumulation, and
//!   [`engine::AnyProgressive`], the CPU or the GPU engine behind one interface.
//! * [`gpu`]: the same estimator in wgpu compute shaders (WGSL), progressive on the GPU.
//! * [`image_io`] and [`metrics`]: EXR/PFM/PNG and error metrics, statistical image tests;
//!   [`math`]: frames and small shared functions.
//! * Test harness, public only with the `testing` feature (which the crate's own tests, examples
//!   and benches turn on through a dev-dependency on itself, so `cargo build` never exposes it):
//!   `mutants` (deliberate, named errors for measuring the tests; their mutation points stay in
//!   the renderer, constant 1 without the `mutants` feature), `alloc_count` (a counting
//!   allocator), `stats` (the χ² harness) and `scene::mesh::uv_sphere` (a test mesh).
#![warn(missing_docs)]

// A counting allocator for the memory tests: test code, only with the `testing` feature.
#[cfg(any(test, feature = "testing"))]
pub mod alloc_count;
pub mod camera;
pub mod engine;
pub mod erf;
pub mod geometry;
pub mod gpu;
pub mod image_io;
pub mod integrator;
pub mod lights;
pub mod materials;
pub mod math;
pub mod metrics;
pub mod quadrature;
// The mutation points are in the renderer (constant 1 without the `mutants` feature); choosing
// and applying a mutant is test harness, public only to the tests.
#[cfg(any(test, feature = "testing", feature = "mutants"))]
pub mod mutants;
#[cfg(not(any(test, feature = "testing", feature = "mutants")))]
#[allow(dead_code)]
mod mutants;
pub mod rng;
pub mod sampler;
pub mod sampling;
pub mod scene;
pub mod textures;
// The χ² harness of the sampler tests: test code, only with the `testing` feature.
#[cfg(any(test, feature = "testing"))]
pub mod stats;
