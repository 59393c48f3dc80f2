//! Tests of glTF's metallic-roughness material: its eval against the specification's formulas
//! written here independently in f64, its directional albedo by sampling against a quadrature of
//! those formulas (the white furnace), the shared material checks (sampling against eval and pdf,
//! ∫pdf, reciprocity, grazing angles, energy), and its lobe selection.

use super::*;
use crate::materials::{Material, testing};
use crate::rng::Rng;
use glam::DVec3;
use std::f64::consts::PI;

/// The specification's BRDF f (not times cosθi), Appendix B as written, in f64: D the GGX
/// α²/(π((N·H)²(α² − 1) + 1)²), V the separable Smith
/// 1/((|N·L| + √(α² + (1 − α²)(N·L)²))(|N·V| + √(α² + (1 − α²)(N·V)²))), Schlick's Fresnel at
/// |V·H| with the base colour (metal) or ((1 − ior)/(1 + ior))² (dielectric) as f0, then
/// mix(mix(diffuse, specular, F_d), F_m·specular, metallic); the dielectric's `fresnel_mix` as
/// `KHR_materials_specular` rewrites it: f0 = min(f0·specularColor, 1),
/// (1 − specular·max(fr))·diffuse + specular·fr·specular_brdf (the plain one at its defaults).
fn spec_brdf(p: &GltfPbr, v: DVec3, l: DVec3) -> DVec3 {
    if v.z <= 0.0 || l.z <= 0.0 {
        return DVec3::ZERO;
    }
    let alpha = (p.roughness as f64).powi(2).max(1e-3);
    let a2 = alpha * alpha;
    let h = (v + l).normalize();
    let d = a2 / (PI * (h.z * h.z * (a2 - 1.0) + 1.0).powi(2));
    let lam = |c: f64| c + (a2 + (1.0 - a2) * c * c).sqrt();
    let vis = 1.0 / (lam(l.z) * lam(v.z));
    let specular = d * vis;
    let c = p.base_color.as_dvec3();
    let m5 = (1.0 - v.dot(h).abs()).powi(5);
    let f0 = ((1.0 - p.ior as f64) / (1.0 + p.ior as f64)).powi(2);
    let f0 = (f0 * p.specular_color.as_dvec3()).min(DVec3::ONE);
    let fr = f0 + (DVec3::ONE - f0) * m5;
    let weight = p.specular as f64;
    let f_m = c + (DVec3::ONE - c) * m5;
    let dielectric = (1.0 - weight * fr.max_element()) * c / PI + weight * fr * specular;
    let metal = f_m * specular;
    dielectric * (1.0 - p.metallic as f64) + metal * p.metallic as f64
}

/// ∫ spec_brdf·cosθi dωi over the hemisphere, by midpoint quadrature in half-vector space
/// (dωi = 4(wo·h) dωh), θh = (π/2)t² crowding nodes at the normal where narrow lobes peak.
fn spec_albedo(p: &GltfPbr, wo: DVec3, n_t: usize, n_phi: usize) -> DVec3 {
    let mut sum = DVec3::ZERO;
    for i in 0..n_t {
        let t = (i as f64 + 0.5) / n_t as f64;
        let th = 0.5 * PI * t * t;
        let dth = PI * t / n_t as f64;
        for j in 0..n_phi {
            let ph = 2.0 * PI * (j as f64 + 0.5) / n_phi as f64;
            let h = DVec3::new(th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos());
            let cos_oh = wo.dot(h);
            if cos_oh <= 0.0 {
                continue;
            }
            let wi = 2.0 * cos_oh * h - wo;
            if wi.z <= 0.0 {
                continue;
            }
            let w = th.sin() * dth * 2.0 * PI / n_phi as f64;
            sum += spec_brdf(p, wo, wi) * wi.z * 4.0 * cos_oh * w;
        }
    }
    sum
}

fn dir(theta_deg: f64) -> DVec3 {
    let t = theta_deg.to_radians();
    DVec3::new(t.sin(), 0.0, t.cos())
}

/// eval/cosθi equals the specification's formula at 4000 random pairs (seed 9710) of materials
/// across the parameters, within 2e-4 relative (f32 against f64; the floor 1e-6 of the value's
/// scale covers f32 rounding near the horizon). Catches any term written otherwise: the
/// height-correlated Smith G in place of the separable one (several % apart at these
/// roughnesses), α = roughness instead of roughness², the Fresnel at N·V instead of V·H, the
/// diffuse lobe not weighted by 1 − F, a metal's f0 not the base colour; with
/// `KHR_materials_specular` (a third of the pairs), the colour's clamp or the weight misplaced.
#[test]
fn eval_is_the_specifications_formula() {
    let mut rng = Rng::new(9710, 0, 0);
    let mut worst = 0.0f64;
    for k in 0..4000 {
        let p = GltfPbr {
            base_color: Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()),
            metallic: [0.0, 1.0, rng.next_f32()][k % 3],
            roughness: 0.1 + 0.9 * rng.next_f32(),
            ior: 1.0 + 2.0 * rng.next_f32(),
            ..GltfPbr::default()
        };
        let p = if k % 3 == 1 {
            GltfPbr {
                specular: rng.next_f32(),
                specular_color: Vec3::new(rng.next_f32(), rng.next_f32(), 30.0 * rng.next_f32()),
                ..p
            }
        } else {
            p
        };
        let wo = crate::sampling::sample_uniform_sphere(rng.next_2d());
        let wi = crate::sampling::sample_uniform_sphere(rng.next_2d());
        let (wo, wi) = (
            Vec3::new(wo.x, wo.y, wo.z.abs()),
            Vec3::new(wi.x, wi.y, wi.z.abs()),
        );
        if wo.z < 1e-3 || wi.z < 1e-3 {
            continue;
        }
        let got = (p.eval(wo, wi) / wi.z).as_dvec3();
        let want = spec_brdf(&p, wo.as_dvec3(), wi.as_dvec3());
        let err = ((got - want).abs() / (want.abs() + DVec3::splat(1e-6 * want.max_element())))
            .max_element();
        worst = worst.max(err);
        assert!(err < 2e-4, "{p:?} wo {wo} wi {wi}: {got} vs {want}");
    }
    eprintln!("largest relative difference from the specification: {worst:.2e}");
    // Below the surface on either side: nothing (a two-sided material is flipped before).
    let p = GltfPbr::default();
    assert_eq!(p.eval(Vec3::Z, -Vec3::Z), Vec3::ZERO);
    assert_eq!(p.eval(-Vec3::Z, Vec3::Z), Vec3::ZERO);
}

/// The white furnace: a white base's directional albedo by the sampler's mean weight (400 000
/// samples, seeds 9720 + case) against the quadrature of [`spec_brdf`] (1500 × 600 nodes,
/// checked converged to 2e-4 against 3000 × 1200), for metallic 0 and 1, roughness 0.2, 0.5, 1 and
/// θo 0°, 45°, 80°. Tolerance 5σ of the Monte Carlo mean + 2e-4. Catches a sampler whose
/// weight is not eval/pdf of what it draws (a lobe probability left out of the pdf, the VNDF
/// pdf without its 1/(4 wo·h)), and together with [`eval_is_the_specifications_formula`] an
/// albedo that is not the specification's. The values are printed (a white metal loses energy
/// to single scattering: 0.31 at roughness 1 seen head-on, by an independent numpy quadrature;
/// a white dielectric exceeds 1 towards grazing, as the specification's fresnel_mix weighs the
/// diffuse lobe by 1 − F at V·H of each light direction, not of the view).
#[test]
fn white_furnace_albedo_matches_quadrature() {
    let mut case = 0;
    for metallic in [0.0f32, 1.0] {
        for roughness in [0.2f32, 0.5, 1.0] {
            for th in [0.0, 45.0, 80.0] {
                let p = GltfPbr {
                    base_color: Vec3::ONE,
                    metallic,
                    roughness,
                    ..GltfPbr::default()
                };
                let wo = dir(th);
                let quad = spec_albedo(&p, wo, 1500, 600).x;
                let fine = spec_albedo(&p, wo, 3000, 1200).x;
                assert!((quad - fine).abs() < 2e-4, "quadrature {quad} vs {fine}");
                let mut rng = Rng::new(9720 + case, 0, 0);
                case += 1;
                let n = 400_000;
                let (mut sum, mut sum2) = (0.0f64, 0.0f64);
                for _ in 0..n {
                    if let Some(s) = p.sample(wo.as_vec3(), rng.next_f32(), rng.next_2d()) {
                        let w = s.weight.x as f64;
                        sum += w;
                        sum2 += w * w;
                    }
                }
                let mean = sum / n as f64;
                let sigma = ((sum2 / n as f64 - mean * mean) / n as f64).sqrt();
                eprintln!(
                    "metallic {metallic} roughness {roughness} θo {th}°: sampled {mean:.5} ± \
                     {sigma:.1e}, quadrature {fine:.5}"
                );
                assert!(
                    (mean - fine).abs() < 5.0 * sigma + 2e-4,
                    "metallic {metallic} roughness {roughness} θ {th}: {mean} vs {fine}"
                );
            }
        }
    }
}

/// The shared material checks (seed 9730) on materials across the parameters. Energy bounds
/// stated before the first run from an independent quadrature of the specification's formulas
/// (numpy, white base): a metal conserves energy (≤ 1); a dielectric does not, reaching 1.84 at
/// 89.5° for roughness 0.05 (white), so its bound is 2.
///
/// A narrow lobe is checked on a metal only: beside a diffuse lobe, the checks' uniform
/// estimate of the energy passes its effective-sample-size guard on the diffuse lobe's samples
/// and misses a lobe of α ≲ 0.01 (first run: a white dielectric of roughness 0.05 at 85°, uniform
/// 0.885 against the sampler's 1.469, which the half-vector quadrature agreed with). That
/// dielectric is checked at roughness 0.3 here; narrow dielectric lobes are covered by the
/// quadrature comparison of [`white_furnace_albedo_matches_quadrature`] and by χ².
#[test]
fn shared_checks() {
    let colour = Vec3::new(0.8, 0.5, 0.2);
    let cases = [
        (GltfPbr::default(), 1.0),
        (
            GltfPbr {
                base_color: colour,
                roughness: 0.3,
                ..GltfPbr::default()
            },
            1.0,
        ),
        (
            GltfPbr {
                base_color: colour,
                metallic: 0.0,
                roughness: 0.5,
                ..GltfPbr::default()
            },
            2.0,
        ),
        (
            GltfPbr {
                base_color: Vec3::new(0.9, 0.9, 0.9),
                metallic: 0.0,
                roughness: 0.3,
                ior: 1.8,
                ..GltfPbr::default()
            },
            2.0,
        ),
        (
            GltfPbr {
                base_color: Vec3::new(0.95, 0.64, 0.54),
                roughness: 0.05,
                ..GltfPbr::default()
            },
            1.0,
        ),
        (
            GltfPbr {
                base_color: Vec3::new(0.3, 0.7, 0.9),
                metallic: 0.6,
                roughness: 0.7,
                ior: 1.0,
                ..GltfPbr::default()
            },
            2.0,
        ),
        (
            GltfPbr {
                base_color: Vec3::new(0.6, 0.6, 0.3),
                metallic: 0.2,
                roughness: 0.4,
                specular: 0.5,
                specular_color: Vec3::new(1.5, 0.5, 20.0),
                ..GltfPbr::default()
            },
            2.0,
        ),
        (
            GltfPbr {
                base_color: Vec3::ZERO,
                metallic: 0.0,
                roughness: 0.4,
                ..GltfPbr::default()
            },
            2.0,
        ),
    ];
    for (p, max_energy) in cases {
        let reports = testing::check_material_with_energy(&Material::GltfPbr(p), 9730, max_energy);
        let most = reports
            .iter()
            .map(|r| r.albedo_quad.max_element())
            .fold(0.0, f64::max);
        eprintln!("{p:?}: largest energy {most:.4}");
    }
}

/// The specular lobe's probability: 1 without a diffuse lobe (a metal, a black base), the
/// Fresnel estimate otherwise, never below the floor; and the pdf is the mixture's, so a
/// direction only the diffuse lobe reaches still has density (1 − p_s)·cosθ/π. Catches a pdf
/// that forgets the lobe not drawn (MIS would then weigh with the wrong density).
#[test]
fn lobe_probabilities_and_the_mixtures_pdf() {
    let wo = dir(30.0).as_vec3();
    assert_eq!(GltfPbr::default().specular_probability(wo), 1.0);
    let black = GltfPbr {
        base_color: Vec3::ZERO,
        metallic: 0.0,
        ..GltfPbr::default()
    };
    assert_eq!(black.specular_probability(wo), 1.0);
    let white = GltfPbr {
        base_color: Vec3::ONE,
        metallic: 0.0,
        roughness: 0.1,
        ..GltfPbr::default()
    };
    let f = super::super::fresnel::fresnel_schlick(0.04, wo.z);
    let p_s = white.specular_probability(wo);
    assert!((p_s - f.max(MIN_SPECULAR_RATE)).abs() < 1e-6, "{p_s} {f}");
    let ior1 = GltfPbr { ior: 1.0, ..white };
    assert_eq!(ior1.specular_probability(Vec3::Z), MIN_SPECULAR_RATE);
    // Far from the mirror direction of a narrow lobe the diffuse share dominates, and the pdf
    // is both shares (GGX's tail is long: the specular one is not 0 there).
    let wi = dir(-60.0).as_vec3();
    let diffuse = (1.0 - p_s) * wi.z * FRAC_1_PI;
    let (h, _) = ggx::half_vector(wo, wi);
    let alpha = white.alpha();
    let specular = p_s * ggx::g1(alpha, wo) * ggx::d(alpha, h) / (4.0 * wo.z);
    assert!(diffuse > 10.0 * specular, "{diffuse} {specular}");
    let want = diffuse + specular;
    assert!((white.pdf(wo, wi) - want).abs() < 1e-6 * want);
}
