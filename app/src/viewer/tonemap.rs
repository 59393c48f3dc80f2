//! From linear radiance to display pixels: exposure, clamp and the sRGB curve (the same as
//! `lumis render`'s PNG output), a false-colour map of the per-pixel relative error, or a signed
//! false-colour map of the difference of two images ([`Content`]).

use glam::Vec3;
/// One display pixel (sRGB bytes) of linear `c` at a gain (`2^exposure`), as `lumis render`
/// writes PNGs.
pub use lumis::image_io::srgb8;

/// What each pane shows per pixel. Display only: switching never restarts accumulation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Content {
    /// The image, exposed and sRGB-encoded.
    #[default]
    Image,
    /// The per-pixel relative error in false colour ([`error_colour`]): against the reference
    /// where one is loaded, else the half-buffer estimate.
    RelativeError,
    /// The signed relative difference `(A − B)/(|B| + 0.01)` of the luminance in a diverging map
    /// ([`difference_colour`]): in the wipe, its A against its B; elsewhere each pane against
    /// the reference, or without one against the first pane.
    Difference,
    /// Where light samples and where BSDF samples carry the direct light
    /// ([`technique_colour`]), from the weights the estimator actually applied (CPU lanes).
    TechniqueMap,
}

impl Content {
    /// Every content, in menu order (one line per mode).
    pub const ALL: [Content; 4] = [
        Content::Image,
        Content::RelativeError,
        Content::Difference,
        Content::TechniqueMap,
    ];

    /// Its menu name.
    pub fn label(self) -> &'static str {
        match self {
            Content::Image => "image",
            Content::RelativeError => "relative error",
            Content::Difference => "difference A − B",
            Content::TechniqueMap => "technique map (light vs BSDF)",
        }
    }
}

/// How the image is shown.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Display {
    /// Exposure in stops: pixels are multiplied by `2^exposure`.
    pub exposure: f32,
    /// What the panes show.
    pub content: Content,
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

/// The diverging map of [`Content::Difference`], from blue (B brighter) through light grey
/// (equal) to red (A brighter): Moreland's cool-warm at five stops, whose ends are equally
/// bright so that neither sign looks larger.
const COOL_WARM: [[f32; 3]; 5] = [
    [0.230, 0.299, 0.754],
    [0.552, 0.690, 0.996],
    [0.866, 0.866, 0.866],
    [0.957, 0.604, 0.482],
    [0.706, 0.016, 0.150],
];

/// The false colour (sRGB bytes) of signed relative difference `d`: `|d|` on the same decades
/// as the error map ([`ERROR_DECADES`]), below 10⁻³ grey, at 1 and over the ends; NaN is
/// dark grey.
pub fn difference_colour(d: f32) -> [u8; 3] {
    if !d.is_finite() {
        return [64, 64, 64];
    }
    let (lo, hi) = ERROR_DECADES;
    let m = ((d.abs().max(1e-12).log10() - lo) / (hi - lo)).clamp(0.0, 1.0);
    // t in [0, 4]: 0 is −1, 2 is 0, 4 is +1.
    let t = 2.0 + 2.0 * m * d.signum();
    let i = (t as usize).min(3);
    let f = t - i as f32;
    std::array::from_fn(|c| {
        let v = COOL_WARM[i][c] * (1.0 - f) + COOL_WARM[i + 1][c] * f;
        (v * 255.0 + 0.5) as u8
    })
}

/// The technique map's hues at a pixel's light share 0 (BSDF samples carry all its direct
/// light), ½ (both alike) and 1 (light samples carry all of it): blue, light grey, orange.
const TECHNIQUE_HUES: [[f32; 3]; 3] = [[0.15, 0.55, 1.0], [0.85, 0.85, 0.85], [1.0, 0.5, 0.05]];

/// The hue (linear in [0, 1]) of light share `s` (see [`TECHNIQUE_HUES`]).
pub fn technique_hue(s: f32) -> [f32; 3] {
    let t = s.clamp(0.0, 1.0) * 2.0;
    let i = (t as usize).min(1);
    let f = t - i as f32;
    std::array::from_fn(|c| TECHNIQUE_HUES[i][c] * (1.0 - f) + TECHNIQUE_HUES[i + 1][c] * f)
}

/// The technique map's colour (sRGB bytes) of a pixel whose light samples contributed `light`
/// and whose BSDF samples contributed `bsdf` (means, linear): the hue of the light share
/// ([`lumis::integrator::technique::light_share`]), as bright as the direct light exposed by
/// `gain` (at least a quarter, so that dim regions still show their hue); dark grey where no
/// direct light arrived.
pub fn technique_colour(light: Vec3, bsdf: Vec3, gain: f32) -> [u8; 3] {
    let Some(s) = lumis::integrator::technique::light_share(light, bsdf) else {
        return [40, 40, 40];
    };
    let direct = srgb8(Vec3::splat(luminance(light + bsdf) * gain), 1.0)[0] as f32 / 255.0;
    let brightness = direct.max(0.25);
    technique_hue(s).map(|h| (h * brightness * 255.0 + 0.5) as u8)
}

/// The technique map of per-pixel parts ([`lumis::integrator::Technique::ALL`] order) as RGB
/// bytes.
pub fn technique_rgb(parts: &[[Vec3; 4]], gain: f32) -> Vec<u8> {
    use lumis::integrator::Technique;
    parts
        .iter()
        .flat_map(|p| {
            technique_colour(
                p[Technique::Light.index()],
                p[Technique::Bsdf.index()],
                gain,
            )
        })
        .collect()
}

/// The luminance of linear `c` (Rec. 709 weights).
pub fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

/// Per pixel, the signed relative difference of the luminance `(a − b)/(|b| + 0.01)`, the
/// denominator as in relMSE; NaN where the sizes differ (a preview against a full image).
pub fn signed_difference(a: &[Vec3], b: &[Vec3]) -> Vec<f32> {
    if a.len() != b.len() {
        return vec![f32::NAN; a.len().max(1)];
    }
    a.iter()
        .zip(b)
        .map(|(a, b)| (luminance(*a) - luminance(*b)) / (luminance(*b).abs() + 0.01))
        .collect()
}

/// The displayed pixels, RGB bytes row-major. False colour needs per-pixel errors of the same
/// size; previews have none, so they are shown as images. (The difference, which needs two
/// images, is [`difference_rgb`].)
pub fn display_rgb(pixels: &[Vec3], errors: &[f32], display: Display) -> Vec<u8> {
    if display.content == Content::RelativeError && errors.len() == pixels.len() {
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

/// The difference view of `a` against `b` as RGB bytes (see [`signed_difference`]).
pub fn difference_rgb(a: &[Vec3], b: &[Vec3]) -> Vec<u8> {
    signed_difference(a, b)
        .into_iter()
        .flat_map(difference_colour)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The diverging map is grey at 0, red for A brighter, blue for B brighter, symmetric in
    /// brightness, and saturates at ±1 (the end stops).
    #[test]
    fn difference_map_is_signed_and_symmetric() {
        let grey = difference_colour(0.0);
        assert_eq!(grey, difference_colour(1e-5));
        assert_eq!(grey, [221, 221, 221]);
        let (red, blue) = (difference_colour(0.1), difference_colour(-0.1));
        assert!(red[0] > red[2] && blue[2] > blue[0], "{red:?} {blue:?}");
        assert_eq!(difference_colour(5.0), difference_colour(1.0));
        assert_eq!(difference_colour(1.0), [180, 4, 38]);
        assert_eq!(difference_colour(-1.0), [59, 76, 192]);
        assert_eq!(difference_colour(f32::NAN), [64, 64, 64]);
        let d = signed_difference(&[Vec3::splat(2.0)], &[Vec3::ONE]);
        assert!((d[0] - 1.0 / 1.01).abs() < 1e-6);
    }

    /// The technique map: blue where BSDF samples carry the direct light, orange where light
    /// samples do, grey where both alike; brighter with more direct light; dark grey without.
    #[test]
    fn technique_map_colours_the_light_share() {
        let bright = Vec3::splat(10.0);
        let [r, _, b] = technique_colour(Vec3::ZERO, bright, 1.0);
        assert!(b > 200 && r < 60, "all BSDF: {r} {b}");
        let [r, _, b] = technique_colour(bright, Vec3::ZERO, 1.0);
        assert!(r > 200 && b < 30, "all light: {r} {b}");
        let [r, g, b] = technique_colour(bright, bright, 1.0);
        assert!(r == g && g == b && r > 200, "half: {r} {g} {b}");
        let dim = technique_colour(Vec3::splat(0.01), Vec3::ZERO, 1.0);
        let lit = technique_colour(Vec3::splat(0.3), Vec3::ZERO, 1.0);
        assert!(dim[0] < lit[0] && dim[0] >= 63, "{dim:?} {lit:?}");
        assert_eq!(technique_colour(Vec3::ZERO, Vec3::ZERO, 1.0), [40, 40, 40]);
    }
}
