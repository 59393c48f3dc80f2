//! Reduced-resolution first images. One sample per pixel of the full image costs about half a
//! second at 512×512 on two cores, far over the 100 ms the viewer promises after a slider
//! change, so every restart first renders 1 spp at 1/8, 1/4 and 1/2 of the resolution (about a
//! third of a full pass in all) and shows each, scaled up, until the full film has a sample.
//! Previews sample the scene's pixel filter (box or gaussian, [`camera_at`]) on the CPU whatever
//! the lane's backend, as the full passes do on either backend.

use glam::{Vec3, Vec3A};
use lumis::camera::{Camera, PixelFilter};
use lumis::integrator::{Settings, radiance};
use lumis::rng::Rng;
use lumis::sampler::Sampler;
use lumis::scene::{CameraDesc, Scene};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

/// Fewest pixels the first preview may have: below this the image says too little to be
/// worth a pass; above it the first image takes longer.
const FIRST_PREVIEW_PIXELS: u64 = 4096;

/// Downscale factors of the previews for a `width`×`height` image, coarsest first: powers of
/// two down to 2, starting from the largest whose image still has about
/// [`FIRST_PREVIEW_PIXELS`] pixels. Small images get no preview.
pub fn preview_factors(width: u32, height: u32) -> Vec<u32> {
    let pixels = width as u64 * height as u64;
    let mut f = 1u32;
    while pixels / ((2 * f) as u64 * (2 * f) as u64) >= FIRST_PREVIEW_PIXELS {
        f *= 2;
    }
    let mut out = Vec::new();
    while f > 1 {
        out.push(f);
        f /= 2;
    }
    out
}

/// The camera of `desc` at `width`×`height`: the same frustum as the scene's camera, so a
/// preview pixel covers `factor`² pixels of the full image, with the scene's pixel filter
/// `filter` (of the full film) in preview pixels: a gaussian's σ and radius divided by `factor`,
/// so that it weights the same part of the image as on the full film (the box stays the box; a
/// filter with negative lobes becomes a tent of its radius).
pub fn camera_at(
    desc: &CameraDesc,
    filter: PixelFilter,
    factor: u32,
    width: u32,
    height: u32,
) -> Camera {
    let filter = match filter {
        PixelFilter::Box => PixelFilter::Box,
        PixelFilter::Gaussian { stddev, radius } => PixelFilter::Gaussian {
            stddev: stddev / factor as f32,
            radius: radius / factor as f32,
        },
        PixelFilter::Tent { radius } => PixelFilter::Tent {
            radius: radius / factor as f32,
        },
        // One sample per preview pixel with a signed weight would show negative pixels: a
        // filter with negative lobes previews as a tent of its radius.
        PixelFilter::Lanczos { .. } | PixelFilter::Mitchell { .. } => PixelFilter::Tent {
            radius: filter.radius() / factor as f32,
        },
    };
    lumis::scene::build::camera_of(desc, width, height).with_filter(filter)
}

/// A preview image: `width`×`height` linear pixels, row 0 at the top.
pub struct PreviewImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Pixels, row-major.
    pub pixels: Vec<Vec3>,
}

/// Renders one sample per pixel at `1/factor` of the scene's resolution. Returns `None` when
/// `cancel` is set meanwhile (a newer restart is waiting).
pub fn render_preview(
    scene: &Scene,
    camera: &CameraDesc,
    settings: &Settings,
    factor: u32,
    seed: u32,
    cancel: &AtomicBool,
) -> Option<PreviewImage> {
    let width = scene.camera.width.div_ceil(factor).max(1);
    let height = scene.camera.height.div_ceil(factor).max(1);
    let cam = camera_at(camera, scene.camera.filter, factor, width, height);
    let mut pixels = vec![Vec3::ZERO; (width * height) as usize];
    pixels
        .par_chunks_mut(width as usize)
        .enumerate()
        .for_each(|(y, row)| {
            if cancel.load(Ordering::Relaxed) {
                return;
            }
            for (x, px) in row.iter_mut().enumerate() {
                // A stream of its own (sample index u32::MAX − factor) so previews never repeat
                // the film's first samples' noise pattern.
                let pixel = y as u32 * width + x as u32;
                // Previews always use the independent sampler: one sample per pixel of a
                // reduced image, where a net has nothing to stratify.
                let mut rng = Sampler::from(Rng::new(seed, pixel, u32::MAX - factor));
                let p = cam.film_position(rng.camera_2d(), x as u32, y as u32);
                let ray = cam.ray(p.x, p.y);
                let l = radiance(scene, ray, &mut rng, settings);
                // Non-finite samples count as zero, as in the engine.
                *px = if Vec3A::from(l).is_finite() {
                    l
                } else {
                    Vec3::ZERO
                };
            }
        });
    (!cancel.load(Ordering::Relaxed)).then_some(PreviewImage {
        width,
        height,
        pixels,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn factors() {
        assert_eq!(preview_factors(512, 512), vec![8, 4, 2]);
        assert_eq!(preview_factors(256, 256), vec![4, 2]);
        assert!(preview_factors(64, 64).is_empty());
    }

    /// The preview camera carries the scene's filter in preview pixels: a gaussian's σ and radius
    /// over the factor, the box unchanged (its film positions are the original jitter). Catches
    /// a preview that drops the filter (the box everywhere, as before issue 18) or forgets the
    /// scale (deliberate bug tried: σ and radius not divided by the factor: the first assertion
    /// failed, σ 0.5 for 0.125).
    #[test]
    fn preview_camera_has_the_scenes_filter_in_preview_pixels() {
        let desc = CameraDesc {
            from: glam::DVec3::new(0.0, 0.0, -3.0),
            to: glam::DVec3::ZERO,
            up: glam::DVec3::Y,
            projection: lumis::scene::ProjectionDesc::Perspective { vfov_deg: 40.0 },
            principal_point_offset: [0.0; 2],
            width: 512,
            height: 256,
            filter: Default::default(),
        };
        let gaussian = PixelFilter::Gaussian {
            stddev: 0.5,
            radius: 2.0,
        };
        let cam = camera_at(&desc, gaussian, 4, 128, 64);
        assert_eq!(
            cam.filter,
            PixelFilter::Gaussian {
                stddev: 0.125,
                radius: 0.5
            }
        );
        let cam = camera_at(&desc, PixelFilter::Box, 4, 128, 64);
        assert_eq!(cam.filter, PixelFilter::Box);
        let u = glam::Vec2::new(0.25, 0.75);
        assert_eq!(cam.film_position(u, 3, 5), glam::Vec2::new(3.25, 5.75));
    }
}
