//! Tests of the environment map: Mitsuba's lookup conventions, rotation, and the sampler's
//! density, consistency and inverse. The χ² tests of the sampler are in the statistical suite
//! (`stats::suite::envmap_cases`).

use super::*;
use crate::rng::Rng;

/// A map whose texel (i, j) holds (i, j, 1 + i + W·j): every lookup says where it read.
fn index_map(w: usize, h: usize) -> Vec<Vec3> {
    (0..h)
        .flat_map(|j| (0..w).map(move |i| Vec3::new(i as f32, j as f32, 1.0 + (i + w * j) as f32)))
        .collect()
}

fn light(w: usize, h: usize, texels: &[Vec3], rotate: f32) -> EnvmapLight {
    EnvmapLight::new(
        w,
        h,
        texels,
        1.0,
        EnvmapLight::rotation_matrix(rotate, None),
        1.0,
    )
    .unwrap()
}

/// World direction of map coordinates `(u, v)` (no rotation).
fn direction(u: f32, v: f32) -> Vec3 {
    let (phi, theta) = (TAU * u, PI * v);
    Vec3::new(
        theta.sin() * phi.sin(),
        theta.cos(),
        -theta.sin() * phi.cos(),
    )
}

fn close(a: Vec3, b: Vec3, tol: f32) -> bool {
    (a - b).abs().max_element() <= tol * b.abs().max_element().max(1.0)
}

/// Texel centres sit at u = (i + ½)/W and v = j/(H − 1) (Mitsuba 3.9.1's `envmap`): looking there
/// reads the texel alone; −z is u = 0, +x is u = ¼, +y the top row.
#[test]
fn texel_centres_follow_mitsubas_layout() {
    let (w, h) = (8, 5);
    let texels = index_map(w, h);
    let map = light(w, h, &texels, 0.0);
    // Rows 0 and H−1 lie on the poles, where u is undefined: checked below.
    for j in 1..h - 1 {
        for i in 0..w {
            let d = direction((i as f32 + 0.5) / w as f32, j as f32 / (h - 1) as f32);
            let got = map.eval(d);
            assert!(close(got, texels[j * w + i], 1e-4), "({i}, {j}): {got}");
        }
    }
    // Half-way between the last and the first column: the lookup wraps around.
    let seam = map.eval(direction(0.0, 0.5));
    let expected = 0.5 * (texels[2 * w + w - 1] + texels[2 * w]);
    assert!(close(seam, expected, 1e-4), "{seam} vs {expected}");
    // The poles read the first and last rows, interpolated in u only.
    assert_eq!(map.eval(Vec3::Y).y, 0.0);
    assert_eq!(map.eval(-Vec3::Y).y, (h - 1) as f32);
    assert!(close(
        map.eval(Vec3::X),
        map.eval(direction(0.25, 0.5)),
        1e-5
    ));
}

/// `rotate_y_deg` turns the map with the world: the rotated map seen along R·d is the unrotated
/// one seen along d, R the box's rotation about +y.
#[test]
fn rotation_turns_the_map_like_a_box() {
    let (w, h) = (16, 9);
    let texels = index_map(w, h);
    let plain = light(w, h, &texels, 0.0);
    let angle = 30.0f32;
    let turned = light(w, h, &texels, angle);
    let (s, c) = angle.to_radians().sin_cos();
    let mut rng = Rng::new(11, 0, 0);
    for _ in 0..1000 {
        let d = sample_uniform_sphere(rng.next_2d());
        let rd = Vec3::new(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);
        assert!(close(turned.eval(rd), plain.eval(d), 1e-3), "{d}");
    }
}

/// Any rotation (`rotation`, then `rotate_y_deg`) turns the map with the world: seen along R·d it
/// is the unturned map seen along d, and sampling, the pdf and the inverse agree under it.
#[test]
fn any_rotation_turns_the_map_and_its_sampler() {
    let (w, h) = (16, 9);
    let texels = index_map(w, h);
    let plain = light(w, h, &texels, 0.0);
    let tilt = crate::stats::suite::envmap_tilt();
    let r = EnvmapLight::rotation_matrix(20.0, Some(tilt));
    let want = (glam::DMat3::from_rotation_y(20f64.to_radians()) * tilt).as_mat3();
    assert!((r - want).abs_diff_eq(Mat3::ZERO, 1e-6), "{r} vs {want}");
    let turned = EnvmapLight::new(w, h, &texels, 1.0, r, 1.0).unwrap();
    let mut rng = Rng::new(14, 0, 0);
    for _ in 0..1000 {
        let d = sample_uniform_sphere(rng.next_2d());
        assert!(close(turned.eval(r * d), plain.eval(d), 1e-3), "{d}");
        let (wi, pdf) = turned.sample_importance(rng.next_2d());
        assert!(
            (turned.pdf_importance(wi) - pdf).abs() <= 1e-3 * pdf,
            "{wi}"
        );
        // The turned map's density at R·d is the plain one's at d.
        let (pd, pp) = (turned.pdf_importance(r * d), plain.pdf_importance(d));
        assert!((pd - pp).abs() <= 1e-3 * pp.max(1e-3), "{d}: {pd} vs {pp}");
    }
}

/// The suite's maps: constant, sun-like peak, black rows and columns, one and two texels.
fn test_maps() -> Vec<crate::stats::suite::TestMap> {
    crate::stats::suite::envmap_maps()
}

/// Every sample's pdf is `pdf(wi)`, `invert` undoes the sample, and radiance is never where the
/// density is zero (the distribution covers the bilinear lookup's support).
#[test]
fn samples_agree_with_pdf_and_inverse() {
    for (name, w, h, texels) in test_maps() {
        for rotate in [0.0, 75.0] {
            let map = light(w, h, &texels, rotate);
            let mut rng = Rng::new(12, w as u32, h as u32);
            for _ in 0..4000 {
                let u = rng.next_2d();
                let (wi, pdf) = map.sample_importance(u);
                assert!((wi.length() - 1.0).abs() < 1e-5, "{name}");
                let again = map.pdf_importance(wi);
                assert!(
                    (again - pdf).abs() <= 1e-3 * pdf,
                    "{name}: pdf {pdf} vs {again} at {wi}"
                );
                let back = map.invert_importance(wi).unwrap();
                // Cell edges can round into the neighbour cell; compare the directions instead.
                let (wi2, _) = map.sample_importance(back);
                assert!(
                    (wi2 - wi).length() < 1e-3,
                    "{name}: {u} -> {wi} -> {back} -> {wi2}"
                );
                let d = sample_uniform_sphere(rng.next_2d());
                if map.eval(d).max_element() > 0.0 {
                    assert!(
                        map.pdf_importance(d) > 0.0,
                        "{name}: radiance without density at {d}"
                    );
                }
            }
        }
    }
}

/// The density integrates to 1 over the sphere: the mean of pdf/(1/4π) over 2e5 uniform
/// directions is 1 within 5 standard errors (seed 13).
#[test]
fn pdf_integrates_to_one() {
    for (name, w, h, texels) in test_maps() {
        let map = light(w, h, &texels, 20.0);
        let mut rng = Rng::new(13, 0, 0);
        let n = 200_000;
        let (mut sum, mut sum2) = (0.0f64, 0.0f64);
        for _ in 0..n {
            let x = (map.pdf_importance(sample_uniform_sphere(rng.next_2d()))
                / uniform_sphere_pdf()) as f64;
            sum += x;
            sum2 += x * x;
        }
        let mean = sum / n as f64;
        let se = ((sum2 / n as f64 - mean * mean) / n as f64).sqrt();
        assert!(
            (mean - 1.0).abs() < 5.0 * se + 1e-6,
            "{name}: {mean} ± {se}"
        );
    }
}

/// A constant map is sampled uniformly (its density is 1/4π everywhere, within rounding), and its
/// power is that of the constant background of the same radiance.
#[test]
fn constant_map_is_uniform_and_has_the_backgrounds_power() {
    let le = Vec3::new(0.3, 0.6, 0.9);
    for (w, h) in [(1, 1), (2, 1), (7, 3), (64, 32)] {
        let map = EnvmapLight::new(
            w,
            h,
            &vec![le; w * h],
            2.0,
            EnvmapLight::rotation_matrix(40.0, None),
            3.0,
        )
        .unwrap();
        let mut rng = Rng::new(14, 0, 0);
        for _ in 0..2000 {
            let d = sample_uniform_sphere(rng.next_2d());
            let pdf = map.pdf_importance(d);
            assert!((pdf * 4.0 * PI - 1.0).abs() < 1e-4, "{w}x{h}: {pdf}");
            assert!(close(map.eval(d), 2.0 * le, 1e-6));
        }
        let background = super::super::BackgroundLight {
            le: 2.0 * le,
            scene_radius: 3.0,
        };
        assert!((map.power() / background.power() - 1.0).abs() < 1e-5);
    }
}

/// A map of zeros is no light.
#[test]
fn black_map_is_no_light() {
    assert!(EnvmapLight::new(3, 2, &[Vec3::ZERO; 6], 1.0, glam::Mat3::IDENTITY, 1.0).is_none());
    assert!(EnvmapLight::new(3, 2, &[Vec3::ONE; 6], 0.0, glam::Mat3::IDENTITY, 1.0).is_none());
}
