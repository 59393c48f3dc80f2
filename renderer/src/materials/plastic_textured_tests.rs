//! Tests of the α grid: the blend's error against the exact table at mid-grid α, the hit's
//! plastic through the shared BSDF checks and against quadrature at off-grid α, and χ² of its
//! sampling there.

use super::*;
use crate::materials::coat_albedo::tests::e_reference;
use crate::materials::{Material, Plastic, fresnel, testing};
use crate::stats::{BsdfSampler, ChiSquareTest};
use glam::{DVec3, Vec3};

/// Coat IORs of the blend-error measurement (F0 0.0023 … 0.67).
const BLEND_IORS: [f32; 4] = [1.1, 1.5, 3.0, 10.0];

/// The midpoint in ln α of grid interval `i`: where a blend linear in ln α is furthest from both
/// of its nodes.
fn mid_grid(i: usize) -> f32 {
    (0.5 * (node_alpha(i).ln() + node_alpha(i + 1).ln())).exp()
}

/// Off-grid roughnesses of the material tests: mid-grid near α ≈ 0.0085 (narrow), 0.049 and
/// 0.38.
fn off_grid() -> [f32; 3] {
    [mid_grid(14), mid_grid(26), mid_grid(40)]
}

/// A plastic whose α comes from the grid, as a textured one at a hit.
fn grid_plastic(albedo: Vec3, alpha: f32, ior: f32, specular: Vec3) -> Plastic {
    // The base's own α (its mean in a scene) does not matter: the grid replaces its coat.
    let mut p = Plastic::new(albedo, 0.5, ior, specular);
    p.set_alpha_from_grid(alpha, &CoatGrid::new(p.f0()));
    p
}

/// Largest |a − b| over the table entries (both are piecewise linear on the same μ nodes, so this
/// is the largest difference at any μ) and the difference of their E_avg.
fn table_distance(a: &CoatAlbedo, b: &CoatAlbedo) -> (f32, f32) {
    let d = a
        .table()
        .iter()
        .zip(b.table())
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f32::max);
    (d, (a.average() - b.average()).abs())
}

#[test]
fn grid_spans_smooth_alpha_to_one_evenly_in_log() {
    assert_eq!(node_alpha(0), ggx::SMOOTH_ALPHA);
    assert_eq!(node_alpha(GRID_SIZE - 1), 1.0);
    let ratio = node_alpha(1) / node_alpha(0);
    for i in 1..GRID_SIZE {
        let r = node_alpha(i) / node_alpha(i - 1);
        assert!((r / ratio - 1.0).abs() < 1e-4, "{i}: {r} vs {ratio}");
    }
    for i in 0..GRID_SIZE - 1 {
        let (j, t) = locate(mid_grid(i));
        assert!(j == i && (t - 0.5).abs() < 1e-3, "{i}: {j} {t}");
    }
}

/// The blend's interpolation error, which the module documents: at the midpoint (in ln α) of
/// every grid interval, the blended table against the table built at that α, for IORs 1.1 … 3
/// (bounds [`MAX_BLEND_ERROR`], 3e-4 on E_avg) and 10 (F0 0.67, bounds 2.5e-3 and 7e-4: there
/// the exact tables themselves jitter with α by ~1.5e-3, their quadrature's error). Fails if the grid is too coarse, the
/// blend weight is wrong (the midpoint would not be halfway) or E_avg is not blended with the
/// table.
#[test]
fn blend_error_at_mid_grid() {
    for ior in BLEND_IORS {
        let (bound, bound_avg) = if ior <= 3.0 {
            (MAX_BLEND_ERROR, 3e-4)
        } else {
            (2.5e-3, 7e-4)
        };
        let f0 = fresnel::schlick_f0_from_ior(ior);
        let grid = CoatGrid::new(f0);
        let errors: Vec<(f32, f32, f32)> = (0..GRID_SIZE - 1)
            .into_par_iter()
            .map(|i| {
                let a = mid_grid(i);
                let (d, d_avg) = table_distance(&grid.coat(a), &CoatAlbedo::new(a, f0));
                (a, d, d_avg)
            })
            .collect();
        let (mut worst, mut worst_avg) = ((0.0f32, 0.0f32), (0.0f32, 0.0f32));
        for (a, d, d_avg) in errors {
            if d > worst.0 {
                worst = (d, a);
            }
            if d_avg > worst_avg.0 {
                worst_avg = (d_avg, a);
            }
            assert!(
                d <= bound && d_avg <= bound_avg,
                "ior {ior} α {a}: |ΔE| {d:.2e}, |ΔE_avg| {d_avg:.2e}"
            );
        }
        eprintln!(
            "blend at mid-grid, ior {ior}: max |ΔE| = {:.2e} (α {:.4}), max |ΔE_avg| = {:.2e} \
             (α {:.4})",
            worst.0, worst.1, worst_avg.0, worst_avg.1
        );
    }
}

/// Blend error at mid-grid for other node counts and variables: linear in ln α, √α and α, over
/// [`BLEND_IORS`] (the module doc's comparison). A measurement, not a check: run with
/// `--ignored --nocapture`.
#[test]
#[ignore]
fn blend_variables_compared() {
    type Map = fn(f32) -> f32;
    let variables: [(&str, Map, Map); 3] = [
        ("ln α", f32::ln, f32::exp),
        ("√α", f32::sqrt, |x| x * x),
        ("α", |x| x, |x| x),
    ];
    for n in [24, 32, 48, 64] {
        for (name, to, from) in variables {
            if n != GRID_SIZE && name != "ln α" {
                continue;
            }
            let (lo, hi) = (to(ggx::SMOOTH_ALPHA), to(1.0));
            let node = |i: usize| from(lo + (hi - lo) * i as f32 / (n - 1) as f32);
            let (mut worst, mut at, mut worst_avg) = (0.0f32, 0.0f32, 0.0f32);
            for ior in BLEND_IORS {
                let f0 = fresnel::schlick_f0_from_ior(ior);
                let tables: Vec<CoatAlbedo> = (0..n)
                    .into_par_iter()
                    .map(|i| CoatAlbedo::new(node(i).max(ggx::SMOOTH_ALPHA), f0))
                    .collect();
                let errors: Vec<(f32, f32, f32)> = (0..n - 1)
                    .into_par_iter()
                    .map(|i| {
                        let a = from(0.5 * (to(node(i)) + to(node(i + 1))));
                        let a = a.max(ggx::SMOOTH_ALPHA);
                        let b = CoatAlbedo::blend(&tables[i], &tables[i + 1], 0.5, a);
                        let (d, d_avg) = table_distance(&b, &CoatAlbedo::new(a, f0));
                        (d, a, d_avg)
                    })
                    .collect();
                for (d, a, d_avg) in errors {
                    if d > worst {
                        (worst, at) = (d, a);
                    }
                    worst_avg = worst_avg.max(d_avg);
                }
            }
            eprintln!(
                "{n} nodes, blend linear in {name}: max |ΔE| = {worst:.2e} at α {at:.4}, \
                 max |ΔE_avg| = {worst_avg:.2e}"
            );
        }
    }
}

#[test]
fn at_a_node_and_below_smooth_alpha_the_grid_gives_the_plain_table() {
    let f0 = fresnel::schlick_f0_from_ior(1.5);
    let grid = CoatGrid::new(f0);
    for i in [0, 7, GRID_SIZE - 1] {
        let exact = CoatAlbedo::new(node_alpha(i), f0);
        assert_eq!(grid.node(i), &exact);
        let (d, d_avg) = table_distance(&grid.coat(node_alpha(i)), &exact);
        assert!(d < 1e-6 && d_avg < 1e-6, "node {i}: {d} {d_avg}");
    }
    // A smooth coat is exactly the untextured smooth plastic's.
    for a in [0.0, 5e-4] {
        let p = grid_plastic(Vec3::splat(0.5), a, 1.5, Vec3::ONE);
        assert_eq!(p, Plastic::new(Vec3::splat(0.5), a, 1.5, Vec3::ONE));
    }
}

/// The hit's plastic at off-grid α through the shared BSDF checks (sampling, pdf and eval agree;
/// reciprocity; ∫pdf; energy ≤ 1), and its directional albedo against quadrature of the true coat:
/// expected specular·E_true(μo) + albedo·(1 − E_blend(μo)), to the checks' quadrature error
/// (2e-3) plus the reference's (1e-4). Seeds 21 (coloured, IOR 1.5 and 3) and 22 (white, IOR
/// 1.1, where the coat's albedo changes most with μ).
#[test]
fn off_grid_plastic_passes_the_material_checks_and_matches_quadrature() {
    let cases: [(Vec3, Vec3, &[f32], u32); 2] = [
        (
            Vec3::new(0.8, 0.4, 0.1),
            Vec3::new(1.0, 0.9, 0.8),
            &[1.5, 3.0],
            21,
        ),
        (Vec3::ONE, Vec3::ONE, &[1.1], 22),
    ];
    for (albedo, specular, iors, seed) in cases {
        for alpha in off_grid() {
            for &ior in iors {
                let p = grid_plastic(albedo, alpha, ior, specular);
                assert_eq!(p.alpha(), alpha, "α is not quantised");
                for r in testing::check_material(&Material::Plastic(p.clone()), seed) {
                    let mu = r.theta_deg.to_radians().cos();
                    let e_true = e_reference(alpha, p.f0(), mu);
                    let expect =
                        (specular * e_true + albedo * (1.0 - p.coat_albedo(mu))).as_dvec3();
                    let d = (r.albedo_quad - expect).abs().max_element();
                    assert!(d < 2.1e-3, "a {alpha} ior {ior} {r:?}: expected {expect}");
                    if albedo == Vec3::ONE {
                        // Energy: 1 up to the table's error (≤ 1.2e-3 at α ≥ 0.005), the blend's
                        // (≤ MAX_BLEND_ERROR) and 5σ of Monte Carlo noise.
                        let tol =
                            1.2e-3 + MAX_BLEND_ERROR as f64 + 5.0 * r.albedo_sigma.max_element();
                        let d = (r.albedo_mc - DVec3::ONE).abs().max_element();
                        assert!(
                            d < tol,
                            "a {alpha} ior {ior} θ {}: {}",
                            r.theta_deg,
                            r.albedo_mc
                        );
                    }
                }
            }
        }
    }
}

/// χ² of the hit's plastic sampling against its pdf at the off-grid α and the suite's incidence
/// angles (IOR 1.5, 1e6 samples each, seeds 3000 + case): family-wise α = 0.01 over these
/// [`off_grid`] × [`crate::stats::suite::THETAS_DEG`] = 15 tests, Šidák-corrected. Detects a
/// sampler whose lobe choice or coat probability reads another table than its pdf.
#[test]
fn off_grid_plastic_sampling_matches_its_pdf() {
    let thetas = crate::stats::suite::THETAS_DEG;
    let cases: Vec<(f32, f32)> = off_grid()
        .into_iter()
        .flat_map(|a| thetas.map(|t| (a, t)))
        .collect();
    let n = cases.len();
    let results: Vec<String> = cases
        .par_iter()
        .enumerate()
        .filter_map(|(i, &(alpha, theta))| {
            let m = grid_plastic(Vec3::new(0.8, 0.4, 0.1), alpha, 1.5, Vec3::ONE);
            let sampler = BsdfSampler::at_angle(Material::Plastic(m), theta);
            let r = ChiSquareTest::new(&sampler)
                .samples(1_000_000)
                .seed(3000 + i as u32)
                .significance(0.01, n)
                .run();
            eprintln!("plastic grid a{alpha:.4} th{theta}: {r}");
            (!r.passed()).then(|| format!("a {alpha} θ {theta}: {r}"))
        })
        .collect();
    assert!(results.is_empty(), "{}", results.join("\n"));
}
