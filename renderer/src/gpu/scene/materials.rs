//! Material records (`Material` in `materials/mod.wgsl`), one per [`Material`], and their kind tags;
//! a mix's slot holds a mix record instead (`materials/mix.wgsl`), a two-sided pair's a pair record
//! (`materials/two_sided.wgsl`), and a plastic with a textured α points
//! at its coat grid's tables instead of one table.
//!
//! A plastic's coat grid in `tables` ([`crate::materials::plastic_textured`]): the
//! [`GRID_SIZE`] node tables of [`E_TABLE_SIZE`] entries one after another, then the
//! [`GRID_SIZE`] E_avg values: 48 × 65 × 4 B = 12 480 B per plastic with a textured α (the
//! CPU's grid is the same size). Its record's `h.z` is the grid's offset and `b.w` 0;
//! `material_at` turns `h.z` into the offset of the hit's lower node table and sets `b.w` to the
//! blend weight of the next one (`coat_albedo_eval`; 0 is exactly no blend, which every other
//! plastic has).
//!
//! A plastic with Mitsuba's coupling ([`MaterialTag::PlasticMitsuba`]) has in `tables`, at its
//! record's `h.z`, the rough transmittance table ([`TRANSMITTANCE_SIZE`] entries, zeros for a
//! smooth coat), then R, w and nonlinear (0 or 1); its record holds the albedo in `a`, the tint
//! and η in `b`, the microfacet slot in `c`.
//! WGSL twin: `materials/mod.wgsl` (the record layout and the `switch` on [`MaterialTag`]),
//! `materials/mix.wgsl` (a mix's record), `materials/two_sided.wgsl` (a pair's record) and `materials/normal_map.wgsl` (the normal map's bits
//! of `h.y`, [`sides_word`]).

use super::{bits, v4};
use crate::geometry::primitive::NONE;
use crate::gpu::prelude::gpu_tags;
use crate::materials::coat_albedo::E_TABLE_SIZE;
use crate::materials::normal_map::NormalMap;
#[cfg(doc)]
use crate::materials::plastic_mitsuba::TRANSMITTANCE_SIZE;
use crate::materials::plastic_textured::{CoatGrid, GRID_SIZE};
use crate::materials::{ConductorFresnel, Distribution, Material, Microfacet};
use crate::scene::Scene;
use bytemuck::{Pod, Zeroable};

/// A material record (`Material` in `materials/mod.wgsl`): `h` = (kind, two-sided, aux, has a smooth
/// part), then four vec4 of parameters per kind (see the comment at the top of `materials/mod.wgsl`);
/// `a.w` and `c.w` hold the bits of its colour and roughness textures' ids, `NONE` where constant
/// ([`super::textures`]).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuMaterial {
    pub(crate) h: [u32; 4],
    pub(crate) a: [f32; 4],
    pub(crate) b: [f32; 4],
    pub(crate) c: [f32; 4],
    /// A fourth parameter vec4: only the principled kinds fill it (their textured parameters do
    /// not fit in three).
    pub(crate) d: [f32; 4],
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
        /// No [`Material`]: a mix's record ([`crate::materials::mix::Mix`]), which `materials/mix.wgsl`
        /// resolves before any BSDF function sees the material ([`MaterialTag::of`] never
        /// gives it; the BSDF `switch`es flag it as unknown).
        Mix => "MATERIAL_MIX",
        /// [`Material::Plastic`] coupled as Mitsuba's ([`crate::materials::plastic_mitsuba`]):
        /// one Rust variant, two programs (`materials/plastic_mitsuba.wgsl`).
        PlasticMitsuba => "MATERIAL_PLASTIC_MITSUBA",
        /// [`Material::ThinDielectric`].
        ThinDielectric => "MATERIAL_THIN_DIELECTRIC",
        /// [`Material::Principled`] (`materials/principled.wgsl`).
        Principled => "MATERIAL_PRINCIPLED",
        /// No [`Material`]: a two-sided pair's record
        /// ([`crate::materials::two_sided::TwoSided`]), which `materials/mix.wgsl`'s resolve loop
        /// resolves as it does a mix.
        TwoSided => "MATERIAL_TWO_SIDED",
        /// [`Material::PrincipledThin`] (`materials/principled_thin.wgsl`).
        PrincipledThin => "MATERIAL_PRINCIPLED_THIN",
        /// [`Material::GltfPbr`] (`materials/gltf_pbr.wgsl`).
        GltfPbr => "MATERIAL_GLTF_PBR",
    }
}

impl MaterialTag {
    /// The tag of `m`.
    pub fn of(m: &Material) -> MaterialTag {
        match m {
            Material::Diffuse(_) => MaterialTag::Diffuse,
            Material::Conductor(_) => MaterialTag::Conductor,
            Material::Plastic(p) if p.mitsuba_coat().is_some() => MaterialTag::PlasticMitsuba,
            Material::Plastic(_) => MaterialTag::Plastic,
            Material::Dielectric(_) => MaterialTag::Dielectric,
            Material::ThinDielectric(_) => MaterialTag::ThinDielectric,
            Material::Principled(_) => MaterialTag::Principled,
            Material::PrincipledThin(_) => MaterialTag::PrincipledThin,
            Material::GltfPbr(_) => MaterialTag::GltfPbr,
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
        /// [`ConductorFresnel::Complex`] with a tint other than 1: η in `a`, k in `b`, the
        /// tint's three values in `tables` at the offset whose bits are `b.w`.
        ComplexTinted => "FRESNEL_COMPLEX_TINTED",
    }
}

gpu_tags! {
    /// A rough material's microfacet distribution (the bits of `c.z` in a conductor's or a
    /// dielectric's record), in the variant order of [`Distribution`].
    pub enum DistributionTag {
        /// [`Distribution::Ggx`].
        Ggx => "DISTRIBUTION_GGX",
        /// [`Distribution::Beckmann`].
        Beckmann => "DISTRIBUTION_BECKMANN",
    }
}

impl DistributionTag {
    /// The tag of `d`.
    pub fn of(d: Distribution) -> DistributionTag {
        match d {
            Distribution::Ggx => DistributionTag::Ggx,
            Distribution::Beckmann => DistributionTag::Beckmann,
        }
    }
}

/// A microfacet record slot (`c` of a conductor or dielectric, `record_microfacet` in
/// `materials/microfacet.wgsl`): α_u, α_v, the distribution's tag as bits; `w` is the α
/// texture's slot, set by the caller.
fn microfacet_slot(m: &Microfacet) -> [f32; 4] {
    let tag = DistributionTag::of(m.distribution).gpu_tag();
    [m.alpha_u, m.alpha_v, bits(tag), 0.0]
}

/// A record's roughness slot `c.w` from the ids of the α (α_u) and α_v textures: `NONE` without
/// an α texture, else α's id in the low 16 bits and α_v's in the high 16 (`0xFFFF`: none,
/// isotropic); `textures::check_records` keeps ids below 0xFFFF.
pub(crate) fn roughness_slot(alpha: u32, alpha_v: u32) -> u32 {
    if alpha == NONE {
        return NONE;
    }
    let v = if alpha_v == NONE { 0xFFFF } else { alpha_v };
    (alpha & 0xFFFF) | (v << 16)
}

/// A glTF material's `c.w` from the ids of its roughness and metallic textures: `NONE` where
/// neither is textured, else roughness's id in the low 16 bits and metallic's in the high 16
/// (`0xFFFF`: that one constant; `textures::check_records` keeps ids below 0xFFFF).
pub(crate) fn gltf_pbr_slot(roughness: u32, metallic: u32) -> u32 {
    if roughness == NONE && metallic == NONE {
        return NONE;
    }
    let half = |id: u32| if id == NONE { 0xFFFF } else { id & 0xFFFF };
    half(roughness) | (half(metallic) << 16)
}

/// Appends `grid`'s node tables, then their E_avg, to `tables` (layout in the module doc);
/// returns its offset.
pub(crate) fn push_grid(grid: &CoatGrid, tables: &mut Vec<f32>) -> u32 {
    let offset = tables.len() as u32;
    for i in 0..GRID_SIZE {
        tables.extend_from_slice(grid.node(i).table());
    }
    tables.extend((0..GRID_SIZE).map(|i| grid.node(i).average()));
    debug_assert_eq!(
        tables.len() - offset as usize,
        GRID_SIZE * (E_TABLE_SIZE + 1)
    );
    offset
}

/// The bits a material's normal map adds to its record's `h.y` (bit 0: two-sided): bit 1 its
/// `flip_invalid_normals`, bit 2 its shadowing term, bits 3… its texture's id + 1 (0: no map).
fn sides_word(texture: u32, map: Option<&Option<NormalMap>>) -> u32 {
    match map {
        Some(Some(map)) => {
            (map.flip_invalid_normals as u32) << 1
                | (map.shadowing as u32) << 2
                | (map.height_scale.is_some() as u32) << 3
                | (texture + 1) << 4
        }
        _ => 0,
    }
}

/// The records of `scene`'s materials; a plastic's coat table (its coat grid, with a textured
/// α) is appended to `tables` and its record holds the offset; `slots` are each material's
/// texture ids and `mix_weights` each mix's weight texture id ([`super::textures`]).
pub(super) fn encode(
    scene: &Scene,
    tables: &mut Vec<f32>,
    slots: &[[u32; 3]],
    mix_weights: &[u32],
    normal_maps: &[u32],
    principled: &[[u32; 10]],
) -> Vec<GpuMaterial> {
    scene
        .materials
        .iter()
        .zip(&scene.two_sided)
        .zip(slots)
        .enumerate()
        .map(|(index, ((m, &two_sided), &[colour, alpha, alpha_v]))| {
            if let Some(Some(mix)) = scene.mixes.get(index) {
                let weight = match &mix.weight {
                    crate::textures::Texture::Constant(c) => c.x,
                    _ => 0.0,
                };
                let [first, second] = mix.materials;
                return GpuMaterial {
                    h: [
                        MaterialTag::Mix.gpu_tag(),
                        first,
                        second,
                        mix_weights[index],
                    ],
                    // a.y: Mitsuba's blend (`Mix::mitsuba`).
                    a: [weight, f32::from(u8::from(mix.mitsuba)), 0.0, bits(NONE)],
                    b: [0.0; 4],
                    c: [0.0, 0.0, 0.0, bits(NONE)],
                    d: [0.0; 4],
                };
            }
            if let Some(Some(pair)) = scene.sides.get(index) {
                return GpuMaterial {
                    h: [MaterialTag::TwoSided.gpu_tag(), pair.front, pair.back, NONE],
                    a: [0.0, 0.0, 0.0, bits(NONE)],
                    b: [0.0; 4],
                    c: [0.0, 0.0, 0.0, bits(NONE)],
                    d: [0.0; 4],
                };
            }
            let grid = scene.material_textures[index]
                .as_ref()
                .and_then(|t| t.coat_grid.as_ref());
            let kind = MaterialTag::of(m).gpu_tag();
            let smooth = m.has_smooth_part() as u32;
            let z = [0.0; 4];
            let mut r = match m {
                Material::Diffuse(d) => GpuMaterial {
                    h: [kind, two_sided as u32, 0, smooth],
                    a: v4(d.albedo, 0.0),
                    b: z,
                    c: z,
                    d: z,
                },
                Material::Conductor(c) => {
                    let (fresnel, a, b, bw) = match c.fresnel {
                        ConductorFresnel::Complex { eta, k, tint } if tint == glam::Vec3::ONE => {
                            (FresnelTag::Complex, eta, k, 0.0)
                        }
                        // The tint in `tables`, at the offset in b.w.
                        ConductorFresnel::Complex { eta, k, tint } => {
                            let offset = tables.len() as u32;
                            tables.extend(tint.to_array());
                            (FresnelTag::ComplexTinted, eta, k, bits(offset))
                        }
                        ConductorFresnel::Tint(r) => (FresnelTag::Tint, r, glam::Vec3::ZERO, 0.0),
                    };
                    GpuMaterial {
                        h: [kind, two_sided as u32, fresnel.gpu_tag(), smooth],
                        a: v4(a, 0.0),
                        b: v4(b, bw),
                        c: microfacet_slot(&c.microfacet),
                        d: z,
                    }
                }
                Material::Plastic(p) if p.mitsuba_coat().is_some() => {
                    let coat = p.mitsuba_coat().expect("Mitsuba's coupling");
                    let offset = tables.len() as u32;
                    tables.extend_from_slice(coat.table());
                    tables.extend([
                        coat.internal_reflectance(),
                        coat.specular_weight(),
                        coat.nonlinear() as u32 as f32,
                    ]);
                    GpuMaterial {
                        h: [kind, two_sided as u32, offset, smooth],
                        a: v4(p.albedo(), 0.0),
                        b: v4(p.specular(), coat.eta()),
                        c: microfacet_slot(&coat.microfacet()),
                        d: z,
                    }
                }
                Material::Plastic(p) => {
                    let coat = p.coat().expect("lumis' coupling");
                    // With a textured α every hit takes its coat from the grid (`material_at`).
                    let offset = match grid {
                        Some(g) => push_grid(g, tables),
                        None => {
                            let offset = tables.len() as u32;
                            tables.extend_from_slice(coat.table());
                            offset
                        }
                    };
                    let f0 = crate::materials::fresnel::schlick_f0_from_ior(p.ior());
                    // As `Plastic::new`: no light reaches the base of a coat that reflects all.
                    let e_avg = coat.average();
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
                        d: z,
                    }
                }
                // Never two-sided: its two sides are its two media.
                Material::Dielectric(d) => GpuMaterial {
                    h: [kind, 0, 0, smooth],
                    a: [d.ior, 0.0, 0.0, 0.0],
                    b: z,
                    c: microfacet_slot(&d.microfacet),
                    d: z,
                },
                // Two-sided as any reflection-only material, never with transmission (its two
                // sides are then its two media).
                Material::Principled(p) => {
                    let offset = tables.len() as u32;
                    let ids = principled.get(index).copied().unwrap_or([NONE; 10]);
                    tables.extend([
                        p.rates.specular,
                        p.rates.clearcoat,
                        p.rates.diffuse,
                        f32::from(u8::from(p.transmission)),
                    ]);
                    tables.extend(ids.map(bits));
                    let two_sided = two_sided && !p.transmission;
                    GpuMaterial {
                        h: [kind, two_sided as u32, offset, smooth],
                        a: v4(p.base_color, 0.0),
                        b: [p.roughness, p.anisotropic, p.metallic, p.spec_trans],
                        c: [p.spec_tint, p.sheen, p.sheen_tint, 0.0],
                        d: [p.flatness, p.clearcoat, p.clearcoat_gloss, p.eta],
                    }
                }
                // The same from both sides: never two-sided.
                Material::PrincipledThin(p) => {
                    let offset = tables.len() as u32;
                    let ids = principled.get(index).copied().unwrap_or([NONE; 10]);
                    tables.extend(p.rates.to_array());
                    tables.extend(ids[..9].iter().map(|&i| bits(i)));
                    GpuMaterial {
                        h: [kind, 0, offset, smooth],
                        a: v4(p.base_color, 0.0),
                        b: [p.roughness, p.anisotropic, p.spec_trans, p.spec_tint],
                        c: [p.sheen, p.sheen_tint, p.flatness, 0.0],
                        d: [p.diff_trans, p.eta, 0.0, 0.0],
                    }
                }
                // Two-sided as any reflection-only material; c.w its scalar textures (below).
                Material::GltfPbr(p) => GpuMaterial {
                    h: [kind, two_sided as u32, 0, smooth],
                    a: v4(p.base_color, 0.0),
                    b: [p.roughness, p.metallic, p.ior, p.specular],
                    c: v4(p.specular_color, 0.0),
                    d: z,
                },
                // The same from both sides.
                Material::ThinDielectric(t) => GpuMaterial {
                    h: [kind, 0, 0, smooth],
                    a: [t.ior, 0.0, 0.0, 0.0],
                    b: z,
                    c: z,
                    d: z,
                },
            };
            r.a[3] = bits(colour);
            r.c[3] = bits(roughness_slot(alpha, alpha_v));
            // A principled (thin or not) with a textured scalar: a roughness slot that is not
            // `NONE` makes `material_textured` see it (its ids are in `tables`; `alpha` is never
            // set for it).
            if let Material::Principled(_) | Material::PrincipledThin(_) = m
                && principled
                    .get(index)
                    .is_some_and(|ids| ids.iter().any(|&i| i != NONE))
            {
                r.c[3] = bits(0);
            }
            // A glTF material's roughness and metallic textures, both ids in c.w (its α is
            // roughness², taken at the hit, so it has no α slot).
            if let Material::GltfPbr(_) = m {
                let ids = principled.get(index).copied().unwrap_or([NONE; 10]);
                r.c[3] = bits(gltf_pbr_slot(ids[0], ids[1]));
            }
            r.h[1] |= sides_word(normal_maps[index], scene.normal_maps.get(index));
            r
        })
        .collect()
}
