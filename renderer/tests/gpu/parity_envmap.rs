//! Parity of the environment map's WGSL twin (`lights/envmap.wgsl`) with `lights/envmap.rs`, in
//! the style of `renderer/tests/gpu/parity.rs`: the same inputs through `run_snippet` and through the Rust
//! functions, on maps uploaded as scenes (`stats::suite::envmap_scene`), so the texture, the
//! tables in `tables` and the light record are checked with the maths.
//!
//! * lookup at given (u, v) and radiance in given directions: the seam at u = 0, the poles, texel
//!   centres and edges, rotated maps, 1×1, 2×1 and one-band maps;
//! * importance sampling for the same u (direction, pdf, radiance) and uniform sampling;
//! * the pdf of given directions, both methods.
//!
//! Tolerances are f32 roundings carried through each quantity's conditioning, stated per test.
//! `LUMIS_SKIP_GPU_TESTS=1` skips the file where no adapter exists (see `gpu_common`).

use crate::gpu_common;
use glam::{DMat3, Mat3, Vec2, Vec3};
use gpu_common::*;
use lumis::gpu::GpuScene;
use lumis::gpu::kernel::run_snippet;
use lumis::gpu::scene::LightSamplingTag;
use lumis::integrator::Settings;
use lumis::lights::{EnvmapLight, Light, LightSampling};
use lumis::rng::Rng;
use lumis::sampling;
use lumis::scene::Scene;
use lumis::stats::suite::{self, TestMap};
use std::f32::consts::{PI, TAU};
use std::sync::Arc;

/// Random items per map and test.
const N: usize = 4096;

/// A map uploaded as the only light of a scene.
struct Map {
    name: &'static str,
    width: usize,
    height: usize,
    /// The rotation from the map's frame to the world, as the renderer builds it.
    rotation: Mat3,
    scene: Arc<Scene>,
    gpu: GpuScene,
    light: usize,
    /// The largest difference between neighbouring texels (periodic in u), any channel: a bound
    /// on how fast the bilinear lookup changes per texel.
    gradient: f32,
    max_texel: f32,
}

impl Map {
    fn new(map: TestMap, rotate_y_deg: f32) -> Option<Map> {
        Map::rotated(map, rotate_y_deg, None)
    }

    /// The map turned by `rotation`, then by `rotate_y_deg` about +y.
    fn rotated(map: TestMap, rotate_y_deg: f32, rotation: Option<DMat3>) -> Option<Map> {
        let ctx = context()?;
        let scene = suite::envmap_scene_rotated(&map, rotate_y_deg as f64, rotation);
        let gpu = GpuScene::new(ctx, scene.clone()).expect("upload");
        let light = scene.background_light.expect("the map emits") as usize;
        let (name, width, height, texels) = map;
        let t = |i: usize, j: usize| texels[j * width + i];
        let mut gradient = 0.0f32;
        for j in 0..height {
            for i in 0..width {
                gradient = gradient.max((t(i, j) - t((i + 1) % width, j)).abs().max_element());
                if j + 1 < height {
                    gradient = gradient.max((t(i, j) - t(i, j + 1)).abs().max_element());
                }
            }
        }
        let max_texel = texels.iter().map(|t| t.max_element()).fold(0.0, f32::max);
        Some(Map {
            name,
            width,
            height,
            rotation: EnvmapLight::rotation_matrix(rotate_y_deg, rotation),
            scene,
            gpu,
            light,
            gradient,
            max_texel,
        })
    }

    fn light(&self) -> &Light {
        &self.scene.lights[self.light]
    }

    fn envmap(&self) -> &EnvmapLight {
        match self.light() {
            Light::Envmap(e) => e,
            _ => panic!("{}: not an environment map", self.name),
        }
    }

    fn bands(&self) -> usize {
        self.height.saturating_sub(1).max(1)
    }

    /// The map's frame → world.
    fn to_world(&self, d: Vec3) -> Vec3 {
        self.rotation * d
    }

    fn to_map(&self, d: Vec3) -> Vec3 {
        self.rotation.transpose() * d
    }

    /// Runs `body` with `l` bound to the map's light record.
    fn run(
        &self,
        body: &str,
        inputs: &[[f32; 4]],
        in_stride: usize,
        out_stride: usize,
    ) -> Vec<[f32; 4]> {
        let body = format!("let l = lights[{}u];\n{body}", self.light);
        run_snippet(
            &self.gpu,
            &Settings::default(),
            &body,
            inputs,
            in_stride,
            out_stride,
        )
        .unwrap_or_else(|e| panic!("{}: {e}", self.name))
    }

    /// How much the GPU's lookup in world direction `d` may differ from the CPU's: both turn
    /// `d` into (u, v) with a few ulp of error (`atan2_precise`, the acos built from it, glam's
    /// normalisation), and the lookup changes by at most the map's `gradient` per texel.
    /// u = atan2(x, −z) depends on the ratio of x and z only, so its error does not grow towards
    /// the poles; v = acos(y)/π does: one ulp of y moves θ by 1.2e-7/sin θ, and by
    /// √(2·1.2e-7) = 5e-4 at most (at the poles themselves).
    fn eval_tolerance(&self, d_world: Vec3) -> f32 {
        let d = self.to_map(d_world).normalize();
        let sin_theta = (d.x * d.x + d.z * d.z).sqrt();
        let du = U_AGREEMENT;
        let dtheta = THETA_AGREEMENT + Y_ULP / sin_theta.max(Y_ULP.sqrt());
        let dv = dtheta / PI;
        self.gradient * (self.width as f32 * du + (self.height - 1) as f32 * dv)
    }
}

/// Agreement of the two sides' u: a few ulp of atan2 (2π·2⁻²⁴ ≈ 4e-7) over 2π.
const U_AGREEMENT: f32 = 2e-7;
/// Agreement of the two sides' θ from the same y (acos through `atan2_precise`).
const THETA_AGREEMENT: f32 = 5e-7;
/// One ulp of y near 1, where normalisations may differ by one rounding.
const Y_ULP: f32 = 1.2e-7;

/// A map of random texels in [0, 4).
fn random_map(name: &'static str, w: usize, h: usize, seed: u32) -> TestMap {
    let mut r = Rng::new(seed, 0, 0);
    let texels = (0..w * h)
        .map(|_| Vec3::new(r.next_f32(), r.next_f32(), r.next_f32()) * 4.0)
        .collect();
    (name, w, h, texels)
}

/// The suite's map called `name`.
fn suite_map(name: &str) -> TestMap {
    suite::envmap_maps()
        .into_iter()
        .find(|m| m.0 == name)
        .unwrap_or_else(|| panic!("no suite map {name}"))
}

/// The maps of the lookup tests: random texels unrotated and rotated (30°, 200°), a one-band
/// map (H = 2), the suite's black stripes, its 1×1 and 2×1 maps.
fn lookup_maps() -> Option<Vec<Map>> {
    Some(vec![
        Map::new(random_map("random16x9", 16, 9, 1), 0.0)?,
        Map::new(random_map("random16x9", 16, 9, 1), 30.0)?,
        Map::new(random_map("random7x5", 7, 5, 2), 200.0)?,
        Map::new(random_map("random5x2", 5, 2, 3), 0.0)?,
        Map::new(suite_map("stripes"), 75.0)?,
        Map::new(suite_map("1x1"), 30.0)?,
        Map::new(suite_map("2x1"), 30.0)?,
        Map::rotated(
            random_map("random16x9", 16, 9, 1),
            0.0,
            Some(suite::envmap_tilt()),
        )?,
    ])
}

/// The maps of the sampling tests: the suite's (constant, sun 1e5, stripes, 1×1, 2×1, as the χ²
/// tests rotate them by 30°) and a rotated random one.
fn sampling_maps() -> Option<Vec<Map>> {
    let mut maps = Vec::new();
    for m in suite::envmap_maps() {
        maps.push(Map::new(m, 30.0)?);
    }
    maps.push(Map::new(random_map("random16x9", 16, 9, 4), 200.0)?);
    maps.push(Map::rotated(
        suite_map("sun"),
        0.0,
        Some(suite::envmap_tilt()),
    )?);
    Some(maps)
}

/// Direction of map coordinates (u, v), in the map's frame.
fn direction(u: f32, v: f32) -> Vec3 {
    let (phi, theta) = (TAU * u, PI * v);
    Vec3::new(
        theta.sin() * phi.sin(),
        theta.cos(),
        -theta.sin() * phi.cos(),
    )
}

/// World directions to look up: the seam (u = 0 and either side of it), the poles and their
/// neighbourhood, every texel centre and the midpoints between them (the cells' corners and
/// centres), then `N` random ones. Also the count of special ones (they come first).
fn directions(m: &Map, seed: u32) -> (Vec<Vec3>, usize) {
    let (w, h) = (m.width as f32, m.height as f32);
    let mut d = Vec::new();
    for u in [0.0, 1e-6, 1.0 - 1e-6, 0.5 / w, 1.0 - 0.5 / w] {
        for v in [0.25, 0.5, 0.8] {
            d.push(direction(u, v));
        }
    }
    d.extend([Vec3::Y, -Vec3::Y]);
    for v in [1e-6, 1e-4, 1e-2, 1.0 - 1e-2, 1.0 - 1e-4, 1.0 - 1e-6] {
        for u in [0.0, 0.3, 0.7] {
            d.push(direction(u, v));
        }
    }
    let rows: Vec<f32> = if m.height > 1 {
        (0..2 * m.height - 1)
            .map(|k| k as f32 / (2.0 * (h - 1.0)))
            .collect()
    } else {
        vec![0.3, 0.6]
    };
    for &v in &rows {
        for k in 0..2 * m.width {
            d.push(direction(k as f32 / (2.0 * w) + 0.25 / w, v));
        }
    }
    let special = d.len();
    let mut r = Rng::new(seed, 0, 0);
    d.extend((0..N).map(|_| sampling::sample_uniform_sphere(r.next_2d())));
    let world = d.iter().map(|&x| m.to_world(x)).collect();
    (world, special)
}

/// The largest difference seen and the largest fraction of its tolerance, for the report.
#[derive(Default)]
struct Worst {
    abs: f32,
    fraction: f32,
    at: String,
}

impl Worst {
    fn see(&mut self, got: [f32; 4], want: Vec3, tolerance: f32, what: &str) {
        for (g, w) in got[..3].iter().zip(want.to_array()) {
            let diff = (g - w).abs();
            self.abs = self.abs.max(diff);
            if tolerance > 0.0 && diff / tolerance > self.fraction {
                self.fraction = diff / tolerance;
                self.at = format!("{what}: gpu {g:e} cpu {w:e}");
            }
        }
    }

    fn report(&self, name: &str) {
        eprintln!(
            "{name}: largest difference {:e}, at most {:.3} of its tolerance ({})",
            self.abs, self.fraction, self.at
        );
    }
}

fn f4(v: Vec3, w: f32) -> [f32; 4] {
    [v.x, v.y, v.z, w]
}

/// Bilinear lookup at given (u, v): the seam (u = 0, just below 1), the poles (v = 0, 1), texel
/// centres and edges, and random points. Both sides run the same f32 operations on the same
/// texels, so they agree to a rounding or two of the texel values (1e-6 of the largest texel;
/// a driver may fuse a product and a sum).
#[test]
fn lookup_matches() {
    let Some(maps) = lookup_maps() else { return };
    for m in &maps {
        let (w, h) = (m.width as f32, m.height as f32);
        let mut uv = Vec::new();
        let mut us = vec![
            0.0,
            1e-7,
            0.5 / w,
            1.0 / w,
            0.5,
            1.0 - 0.5 / w,
            sampling::ONE_MINUS_EPSILON,
        ];
        us.extend((0..m.width).map(|i| (i as f32 + 0.5) / w));
        let mut vs = vec![0.0, 1e-7, 0.5, 1.0 - 1e-7, 1.0];
        if m.height > 1 {
            vs.extend((0..m.height).map(|j| j as f32 / (h - 1.0)));
        }
        for &u in &us {
            for &v in &vs {
                uv.push(Vec2::new(u, v));
            }
        }
        let mut r = Rng::new(21, 0, 0);
        uv.extend((0..N).map(|_| r.next_2d()));
        let inputs: Vec<[f32; 4]> = uv.iter().map(|p| [p.x, p.y, 0.0, 0.0]).collect();
        let out = m.run(
            "outp(0u, vec4f(envmap_lookup(l, inp(0u).xy), 0.0));",
            &inputs,
            1,
            1,
        );
        let atol = 1e-6 * m.max_texel;
        let mut c = Compare::new(&format!("lookup {}", m.name), 0.0, atol);
        let mut worst = Worst::default();
        for (p, o) in uv.iter().zip(&out) {
            let want = m.envmap().lookup(*p);
            c.v3(*o, want, &format!("{} at {p}", m.name));
            worst.see(*o, want, atol, &format!("at {p}"));
        }
        worst.report(&format!("lookup {}", m.name));
        c.finish(0);
    }
}

/// Radiance in given world directions (`envmap_eval`, and `light_radiance` of the record, which
/// the path tracer calls for rays that miss): rotation, (u, v) and the lookup together, within
/// [`Map::eval_tolerance`] (the (u, v) roundings times the map's gradient) and 1e-6 of the
/// largest texel.
#[test]
fn radiance_in_directions_matches() {
    let Some(maps) = lookup_maps() else { return };
    for m in &maps {
        let (dirs, _) = directions(m, 22);
        let inputs: Vec<[f32; 4]> = dirs.iter().map(|&d| f4(d, 0.0)).collect();
        let out = m.run(
            "let d = inp(0u).xyz;
             outp(0u, vec4f(envmap_eval(l, d), 0.0));
             outp(1u, vec4f(light_radiance(l, vec3f(0.0), d), 0.0));",
            &inputs,
            1,
            2,
        );
        let atol = 1e-6 * m.max_texel;
        let mut c = Compare::new(&format!("radiance {}", m.name), 1e-6, atol);
        let mut worst = Worst::default();
        for (&d, o) in dirs.iter().zip(out.chunks(2)) {
            let want = m.envmap().eval(d);
            let what = format!("{} towards {d}", m.name);
            let extra = m.eval_tolerance(d);
            c.v3_conditioned(o[0], want, extra, &what);
            c.v3_conditioned(o[1], m.light().radiance(Vec3::ZERO, d), extra, &what);
            worst.see(o[0], want, atol + 1e-6 * want.max_element() + extra, &what);
        }
        worst.report(&format!("radiance {}", m.name));
        c.finish(0);
    }
}

/// The reference point of the light queries (unused by a light at infinity, but passed through).
const P: Vec3 = Vec3::new(0.3, 0.2, -0.1);

/// Agreement in u of the f32 CDFs with the CPU's f64 ones (a few roundings of numbers ≤ 1).
const CDF_AGREEMENT: f32 = 3e-7;
/// The GPU's sin and cos of angles up to 2π, absolute (as in `gpu/parity.rs`'s warps).
const SIN_COS_AGREEMENT: f32 = 2e-6;
/// Relative agreement of a pdf read from the same cell: the same density (the CPU's, uploaded)
/// divided by the same band's solid angle, in f32.
const PDF_AGREEMENT: f32 = 2e-6;
/// How far (rad) a direction may be moved to find the cell whose density the other side read
/// (see [`pdfs_near`]).
const EDGE_DELTA: f32 = 1e-5;
/// At most one in this many random samples or directions may lie on an edge (see [`pdfs_near`]
/// and [`sampling_matches`]).
const EDGE_RARITY: usize = 500;

/// The uniforms of the sampling tests: the corners and the middle of the square (the first
/// [`SPECIAL_U`]), then `N` random pairs.
fn uniforms(seed: u32) -> Vec<Vec2> {
    let e = sampling::ONE_MINUS_EPSILON;
    let mut u = vec![
        Vec2::ZERO,
        Vec2::new(e, e),
        Vec2::new(0.0, e),
        Vec2::new(e, 0.0),
        Vec2::splat(0.5),
    ];
    let mut r = Rng::new(seed, 0, 0);
    u.extend((0..N).map(|_| r.next_2d()));
    u
}

/// The special uniforms that come first in [`uniforms`].
const SPECIAL_U: usize = 5;

/// `light_sample` of the map by `method` for each u: (wi, pdf or −1 for none), (radiance,
/// `light_pdf` of wi), (p, infinite), (n, _).
fn gpu_samples(m: &Map, u: &[Vec2], method: LightSampling) -> Vec<[[f32; 4]; 4]> {
    let inputs: Vec<[f32; 4]> = u
        .iter()
        .map(|u| [u.x, u.y, LightSamplingTag::of(method).gpu_tag() as f32, 0.0])
        .collect();
    let body = format!(
        "let p = vec3f({:?}, {:?}, {:?}); let method = u32(inp(0u).z);
         let s = light_sample(l, p, vec3f(0.0), inp(0u).xy, method);
         outp(0u, vec4f(s.wi, select(-1.0, s.pdf, s.ok)));
         outp(1u, vec4f(s.le, light_pdf(l, p, vec3f(0.0), s.wi, s.p, s.n, method)));
         outp(2u, vec4f(s.p, select(0.0, 1.0, s.infinite)));
         outp(3u, vec4f(s.n, 0.0));",
        P.x, P.y, P.z
    );
    m.run(&body, &inputs, 1, 4)
        .chunks(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect()
}

/// The CPU's pdf by `method` of `d`, then of the directions [`EDGE_DELTA`] away from it in φ
/// and in θ (in the map's frame): the importance density is constant on each cell and the
/// uniform one is 0 where the map is black, so a direction within rounding of a cell's edge (or
/// of a black region's) may read either side's value.
fn pdfs_near(m: &Map, d_world: Vec3, method: LightSampling) -> Vec<f32> {
    let d = m.to_map(d_world).normalize();
    let theta = d.y.clamp(-1.0, 1.0).acos();
    let phi = d.x.atan2(-d.z);
    let mut out = vec![m.envmap().pdf(d_world, method)];
    for dt in [0.0, -EDGE_DELTA, EDGE_DELTA] {
        for dp in [0.0, -EDGE_DELTA, EDGE_DELTA] {
            let (t, p) = (theta + dt, phi + dp);
            let n = Vec3::new(t.sin() * p.sin(), t.cos(), -t.sin() * p.cos());
            out.push(m.envmap().pdf(m.to_world(n), method));
        }
    }
    out
}

/// How a GPU pdf compares with the CPU's.
#[derive(Clone, Copy, PartialEq, Debug)]
enum PdfMatch {
    /// The CPU's at the same direction (to [`PDF_AGREEMENT`]).
    Same,
    /// A neighbouring cell's (or side of a black region's) within [`EDGE_DELTA`].
    Edge,
    /// Neither.
    Wrong,
}

fn pdf_match(m: &Map, got: f32, d: Vec3, method: LightSampling) -> PdfMatch {
    let close = |want: f32| (got - want).abs() <= PDF_AGREEMENT * want.abs().max(got.abs());
    let near = pdfs_near(m, d, method);
    if close(near[0]) {
        PdfMatch::Same
    } else if near.iter().any(|&w| close(w)) {
        PdfMatch::Edge
    } else {
        PdfMatch::Wrong
    }
}

/// Importance sampling for the same u: the GPU's direction lies where the CPU's sampler puts u,
/// its pdf is the CPU's density there, and its radiance the CPU's lookup there.
///
/// The direction is compared through the CPU's inverse (`invert_importance`: the u that the CPU
/// maps to the GPU's direction), which must give back u. In u the two sides differ by the f32
/// rounding of the CDFs (the CPU's are f64), an absolute [`CDF_AGREEMENT`] wherever u falls, even
/// where a rounded CDF boundary makes the two sides pick neighbouring cells; comparing directions
/// instead would amplify it by the inverse of a cell's probability. Going back through the CPU's
/// inverse adds: in v, one ulp of y over the band's Δcos θ; in u, the GPU's sin/cos error
/// ([`SIN_COS_AGREEMENT`] rad, and the rotation's rounding over sin θ near the poles) times W (a
/// column's CDF rises by at most 1 per 1/W). At the poles themselves u is undefined.
///
/// The sample's pdf is its cell's: the CPU's for the same u, or the CPU's density at the GPU's
/// direction (the two differ where the sides picked neighbouring cells across a rounded CDF
/// boundary, and at the poles, which lie in every cell of their band and whose density reads the
/// cell at u = ½); `light_pdf` of the sampled direction is the CPU's density there. Either may be
/// a neighbouring cell's within [`EDGE_DELTA`] for at most 1 in [`EDGE_RARITY`] random samples,
/// as may a sample whose radiance is 0 on one side and within the lookup's tolerance of 0 on the
/// other (at a black region's edge; then one side returns no sample).
#[test]
fn importance_sampling_matches() {
    let Some(maps) = sampling_maps() else { return };
    for m in &maps {
        check_importance_sampling(m, &uniforms(23));
    }
}

/// A 4096 × 2048 map (8.4M cells; its tables take 67 MB of the 128 MiB lavapipe binds, its
/// texture 134 MB) uploads and samples as [`importance_sampling_matches`] requires.
#[test]
fn a_large_map_samples_like_the_cpu() {
    let Some(m) = Map::new(random_map("random4096x2048", 4096, 2048, 5), 10.0) else {
        return;
    };
    check_importance_sampling(&m, &uniforms(26));
}

/// The checks of [`importance_sampling_matches`] on `m` for the uniforms `us` (the first
/// [`SPECIAL_U`] special).
fn check_importance_sampling(m: &Map, us: &[Vec2]) {
    let method = LightSampling::SolidAngle;
    {
        let name = format!("importance {}", m.name);
        let out = gpu_samples(m, us, method);
        let lookup_atol = 1e-6 * m.max_texel;
        let mut c = Compare::new(&name, PDF_AGREEMENT, lookup_atol);
        let mut worst_u = (0.0f32, 0.0f32, String::new());
        let mut worst_dir = 0.0f32;
        let mut edges = 0;
        for (k, (&u, o)) in us.iter().zip(&out).enumerate() {
            let random = k >= SPECIAL_U;
            let wi = Vec3::from_slice(&o[0][..3]);
            let what = format!("{name} u {u} -> gpu {wi}");
            let black = |le: Vec3, d: Vec3| le.max_element() <= lookup_atol + m.eval_tolerance(d);
            let want = match (m.light().sample(P, Vec3::ZERO, u, method), o[0][3] >= 0.0) {
                (Some(w), true) => w,
                (None, false) => continue,
                (Some(w), false) if black(w.le, w.wi) => {
                    edges += random as usize;
                    continue;
                }
                (None, true) if black(Vec3::from_slice(&o[1][..3]), wi) => {
                    edges += random as usize;
                    continue;
                }
                (w, _) => {
                    let want = w.map_or(-1.0, |w| w.pdf);
                    c.scalar(o[0][3], want, &format!("{what}: a sample on one side only"));
                    continue;
                }
            };
            check_infinite_sample(o, &what);
            c.scalar(wi.length(), 1.0, &format!("{what}: |wi|"));
            c.v3_conditioned(o[1], m.envmap().eval(wi), m.eval_tolerance(wi), &what);
            worst_dir = worst_dir.max((wi - want.wi).length());

            let back = m.envmap().invert_importance(wi).expect("a sampled cell");
            let d = m.to_map(wi).normalize();
            let sin_theta = (d.x * d.x + d.z * d.z).sqrt();
            let bands = m.bands() as f32;
            let band = (d.y.clamp(-1.0, 1.0).acos() / PI * bands)
                .floor()
                .min(bands - 1.0);
            let dcos = (PI * band / bands).cos() - (PI * (band + 1.0) / bands).cos();
            let tol_y = CDF_AGREEMENT + Y_ULP / dcos;
            let dphi = SIN_COS_AGREEMENT + Y_ULP / sin_theta.max(1e-6);
            let tol_x = CDF_AGREEMENT + m.width as f32 * dphi / TAU;
            // u is periodic in x (the first and last columns meet at the seam).
            let dx = (back.x - u.x).abs();
            let dx = if sin_theta == 0.0 {
                0.0
            } else {
                dx.min(1.0 - dx)
            };
            let dy = (back.y - u.y).abs();
            c.scalar_conditioned(dx, 0.0, tol_x, &format!("{what}: u.x back {}", back.x));
            c.scalar_conditioned(dy, 0.0, tol_y, &format!("{what}: u.y back {}", back.y));
            for (f, axis) in [(dx / tol_x, "x"), (dy / tol_y, "y")] {
                if f > worst_u.0 {
                    worst_u = (f, dx.max(dy), format!("{what} ({axis})"));
                }
            }

            let same_cell = (o[0][3] - want.pdf).abs() <= PDF_AGREEMENT * want.pdf;
            for (got, label, also) in [(o[0][3], "pdf", same_cell), (o[1][3], "pdf()", false)] {
                match pdf_match(m, got, wi, method) {
                    PdfMatch::Same => {}
                    _ if also => {}
                    PdfMatch::Edge => edges += random as usize,
                    PdfMatch::Wrong => c.scalar(
                        got,
                        m.envmap().pdf_importance(wi),
                        &format!("{what}: {label}"),
                    ),
                }
            }
        }
        eprintln!(
            "{name}: u back within {:.3} of its tolerance (|Δu| {:e}; {}); directions within \
             {worst_dir:e} of the CPU's; {edges} samples or pdfs at an edge",
            worst_u.0, worst_u.1, worst_u.2
        );
        assert!(
            edges * EDGE_RARITY <= 2 * N,
            "{name}: {edges} samples or pdfs at an edge"
        );
        c.finish(0);
    }
}

/// A sample of a light at infinity: the point is the direction, the normal faces back.
fn check_infinite_sample(o: &[[f32; 4]; 4], what: &str) {
    assert_eq!(o[2][..3], o[0][..3], "{what}: p");
    assert_eq!(o[3][..3], [-o[0][0], -o[0][1], -o[0][2]], "{what}: n");
    assert_eq!(o[2][3], 1.0, "{what}: infinite");
}

/// Uniform sampling (the `Area` method): the sphere warp to 2e-6 absolute (as in
/// `gpu/parity.rs`), pdf 1/4π, the lookup's radiance; no sample where the map is black on both
/// sides, except at a black region's edge (as in [`importance_sampling_matches`]).
#[test]
fn uniform_sampling_matches() {
    let Some(maps) = sampling_maps() else { return };
    let method = LightSampling::Area;
    for m in &maps {
        let name = format!("uniform {}", m.name);
        let us = uniforms(25);
        let out = gpu_samples(m, &us, method);
        let lookup_atol = 1e-6 * m.max_texel;
        let mut c = Compare::new(&name, 0.0, 2e-6);
        let mut le = Compare::new(&format!("{name} radiance"), 1e-6, lookup_atol);
        let mut edges = 0;
        for (&u, o) in us.iter().zip(&out) {
            let wi = Vec3::from_slice(&o[0][..3]);
            let what = format!("{name} u {u} -> gpu {wi}");
            let black = |le: Vec3, d: Vec3| le.max_element() <= lookup_atol + m.eval_tolerance(d);
            let want = match (m.light().sample(P, Vec3::ZERO, u, method), o[0][3] >= 0.0) {
                (Some(w), true) => w,
                (None, false) => continue,
                (Some(w), false) if black(w.le, w.wi) => {
                    edges += 1;
                    continue;
                }
                (None, true) if black(Vec3::from_slice(&o[1][..3]), wi) => {
                    edges += 1;
                    continue;
                }
                (w, _) => {
                    let want = w.map_or(-1.0, |w| w.pdf);
                    c.scalar(o[0][3], want, &format!("{what}: a sample on one side only"));
                    continue;
                }
            };
            check_infinite_sample(o, &what);
            c.v3(o[0], want.wi, &what);
            c.scalar(o[0][3], want.pdf, &format!("{what}: pdf"));
            c.scalar(o[1][3], want.pdf, &format!("{what}: pdf()"));
            le.v3_conditioned(o[1], m.envmap().eval(wi), m.eval_tolerance(wi), &what);
        }
        eprintln!("{name}: {edges} samples at a black region's edge");
        assert!(
            edges * EDGE_RARITY <= N,
            "{name}: {edges} samples at an edge"
        );
        c.finish(0);
        le.finish(0);
    }
}

/// The pdf of given directions, both methods: the directions of the lookups (seam, poles, texel
/// centres, which lie on cell edges, and random ones). The CPU's pdf at the direction (to
/// [`PDF_AGREEMENT`]), or a neighbouring cell's within [`EDGE_DELTA`] ([`pdf_match`]), which at
/// most 1 in [`EDGE_RARITY`] random directions may need; the special directions sit on cell
/// edges by construction and may all need it.
#[test]
fn pdf_of_directions_matches() {
    let Some(maps) = sampling_maps() else { return };
    for m in &maps {
        let (dirs, special) = directions(m, 24);
        let inputs: Vec<[f32; 4]> = dirs.iter().map(|&d| f4(d, 0.0)).collect();
        let body = format!(
            "let p = vec3f({:?}, {:?}, {:?}); let d = inp(0u).xyz;
             outp(0u, vec4f(light_pdf(l, p, vec3f(0.0), d, vec3f(0.0), vec3f(0.0), LIGHT_SAMPLING_SOLID_ANGLE),
                            light_pdf(l, p, vec3f(0.0), d, vec3f(0.0), vec3f(0.0), LIGHT_SAMPLING_AREA), 0.0, 0.0));",
            P.x, P.y, P.z
        );
        let out = m.run(&body, &inputs, 1, 1);
        let name = format!("pdf {}", m.name);
        let mut c = Compare::new(&name, PDF_AGREEMENT, 0.0);
        let (mut edges, mut special_edges) = (0, 0);
        for (k, (&d, o)) in dirs.iter().zip(&out).enumerate() {
            for (got, method) in [
                (o[0], LightSampling::SolidAngle),
                (o[1], LightSampling::Area),
            ] {
                let want = m
                    .light()
                    .pdf(P, Vec3::ZERO, d, Vec3::ZERO, Vec3::ZERO, method);
                match pdf_match(m, got, d, method) {
                    PdfMatch::Edge if k < special => special_edges += 1,
                    PdfMatch::Edge => edges += 1,
                    _ => c.scalar(got, want, &format!("{name} towards {d} by {method:?}")),
                }
            }
        }
        eprintln!(
            "{name}: {edges} of {N} random and {special_edges} of {special} special directions \
             read a neighbouring cell"
        );
        assert!(
            edges * EDGE_RARITY <= N,
            "{name}: {edges} pdfs from a neighbouring cell"
        );
        c.finish(0);
    }
}
