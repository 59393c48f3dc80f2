//! Decoding texture files into linear `f32` RGB, once, at load: PNG and JPEG (8- or 16-bit) are
//! sRGB-decoded unless `raw`; EXR and PFM (float) are linear and read by
//! [`crate::image_io::Image::read`]. Alpha is dropped and grey copied to R, G and B (Mitsuba
//! 3.9.1 does the same: it stores Y or RGB, without alpha, and linearises 8-bit sRGB texels
//! before it filters them).

use crate::image_io::{Image, ImageError};
use glam::Vec3;
use image::DynamicImage;
use std::path::Path;

/// Largest accepted texture, in texels (8k × 16k): 12 bytes a texel once decoded.
pub const MAX_TEXTURE_TEXELS: u64 = 1 << 27;

/// The sRGB decoding function (IEC 61966-2-1) of an encoded value in [0, 1].
pub fn srgb_to_linear(x: f64) -> f64 {
    if x <= 0.04045 {
        x / 12.92
    } else {
        ((x + 0.055) / 1.055).powf(2.4)
    }
}

fn err(path: &Path, message: impl ToString) -> ImageError {
    ImageError {
        path: path.display().to_string(),
        message: message.to_string(),
    }
}

/// Whether a file of this name is read as linear floats (`raw` makes no difference to it).
pub fn is_float_format(path: &Path) -> bool {
    matches!(extension(path).as_str(), "exr" | "hdr" | "rgbe" | "pfm")
}

/// Reads a texture file by its extension (`.png`, `.jpg`/`.jpeg`, `.bmp`, `.exr`, `.hdr`/`.rgbe`,
/// `.pfm`):
/// linear RGB,
/// row 0 at the top, 1 to [`MAX_TEXTURE_TEXELS`] texels.
pub fn load_texture_image(path: &Path, raw: bool) -> Result<Image, ImageError> {
    let image = match extension(path).as_str() {
        "exr" | "hdr" | "rgbe" | "pfm" => Image::read(path)?,
        "png" | "jpg" | "jpeg" | "bmp" => {
            let img = image::open(path).map_err(|e| err(path, e))?;
            from_dynamic(img, raw)
        }
        other => {
            return Err(err(
                path,
                format!(
                    "unsupported texture format '.{other}' (use .png, .jpg, .jpeg, .bmp, .exr or .hdr)"
                ),
            ));
        }
    };
    check_size(&image, path)?;
    Ok(image)
}

/// Decodes an image file held in memory (a glTF buffer's PNG or JPEG), by its content; `name`
/// is for messages. The same rules as [`load_texture_image`].
pub fn decode_texture_image(bytes: &[u8], name: &Path, raw: bool) -> Result<Image, ImageError> {
    let img = image::load_from_memory(bytes).map_err(|e| err(name, e))?;
    let image = from_dynamic(img, raw);
    check_size(&image, name)?;
    Ok(image)
}

/// The alpha channel of an image file held in memory (a glTF base colour's: linear, whatever
/// the colour's encoding), as a grey image; `None` when the file has none. `name` is for
/// messages.
pub fn decode_alpha(bytes: &[u8], name: &Path) -> Result<Option<Image>, ImageError> {
    let img = image::load_from_memory(bytes).map_err(|e| err(name, e))?;
    if !img.color().has_alpha() {
        return Ok(None);
    }
    let (width, height) = (img.width(), img.height());
    let data = img
        .into_rgba32f()
        .pixels()
        .map(|p| Vec3::splat(p[3]))
        .collect();
    let image = Image {
        width,
        height,
        data,
    };
    check_size(&image, name)?;
    Ok(Some(image))
}

fn check_size(image: &Image, path: &Path) -> Result<(), ImageError> {
    let texels = image.width as u64 * image.height as u64;
    if texels == 0 || texels > MAX_TEXTURE_TEXELS {
        return Err(err(
            path,
            format!(
                "{}×{} texels; a texture needs 1 to {MAX_TEXTURE_TEXELS}",
                image.width, image.height
            ),
        ));
    }
    Ok(())
}

/// Integer samples (8 or 16 bits) are display-encoded: sRGB-decoded through a table built in
/// f64, unless `raw` (then `x / max`); float samples are linear already.
fn from_dynamic(img: DynamicImage, raw: bool) -> Image {
    let (width, height) = (img.width(), img.height());
    let bits = 8 * img.color().bytes_per_pixel() / img.color().channel_count();
    let decode = |max: f64| -> Vec<f32> {
        (0..=max as u32)
            .map(|v| {
                let x = v as f64 / max;
                (if raw { x } else { srgb_to_linear(x) }) as f32
            })
            .collect()
    };
    let data: Vec<Vec3> = match bits {
        8 => {
            let lut = decode(255.0);
            let rgb = img.into_rgb8();
            rgb.pixels()
                .map(|p| Vec3::new(lut[p[0] as usize], lut[p[1] as usize], lut[p[2] as usize]))
                .collect()
        }
        16 => {
            let lut = decode(65535.0);
            let rgb = img.into_rgb16();
            rgb.pixels()
                .map(|p| Vec3::new(lut[p[0] as usize], lut[p[1] as usize], lut[p[2] as usize]))
                .collect()
        }
        _ => {
            let rgb = img.into_rgb32f();
            rgb.pixels().map(|p| Vec3::new(p[0], p[1], p[2])).collect()
        }
    };
    Image {
        width,
        height,
        data,
    }
}

fn extension(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("lumis-texture-load-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir.join(name)
    }

    /// The formula, written out independently in f32 (the encoded byte `v`).
    fn srgb_formula(v: f32) -> f32 {
        let c = v / 255.0;
        if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    }

    #[test]
    fn srgb_decode_against_the_formula() {
        // Known points of the curve: 0, the linear segment, mid-grey, 1.
        assert_eq!(srgb_to_linear(0.0), 0.0);
        assert_eq!(srgb_to_linear(1.0), 1.0);
        assert!((srgb_to_linear(0.04) - 0.04 / 12.92).abs() < 1e-15);
        assert!((srgb_to_linear(0.5) - 0.214_041_140_482_232_5).abs() < 1e-12);
        // Every 8-bit value of an RGB and a grey PNG, decoded, raw, and as a texture.
        let bytes: Vec<u8> = (0..=255u8).flat_map(|v| [v, 255 - v, v / 2]).collect();
        let path = scratch("ramp.png");
        image::RgbImage::from_raw(256, 1, bytes.clone())
            .unwrap()
            .save(&path)
            .unwrap();
        let img = load_texture_image(&path, false).unwrap();
        let raw = load_texture_image(&path, true).unwrap();
        assert_eq!((img.width, img.height), (256, 1));
        for (k, (t, r)) in img.data.iter().zip(&raw.data).enumerate() {
            for c in 0..3 {
                let v = bytes[3 * k + c] as f32;
                let want = srgb_formula(v);
                assert!(
                    (t[c] - want).abs() <= 1e-6 * want.max(1e-3),
                    "byte {v}: {} vs {want}",
                    t[c]
                );
                assert_eq!(r[c], v / 255.0, "raw byte {v}");
            }
        }
        let path = scratch("grey.png");
        image::GrayImage::from_raw(2, 1, vec![128, 10])
            .unwrap()
            .save(&path)
            .unwrap();
        let g = load_texture_image(&path, false).unwrap();
        assert_eq!(g.data[0], Vec3::splat(srgb_to_linear(128.0 / 255.0) as f32));
        assert_eq!(g.data[1], Vec3::splat(srgb_to_linear(10.0 / 255.0) as f32));
    }

    #[test]
    fn sixteen_bit_and_alpha() {
        let path = scratch("deep.png");
        let px: Vec<u16> = vec![0, 32768, 65535, 7, 1000, 50000, 60000, 65535];
        image::ImageBuffer::<image::Rgba<u16>, _>::from_raw(2, 1, px.clone())
            .unwrap()
            .save(&path)
            .unwrap();
        let img = load_texture_image(&path, false).unwrap();
        let raw = load_texture_image(&path, true).unwrap();
        // Alpha (px[3], px[7]) is dropped.
        for k in [0, 1, 2, 4, 5, 6] {
            let (v, p, c) = (px[k], k / 4, k % 4);
            let x = v as f64 / 65535.0;
            assert_eq!(img.data[p][c], srgb_to_linear(x) as f32, "sample {k}");
            assert_eq!(raw.data[p][c], x as f32, "raw sample {k}");
        }
    }

    #[test]
    fn jpeg_is_srgb_decoded_and_exr_is_linear() {
        // A uniform grey JPEG: only the DC term, so the byte survives within ±1.
        let path = scratch("flat.jpg");
        image::RgbImage::from_pixel(16, 16, image::Rgb([100, 100, 100]))
            .save(&path)
            .unwrap();
        let img = load_texture_image(&path, false).unwrap();
        let (lo, hi) = (srgb_formula(99.0), srgb_formula(101.0));
        assert!(
            img.data.iter().all(|t| t.x >= lo && t.x <= hi),
            "{:?}",
            img.data[0]
        );
        let path = scratch("lin.exr");
        let exr = Image {
            width: 2,
            height: 1,
            data: vec![Vec3::new(0.5, 2.0, 0.0), Vec3::new(0.25, 0.125, 1.0)],
        };
        exr.write(&path, 0.0).unwrap();
        assert_eq!(load_texture_image(&path, false).unwrap(), exr);
        assert_eq!(load_texture_image(&path, true).unwrap(), exr);
    }

    /// A BMP (Mitsuba's gallery projects one) decodes to the texels of the same 8-bit image
    /// stored as PNG: sRGB-decoded, row 0 at the top.
    #[test]
    fn bmp_reads_as_png_does() {
        let mut img = image::RgbImage::new(3, 2);
        for (x, y, p) in img.enumerate_pixels_mut() {
            *p = image::Rgb([40 * x as u8, 100 + 50 * y as u8, 7]);
        }
        let (png, bmp) = (scratch("t.png"), scratch("t.bmp"));
        img.save(&png).unwrap();
        img.save(&bmp).unwrap();
        for raw in [false, true] {
            let a = load_texture_image(&png, raw).unwrap();
            assert_eq!(load_texture_image(&bmp, raw).unwrap(), a);
        }
        assert_ne!(load_texture_image(&bmp, false).unwrap().data[0], Vec3::ZERO);
    }

    #[test]
    fn bad_files_name_the_file() {
        let e = load_texture_image(Path::new("/nonexistent/wood.png"), false).unwrap_err();
        assert!(e.to_string().contains("/nonexistent/wood.png"), "{e}");
        let e = load_texture_image(&scratch("a.tga"), false).unwrap_err();
        assert!(
            e.to_string().contains("unsupported texture format '.tga'"),
            "{e}"
        );
        let path = scratch("garbage.png");
        std::fs::write(&path, b"not a png").unwrap();
        let e = load_texture_image(&path, false).unwrap_err();
        assert!(e.to_string().contains("garbage.png"), "{e}");
        let e = decode_texture_image(b"junk", Path::new("buffer 3"), false).unwrap_err();
        assert!(e.to_string().starts_with("buffer 3: "), "{e}");
    }

    #[test]
    fn decodes_from_memory_like_from_a_file() {
        let path = scratch("mem.png");
        image::RgbImage::from_raw(2, 2, (0..12).map(|i| i * 20).collect())
            .unwrap()
            .save(&path)
            .unwrap();
        let bytes = std::fs::read(&path).unwrap();
        for raw in [false, true] {
            assert_eq!(
                decode_texture_image(&bytes, &path, raw).unwrap(),
                load_texture_image(&path, raw).unwrap()
            );
        }
    }
}
