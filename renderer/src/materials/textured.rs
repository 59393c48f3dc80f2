//! A material's textured parameters: at a hit, the textures are evaluated at its texture
//! coordinates and give the plain [`Material`] the BSDF code sees (pbrt-v4's `GetBSDF`). Untextured
//! materials never come here; the path tracer uses them as they are.
//!
//! Which parameters: `albedo` (diffuse, plastic, and the principled kinds' and glTF material's base
//! colour), `reflectance` (a conductor's tint), `alpha` (conductor, plastic, dielectric), and the
//! scalar slots of the principled kinds and the glTF material (`principled`). A plastic's
//! coat-albedo table depends on its α and takes ≈ 1 ms to build, far too slow per hit:
//! [`MaterialTextures::new`] builds the plastic's tables on a grid of α once, and a hit blends the
//! two around its α ([`super::plastic_textured`]).
//!
//! WGSL twin: `materials/mod.wgsl` (`material_at`).

use super::gltf_pbr::GltfParam;
use super::plastic_textured::CoatGrid;
use super::principled::PrincipledParam;
use super::principled_thin::ThinParam;
use super::{ConductorFresnel, Material, Microfacet, Plastic};
use crate::textures::{TexPoint, Texture};

/// The textures of one material's slots (`None`: the material's constant).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MaterialTextures {
    /// Diffuse or plastic albedo.
    pub albedo: Option<Texture>,
    /// Conductor reflectance (tint).
    pub reflectance: Option<Texture>,
    /// GGX α of a conductor, plastic or dielectric (the texture's scalar); α_u where `alpha_v`
    /// is set.
    pub alpha: Option<Texture>,
    /// α_v of an anisotropic conductor or dielectric (with `alpha` as α_u).
    pub alpha_v: Option<Texture>,
    /// A plastic with a textured α: its coat tables on the α grid, for its F0.
    pub(crate) coat_grid: Option<CoatGrid>,
    /// A principled's scalar parameters, in [`PrincipledParam::ALL`]'s order, a thin
    /// principled's in [`ThinParam::ALL`]'s or a glTF material's in [`GltfParam::ALL`]'s (the
    /// base colour of each is `albedo`).
    pub principled: [Option<Texture>; 10],
}

impl MaterialTextures {
    /// The textures of `base`'s slots, after [`MaterialTextures::check`]; a plastic with a
    /// textured α gets its coat grid here (≈ 60 ms of work, at scene build).
    pub fn new(
        albedo: Option<Texture>,
        reflectance: Option<Texture>,
        alpha: Option<Texture>,
        alpha_v: Option<Texture>,
        base: &Material,
    ) -> Result<MaterialTextures, &'static str> {
        let mut t = MaterialTextures {
            albedo,
            reflectance,
            alpha,
            alpha_v,
            coat_grid: None,
            principled: Default::default(),
        };
        t.check(base)?;
        if let (Material::Plastic(p), Some(_)) = (base, &t.alpha) {
            t.coat_grid = Some(CoatGrid::new(p.f0()));
        }
        Ok(t)
    }

    /// Whether a slot is textured for `base`'s kind, or why it cannot be.
    pub fn check(&self, base: &Material) -> Result<(), &'static str> {
        // α_v only beside an α_u, and only where roughness may be anisotropic.
        let pair = self.alpha_v.is_none()
            || (self.alpha.is_some()
                && matches!(base, Material::Conductor(_) | Material::Dielectric(_)));
        let principled = matches!(
            base,
            Material::Principled(_) | Material::PrincipledThin(_) | Material::GltfPbr(_)
        );
        let ok = pair
            && (principled || self.principled.iter().all(Option::is_none))
            && match base {
                Material::Diffuse(_) => self.reflectance.is_none() && self.alpha.is_none(),
                Material::Conductor(_) => self.albedo.is_none(),
                // Mitsuba's coupling tabulates one α.
                Material::Plastic(p) => {
                    self.reflectance.is_none() && (self.alpha.is_none() || p.coat().is_some())
                }
                Material::Dielectric(_) => self.albedo.is_none() && self.reflectance.is_none(),
                Material::ThinDielectric(_) => {
                    self.albedo.is_none() && self.reflectance.is_none() && self.alpha.is_none()
                }
                // Its base colour in `albedo`, the rest in `principled`.
                Material::Principled(_) | Material::PrincipledThin(_) | Material::GltfPbr(_) => {
                    self.reflectance.is_none() && self.alpha.is_none()
                }
            };
        if ok {
            Ok(())
        } else {
            Err("a texture in a slot this material does not have")
        }
    }

    /// `base` with its textured parameters evaluated at `uv` (a [`TexPoint`], or texture
    /// coordinates off any mesh).
    pub fn at<'a>(&self, base: &Material, uv: impl Into<TexPoint<'a>>) -> Material {
        let uv = uv.into();
        let mut m = base.clone();
        match &mut m {
            Material::Diffuse(d) => {
                if let Some(t) = &self.albedo {
                    d.albedo = t.eval(uv);
                }
            }
            Material::Conductor(c) => {
                if let Some(t) = &self.reflectance {
                    c.fresnel = ConductorFresnel::Tint(t.eval(uv));
                }
                if let Some(t) = &self.alpha {
                    c.microfacet = self.microfacet_at(c.microfacet, t, uv);
                }
            }
            Material::Plastic(p) => {
                if let Some(t) = &self.albedo {
                    p.set_albedo(t.eval(uv));
                }
                match (&self.alpha, &self.coat_grid) {
                    (Some(t), Some(grid)) => p.set_alpha_from_grid(t.eval_scalar(uv), grid),
                    // Slots set by hand, without `new`: correct (the exact table), but slow.
                    (Some(t), None) => {
                        *p = Plastic::new(p.albedo(), t.eval_scalar(uv), p.ior(), p.specular())
                    }
                    (None, _) => {}
                }
            }
            Material::Dielectric(d) => {
                if let Some(t) = &self.alpha {
                    d.microfacet = self.microfacet_at(d.microfacet, t, uv);
                }
            }
            Material::ThinDielectric(_) => {}
            Material::Principled(p) => {
                if let Some(t) = &self.albedo {
                    p.base_color = t.eval(uv);
                }
                for (param, t) in PrincipledParam::ALL.into_iter().zip(&self.principled) {
                    if let Some(t) = t {
                        param.set(p, t.eval_scalar(uv));
                    }
                }
            }
            Material::PrincipledThin(p) => {
                if let Some(t) = &self.albedo {
                    p.base_color = t.eval(uv);
                }
                for (param, t) in ThinParam::ALL.into_iter().zip(&self.principled) {
                    if let Some(t) = t {
                        param.set(p, t.eval_scalar(uv));
                    }
                }
            }
            // α = roughness² is taken at the hit, after the texture's filtering (glTF's order).
            Material::GltfPbr(p) => {
                if let Some(t) = &self.albedo {
                    p.base_color = t.eval(uv);
                }
                for (param, t) in GltfParam::ALL.into_iter().zip(&self.principled) {
                    if let Some(t) = t {
                        param.set(p, t.eval_scalar(uv));
                    }
                }
            }
        }
        m
    }

    /// `base`'s distribution with the roughness of textures `alpha` (α_u) and `alpha_v` at `uv`;
    /// isotropic without `alpha_v`.
    fn microfacet_at(&self, base: Microfacet, alpha: &Texture, uv: TexPoint) -> Microfacet {
        let u = alpha.eval_scalar(uv);
        match &self.alpha_v {
            Some(v) => Microfacet::new(base.distribution, u, v.eval_scalar(uv)),
            None => base.with_alpha(u),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::{Conductor, Dielectric, Diffuse, Microfacet, Plastic};
    use crate::textures::Checkerboard;
    use glam::{Vec2, Vec3};

    fn checker(a: Vec3, b: Vec3) -> Texture {
        Texture::Checkerboard(Checkerboard {
            color0: a,
            color1: b,
            ..Checkerboard::default()
        })
    }

    #[test]
    fn textured_slots_take_the_texture_value_at_the_uv() {
        let tex = checker(Vec3::new(0.1, 0.2, 0.3), Vec3::new(0.7, 0.8, 0.9));
        let (u0, u1) = (Vec2::new(0.25, 0.25), Vec2::new(0.75, 0.25));
        let (c0, c1) = (tex.eval(u0), tex.eval(u1));
        assert_ne!(c0, c1, "the two points lie on different squares");
        let albedo = MaterialTextures {
            albedo: Some(tex.clone()),
            ..Default::default()
        };
        let diffuse = Material::Diffuse(Diffuse {
            albedo: Vec3::splat(0.5),
        });
        for (uv, c) in [(u0, c0), (u1, c1)] {
            assert_eq!(
                albedo.at(&diffuse, uv),
                Material::Diffuse(Diffuse { albedo: c })
            );
        }
        let plastic = Plastic::new(Vec3::splat(0.5), 0.2, 1.5, Vec3::ONE);
        let Material::Plastic(p) = albedo.at(&Material::Plastic(plastic.clone()), u1) else {
            panic!()
        };
        assert_eq!(p, Plastic::new(c1, 0.2, 1.5, Vec3::ONE));

        let metal = MaterialTextures {
            reflectance: Some(tex.clone()),
            alpha: Some(tex.clone()),
            ..Default::default()
        };
        let conductor = Material::Conductor(Conductor {
            microfacet: Microfacet::ggx(0.5),
            fresnel: ConductorFresnel::Tint(Vec3::ONE),
        });
        assert_eq!(
            metal.at(&conductor, u0),
            Material::Conductor(Conductor {
                microfacet: Microfacet::ggx(tex.eval_scalar(u0)),
                fresnel: ConductorFresnel::Tint(c0),
            })
        );
        let glass = Material::Dielectric(Dielectric {
            ior: 1.5,
            microfacet: Microfacet::ggx(0.0),
        });
        let rough = MaterialTextures {
            alpha: Some(tex.clone()),
            ..Default::default()
        };
        assert_eq!(
            rough.at(&glass, u1),
            Material::Dielectric(Dielectric {
                ior: 1.5,
                microfacet: Microfacet::ggx(tex.eval_scalar(u1)),
            })
        );
    }

    #[test]
    fn slots_a_material_lacks_are_refused() {
        let tex = Some(Texture::Constant(Vec3::splat(0.5)));
        let plastic = Material::Plastic(Plastic::new(Vec3::splat(0.5), 0.2, 1.5, Vec3::ONE));
        let alpha = MaterialTextures {
            alpha: tex.clone(),
            ..Default::default()
        };
        let diffuse = Material::Diffuse(Diffuse { albedo: Vec3::ONE });
        assert!(alpha.check(&diffuse).is_err());
        let reflectance = MaterialTextures {
            reflectance: tex.clone(),
            ..Default::default()
        };
        assert!(reflectance.check(&plastic).is_err());
        let albedo = MaterialTextures {
            albedo: tex,
            ..Default::default()
        };
        assert!(albedo.check(&diffuse).is_ok() && albedo.check(&plastic).is_ok());
        assert!(
            alpha.check(&plastic).is_ok(),
            "a plastic's alpha is texturable"
        );
    }

    #[test]
    fn a_textured_plastic_alpha_takes_the_texture_value_and_the_grid_coat() {
        let tex = checker(Vec3::splat(0.03), Vec3::splat(0.6));
        let base = Plastic::new(Vec3::splat(0.5), 0.3, 1.5, Vec3::ONE);
        let base_m = Material::Plastic(base.clone());
        let t = MaterialTextures::new(None, None, Some(tex.clone()), None, &base_m).unwrap();
        let grid = t
            .coat_grid
            .as_ref()
            .expect("a plastic with a textured alpha has a grid");
        assert_eq!(grid.f0(), base.f0());
        for uv in [Vec2::new(0.25, 0.25), Vec2::new(0.75, 0.25)] {
            let Material::Plastic(p) = t.at(&base_m, uv) else {
                panic!()
            };
            let a = tex.eval_scalar(uv);
            assert_eq!(p.alpha(), a);
            assert_eq!(
                p.coat(),
                Some(&grid.coat(a)),
                "the coat comes from the grid"
            );
            // The untextured parameters are the base's.
            assert_eq!(
                (p.albedo(), p.ior(), p.specular()),
                (base.albedo(), 1.5, Vec3::ONE)
            );
        }
        // Without the grid (slots set by hand) the hit builds the exact table instead.
        let by_hand = MaterialTextures {
            alpha: Some(tex.clone()),
            ..Default::default()
        };
        let uv = Vec2::new(0.75, 0.25);
        assert_eq!(
            by_hand.at(&base_m, uv),
            Material::Plastic(Plastic::new(
                Vec3::splat(0.5),
                tex.eval_scalar(uv),
                1.5,
                Vec3::ONE
            ))
        );
        // Other materials and an untextured plastic alpha get no grid.
        let albedo_only =
            MaterialTextures::new(Some(tex.clone()), None, None, None, &base_m).unwrap();
        assert!(albedo_only.coat_grid.is_none());
        let glass = Material::Dielectric(Dielectric {
            ior: 1.5,
            microfacet: Microfacet::ggx(0.1),
        });
        let rough = MaterialTextures::new(None, None, Some(tex), None, &glass).unwrap();
        assert!(rough.coat_grid.is_none());
        let err = MaterialTextures::new(
            None,
            Some(checker(Vec3::ONE, Vec3::ZERO)),
            None,
            None,
            &glass,
        );
        assert!(err.is_err());
    }
}
