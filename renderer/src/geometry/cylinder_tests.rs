use super::*;
use crate::rng::Rng;

/// Radius 0.5 around the segment (1, 2, 3) → (1, 2, 5), u = 0 towards +x.
fn upright() -> Cylinder {
    Cylinder {
        p0: Vec3::new(1.0, 2.0, 3.0),
        axis: Vec3::new(0.0, 0.0, 2.0),
        u_axis: Vec3::X,
        radius: 0.5,
        flip: false,
    }
}

#[test]
fn hits_the_outside_then_the_inside_and_misses_past_the_ends() {
    let c = upright();
    // From −x towards +x at mid-height: the near wall at x = 0.5.
    let ray = Ray::new(Vec3::new(-2.0, 2.0, 4.0), Vec3::X);
    let t = c.intersect(&ray).unwrap();
    assert!((t - 2.5).abs() < 1e-5, "{t}");
    let (p, _, n) = c.surface_point(&ray, t);
    assert!((p - Vec3::new(0.5, 2.0, 4.0)).length() < 1e-5 && (n + Vec3::X).length() < 1e-6);
    // From the axis: the wall at distance r, seen from inside (the normal faces away).
    let ray = Ray::new(Vec3::new(1.0, 2.0, 4.0), Vec3::Y);
    let t = c.intersect(&ray).unwrap();
    assert!((t - 0.5).abs() < 1e-6);
    assert!(c.surface_point(&ray, t).2.dot(ray.d) > 0.99);
    // Above the top: the near wall is past the end, the far one too.
    assert!(
        c.intersect(&Ray::new(Vec3::new(-2.0, 2.0, 5.1), Vec3::X))
            .is_none()
    );
    // Down through the open top at a slant: the near wall is above the end, so the ray enters
    // and hits the far wall's inside.
    let d = Vec3::new(1.0, 0.0, -1.0).normalize();
    let ray = Ray::new(Vec3::new(0.0, 2.0, 5.7), d);
    let t = c.intersect(&ray).unwrap();
    let p = ray.at(t);
    assert!((p.x - 1.5).abs() < 1e-5 && (p.z - 4.2).abs() < 1e-5, "{p}");
    // Along the axis: never on the tube.
    assert!(
        c.intersect(&Ray::new(Vec3::new(1.0, 2.0, 0.0), Vec3::Z))
            .is_none()
    );
    // A flipped cylinder's normal points inward.
    let flipped = Cylinder { flip: true, ..c };
    let ray = Ray::new(Vec3::new(-2.0, 2.0, 4.0), Vec3::X);
    let t = flipped.intersect(&ray).unwrap();
    assert!((flipped.surface_point(&ray, t).2 - Vec3::X).length() < 1e-6);
}

/// Mitsuba's parameterisation: u from the u axis towards axis × u_axis, v along the axis, and
/// ∂p/∂u along growing u.
#[test]
fn uv_and_dp_du_follow_mitsubas_frame() {
    let c = upright();
    let uv = c.uv(Vec3::new(1.0, 2.5, 3.5)); // φ = 90° (+y = z × x), a quarter of the height
    assert!((uv - Vec2::new(0.25, 0.25)).length() < 1e-6, "{uv}");
    let uv = c.uv(Vec3::new(0.5, 2.0, 5.0)); // φ = 180°, the top
    assert!((uv - Vec2::new(0.5, 1.0)).length() < 1e-6, "{uv}");
    let p = Vec3::new(1.5, 2.0, 4.0);
    let t = c.dp_du(p).normalize();
    assert!((t - Vec3::Y).length() < 1e-6, "{t}");
    let u_ahead = c.uv(c.p0 + (p - c.p0 + 1e-3 * t).normalize() * 0.5 + Vec3::Z);
    assert!(u_ahead.x > c.uv(p).x);
}

/// Rays from random points towards random points of random cylinders: every hit lies on the
/// tube within its error bound and inside the bounds; every ray aimed at a wall point hits (the
/// first hit is no farther than the aimed point), except grazing ones (|cos| < 0.05 to the
/// wall's normal), whose two roots are too close for f32 to tell from a miss.
#[test]
fn random_hits_lie_on_the_tube_within_their_bounds() {
    let mut rng = Rng::new(0x5eed_c71d, 0, 0);
    let mut grazing = 0;
    let v = |rng: &mut Rng| Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) - 0.5;
    for _ in 0..2000 {
        let axis = v(&mut rng) * 4.0;
        if axis.length() < 0.1 {
            continue;
        }
        let z = axis.normalize();
        let u_axis = crate::math::Frame::from_normal(z).s;
        let c = Cylinder {
            p0: v(&mut rng) * 10.0,
            axis,
            u_axis,
            radius: 0.05 + rng.next_f32(),
            flip: false,
        };
        let (lo, hi) = c.bounds();
        // A point on the wall, seen from a random origin.
        let (phi, h) = (rng.next_f32() * TAU, rng.next_f32());
        let y = z.cross(u_axis);
        let target = c.p0 + axis * h + (u_axis * phi.cos() + y * phi.sin()) * c.radius;
        let o = target + v(&mut rng) * 20.0;
        let ray = Ray::new(o, (target - o).normalize());
        if ray.d.dot(u_axis * phi.cos() + y * phi.sin()).abs() < 0.05 {
            grazing += 1;
            continue;
        }
        let t_target = (target - o).length();
        let t = c
            .intersect(&ray)
            .unwrap_or_else(|| panic!("missed the aimed wall point {target} of {c:?} from {o}"));
        assert!(t <= t_target * (1.0 + 1e-4) + 1e-4, "{t} > {t_target}");
        let (p, err, n) = c.surface_point(&ray, t);
        let rel = p - c.p0;
        let radial = (rel - z * rel.dot(z)).length();
        assert!((radial - c.radius).abs() <= 8.0 * err.max_element() + 1e-6);
        assert!((n.length() - 1.0).abs() < 1e-5 && n.dot(z).abs() < 1e-4);
        assert!(
            p.cmpge(lo - 1e-4).all() && p.cmple(hi + 1e-4).all(),
            "{p} ∉ {lo}..{hi}"
        );
        let uv = c.uv(p);
        assert!((0.0..=1.0).contains(&uv.x) && uv.y > -1e-4 && uv.y < 1.0 + 1e-4);
    }
    assert!(
        grazing < 200,
        "{grazing} of 2000 rays grazed: the test tested little"
    );
}
