//! Rays through the scene: the closest hit and occlusion, through the alpha masks
//! ([`crate::materials::mask`]). In a scene without masks these are the BVH's own queries; with
//! masks, the BVH's any-hit test keeps a hit on a masked primitive with probability its
//! opacity at the hit, the same rule for the paths' rays and for their shadow rays.
//! WGSL twin: `materials/mask.wgsl` (`mask_meets`, which the traversals' `prim_hit_t` calls).

use super::Scene;
use super::surface::SurfacePoint;
use crate::geometry::primitive::ShapeHit;
use crate::geometry::{Ray, SurfaceHit};
use crate::materials::mask;
use crate::textures::Texture;
use glam::Vec2;

impl Scene {
    /// The closest surface `ray` meets within `(0, ray.t_max)`.
    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<SurfaceHit> {
        if self.opacity.is_empty() {
            return self.accel.intersect(ray);
        }
        self.intersect_masked(ray)
    }

    /// Whether a surface blocks `ray` within `(0, ray.t_max)`.
    #[inline]
    pub fn occluded(&self, ray: &Ray) -> bool {
        if self.opacity.is_empty() {
            return self.accel.occluded(ray);
        }
        self.occluded_masked(ray)
    }

    // Kept out of line: the masked traversals are separate instantiations, and scenes without
    // masks should not carry them inline.
    #[inline(never)]
    fn intersect_masked(&self, ray: &Ray) -> Option<SurfaceHit> {
        self.accel
            .intersect_kept(ray, |id, h| self.meets(id, ray, h))
    }

    #[inline(never)]
    fn occluded_masked(&self, ray: &Ray) -> bool {
        self.accel
            .occluded_kept(ray, |id, h| self.meets(id, ray, h))
    }

    /// Whether `ray` meets primitive `id` at its candidate hit `h` (found by
    /// [`crate::geometry::Shape::intersect_t`] on `ray`): always where the material is opaque,
    /// else with probability its opacity at the hit's texture coordinates.
    pub fn meets(&self, id: usize, ray: &Ray, h: &ShapeHit) -> bool {
        let prim = &self.accel.primitives()[id];
        let Some(Some(opacity)) = self.opacity.get(prim.material as usize) else {
            return true;
        };
        // A triangle's coordinates come from the candidate's barycentrics, as `Scene::uv` takes
        // them from the hit record, without building that record.
        let at = match (opacity, &prim.shape) {
            (Texture::Constant(_), _) => Vec2::ZERO.into(),
            (_, crate::geometry::Shape::Triangle { .. }) => {
                self.tex_point_at(SurfacePoint::Triangle {
                    attr: prim.attr,
                    b: Vec2::new(h.b[1], h.b[2]),
                })
            }
            _ => self.tex_point(&prim.shape.surface_hit(ray, *h, id as u32)),
        };
        mask::kept(opacity.eval_scalar(at), ray.o, h.t, id as u32)
    }
}
