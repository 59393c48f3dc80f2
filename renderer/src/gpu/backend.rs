//! [`AnyProgressive`]: the CPU or the GPU engine behind one interface, for front ends (the
//! command line, the viewer) that let the user pick the backend.

use super::{GpuError, GpuProgressive};
use crate::engine::{Film, Progressive};
use crate::integrator::Settings;
use crate::scene::Scene;
use std::sync::Arc;

/// Which engine renders.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Backend {
    /// The multi-threaded CPU engine (runs in the caller's rayon pool).
    #[default]
    Cpu,
    /// The wgpu compute engine.
    Gpu,
}

/// A progressive render on either backend.
pub enum AnyProgressive {
    /// On the CPU.
    Cpu(Progressive),
    /// On the GPU.
    Gpu(Box<GpuProgressive>),
}

impl AnyProgressive {
    /// A new, empty render on `backend` (GPU: the default adapter, or [`GpuError::NoAdapter`]).
    pub fn new(
        backend: Backend,
        scene: Arc<Scene>,
        settings: Settings,
        seed: u32,
    ) -> Result<AnyProgressive, GpuError> {
        Ok(match backend {
            Backend::Cpu => AnyProgressive::Cpu(Progressive::new(scene, settings, seed)),
            Backend::Gpu => {
                AnyProgressive::Gpu(Box::new(GpuProgressive::new(scene, settings, seed)?))
            }
        })
    }

    /// Samples per pixel so far.
    pub fn spp(&self) -> u32 {
        match self {
            AnyProgressive::Cpu(r) => r.film().spp,
            AnyProgressive::Gpu(r) => r.spp(),
        }
    }

    /// Renders `n` more samples per pixel; `false` if a CPU pass was cancelled.
    pub fn render_pass(&mut self, n: u32) -> bool {
        match self {
            AnyProgressive::Cpu(r) => r.render_pass(n),
            AnyProgressive::Gpu(r) => r.render_pass(n),
        }
    }

    /// Drops the accumulation and restarts with new settings.
    pub fn restart(&mut self, settings: Settings) {
        match self {
            AnyProgressive::Cpu(r) => r.restart(settings),
            AnyProgressive::Gpu(r) => r.restart(settings),
        }
    }

    /// The accumulated image (a copy; read back from the GPU for the GPU backend).
    pub fn film(&self) -> Result<Film, GpuError> {
        match self {
            AnyProgressive::Cpu(r) => Ok(r.film().clone()),
            AnyProgressive::Gpu(r) => r.film(),
        }
    }
}
