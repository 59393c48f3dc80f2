//! Material records (`Material` in `material.wgsl`), one per [`Material`], and their kind tags.
//! WGSL twin: `material.wgsl` (the record layout and the `switch` on [`MaterialTag`]).

use super::{bits, v4};
use crate::gpu::prelude::gpu_tags;
use crate::materials::{ConductorFresnel, Material};
use crate::scene::Scene;
use bytemuck::{Pod, Zeroable};

/// A material record (`Material` in `material.wgsl`): `h` = (kind, two-sided, aux, has a smooth
/// part), then three vec4 of parameters per kind (see the comment at the top of `material.wgsl`);
/// `a.w` and `c.w` hold the bits of its colour and roughness textures' ids, `NONE` where constant
/// ([`super::textures`]).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuMaterial {
    pub(crate) h: [u32; 4],
    pub(crate) a: [f32; 4],
    pub(crate) b: [f32; 4],
    pub(crate) c: [f32; 4],
}

gpu_tags! {
    /// A material record's kind (`h.x`), in the variant order of [`Material`].
    pub enum MaterialTag {
        /// [`Material::Diffuse`].
        Diffuse => "MATERIAL_DIFFUSE",
        /// [`Material::Conductor`].
        Conductor => "MATERIAL_CONDUCTOR",
        /// [`Material::Plastic`].
        Plastic => "MATERIAL_PLASTIC",
        /// [`Material::Dielectric`].
        Dielectric => "MATERIAL_DIELECTRIC",
    }
}

impl MaterialTag {
    /// The tag of `m`.
    pub fn of(m: &Material) -> MaterialTag {
        match m {
            Material::Diffuse(_) => MaterialTag::Diffuse,
            Material::Conductor(_) => MaterialTag::Conductor,
            Material::Plastic(_) => MaterialTag::Plastic,
            Material::Dielectric(_) => MaterialTag::Dielectric,
        }
    }
}

gpu_tags! {
    /// A conductor's Fresnel kind (`h.z` of its record).
    pub enum FresnelTag {
        /// [`ConductorFresnel::Complex`]: η in `a`, k in `b`.
        Complex => "FRESNEL_COMPLEX",
        /// [`ConductorFresnel::Tint`]: the reflectance in `a`.
        Tint => "FRESNEL_TINT",
    }
}

/// The records of `scene`'s materials; a plastic's coat table is appended to `tables` and its
/// record holds the offset; `slots` are each material's texture ids ([`super::textures`]).
pub(super) fn encode(scene: &Scene, tables: &mut Vec<f32>, slots: &[[u32; 2]]) -> Vec<GpuMaterial> {
    scene
        .materials
        .iter()
        .zip(&scene.two_sided)
        .zip(slots)
        .map(|((m, &two_sided), &[colour, alpha])| {
            let kind = MaterialTag::of(m).gpu_tag();
            let smooth = m.has_smooth_part() as u32;
            let z = [0.0; 4];
            let mut r = match m {
                Material::Diffuse(d) => GpuMaterial {
                    h: [kind, two_sided as u32, 0, smooth],
                    a: v4(d.albedo, 0.0),
                    b: z,
                    c: z,
                },
                Material::Conductor(c) => {
                    let (fresnel, a, b) = match c.fresnel {
                        ConductorFresnel::Complex { eta, k } => (FresnelTag::Complex, eta, k),
                        ConductorFresnel::Tint(r) => (FresnelTag::Tint, r, glam::Vec3::ZERO),
                    };
                    GpuMaterial {
                        h: [kind, two_sided as u32, fresnel.gpu_tag(), smooth],
                        a: v4(a, 0.0),
                        b: v4(b, 0.0),
                        c: [c.alpha, 0.0, 0.0, 0.0],
                    }
                }
                Material::Plastic(p) => {
                    let offset = tables.len() as u32;
                    tables.extend_from_slice(p.coat().table());
                    let f0 = crate::materials::fresnel::schlick_f0_from_ior(p.ior());
                    // As `Plastic::new`: no light reaches the base of a coat that reflects all.
                    let e_avg = p.coat().average();
                    let diffuse_norm = if 1.0 - e_avg > 1e-6 {
                        1.0 / (1.0 - e_avg)
                    } else {
                        0.0
                    };
                    GpuMaterial {
                        h: [kind, two_sided as u32, offset, smooth],
                        a: v4(p.albedo(), 0.0),
                        b: v4(p.specular(), 0.0),
                        c: [p.alpha(), f0, diffuse_norm, 0.0],
                    }
                }
                // Never two-sided: its two sides are its two media.
                Material::Dielectric(d) => GpuMaterial {
                    h: [kind, 0, 0, smooth],
                    a: [d.ior, d.alpha, 0.0, 0.0],
                    b: z,
                    c: z,
                },
            };
            r.a[3] = bits(colour);
            r.c[3] = bits(alpha);
            r
        })
        .collect()
}
