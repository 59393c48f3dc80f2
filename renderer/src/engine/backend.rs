//! [`AnyProgressive`]: the CPU engine ([`Progressive`]) or its GPU twin
//! ([`GpuProgressive`]) behind one interface, for front ends (the command line, the viewer) that
//! let the user pick the [`Backend`].

use super::{Film, Progressive};
use crate::gpu::{AccumulationView, GpuContext, GpuError, GpuProgressive};
use crate::integrator::Settings;
use crate::scene::Scene;
use std::borrow::Cow;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

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
        AnyProgressive::with_device(backend, scene, settings, seed, &mut None)
    }

    /// A new, empty render on `backend`; a GPU render uses the device in `gpu`, creating the
    /// default one there first if it is empty, so that later renders (a viewer's restarts)
    /// reuse it instead of paying for a new device each time.
    pub fn with_device(
        backend: Backend,
        scene: Arc<Scene>,
        settings: Settings,
        seed: u32,
        gpu: &mut Option<Arc<GpuContext>>,
    ) -> Result<AnyProgressive, GpuError> {
        Ok(match backend {
            Backend::Cpu => AnyProgressive::Cpu(Progressive::new(scene, settings, seed)),
            Backend::Gpu => {
                let ctx = match gpu {
                    Some(c) => c.clone(),
                    None => gpu.insert(GpuContext::new()?).clone(),
                };
                AnyProgressive::Gpu(Box::new(GpuProgressive::with_context(
                    ctx, scene, settings, seed,
                )?))
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

    /// Renders `n` more samples per pixel; `false` if a CPU pass was cancelled (then nothing
    /// was added).
    pub fn render_pass(&mut self, n: u32) -> bool {
        match self {
            AnyProgressive::Cpu(r) => r.render_pass(n),
            AnyProgressive::Gpu(r) => r.render_pass(n),
        }
    }

    /// Drops the accumulation and restarts with new settings; on the GPU
    /// [`GpuError::TooLarge`] (nothing changed) where they need more memory than it allows.
    pub fn restart(&mut self, settings: Settings) -> Result<(), GpuError> {
        match self {
            AnyProgressive::Cpu(r) => {
                r.restart(settings);
                Ok(())
            }
            AnyProgressive::Gpu(r) => r.restart(settings),
        }
    }

    /// The accumulated image: borrowed on the CPU, read back from the GPU.
    pub fn film(&self) -> Result<Cow<'_, Film>, GpuError> {
        match self {
            AnyProgressive::Cpu(r) => Ok(Cow::Borrowed(r.film())),
            AnyProgressive::Gpu(r) => r.film().map(Cow::Owned),
        }
    }

    /// The flag that stops a running pass early: CPU passes only (a submitted GPU pass runs to
    /// its end, so GPU callers keep passes short instead).
    pub fn cancel_flag(&self) -> Option<Arc<AtomicBool>> {
        match self {
            AnyProgressive::Cpu(r) => Some(r.cancel_flag()),
            AnyProgressive::Gpu(_) => None,
        }
    }

    /// Records, per pixel, which technique contributed what (the viewer's technique map; see
    /// [`Progressive::enable_technique_map`]). CPU only: returns `false` on the GPU, whose
    /// kernels do not record it.
    pub fn enable_technique_map(&mut self) -> bool {
        match self {
            AnyProgressive::Cpu(r) => {
                r.enable_technique_map();
                true
            }
            AnyProgressive::Gpu(_) => false,
        }
    }

    /// Per pixel, the mean of each technique's part
    /// ([`crate::integrator::Technique::ALL`] order); empty unless recorded.
    pub fn technique_means(&self) -> Vec<[glam::Vec3; 4]> {
        match self {
            AnyProgressive::Cpu(r) => {
                let spp = r.technique_spp();
                r.technique_sums().iter().map(|t| t.means(spp)).collect()
            }
            AnyProgressive::Gpu(_) => Vec::new(),
        }
    }

    /// Where a GPU render's image lives on the device, for display without a readback.
    pub fn accumulation(&self) -> Option<AccumulationView<'_>> {
        match self {
            AnyProgressive::Cpu(_) => None,
            AnyProgressive::Gpu(r) => Some(r.accumulation()),
        }
    }
}
