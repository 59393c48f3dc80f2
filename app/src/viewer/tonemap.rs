//! From linear radiance to display pixels: exposure, clamp and the sRGB curve (the same as
//! `lumis render`'s PNG output), or a false-colour map of the per-pixel relative error.

use glam::Vec3;
/// One display pixel (sRGB bytes) of linear `c` at a gain (`2^exposure`), as `lumis render`
/// writes PNGs.
pub use lumis::image_io::srgb8;

/// How the image is shown.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Display {
    /// Exposure in stops: pixels are multiplied by `2^exposure`.
    pub exposure: f32,
    /// Show the relative error in false colour instead of the image.
    pub false_colour: bool,
}

impl Default for Display {
    fn default() -> Display {
        Display {
            exposure: 0.0,
            false_colour: false,
        }
    }
}

/// Decades of relative error the false-colour map spans: 10⁻³ (dark blue) to 10⁰ (yellow).
pub const ERROR_DECADES: (f32, f32) = (-3.0, 0.0);

/// Viridis at five stops, linearly interpolated: perceptually ordered and readable by most
/// colour-blind viewers.
const VIRIDIS: [[f32; 3]; 5] = [
    [0.267, 0.005, 0.329],
    [0.230, 0.322, 0.546],
    [0.128, 0.567, 0.551],
    [0.369, 0.789, 0.383],
    [0.993, 0.906, 0.144],
];

/// The false colour (sRGB bytes) of relative error `e`; NaN (unknown yet) is grey.
pub fn error_colour(e: f32) -> [u8; 3] {
    if !e.is_finite() {
        return [64, 64, 64];
    }
    let (lo, hi) = ERROR_DECADES;
    let t = ((e.max(1e-12).log10() - lo) / (hi - lo)).clamp(0.0, 1.0) * 4.0;
    let i = (t as usize).min(3);
    let f = t - i as f32;
    std::array::from_fn(|c| {
        let v = VIRIDIS[i][c] * (1.0 - f) + VIRIDIS[i + 1][c] * f;
        (v * 255.0 + 0.5) as u8
    })
}

/// The displayed pixels, RGB bytes row-major. False colour needs per-pixel errors of the same
/// size; previews have none, so they are shown as images.
pub fn display_rgb(pixels: &[Vec3], errors: &[f32], display: Display) -> Vec<u8> {
    if display.false_colour && errors.len() == pixels.len() {
        return errors.iter().flat_map(|&e| error_colour(e)).collect();
    }
    let gain = 2f32.powf(display.exposure);
    pixels.iter().flat_map(|&c| srgb8(c, gain)).collect()
}

/// The same as an egui image.
pub fn color_image(
    width: u32,
    height: u32,
    pixels: &[Vec3],
    errors: &[f32],
    display: Display,
) -> egui::ColorImage {
    egui::ColorImage::from_rgb(
        [width as usize, height as usize],
        &display_rgb(pixels, errors, display),
    )
}
