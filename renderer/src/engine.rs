//! The progressive CPU engine: renders whole sample passes over the image with rayon and
//! accumulates them in f64.
//!
//! Each (pixel, sample index) pair draws from its own sampler (`Settings::sampler`: a
//! counter-based random stream, or its own point of a scrambled Sobol sequence) and each pixel's
//! samples are added in sample order by one thread, so the image for a given seed and sample count
//! is bit-identical for any thread count.
//!
//! With [`Strategy::MisOptimal`] each pixel also keeps its optimal-MIS moments and the α of its
//! current stage ([`crate::integrator::optimal::PixelState`]); since a pixel's samples are
//! added in order, α for sample `s` comes from the same earlier samples however the render is
//! split into passes or threads.
//!
//! WGSL twin: `gpu/film.wgsl` (the render kernel and the accumulation).
//!
//! [`backend`] puts this engine and the GPU's ([`crate::gpu::GpuProgressive`]) behind one
//! interface, [`AnyProgressive`].

pub mod backend;

pub use backend::{AnyProgressive, Backend};

use crate::integrator::optimal::PixelState;
use crate::integrator::{
    OptimalSample, Settings, Strategy, TechniqueSplit, TechniqueSums, radiance_recorded,
};
use crate::sampler::Sampler;
use crate::scene::Scene;
use glam::Vec3;
use rayon::prelude::*;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

/// Running sums for one pixel.
#[derive(Clone, Copy, Debug, Default)]
pub struct PixelSums {
    /// Σ x over all samples.
    pub sum: [f64; 3],
    /// Σ x² (for the per-pixel variance).
    pub sum_sq: [f64; 3],
    /// Σ x over even-numbered samples (half-buffer A; B = sum − A).
    pub sum_even: [f64; 3],
}

/// The accumulated image.
#[derive(Clone, Debug)]
pub struct Film {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Per-pixel sums, row-major, row 0 at the top.
    pub pixels: Vec<PixelSums>,
    /// Samples per pixel accumulated so far.
    pub spp: u32,
    /// Samples discarded because they were NaN or infinite (each counts as a zero sample).
    pub nonfinite: u64,
}

impl Film {
    /// An empty film.
    pub fn new(width: u32, height: u32) -> Film {
        Film {
            width,
            height,
            pixels: vec![PixelSums::default(); (width * height) as usize],
            spp: 0,
            nonfinite: 0,
        }
    }

    /// The running mean (the image).
    pub fn mean(&self) -> Vec<Vec3> {
        let inv = if self.spp > 0 {
            1.0 / self.spp as f64
        } else {
            0.0
        };
        self.pixels.iter().map(|p| to_vec3(p.sum, inv)).collect()
    }

    /// Means of the even- and odd-numbered samples: two independent images whose difference
    /// estimates the noise without a reference (`E[(A−B)²]/4` = variance of the full mean).
    pub fn half_means(&self) -> (Vec<Vec3>, Vec<Vec3>) {
        let n_even = self.spp.div_ceil(2) as f64;
        let n_odd = (self.spp / 2) as f64;
        let inv = |n: f64| if n > 0.0 { 1.0 / n } else { 0.0 };
        let a = self
            .pixels
            .iter()
            .map(|p| to_vec3(p.sum_even, inv(n_even)))
            .collect();
        let b = self
            .pixels
            .iter()
            .map(|p| {
                to_vec3(
                    std::array::from_fn(|c| p.sum[c] - p.sum_even[c]),
                    inv(n_odd),
                )
            })
            .collect();
        (a, b)
    }

    /// `(relMSE, RMSE)` of the mean estimated from the two independent half images, without a
    /// reference.
    ///
    /// With `a` of the `na` even samples and `b` of the `nb` odd ones, `E[(a−b)²] = σ²(1/na +
    /// 1/nb)`, so `(a−b)²·na·nb/n²` estimates `σ²/n`, the variance of the full mean, which is
    /// its expected squared error (`/4` when the halves are equal). The relMSE mirrors
    /// [`crate::metrics::relmse`]: per pixel and channel divided by `m² + 0.01`, with the mean
    /// `m` standing in for the unknown reference, then averaged. Zero before two samples.
    pub fn half_buffer_error(&self) -> (f64, f64) {
        let n = self.spp as f64;
        let (na, nb) = (self.spp.div_ceil(2) as f64, (self.spp / 2) as f64);
        let scale = if self.spp >= 2 {
            na * nb / (n * n)
        } else {
            0.0
        };
        let (a, b) = self.half_means();
        let mean = self.mean();
        let (mut rel, mut sq) = (0.0f64, 0.0f64);
        for ((a, b), m) in a.iter().zip(&b).zip(&mean) {
            for c in 0..3 {
                let d = a[c] as f64 - b[c] as f64;
                let var = d * d * scale;
                let m = m[c] as f64;
                rel += var / (m * m + 0.01);
                sq += var;
            }
        }
        let count = (3 * mean.len()).max(1) as f64;
        (rel / count, (sq / count).sqrt())
    }

    /// Per-pixel, per-channel variance of the mean, from the sample variance (`s² / n`).
    pub fn variance_of_mean(&self) -> Vec<[f64; 3]> {
        let n = self.spp as f64;
        self.pixels
            .iter()
            .map(|p| {
                std::array::from_fn(|c| {
                    if n < 2.0 {
                        return f64::INFINITY;
                    }
                    let mean = p.sum[c] / n;
                    let s2 = ((p.sum_sq[c] - n * mean * mean) / (n - 1.0)).max(0.0);
                    s2 / n
                })
            })
            .collect()
    }

    /// The block z-test (`block`×`block` pixels, family-wise `alpha`, Šidák over blocks and
    /// channels) of this film against `other`, each with its own per-pixel variance of the mean:
    /// whether two independent renders estimate the same image.
    pub fn z_test(&self, other: &Film, block: u32, alpha: f64) -> crate::metrics::BlockTest {
        use crate::metrics::{ImageWithVariance, block_z_test};
        assert_eq!(
            (self.width, self.height),
            (other.width, other.height),
            "films of different sizes"
        );
        let (mean, var) = (self.mean(), self.variance_of_mean());
        let (other_mean, other_var) = (other.mean(), other.variance_of_mean());
        block_z_test(
            self.width,
            self.height,
            &ImageWithVariance {
                mean: &mean,
                var: &var,
            },
            &ImageWithVariance {
                mean: &other_mean,
                var: &other_var,
            },
            block,
            alpha,
        )
    }
}

fn to_vec3(s: [f64; 3], scale: f64) -> Vec3 {
    Vec3::new(
        (s[0] * scale) as f32,
        (s[1] * scale) as f32,
        (s[2] * scale) as f32,
    )
}

/// A progressive render of one scene with one set of settings.
pub struct Progressive {
    scene: Arc<Scene>,
    settings: Settings,
    seed: u32,
    /// Index of the first sample this render draws (0 for a whole render; `START` of a
    /// `--sample-range` part).
    first_sample: u32,
    film: Film,
    /// Per-pixel optimal-MIS state ([`Strategy::MisOptimal`] only; empty otherwise).
    optimal: Vec<PixelState>,
    /// Per-pixel sums of the samples' split by technique (empty unless
    /// [`Progressive::enable_technique_map`] was called).
    techniques: Vec<TechniqueSums>,
    /// Samples per pixel in `techniques`.
    technique_spp: u32,
    cancel: Arc<AtomicBool>,
}

/// The optimal-MIS state a film of `width`×`height` needs with `settings`: one per pixel for
/// [`Strategy::MisOptimal`], none otherwise.
fn optimal_state(settings: &Settings, width: u32, height: u32) -> Vec<PixelState> {
    if settings.strategy == Strategy::MisOptimal {
        vec![PixelState::default(); (width * height) as usize]
    } else {
        Vec::new()
    }
}

impl Progressive {
    /// A new, empty render.
    pub fn new(scene: Arc<Scene>, settings: Settings, seed: u32) -> Progressive {
        Progressive::with_first_sample(scene, settings, seed, 0)
    }

    /// A new, empty render whose samples are `first`, `first + 1`, …: since each (pixel,
    /// sample index) has its own random stream, its film is an exact slice of the whole render
    /// and the sums of slices add up to it. The film's `sum_even` holds the samples whose
    /// global index is even, so that it adds up too; its [`Film::half_means`] counts assume
    /// `first` = 0.
    ///
    /// [`Strategy::MisOptimal`] learns each pixel's α from its samples before `first`, which a
    /// slice does not have: `first` must be 0 there (the command line refuses such parts).
    ///
    /// # Panics
    ///
    /// With [`Strategy::MisOptimal`] and `first > 0`.
    pub fn with_first_sample(
        scene: Arc<Scene>,
        settings: Settings,
        seed: u32,
        first: u32,
    ) -> Progressive {
        assert!(
            first == 0 || settings.strategy != Strategy::MisOptimal,
            "mis-optimal renders cannot start at sample {first}: α comes from the earlier samples"
        );
        let (w, h) = (scene.camera.width, scene.camera.height);
        Progressive {
            optimal: optimal_state(&settings, w, h),
            techniques: Vec::new(),
            technique_spp: 0,
            film: Film::new(w, h),
            scene,
            settings,
            seed,
            first_sample: first,
            cancel: Arc::new(AtomicBool::new(false)),
        }
    }

    /// The accumulated image.
    pub fn film(&self) -> &Film {
        &self.film
    }

    /// Per-pixel optimal-MIS state (moments and current α), row-major; empty unless the
    /// strategy is [`Strategy::MisOptimal`].
    pub fn optimal_state(&self) -> &[PixelState] {
        &self.optimal
    }

    /// Records from now on, per pixel, which technique contributed what
    /// ([`crate::integrator::technique`]; the viewer's technique map). The film is unchanged bit
    /// for bit. Starts the sums over (clears nothing else): call it on an empty render, or read
    /// the sums against their own sample count, [`Progressive::technique_spp`].
    pub fn enable_technique_map(&mut self) {
        let n = (self.film.width * self.film.height) as usize;
        self.techniques = vec![TechniqueSums::default(); n];
        self.technique_spp = 0;
    }

    /// Per-pixel sums of the split by technique, row-major; empty unless enabled.
    pub fn technique_sums(&self) -> &[TechniqueSums] {
        &self.techniques
    }

    /// The samples per pixel in [`Progressive::technique_sums`].
    pub fn technique_spp(&self) -> u32 {
        self.technique_spp
    }

    /// The scene.
    pub fn scene(&self) -> &Arc<Scene> {
        &self.scene
    }

    /// The settings.
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// Index of the first sample (see [`Progressive::with_first_sample`]).
    pub fn first_sample(&self) -> u32 {
        self.first_sample
    }

    /// A flag that, once set, makes the running pass stop early (its partial results are then
    /// dropped: the film keeps only complete passes). Cleared by [`Progressive::restart`].
    pub fn cancel_flag(&self) -> Arc<AtomicBool> {
        self.cancel.clone()
    }

    /// Drops the accumulation and starts over with new settings (same scene, seed and first
    /// sample).
    pub fn restart(&mut self, settings: Settings) {
        self.settings = settings;
        let (w, h) = (self.scene.camera.width, self.scene.camera.height);
        self.film = Film::new(w, h);
        self.optimal = optimal_state(&settings, w, h);
        if !self.techniques.is_empty() {
            self.enable_technique_map();
        }
        self.cancel.store(false, Ordering::Relaxed);
    }

    /// Renders `n` more samples per pixel. Returns `false` if cancelled (nothing was added).
    pub fn render_pass(&mut self, n: u32) -> bool {
        let width = self.film.width as usize;
        let first = self.first_sample + self.film.spp;
        let scene = &*self.scene;
        let settings = &self.settings;
        let seed = self.seed;
        let cancel = &*self.cancel;
        let nonfinite = AtomicU64::new(0);
        let transmission = scene.has_transmission();
        let mut pixels = self.film.pixels.clone();
        let mut optimal = self.optimal.clone();
        // One optimal-MIS row per film row (rows of one unused state for other strategies).
        let mut no_state = vec![PixelState::default(); self.film.height as usize];
        let optimal_rows = if optimal.is_empty() {
            no_state.par_chunks_mut(1)
        } else {
            optimal.par_chunks_mut(width)
        };
        // The same for the technique sums.
        let mut techniques = self.techniques.clone();
        let mut no_sums = vec![TechniqueSums::default(); self.film.height as usize];
        let technique_rows = if techniques.is_empty() {
            no_sums.par_chunks_mut(1)
        } else {
            techniques.par_chunks_mut(width)
        };
        pixels
            .par_chunks_mut(width)
            .zip(optimal_rows)
            .zip(technique_rows)
            .enumerate()
            .for_each(|(y, ((row, optimal_row), technique_row))| {
                if cancel.load(Ordering::Relaxed) {
                    return;
                }
                let learn = optimal_row.len() == row.len();
                let record = technique_row.len() == row.len();
                let mut bad = 0u64;
                for (x, px) in row.iter_mut().enumerate() {
                    for s in first..first + n {
                        let mut sampler = Sampler::new(
                            settings.sampler,
                            seed,
                            x as u32,
                            y as u32,
                            width as u32,
                            s,
                        );
                        let (ray, weight) =
                            scene.camera.sample_ray(&mut sampler, x as u32, y as u32);
                        let mut one = learn.then(|| OptimalSample {
                            alpha: optimal_row[x].alpha_for(s),
                            ..OptimalSample::default()
                        });
                        let mut split = record.then(TechniqueSplit::default);
                        let (o, t) = (one.as_mut(), split.as_mut());
                        let l = if transmission {
                            radiance_recorded::<true>(scene, ray, &mut sampler, settings, o, t)
                        } else {
                            radiance_recorded::<false>(scene, ray, &mut sampler, settings, o, t)
                        };
                        // A sample that is dropped adds nothing to the moments either.
                        if let Some(one) = &one
                            && l.is_finite()
                            && one.moments.is_finite()
                        {
                            optimal_row[x].moments.add(&one.moments);
                        }
                        // A filter with negative lobes weighs the sample (1 otherwise: the same
                        // bits). The optimal-MIS moments stay unweighted: the weight's magnitude
                        // is the pixel's constant, its sign does not change which α is best.
                        let l = l * weight;
                        if !l.is_finite() {
                            bad += 1;
                            continue;
                        }
                        if let Some(split) = &mut split {
                            split.parts.iter_mut().for_each(|p| *p *= weight);
                            technique_row[x].add(split);
                        }
                        let l = [l.x as f64, l.y as f64, l.z as f64];
                        for (c, v) in l.into_iter().enumerate() {
                            px.sum[c] += v;
                            px.sum_sq[c] += v * v;
                            if s % 2 == 0 {
                                px.sum_even[c] += v;
                            }
                        }
                    }
                }
                if bad > 0 {
                    nonfinite.fetch_add(bad, Ordering::Relaxed);
                }
            });
        if cancel.load(Ordering::Relaxed) {
            return false;
        }
        self.film.pixels = pixels;
        self.optimal = optimal;
        if !techniques.is_empty() {
            self.techniques = techniques;
            self.technique_spp += n;
        }
        self.film.spp += n;
        self.film.nonfinite += nonfinite.into_inner();
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::Technique;

    /// The half-buffer estimate on a film with known sums: one pixel, 4 samples with values
    /// 1, 3, 1, 3 (even samples 1 and 1, odd 3 and 3) in every channel.
    #[test]
    fn half_buffer_error_matches_hand_computation() {
        let mut film = Film::new(1, 1);
        film.spp = 4;
        film.pixels[0] = PixelSums {
            sum: [8.0; 3],
            sum_sq: [20.0; 3],
            sum_even: [2.0; 3],
        };
        let (rel, rmse) = film.half_buffer_error();
        // a = 1, b = 3, mean 2: variance of the mean (a−b)²/4 = 1; relMSE 1 / (4 + 0.01).
        assert!((rmse - 1.0).abs() < 1e-12, "{rmse}");
        assert!((rel - 1.0 / 4.01).abs() < 1e-12, "{rel}");

        // Odd spp weighs the unequal halves: 3 samples 1, 3, 1 → a = 1 (2 samples), b = 3 (1).
        film.spp = 3;
        film.pixels[0] = PixelSums {
            sum: [5.0; 3],
            sum_sq: [11.0; 3],
            sum_even: [2.0; 3],
        };
        let (_, rmse) = film.half_buffer_error();
        // (a−b)²·na·nb/n² = 4·2/9.
        assert!((rmse * rmse - 8.0 / 9.0).abs() < 1e-9, "{rmse}");
    }

    use crate::scene::parse_scene;

    fn small_scene() -> Arc<Scene> {
        let json = r#"{
            "camera": {"from": [0, 1, -3], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 60, "width": 12, "height": 8},
            "materials": {"white": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
            "shapes": [
                {"type": "quad", "corner": [-2, 0, -2], "edge_u": [0, 0, 4], "edge_v": [4, 0, 0], "material": "white"},
                {"type": "disk", "center": [0, 1.5, 0], "normal": [0, -1, 0], "radius": 0.5, "emission": [4, 4, 4]}
            ]
        }"#;
        Arc::new(Scene::from_desc(&parse_scene(json).unwrap()).unwrap())
    }

    #[test]
    fn passes_accumulate_like_one_render() {
        let scene = small_scene();
        let mut a = Progressive::new(scene.clone(), Settings::default(), 3);
        assert!(a.render_pass(3) && a.render_pass(5));
        let mut b = Progressive::new(scene, Settings::default(), 3);
        assert!(b.render_pass(8));
        assert_eq!(a.film().spp, 8);
        assert_eq!(a.film().mean(), b.film().mean());
        // The halves average to the mean; the variance is finite and non-negative.
        let (ha, hb) = a.film().half_means();
        for ((m, x), y) in a.film().mean().iter().zip(&ha).zip(&hb) {
            assert!((*m - (*x + *y) * 0.5).abs().max_element() < 1e-5);
        }
        assert!(
            a.film()
                .variance_of_mean()
                .iter()
                .flatten()
                .all(|v| v.is_finite() && *v >= 0.0)
        );
        assert!(
            a.film().mean().iter().any(|c| c.x > 0.0),
            "the lit floor is visible"
        );
    }

    /// Renders starting at a sample offset are exact slices: samples 0..3 and 3..8 add up to
    /// one render of 0..8 within f64 rounding (8 non-negative terms summed in two groupings:
    /// each within `7·u·Σ` of the exact sum, u = ε/2, so at most `7·ε·Σ` apart; 8ε allows for
    /// second-order terms), while a slice that ignored its offset would repeat samples 0..5.
    #[test]
    fn sample_offset_slices_add_up_to_the_whole_render() {
        let scene = small_scene();
        let mut whole = Progressive::new(scene.clone(), Settings::default(), 3);
        assert!(whole.render_pass(8));
        let mut head = Progressive::with_first_sample(scene.clone(), Settings::default(), 3, 0);
        assert!(head.render_pass(3));
        let mut tail = Progressive::with_first_sample(scene, Settings::default(), 3, 3);
        assert!(tail.render_pass(2) && tail.render_pass(3));
        assert_eq!(tail.first_sample(), 3);
        let (w, h, t) = (whole.film(), head.film(), tail.film());
        for ((w, h), t) in w.pixels.iter().zip(&h.pixels).zip(&t.pixels) {
            for c in 0..3 {
                for (whole, parts) in [
                    (w.sum[c], h.sum[c] + t.sum[c]),
                    (w.sum_sq[c], h.sum_sq[c] + t.sum_sq[c]),
                    (w.sum_even[c], h.sum_even[c] + t.sum_even[c]),
                ] {
                    assert!(
                        (whole - parts).abs() <= 8.0 * f64::EPSILON * whole,
                        "{whole} vs {parts}"
                    );
                }
            }
        }
        assert!(w.pixels.iter().any(|p| p.sum[0] > 0.0));
    }

    /// The technique map ([`Progressive::enable_technique_map`]) leaves the film bit for bit as
    /// it was, its parts' means add up to the image (to f32 rounding), and each strategy's
    /// contributions land where they belong: light-only has no BSDF part, BSDF-only no light
    /// part, MIS and the mixture both, only mis-optimal a control variate, and the camera's view
    /// of the disk is its own part. Deliberate bugs tried, each failed: emission found by the
    /// camera ray filed under BSDF (no camera part); next-event estimation's contribution not
    /// recorded (light-only's parts add up to 0 where the image has 0.0094).
    #[test]
    fn technique_map_adds_up_to_the_image_and_splits_by_strategy() {
        let scene = small_scene();
        let strategies = [
            Strategy::Light,
            Strategy::Bsdf,
            Strategy::Mixture { light_weight: 0.5 },
            Strategy::Mis {
                heuristic: crate::integrator::Heuristic::Power,
            },
            Strategy::MisOptimal,
        ];
        for strategy in strategies {
            let settings = Settings {
                strategy,
                ..Settings::default()
            };
            let mut plain = Progressive::new(scene.clone(), settings, 9);
            assert!(plain.render_pass(16));
            let mut mapped = Progressive::new(scene.clone(), settings, 9);
            mapped.enable_technique_map();
            assert!(mapped.render_pass(7) && mapped.render_pass(9));
            let sums = |f: &Film| {
                f.pixels
                    .iter()
                    .map(|p| (p.sum, p.sum_sq))
                    .collect::<Vec<_>>()
            };
            assert_eq!(sums(plain.film()), sums(mapped.film()), "{strategy:?}");
            assert_eq!(mapped.technique_spp(), 16);
            let means: Vec<[Vec3; 4]> = mapped
                .technique_sums()
                .iter()
                .map(|t| t.means(16))
                .collect();
            for (parts, image) in means.iter().zip(mapped.film().mean()) {
                let sum: Vec3 = parts.iter().sum();
                let scale: f32 = parts.iter().map(|p| p.abs().max_element()).sum();
                assert!(
                    (sum - image).abs().max_element() <= 1e-5 * scale + 1e-7,
                    "{strategy:?}: parts {parts:?} add up to {sum}, the image has {image}"
                );
            }
            let any = |t: Technique| means.iter().any(|p| p[t.index()] != Vec3::ZERO);
            assert!(any(Technique::Camera), "{strategy:?} sees the disk");
            let want = match strategy {
                Strategy::Light => [true, false, false],
                Strategy::Bsdf => [false, true, false],
                Strategy::MisOptimal => [true, true, true],
                _ => [true, true, false],
            };
            let got = [
                any(Technique::Light),
                any(Technique::Bsdf),
                any(Technique::ControlVariate),
            ];
            assert_eq!(
                got, want,
                "{strategy:?}: light, BSDF, control variate parts"
            );
        }
        // A restart keeps the map on and starts its sums over.
        let mut r = Progressive::new(scene, Settings::default(), 1);
        r.enable_technique_map();
        assert!(r.render_pass(2));
        r.restart(Settings::default());
        assert_eq!((r.technique_spp(), r.technique_sums().len()), (0, 12 * 8));
    }

    /// mis-optimal: the image and every pixel's moments and α depend on the seed and spp only,
    /// not on the pass split or the thread count (α for sample s comes from samples 0..s of the
    /// same pixel, added in order); past the first stage α is non-zero (the control variate is
    /// on); a restart with another strategy drops the state.
    #[test]
    fn mis_optimal_is_independent_of_passes_and_threads() {
        let scene = small_scene();
        let settings = Settings {
            strategy: Strategy::MisOptimal,
            ..Settings::default()
        };
        let pool = |n| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .unwrap()
        };
        let a = pool(1).install(|| {
            let mut a = Progressive::new(scene.clone(), settings, 5);
            for n in [3, 5, 9, 15] {
                assert!(a.render_pass(n));
            }
            a
        });
        let b = pool(3).install(|| {
            let mut b = Progressive::new(scene.clone(), settings, 5);
            assert!(b.render_pass(32));
            b
        });
        assert_eq!(a.film().spp, 32);
        assert_eq!(a.film().mean(), b.film().mean());
        assert_eq!(a.optimal_state(), b.optimal_state());
        assert_eq!(a.optimal_state().len(), 12 * 8);
        assert!(
            a.optimal_state()
                .iter()
                .any(|p| p.alpha.light != Vec3::ZERO && p.alpha.bsdf != Vec3::ZERO)
        );
        // Not the balance heuristic's image: the control variate changed the samples.
        let balance = Settings {
            strategy: Strategy::Mis {
                heuristic: crate::integrator::Heuristic::Balance,
            },
            ..Settings::default()
        };
        let mut c = Progressive::new(scene, balance, 5);
        assert!(c.render_pass(32));
        assert_ne!(a.film().mean(), c.film().mean());
        let mut a = a;
        a.restart(balance);
        assert!(a.optimal_state().is_empty());
    }

    #[test]
    #[should_panic(expected = "mis-optimal renders cannot start at sample 4")]
    fn mis_optimal_refuses_a_slice() {
        let settings = Settings {
            strategy: Strategy::MisOptimal,
            ..Settings::default()
        };
        Progressive::with_first_sample(small_scene(), settings, 1, 4);
    }

    #[test]
    fn cancel_drops_the_pass_and_restart_clears() {
        let mut r = Progressive::new(small_scene(), Settings::default(), 1);
        assert!(r.render_pass(2));
        let before = r.film().mean();
        r.cancel_flag().store(true, Ordering::Relaxed);
        assert!(!r.render_pass(4), "a cancelled pass reports it");
        assert_eq!(r.film().spp, 2);
        assert_eq!(r.film().mean(), before, "a cancelled pass adds nothing");
        let settings = Settings {
            max_depth: Some(1),
            ..Settings::default()
        };
        r.restart(settings);
        assert_eq!(r.film().spp, 0);
        assert_eq!(r.settings(), &settings);
        assert!(r.render_pass(1), "restart clears the cancel flag");
    }
}
