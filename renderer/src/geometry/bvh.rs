//! The acceleration structure: an obvhs compressed-wide BVH (CWBVH) over all primitives, with
//! closest-hit and any-hit (shadow) queries. CWBVH wins over BVH2 for incoherent and shadow rays on
//! this CPU (see `../shared/notes/stack.md`), which is most of a path tracer's rays.

use super::primitive::Primitive;
use super::ray::{Ray, SurfaceHit};
use super::triangle::TriangleRay;
use glam::Vec3;
use obvhs::cwbvh::CwBvh;
use obvhs::{BvhBuildParams, cwbvh::builder::build_cwbvh};
use std::time::Duration;

/// Primitives in BVH order plus the BVH. Scenes of at most [`Accel::LINEAR_LIMIT`] primitives
/// skip the BVH: testing a handful of shapes directly is faster than traversing.
pub struct Accel {
    prims: Vec<Primitive>,
    bvh: Option<CwBvh>,
}

impl Accel {
    /// Below this many primitives a linear scan beats the BVH.
    pub const LINEAR_LIMIT: usize = 4;

    /// Builds the BVH and reorders the primitives to its leaf order.
    pub fn new(prims: Vec<Primitive>) -> Accel {
        if prims.len() <= Self::LINEAR_LIMIT {
            return Accel { prims, bvh: None };
        }
        let bvh = build_cwbvh(
            &prims,
            BvhBuildParams::medium_build(),
            &mut Duration::default(),
        );
        let prims = bvh
            .primitive_indices
            .iter()
            .map(|&i| prims[i as usize])
            .collect();
        Accel {
            prims,
            bvh: Some(bvh),
        }
    }

    /// The primitives, in the order `SurfaceHit::prim` indexes.
    pub fn primitives(&self) -> &[Primitive] {
        &self.prims
    }

    /// Closest hit along `ray` within `(0, ray.t_max)`.
    pub fn intersect(&self, ray: &Ray) -> Option<SurfaceHit> {
        let mut best_t = ray.t_max;
        let mut best = u32::MAX;
        let tri = TriangleRay::new(ray);
        match &self.bvh {
            Some(bvh) => {
                let r = obvhs::ray::Ray::new(ray.o.into(), ray.d.into(), 0.0, ray.t_max);
                let mut hit = obvhs::ray::RayHit::none();
                bvh.ray_traverse(r, &mut hit, |r, id| {
                    let local = Ray {
                        t_max: r.tmax,
                        ..*ray
                    };
                    match self.prims[id].shape.intersect_t(&local, &tri) {
                        Some(t) => {
                            if t < best_t {
                                best_t = t;
                                best = id as u32;
                            }
                            t
                        }
                        None => f32::INFINITY,
                    }
                });
            }
            None => {
                for (id, p) in self.prims.iter().enumerate() {
                    if let Some(t) = p.shape.intersect_t(
                        &Ray {
                            t_max: best_t,
                            ..*ray
                        },
                        &tri,
                    ) {
                        best_t = t;
                        best = id as u32;
                    }
                }
            }
        }
        (best != u32::MAX).then(|| {
            self.prims[best as usize]
                .shape
                .surface_hit(ray, best_t, best)
        })
    }

    /// Whether anything blocks `ray` within `(0, ray.t_max)`; stops at the first blocker.
    pub fn occluded(&self, ray: &Ray) -> bool {
        let tri = TriangleRay::new(ray);
        match &self.bvh {
            Some(bvh) => {
                let r = obvhs::ray::Ray::new(ray.o.into(), ray.d.into(), 0.0, ray.t_max);
                !bvh.ray_traverse_miss(r, |_, id| {
                    self.prims[id]
                        .shape
                        .intersect_t(ray, &tri)
                        .unwrap_or(f32::INFINITY)
                })
            }
            None => self
                .prims
                .iter()
                .any(|p| p.shape.intersect_t(ray, &tri).is_some()),
        }
    }

    /// Bounds of all primitives.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        self.prims
            .iter()
            .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| {
                let (a, b) = p.shape.bounds();
                (lo.min(a), hi.max(b))
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::primitive::{NONE, Shape};
    use crate::geometry::sphere::Sphere;
    use crate::rng::Rng;

    /// The BVH must return exactly what a brute-force scan returns.
    #[test]
    fn bvh_matches_brute_force() {
        let mut rng = Rng::new(9, 0, 0);
        let mut prims = Vec::new();
        for i in 0..300 {
            let c = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 10.0;
            let shape = if i % 3 == 0 {
                Shape::Sphere(Sphere {
                    center: c,
                    radius: 0.3,
                })
            } else {
                let d = |r: &mut Rng| Vec3::new(r.next_f32(), r.next_f32(), r.next_f32()) - 0.5;
                match Shape::triangle([c, c + d(&mut rng), c + d(&mut rng)]) {
                    Some(s) => s,
                    None => continue,
                }
            };
            prims.push(Primitive {
                shape,
                material: 0,
                light: NONE,
            });
        }
        let brute = Accel {
            prims: prims.clone(),
            bvh: None,
        };
        let accel = Accel::new(prims);
        for _ in 0..5000 {
            let o = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 12.0 - 1.0;
            let d = (Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) - 0.5).normalize();
            let ray = Ray::new(o, d);
            let a = accel.intersect(&ray).map(|h| h.t);
            let b = brute.intersect(&ray).map(|h| h.t);
            assert_eq!(a, b);
            let short = Ray { t_max: 2.0, ..ray };
            assert_eq!(accel.occluded(&short), brute.occluded(&short));
        }
    }
}
