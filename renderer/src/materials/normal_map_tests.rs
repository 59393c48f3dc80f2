use super::*;
use crate::materials::{Diffuse, Distribution, Microfacet, Plastic};
use crate::rng::Rng;
use crate::sampling::sample_uniform_sphere;

fn map(flip: bool, shadowing: bool) -> NormalMap {
    NormalMap {
        texture: Texture::Constant(Vec3::new(0.5, 0.5, 1.0)),
        flip_invalid_normals: flip,
        shadowing,
        height_scale: None,
    }
}

/// A tilted frame with first axis along a tangent that is not one of the world's.
fn base() -> Frame {
    let n = Vec3::new(0.3, -0.5, 0.8).normalize();
    crate::geometry::tangent::tangent_frame(n, Vec3::new(1.0, 2.0, 0.5))
}

/// What [`NormalMap::perturb`] gets from the texel that encodes local normal `n` (unit or not).
fn texel(n: Vec3) -> Vec3 {
    NormalMap::decode((n + Vec3::ONE) * 0.5)
}

fn assert_orthonormal(f: &Frame) {
    for (a, b) in [(f.s, f.t), (f.t, f.n), (f.n, f.s)] {
        assert!(a.dot(b).abs() < 1e-6, "{f:?}");
    }
    for v in [f.s, f.t, f.n] {
        assert!((v.length() - 1.0).abs() < 1e-6, "{f:?}");
    }
    assert!(f.s.cross(f.t).dot(f.n) > 0.999, "right-handed: {f:?}");
}

#[test]
fn a_texel_along_the_normal_changes_nothing() {
    // (½, ½, z) for any z > ½ encodes the unperturbed normal: no frame is even asked for.
    for z in [0.51, 0.75, 1.0] {
        let got = map(true, true).perturb(
            NormalMap::decode(Vec3::new(0.5, 0.5, z)),
            || panic!("no frame needed"),
            Vec3::Z,
        );
        assert!(got.is_none());
    }
}

#[test]
fn the_perturbed_frame_is_mitsubas() {
    let b = base();
    let n_local = Vec3::new(0.4, 0.2, 0.7);
    let wo_world = b.n; // seen from above: no flip
    let (f, _) = map(true, true)
        .perturb(texel(n_local), || b, wo_world)
        .unwrap();
    assert_orthonormal(&f);
    // Its normal is the decoded one, in the base frame.
    let n = b.to_world(n_local.normalize());
    assert!((f.n - n).length() < 1e-6, "{:?} vs {n:?}", f.n);
    // Its first axis is the base's first axis made orthogonal to it (Gram–Schmidt).
    let s = (b.s - n * n.dot(b.s)).normalize();
    assert!((f.s - s).length() < 1e-6, "{:?} vs {s:?}", f.s);
}

#[test]
fn a_normal_facing_away_from_the_viewer_is_mirrored_about_the_unperturbed_one() {
    let b = base();
    let n_local = Vec3::new(0.8, 0.0, 0.3);
    // A viewer tilted the other way, on the far side of the perturbed normal.
    let wo_local = Vec3::new(-0.9, 0.0, 0.2).normalize();
    assert!(wo_local.dot(n_local) < 0.0);
    let wo = b.to_world(wo_local);
    let (flipped, _) = map(true, true).perturb(texel(n_local), || b, wo).unwrap();
    let mirrored = Vec3::new(-n_local.x, -n_local.y, n_local.z).normalize();
    assert!((flipped.n - b.to_world(mirrored)).length() < 1e-6);
    assert!(flipped.n.dot(wo) > 0.0, "the surface now faces the viewer");
    // Without the flip the normal stays as the map says.
    let (kept, _) = map(false, true).perturb(texel(n_local), || b, wo).unwrap();
    assert!((kept.n - b.to_world(n_local.normalize())).length() < 1e-6);
    // A viewer on the normal's side sees no flip.
    let (same, _) = map(true, true).perturb(texel(n_local), || b, b.n).unwrap();
    assert!((same.n - kept.n).length() < 1e-6);
}

#[test]
fn undefined_texels_give_no_nan() {
    let b = base();
    // Length 0: the unperturbed normal is kept.
    assert!(
        map(true, true)
            .perturb(NormalMap::decode(Vec3::splat(0.5)), || b, b.n)
            .is_none()
    );
    // Along the first axis: any tangent.
    for n in [Vec3::X, -Vec3::X] {
        let (f, p) = map(false, true).perturb(texel(n), || b, b.n).unwrap();
        assert_orthonormal(&f);
        assert!((f.n - b.to_world(n)).length() < 1e-6);
        assert!(p.factor(Vec3::Z).is_finite());
    }
}

/// The shadowing term from the angles measured in the world, as normalmap_helpers.h states it.
fn shadowing_in_world(b: &Frame, n_world: Vec3, wi_world: Vec3) -> f32 {
    let tan2 = |c: f32| (1.0 - c * c) / (c * c);
    let alpha2 = (0.125 * tan2(n_world.dot(b.n))).min(1.0);
    2.0 / (1.0 + (1.0 + alpha2 * tan2(wi_world.dot(b.n))).sqrt())
}

#[test]
fn the_factor_is_the_side_rule_times_the_shadowing_term() {
    let b = base();
    let n_local = Vec3::new(0.3, -0.6, 0.5);
    let (f, p) = map(true, true).perturb(texel(n_local), || b, b.n).unwrap();
    let (_, plain) = map(true, false).perturb(texel(n_local), || b, b.n).unwrap();
    let mut rng = Rng::new(2445, 0, 0);
    let (mut zero, mut some) = (0, 0);
    for _ in 0..20_000 {
        let wi_world = sample_uniform_sphere(rng.next_2d());
        let wi = f.to_local(wi_world);
        let same_side = wi.z * wi_world.dot(b.n) > 0.0;
        let k = p.factor(wi);
        if !same_side {
            assert_eq!((k, plain.factor(wi)), (0.0, 0.0), "wi {wi_world:?}");
            zero += 1;
            continue;
        }
        some += 1;
        assert_eq!(plain.factor(wi), 1.0);
        let want = shadowing_in_world(&b, f.n, wi_world);
        assert!((k - want).abs() < 1e-4, "{k} vs {want} at {wi_world:?}");
        assert!(k > 0.0 && k <= 1.0);
    }
    // Both branches ran (the tilt is ~50°: a large wedge of disagreeing sides).
    assert!(zero > 1000 && some > 1000, "{zero} {some}");
    // At the unperturbed normal the term is 1: tan θ = 0.
    assert!((p.factor(f.to_local(b.n)) - 1.0).abs() < 1e-6);
}

#[test]
fn the_vertex_bsdf_keeps_sample_eval_and_pdf_consistent() {
    let materials = [
        Material::Diffuse(Diffuse {
            albedo: Vec3::new(0.8, 0.5, 0.2),
        }),
        Material::Plastic(Plastic::new(Vec3::splat(0.5), 0.3, 1.5, Vec3::ONE)),
        Material::Conductor(crate::materials::Conductor {
            microfacet: Microfacet::new(Distribution::Ggx, 0.2, 0.2),
            fresnel: crate::materials::ConductorFresnel::Tint(Vec3::splat(0.9)),
        }),
    ];
    let b = base();
    let n_local = Vec3::new(0.5, 0.3, 0.6);
    let (f, p) = map(true, true).perturb(texel(n_local), || b, b.n).unwrap();
    let mut rng = Rng::new(2446, 0, 0);
    for m in &materials {
        let bsdf = VertexBsdf {
            material: m,
            perturbation: Some(p),
        };
        let (mut kept, mut dropped) = (0, 0);
        for _ in 0..4000 {
            let wo_world = sample_uniform_sphere(rng.next_2d());
            let wo = f.to_local(wo_world);
            if wo.z <= 0.0 {
                continue;
            }
            let (u_lobe, u) = (rng.next_f32(), rng.next_2d());
            let Some(plain) = m.sample(wo, u_lobe, u) else {
                continue;
            };
            match bsdf.sample::<true>(wo, u_lobe, u) {
                None => {
                    assert_eq!(p.factor(plain.wi), 0.0);
                    assert_eq!(bsdf.pdf::<true>(wo, plain.wi), 0.0);
                    assert_eq!(bsdf.eval::<true>(wo, plain.wi), Vec3::ZERO);
                    dropped += 1;
                }
                Some(s) => {
                    kept += 1;
                    assert_eq!(s.wi, plain.wi);
                    assert_eq!(s.pdf, bsdf.pdf::<true>(wo, s.wi));
                    let k = p.factor(s.wi);
                    assert!((s.weight - plain.weight * k).abs().max_element() < 1e-6);
                    let ratio = bsdf.eval::<true>(wo, s.wi) / s.pdf;
                    assert!(
                        (ratio - s.weight).abs().max_element() <= 1e-4 * s.weight.max_element(),
                        "{m:?}: eval/pdf {ratio:?} vs weight {:?}",
                        s.weight
                    );
                }
            }
        }
        assert!(
            kept > 1000 && dropped > 10,
            "{m:?}: {kept} kept, {dropped} dropped"
        );
    }
}

#[test]
fn without_a_perturbation_the_vertex_bsdf_is_the_material() {
    let m = Material::Plastic(Plastic::new(Vec3::splat(0.4), 0.2, 1.5, Vec3::ONE));
    let bsdf = VertexBsdf {
        material: &m,
        perturbation: None,
    };
    let mut rng = Rng::new(2447, 0, 0);
    for _ in 0..1000 {
        let wo = sample_uniform_sphere(rng.next_2d());
        let wi = sample_uniform_sphere(rng.next_2d());
        assert_eq!(bsdf.eval::<true>(wo, wi), m.eval(wo, wi));
        assert_eq!(bsdf.pdf::<true>(wo, wi), m.pdf(wo, wi));
        let (ul, u) = (rng.next_f32(), rng.next_2d());
        assert_eq!(bsdf.sample::<true>(wo, ul, u), m.sample(wo, ul, u));
    }
}
