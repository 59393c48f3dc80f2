//! Bump maps, as Mitsuba 3.9.1's `bumpmap` defines them (`src/bsdfs/bumpmap.cpp`): a scalar
//! height texture h whose gradient, scaled, replaces the normal components of the surface's
//! partials, ∂p/∂u' = ∂p/∂u + n_s·(scale·∂h/∂u − n_s·∂p/∂u) and likewise for v; the bumped normal
//! is their normalised cross product, turned to the geometric normal's side. What follows is the
//! normal map's (`materials/normal_map.rs`): the bumped normal in the shading frame of ∂p/∂u, the
//! flip, the frame about it, the side rule and the shadowing term, exactly as for a texel.
//!
//! The gradient is [`crate::textures::Texture::eval_1_grad`]'s: a bitmap's luminance (Mitsuba's
//! `eval_1_grad`). Both partials come from the mesh's parameterisation
//! ([`crate::geometry::tangent::dp_duv`]); analytic shapes are refused where the scene is read.
//! A zero gradient leaves the frame as it is (`None`): a flat height field changes no image.
//! WGSL twin: `bump_normal` in `materials/normal_map.wgsl`.

use crate::math::Frame;
use glam::{Vec2, Vec3};

/// The bumped normal in `front`'s local coordinates (unnormalised input for
/// [`super::normal_map::NormalMap::perturb`]), or `None` for no tilt: a zero gradient, or partials
/// that leave no normal. `grad` is scale·(∂h/∂u, ∂h/∂v); `dp_du`, `dp_dv` the parameterisation's
/// partials, `ns` the front's unit shading normal, `ng` the geometric normal (the side the bumped
/// normal is turned to), `front` the front's shading frame about ∂p/∂u.
pub fn local_normal(
    grad: Vec2,
    dp_du: Vec3,
    dp_dv: Vec3,
    ns: Vec3,
    ng: Vec3,
    front: &Frame,
) -> Option<Vec3> {
    if grad == Vec2::ZERO {
        return None;
    }
    let du = dp_du + ns * (grad.x - ns.dot(dp_du));
    let dv = dp_dv + ns * (grad.y - ns.dot(dp_dv));
    let n = du.cross(dv);
    let len = n.length();
    if !(len > 0.0 && len.is_finite()) {
        return None;
    }
    let n = n / len;
    let n = if ng.dot(n) < 0.0 { -n } else { n };
    Some(front.to_local(n))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A height field h = a·u on a unit square (∂p/∂u = x, ∂p/∂v = y, n = z) tilts the normal to
    /// (−a, 0, 1)/√(1 + a²), the normal of the graph z = a·x: the formula is the surface's own
    /// normal, not a guess. Catches a swapped or unscaled partial and a wrong sign.
    #[test]
    fn a_linear_height_field_tilts_the_normal_to_its_graphs() {
        let front = Frame {
            s: Vec3::X,
            t: Vec3::Y,
            n: Vec3::Z,
        };
        for (a, b) in [(0.5, 0.0), (0.0, -2.0), (3.0, 1.0)] {
            let n =
                local_normal(Vec2::new(a, b), Vec3::X, Vec3::Y, Vec3::Z, Vec3::Z, &front).unwrap();
            let want = Vec3::new(-a, -b, 1.0).normalize();
            assert!((n - want).length() < 1e-6, "{a} {b}: {n} vs {want}");
        }
        // The partials' lengths scale the tilt: u running twice as fast over the surface halves
        // the slope (∂p/∂u = 2x: h = a·u rises a over 2 units of length).
        let n = local_normal(
            Vec2::new(1.0, 0.0),
            2.0 * Vec3::X,
            Vec3::Y,
            Vec3::Z,
            Vec3::Z,
            &front,
        )
        .unwrap();
        assert!(
            (n - Vec3::new(-0.5, 0.0, 1.0).normalize()).length() < 1e-6,
            "{n}"
        );
    }

    /// The bumped normal is turned to the geometric normal's side, whichever way the partials'
    /// cross product points (a parameterisation mirrored in v), and a zero gradient is no tilt.
    #[test]
    fn the_normal_faces_the_geometric_side_and_a_flat_field_is_no_tilt() {
        let front = Frame {
            s: Vec3::X,
            t: Vec3::Y,
            n: Vec3::Z,
        };
        let n = local_normal(
            Vec2::new(0.3, 0.2),
            Vec3::X,
            -Vec3::Y,
            Vec3::Z,
            Vec3::Z,
            &front,
        )
        .unwrap();
        assert!(n.z > 0.0, "{n}");
        assert_eq!(
            local_normal(Vec2::ZERO, Vec3::X, Vec3::Y, Vec3::Z, Vec3::Z, &front),
            None
        );
        // Degenerate partials: no normal, no tilt (and no NaN).
        assert_eq!(
            local_normal(
                Vec2::new(1.0, 1.0),
                Vec3::ZERO,
                Vec3::ZERO,
                Vec3::Z,
                Vec3::Z,
                &front
            ),
            None
        );
    }
}
