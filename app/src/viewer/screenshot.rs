//! Screenshots: per pane the image as shown (PNG) and the linear mean (EXR), the error curves as
//! CSV, and, in a real window, the whole window (PNG). Files are numbered `lumis-0001…` in the
//! output folder, always past the highest number already there, so nothing is overwritten.

use super::convergence::curves_csv;
use super::tonemap::{Display, display_rgb};
use super::worker::LaneView;
use lumis::image_io::Image;
use std::path::{Path, PathBuf};

/// File name prefix of every screenshot.
pub const PREFIX: &str = "lumis-";

/// `dir/lumis-NNNN`, with NNNN one past the highest number any file in `dir` already uses.
pub fn next_stem(dir: &Path) -> PathBuf {
    let highest = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .filter_map(|e| {
            let name = e.file_name().into_string().ok()?;
            let rest = name.strip_prefix(PREFIX)?;
            let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
            digits.parse::<u32>().ok()
        })
        .max()
        .unwrap_or(0);
    dir.join(format!("{PREFIX}{:04}", highest + 1))
}

/// A label as a file-name part: letters, digits, `.` and `-`; anything else becomes `_`.
fn file_safe(label: &str) -> String {
    label
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '.' || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

fn with_suffix(stem: &Path, suffix: &str) -> PathBuf {
    let mut s = stem.as_os_str().to_owned();
    s.push(suffix);
    PathBuf::from(s)
}

/// Writes PNG (as displayed) and EXR (linear) files for each lane and the curves CSV under a new
/// stem in `dir`. Returns the stem and the files written.
pub fn save(
    dir: &Path,
    lanes: &[LaneView],
    display: Display,
) -> Result<(PathBuf, Vec<PathBuf>), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let stem = next_stem(dir);
    let mut files = Vec::new();
    for (i, lane) in lanes.iter().enumerate() {
        if lane.pixels.is_empty() {
            continue;
        }
        let base = if lanes.len() == 1 {
            stem.clone()
        } else {
            with_suffix(&stem, &format!("-{}-{}", i + 1, file_safe(&lane.label)))
        };
        let png = with_suffix(&base, ".png");
        let rgb = display_rgb(&lane.pixels, &lane.errors, display);
        image::RgbImage::from_raw(lane.width, lane.height, rgb)
            .ok_or("image size mismatch")?
            .save(&png)
            .map_err(|e| format!("{}: {e}", png.display()))?;
        files.push(png);
        let exr = with_suffix(&base, ".exr");
        Image {
            width: lane.width,
            height: lane.height,
            data: lane.pixels.to_vec(),
        }
        .write(&exr, 0.0)
        .map_err(|e| e.to_string())?;
        files.push(exr);
    }
    let csv = with_suffix(&stem, "-error.csv");
    let curves: Vec<_> = lanes
        .iter()
        .map(|l| {
            let source = l.error.map_or(
                super::convergence::ErrorSource::HalfBuffers,
                |(_, source)| source,
            );
            (l.label.clone(), source, l.curve.clone())
        })
        .collect();
    std::fs::write(&csv, curves_csv(&curves)).map_err(|e| format!("{}: {e}", csv.display()))?;
    files.push(csv);
    Ok((stem, files))
}

/// Saves a window capture next to the other files of `stem`.
pub fn save_window(stem: &Path, image: &egui::ColorImage) -> Result<PathBuf, String> {
    let path = with_suffix(stem, "-window.png");
    let [w, h] = image.size;
    let rgba: Vec<u8> = image.pixels.iter().flat_map(|c| c.to_array()).collect();
    image::RgbaImage::from_raw(w as u32, h as u32, rgba)
        .ok_or("window image size mismatch")?
        .save(&path)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(path)
}
