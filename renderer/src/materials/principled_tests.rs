//! Tests of Mitsuba's principled BSDF: against Mitsuba 3.9.1's own eval and pdf, the shared
//! material checks (sampling against eval and pdf, ∫pdf, reciprocity, grazing angles, energy by
//! sampling, quadrature and uniform sampling) and its constants.

use super::*;
use crate::materials::{Material, testing};
use serde_json::Value;
use testing::json_vec3 as vec3;

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

/// lumis' eval and pdf against Mitsuba's (variant llvm_ad_rgb, `tools/mitsuba_principled_values.py`)
/// at 6723 direction pairs of 18 principled BSDFs covering every parameter, both sides and
/// transmission ([`testing::assert_matches_mitsuba_values`]). Tolerance 2e-3 relative on eval and
/// pdf (f32 arithmetic in a different order:
/// Mitsuba's own scalar and JIT variants differ by up to 4.4e-4 on these pairs, as the tool's
/// author measured); the floor is 1e-4 of the case's largest value. Power: the sheen evaluated
/// only where the diffuse lobe is on (Mitsuba's scalar variant) differs by 3.3% at the tool's
/// case 14; a clearcoat without its 0.25 weight, a metal F0 of 0.04, a transmission without
/// √base all move values by far more.
#[test]
fn values_match_mitsuba() {
    testing::assert_matches_mitsuba_values("mitsuba_principled_values.json", 6000, 2e-3, |c| {
        Material::Principled(principled_of(c))
    });
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
