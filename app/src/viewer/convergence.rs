//! Error of a progressive image: relMSE against a reference when one is loaded, otherwise the
//! reference-free estimate from the film's two independent half images, plus a per-pixel
//! relative error for the false-colour view.

use glam::Vec3;
use lumis::engine::Film;
use lumis::metrics::relmse;

/// One point of a convergence curve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurvePoint {
    /// Render time of the lane so far, in seconds.
    pub seconds: f64,
    /// Samples per pixel.
    pub spp: u32,
    /// relMSE (measured or estimated, see [`ErrorSource`]).
    pub relmse: f64,
}

/// Where an error value comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ErrorSource {
    /// Against the loaded reference image.
    Reference,
    /// `E[(A−B)²]/4` from the two half images (no reference loaded).
    HalfBuffers,
}

impl ErrorSource {
    /// Name used in the UI and the CSV.
    pub fn label(self) -> &'static str {
        match self {
            ErrorSource::Reference => "reference",
            ErrorSource::HalfBuffers => "half-buffer estimate",
        }
    }
}

/// The luminance weights of Rec. 709, for scalar per-pixel errors.
fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

/// The error of `film`'s mean image. With a reference of the same size, the relMSE against it;
/// otherwise [`Film::half_buffer_error`], normalised as [`relmse`] so that both kinds of curve
/// sit on the same scale (the same estimate `lumis bench` uses). `None` before the half-buffer
/// estimate has two samples.
pub fn film_error(
    film: &Film,
    mean: &[Vec3],
    reference: Option<&[Vec3]>,
) -> Option<(f64, ErrorSource)> {
    if let Some(r) = reference.filter(|r| r.len() == mean.len()) {
        return (film.spp >= 1).then(|| (relmse(mean, r), ErrorSource::Reference));
    }
    if film.spp < 2 {
        return None;
    }
    Some((film.half_buffer_error().0, ErrorSource::HalfBuffers))
}

/// Per-pixel relative error of the luminance for the false-colour view: against the reference
/// when given, else the half-buffer standard error (`|A−B|/2` for equal halves) over the mean.
pub fn pixel_errors(film: &Film, mean: &[Vec3], reference: Option<&[Vec3]>) -> Vec<f32> {
    if let Some(r) = reference.filter(|r| r.len() == mean.len()) {
        return mean
            .iter()
            .zip(r)
            .map(|(m, r)| (luminance(*m) - luminance(*r)).abs() / (luminance(*r).abs() + 0.01))
            .collect();
    }
    if film.spp < 2 {
        return vec![f32::NAN; mean.len()];
    }
    // Standard error of the mean from the halves' difference (see Film::half_buffer_error).
    let n = film.spp as f32;
    let scale = (film.spp.div_ceil(2) as f32 * (film.spp / 2) as f32).sqrt() / n;
    let (a, b) = film.half_means();
    a.iter()
        .zip(&b)
        .zip(mean)
        .map(|((a, b), m)| scale * (luminance(*a) - luminance(*b)).abs() / (luminance(*m) + 0.01))
        .collect()
}

/// The curves of every lane as CSV: `lane,strategy,seconds,spp,relmse,error_source`.
pub fn curves_csv(curves: &[(String, ErrorSource, Vec<CurvePoint>)]) -> String {
    let mut out = String::from("lane,strategy,seconds,spp,relmse,error_source\n");
    for (i, (label, source, points)) in curves.iter().enumerate() {
        for p in points {
            out += &format!(
                "{i},{label},{:.6},{},{:.6e},{}\n",
                p.seconds,
                p.spp,
                p.relmse,
                source.label()
            );
        }
    }
    out
}
