//! The environment map on the GPU: its texels as an `rgba32float` texture (read with
//! `textureLoad` and interpolated by hand, so the lookup is the CPU's bilinear one and not the
//! sampler hardware's), and its sampling distribution as f32 tables appended to the scene's
//! `tables` buffer, like the light-selection tables (no storage binding of its own: the scene's
//! group already holds eight, the WebGPU default per stage; lavapipe allows 32, but the test
//! kernels add two of their own). The tables then share that buffer's binding-size limit (128 MiB
//! on lavapipe: maps up to about 16M texels), which `GpuScene` checks with a clear error.
//!
//! Tables of a map of `W` columns and `B` bands (`EnvmapLight`'s cells), from its offset on:
//! the `B + 1` band-edge cosines (the CPU's own values, so both sides cut the same bands), the
//! marginal CDF over the bands (`B + 1`), one conditional CDF over the columns per band
//! (`W + 1` each; uniform for a band of zero weight, which the marginal never picks), and the
//! density of every cell on the unit square (`W` per band, `Piecewise2D::pdf_cell`). The CDFs
//! are the CPU's f64 ones rounded to f32, like the light-selection CDF.
//! WGSL twin: `lights/envmap.wgsl`.

use crate::lights::EnvmapLight;

/// The texels of a map, as the texture will hold them.
pub(crate) struct EnvmapTexels {
    pub(crate) width: u32,
    pub(crate) height: u32,
    /// Row-major rgba (a = 0), row 0 at the zenith.
    pub(crate) rgba: Vec<[f32; 4]>,
}

impl EnvmapTexels {
    /// The texels of `map` (its radiance, `scale` included).
    pub(crate) fn of(map: &EnvmapLight) -> EnvmapTexels {
        let (w, h) = map.size();
        EnvmapTexels {
            width: w as u32,
            height: h as u32,
            rgba: map.texels().iter().map(|t| [t.x, t.y, t.z, 0.0]).collect(),
        }
    }

    /// The 1×1 black placeholder bound in scenes without a map (the binding must hold a texture;
    /// their programs never read it).
    pub(crate) fn placeholder() -> EnvmapTexels {
        EnvmapTexels {
            width: 1,
            height: 1,
            rgba: vec![[0.0; 4]],
        }
    }

    /// Uploads the texels as an `rgba32float` texture.
    pub(crate) fn upload(&self, device: &wgpu::Device, queue: &wgpu::Queue) -> wgpu::Texture {
        super::textures::upload_rgba32float(
            device,
            queue,
            "lumis envmap",
            (self.width, self.height),
            &self.rgba,
        )
    }
}

/// Appends the sampling tables of `map` to `tables` (layout in the module doc); returns their
/// offset.
pub(crate) fn append_tables(map: &EnvmapLight, tables: &mut Vec<f32>) -> u32 {
    let offset = tables.len() as u32;
    let cells = map.cells();
    let (w, bands) = cells.size();
    let f32_cdf = |cdf: &[f64]| cdf.iter().map(|&c| c as f32).collect::<Vec<f32>>();
    tables.extend_from_slice(map.band_cos());
    tables.extend(f32_cdf(cells.rows().cdf()));
    for columns in cells.columns() {
        match columns {
            Some(d) => tables.extend(f32_cdf(d.cdf())),
            None => tables.extend((0..=w).map(|i| i as f32 / w as f32)),
        }
    }
    for row in 0..bands {
        tables.extend((0..w).map(|column| cells.pdf_cell([column, row])));
    }
    debug_assert_eq!(
        tables.len() - offset as usize,
        2 * (bands + 1) + bands * (w + 1) + bands * w
    );
    offset
}
