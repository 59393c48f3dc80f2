//! Image files: EXR (linear float RGB), PFM, and PNG (sRGB, clamped, with exposure).

use glam::Vec3;
use std::io::{BufWriter, Read, Write};
use std::path::Path;

/// A linear RGB float image, row 0 at the top.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Pixels, row-major.
    pub data: Vec<Vec3>,
}

/// An image I/O failure, naming the file.
#[derive(Debug, thiserror::Error)]
#[error("{path}: {message}")]
pub struct ImageError {
    /// The file.
    pub path: String,
    /// What went wrong.
    pub message: String,
}

fn err(path: &Path, message: impl ToString) -> ImageError {
    ImageError {
        path: path.display().to_string(),
        message: message.to_string(),
    }
}

/// The sRGB transfer function of a linear value in [0, 1].
pub fn linear_to_srgb(x: f32) -> f32 {
    if x <= 0.003_130_8 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    }
}

/// One display pixel (sRGB bytes) of linear `c` at `gain`: scaled, clamped to [0, 1] (non-finite
/// values to 0), the sRGB curve, rounded. The PNG writer and the viewer both use it.
pub fn srgb8(c: Vec3, gain: f32) -> [u8; 3] {
    let c = c * gain;
    [c.x, c.y, c.z].map(|x| {
        let x = if x.is_finite() {
            x.clamp(0.0, 1.0)
        } else {
            0.0
        };
        (linear_to_srgb(x) * 255.0 + 0.5) as u8
    })
}

impl Image {
    /// Reads an EXR, Radiance HDR (`.hdr`, `.rgbe`) or PFM file (RGB; alpha and extra channels
    /// ignored).
    pub fn read(path: &Path) -> Result<Image, ImageError> {
        match extension(path).as_str() {
            "pfm" => read_pfm(path),
            "exr" | "hdr" | "rgbe" => Ok(Image::from_dynamic(decode_linear(path)?)),
            // PNG and the like hold display-encoded 8-bit values, not linear radiance.
            other => Err(err(
                path,
                format!("cannot read '.{other}' as linear radiance (use .exr, .hdr or .pfm)"),
            )),
        }
    }

    /// Reads the linear RGB image of an environment map: an EXR or a Radiance HDR (`.hdr`,
    /// `.rgbe`) file and nothing else; another extension, an unreadable file or one without
    /// colour channels (a grey-scale EXR) is an error. Alpha is ignored.
    pub fn read_rgb_map(path: &Path) -> Result<Image, ImageError> {
        let ext = extension(path);
        if !matches!(ext.as_str(), "exr" | "hdr" | "rgbe") {
            return Err(err(
                path,
                format!(
                    "an environment map must be an RGB EXR or Radiance HDR (.hdr, .rgbe) file, \
                     not '.{ext}'"
                ),
            ));
        }
        let img = decode_linear(path)?;
        if !img.color().has_color() {
            return Err(err(
                path,
                format!(
                    "has no RGB channels ({:?}); an environment map must be an RGB EXR or HDR",
                    img.color()
                ),
            ));
        }
        Ok(Image::from_dynamic(img))
    }

    /// The RGB channels of a decoded image as linear f32 (alpha and extra channels dropped).
    fn from_dynamic(img: image::DynamicImage) -> Image {
        let img = img.into_rgb32f();
        let (width, height) = img.dimensions();
        let data = img
            .pixels()
            .map(|p| Vec3::new(p.0[0], p.0[1], p.0[2]))
            .collect();
        Image {
            width,
            height,
            data,
        }
    }

    /// Writes by extension: `.exr`, `.pfm` (linear float) or `.png` (sRGB 8-bit after multiplying by
    /// `2^exposure` and clamping).
    pub fn write(&self, path: &Path, exposure: f32) -> Result<(), ImageError> {
        match extension(path).as_str() {
            "exr" => {
                let buf: Vec<f32> = self.data.iter().flat_map(|c| [c.x, c.y, c.z]).collect();
                let img = image::Rgb32FImage::from_raw(self.width, self.height, buf)
                    .ok_or_else(|| err(path, "image size mismatch"))?;
                img.save(path).map_err(|e| err(path, e))
            }
            "pfm" => write_pfm(self, path),
            "png" => {
                let scale = 2f32.powf(exposure);
                let buf: Vec<u8> = self.data.iter().flat_map(|&c| srgb8(c, scale)).collect();
                let img = image::RgbImage::from_raw(self.width, self.height, buf)
                    .ok_or_else(|| err(path, "image size mismatch"))?;
                img.save(path).map_err(|e| err(path, e))
            }
            other => Err(err(
                path,
                format!("unsupported image format '.{other}' (use .exr, .pfm or .png)"),
            )),
        }
    }
}

/// Decodes a linear float file, EXR or Radiance HDR, by its extension (`.rgbe` is HDR too,
/// which the `image` crate would not guess from the name).
fn decode_linear(path: &Path) -> Result<image::DynamicImage, ImageError> {
    let format = match extension(path).as_str() {
        "exr" => image::ImageFormat::OpenExr,
        _ => image::ImageFormat::Hdr,
    };
    let file = std::fs::File::open(path).map_err(|e| err(path, e))?;
    image::ImageReader::with_format(std::io::BufReader::new(file), format)
        .decode()
        .map_err(|e| err(path, e))
}

fn extension(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase()
}

/// PFM stores rows bottom to top, little-endian when the scale is negative.
fn write_pfm(img: &Image, path: &Path) -> Result<(), ImageError> {
    let file = std::fs::File::create(path).map_err(|e| err(path, e))?;
    let mut w = BufWriter::new(file);
    let mut out = format!("PF\n{} {}\n-1.0\n", img.width, img.height).into_bytes();
    for y in (0..img.height as usize).rev() {
        for c in &img.data[y * img.width as usize..(y + 1) * img.width as usize] {
            for v in [c.x, c.y, c.z] {
                out.extend_from_slice(&v.to_le_bytes());
            }
        }
    }
    w.write_all(&out)
        .and_then(|_| w.flush())
        .map_err(|e| err(path, e))
}

fn read_pfm(path: &Path) -> Result<Image, ImageError> {
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|mut f| f.read_to_end(&mut bytes))
        .map_err(|e| err(path, e))?;
    // Header: three whitespace-separated tokens lines: "PF", "W H", "scale".
    let mut tokens = Vec::new();
    let mut pos = 0;
    while tokens.len() < 4 && pos < bytes.len() {
        while pos < bytes.len() && bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        let start = pos;
        while pos < bytes.len() && !bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        tokens.push(String::from_utf8_lossy(&bytes[start..pos]).to_string());
    }
    pos += 1; // the single whitespace byte after the scale
    let bad = || err(path, "malformed PFM header");
    if tokens.len() < 4 {
        return Err(bad());
    }
    let channels = match tokens[0].as_str() {
        "PF" => 3,
        "Pf" => 1,
        _ => return Err(bad()),
    };
    let width: u32 = tokens[1].parse().map_err(|_| bad())?;
    let height: u32 = tokens[2].parse().map_err(|_| bad())?;
    let scale: f32 = tokens[3].parse().map_err(|_| bad())?;
    let n = width as usize * height as usize * channels;
    let body = bytes
        .get(pos..pos + 4 * n)
        .ok_or_else(|| err(path, "PFM file is truncated"))?;
    let vals: Vec<f32> = body
        .chunks_exact(4)
        .map(|b| {
            let b = [b[0], b[1], b[2], b[3]];
            if scale < 0.0 {
                f32::from_le_bytes(b)
            } else {
                f32::from_be_bytes(b)
            }
        })
        .collect();
    let mut data = vec![Vec3::ZERO; width as usize * height as usize];
    for y in 0..height as usize {
        let src_row = height as usize - 1 - y;
        for x in 0..width as usize {
            let i = (src_row * width as usize + x) * channels;
            data[y * width as usize + x] = if channels == 3 {
                Vec3::new(vals[i], vals[i + 1], vals[i + 2])
            } else {
                Vec3::splat(vals[i])
            };
        }
    }
    Ok(Image {
        width,
        height,
        data,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample_image() -> Image {
        let data = (0..12)
            .map(|i| Vec3::new(i as f32 * 0.25, 1.0 / (i as f32 + 1.0), -(i as f32)))
            .collect();
        Image {
            width: 4,
            height: 3,
            data,
        }
    }

    #[test]
    fn exr_and_pfm_round_trip_exactly() {
        let dir = std::env::temp_dir().join(format!("lumis-io-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let img = sample_image();
        for name in ["a.exr", "a.pfm"] {
            let p = dir.join(name);
            img.write(&p, 0.0).unwrap();
            assert_eq!(Image::read(&p).unwrap(), img, "{name}");
        }
        let p = dir.join("a.png");
        img.write(&p, 0.0).unwrap();
        let png = image::open(&p).unwrap().into_rgb8();
        // pixel 1 = (0.25, 0.5, -1): sRGB(0.25) = 137, sRGB(0.5) = 188, negative clamps to 0
        assert_eq!(png.get_pixel(1, 0).0, [137, 188, 0]);
        assert!(img.write(&dir.join("a.bmp"), 0.0).is_err());
        let e = Image::read(&p).unwrap_err().to_string();
        assert!(e.contains("a.png") && e.contains("linear"), "{e}");
        std::fs::remove_dir_all(&dir).ok();
    }
}
