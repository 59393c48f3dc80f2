//! Part files: what `lumis render --sample-range` writes and `lumis merge` reads and writes.
//!
//! A part is an OpenEXR file (one layer, scanlines, ZIP) that any EXR reader shows as the image
//! and that holds, besides, everything an exact merge needs:
//!
//! - `R`, `G`, `B` (f32): the mean, as a plain `lumis render -o X.exr` writes it.
//! - The film's f64 per-pixel sums, bit for bit, each as two u32 channels with the high and low
//!   32 bits of the f64: `lumis.sum.R.hi`, `lumis.sum.R.lo`, … for `sum` (Σx), `sumSq` (Σx²)
//!   and `sumEven` (Σx over the samples whose global index is even: the half images) × R, G, B.
//!   The CPU film accumulates in f64, so an f32 mean would lose what the merge must keep.
//! - One text attribute, `lumisPart`, of `key=value` lines (one attribute, so that the header,
//!   and the file, is the same for the same samples): `format` (`1`), `samples` (the sample
//!   indices held: sorted, disjoint, non-empty ranges such as `0..3,5..8`, END excluded),
//!   `nonfinite` (samples dropped as NaN or infinite), and what parts must share to be merged:
//!   `seed`, `scene` (a hash of the scene's JSON), `settings` (the estimator settings),
//!   `backend` and `version`; `sceneFile` (the scene file's name) is for messages only.

use anyhow::{Context, bail};
use exr::prelude::{
    AnyChannel, AnyChannels, AttributeValue, Encoding, FlatSamples, Image, Layer, LayerAttributes,
    ReadChannels, ReadLayers, Text, WritableImage,
};
use lumis::engine::{Film, PixelSums};
use lumis::integrator::Settings;
use std::ops::Range;
use std::path::Path;

/// The format version this build writes and reads.
const VERSION: &str = "1";

/// The header attribute that makes an EXR a part.
const ATTRIBUTE: &str = "lumisPart";

/// What parts must have in common to be merged (besides the image size).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Provenance {
    /// Random seed.
    pub seed: u32,
    /// FNV-1a hash of the scene's JSON (as re-serialised, so whitespace does not matter), hex.
    pub scene: String,
    /// The scene file's name, for messages (not compared).
    pub scene_file: String,
    /// The estimator settings (`Settings`' debug text).
    pub settings: String,
    /// The engine that rendered it (`cpu`).
    pub backend: String,
    /// The lumis version that rendered it.
    pub version: String,
}

impl Provenance {
    /// The provenance of a CPU render of the scene file `scene` (already loaded, so valid JSON).
    pub fn new(scene: &Path, seed: u32, settings: &Settings) -> anyhow::Result<Provenance> {
        let text = std::fs::read_to_string(scene)
            .with_context(|| format!("{}: cannot read the scene file", scene.display()))?;
        let json: serde_json::Value = serde_json::from_str(&text)
            .with_context(|| format!("{}: not JSON", scene.display()))?;
        // FNV-1a (64-bit): stable across builds and platforms, unlike std's hasher.
        let hash = json
            .to_string()
            .bytes()
            .fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
                (h ^ b as u64).wrapping_mul(0x0100_0000_01b3)
            });
        let name = scene.file_name().unwrap_or(scene.as_os_str());
        Ok(Provenance {
            seed,
            scene: format!("{hash:016x}"),
            scene_file: name.to_string_lossy().into_owned(),
            settings: format!("{settings:?}"),
            backend: "cpu".into(),
            version: env!("CARGO_PKG_VERSION").into(),
        })
    }

    /// The first field in which `self` differs from `other`: `(name, self's value, other's)`.
    pub fn difference(&self, other: &Provenance) -> Option<(&'static str, String, String)> {
        let fields = |p: &Provenance| {
            [
                ("seed", p.seed.to_string()),
                ("scene", format!("{} ({})", p.scene, p.scene_file)),
                ("settings", p.settings.clone()),
                ("backend", p.backend.clone()),
                ("version", p.version.clone()),
            ]
        };
        let (mine, theirs) = (fields(self), fields(other));
        // The scene file's name is shown, not compared: parts of one scene may come from copies.
        let same = |i: usize| match i {
            1 => self.scene == other.scene,
            _ => mine[i].1 == theirs[i].1,
        };
        (0..mine.len())
            .find(|&i| !same(i))
            .map(|i| (mine[i].0, mine[i].1.clone(), theirs[i].1.clone()))
    }
}

/// A part: the film of some samples of a render, which samples, and where they come from.
#[derive(Clone, Debug)]
pub struct Part {
    /// The sums; `spp` is the number of samples held.
    pub film: Film,
    /// The sample indices held: sorted, disjoint, non-empty ranges.
    pub samples: Vec<Range<u32>>,
    /// What parts must share to be merged.
    pub provenance: Provenance,
}

/// The sums of a pixel in part-file channel order: sum, sumSq, sumEven.
const SUMS: [&str; 3] = ["sum", "sumSq", "sumEven"];
const RGB: [&str; 3] = ["R", "G", "B"];

fn sums_of(p: &PixelSums, which: usize) -> &[f64; 3] {
    [&p.sum, &p.sum_sq, &p.sum_even][which]
}

fn sums_of_mut(p: &mut PixelSums, which: usize) -> &mut [f64; 3] {
    match which {
        0 => &mut p.sum,
        1 => &mut p.sum_sq,
        _ => &mut p.sum_even,
    }
}

impl Part {
    /// Writes the part to `path` (an `.exr`); the error names the file.
    pub fn write(&self, path: &Path) -> anyhow::Result<()> {
        let film = &self.film;
        let mean = film.mean();
        let mut channels = Vec::new();
        for (c, name) in RGB.iter().enumerate() {
            let v = mean.iter().map(|m| m[c]).collect();
            channels.push(AnyChannel::new(*name, FlatSamples::F32(v)));
        }
        for (which, sum) in SUMS.iter().enumerate() {
            for (c, rgb) in RGB.iter().enumerate() {
                let bits = || film.pixels.iter().map(|p| sums_of(p, which)[c].to_bits());
                let hi = bits().map(|b| (b >> 32) as u32).collect();
                let lo = bits().map(|b| b as u32).collect();
                channels.push(AnyChannel::new(
                    format!("lumis.{sum}.{rgb}.hi").as_str(),
                    FlatSamples::U32(hi),
                ));
                channels.push(AnyChannel::new(
                    format!("lumis.{sum}.{rgb}.lo").as_str(),
                    FlatSamples::U32(lo),
                ));
            }
        }
        let p = &self.provenance;
        let fields = [
            ("format", VERSION.to_string()),
            ("samples", format_ranges(&self.samples)),
            ("nonfinite", film.nonfinite.to_string()),
            ("seed", p.seed.to_string()),
            ("scene", p.scene.clone()),
            ("sceneFile", p.scene_file.clone()),
            ("settings", p.settings.clone()),
            ("backend", p.backend.clone()),
            ("version", p.version.clone()),
        ];
        let text: String = fields
            .iter()
            .map(|(key, value)| format!("{key}={}\n", one_ascii_line(value)))
            .collect();
        let mut attributes = LayerAttributes::default();
        attributes.other.insert(
            Text::from(ATTRIBUTE),
            AttributeValue::Text(Text::from(text.as_str())),
        );
        let layer = Layer::new(
            (film.width as usize, film.height as usize),
            attributes,
            Encoding::SMALL_LOSSLESS,
            AnyChannels::sort(channels.into()),
        );
        Image::from_layer(layer)
            .write()
            .to_file(path)
            .with_context(|| format!("{}: cannot write the part file", path.display()))
    }

    /// Reads a part file; every error names the file, and a plain EXR is refused as not a part.
    pub fn read(path: &Path) -> anyhow::Result<Part> {
        let file = path.display();
        if !path.is_file() {
            bail!("{file}: no such file");
        }
        let image = exr::prelude::read()
            .no_deep_data()
            .largest_resolution_level()
            .all_channels()
            .first_valid_layer()
            .all_attributes()
            .from_file(path)
            .with_context(|| format!("{file}: not a readable EXR file"))?;
        let layer = image.layer_data;
        let text = match layer.attributes.other.get(&Text::from(ATTRIBUTE)) {
            Some(AttributeValue::Text(t)) => t.to_string(),
            Some(_) => bail!("{file}: the attribute {ATTRIBUTE} is not text"),
            None => bail!(
                "{file}: not a lumis part file (no {ATTRIBUTE} attribute; `lumis render --sample-range` writes them)"
            ),
        };
        let fields: Vec<(&str, &str)> = text.lines().filter_map(|l| l.split_once('=')).collect();
        let attr = |key: &str| -> anyhow::Result<String> {
            match fields.iter().find(|(k, _)| *k == key) {
                Some((_, v)) => Ok(v.to_string()),
                None => bail!("{file}: {ATTRIBUTE} has no {key}"),
            }
        };
        let version = attr("format")?;
        if version != VERSION {
            bail!("{file}: part format {version}, this lumis reads {VERSION}");
        }
        let number = |key: &str| -> anyhow::Result<u64> {
            let text = attr(key)?;
            text.parse()
                .map_err(|_| anyhow::anyhow!("{file}: {key} is {text:?}, not a number"))
        };
        let samples =
            parse_ranges(&attr("samples")?).map_err(|e| anyhow::anyhow!("{file}: samples: {e}"))?;
        let (width, height) = (layer.size.0 as u32, layer.size.1 as u32);
        let mut film = Film::new(width, height);
        film.spp = samples.iter().map(|r| r.end - r.start).sum();
        film.nonfinite = number("nonfinite")?;
        let pixels = film.pixels.len();
        let channel = |name: &str| -> anyhow::Result<&Vec<u32>> {
            let found = layer
                .channel_data
                .list
                .iter()
                .find(|c| c.name.to_string() == name);
            match found.map(|c| &c.sample_data) {
                Some(FlatSamples::U32(v)) if v.len() == pixels => Ok(v),
                Some(_) => bail!("{file}: channel {name} is not u32 of the image's size"),
                None => bail!("{file}: the channel {name} is missing"),
            }
        };
        for (which, sum) in SUMS.iter().enumerate() {
            for (c, rgb) in RGB.iter().enumerate() {
                let hi = channel(&format!("lumis.{sum}.{rgb}.hi"))?;
                let lo = channel(&format!("lumis.{sum}.{rgb}.lo"))?;
                for ((p, &hi), &lo) in film.pixels.iter_mut().zip(hi).zip(lo) {
                    sums_of_mut(p, which)[c] = f64::from_bits(((hi as u64) << 32) | lo as u64);
                }
            }
        }
        let seed = number("seed")?;
        let provenance = Provenance {
            seed: u32::try_from(seed).with_context(|| format!("{file}: seed {seed}"))?,
            scene: attr("scene")?,
            scene_file: attr("sceneFile")?,
            settings: attr("settings")?,
            backend: attr("backend")?,
            version: attr("version")?,
        };
        Ok(Part {
            film,
            samples,
            provenance,
        })
    }
}

/// A value for a `key=value` line: EXR text holds bytes, not Unicode, so anything outside
/// printable ASCII (and a line break above all) becomes `?`.
fn one_ascii_line(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_ascii_graphic() || c == ' ' {
                c
            } else {
                '?'
            }
        })
        .collect()
}

/// Parses `START..END` (END excluded) into a non-empty range; the message says what is wrong.
pub fn parse_range(text: &str) -> Result<Range<u32>, String> {
    let (start, end) = text
        .split_once("..")
        .ok_or_else(|| format!("{text:?} is not START..END (e.g. 0..64)"))?;
    let number = |s: &str| {
        s.trim().parse::<u32>().map_err(|_| {
            format!(
                "{s:?} in {text:?} is not a sample index (0 to {})",
                u32::MAX
            )
        })
    };
    let (start, end) = (number(start)?, number(end)?);
    if end < start {
        return Err(format!("{text} is reversed (END must exceed START)"));
    }
    if end == start {
        return Err(format!(
            "{text} is empty (END is excluded, so it must exceed START)"
        ));
    }
    Ok(start..end)
}

/// `0..3,5..8`.
pub fn format_ranges(ranges: &[Range<u32>]) -> String {
    let text: Vec<String> = ranges
        .iter()
        .map(|r| format!("{}..{}", r.start, r.end))
        .collect();
    text.join(",")
}

/// Parses [`format_ranges`]' text, checking that the ranges are sorted and disjoint.
pub fn parse_ranges(text: &str) -> Result<Vec<Range<u32>>, String> {
    let ranges = text
        .split(',')
        .map(parse_range)
        .collect::<Result<Vec<_>, _>>()?;
    if ranges.windows(2).any(|w| w[1].start < w[0].end) {
        return Err(format!("{text} is not sorted and disjoint"));
    }
    Ok(ranges)
}

/// The union of disjoint ranges, sorted, with touching ones joined (`0..3` and `3..8` make
/// `0..8`).
pub fn union(mut ranges: Vec<Range<u32>>) -> Vec<Range<u32>> {
    ranges.sort_by_key(|r| r.start);
    let mut out: Vec<Range<u32>> = Vec::new();
    for r in ranges {
        match out.last_mut() {
            Some(last) if last.end == r.start => last.end = r.end,
            _ => out.push(r),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_parse_format_and_join() {
        assert_eq!(parse_range("3..8"), Ok(3..8));
        assert!(parse_range("5..5").unwrap_err().contains("empty"));
        assert!(parse_range("8..3").unwrap_err().contains("reversed"));
        assert!(parse_range("3").unwrap_err().contains("START..END"));
        assert!(parse_range("a..3").unwrap_err().contains("sample index"));
        assert_eq!(parse_ranges("0..3,5..8"), Ok(vec![0..3, 5..8]));
        assert!(parse_ranges("0..3,2..8").is_err());
        assert_eq!(union(vec![5..8, 0..3, 3..4]), vec![0..4, 5..8]);
        assert_eq!(format_ranges(&[0..4, 5..8]), "0..4,5..8");
    }

    /// Every sum survives the file bit for bit, including values an f32 cannot hold.
    #[test]
    fn part_files_round_trip_exactly() {
        let mut film = Film::new(3, 2);
        film.spp = 7;
        film.nonfinite = 2;
        for (i, p) in film.pixels.iter_mut().enumerate() {
            let x = 0.1 + i as f64 / 3.0;
            *p = PixelSums {
                sum: [x, x * 1e-300, -x],
                sum_sq: [x * x, 1e300, f64::MIN_POSITIVE],
                sum_even: [x / 7.0, 0.0, 1.0 + f64::EPSILON],
            };
        }
        let part = Part {
            film,
            samples: vec![0..3, 10..14],
            provenance: Provenance {
                seed: 9,
                scene: "abc".into(),
                scene_file: "s\u{e9}.json".into(),
                settings: "Settings { .. }".into(),
                backend: "cpu".into(),
                version: "0.1.0".into(),
            },
        };
        let path = std::env::temp_dir().join(format!("lumis-part-{}.exr", std::process::id()));
        part.write(&path).unwrap();
        let back = Part::read(&path).unwrap();
        std::fs::remove_file(&path).ok();
        assert_eq!(back.samples, part.samples);
        assert_eq!((back.film.spp, back.film.nonfinite), (7, 2));
        assert_eq!(back.provenance.scene_file, "s?.json");
        assert_eq!(back.provenance.difference(&part.provenance), None);
        for (a, b) in back.film.pixels.iter().zip(&part.film.pixels) {
            for w in 0..3 {
                let bits = |p: &PixelSums| sums_of(p, w).map(f64::to_bits);
                assert_eq!(bits(a), bits(b));
            }
        }
    }
}
