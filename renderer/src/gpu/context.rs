//! The wgpu device the backend renders with.

use super::GpuError;
use super::progressive::PathPipelines;
use std::collections::VecDeque;
use std::sync::{Arc, Mutex};

/// How many compiled path tracers a context keeps. Each is a whole megakernel, and on lavapipe
/// its JIT-compiled code costs about a hundred megabytes: kept without bound, the GPU test
/// binary (one context, hundreds of scene variants) grew past 24 GB and was killed
/// (2026-12-06). A viewer alternates between a few feature sets.
pub const PIPELINE_CACHE: usize = 8;

/// A device and its queue. Create one headless with [`GpuContext::new`], or wrap the viewer's
/// (eframe's) device with [`GpuContext::from_device`] so the accumulation buffer can be drawn
/// without a round trip through the CPU.
#[derive(Debug)]
pub struct GpuContext {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// What the adapter is ("llvmpipe (LLVM 15.0.6, 256 bits)" on Mesa's software driver).
    pub adapter_info: wgpu::AdapterInfo,
    /// Compiled path tracers by their WGSL source, the most recently used last (see
    /// [`GpuContext::pipeline`]).
    pipelines: Mutex<VecDeque<(String, PathPipelines)>>,
}

impl GpuContext {
    /// The default adapter (any backend wgpu finds; `WGPU_BACKEND` can force one) and a device with
    /// the adapter's own limits (the defaults allow only 8 storage buffers and small dispatches;
    /// the path tracer binds 8). [`GpuError::NoAdapter`] when there is none.
    pub fn new() -> Result<Arc<GpuContext>, GpuError> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let adapter =
            pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions::default()))
                .map_err(|_| GpuError::NoAdapter)?;
        let adapter_info = adapter.get_info();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("lumis"),
            required_limits: adapter.limits(),
            ..Default::default()
        }))
        .map_err(|e| GpuError::Device(e.to_string()))?;
        Ok(Arc::new(GpuContext {
            device,
            queue,
            adapter_info,
            pipelines: Mutex::default(),
        }))
    }

    /// Wraps an existing device (the viewer's), so GPU renders and their display share buffers.
    pub fn from_device(
        device: wgpu::Device,
        queue: wgpu::Queue,
        adapter_info: wgpu::AdapterInfo,
    ) -> Arc<GpuContext> {
        Arc::new(GpuContext {
            device,
            queue,
            adapter_info,
            pipelines: Mutex::default(),
        })
    }

    /// The path tracer's pipelines for `source`, compiled by `compile` unless one of the
    /// [`PIPELINE_CACHE`] most recently used is for it: a viewer restarts renders with the same
    /// scene features again and again, and compiling the path tracer takes about a second on
    /// lavapipe. (wgpu deduplicates equal bind group layouts, so a cached pipeline accepts bind
    /// groups made from a later scene's equal layout.)
    pub fn pipeline(
        &self,
        source: &str,
        compile: impl FnOnce() -> Result<PathPipelines, GpuError>,
    ) -> Result<PathPipelines, GpuError> {
        let mut cache = self.pipelines.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(i) = cache.iter().position(|(s, _)| s == source) {
            let hit = cache.remove(i).expect("the position found");
            let p = hit.1.clone();
            cache.push_back(hit);
            return Ok(p);
        }
        let p = compile()?;
        if cache.len() == PIPELINE_CACHE {
            cache.pop_front();
        }
        cache.push_back((source.to_owned(), p.clone()));
        Ok(p)
    }

    /// Copies `size` bytes of `buffer` (which needs `COPY_SRC`) to the CPU, waiting for the GPU.
    pub fn read_buffer(&self, buffer: &wgpu::Buffer, size: u64) -> Result<Vec<u8>, GpuError> {
        let staging = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("lumis readback"),
            size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, size);
        self.queue.submit([encoder.finish()]);
        let (tx, rx) = std::sync::mpsc::channel();
        staging.map_async(wgpu::MapMode::Read, .., move |r| {
            let _ = tx.send(r);
        });
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| GpuError::Readback(e.to_string()))?;
        rx.recv()
            .map_err(|e| GpuError::Readback(e.to_string()))?
            .map_err(|e| GpuError::Readback(e.to_string()))?;
        let data = staging
            .get_mapped_range(..)
            .map_err(|e| GpuError::Readback(e.to_string()))?
            .to_vec();
        staging.unmap();
        Ok(data)
    }
}

#[cfg(test)]
impl GpuContext {
    /// The device the library's own GPU tests share, with the rule of `renderer/tests/gpu/common`: `None`
    /// (the test passes vacuously) when `LUMIS_SKIP_GPU_TESTS` is set; without an adapter and
    /// without that variable the test fails.
    pub(crate) fn for_tests() -> Option<Arc<GpuContext>> {
        use std::sync::OnceLock;
        if std::env::var_os("LUMIS_SKIP_GPU_TESTS").is_some() {
            eprintln!("LUMIS_SKIP_GPU_TESTS is set: skipping a GPU test");
            return None;
        }
        static CTX: OnceLock<Result<Arc<GpuContext>, String>> = OnceLock::new();
        match CTX.get_or_init(|| GpuContext::new().map_err(|e| e.to_string())) {
            Ok(c) => Some(c.clone()),
            Err(e) => panic!("{e} (set LUMIS_SKIP_GPU_TESTS=1 to skip the GPU tests)"),
        }
    }
}
