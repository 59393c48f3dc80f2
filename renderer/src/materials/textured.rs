//! A material's textured parameters: at a hit, the textures are evaluated at its texture
//! coordinates and give the plain [`Material`] the BSDF code sees (pbrt-v4's `GetBSDF`). Untextured
//! materials never come here; the path tracer uses them as they are.
//!
//! Which parameters: `albedo` (diffuse, plastic), `reflectance` (a conductor's tint), `alpha`
//! (conductor, dielectric). A plastic's `alpha` is not texturable: its coat-albedo table is built
//! per roughness (≈ 1 ms), far too slow per hit; the scene builder rejects it with a message.
//!
//! WGSL twin: `material.wgsl` (`material_at`).

use super::{ConductorFresnel, Material};
use crate::textures::Texture;
use glam::Vec2;

/// The textures of one material's slots (`None`: the material's constant).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MaterialTextures {
    /// Diffuse or plastic albedo.
    pub albedo: Option<Texture>,
    /// Conductor reflectance (tint).
    pub reflectance: Option<Texture>,
    /// GGX α of a conductor or dielectric (the texture's scalar).
    pub alpha: Option<Texture>,
}

impl MaterialTextures {
    /// Whether a slot is textured for `base`'s kind, or why it cannot be.
    pub fn check(&self, base: &Material) -> Result<(), &'static str> {
        let ok = match base {
            Material::Diffuse(_) => self.reflectance.is_none() && self.alpha.is_none(),
            Material::Conductor(_) => self.albedo.is_none(),
            Material::Plastic(_) => {
                if self.alpha.is_some() {
                    return Err(
                        "a plastic's alpha cannot be textured (its coat-albedo table is \
                                built per roughness); use a constant",
                    );
                }
                self.reflectance.is_none()
            }
            Material::Dielectric(_) => self.albedo.is_none() && self.reflectance.is_none(),
        };
        if ok {
            Ok(())
        } else {
            Err("a texture in a slot this material does not have")
        }
    }

    /// `base` with its textured parameters evaluated at `uv`.
    pub fn at(&self, base: &Material, uv: Vec2) -> Material {
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
                    c.alpha = t.eval_scalar(uv);
                }
            }
            Material::Plastic(p) => {
                if let Some(t) = &self.albedo {
                    p.set_albedo(t.eval(uv));
                }
            }
            Material::Dielectric(d) => {
                if let Some(t) = &self.alpha {
                    d.alpha = t.eval_scalar(uv);
                }
            }
        }
        m
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::{Conductor, Dielectric, Diffuse, Plastic};
    use crate::textures::Checkerboard;
    use glam::Vec3;

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
            alpha: 0.5,
            fresnel: ConductorFresnel::Tint(Vec3::ONE),
        });
        assert_eq!(
            metal.at(&conductor, u0),
            Material::Conductor(Conductor {
                alpha: tex.eval_scalar(u0),
                fresnel: ConductorFresnel::Tint(c0),
            })
        );
        let glass = Material::Dielectric(Dielectric {
            ior: 1.5,
            alpha: 0.0,
        });
        let rough = MaterialTextures {
            alpha: Some(tex.clone()),
            ..Default::default()
        };
        assert_eq!(
            rough.at(&glass, u1),
            Material::Dielectric(Dielectric {
                ior: 1.5,
                alpha: tex.eval_scalar(u1),
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
        assert!(
            alpha
                .check(&plastic)
                .unwrap_err()
                .contains("plastic's alpha")
        );
        let diffuse = Material::Diffuse(Diffuse { albedo: Vec3::ONE });
        assert!(alpha.check(&diffuse).is_err());
        let albedo = MaterialTextures {
            albedo: tex,
            ..Default::default()
        };
        assert!(albedo.check(&diffuse).is_ok() && albedo.check(&plastic).is_ok());
    }
}
