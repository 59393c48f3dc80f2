use super::*;
use crate::rng::Rng;
use glam::DVec3;

/// Views of a disk as `(height of p above the plane, offset of p's foot from the centre,
/// radius)` with a label: the receiver's distance sets the scale, so these cover near, far,
/// grazing, edge-on, straight above the centre and the rim, and just outside the rim.
const VIEWS: [(&str, f64, f64, f64); 13] = [
    ("on axis", 1.0, 0.0, 1.0),
    ("near, offset", 1.0, 0.5, 0.3),
    ("near, 30° off", 1.299, 0.75, 1.0),
    ("far (Ω 0.027)", 8.66, 5.0, 1.0),
    ("grazing 85°", 0.174_3, 1.992_4, 1.0),
    (
        "edge-on, 89° off at 1.5 (Ω 0.047)",
        0.026_178,
        1.499_772,
        1.0,
    ),
    ("close over the centre (Ω 5.97)", 0.05, 0.0, 1.0),
    ("close over the rim", 0.05, 1.0, 1.0),
    ("close beside the rim", 0.02, 1.2, 1.0),
    ("above, far outside", 0.5, 3.0, 1.0),
    ("over the disk, near its rim", 0.2, 0.9, 1.0),
    ("1e-4 over the rim (b 100)", 1e-4, 1.0, 1.0),
    ("2e-4 over the disk by its rim (b 90)", 2e-4, 0.999_9, 1.0),
];

/// A disk of view `(h, cx, r)` in a random frame, position and scale (1e-3…1e3): (p, centre,
/// normal, radius).
fn placed(h: f64, cx: f64, r: f64, rng: &mut Rng) -> (Vec3, Vec3, Vec3, f32) {
    let n = crate::sampling::sample_uniform_sphere(rng.next_2d()).as_dvec3();
    let f = Frame::from_normal(n.as_vec3());
    let angle = std::f64::consts::TAU * rng.next_f32() as f64;
    let e = f.s.as_dvec3() * angle.cos() + f.t.as_dvec3() * angle.sin();
    let scale = 10f64.powf(-3.0 + 6.0 * rng.next_f32() as f64);
    let foot = DVec3::new(3.0, -2.0, 1.0) * scale;
    let p = foot + n * h * scale;
    let c = foot + e * cx * scale;
    (p.as_vec3(), c.as_vec3(), n.as_vec3(), (r * scale) as f32)
}

/// `1 − h/√(h² + ρ²)` without cancellation.
fn versine(h: f64, rho: f64) -> f64 {
    let l = (h * h + rho * rho).sqrt();
    rho * rho / (l * (l + h))
}

/// The solid angle of the disk of view `(h, cx, r)`, independently of the ellipse: by azimuth
/// about p's foot on the plane, each ray of the plane from the foot crossing the disk between
/// distances ρ₁ and ρ₂ contributes `h/√(h² + ρ₁²) − h/√(h² + ρ₂²)` (f64, composite Simpson,
/// with `φ = φ_m sin τ` where the foot is outside, so the square-root ends at the tangents are
/// smooth).
fn quadrature_solid_angle(h: f64, cx: f64, r: f64) -> f64 {
    let n = 200_000;
    let simpson = |f: &dyn Fn(f64) -> f64, lo: f64, hi: f64| {
        let step = (hi - lo) / n as f64;
        let mut sum = f(lo) + f(hi);
        for i in 1..n {
            sum += f(lo + i as f64 * step) * if i % 2 == 1 { 4.0 } else { 2.0 };
        }
        sum * step / 3.0
    };
    if cx < r {
        let f = |phi: f64| {
            let (s, c) = phi.sin_cos();
            versine(h, cx * c + (r * r - cx * cx * s * s).sqrt())
        };
        simpson(&f, 0.0, std::f64::consts::TAU)
    } else {
        let phi_m = (r / cx).asin();
        let f = |tau: f64| {
            let phi = phi_m * tau.sin();
            let (s, c) = phi.sin_cos();
            let root = (r * r - cx * cx * s * s).max(0.0).sqrt();
            (versine(h, cx * c + root) - versine(h, cx * c - root)) * phi_m * tau.cos()
        };
        let half = std::f64::consts::FRAC_PI_2;
        simpson(&f, -half, half)
    }
}

/// The view `(h, cx, r)` of the placed disk `(p, c, n, r)` in f64, and how far f32 arithmetic on
/// those inputs may move `h` and `cx`: `h = −(c − p)·n` and the offset are rounded to a few ulp of
/// the coordinates, which matters for views 1e-4 above the plane, where Ω depends steeply on
/// both (the renderer cannot know the geometry better either).
fn view_of(p: Vec3, c: Vec3, n: Vec3, r: f32) -> ((f64, f64, f64), f64) {
    let (v, n) = (c.as_dvec3() - p.as_dvec3(), n.as_dvec3().normalize());
    let h = -v.dot(n);
    let slack = 4.0 * f32::EPSILON as f64 * (p.length() + c.length()) as f64;
    ((h, (v + h * n).length(), r as f64), slack)
}

/// Ω against the independent quadrature, in random frames and at random scales (4 per view;
/// about 1 s of CPU). Measured: at most 8.7e-7 absolute (4.3e-6 over an earlier run of 8 per
/// view; from Ω 0.027 to 5.97; the f32 cancellation in `π/2 − G` is a few
/// 1e-7 per quadrant, so about 1e-6/Ω relative: 1e-4 at `MIN_ELLIPSE_SOLID_ANGLE`), beyond the
/// spread of the quadrature over the inputs' own rounding (which reaches 1e-3 at 1e-4 above
/// the rim).
#[test]
fn solid_angle_matches_quadrature() {
    let mut rng = Rng::new(300, 0, 0);
    let mut worst = 0.0f64;
    for (name, h, cx, r) in VIEWS {
        for _ in 0..4 {
            let (p, c, n, radius) = placed(h, cx, r, &mut rng);
            let e = SphericalEllipse::new(p, c, n, radius).unwrap_or_else(|| panic!("{name}"));
            let ((h, cx, r), slack) = view_of(p, c, n, radius);
            let band = [
                (0.0, 0.0),
                (-1.0, -1.0),
                (-1.0, 1.0),
                (1.0, -1.0),
                (1.0, 1.0),
            ]
            .map(|(dh, dc)| quadrature_solid_angle(h + dh * slack, cx + dc * slack, r));
            let lo = band.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = band.iter().copied().fold(0.0, f64::max);
            let omega = e.solid_angle() as f64;
            let err = (lo - omega).max(omega - hi).max(0.0);
            worst = worst.max(err);
            assert!(err < 1e-5, "{name}: Ω {omega} vs [{lo}, {hi}]");
            assert!((e.pdf() as f64 * omega - 1.0).abs() < 1e-6);
        }
    }
    eprintln!("worst absolute error of Ω: {worst:.2e}");
}

/// The map is area-preserving: the finite-difference Jacobian `|∂w/∂u₀ × ∂w/∂u₁|` equals Ω
/// everywhere (away from the quadrant seams and the pole, where differences straddle a kink or
/// divide by sin θ). A wrong `G` or `F'` would bend the azimuth's CDF and show here even where
/// Ω is right. Measured: within 2e-3 (the f32 directions' rounding over the 2e-3 differences).
#[test]
fn map_preserves_area() {
    let mut rng = Rng::new(301, 0, 0);
    for (name, h, cx, r) in VIEWS {
        let (p, c, n, radius) = placed(h, cx, r, &mut rng);
        let e = SphericalEllipse::new(p, c, n, radius).unwrap();
        let omega = e.solid_angle() as f64;
        let w = |u: Vec2| e.sample(u).as_dvec3();
        let step = 5e-3f32;
        let mut worst = 0.0f64;
        for _ in 0..2000 {
            let u = Vec2::new(rng.next_f32(), 0.1 + 0.8 * rng.next_f32());
            let seam = (4.0 * u.x).fract();
            if !(0.05..0.95).contains(&seam) {
                continue;
            }
            let dx = (w(u + Vec2::X * step) - w(u - Vec2::X * step)) / (2.0 * step as f64);
            let dy = (w(u + Vec2::Y * step) - w(u - Vec2::Y * step)) / (2.0 * step as f64);
            let jacobian = dx.cross(dy).length();
            worst = worst.max((jacobian / omega - 1.0).abs());
        }
        eprintln!("{name}: Ω {omega:.4}, worst Jacobian error {worst:.1e}");
        assert!(worst < 1e-2, "{name}: {worst}");
    }
}

/// Every sampled direction meets the disk (up to rounding of the direction), and sampling then
/// inverting returns `u`; inverting then sampling returns the direction.
#[test]
fn samples_hit_the_disk_and_round_trip() {
    let mut rng = Rng::new(302, 0, 0);
    for (name, h, cx, r) in VIEWS {
        let (p, c, n, radius) = placed(h, cx, r, &mut rng);
        let e = SphericalEllipse::new(p, c, n, radius).unwrap();
        let (pd, cd, nd) = (p.as_dvec3(), c.as_dvec3(), n.as_dvec3());
        let (mut du, mut dw, mut outside) = (0.0f32, 0.0f32, 0.0f64);
        for _ in 0..20_000 {
            let u = rng.next_2d();
            let w = e.sample(u);
            assert!((w.length() - 1.0).abs() < 1e-5, "{name}: {w}");
            let wd = w.as_dvec3();
            let t = (cd - pd).dot(nd) / wd.dot(nd);
            assert!(t > 0.0, "{name}: behind");
            let rho = ((pd + t * wd - cd).length() / radius as f64 - 1.0).max(0.0);
            outside = outside.max(rho);
            du = du.max((e.invert(w) - u).abs().max_element());
            dw = dw.max((e.sample(e.invert(w)) - w).length());
        }
        eprintln!("{name}: outside by {outside:.1e} radii, du {du:.1e}, dw {dw:.1e}");
        assert!(outside < 1e-4, "{name}: a sample misses by {outside} radii");
        assert!(du < 2e-4 && dw < 2e-4, "{name}: du {du}, dw {dw}");
    }
}

/// Refused: p behind the disk or in its plane, tiny and nearly-hemispherical solid angles, and a
/// rim seen from within 0.1° of its plane; a circle straight ahead has a = b.
#[test]
fn refuses_degenerate_views() {
    let (c, n, r) = (Vec3::new(0.0, 0.0, 5.0), Vec3::new(0.0, 0.0, -1.0), 1.0);
    let at = |x: f32, z: f32| SphericalEllipse::new(Vec3::new(x, 0.0, z), c, n, r);
    assert!(at(0.0, 6.0).is_none(), "behind");
    assert!(at(0.0, 5.0).is_none(), "in the plane");
    assert!(at(3.0, 5.0).is_none(), "in the plane, outside");
    assert!(at(0.0, -100.0).is_none(), "tiny: Ω ≈ 3e-4");
    assert!(at(0.0, 4.999).is_none(), "Ω ≈ 2π");
    assert!(
        at(1.0, 4.999_998).is_none(),
        "the rim from 2e-6 above: b ≈ 700"
    );
    let e = at(0.0, 0.0).unwrap();
    let (a, b) = e.semi_axes();
    assert!((a - 0.2).abs() < 1e-6 && (b - 0.2).abs() < 1e-6, "{a} {b}");
    assert!((e.axis() - Vec3::Z).length() < 1e-6);
    // Non-finite input.
    assert!(SphericalEllipse::new(Vec3::NAN, c, n, r).is_none());
    assert!(SphericalEllipse::new(Vec3::ZERO, c, n, f32::INFINITY).is_none());
}

/// Newton steps (evaluations of `F`) per sample and duplication steps per `R_F`/`R_J` pair, over
/// the views and a sweep of nearly edge-on ones: the seed is exact for circles and small cones,
/// so most samples take 1–2 steps; the caps are never reached. Measured: mean ≤ 2.5 on every view
/// (1.0 on round ones), at most 8 Newton steps (thin ellipses: 89° and 87° off the normal, just
/// beside the rim); at most 5 duplication steps.
#[test]
fn newton_and_carlson_step_counts() {
    use crate::sampling::elliptic::carlson_rf_rj_steps;
    let mut rng = Rng::new(303, 0, 0);
    let mut views: Vec<(String, f64, f64, f64)> = VIEWS
        .iter()
        .map(|v| (v.0.to_string(), v.1, v.2, v.3))
        .collect();
    for deg in [60.0f64, 80.0, 87.0, 89.0] {
        for d in [0.3f64, 1.0, 3.0] {
            let (h, cx) = (d * deg.to_radians().cos(), d * deg.to_radians().sin());
            views.push((format!("{deg}° at {d}"), h, cx, 1.0));
        }
    }
    let (mut worst_newton, mut worst_carlson) = (0usize, 0usize);
    for (name, h, cx, r) in views {
        let (p, c, n, radius) = placed(h, cx, r, &mut rng);
        let Some(e) = SphericalEllipse::new(p, c, n, radius) else {
            continue;
        };
        let (mut total, mut most) = (0usize, 0usize);
        let count = 4000;
        for _ in 0..count {
            let (_, steps) = e.sample_steps(rng.next_2d());
            total += steps;
            most = most.max(steps);
            // The duplication loops at this sample's azimuth.
            let (a2, b2) = (e.a * e.a, e.b * e.b);
            let (s, c) = (rng.next_f32() * FRAC_PI_2).sin_cos();
            let (x, y) = (a2 * c * c, a2 * c * c + b2 * s * s);
            let z = a2 + (b2 - a2) * s * s / (1.0 + b2);
            worst_carlson = worst_carlson.max(carlson_rf_rj_steps(x, y, z, a2).2);
        }
        let mean = total as f64 / count as f64;
        eprintln!(
            "{name}: Ω {:.3}, a/b {:.2e}: Newton mean {mean:.2}, max {most}",
            e.solid_angle(),
            e.a / e.b
        );
        assert!(mean < 3.0, "{name}: mean {mean}");
        worst_newton = worst_newton.max(most);
    }
    eprintln!("most Newton steps {worst_newton}, most duplication steps {worst_carlson}");
    assert!(worst_newton < MAX_ELLIPSE_NEWTON_STEPS, "{worst_newton}");
    assert!(
        worst_carlson < crate::sampling::elliptic::MAX_CARLSON_STEPS,
        "{worst_carlson}"
    );
}
