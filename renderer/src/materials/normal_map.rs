//! Normal maps, as Mitsuba 3.9.1's `normalmap` defines them (`src/bsdfs/normalmap.cpp`,
//! `normalmap_helpers.h`): an RGB texture whose value `c` at a hit encodes the shading normal
//! `n = 2c − 1` in the hit's shading frame, whose first axis runs along ∂p/∂u
//! (`geometry/tangent.rs`); the material then sees the *perturbed* frame about `n`, with three
//! rules of Mitsuba's on top:
//!
//! - **Sides** (always): a light direction counts only where the unperturbed and the perturbed
//!   frame put it on the same side (their cosines' product > 0); elsewhere the BSDF and its pdf
//!   are zero and a sample there is no sample.
//! - **Shadowing** (`use_shadowing_function`, default on): the BSDF value and a sample's weight
//!   (not the pdf) are multiplied by Estevez et al.'s microfacet shadowing term
//!   `2 / (1 + √(1 + α²·tan²θ))`, θ the light direction's angle in the unperturbed frame and
//!   `α² = min(tan²θ_n / 8, 1)` from the tilt θ_n of the perturbed normal (Ray Tracing Gems,
//!   2019: it softens the "bump terminator").
//! - **Flip** (`flip_invalid_normals`, default on): where the viewer is on the other side of the
//!   perturbed normal than of the unperturbed one, the perturbed normal is mirrored about the
//!   unperturbed one (its tangent components negated), so that the surface faces the viewer.
//!
//! On the back of a two-sided material the map is read in the front's frame mirrored through the
//! surface ([`seen_from`]), which is what Mitsuba's `twosided` around a `normalmap` renders.
//!
//! A bump map (Mitsuba's `bumpmap`, [`super::bump_map`]) is the same map with another source of
//! the normal: a height texture's gradient instead of a texel ([`NormalMap::height_scale`]).
//!
//! The perturbed frame's first axis is the unperturbed first axis made orthogonal to `n`
//! (Gram–Schmidt), as Mitsuba's. Where Mitsuba's construction is undefined (a texel `(½, ½, ½)`,
//! `n` of length 0, or `n` along the first axis) lumis keeps the unperturbed normal, resp. any
//! tangent, instead of a NaN. A texel that encodes the unperturbed normal exactly (`(½, ½, 1)`)
//! changes nothing, and the path keeps its usual frame: an identity map leaves every image bit
//! for bit as it was (an isotropic BSDF is the same in any frame about its normal).
//! WGSL twin: `materials/normal_map.wgsl`.

use super::{BsdfSample, Material};
use crate::math::Frame;
use crate::textures::Texture;
use glam::{Vec2, Vec3};

/// A material's normal map.
#[derive(Clone, Debug, PartialEq)]
pub struct NormalMap {
    /// The encoded normals `(n + 1)/2` (read as linear RGB: Mitsuba's scenes load them `raw`).
    pub texture: Texture,
    /// Mitsuba's `flip_invalid_normals`.
    pub flip_invalid_normals: bool,
    /// Mitsuba's `use_shadowing_function`.
    pub shadowing: bool,
    /// `Some(scale)`: the texture is a height field whose gradient times `scale` tilts the
    /// normal (Mitsuba's `bumpmap` and its `scale`), not encoded normals.
    pub height_scale: Option<f32>,
}

impl NormalMap {
    /// The normal a texel encodes, `2c − 1` (not normalised).
    #[inline]
    pub fn decode(texel: Vec3) -> Vec3 {
        2.0 * texel - Vec3::ONE
    }

    /// The frame the material sees at a hit where the map gives the normal `n` (in the
    /// unperturbed frame, not necessarily unit: [`NormalMap::decode`] of a texel, or a bump
    /// map's [`super::bump_map::local_normal`]), and the perturbation that goes with it; `None`
    /// where the map leaves the normal as it is (the path then keeps its usual frame). `base`
    /// gives the unperturbed shading frame, first axis along ∂p/∂u (only asked for where the map
    /// tilts the normal); `wo_world` points towards the viewer.
    pub fn perturb(
        &self,
        n: Vec3,
        base: impl FnOnce() -> Frame,
        wo_world: Vec3,
    ) -> Option<(Frame, Perturbation)> {
        let mut n = n;
        if n.x == 0.0 && n.y == 0.0 && n.z > 0.0 {
            return None;
        }
        let len = n.length();
        if !(len > 0.0 && len.is_finite()) {
            return None;
        }
        let base = base();
        if self.flip_invalid_normals {
            let wo = base.to_local(wo_world);
            if wo.z * wo.dot(n) <= 0.0 {
                n = Vec3::new(-n.x, -n.y, n.z);
            }
        }
        let n = n / len;
        let s = Vec3::X - n * n.x;
        let s_len = s.length();
        let s = if s_len > 0.0 {
            s / s_len
        } else {
            Frame::from_normal(n).s
        };
        let t = n.cross(s);
        let frame = Frame {
            s: base.to_world(s),
            t: base.to_world(t),
            n: base.to_world(n),
        };
        // The unperturbed normal (local +z) in the perturbed frame.
        let up = Vec3::new(s.z, t.z, n.z);
        let alpha2 = (0.125 * tan2(up.z)).min(1.0);
        Some((
            frame,
            Perturbation {
                up,
                alpha2: if self.shadowing { alpha2 } else { 0.0 },
            },
        ))
    }
}

/// The frame a normal map is read in: `frame`, the shading frame of the side the path sees
/// (first axis along ∂p/∂u), except on the back of a two-sided material (`back`), where
/// `frame`'s normal and second axis are the front's negated: there its second axis is turned
/// back, so that the map is read in the front's frame mirrored through the surface, as Mitsuba's
/// `twosided` around a `normalmap` does (it mirrors the directions it hands in): a map tilted
/// towards +t tilts towards +t on both sides. A left-handed frame, which no BSDF here minds
/// (each is even in its second tangent axis).
pub fn seen_from(frame: Frame, back: bool) -> Frame {
    if back {
        Frame {
            t: -frame.t,
            ..frame
        }
    } else {
        frame
    }
}

/// tan²θ of a direction with cosθ = `cos`.
#[inline]
fn tan2(cos: f32) -> f32 {
    (1.0 - cos * cos).max(0.0) / (cos * cos)
}

/// A normal map's rules at one hit, for directions in the perturbed frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Perturbation {
    /// The unperturbed shading normal, in the perturbed frame.
    up: Vec3,
    /// The shadowing term's α² (0 without it: the term is then 1).
    alpha2: f32,
}

impl Perturbation {
    /// What the BSDF value towards `wi` (perturbed frame) is multiplied by: 0 on the wrong side
    /// of the unperturbed frame, else the shadowing term.
    #[inline]
    pub fn factor(&self, wi: Vec3) -> f32 {
        let cos = wi.dot(self.up);
        // Also 0 for a NaN product.
        if wi.z * cos <= 0.0 || (wi.z * cos).is_nan() {
            return 0.0;
        }
        if self.alpha2 == 0.0 {
            return 1.0;
        }
        2.0 / (1.0 + (1.0 + self.alpha2 * tan2(cos)).sqrt())
    }
}

/// The BSDF of one path vertex: its material in the frame the path uses there, under the normal
/// map's rules where it has one. The one place those rules meet the integrator.
#[derive(Clone, Copy, Debug)]
pub struct VertexBsdf<'a> {
    /// The material, evaluated at the hit (textures, mix).
    pub material: &'a Material,
    /// The normal map's perturbation, if the material has one that tilts the normal here.
    pub perturbation: Option<Perturbation>,
}

impl VertexBsdf<'_> {
    /// [`Material::eval_specialised`] times the perturbation's factor.
    #[inline(always)]
    pub fn eval<const TRANSMISSION: bool>(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        let f = self.material.eval_specialised::<TRANSMISSION>(wo, wi);
        match &self.perturbation {
            None => f,
            Some(p) => match p.factor(wi) {
                0.0 => Vec3::ZERO,
                k => f * k,
            },
        }
    }

    /// [`Material::pdf_specialised`], zero on the side the perturbation rules out.
    #[inline(always)]
    pub fn pdf<const TRANSMISSION: bool>(&self, wo: Vec3, wi: Vec3) -> f32 {
        match &self.perturbation {
            Some(p) if p.factor(wi) == 0.0 => 0.0,
            _ => self.material.pdf_specialised::<TRANSMISSION>(wo, wi),
        }
    }

    /// [`Material::sample_specialised`], its weight times the perturbation's factor; no sample on
    /// the side the perturbation rules out.
    #[inline(always)]
    pub fn sample<const TRANSMISSION: bool>(
        &self,
        wo: Vec3,
        u_lobe: f32,
        u: Vec2,
    ) -> Option<BsdfSample> {
        let mut s = self
            .material
            .sample_specialised::<TRANSMISSION>(wo, u_lobe, u)?;
        if let Some(p) = &self.perturbation {
            match p.factor(s.wi) {
                0.0 => return None,
                k => s.weight *= k,
            }
        }
        Some(s)
    }
}

#[cfg(test)]
#[path = "normal_map_tests.rs"]
mod tests;
