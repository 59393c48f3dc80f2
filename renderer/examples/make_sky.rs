//! Writes an analytic sky with a sun as a latitude-longitude environment map (linear RGB float
//! EXR), in the layout of the scene format's `background.envmap`: pixel row `j` is centred at
//! `v = j / (H − 1)` (row 0 at the zenith, row H−1 at the nadir), column `i` at
//! `u = (i + 0.5) / W`, and `(u, v)` is the direction `d = (sin 2πu · sin πv, cos πv,
//! −cos 2πu · sin πv)`, the inverse of `u = atan2(d.x, −d.z) / 2π`, `v = acos(d.y) / π`.
//!
//! The model is hand-made (not a fit to measured skies), smooth, and in units of the zenith's
//! luminance (Rec. 709 weights), times `--sky`:
//! - above the horizon, a blue zenith blending into a brighter, whiter horizon with weight
//!   `(1 − cos θ)^4`, plus a warm circumsolar glow `0.12 · HG(g = 0.8, cos γ)` (the Henyey-Greenstein
//!   lobe, γ the angle to the sun);
//! - below it, a dark brown ground (luminance ~0.2) that fades into the horizon colour over the first
//!   ~3° (haze), so the map has no hard edge there;
//! - a uniform sun disk of angular radius `--sun-radius` degrees, radiance `--sun-contrast` times the
//!   zenith's luminance, slightly warm, cut by the horizon.
//!
//! The sun sits at elevation `--sun-elevation` and azimuth `--sun-azimuth` (degrees, the map's
//! azimuth `2πu`: 0 towards −z, 90 towards +x), i.e. at column `azimuth/360 · W`. A scene's
//! `rotate_y_deg = ρ` (Mitsuba's `to_world` rotation about +y) moves it to azimuth `azimuth − ρ`.
//!
//! Each pixel holds the solid-angle-weighted mean radiance over its footprint (the half-open cell
//! `u ∈ [i/W, (i+1)/W)`, `v ∈ [(j − ½)/(H − 1), (j + ½)/(H − 1)]` clipped to `[0, 1]`): `N × N`
//! stratified points (`--supersample`, default 8), and `8N × 8N` for the sun disk in the pixels
//! near it, so a sun smaller than a pixel is neither aliased nor lost. There is no randomness:
//! the output is a deterministic function of the arguments.
//!
//! The output is original (computed by this program from the formulas above, from no photograph
//! or third-party map) and may be redistributed under the licence of this repository.
//!
//! The maps in the repository were made by
//! `cargo run --release -p lumis-renderer --example make_sky -- --width 512 --height 256 --sun-elevation 35 --sun-azimuth 60 --sun-radius 0.75 --sun-contrast 3e4 assets/envmaps/sky.exr`
//! (`assets/envmaps/README.md`) and
//! `cargo run --release -p lumis-renderer --example make_sky -- --width 128 --height 64 --sun-elevation 40 --sun-azimuth 120 --sun-radius 5 --sun-contrast 1e3 tests/data/scenes/envmap_test_sky.exr`
//! (the soft-sun map of `tests/data/scenes/envmap_objects.json`).

use glam::{DVec3, Vec3};
use lumis::image_io::Image;
use std::f64::consts::PI;
use std::path::PathBuf;

const USAGE: &str = "usage: make_sky [--width W] [--height H] [--sun-elevation DEG] \
[--sun-azimuth DEG] [--sun-radius DEG] [--sun-contrast X] [--sky X] [--supersample N] OUT.exr";

/// The model's parameters (the command line).
struct Sky {
    width: u32,
    height: u32,
    /// Unit direction to the sun's centre.
    sun: DVec3,
    /// Cosine of the sun's angular radius.
    cos_sun_radius: f64,
    /// Angular radius, radians.
    sun_radius: f64,
    /// Sun radiance over the zenith's luminance.
    sun_contrast: f64,
    /// Overall scale (the zenith's luminance).
    sky: f64,
    supersample: u32,
}

/// Rec. 709 luminance.
fn luminance(c: DVec3) -> f64 {
    c.dot(DVec3::new(0.2126, 0.7152, 0.0722))
}

/// `c` rescaled to luminance 1.
fn unit_luminance(c: DVec3) -> DVec3 {
    c / luminance(c)
}

fn smoothstep(e0: f64, e1: f64, x: f64) -> f64 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The direction of map coordinates `(u, v)` (Mitsuba 3's `envmap` convention).
fn direction(u: f64, v: f64) -> DVec3 {
    let (sin_t, cos_t) = (PI * v).sin_cos();
    let (sin_p, cos_p) = (2.0 * PI * u).sin_cos();
    DVec3::new(sin_p * sin_t, cos_t, -cos_p * sin_t)
}

impl Sky {
    /// Radiance of the sky without the sun disk, in zenith-luminance units.
    fn sky(&self, d: DVec3) -> DVec3 {
        let zenith = unit_luminance(DVec3::new(0.22, 0.42, 1.0));
        let horizon = 2.5 * unit_luminance(DVec3::new(0.80, 0.88, 1.0));
        let ground = 0.2 * unit_luminance(DVec3::new(0.30, 0.25, 0.19));
        let glow_colour = unit_luminance(DVec3::new(1.0, 0.85, 0.65));
        let y = d.y;
        if y >= 0.0 {
            let t = (1.0 - y).powi(4);
            let g = 0.8;
            let cos_gamma = d.dot(self.sun).clamp(-1.0, 1.0);
            let hg = (1.0 - g * g) / (1.0 + g * g - 2.0 * g * cos_gamma).powf(1.5);
            zenith.lerp(horizon, t) + glow_colour * (0.12 * hg)
        } else {
            // Haze over the first ~3° below the horizon (sin 3° ≈ 0.05).
            horizon.lerp(ground, smoothstep(0.0, 0.05, -y))
        }
    }

    /// Radiance of the sun disk (zero outside it and below the horizon), zenith-luminance units.
    fn sun(&self, d: DVec3) -> DVec3 {
        if d.y >= 0.0 && d.dot(self.sun) >= self.cos_sun_radius {
            self.sun_contrast * unit_luminance(DVec3::new(1.0, 0.93, 0.84))
        } else {
            DVec3::ZERO
        }
    }

    /// Solid-angle-weighted mean of `f` over pixel `(i, j)` with `n × n` stratified points.
    fn pixel_mean(&self, i: u32, j: u32, n: u32, f: impl Fn(DVec3) -> DVec3) -> DVec3 {
        let (w, h) = (self.width as f64, self.height as f64);
        let u0 = i as f64 / w;
        let half = 0.5 / (h - 1.0);
        let v_centre = j as f64 / (h - 1.0);
        let (v0, v1) = ((v_centre - half).max(0.0), (v_centre + half).min(1.0));
        let (mut sum, mut weight) = (DVec3::ZERO, 0.0);
        for b in 0..n {
            let v = v0 + (v1 - v0) * (b as f64 + 0.5) / n as f64;
            // dω = 2π² sin θ du dv with θ = πv: the weight of this row of points.
            let sin_t = (PI * v).sin();
            for a in 0..n {
                let u = u0 + (a as f64 + 0.5) / (n as f64 * w);
                sum += f(direction(u, v)) * sin_t;
            }
            weight += sin_t * n as f64;
        }
        sum / weight
    }

    /// Could pixel `(i, j)` overlap the sun disk? Conservative: its centre lies within the sun's
    /// radius plus a pixel's full height and width (in angle) of the sun's centre.
    fn near_sun(&self, i: u32, j: u32) -> bool {
        let (w, h) = (self.width as f64, self.height as f64);
        let centre = direction((i as f64 + 0.5) / w, j as f64 / (h - 1.0));
        let margin = PI / (h - 1.0) + 2.0 * PI / w;
        centre.dot(self.sun).clamp(-1.0, 1.0).acos() <= self.sun_radius + margin
    }

    fn render(&self) -> Image {
        let mut data = Vec::with_capacity((self.width * self.height) as usize);
        let n = self.supersample;
        for j in 0..self.height {
            for i in 0..self.width {
                let mut c = self.pixel_mean(i, j, n, |d| self.sky(d));
                if self.near_sun(i, j) {
                    c += self.pixel_mean(i, j, 8 * n, |d| self.sun(d));
                }
                let c = c * self.sky;
                data.push(Vec3::new(c.x as f32, c.y as f32, c.z as f32));
            }
        }
        Image {
            width: self.width,
            height: self.height,
            data,
        }
    }
}

/// The value of option `name`.
fn number<T: std::str::FromStr>(name: &str, value: &str) -> Result<T, String> {
    value
        .parse()
        .map_err(|_| format!("{name}: cannot parse '{value}'"))
}

/// The command line: `--name value` options and one output path.
fn parse() -> Result<(Sky, PathBuf), String> {
    let mut width = 512u32;
    let mut height = 256u32;
    let (mut elevation, mut azimuth, mut radius) = (35.0f64, 60.0f64, 0.75f64);
    let (mut contrast, mut sky, mut supersample) = (3e4f64, 1.0f64, 8u32);
    let mut out = None;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        if !a.starts_with("--") {
            if out.replace(PathBuf::from(&a)).is_some() {
                return Err(format!("more than one output path ({a})"));
            }
            continue;
        }
        let value = args.next().ok_or(format!("{a} needs a value"))?;
        match a.as_str() {
            "--width" => width = number(&a, &value)?,
            "--height" => height = number(&a, &value)?,
            "--sun-elevation" => elevation = number(&a, &value)?,
            "--sun-azimuth" => azimuth = number(&a, &value)?,
            "--sun-radius" => radius = number(&a, &value)?,
            "--sun-contrast" => contrast = number(&a, &value)?,
            "--sky" => sky = number(&a, &value)?,
            "--supersample" => supersample = number(&a, &value)?,
            _ => return Err(format!("unknown option {a}")),
        }
    }
    let out = out.ok_or("no output path")?;
    if width < 2 || height < 3 || width > 16384 || height > 8192 {
        // Mitsuba 3's envmap rejects maps under 2×3.
        return Err(format!("size {width}×{height} outside 2×3 ..= 16384×8192"));
    }
    // Written so that NaN fails every check.
    let valid = radius > 0.0
        && radius < 90.0
        && contrast.is_finite()
        && contrast >= 0.0
        && sky.is_finite()
        && sky > 0.0
        && supersample > 0
        && elevation.is_finite()
        && azimuth.is_finite();
    if !valid {
        return Err(
            "need 0 < sun radius < 90, finite sun contrast ≥ 0 and sky > 0, supersample ≥ 1, \
             finite sun elevation and azimuth"
                .into(),
        );
    }
    let (e, a) = (elevation.to_radians(), azimuth.to_radians());
    let sun = DVec3::new(a.sin() * e.cos(), e.sin(), -a.cos() * e.cos());
    let radius = radius.to_radians();
    Ok((
        Sky {
            width,
            height,
            sun,
            cos_sun_radius: radius.cos(),
            sun_radius: radius,
            sun_contrast: contrast,
            sky,
            supersample,
        },
        out,
    ))
}

fn main() {
    let (sky, out) = parse().unwrap_or_else(|e| {
        eprintln!("make_sky: {e}\n{USAGE}");
        std::process::exit(2);
    });
    let img = sky.render();
    img.write(&out, 0.0).unwrap_or_else(|e| {
        eprintln!("make_sky: {e}");
        std::process::exit(1);
    });
    // What the map holds, for choosing a scene's `scale`: irradiance on an upward surface
    // (∫ L cos θ⁺ dω) from the sky alone and from the whole map, by the same pixel quadrature a
    // renderer's piecewise-constant sampling sees.
    let (w, h) = (img.width as f64, img.height as f64);
    let (mut e_all, mut max) = (0.0f64, 0.0f32);
    for j in 0..img.height {
        let v = j as f64 / (h - 1.0);
        let row_dv = if j == 0 || j == img.height - 1 {
            0.5
        } else {
            1.0
        } / (h - 1.0);
        let d_omega = 2.0 * PI * PI * (PI * v).sin() * row_dv / w;
        for i in 0..img.width {
            let c = img.data[(j * img.width + i) as usize];
            max = max.max(c.max_element());
            e_all += luminance(c.as_dvec3()) * (PI * v).cos().max(0.0) * d_omega;
        }
    }
    let sun_solid_angle = 2.0 * PI * (1.0 - sky.cos_sun_radius);
    let e_sun = sky.sky * sky.sun_contrast * sun_solid_angle * sky.sun.y.max(0.0);
    eprintln!(
        "{}: {}×{}, max texel {max:.4e}; luminance irradiance on +y: total {e_all:.4} \
         (sun disk alone ≈ {e_sun:.4}, solid angle {sun_solid_angle:.3e} sr)",
        out.display(),
        img.width,
        img.height
    );
}
