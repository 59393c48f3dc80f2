//! Tests of Mitsuba's principled BSDF: against Mitsuba 3.9.1's own eval and pdf, the shared
//! material checks (sampling against eval and pdf, ∫pdf, reciprocity, grazing angles, energy by
//! sampling, quadrature and uniform sampling) and its constants.

use super::*;
use crate::materials::{Material, testing};
use serde_json::Value;

fn vec3(v: &Value) -> Vec3 {
    let c = |i: usize| v[i].as_f64().expect("a number") as f32;
    Vec3::new(c(0), c(1), c(2))
}

/// The principled of one case of `tests/data/refs/mitsuba_principled_values.json`, Mitsuba's
/// defaults and flags applied as the scene parser applies them.
fn principled_of(case: &Value) -> Principled {
    let get = |k: &str| case.get(k).map(|v| v.as_f64().expect("a number") as f32);
    let mut p = Principled::default();
    if let Some(c) = case.get("base_color") {
        p.base_color = vec3(c);
    }
    for param in PrincipledParam::ALL {
        if let Some(v) = get(param.name()) {
            param.set(&mut p, v);
        }
    }
    p.transmission = get("spec_trans").is_some_and(|t| t != 0.0);
    p.eta = mitsuba_eta(get("eta"), get("specular"), p.transmission);
    p.rates = SamplingRates {
        specular: get("main_specular_sampling_rate").unwrap_or(1.0),
        clearcoat: get("clearcoat_sampling_rate").unwrap_or(1.0),
        diffuse: get("diffuse_reflectance_sampling_rate").unwrap_or(1.0),
    };
    p
}

/// Relative difference with an absolute floor of 1e-4 of the pair's larger value's scale: the
/// cases hold values down to 1e-9 at grazing angles, where f32 rounding of the half vector alone
/// moves them by more than any relative tolerance.
fn relative(a: f32, b: f32, scale: f32) -> f32 {
    (a - b).abs() / a.abs().max(b.abs()).max(1e-4 * scale).max(1e-30)
}

/// lumis' eval and pdf against Mitsuba's (variant llvm_ad_rgb, `tools/mitsuba_principled_values.py`)
/// at 6723 direction pairs of 18 principled BSDFs covering every parameter, both sides and
/// transmission. Tolerance 2e-3 relative on eval and pdf (f32 arithmetic in a different order:
/// Mitsuba's own scalar and JIT variants differ by up to 4.4e-4 on these pairs, as the tool's
/// author measured); the floor is 1e-4 of the case's largest value. Power: the sheen evaluated
/// only where the diffuse lobe is on (Mitsuba's scalar variant) differs by 3.3% at the tool's
/// case 14; a clearcoat without its 0.25 weight, a metal F0 of 0.04, a transmission without
/// √base all move values by far more.
#[test]
fn values_match_mitsuba() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../tests/data/refs/mitsuba_principled_values.json");
    let data: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let (mut worst_eval, mut worst_pdf, mut pairs) = (0.0f32, 0.0f32, 0);
    let mut failures = Vec::new();
    for case in data["cases"].as_array().unwrap() {
        let bsdf = &case["bsdf"];
        let m = Material::Principled(principled_of(bsdf));
        let values = case["values"].as_array().unwrap();
        let all_pairs = || values.iter().flat_map(|e| e["pairs"].as_array().unwrap());
        let eval_scale = all_pairs()
            .map(|p| vec3(&p["eval"]).max_element())
            .fold(0.0, f32::max);
        let pdf_scale = all_pairs()
            .map(|p| p["pdf"].as_f64().unwrap() as f32)
            .fold(0.0, f32::max);
        for entry in values {
            let wo = vec3(&entry["wo"]);
            for pair in entry["pairs"].as_array().unwrap() {
                let wi = vec3(&pair["wi"]);
                let (f, pdf) = (m.eval(wo, wi), m.pdf(wo, wi));
                let (f_mi, pdf_mi) = (vec3(&pair["eval"]), pair["pdf"].as_f64().unwrap() as f32);
                let d_eval = (0..3)
                    .map(|c| relative(f[c], f_mi[c], eval_scale))
                    .fold(0.0, f32::max);
                let d_pdf = relative(pdf, pdf_mi, pdf_scale);
                worst_eval = worst_eval.max(d_eval);
                worst_pdf = worst_pdf.max(d_pdf);
                pairs += 1;
                if d_eval >= 2e-3 || d_pdf >= 2e-3 {
                    failures.push(format!(
                        "{bsdf} wo {wo} wi {wi}: lumis {f} pdf {pdf}, Mitsuba {f_mi} pdf {pdf_mi}"
                    ));
                }
            }
        }
    }
    eprintln!(
        "{pairs} pairs; largest relative differences from Mitsuba: eval {worst_eval:.2e}, pdf \
         {worst_pdf:.2e}"
    );
    assert!(pairs > 6000);
    assert!(
        failures.is_empty(),
        "{} of {pairs} pairs differ:\n{}",
        failures.len(),
        failures[..failures.len().min(30)].join("\n")
    );
}

/// The shared material checks (seed 9300) on principled BSDFs that exercise each lobe, with the
/// energy bound each case states: 1 where the model conserves energy, more where Burley's model
/// does not by design: its fake subsurface and clearcoat are added on top of the base (the
/// flatness case reflects 1.081 of the light at 85°), and its diffuse lobe is not reduced by the
/// Fresnel reflection beside it (the mostly transmitting case scatters 1.010 of its nearly white
/// base at normal incidence); Mitsuba's values above confirm the terms.
#[test]
fn shared_checks() {
    let colour = Vec3::new(0.8, 0.5, 0.2);
    let cases = [
        Principled::default(),
        Principled {
            base_color: colour,
            metallic: 1.0,
            roughness: 0.3,
            ..Principled::default()
        },
        Principled {
            base_color: colour,
            roughness: 0.4,
            anisotropic: 0.7,
            metallic: 0.4,
            spec_tint: 0.6,
            ..Principled::default()
        },
        Principled {
            base_color: colour,
            clearcoat: 0.5,
            clearcoat_gloss: 0.5,
            flatness: 0.5,
            roughness: 0.6,
            rates: SamplingRates {
                specular: 0.5,
                clearcoat: 3.0,
                diffuse: 2.0,
            },
            ..Principled::default()
        },
        Principled {
            base_color: Vec3::new(0.9, 0.95, 1.0),
            spec_trans: 0.8,
            eta: 1.5,
            roughness: 0.3,
            transmission: true,
            ..Principled::default()
        },
        Principled {
            base_color: Vec3::new(0.2, 0.6, 0.9),
            spec_trans: 1.0,
            eta: 1.33,
            roughness: 0.5,
            transmission: true,
            ..Principled::default()
        },
    ];
    let bounds = [1.0, 1.0, 1.0, 1.1, 1.02, 1.0];
    for (p, max_energy) in cases.into_iter().zip(bounds) {
        let reports =
            testing::check_material_with_energy(&Material::Principled(p), 9300, max_energy);
        let most = reports
            .iter()
            .map(|r| r.albedo_quad.max_element())
            .fold(0.0, f64::max);
        eprintln!("{p:?}: largest energy {most:.4}");
    }
}
