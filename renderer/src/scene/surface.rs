//! A hit's texture coordinates and its material: a mix resolved, textures evaluated there. Texture
//! coordinates by shape: mesh triangles interpolate their file's UVs (else their barycentrics),
//! quads and box faces run `u` along `edge_u` and `v` along `edge_v`, other triangles give their
//! barycentrics; spheres as Mitsuba 3's (`u = φ/2π` from +x towards +y, `v = θ/π` from +z),
//! disks `(r/radius, φ/2π)` around the normal's frame.

use super::Scene;
use crate::geometry::{Shape, SurfaceHit};
use crate::materials::Material;
use crate::math::{Frame, atan2};
use glam::Vec2;
use std::borrow::Cow;
use std::f32::consts::{PI, TAU};

impl Scene {
    /// The texture coordinates of `hit`.
    pub fn uv(&self, hit: &SurfaceHit) -> Vec2 {
        let prim = &self.accel.primitives()[hit.prim as usize];
        match &prim.shape {
            Shape::Triangle { .. } => self.attributes.uv(prim.attr, hit.b),
            Shape::Sphere(s) => {
                let d = (hit.p - s.center) / s.radius;
                let phi = atan2(d.y, d.x);
                let u = if phi < 0.0 { phi + TAU } else { phi } / TAU;
                Vec2::new(u, d.z.clamp(-1.0, 1.0).acos() / PI)
            }
            Shape::Disk(d) => {
                let local = Frame::from_normal(d.n).to_local(hit.p - d.center);
                let phi = atan2(local.y, local.x);
                let v = if phi < 0.0 { phi + TAU } else { phi } / TAU;
                Vec2::new((local.x.hypot(local.y) / d.radius).min(1.0), v)
            }
        }
    }

    /// The material of `hit`'s primitive: a mix resolved to one of its materials
    /// ([`Scene::resolve_mix`]), then its textures evaluated at the hit (borrowed when it has
    /// none).
    #[inline]
    pub fn material_at(&self, hit: &SurfaceHit, material: u32) -> Cow<'_, Material> {
        let material = self.resolve_mix(hit, material);
        let base = &self.materials[material as usize];
        match &self.material_textures[material as usize] {
            None => Cow::Borrowed(base),
            Some(t) => Cow::Owned(t.at(base, self.uv(hit))),
        }
    }

    /// The material a mix chooses at `hit`, through nested mixes (`material` itself when it is
    /// no mix): pbrt-v4's `ChooseMaterial`, by the hash of [`crate::materials::mix`], so that
    /// one hit always sees one material.
    #[inline]
    pub fn resolve_mix(&self, hit: &SurfaceHit, material: u32) -> u32 {
        let mut m = material;
        // The builder checked that every chain of mixes ends.
        while let Some(Some(mix)) = self.mixes.get(m as usize) {
            m = mix.choose(hit.p, hit.t, m, || self.uv(hit));
        }
        m
    }
}
