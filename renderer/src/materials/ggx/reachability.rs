//! Can the visible-normal sampler reach all of its support in f32 (issue 14, item 6)?
//!
//! The renderer's uniforms are the 2^24 values k/2^24 ([`crate::rng::unit_f32`]), so the sampler's
//! image is a finite set, and f32 cancellation could leave part of the lobe's tail with no sample
//! at all while the pdf still gives it mass. These tests push a lattice of exactly such uniforms
//! through [`sample_visible_normal`] and compare the mass landing in each cell of half-vector
//! space with ∫pdf over the cell (quadrature of [`visible_normal_pdf`]).
//!
//! The tail lives in u.y: the stretched half vector has h_std.z = (1 − u.y)(1 + wo_std.z) and
//! tanθh = α|h_std.xy|/h_std.z, so m = 2^24 (1 − u.y) ∈ [1, 2^24] sets how close h comes to the
//! horizon. The lattice therefore takes every RNG value of m < 2·[`ROWS_PER_OCTAVE`] and that
//! many rows per octave above (each at its stride's midpoint, itself an RNG value, weighted by the stride). u.x
//! only sets the azimuth 2πu.x, with no cancellation, so [`COLUMNS`] evenly spaced values do.
//! Cells are octaves of t = tanθh/α (one core cell t < 1, then up to 2^17, then to the horizon)
//! times 8 azimuth sectors; the silhouette wo·h = 0 is cut exactly in the quadrature.

use super::{sample_visible_normal, visible_normal_pdf};
use crate::rng::unit_f32;
use glam::{DVec3, Vec2, Vec3};
use std::f64::consts::PI;

/// Lattice columns in u.x.
const COLUMNS: u32 = 2048;
/// Lattice rows per octave of m = 2^24 (1 − u.y): every RNG value while m < 2·ROWS_PER_OCTAVE.
const ROWS_PER_OCTAVE: u32 = 128;
/// Azimuth sectors of |φh| ∈ [0, π] (wo lies in the xz half-plane x > 0; the lobe is symmetric).
const SECTORS: usize = 8;
/// Highest finite t cell edge, 2^17 (α = 0.01: 89.96° from the normal).
const MAX_OCTAVE: i32 = 17;

/// Unreachable mass allowed: ∫pdf over cells the lattice never reaches. The correct sampler
/// leaves < 1e-9 (lattice effects); a 16-bit u.y loses ≥ 7e-6, Heitz 2018's form ≥ 3e-5.
const MAX_UNREACHABLE: f64 = 1e-7;
/// Cells with at least this ∫pdf must receive it to [`MAX_RELATIVE`].
const MIN_CHECKED_MASS: f64 = 1e-5;
/// Relative error allowed in such cells; the correct sampler is within 2.1% (the lattice's own
/// discretisation: an f64 twin of the sampler on the same lattice measures the same).
const MAX_RELATIVE: f64 = 0.05;

/// A sampler of visible normals: (α, wo, u) → h.
type Sampler = fn(f32, Vec3, Vec2) -> Vec3;

/// The cell edges in t = tanθh/α: 0, 1, 2, 4, …, 2^MAX_OCTAVE, ∞.
fn t_edges() -> Vec<f64> {
    let mut e = vec![0.0];
    e.extend((0..=MAX_OCTAVE).map(|k| 2f64.powi(k)));
    e.push(f64::INFINITY);
    e
}

/// The cell of a half vector (the last t cell includes h on the horizon). Matches the cells of
/// [`t_edges`]: t ∈ [2^(k−1), 2^k) is t cell k, read off t's binary exponent; `sector_cos` holds
/// cos(kπ/SECTORS) for k = 1…SECTORS−1.
fn cell(alpha: f64, h: Vec3, sector_cos: &[f64]) -> usize {
    let h = h.as_dvec3();
    let r = (h.x * h.x + h.y * h.y).sqrt();
    let t = if h.z > 0.0 {
        r / h.z / alpha
    } else {
        f64::INFINITY
    };
    let it = if t < 1.0 {
        0
    } else {
        let exponent = ((t.to_bits() >> 52) & 0x7ff) as i32 - 1023;
        (exponent + 1).min(MAX_OCTAVE + 1) as usize
    };
    // |φ| > kπ/SECTORS ⇔ cos φ < cos(kπ/SECTORS); h = +z counts as sector 0.
    let cos_phi = if r > 0.0 { h.x / r } else { 1.0 };
    let is = sector_cos.iter().filter(|&&c| cos_phi < c).count();
    it * SECTORS + is
}

/// 8-point Gauss–Legendre nodes and weights on [−1, 1].
const GL8: [(f64, f64); 8] = [
    (-0.960_289_856_497_536_3, 0.101_228_536_290_376_3),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
    (-0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (-0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
    (0.960_289_856_497_536_3, 0.101_228_536_290_376_3),
];

/// ∫ f over [a, b], composite 8-point Gauss–Legendre on `n` pieces.
fn integrate(a: f64, b: f64, n: usize, f: &mut dyn FnMut(f64) -> f64) -> f64 {
    let w = (b - a) / n as f64;
    let mut sum = 0.0;
    for k in 0..n {
        let c = a + (k as f64 + 0.5) * w;
        for &(x, g) in &GL8 {
            sum += g * 0.5 * w * f(c + 0.5 * w * x);
        }
    }
    sum
}

/// ∫pdf per cell, by quadrature in (θh, φh). The pdf is smooth in each cell up to the
/// silhouette cos φ = −cot θh cot θo, so the φ range stops there.
fn expected(alpha: f32, wo: Vec3, edges: &[f64]) -> Vec<f64> {
    let a = alpha as f64;
    let w = wo.as_dvec3();
    let cot_o = w.z / (w.x * w.x + w.y * w.y).sqrt();
    let mut mass = vec![0.0; (edges.len() - 1) * SECTORS];
    for it in 0..edges.len() - 1 {
        let (th0, th1) = ((a * edges[it]).atan(), (a * edges[it + 1]).atan());
        for is in 0..SECTORS {
            let p0 = PI * is as f64 / SECTORS as f64;
            let p1 = PI * (is + 1) as f64 / SECTORS as f64;
            let m = integrate(th0, th1, 16, &mut |th| {
                let c = -cot_o / th.tan();
                let silhouette = if c <= -1.0 { PI } else { c.min(1.0).acos() };
                let hi = p1.min(silhouette);
                if hi <= p0 {
                    return 0.0;
                }
                let (st, ct) = th.sin_cos();
                st * integrate(p0, hi, 4, &mut |ph| {
                    let h = DVec3::new(st * ph.cos(), st * ph.sin(), ct).as_vec3();
                    visible_normal_pdf(alpha, wo, h) as f64
                })
            });
            // Both signs of φ.
            mass[it * SECTORS + is] = 2.0 * m;
        }
    }
    mass
}

/// The lattice rows: (u.y, the fraction of the RNG's u.y values it stands for).
fn rows() -> Vec<(f32, f64)> {
    let mut r = Vec::new();
    for j in 0..24 {
        let lo = 1u32 << j;
        let stride = (lo / ROWS_PER_OCTAVE).max(1);
        for m0 in (lo..2 * lo).step_by(stride as usize) {
            let m = m0 + stride / 2;
            r.push((unit_f32(((1 << 24) - m) << 8), stride as f64 / 16_777_216.0));
        }
    }
    r.push((0.0, 1.0 / 16_777_216.0)); // m = 2^24
    r
}

/// The mass the lattice puts in each cell through `sampler`.
fn reachable(sampler: Sampler, alpha: f32, wo: Vec3, cells: usize) -> Vec<f64> {
    let mut mass = vec![0.0; cells];
    let sector_cos: Vec<f64> = (1..SECTORS)
        .map(|k| (PI * k as f64 / SECTORS as f64).cos())
        .collect();
    let columns: Vec<f32> = (0..COLUMNS)
        .map(|i| unit_f32((2 * i + 1) << (31 - COLUMNS.trailing_zeros())))
        .collect();
    let rows = rows();
    assert!((rows.iter().map(|r| r.1).sum::<f64>() - 1.0).abs() < 1e-12);
    for (uy, weight) in rows {
        let w = weight / COLUMNS as f64;
        for &ux in &columns {
            let h = sampler(alpha, wo, Vec2::new(ux, uy));
            mass[cell(alpha as f64, h, &sector_cos)] += w;
        }
    }
    mass
}

/// What one case measured.
#[derive(Debug)]
struct Reach {
    /// ∫pdf over cells the lattice never reaches.
    unreachable: f64,
    /// Largest |reachable/∫pdf − 1| over cells with ∫pdf ≥ [`MIN_CHECKED_MASS`], and its cell's
    /// lower t edge.
    worst: (f64, f64),
    /// ∫pdf and reachable mass of the far tail t ≥ 2^10.
    tail: (f64, f64),
}

fn measure(sampler: Sampler, alpha: f32, theta_deg: f32) -> Reach {
    let t = theta_deg.to_radians();
    let wo = Vec3::new(t.sin(), 0.0, t.cos());
    let edges = t_edges();
    let p = expected(alpha, wo, &edges);
    let total: f64 = p.iter().sum();
    assert!((total - 1.0).abs() < 1e-4, "quadrature: ∫pdf = {total}");
    let r = reachable(sampler, alpha, wo, p.len());
    let mut out = Reach {
        unreachable: 0.0,
        worst: (0.0, 0.0),
        tail: (0.0, 0.0),
    };
    for (k, (&pk, &rk)) in p.iter().zip(&r).enumerate() {
        let t0 = edges[k / SECTORS];
        if rk == 0.0 {
            out.unreachable += pk;
        }
        if pk >= MIN_CHECKED_MASS && (rk / pk - 1.0).abs() > out.worst.0 {
            out.worst = ((rk / pk - 1.0).abs(), t0);
        }
        if t0 >= 1024.0 {
            out.tail.0 += pk;
            out.tail.1 += rk;
        }
    }
    out
}

fn passes(r: &Reach) -> bool {
    r.unreachable <= MAX_UNREACHABLE && r.worst.0 <= MAX_RELATIVE
}

/// The grazing cases of issue 14 (α, θo in degrees), plus the stress matrix's α at 89.9°.
const CASES: [(f32, f32); 13] = [
    (0.01, 80.0),
    (0.01, 85.0),
    (0.01, 89.0),
    (0.01, 89.5),
    (0.01, 89.9),
    (0.02, 80.0),
    (0.02, 85.0),
    (0.02, 89.0),
    (0.02, 89.5),
    (0.05, 80.0),
    (0.05, 85.0),
    (0.05, 89.0),
    (0.05, 89.5),
];

#[test]
fn vndf_reaches_its_whole_support_in_f32() {
    let mut failed = Vec::new();
    for (alpha, theta) in CASES {
        let r = measure(sample_visible_normal, alpha, theta);
        eprintln!(
            "α {alpha} θo {theta}°: unreachable ∫pdf {:.1e}, worst cell {:.2e} (t ≥ {}), \
             tail t ≥ 1024: ∫pdf {:.4e} reachable {:.4e}",
            r.unreachable, r.worst.0, r.worst.1, r.tail.0, r.tail.1
        );
        if !passes(&r) {
            failed.push((alpha, theta, r));
        }
    }
    assert!(failed.is_empty(), "{failed:?}");
}

/// Heitz 2018's listing (as in pbrt-v3) in f32: `sqrt(1 − t1² − t2²)` cancels at the projected
/// disk's rim, where the tail lives, so h.z snaps to 0 or to ≥ ~3e-4 and the tail between is
/// empty. The form the issue suspected; the spherical-cap sampler has no such step.
fn heitz2018(alpha: f32, wo: Vec3, u: Vec2) -> Vec3 {
    let vh = Vec3::new(alpha * wo.x, alpha * wo.y, wo.z).normalize();
    let len2 = vh.x * vh.x + vh.y * vh.y;
    let t1v = if len2 > 0.0 {
        Vec3::new(-vh.y, vh.x, 0.0) / len2.sqrt()
    } else {
        Vec3::X
    };
    let t2v = vh.cross(t1v);
    let r = u.x.sqrt();
    let phi = 2.0 * std::f32::consts::PI * u.y;
    let t1 = r * phi.cos();
    let s = 0.5 * (1.0 + vh.z);
    let t2 = (1.0 - s) * (1.0 - t1 * t1).sqrt() + s * r * phi.sin();
    let nh = t1 * t1v + t2 * t2v + (1.0 - t1 * t1 - t2 * t2).max(0.0).sqrt() * vh;
    Vec3::new(alpha * nh.x, alpha * nh.y, nh.z.max(0.0)).normalize()
}

/// The correct sampler fed a 16-bit u.y (as from a 16-bit sequence): 1 − u.y ≥ 2^-16, so the
/// tail beyond tanθh ≈ 2^16 α/(1 + wo_std.z) is never drawn.
fn sixteen_bits(alpha: f32, wo: Vec3, u: Vec2) -> Vec3 {
    sample_visible_normal(alpha, wo, Vec2::new(u.x, (u.y * 65536.0).floor() / 65536.0))
}

#[test]
fn reachability_check_catches_lost_tails() {
    for (name, sampler) in [
        ("Heitz 2018 in f32", heitz2018 as Sampler),
        ("16-bit u.y", sixteen_bits),
    ] {
        for (alpha, theta) in [(0.01, 89.5), (0.05, 80.0)] {
            let r = measure(sampler, alpha, theta);
            eprintln!("{name}, α {alpha} θo {theta}°: {r:?}");
            assert!(!passes(&r), "{name} α {alpha} θo {theta}: {r:?}");
        }
    }
}
