//! Values: numbers, colours and spectra, and how Mitsuba 3's RGB variants turn them into the
//! RGB a parameter sees (`Properties::get_texture_impl`, `spectrum_list_to_srgb`, Mitsuba
//! 3.9.1): a float or `<rgb>` as given; a one-value `<spectrum>` grey, except in an emitter's
//! `radiance`, where it is that value times the sRGB of the equal-energy spectrum (a uniform
//! spectrum is not white under D65); a wavelength list (`value="400:0.1, 500:0.2"` or a `.spd`
//! file) integrated against the CIE 1931 curves (weighted by D65 unless it is emission) and
//! converted to linear sRGB, clamped to [0, 1] for reflectances and to ≥ 0 otherwise. Also the
//! named indices of refraction of dielectrics (`lookup_ior`).

use super::cie;
use super::plugin::{Plugin, Prop, Value};
use super::xml::{Element, Pos};
use crate::scene::error::SceneError;
use glam::DVec3;

/// The tokens of a list value: Mitsuba separates them by spaces and commas.
pub fn tokens(s: &str) -> Vec<&str> {
    s.split([' ', ',', '\t', '\n', '\r'])
        .filter(|t| !t.is_empty())
        .collect()
}

/// A finite number; the error names `pos`.
pub fn parse_number(s: &str, pos: &Pos) -> Result<f64, SceneError> {
    match s.trim().parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(_) => Err(pos.error(format!("`{s}` is not a finite number"))),
        Err(_) => Err(pos.error(format!("`{s}` is not a number"))),
    }
}

/// Three numbers, or with `allow_one` one number for all three.
pub fn parse_triple(s: &str, pos: &Pos, allow_one: bool) -> Result<DVec3, SceneError> {
    let t = tokens(s);
    match t.len() {
        1 if allow_one => Ok(DVec3::splat(parse_number(t[0], pos)?)),
        3 => Ok(DVec3::new(
            parse_number(t[0], pos)?,
            parse_number(t[1], pos)?,
            parse_number(t[2], pos)?,
        )),
        n => Err(pos.error(format!(
            "expected {}3 numbers, found {n}",
            if allow_one { "1 or " } else { "" }
        ))),
    }
}

/// A `<spectrum>` property's value.
#[derive(Clone, Debug, PartialEq)]
pub enum Spectrum {
    /// One value at every wavelength.
    Uniform(f64),
    /// Values at increasing wavelengths (nm), linearly interpolated, zero outside.
    List {
        /// Wavelengths in nm, increasing, at least two.
        wavelengths: Vec<f64>,
        /// The values there.
        values: Vec<f64>,
    },
}

/// `<spectrum value="…">` or `<spectrum filename="x.spd">` (the file name already resolved by
/// [`super::xml`]).
pub fn parse_spectrum(el: &Element) -> Result<Spectrum, SceneError> {
    match (el.attr("value"), el.attr("filename")) {
        (Some(a), None) => {
            let t = tokens(&a.value);
            if let [one] = t.as_slice()
                && !one.contains(':')
            {
                return Ok(Spectrum::Uniform(parse_number(one, &a.pos)?));
            }
            let mut wl = Vec::new();
            let mut vals = Vec::new();
            for tok in t {
                let (w, v) = tok.split_once(':').ok_or_else(|| {
                    a.pos.error(format!(
                        "`{tok}` is not a wavelength:value pair (a spectrum is one value, or \
                         pairs like 400:0.1, 500:0.2)"
                    ))
                })?;
                wl.push(parse_number(w, &a.pos)?);
                vals.push(parse_number(v, &a.pos)?);
            }
            list(wl, vals, &a.pos)
        }
        (None, Some(a)) => {
            let path = std::path::Path::new(&a.value);
            let text = std::fs::read_to_string(path)
                .map_err(|e| a.pos.error(format!("cannot read {}: {e}", path.display())))?;
            let (wl, vals) = parse_spd(&text).map_err(|(line, msg)| {
                a.pos
                    .error(format!("{} line {line}: {msg}", path.display()))
            })?;
            list(wl, vals, &a.pos)
        }
        _ => Err(el
            .pos
            .error("<spectrum> needs either `value` or `filename` (but not both)")),
    }
}

/// Checks a wavelength list as Mitsuba does: at least two entries, increasing wavelengths.
fn list(wavelengths: Vec<f64>, values: Vec<f64>, pos: &Pos) -> Result<Spectrum, SceneError> {
    if wavelengths.len() < 2 {
        return Err(pos.error("a spectrum list needs at least two wavelength:value pairs"));
    }
    if let Some(w) = wavelengths.windows(2).find(|w| w[1] <= w[0]) {
        return Err(pos.error(format!(
            "wavelengths must increase, but {} follows {}",
            w[1], w[0]
        )));
    }
    Ok(Spectrum::List {
        wavelengths,
        values,
    })
}

/// The `(wavelength, value)` lines of a `.spd` file (`#` starts a comment); an error gives the
/// line number.
pub fn parse_spd(text: &str) -> Result<(Vec<f64>, Vec<f64>), (usize, String)> {
    let (mut wl, mut vals) = (Vec::new(), Vec::new());
    for (i, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("");
        let t: Vec<&str> = line.split_whitespace().collect();
        match t.as_slice() {
            [] => {}
            [w, v] => match (w.parse::<f64>(), v.parse::<f64>()) {
                (Ok(w), Ok(v)) if w.is_finite() && v.is_finite() => {
                    wl.push(w);
                    vals.push(v);
                }
                _ => return Err((i + 1, format!("`{}` is not two numbers", line.trim()))),
            },
            _ => return Err((i + 1, "expected a wavelength and a value".to_owned())),
        }
    }
    Ok((wl, vals))
}

/// Linear Rec. 709 RGB from CIE XYZ, with Mitsuba's single-precision matrix (`xyz_to_srgb`).
pub fn xyz_to_srgb(xyz: DVec3) -> DVec3 {
    const M: [[f32; 3]; 3] = [
        [3.240479, -1.53715, -0.498535],
        [-0.969256, 1.875991, 0.041556],
        [0.055648, -0.204043, 1.057311],
    ];
    let row = |r: [f32; 3]| r[0] as f64 * xyz.x + r[1] as f64 * xyz.y + r[2] as f64 * xyz.z;
    DVec3::new(row(M[0]), row(M[1]), row(M[2]))
}

/// A table of [`cie`] linearly interpolated at `w` nm (zero outside 360–830 nm).
fn table(t: &[f32; cie::SAMPLES], w: f64) -> f64 {
    if !(cie::MIN_NM..=cie::MAX_NM).contains(&w) {
        return 0.0;
    }
    let x = (w - cie::MIN_NM) * ((cie::SAMPLES - 1) as f64 / (cie::MAX_NM - cie::MIN_NM));
    let i0 = (x as usize).min(cie::SAMPLES - 2);
    let w1 = x - i0 as f64;
    (1.0 - w1) * t[i0] as f64 + w1 * t[i0 + 1] as f64
}

/// The linear sRGB of a wavelength list, as Mitsuba's `spectrum_list_to_srgb`: 1000 uniform
/// steps over 360–830 nm (those outside the list's range skipped), the list interpolated
/// linearly, times the CIE 1931 curves and, with `d65`, the D65 illuminant; then clamped to
/// [0, 1] when `bounded`, else to ≥ 0. Returns the colour and whether it was clamped.
pub fn spectrum_list_to_srgb(wl: &[f64], vals: &[f64], bounded: bool, d65: bool) -> (DVec3, bool) {
    const STEPS: usize = 1000;
    let (first, last) = (wl[0], wl[wl.len() - 1]);
    let mut xyz = DVec3::ZERO;
    for i in 0..STEPS {
        let w = cie::MIN_NM + (i as f64 / (STEPS - 1) as f64) * (cie::MAX_NM - cie::MIN_NM);
        if w < first || w > last {
            continue;
        }
        // The last interval whose start is at or below w.
        let k = wl[..wl.len() - 1]
            .partition_point(|&x| x <= w)
            .saturating_sub(1);
        let (w0, w1, v0, v1) = (wl[k], wl[k + 1], vals[k], vals[k + 1]);
        let v = ((w - w1) * v0 + (w0 - w) * v1) / (w0 - w1);
        let weight = if d65 {
            table(&cie::D65, w) * cie::D65_NORMALIZATION
        } else {
            1.0
        };
        let cmf = DVec3::new(
            table(&cie::CIE_X, w),
            table(&cie::CIE_Y, w),
            table(&cie::CIE_Z, w),
        );
        xyz += cmf * v * weight;
    }
    xyz *= (cie::MAX_NM - cie::MIN_NM) * cie::Y_NORMALIZATION / STEPS as f64;
    let rgb = xyz_to_srgb(xyz);
    let clamped = if bounded {
        rgb.clamp(DVec3::ZERO, DVec3::ONE)
    } else {
        rgb.max(DVec3::ZERO)
    };
    (clamped, clamped != rgb)
}

/// What a colour parameter is, which decides how Mitsuba converts a spectrum for it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Slot {
    /// A reflectance (`reflectance`, `diffuse_reflectance`, …): bounded, D65-weighted.
    Reflectance,
    /// Emitted radiance (`radiance`): unbounded, not D65-weighted, a uniform spectrum tinted.
    Emission,
    /// Anything else (`eta`, `k`, `alpha`): unbounded, D65-weighted.
    Unbounded,
}

/// The RGB a constant property (`float`, `integer`, `rgb`, `spectrum`) gives parameter slot
/// `slot`, or `None` for an object (a texture). A clamped spectrum adds a warning.
pub fn constant_color(
    prop: &Prop,
    slot: Slot,
    warnings: &mut Vec<String>,
) -> Result<Option<DVec3>, SceneError> {
    Ok(Some(match &prop.value {
        Value::Float(x) => DVec3::splat(*x),
        Value::Int(i) => DVec3::splat(*i as f64),
        Value::Rgb(c) => *c,
        Value::Spectrum(Spectrum::Uniform(x)) => match slot {
            Slot::Emission => *x * xyz_to_srgb(DVec3::ONE),
            _ => DVec3::splat(*x),
        },
        Value::Spectrum(Spectrum::List {
            wavelengths,
            values,
        }) => {
            let (rgb, clamped) = spectrum_list_to_srgb(
                wavelengths,
                values,
                slot == Slot::Reflectance,
                slot != Slot::Emission,
            );
            if clamped {
                warnings.push(format!(
                    "{}: the spectrum's RGB is out of gamut and was clamped to {:?}, as Mitsuba \
                     does",
                    prop.pos().describe(),
                    rgb.to_array()
                ));
            }
            rgb
        }
        Value::Object(_) => return Ok(None),
        _ => return Err(prop.wrong_type("a colour (rgb, float, spectrum) or a texture")),
    }))
}

/// A scalar parameter from a constant property (a colour's mean, as Mitsuba's `eval_1` of a
/// constant); `None` for a texture.
pub fn constant_scalar(prop: &Prop) -> Result<Option<f64>, SceneError> {
    Ok(match &prop.value {
        Value::Float(x) => Some(*x),
        Value::Int(i) => Some(*i as f64),
        Value::Object(_) => None,
        Value::Rgb(_) | Value::Spectrum(_) => {
            let c = constant_color(prop, Slot::Unbounded, &mut Vec::new())?.unwrap_or_default();
            Some((c.x + c.y + c.z) / 3.0)
        }
        _ => return Err(prop.wrong_type("a number or a texture")),
    })
}

/// Named indices of refraction Mitsuba knows (`include/mitsuba/render/ior.h`, from Hecht,
/// *Optics*, at about 589 nm).
const IOR_NAMES: [(&str, f64); 23] = [
    ("vacuum", 1.0),
    ("helium", 1.000036),
    ("hydrogen", 1.000132),
    ("air", 1.000277),
    ("carbon dioxide", 1.00045),
    ("water", 1.3330),
    ("acetone", 1.36),
    ("ethanol", 1.361),
    ("carbon tetrachloride", 1.461),
    ("glycerol", 1.4729),
    ("benzene", 1.501),
    ("silicone oil", 1.52045),
    ("bromine", 1.661),
    ("water ice", 1.31),
    ("fused quartz", 1.458),
    ("pyrex", 1.470),
    ("acrylic glass", 1.49),
    ("polypropylene", 1.49),
    ("bk7", 1.5046),
    ("sodium chloride", 1.544),
    ("amber", 1.55),
    ("pet", 1.5750),
    ("diamond", 2.419),
];

/// An index of refraction `name` of `plugin`: a float, or a name from Mitsuba's table
/// (case-insensitive), or `default` (a name) when absent. Mitsuba stores it in single
/// precision, so lumis does too.
pub fn ior(plugin: &Plugin, name: &str, default: &str) -> Result<f64, SceneError> {
    let lookup = |key: &str, prop: Option<&Prop>| -> Result<f64, SceneError> {
        let lower = key.to_ascii_lowercase();
        match IOR_NAMES.iter().find(|(n, _)| *n == lower) {
            Some((_, v)) => Ok(*v as f32 as f64),
            None => {
                let known: Vec<&str> = IOR_NAMES.iter().map(|(n, _)| *n).collect();
                let msg = format!(
                    "unknown index of refraction `{key}` (Mitsuba knows: {})",
                    known.join(", ")
                );
                Err(prop.map_or_else(|| plugin.error(&msg), |p| p.error(&msg)))
            }
        }
    };
    match plugin.get(name) {
        None => lookup(default, None),
        Some(p) => match &p.value {
            Value::Float(x) => Ok(*x as f32 as f64),
            Value::Int(i) => Ok(*i as f32 as f64),
            Value::Str(s) => lookup(s, Some(p)),
            _ => Err(p.wrong_type("a number or a material name")),
        },
    }
}
