//! The acceleration structure: an obvhs compressed-wide BVH (CWBVH) over all primitives, with
//! closest-hit and any-hit (shadow) queries. CWBVH wins over BVH2 for incoherent and shadow rays on
//! this CPU (see `../shared/notes/stack.md`), which is most of a path tracer's rays. The GPU
//! traverses the compressed nodes; the CPU traverses the same tree decoded to `f32`
//! ([`super::wide_bvh`]), which costs 224 instead of 80 bytes a node and saves decoding the
//! quantized boxes at every visit. How the tree is built, in parts for large scenes so that the
//! builder's temporaries stay small: [`super::bvh_build`].
//! WGSL twin: `geometry/bvh.wgsl`.

use super::primitive::{Primitive, ShapeHit};
use super::ray::{Ray, SurfaceHit};
use super::triangle::TriangleRay;
use super::wide_bvh::WideBvh;
use glam::Vec3;
use obvhs::cwbvh::CwBvh;
use std::ops::Range;

/// Primitives in BVH order plus the BVH. Scenes of at most [`Accel::LINEAR_LIMIT`] primitives
/// skip the BVH: testing a handful of shapes directly is faster than traversing.
pub struct Accel {
    prims: Vec<Primitive>,
    /// The CWBVH (uploaded to the GPU as it is) and its decoded copy the CPU traverses.
    bvh: Option<(CwBvh, WideBvh)>,
}

impl Accel {
    /// Below this many primitives a linear scan beats the BVH.
    pub const LINEAR_LIMIT: usize = 4;

    /// Builds the BVH and reorders the primitives (in place) to its leaf order.
    pub fn new(mut prims: Vec<Primitive>) -> Accel {
        if prims.len() <= Self::LINEAR_LIMIT {
            return Accel { prims, bvh: None };
        }
        // A vector grown by doubling holds up to twice what it needs, for the scene's lifetime.
        prims.shrink_to_fit();
        let bvh = super::bvh_build::build(&mut prims);
        let wide = WideBvh::from_cwbvh(&bvh);
        Accel {
            prims,
            bvh: Some((bvh, wide)),
        }
    }

    /// The primitives, in the order `SurfaceHit::prim` indexes.
    pub fn primitives(&self) -> &[Primitive] {
        &self.prims
    }

    /// The CWBVH over [`Accel::primitives`] (its leaves index them directly), or `None` when the
    /// scene is small enough to be scanned linearly. The GPU backend uploads its nodes as they are.
    pub fn cwbvh(&self) -> Option<&CwBvh> {
        self.bvh.as_ref().map(|(cw, _)| cw)
    }

    /// Closest hit along `ray` within `(0, ray.t_max)`.
    pub fn intersect(&self, ray: &Ray) -> Option<SurfaceHit> {
        let tri = TriangleRay::new(ray);
        let mut best = None;
        // The leaf tests are forced inline into every traversal instantiation: left to the
        // optimiser, whether they are depends on how the crate is split into codegen units, which
        // moved unrelated changes' instruction counts by 5% (docs/performance.md).
        self.closest(
            ray,
            #[inline(always)]
            |slots, t_max| self.closest_in(slots, ray, &tri, t_max, &mut best),
        );
        best.map(|(id, h)| self.prims[id].shape.surface_hit(ray, h, id as u32))
    }

    /// Closest hit along `ray` within `(0, ray.t_max)` among the candidate hits that `keep`
    /// (given the primitive's index and its hit on `ray`) keeps: the any-hit test of alpha masks
    /// ([`crate::materials::mask`]). A sphere or cylinder whose near hit is rejected is tested
    /// again on its far side. Its own leaf test, so that [`Accel::intersect`] stays as it was.
    #[inline(always)]
    pub fn intersect_kept(
        &self,
        ray: &Ray,
        keep: impl Fn(usize, &ShapeHit) -> bool,
    ) -> Option<SurfaceHit> {
        let tri = TriangleRay::new(ray);
        let mut best = None;
        self.closest(
            ray,
            #[inline(always)]
            |slots, t_max| self.closest_in_kept(slots, ray, &tri, t_max, &mut best, &keep),
        );
        best.map(|(id, h)| self.prims[id].shape.surface_hit(ray, h, id as u32))
    }

    /// The closest-hit traversal, `leaf` testing each leaf's primitives within `(0, t_max)`
    /// and returning a closer hit's parameter.
    #[inline(always)]
    fn closest(&self, ray: &Ray, mut leaf: impl FnMut(Range<usize>, f32) -> Option<f32>) {
        match &self.bvh {
            Some((_, wide)) => wide.closest(ray, leaf),
            None => {
                leaf(0..self.prims.len(), ray.t_max);
            }
        }
    }

    /// Tests the primitives `slots` within `(0, t_max)`; records a closer hit in `best` and returns
    /// its parameter.
    #[inline(always)]
    fn closest_in(
        &self,
        slots: Range<usize>,
        ray: &Ray,
        tri: &TriangleRay,
        t_max: f32,
        best: &mut Option<(usize, ShapeHit)>,
    ) -> Option<f32> {
        let local = Ray { t_max, ..*ray };
        let mut closer = None;
        for id in slots {
            if let Some(h) = self.prims[id].shape.intersect_t(&local, tri)
                && h.t < closer.unwrap_or(t_max)
            {
                closer = Some(h.t);
                *best = Some((id, h));
            }
        }
        closer
    }

    /// [`Accel::closest_in`] keeping only the hits `keep` keeps, a passed sphere's or
    /// cylinder's far side tested in turn.
    #[inline(always)]
    fn closest_in_kept(
        &self,
        slots: Range<usize>,
        ray: &Ray,
        tri: &TriangleRay,
        t_max: f32,
        best: &mut Option<(usize, ShapeHit)>,
        keep: &impl Fn(usize, &ShapeHit) -> bool,
    ) -> Option<f32> {
        let local = Ray { t_max, ..*ray };
        let mut closer = None;
        for id in slots {
            let shape = &self.prims[id].shape;
            let mut hit = shape.intersect_t(&local, tri);
            while let Some(h) = hit
                && h.t < closer.unwrap_or(t_max)
            {
                if keep(id, &h) {
                    closer = Some(h.t);
                    *best = Some((id, h));
                    break;
                }
                hit = shape.intersect_t_beyond(&local, h.t);
            }
        }
        closer
    }

    /// Whether anything blocks `ray` within `(0, ray.t_max)`; stops at the first blocker.
    pub fn occluded(&self, ray: &Ray) -> bool {
        let tri = TriangleRay::new(ray);
        match &self.bvh {
            Some((_, wide)) => wide.any(
                ray,
                #[inline(always)]
                |slots| self.any_in(slots, ray, &tri),
            ),
            None => self.any_in(0..self.prims.len(), ray, &tri),
        }
    }

    /// Whether a primitive of `slots` blocks `ray`.
    #[inline(always)]
    fn any_in(&self, slots: Range<usize>, ray: &Ray, tri: &TriangleRay) -> bool {
        self.prims[slots]
            .iter()
            .any(|p| p.shape.intersect_t(ray, tri).is_some())
    }

    /// Whether a hit that `keep` keeps blocks `ray` within `(0, ray.t_max)` (as
    /// [`Accel::intersect_kept`]); stops at the first.
    #[inline(always)]
    pub fn occluded_kept(&self, ray: &Ray, keep: impl Fn(usize, &ShapeHit) -> bool) -> bool {
        let tri = TriangleRay::new(ray);
        let any_in = |slots: Range<usize>| {
            slots.into_iter().any(|id| {
                let shape = &self.prims[id].shape;
                let mut hit = shape.intersect_t(ray, &tri);
                while let Some(h) = hit {
                    if keep(id, &h) {
                        return true;
                    }
                    hit = shape.intersect_t_beyond(ray, h.t);
                }
                false
            })
        };
        match &self.bvh {
            Some((_, wide)) => wide.any(ray, any_in),
            None => any_in(0..self.prims.len()),
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

    /// Rays leaving a point a hair inside an edge of a closed box must hit the box, through the
    /// BVH as by brute force. obvhs's fixed node epsilon, and the triangle test's error bound at
    /// grazing angles, once let them escape (issue 7).
    #[test]
    fn rays_from_inside_edges_never_escape_a_closed_box() {
        let mut prims = Vec::new();
        let c = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
        // Six faces of [-1, 1]^3, two triangles each, several times over at different scales.
        for scale in [1e-4f32, 1.0, 1e4] {
            prims.clear();
            for axis in 0..3 {
                for sign in [-1.0f32, 1.0] {
                    let at = |u: f32, v: f32| {
                        let mut p = [0.0f32; 3];
                        p[axis] = sign * scale;
                        p[(axis + 1) % 3] = u * scale;
                        p[(axis + 2) % 3] = v * scale;
                        c(p[0], p[1], p[2])
                    };
                    let q = [at(-1.0, -1.0), at(1.0, -1.0), at(1.0, 1.0), at(-1.0, 1.0)];
                    for t in [[q[0], q[1], q[2]], [q[0], q[2], q[3]]] {
                        prims.push(Primitive {
                            shape: Shape::triangle(t).unwrap(),
                            material: 0,
                            light: NONE,
                            attr: NONE,
                        });
                    }
                }
            }
            let accel = Accel::new(prims.clone());
            assert!(accel.bvh.is_some());
            let brute = Accel {
                prims: prims.clone(),
                bvh: None,
            };
            let mut rng = Rng::new(17, 0, 0);
            for i in 0..20_000 {
                // A point on an edge of the box, moved inside by 1e-7 to 1e-3 of its size (an
                // origin exactly on a wall's plane cannot tell which side it is on).
                let inset = 10f32.powf(-7.0 + 4.0 * rng.next_f32());
                let along = 2.0 * rng.next_f32() - 1.0;
                let mut p = [along; 3];
                let axis = i % 3;
                p[(axis + 1) % 3] = if rng.next_f32() < 0.5 { -1.0 } else { 1.0 };
                p[(axis + 2) % 3] = if rng.next_f32() < 0.5 { -1.0 } else { 1.0 };
                let o = c(p[0], p[1], p[2]) * (1.0 - inset) * scale;
                let d =
                    (Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) - 0.5).normalize();
                let ray = Ray::new(o, d);
                let brute_hit = brute.intersect(&ray);
                let hit = accel.intersect(&ray);
                assert_eq!(
                    hit.map(|h| h.t),
                    brute_hit.map(|h| h.t),
                    "scale {scale}: BVH and brute force differ for {ray:?}"
                );
                assert!(hit.is_some(), "scale {scale}: {ray:?} escaped the box");
                assert!(
                    accel.occluded(&ray),
                    "scale {scale}: {ray:?} escaped the box"
                );
            }
        }
    }

    /// The masked queries: a hit that `keep` rejects is passed, and on a sphere the far side is
    /// then met (a mask let the ray through the near side, not the whole sphere); a flat shape
    /// passed is passed for good. Through the BVH as by brute force.
    #[test]
    fn rejected_hits_are_passed_and_a_spheres_far_side_is_met() {
        let mut rng = Rng::new(11, 0, 0);
        let mut prims = random_prims(&mut rng, 40);
        // A sphere and a triangle across the ray's line, both centred on the z axis.
        prims.push(Primitive {
            shape: Shape::Sphere(Sphere::new(Vec3::new(0.0, 0.0, 20.0), 1.0)),
            material: 1000,
            light: NONE,
            attr: NONE,
        });
        prims.push(Primitive {
            shape: Shape::triangle([
                Vec3::new(-1.0, -1.0, 25.0),
                Vec3::new(2.0, -1.0, 25.0),
                Vec3::new(-1.0, 2.0, 25.0),
            ])
            .unwrap(),
            material: 1001,
            light: NONE,
            attr: NONE,
        });
        let brute = Accel {
            prims: prims.clone(),
            bvh: None,
        };
        let accel = Accel::new(prims);
        let ray = Ray::new(Vec3::new(0.0, 0.0, 15.0), Vec3::Z);
        for a in [&accel, &brute] {
            let material = |h: &SurfaceHit| a.prims[h.prim as usize].material;
            let near = a.intersect(&ray).unwrap();
            assert_eq!((material(&near), near.t), (1000, 4.0));
            // Reject the sphere's near side only: its far side, at t = 6.
            let far = a
                .intersect_kept(&ray, |id, h| a.prims[id].material != 1000 || h.t > 5.0)
                .unwrap();
            assert_eq!((material(&far), far.t), (1000, 6.0));
            // Reject the sphere altogether: the triangle at t = 10; then nothing.
            let tri = a
                .intersect_kept(&ray, |id, _| a.prims[id].material != 1000)
                .unwrap();
            assert_eq!((material(&tri), tri.t), (1001, 10.0));
            assert!(
                a.intersect_kept(&ray, |id, _| a.prims[id].material < 1000)
                    .is_none()
            );
            let short = Ray { t_max: 5.5, ..ray };
            assert!(a.occluded_kept(&ray, |id, h| a.prims[id].material != 1000 || h.t > 5.0));
            assert!(!a.occluded_kept(&short, |id, h| a.prims[id].material != 1000 || h.t > 5.0));
            assert!(!a.occluded_kept(&ray, |id, _| a.prims[id].material < 1000));
        }
    }

    /// `n` random spheres and triangles in a 10-unit cube, each with its index as its material.
    fn random_prims(rng: &mut Rng, n: usize) -> Vec<Primitive> {
        let mut prims = Vec::new();
        for i in 0..n {
            let c = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 10.0;
            let shape = if i % 3 == 0 {
                Shape::Sphere(Sphere::new(c, 0.3))
            } else {
                let d = |r: &mut Rng| Vec3::new(r.next_f32(), r.next_f32(), r.next_f32()) - 0.5;
                match Shape::triangle([c, c + d(rng), c + d(rng)]) {
                    Some(s) => s,
                    None => continue,
                }
            };
            prims.push(Primitive {
                shape,
                material: prims.len() as u32,
                light: NONE,
                attr: NONE,
            });
        }
        prims
    }

    /// Closest hits and occlusion through `accel` must be exactly a brute-force scan's.
    fn check_against_brute_force(accel: &Accel, prims: Vec<Primitive>, rng: &mut Rng) {
        let brute = Accel { prims, bvh: None };
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

    /// The BVH must return exactly what a brute-force scan returns.
    #[test]
    fn bvh_matches_brute_force() {
        let mut rng = Rng::new(9, 0, 0);
        let prims = random_prims(&mut rng, 300);
        let accel = Accel::new(prims.clone());
        check_against_brute_force(&accel, prims, &mut rng);
    }

    /// The chunked build (large scenes, `bvh_build.rs`), forced on a small scene with one
    /// triangle spanning it (so the parts' boxes overlap): a valid CWBVH (obvhs's own checks:
    /// every node and primitive reached once, every primitive inside its node's boxes), its
    /// `primitive_indices` naming each slot's original primitive, and the same hits as brute force.
    #[test]
    fn chunked_bvh_matches_brute_force() {
        let mut rng = Rng::new(10, 0, 0);
        let mut prims = random_prims(&mut rng, 3000);
        prims.push(Primitive {
            shape: Shape::triangle([Vec3::ZERO, Vec3::new(10.0, 0.0, 0.0), Vec3::splat(10.0)])
                .unwrap(),
            material: prims.len() as u32,
            light: NONE,
            attr: NONE,
        });
        let mut ordered = prims.clone();
        let cw = crate::geometry::bvh_build::build_chunked(&mut ordered);
        cw.validate(&ordered, true);
        for (p, &i) in ordered.iter().zip(&cw.primitive_indices) {
            assert_eq!(p.material, prims[i as usize].material);
        }
        let wide = WideBvh::from_cwbvh(&cw);
        let accel = Accel {
            prims: ordered,
            bvh: Some((cw, wide)),
        };
        check_against_brute_force(&accel, prims, &mut rng);
    }
}
