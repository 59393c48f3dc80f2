//! Tests of the camera's projections: the pinhole's orientation and projection, the thin lens
//! (its focus, its lens sampler by χ², the pinhole as its zero-aperture limit) and the
//! orthographic camera's parallel rays.

use super::*;
use crate::rng::Rng;
use crate::stats::gamma::{chi2_sf, sidak};

fn view() -> (Vec3, Vec3, Vec3) {
    (
        Vec3::new(0.0, 1.0, -4.5),
        Vec3::new(0.0, 0.35, 0.0),
        Vec3::Y,
    )
}

#[test]
fn orientation_and_projection_round_trip() {
    let c = Camera::new(
        Vec3::new(0.0, 1.0, -4.5),
        Vec3::new(0.0, 0.35, 0.0),
        Vec3::Y,
        50.0,
        256,
        128,
    );
    // the centre pixel looks at `to`
    let r = c.ray(128.0, 64.0);
    assert!((r.d - (Vec3::new(0.0, 0.35, 0.0) - c.origin).normalize()).length() < 1e-6);
    // left edge of the image is to the left: cross(forward, up) with forward≈+z, up=+y is -x
    let left = c.ray(0.0, 64.0);
    assert!(
        left.d.x > 0.0,
        "Mitsuba look_at: image x runs along cross(forward, up) = -x here"
    );
    // top row looks up
    assert!(c.ray(128.0, 0.0).d.y > r.d.y);
    let p = c.origin + c.ray(37.25, 101.5).d * 3.0;
    let (x, y) = c.project(p).unwrap();
    assert!((x - 37.25).abs() < 1e-3 && (y - 101.5).abs() < 1e-3);
}

/// Every lens ray of a film position passes through the chief ray's point at perpendicular
/// distance `focus_distance` (the plane in focus is sharp), leaves from within the aperture on
/// the lens plane, and a point off that plane spreads over a disk ∝ its defocus. Catches a focus
/// measured along the ray instead of along `forward` (tried: the off-centre film positions'
/// rays miss their point), a lens disk not perpendicular to `forward`, and a lens sample that is
/// ignored (no spread).
#[test]
fn thin_lens_focuses_its_plane() {
    let (from, to, up) = view();
    let (aperture, focus) = (0.3, 3.0);
    let c = Camera::new(from, to, up, 50.0, 256, 128).with_thin_lens(aperture, focus);
    let mut rng = Rng::new(5, 0, 0);
    for &(x, y) in &[(128.0, 64.0), (3.5, 120.25), (250.0, 2.0)] {
        let chief = c.ray(x, y);
        let t = focus / chief.d.dot(c.forward);
        let target = chief.o + chief.d * t;
        let mut spread = 0.0f32;
        for _ in 0..64 {
            let r = c.lens_ray(x, y, rng.next_2d());
            let off = r.o - c.origin;
            assert!(off.dot(c.forward).abs() < 1e-6, "origin off the lens plane");
            assert!(
                off.length() <= aperture * (1.0 + 1e-6),
                "origin outside the aperture"
            );
            let s = (target - r.o).dot(c.forward) / r.d.dot(c.forward);
            assert!(
                (r.o + r.d * s - target).length() < 1e-4 * focus,
                "({x}, {y}) blurred"
            );
            // Half-way to the plane of focus the rays spread over half the aperture's disk.
            let half =
                (0.5 * focus - r.o.dot(c.forward) + c.origin.dot(c.forward)) / r.d.dot(c.forward);
            let mid = chief.o + chief.d * (0.5 * focus / chief.d.dot(c.forward));
            spread = spread.max((r.o + r.d * half - mid).length());
        }
        assert!(
            spread > 0.3 * aperture && spread <= 0.5 * aperture * 1.001,
            "spread {spread}"
        );
    }
}

/// With a zero aperture the thin lens is the pinhole: every lens ray is the chief ray.
#[test]
fn zero_aperture_is_the_pinhole() {
    let (from, to, up) = view();
    let pin = Camera::new(from, to, up, 50.0, 64, 48);
    let lens = pin.with_thin_lens(0.0, 2.0);
    for &(x, y, u) in &[
        (10.5, 3.25, Vec2::new(0.1, 0.9)),
        (63.0, 47.0, Vec2::new(0.7, 0.2)),
    ] {
        let (a, b) = (pin.ray(x, y), lens.lens_ray(x, y, u));
        assert_eq!(a.o, b.o);
        assert!((a.d - b.d).length() < 1e-6, "{:?} vs {:?}", a.d, b.d);
    }
}

/// Pearson's χ² p-value of `n` lens origins of `camera` (film position `(x, y)`) against the
/// uniform density on the lens disk: the polar pair (r²/R², θ/2π) is uniform on [0,1]² exactly
/// when the origins are, histogrammed on a 16 × 16 grid (every cell expects n/256).
fn lens_chi2_p(camera: &Camera, lens_ray: impl Fn(Vec2) -> Ray, n: usize, seed: u32) -> f64 {
    let Projection::ThinLens {
        aperture_radius, ..
    } = camera.projection
    else {
        panic!("not a thin lens");
    };
    const CELLS: usize = 16;
    let mut counts = [0f64; CELLS * CELLS];
    let mut rng = Rng::new(seed, 0, 0);
    for _ in 0..n {
        let off = lens_ray(rng.next_2d()).o - camera.origin;
        let (a, b) = (off.dot(camera.right), off.dot(camera.up));
        let r2 = ((a * a + b * b) / (aperture_radius * aperture_radius)) as f64;
        let phi = (b as f64).atan2(a as f64).rem_euclid(std::f64::consts::TAU);
        let i = ((r2 * CELLS as f64) as usize).min(CELLS - 1);
        let j = ((phi / std::f64::consts::TAU * CELLS as f64) as usize).min(CELLS - 1);
        counts[j * CELLS + i] += 1.0;
    }
    let e = n as f64 / (CELLS * CELLS) as f64;
    let stat: f64 = counts.iter().map(|o| (o - e).powi(2) / e).sum();
    chi2_sf(stat, (CELLS * CELLS - 1) as f64)
}

/// The thin lens's ray origins are uniform on its disk (Pearson χ², 256 cells, 200,000 rays at
/// three film positions; significance: family-wise α = 0.01 over the 3 cases, Šidák-corrected;
/// seeds 2100–2102). Power (the next test): a lens whose radius is the uniform's r instead of
/// √r, or whose disk is a square's, is rejected with p < 1e-9. With 781 rays expected per cell,
/// a density error of about 7% over one ring of 16 cells (1/16 of the lens area) is detected.
#[test]
fn thin_lens_origins_are_uniform_on_the_lens() {
    let (from, to, up) = view();
    let c = Camera::new(from, to, up, 40.0, 96, 64).with_thin_lens(0.25, 4.0);
    let alpha = sidak(0.01, 3);
    for (k, &(x, y)) in [(48.0, 32.0), (0.5, 0.5), (95.0, 10.0)].iter().enumerate() {
        let p = lens_chi2_p(&c, |u| c.lens_ray(x, y, u), 200_000, 2100 + k as u32);
        assert!(p >= alpha, "({x}, {y}): χ² p = {p:.3e} < {alpha:.2e}");
    }
}

/// Controls of the lens χ²: concentrated towards the centre (radius ∝ u instead of √u) and a
/// square aperture are rejected.
#[test]
fn lens_chi_square_rejects_wrong_lenses() {
    let (from, to, up) = view();
    let c = Camera::new(from, to, up, 40.0, 96, 64).with_thin_lens(0.25, 4.0);
    let on_lens = |p: Vec2| {
        let o = c.origin + 0.25 * (p.x * c.right + p.y * c.up);
        Ray::new(o, c.forward)
    };
    let centred = |u: Vec2| {
        let (r, t) = (u.x, std::f32::consts::TAU * u.y);
        on_lens(r * Vec2::new(t.cos(), t.sin()))
    };
    let p = lens_chi2_p(&c, centred, 200_000, 2110);
    assert!(p < 1e-9, "radius ∝ u not rejected: p = {p:.3e}");
    let square = |u: Vec2| on_lens((2.0 * u - Vec2::ONE) * std::f32::consts::FRAC_1_SQRT_2);
    let p = lens_chi2_p(&c, square, 200_000, 2111);
    assert!(p < 1e-9, "a square lens not rejected: p = {p:.3e}");
}

/// The orthographic camera's rays are parallel to `forward`, start on the film plane through
/// `from`, span `view_width × view_height` across the film, and project back to their film
/// position. Catches half-extents taken as full ones and a film axis flipped.
#[test]
fn orthographic_rays_are_parallel_and_span_the_view() {
    let (from, to, up) = view();
    let c = Camera::orthographic(from, to, up, 4.0, 2.0, 200, 100);
    let (forward, right, up, _, _) = c.basis();
    let corner = c.ray(0.0, 0.0);
    let opposite = c.ray(200.0, 100.0);
    assert_eq!(corner.d, forward);
    let span = opposite.o - corner.o;
    assert!((span.dot(right) - 4.0).abs() < 1e-5 && (span.dot(up) + 2.0).abs() < 1e-5);
    assert!((corner.o - from).dot(forward).abs() < 1e-6);
    let p = c.ray(37.25, 81.5).o + forward * 7.0;
    let (x, y) = c.project(p).unwrap();
    assert!(
        (x - 37.25).abs() < 1e-3 && (y - 81.5).abs() < 1e-3,
        "{x}, {y}"
    );
    assert!(c.project(from - forward).is_none(), "behind the film");
}

/// `sample_ray` draws the lens only for a thin lens: a pinhole's and an orthographic camera's
/// samplers are left where the film position left them (so their images keep their bits), a
/// thin lens's advance by the lens's two numbers.
#[test]
fn only_the_thin_lens_draws_the_lens() {
    let (from, to, up) = view();
    let pin = Camera::new(from, to, up, 50.0, 64, 48);
    let ortho = Camera::orthographic(from, to, up, 2.0, 1.5, 64, 48);
    let lens = pin.with_thin_lens(0.2, 3.0);
    let next = |c: &Camera| {
        let mut s = Sampler::from(Rng::new(9, 4, 2));
        c.sample_ray(&mut s, 5, 6);
        s.get_1d(0)
    };
    let fresh = {
        let mut s = Sampler::from(Rng::new(9, 4, 2));
        s.camera_2d();
        s.get_1d(0)
    };
    assert_eq!(next(&pin), fresh);
    assert_eq!(next(&ortho), fresh);
    assert_ne!(next(&lens), fresh);
}

/// A principal point offset `(ox, oy)` makes the film position `(x, y)` see what the centred
/// camera sees at `(x + ox·width, y + oy·height)`, for every projection, and `project` inverts
/// it. Catches the offset applied with the wrong sign or in the wrong unit (pixels for film
/// fractions).
#[test]
fn principal_point_offset_shifts_the_film() {
    let (from, to, up) = view();
    for centred in [
        Camera::new(from, to, up, 50.0, 64, 48),
        Camera::new(from, to, up, 50.0, 64, 48).with_thin_lens(0.2, 3.0),
        Camera::orthographic(from, to, up, 2.0, 1.5, 64, 48),
    ] {
        let shifted = centred.with_principal_point_offset(0.25, -0.125);
        let (a, b) = (
            shifted.ray(10.5, 20.25),
            centred.ray(10.5 + 16.0, 20.25 - 6.0),
        );
        assert!((a.o - b.o).length() < 1e-5 && (a.d - b.d).length() < 1e-6);
        let u = Vec2::new(0.3, 0.8);
        let (a, b) = (
            shifted.lens_ray(3.0, 7.0, u),
            centred.lens_ray(19.0, 1.0, u),
        );
        assert!((a.o - b.o).length() < 1e-5 && (a.d - b.d).length() < 1e-6);
        let (x, y) = shifted.project(a.o + a.d * 4.0).unwrap();
        if centred.projection
            != (Projection::ThinLens {
                aperture_radius: 0.2,
                focus_distance: 3.0,
            })
        {
            assert!((x - 3.0).abs() < 1e-3 && (y - 7.0).abs() < 1e-3, "{x}, {y}");
        }
    }
}
