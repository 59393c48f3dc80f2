//! The image size a command renders at (`--width`, `--height`, `--resolution-scale`), one rule
//! for `render`, `bench` and `view` (the viewer's open and drop too), whatever the scene format:
//! the scene's field of view (lumis' vertical one) and pixel filter (its width in pixels) stay
//! the scene's, as when Mitsuba renders the same XML with a film of another size, so a gallery
//! scene can be checked at a fraction of its resolution.

use clap::Args;
use lumis::scene::CameraDesc;

/// The command line's image size options.
#[derive(Args, Clone, Copy, Debug, Default, PartialEq)]
pub struct ImageSize {
    /// Image width in pixels; given alone, the height follows at the scene's aspect ratio.
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height in pixels; given alone, the width follows at the scene's aspect ratio.
    #[arg(long)]
    pub height: Option<u32>,
    /// Scale the scene's width and height by F (each rounded, at least 1 pixel), e.g. 0.25.
    #[arg(long, value_name = "F", conflicts_with_all = ["width", "height"])]
    pub resolution_scale: Option<f64>,
}

impl ImageSize {
    /// The size for a scene of `width × height`, or the option that is out of range.
    pub fn of(&self, width: u32, height: u32) -> Result<(u32, u32), String> {
        for (name, v) in [("--width", self.width), ("--height", self.height)] {
            if v == Some(0) {
                return Err(format!("{name} must be at least 1"));
            }
        }
        let scaled = |n: u32, f: f64| ((n as f64 * f).round() as u32).max(1);
        Ok(match (self.width, self.height, self.resolution_scale) {
            (_, _, Some(f)) if !(f.is_finite() && f > 0.0) => {
                return Err(format!("--resolution-scale {f} must be a positive number"));
            }
            (_, _, Some(f)) => (scaled(width, f), scaled(height, f)),
            (Some(w), Some(h), None) => (w, h),
            (Some(w), None, None) => (w, scaled(height, w as f64 / width as f64)),
            (None, Some(h), None) => (scaled(width, h as f64 / height as f64), h),
            (None, None, None) => (width, height),
        })
    }

    /// Sets `camera`'s size; nothing else of it changes.
    pub fn apply(&self, camera: &mut CameraDesc) -> Result<(), String> {
        (camera.width, camera.height) = self.of(camera.width, camera.height)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::ImageSize;

    fn size(width: Option<u32>, height: Option<u32>, scale: Option<f64>) -> ImageSize {
        ImageSize {
            width,
            height,
            resolution_scale: scale,
        }
    }

    #[test]
    fn sizes_follow_the_rule() {
        // Mitsuba's gallery film, 683 × 512.
        assert_eq!(size(None, None, None).of(683, 512), Ok((683, 512)));
        assert_eq!(size(None, None, Some(0.25)).of(683, 512), Ok((171, 128)));
        assert_eq!(size(None, None, Some(1e-6)).of(683, 512), Ok((1, 1)));
        assert_eq!(size(Some(200), None, None).of(683, 512), Ok((200, 150)));
        assert_eq!(size(None, Some(64), None).of(683, 512), Ok((85, 64)));
        assert_eq!(size(Some(10), Some(20), None).of(683, 512), Ok((10, 20)));
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let e = size(None, None, Some(bad)).of(683, 512).unwrap_err();
            assert!(e.contains("--resolution-scale"), "{e}");
        }
        assert!(
            size(Some(0), None, None)
                .of(683, 512)
                .unwrap_err()
                .contains("--width")
        );
        assert!(
            size(None, Some(0), None)
                .of(683, 512)
                .unwrap_err()
                .contains("--height")
        );
    }

    #[test]
    fn apply_changes_only_the_size() {
        let scene = lumis::scene::parse_scene(
            r#"{"camera": {"from": [0, 1, -3], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 35,
                "width": 683, "height": 512, "filter": {"type": "gaussian", "stddev": 0.5}},
                "shapes": []}"#,
        )
        .unwrap();
        let mut camera = scene.camera.clone();
        size(None, None, Some(0.25)).apply(&mut camera).unwrap();
        assert_eq!((camera.width, camera.height), (171, 128));
        (camera.width, camera.height) = (683, 512);
        assert_eq!(
            camera, scene.camera,
            "field of view, frame and filter unchanged"
        );
    }
}
