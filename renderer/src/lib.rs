//! lumis: a progressive, physically based path tracer.
//!
//! The crate is organised like pbrt-v4: one file per concept (each light shape, each BxDF,
//! each sampling routine), closed-set dispatch through enums and `match`.
//!
//! * [`scene`]: the JSON scene format, its validation, and the render-ready [`scene::Scene`].
//! * [`geometry`]: rays, shapes, robust ray offsets and the BVH.
//! * [`sampling`]: pure warping functions with their pdfs and inverses.
//! * [`sampler`]: where a sample's random numbers come from (independent, Owen-scrambled Sobol).
//! * [`materials`]: BSDFs (diffuse, GGX conductor, plastic).
//! * [`lights`]: area lights of every shape, the background, power-based light selection.
//! * [`integrator`]: the path tracer and its four strategies.
//! * [`engine`]: the progressive, multi-threaded CPU accumulation, and
//!   [`engine::AnyProgressive`], the CPU or the GPU engine behind one interface.
//! * [`gpu`]: the same estimator in wgpu compute shaders (WGSL), progressive on the GPU.
//! * [`image_io`] and [`metrics`]: EXR/PFM/PNG and error metrics, statistical image tests.
#![warn(missing_docs)]

pub mod alloc_count;
pub mod camera;
pub mod engine;
pub mod geometry;
pub mod gpu;
pub mod image_io;
pub mod integrator;
pub mod lights;
pub mod materials;
pub mod math;
pub mod metrics;
pub mod mutants;
pub mod rng;
pub mod sampler;
pub mod sampling;
pub mod scene;
pub mod textures;
// The χ² harness of the sampler tests: test code, only with the `testing` feature.
#[cfg(any(test, feature = "testing"))]
pub mod stats;
