//! A hit's texture coordinates and its material: mixes and pairs resolved, textures evaluated
//! there. Texture coordinates by shape: mesh triangles interpolate their file's UVs (else their barycentrics),
//! quads and box faces run `u` along `edge_u` and `v` along `edge_v`, other triangles give their
//! barycentrics; spheres as Mitsuba 3's (`u = φ/2π` from its frame's x towards y, `v = θ/π`
//! from its z), disks `(r/radius, φ/2π)` from their x axis towards their y, cylinders Mitsuba's (`φ/2π` from their
//! u axis, the fraction of the height). Emission with its texture evaluated
//! at a hit or at a point sampled on a light, by the same rule ([`Scene::uv_at`]).

use super::Scene;
use crate::geometry::cylinder::Cylinder;
use crate::geometry::disk::Disk;
use crate::geometry::primitive::NONE;
use crate::geometry::sphere::Sphere;
use crate::geometry::{Shape, SurfaceHit};
use crate::lights::{Light, LightSample, LightSampling};
use crate::materials::Material;
use crate::materials::mix::Blend;
use crate::materials::normal_map::NormalMap;
use crate::math::atan2;
use crate::textures::{MeshPoint, TexPoint};
use glam::{Vec2, Vec3};
use std::borrow::Cow;
use std::f32::consts::{PI, TAU};

/// What a hit shades with ([`Scene::shading_at`]).
pub struct Shading<'a> {
    /// The material, resolved and with its textures evaluated.
    pub material: Cow<'a, Material>,
    /// Its normal or bump map with where to look it up.
    pub detail_map: Option<(&'a NormalMap, TexPoint<'a>)>,
    /// The partner and weight of a mix of model mitsuba that chose it.
    pub blend: Option<Blend>,
}

/// A point of a primitive, in the terms its texture coordinates are computed from.
#[derive(Clone, Copy, Debug)]
pub enum SurfacePoint<'a> {
    /// Barycentrics `b = (b1, b2)` in a triangle whose vertex attributes are `attr`
    /// ([`NONE`]: none, and the texture coordinates are `b`).
    Triangle {
        /// Index into [`crate::geometry::mesh_attributes::MeshAttributes::triangles`], or
        /// [`NONE`].
        attr: u32,
        /// Barycentrics `(b1, b2)`.
        b: Vec2,
    },
    /// A point on a sphere.
    Sphere(&'a Sphere, Vec3),
    /// A point on a disk.
    Disk(&'a Disk, Vec3),
    /// A point on a cylinder.
    Cylinder(&'a Cylinder, Vec3),
}

impl Scene {
    /// The texture coordinates of `hit`.
    #[inline]
    pub fn uv(&self, hit: &SurfaceHit) -> Vec2 {
        self.uv_at(self.surface_point(hit))
    }

    /// `hit` as a point of its primitive, what [`Scene::uv`] and [`Scene::tex_point`] read.
    #[inline]
    fn surface_point(&self, hit: &SurfaceHit) -> SurfacePoint<'_> {
        let prim = &self.accel.primitives()[hit.prim as usize];
        match &prim.shape {
            Shape::Triangle { .. } => SurfacePoint::Triangle {
                attr: prim.attr,
                b: hit.b,
            },
            Shape::Sphere(s) => SurfacePoint::Sphere(s, hit.p),
            Shape::Disk(d) => SurfacePoint::Disk(d, hit.p),
            Shape::Cylinder(c) => SurfacePoint::Cylinder(c, hit.p),
        }
    }

    /// Where textures are looked up at `hit`: its texture coordinates and, on a mesh triangle
    /// with attributes in a scene whose textures read named ones, that triangle.
    #[inline]
    pub fn tex_point(&self, hit: &SurfaceHit) -> TexPoint<'_> {
        self.tex_point_at(self.surface_point(hit))
    }

    /// [`Scene::tex_point`] of a point of a primitive ([`Scene::uv_at`]'s rule for its
    /// coordinates).
    #[inline]
    pub fn tex_point_at(&self, point: SurfacePoint<'_>) -> TexPoint<'_> {
        let mesh = match point {
            SurfacePoint::Triangle { attr, b }
                if attr != NONE && !self.attributes.named_slots.is_empty() =>
            {
                Some(MeshPoint {
                    attributes: &self.attributes,
                    attr,
                    b,
                })
            }
            _ => None,
        };
        TexPoint {
            uv: self.uv_at(point),
            mesh,
        }
    }

    /// The texture coordinates of a point of a primitive: the one rule for hits
    /// ([`Scene::uv`]) and points sampled on lights ([`Scene::light_uv`]), so that the two
    /// cannot disagree.
    pub fn uv_at(&self, point: SurfacePoint<'_>) -> Vec2 {
        match point {
            SurfacePoint::Triangle { attr, b } => self.attributes.uv(attr, b),
            SurfacePoint::Sphere(s, p) => {
                let d = s.frame().to_local((p - s.center) / s.radius);
                let phi = atan2(d.y, d.x);
                let u = if phi < 0.0 { phi + TAU } else { phi } / TAU;
                Vec2::new(u, d.z.clamp(-1.0, 1.0).acos() / PI)
            }
            SurfacePoint::Disk(d, p) => {
                let (rel, [x, y]) = (p - d.center, d.uv_axes());
                let local = Vec2::new(rel.dot(x), rel.dot(y));
                let phi = atan2(local.y, local.x);
                let v = if phi < 0.0 { phi + TAU } else { phi } / TAU;
                Vec2::new((local.x.hypot(local.y) / d.radius).min(1.0), v)
            }
            SurfacePoint::Cylinder(c, p) => c.uv(p),
        }
    }

    /// The texture coordinates of the point `s` sampled on `light` (`None` for the lights at
    /// infinity), those of [`Scene::light_tex_point`].
    pub fn light_uv(&self, light: &Light, s: &LightSample) -> Option<Vec2> {
        self.light_tex_point(light, s).map(|t| t.uv)
    }

    /// Where textures are looked up at the point `s` sampled on `light` (`None` for the lights
    /// at infinity): the primitive under it by the builder's construction (a triangle light's
    /// attributes, a quad's triangle holding the point, a polygon's triangle, which has no
    /// attributes), through [`Scene::tex_point_at`].
    pub fn light_tex_point(&self, light: &Light, s: &LightSample) -> Option<TexPoint<'_>> {
        let point = match light {
            Light::Triangle(l) => SurfacePoint::Triangle {
                attr: l.attr,
                b: s.b,
            },
            Light::Polygon(_) => SurfacePoint::Triangle { attr: NONE, b: s.b },
            Light::Quad(q) => {
                let (k, b) = q.triangle_point(s.p);
                let attr = if q.attr == NONE { NONE } else { q.attr + k };
                SurfacePoint::Triangle { attr, b }
            }
            Light::Disk(d) => SurfacePoint::Disk(&d.disk, s.p),
            Light::Sphere(l) => SurfacePoint::Sphere(&l.sphere, s.p),
            // A spot's or projector's sample carries its texture coordinates.
            Light::Spot(_) | Light::Projector(_) => return Some(s.b.into()),
            Light::Background(_) | Light::Envmap(_) | Light::Point(_) | Light::Directional(_) => {
                return None;
            }
        };
        Some(self.tex_point_at(point))
    }

    /// Radiance emitted by light `light` (the primitive's of `hit`) at `hit` along `-w_in`: its
    /// constant radiance, or its emission texture at the hit's texture coordinates.
    #[inline]
    pub fn emitted(&self, light: u32, hit: &SurfaceHit, w_in: Vec3) -> Vec3 {
        let l = &self.lights[light as usize];
        let le = l.radiance(hit.n, w_in);
        let texture = l.texture();
        if texture == NONE || le == Vec3::ZERO {
            return le;
        }
        self.emission_textures[texture as usize]
            .texture
            .eval(self.tex_point(hit))
    }

    /// [`Light::sample`] of light `index` with the radiance at the sampled point: for a textured
    /// light its texture there ([`Scene::light_tex_point`]); `None` also where that is black.
    #[inline]
    pub fn sample_light(
        &self,
        index: usize,
        p: Vec3,
        ns: Vec3,
        u: Vec2,
        method: LightSampling,
    ) -> Option<LightSample> {
        let light = &self.lights[index];
        let mut s = light.sample(p, ns, u, method)?;
        let texture = light.texture();
        if texture != NONE {
            let at = self.light_tex_point(light, &s)?;
            let t = self.emission_textures[texture as usize].texture.eval(at);
            // A delta light's radiance is its intensity and falloff, modulated by the texture;
            // an area light's is the texture.
            s.le = if light.is_delta() { s.le * t } else { t };
            if !s.le.cmpgt(Vec3::ZERO).any() {
                return None;
            }
        }
        Some(s)
    }

    /// The material of `hit`'s primitive, seen from its back (`back`) or front: mixes and pairs
    /// resolved to one material ([`Scene::resolve`]), then its textures evaluated at the hit
    /// (borrowed when it has none).
    #[inline]
    pub fn material_at(&self, hit: &SurfaceHit, material: u32, back: bool) -> Cow<'_, Material> {
        self.shading_at(hit, material, back).material
    }

    /// [`Scene::material_at`], the normal or bump map of that material with the hit's texture
    /// coordinates (`None` without one: at once in a scene without maps), the material resolved
    /// and the coordinates computed once for both, and the [`Blend`] of a mix of model mitsuba
    /// that chose it.
    #[inline]
    pub fn shading_at(&self, hit: &SurfaceHit, material: u32, back: bool) -> Shading<'_> {
        let (material, blend) = self.resolve_blend(hit, material, back);
        let material = material as usize;
        let base = &self.materials[material];
        let textures = &self.material_textures[material];
        let map = self.normal_maps.get(material).and_then(Option::as_ref);
        if textures.is_none() && map.is_none() {
            return Shading {
                material: Cow::Borrowed(base),
                detail_map: None,
                blend,
            };
        }
        let at = self.tex_point(hit);
        let m = match textures {
            None => Cow::Borrowed(base),
            Some(t) => Cow::Owned(t.at(base, at)),
        };
        Shading {
            material: m,
            detail_map: map.map(|m| (m, at)),
            blend,
        }
    }

    /// The material that `material` is at `hit` for a path arriving on the back (`back`) or
    /// front: `material` itself when it is made of no others, else through nested mixes (pbrt-v4's
    /// `ChooseMaterial`, by the hash of [`crate::materials::mix`], so that one hit always sees
    /// one material) and two-sided pairs ([`crate::materials::two_sided`]).
    #[inline]
    pub fn resolve(&self, hit: &SurfaceHit, material: u32, back: bool) -> u32 {
        self.resolve_blend(hit, material, back).0
    }

    /// [`Scene::resolve`], and the [`Blend`] of the last mix on the way where it is of model
    /// mitsuba (whose parts are materials of their own, so it is the last step).
    #[inline]
    pub fn resolve_blend(
        &self,
        hit: &SurfaceHit,
        material: u32,
        back: bool,
    ) -> (u32, Option<Blend>) {
        let mut m = material;
        let mut blend = None;
        // The builder checked that every chain of mixes and pairs ends.
        loop {
            m = if let Some(Some(mix)) = self.mixes.get(m as usize) {
                let (next, b) = mix.choose_blend(hit.p, hit.t, m, || self.tex_point(hit));
                blend = b;
                next
            } else if let Some(Some(pair)) = self.sides.get(m as usize) {
                pair.choose(back)
            } else {
                return (m, blend);
            };
        }
    }
}
