//! Pictures of a χ² test, like Nori's warptest: observed and expected counts side by side on one
//! colour scale, and the cells' signed residuals `(O − E)/√E` beside them.

use super::chi2::ChiSquareTest;
use crate::image_io::{Image, ImageError};
use glam::Vec3;
use std::path::Path;

/// Pixels per cell edge.
const SCALE: u32 = 4;
/// Pixels between panels.
const GAP: u32 = 6;

/// A dark-to-bright heat colour for `t ∈ [0, 1]` (linear RGB).
fn heat(t: f32) -> Vec3 {
    let t = t.clamp(0.0, 1.0);
    Vec3::new(
        (3.0 * t).min(1.0),
        (3.0 * t - 1.0).clamp(0.0, 1.0),
        (3.0 * t - 2.0).clamp(0.0, 1.0),
    )
}

/// Blue for negative, red for positive `r`, saturating at |r| = 4σ.
fn residual_colour(r: f32) -> Vec3 {
    let t = (r.abs() / 4.0).min(1.0);
    if r >= 0.0 {
        Vec3::new(t, 0.0, 0.0)
    } else {
        Vec3::new(0.0, 0.2 * t, t)
    }
}

/// Renders the last run of `test` as one image: observed | expected | residual, each
/// `res_phi × res_theta` cells (φ to the right, θ downwards from the domain's axis).
pub fn histogram_image(test: &ChiSquareTest) -> Image {
    let (obs, exp) = test.render_histograms();
    let (w, h) = (test.res_phi as u32, test.res_theta as u32);
    let max = obs
        .iter()
        .chain(&exp)
        .fold(0.0f64, |m, &x| m.max(x))
        .max(1.0);
    let panel = w * SCALE;
    let width = 3 * panel + 2 * GAP;
    let height = h * SCALE;
    let mut data = vec![Vec3::splat(0.5); (width * height) as usize];
    for row in 0..h {
        for col in 0..w {
            let i = (row * w + col) as usize;
            let r = if exp[i] > 0.0 {
                ((obs[i] - exp[i]) / exp[i].sqrt()) as f32
            } else if obs[i] > 0.0 {
                f32::INFINITY
            } else {
                0.0
            };
            let colours = [
                heat((obs[i] / max) as f32),
                heat((exp[i] / max) as f32),
                residual_colour(r),
            ];
            for (k, c) in colours.into_iter().enumerate() {
                let x0 = k as u32 * (panel + GAP) + col * SCALE;
                for y in row * SCALE..(row + 1) * SCALE {
                    for x in x0..x0 + SCALE {
                        data[(y * width + x) as usize] = c;
                    }
                }
            }
        }
    }
    Image {
        width,
        height,
        data,
    }
}

/// Writes [`histogram_image`] to `path` (PNG by its extension).
pub fn write_histogram_png(test: &ChiSquareTest, path: &Path) -> Result<(), ImageError> {
    histogram_image(test).write(path, 0.0)
}
