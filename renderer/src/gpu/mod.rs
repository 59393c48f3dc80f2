//! The GPU backend: the CPU's estimator, function for function, in wgpu compute shaders.
//!
//! * [`context`]: the device ([`GpuContext`]), created headless or shared with a viewer.
//! * [`shader`]: the WGSL modules (`shaders/`, one per concept, each the twin of a Rust module)
//!   and their specialisation by scene [`Features`].
//! * [`prelude`]: the WGSL constants and kind tags, generated from their Rust definitions.
//! * [`scene`]: the scene flattened into storage buffers ([`GpuScene`]), one record encoder per
//!   kind, the obvhs CWBVH uploaded as it is.
//! * [`progressive`]: [`GpuProgressive`], the GPU twin of [`crate::engine::Progressive`].
//! * `kernel` (with the `testing` feature): runs WGSL snippets against the scene on many inputs
//!   (the parity tests).
//!
//! The CPU is the reference: the GPU draws the same random numbers (the same PCG streams or the
//! same Owen-scrambled Sobol points, `sampler/mod.wgsl`), evaluates the same
//! materials, lights, strategies and Russian roulette, and its film reads back into a
//! [`crate::engine::Film`] so the CPU's metrics and statistical tests apply unchanged.

pub mod context;
pub mod kernel;
pub mod prelude;
pub mod progressive;
pub mod scene;
pub mod shader;

pub use context::GpuContext;
pub use progressive::{AccumulationView, GpuProgressive};
pub use scene::GpuScene;
pub use shader::Features;

/// What can go wrong on the GPU side.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    /// No wgpu adapter (no GPU, and no software driver such as Mesa's lavapipe either).
    #[error(
        "no GPU adapter found (on a machine without a GPU, install Mesa's software Vulkan driver: \
         apt-get install mesa-vulkan-drivers libvulkan1)"
    )]
    NoAdapter,
    /// The adapter refused to create a device.
    #[error("could not create a GPU device: {0}")]
    Device(String),
    /// A WGSL program failed to parse or validate (a bug in the backend).
    #[error("WGSL shader error: {0}")]
    Shader(String),
    /// Reading results back failed.
    #[error("GPU readback failed: {0}")]
    Readback(String),
    /// The scene exceeds what the GPU's limits allow.
    #[error("the scene does not fit the GPU: {0}")]
    TooLarge(String),
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_adapter_message_is_clear() {
        assert!(
            GpuError::NoAdapter
                .to_string()
                .starts_with("no GPU adapter found")
        );
    }
}
