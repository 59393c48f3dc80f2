//! The GPU tests, one binary (one link, and one device shared by every test): parity of
//! each WGSL twin with its Rust module, χ² of the GPU samplers, and images against the CPU and
//! the references. Each module was a test binary of its own; `cargo test --release -p
//! lumis-renderer --test gpu MODULE::` runs one. Without an adapter the tests fail unless
//! `LUMIS_SKIP_GPU_TESTS` is set (`gpu_common::context`).

// The CPU tests' helpers (`renderer/tests/common/`) and the GPU tests' own (`tests/gpu/common/`).
#[path = "../common/mod.rs"]
mod common;
#[path = "common/mod.rs"]
mod gpu_common;

mod bump_map;
mod bvh2;
mod chi2;
mod filter_images;
mod hide_emitters;
mod images;
mod mask;
mod mitsuba_refs;
mod mix;
mod normal_map;
mod parity;
mod parity_dielectric;
mod parity_envmap;
mod parity_filter;
mod parity_gltf_pbr;
mod parity_mesh;
mod parity_optimal;
mod parity_principled;
mod parity_principled_thin;
mod parity_sampler;
mod parity_spherical;
mod parity_textures;
mod samples_per_dispatch;
mod sobol_images;
mod textured_emission;
mod textured_images;
mod two_sided;
