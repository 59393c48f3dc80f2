//! The WGSL prelude: every constant and kind tag the shaders share with Rust, written as
//! `const NAME: TYPE = VALUE;` from the Rust definitions themselves and put in front of every
//! program by [`super::shader::library_source`]. A change on the Rust side therefore reaches the
//! shaders, and a hand-written copy left in a module is a redefinition that naga rejects.
//!
//! Kind tags (materials, lights, shapes, strategies, …) are `#[repr(u32)]` enums declared with
//! `gpu_tags!` next to the record encoder that writes them (`gpu/scene/`): the encoder stores
//! `tag as u32`, the prelude lists [`Tag::ALL`](super::scene::MaterialTag::ALL) under the names
//! the WGSL `switch`es use. What a `switch` does with a tag no case knows is in `gpu/prelude.wgsl`: it
//! flags the sample, which the film counts as non-finite.
//! WGSL twin: `gpu/prelude.wgsl`.

use super::scene::{
    BVH2_STACK_SIZE, CWBVH_STACK_SIZE, CameraTag, ChannelTag, DistributionTag, FilterTag,
    FresnelTag, HeuristicTag, LightSamplingTag, LightSelectionTag, LightTag, MaterialTag,
    SamplerTag, ShapeTag, StrategyTag, TextureTag, WrapTag, textures,
};
use crate::camera::filter;
use crate::geometry::{mesh_attributes, primitive, ray, wide_bvh};
use crate::lights::{polygon, sphere};
use crate::materials::{beckmann, coat_albedo, ggx, mix, plastic_mitsuba, plastic_textured};
use crate::sampler::{dim, owen, zsobol};
use crate::sampling::{
    self, elliptic, projected_solid_angle, spherical_ellipse, spherical_rectangle,
};
use crate::textures::LUMINANCE_WEIGHTS;

/// A constant's value, with its WGSL type.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    /// `f32`; finite (WGSL has no literal for infinity or NaN).
    F32(f32),
    /// `u32`.
    U32(u32),
    /// `array<u32, N>`: a table (WGSL indexes a `const` array with a runtime index).
    U32Array(&'static [u32]),
}

/// One `const NAME: TYPE = VALUE;` of the prelude.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Constant {
    /// The WGSL name.
    pub name: &'static str,
    /// The value.
    pub value: Value,
}

impl Constant {
    /// The WGSL declaration. An f32 is written with the shortest digits that round-trip (`{:e}`)
    /// and the `f` suffix, so naga rounds the decimal straight to f32 (an abstract float would
    /// round twice, through f64): the shader holds the same bits as Rust.
    pub fn wgsl(&self) -> String {
        match self.value {
            Value::F32(v) => {
                assert!(v.is_finite(), "{}: WGSL has no literal for {v}", self.name);
                format!("const {}: f32 = {v:e}f;", self.name)
            }
            Value::U32(v) => format!("const {}: u32 = {v}u;", self.name),
            Value::U32Array(a) => {
                let items: Vec<String> = a.iter().map(|v| format!("{v}u")).collect();
                format!(
                    "const {}: array<u32, {}> = array<u32, {}>({});",
                    self.name,
                    a.len(),
                    a.len(),
                    items.join(", ")
                )
            }
        }
    }
}

/// A count or size that must fit a u32 (checked at compile time where used in a constant).
const fn count(n: usize) -> u32 {
    assert!(n <= u32::MAX as usize);
    n as u32
}

/// Declares a `#[repr(u32)]` enum of GPU kind tags with `ALL`, every variant and the name of its
/// WGSL constant: the single definition the record encoder and the prelude both read. Variants
/// take the discriminants 0, 1, … in order.
macro_rules! gpu_tags {
    (
        $(#[$meta:meta])*
        $vis:vis enum $name:ident {
            $($(#[$vmeta:meta])* $variant:ident => $wgsl:literal,)+
        }
    ) => {
        $(#[$meta])*
        #[repr(u32)]
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        $vis enum $name {
            $($(#[$vmeta])* $variant,)+
        }

        impl $name {
            /// Every tag with the name of its WGSL constant (in the generated prelude).
            pub const ALL: &'static [($name, &'static str)] = &[$(($name::$variant, $wgsl),)+];

            /// The value GPU records and parameters hold.
            pub const fn gpu_tag(self) -> u32 {
                self as u32
            }
        }

        impl From<$name> for u32 {
            fn from(t: $name) -> u32 {
                t.gpu_tag()
            }
        }
    };
}
pub(crate) use gpu_tags;

fn f32c(name: &'static str, v: f32) -> Constant {
    Constant {
        name,
        value: Value::F32(v),
    }
}

fn u32c(name: &'static str, v: u32) -> Constant {
    Constant {
        name,
        value: Value::U32(v),
    }
}

fn u32a(name: &'static str, v: &'static [u32]) -> Constant {
    Constant {
        name,
        value: Value::U32Array(v),
    }
}

fn tags<T: Copy + Into<u32>>(all: &[(T, &'static str)]) -> impl Iterator<Item = Constant> {
    all.iter().map(|&(t, name)| u32c(name, t.into()))
}

/// Every constant of the prelude, from its Rust definition.
pub fn constants() -> Vec<Constant> {
    use std::f32::consts;
    let mut c = vec![
        // math.wgsl
        f32c("PI", consts::PI),
        f32c("INV_PI", consts::FRAC_1_PI),
        f32c("TAU", consts::TAU),
        f32c("FRAC_PI_2", consts::FRAC_PI_2),
        f32c("FRAC_PI_4", consts::FRAC_PI_4),
        f32c("FRAC_1_SQRT_2", consts::FRAC_1_SQRT_2),
        // Rust's runtime sqrt (correctly rounded); a GPU's sqrt need not be.
        f32c("SQRT_FRAC_PI_2", consts::FRAC_PI_2.sqrt()),
        u32c("NONE", primitive::NONE),
        f32c("ONE_MINUS_EPSILON", sampling::ONE_MINUS_EPSILON),
        f32c("F32_EPSILON", f32::EPSILON),
        // The pixel filter.
        u32c("FILTER_MAX_STEPS", filter::MAX_STEPS),
        f32c("FILTER_TOLERANCE", filter::TOLERANCE),
        u32c("FILTER_MITCHELL_BREAKS", filter::MITCHELL_BREAKS as u32),
        f32c("FILTER_GL_X0", filter::GAUSS_LEGENDRE[0].0),
        f32c("FILTER_GL_X1", filter::GAUSS_LEGENDRE[1].0),
        f32c("FILTER_GL_X2", filter::GAUSS_LEGENDRE[2].0),
        f32c("FILTER_GL_X3", filter::GAUSS_LEGENDRE[3].0),
        f32c("FILTER_GL_W0", filter::GAUSS_LEGENDRE[0].1),
        f32c("FILTER_GL_W1", filter::GAUSS_LEGENDRE[1].1),
        f32c("FILTER_GL_W2", filter::GAUSS_LEGENDRE[2].1),
        f32c("FILTER_GL_W3", filter::GAUSS_LEGENDRE[3].1),
        // Materials.
        f32c("SMOOTH_ALPHA", ggx::SMOOTH_ALPHA),
        f32c("BECKMANN_SAMPLE_TOLERANCE", beckmann::SAMPLE_TOLERANCE),
        u32c("BECKMANN_SAMPLE_MAX_STEPS", beckmann::SAMPLE_MAX_STEPS),
        u32c("E_TABLE_SIZE", const { count(coat_albedo::E_TABLE_SIZE) }),
        u32c(
            "COAT_GRID_SIZE",
            const { count(plastic_textured::GRID_SIZE) },
        ),
        f32c("COAT_GRID_LN_FIRST", plastic_textured::ln_first()),
        u32c(
            "TRANSMITTANCE_SIZE",
            const { count(plastic_mitsuba::TRANSMITTANCE_SIZE) },
        ),
        // Mixes: SplitMix64's increment as (lo, hi) u32 halves.
        u32c("MIX_GOLDEN_LO", mix::GOLDEN as u32),
        u32c("MIX_GOLDEN_HI", (mix::GOLDEN >> 32) as u32),
        // The samplers (and the mixes' finaliser, `owen::mix64`): 64-bit constants as halves.
        u32c("MIX64_M1_LO", owen::MIX64_M1 as u32),
        u32c("MIX64_M1_HI", (owen::MIX64_M1 >> 32) as u32),
        u32c("MIX64_M2_LO", owen::MIX64_M2 as u32),
        u32c("MIX64_M2_HI", (owen::MIX64_M2 >> 32) as u32),
        u32c("HASH32_M1", owen::HASH32_M1),
        u32c("HASH32_M2", owen::HASH32_M2),
        u32c("OWEN_LK_MUL_A", owen::LK_MUL_A),
        u32c("OWEN_LK_MUL_B", owen::LK_MUL_B),
        u32c("OWEN_LK_MUL_C", owen::LK_MUL_C),
        u32a("ZSOBOL_PERMUTATIONS", &zsobol::PERMUTATION_WORDS),
        u32c("ZSOBOL_EPOCH_LOG2", zsobol::EPOCH_LOG2),
        u32c("ZSOBOL_TILE_LOG2", zsobol::TILE_LOG2),
        u32c("ZSOBOL_INDEX_DIGITS", zsobol::INDEX_DIGITS),
        u32c("DIM_CAMERA", dim::CAMERA),
        u32c("DIM_FIRST_BOUNCE", dim::FIRST_BOUNCE),
        u32c("DIM_PER_BOUNCE", dim::PER_BOUNCE),
        u32c("DIM_MIXTURE", dim::MIXTURE),
        u32c("DIM_LIGHT_SELECT", dim::LIGHT_SELECT),
        u32c("DIM_LIGHT", dim::LIGHT),
        u32c("DIM_BSDF_LOBE", dim::BSDF_LOBE),
        u32c("DIM_BSDF", dim::BSDF),
        u32c("DIM_RR", dim::RR),
        u32c("DIM_LENS", dim::LENS),
        // Lights and their warps.
        f32c("SMALL_CONE_SIN2", sphere::SMALL_CONE_SIN2),
        f32c("MAX_EDGE_COS", spherical_rectangle::MAX_EDGE_COS),
        u32c(
            "MAX_NEWTON_STEPS",
            const { count(spherical_rectangle::MAX_NEWTON_STEPS) },
        ),
        f32c(
            "MIN_SPHERICAL_SAMPLE_AREA",
            sampling::MIN_SPHERICAL_SAMPLE_AREA,
        ),
        f32c(
            "MAX_SPHERICAL_SAMPLE_AREA",
            sampling::MAX_SPHERICAL_SAMPLE_AREA,
        ),
        u32c(
            "MAX_SOLID_ANGLE_TRIANGLES",
            const { count(polygon::MAX_SOLID_ANGLE_TRIANGLES) },
        ),
        f32c("MIN_COSINE_WEIGHT", sampling::MIN_COSINE_WEIGHT),
        f32c(
            "MIN_ELLIPSE_SOLID_ANGLE",
            spherical_ellipse::MIN_ELLIPSE_SOLID_ANGLE,
        ),
        f32c(
            "MAX_ELLIPSE_SOLID_ANGLE",
            spherical_ellipse::MAX_ELLIPSE_SOLID_ANGLE,
        ),
        f32c("MAX_ELLIPSE_TAN", spherical_ellipse::MAX_ELLIPSE_TAN),
        f32c(
            "MAX_ELLIPSE_RELATIVE_RADIUS",
            spherical_ellipse::MAX_ELLIPSE_RELATIVE_RADIUS,
        ),
        u32c(
            "MAX_ELLIPSE_NEWTON_STEPS",
            const { count(spherical_ellipse::MAX_ELLIPSE_NEWTON_STEPS) },
        ),
        f32c(
            "ELLIPSE_NEWTON_TOLERANCE",
            spherical_ellipse::ELLIPSE_NEWTON_TOLERANCE,
        ),
        u32c(
            "MAX_CARLSON_STEPS",
            const { count(elliptic::MAX_CARLSON_STEPS) },
        ),
        f32c("CARLSON_RF_Q", elliptic::RF_Q),
        f32c("CARLSON_RJ_Q", elliptic::RJ_Q),
        f32c(
            "ADAPTIVE_MIN_SOLID_ANGLE",
            crate::lights::ADAPTIVE_MIN_SOLID_ANGLE,
        ),
        // Optimal MIS weights (`integrator::optimal`).
        u32c(
            "OPTIMAL_FIRST_STAGE",
            crate::integrator::optimal::FIRST_STAGE,
        ),
        f32c("OPTIMAL_RIDGE", crate::integrator::optimal::RIDGE as f32),
        u32c("PSA_NEWTON_STEPS", projected_solid_angle::NEWTON_STEPS),
        f32c(
            "PSA_NEWTON_TOLERANCE",
            projected_solid_angle::NEWTON_TOLERANCE,
        ),
        f32c("PSA_MAX_CONDITION", projected_solid_angle::MAX_CONDITION),
        u32c(
            "PSA_MAX_VERTICES",
            const { count(projected_solid_angle::PSA_MAX_VERTICES) },
        ),
        // Rays and BVHs.
        f32c("SHADOW_EPSILON", ray::SHADOW_EPSILON),
        f32c("MAX_INV", wide_bvh::MAX_INV),
        u32c("BVH_STACK_SIZE", const { count(CWBVH_STACK_SIZE) }),
        u32c("BVH2_STACK_SIZE", const { count(BVH2_STACK_SIZE) }),
        // Mesh vertex attributes.
        u32c("ATTR_HAS_NORMALS", mesh_attributes::HAS_NORMALS),
        u32c("ATTR_HAS_UVS", mesh_attributes::HAS_UVS),
        // Textures.
        u32c("RECORD_VEC4S", textures::RECORD_VEC4S),
        f32c("LUMINANCE_R", LUMINANCE_WEIGHTS[0]),
        f32c("LUMINANCE_G", LUMINANCE_WEIGHTS[1]),
        f32c("LUMINANCE_B", LUMINANCE_WEIGHTS[2]),
    ];
    c.extend(tags(MaterialTag::ALL));
    c.extend(tags(FresnelTag::ALL));
    c.extend(tags(DistributionTag::ALL));
    c.extend(tags(LightTag::ALL));
    c.extend(tags(ShapeTag::ALL));
    c.extend(tags(StrategyTag::ALL));
    c.extend(tags(HeuristicTag::ALL));
    c.extend(tags(LightSamplingTag::ALL));
    c.extend(tags(TextureTag::ALL));
    c.extend(tags(WrapTag::ALL));
    c.extend(tags(ChannelTag::ALL));
    c.extend(tags(FilterTag::ALL));
    c.extend(tags(SamplerTag::ALL));
    c.extend(tags(LightSelectionTag::ALL));
    c.extend(tags(CameraTag::ALL));
    #[cfg(feature = "mutants")]
    c.extend(mutant_constants(crate::mutants::active()));
    c
}

/// The WGSL side of [`crate::mutants`]: the active mutant's factor and the tags it applies to
/// (`NONE` where it applies to none), read by the `// #if MUTANTS` regions of the shaders.
#[cfg(feature = "mutants")]
pub(crate) fn mutant_constants(m: &crate::mutants::Mutant) -> Vec<Constant> {
    use crate::mutants::{FACTOR, Mutant};
    let (light, bsdf) = match m {
        Mutant::LightPdf(t) => (*t, primitive::NONE),
        Mutant::BsdfPdf(t) => (primitive::NONE, *t),
        _ => (primitive::NONE, primitive::NONE),
    };
    let plastic = if *m == Mutant::PlasticEval {
        FACTOR
    } else {
        1.0
    };
    vec![
        f32c("MUTANT_FACTOR", FACTOR),
        u32c("MUTANT_LIGHT_PDF_TAG", light),
        u32c("MUTANT_BSDF_PDF_TAG", bsdf),
        f32c("MUTANT_PLASTIC_EVAL", plastic),
        // Booleans as 0 or 1: the sampler's dimension-allocation bugs (`sampler/mod.wgsl`).
        u32c(
            "MUTANT_SAMPLER_LIGHT_CAMERA",
            u32::from(*m == Mutant::SamplerLightCamera),
        ),
        u32c(
            "MUTANT_SAMPLER_SHARED_BOUNCES",
            u32::from(*m == Mutant::SamplerSharedBounces),
        ),
        // mis-optimal's pure samples without their control-variate term (`integrator/optimal.wgsl`).
        u32c(
            "MUTANT_OPTIMAL_PURE_ZERO",
            u32::from(*m == Mutant::OptimalPureZero),
        ),
    ]
}

/// The prelude's WGSL for `constants`.
pub fn source(constants: &[Constant]) -> String {
    let mut s = String::from("// Generated from the Rust definitions by `gpu/prelude.rs`.\n");
    for c in constants {
        s += &c.wgsl();
        s.push('\n');
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use wgpu::naga;

    /// The prelude as naga reads it: each constant's name and literals (one for a scalar, the
    /// elements of an array in order).
    fn parsed(src: &str) -> Vec<(String, Vec<naga::Literal>)> {
        let module = naga::front::wgsl::parse_str(src).unwrap_or_else(|e| panic!("{e}\n{src}"));
        let literal =
            |h: naga::Handle<naga::Expression>, name: &str| match module.global_expressions[h] {
                naga::Expression::Literal(l) => l,
                ref e => panic!("{name}: not a literal: {e:?}"),
            };
        module
            .constants
            .iter()
            .map(|(_, c)| {
                let name = c.name.clone().expect("named");
                let lits = match &module.global_expressions[c.init] {
                    naga::Expression::Compose { components, .. } => {
                        components.iter().map(|&h| literal(h, &name)).collect()
                    }
                    _ => vec![literal(c.init, &name)],
                };
                (name, lits)
            })
            .collect()
    }

    #[test]
    fn every_constant_reaches_wgsl_with_its_rust_bits() {
        let table = constants();
        let got = parsed(&source(&table));
        assert_eq!(got.len(), table.len());
        for (c, (name, lits)) in table.iter().zip(&got) {
            assert_eq!(c.name, name);
            match (c.value, lits.as_slice()) {
                (Value::F32(want), [naga::Literal::F32(v)]) => {
                    assert_eq!(v.to_bits(), want.to_bits(), "{name}: {v:e} vs {want:e}")
                }
                (Value::U32(want), [naga::Literal::U32(v)]) => assert_eq!(*v, want, "{name}"),
                (Value::U32Array(want), got) => {
                    let got: Vec<u32> = got
                        .iter()
                        .map(|l| match l {
                            naga::Literal::U32(v) => *v,
                            l => panic!("{name}: {l:?} in a u32 table"),
                        })
                        .collect();
                    assert_eq!(got, want, "{name}");
                }
                (want, got) => panic!("{name}: {got:?} for {want:?}"),
            }
        }
        // Names are unique (WGSL would reject a redefinition; say which).
        let mut names: Vec<_> = table.iter().map(|c| c.name).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), table.len(), "duplicate names");
    }

    #[test]
    fn the_prelude_holds_the_shared_constants_with_their_rust_values() {
        use crate::sampling::{MAX_SPHERICAL_SAMPLE_AREA, MIN_SPHERICAL_SAMPLE_AREA};
        let table = constants();
        let value = |name: &str| {
            table
                .iter()
                .find(|c| c.name == name)
                .unwrap_or_else(|| panic!("{name} is not in the prelude"))
                .value
        };
        for (name, want) in [
            ("SMOOTH_ALPHA", Value::F32(ggx::SMOOTH_ALPHA)),
            ("E_TABLE_SIZE", Value::U32(coat_albedo::E_TABLE_SIZE as u32)),
            ("COAT_GRID_SIZE", Value::U32(48)),
            ("TRANSMITTANCE_SIZE", Value::U32(64)),
            ("COAT_GRID_LN_FIRST", Value::F32(ggx::SMOOTH_ALPHA.ln())),
            ("MIX_GOLDEN_LO", Value::U32(0x7f4a_7c15)),
            ("MIX_GOLDEN_HI", Value::U32(0x9e37_79b9)),
            ("MIX64_M1_LO", Value::U32(0x1ce4_e5b9)),
            ("MIX64_M1_HI", Value::U32(0xbf58_476d)),
            ("MIX64_M2_LO", Value::U32(0x1331_11eb)),
            ("MIX64_M2_HI", Value::U32(0x94d0_49bb)),
            ("MATERIAL_MIX", Value::U32(4)),
            ("SMALL_CONE_SIN2", Value::F32(sphere::SMALL_CONE_SIN2)),
            ("SHADOW_EPSILON", Value::F32(ray::SHADOW_EPSILON)),
            (
                "MAX_NEWTON_STEPS",
                Value::U32(spherical_rectangle::MAX_NEWTON_STEPS as u32),
            ),
            (
                "MAX_EDGE_COS",
                Value::F32(spherical_rectangle::MAX_EDGE_COS),
            ),
            (
                "MIN_SPHERICAL_SAMPLE_AREA",
                Value::F32(MIN_SPHERICAL_SAMPLE_AREA),
            ),
            (
                "MAX_SPHERICAL_SAMPLE_AREA",
                Value::F32(MAX_SPHERICAL_SAMPLE_AREA),
            ),
            (
                "MAX_SOLID_ANGLE_TRIANGLES",
                Value::U32(polygon::MAX_SOLID_ANGLE_TRIANGLES as u32),
            ),
            ("MAX_INV", Value::F32(wide_bvh::MAX_INV)),
            ("NONE", Value::U32(u32::MAX)),
            ("ONE_MINUS_EPSILON", Value::F32(sampling::ONE_MINUS_EPSILON)),
            ("BVH_STACK_SIZE", Value::U32(CWBVH_STACK_SIZE as u32)),
            ("BVH2_STACK_SIZE", Value::U32(BVH2_STACK_SIZE as u32)),
            ("MATERIAL_DIFFUSE", Value::U32(0)),
            ("MATERIAL_PLASTIC", Value::U32(2)),
            ("LIGHT_BACKGROUND", Value::U32(5)),
            ("SHAPE_SPHERE", Value::U32(2)),
            ("STRATEGY_MIS", Value::U32(3)),
            ("HEURISTIC_POWER", Value::U32(1)),
            ("LIGHT_SAMPLING_SOLID_ANGLE", Value::U32(1)),
            ("LIGHT_SAMPLING_SOLID_ANGLE_COSINE", Value::U32(2)),
            ("LIGHT_SAMPLING_ADAPTIVE", Value::U32(3)),
            ("LIGHT_SAMPLING_PROJECTED_SOLID_ANGLE", Value::U32(4)),
            ("MIN_COSINE_WEIGHT", Value::F32(0.01)),
            ("MIN_ELLIPSE_SOLID_ANGLE", Value::F32(0.01)),
            ("MAX_ELLIPSE_NEWTON_STEPS", Value::U32(20)),
            ("MAX_CARLSON_STEPS", Value::U32(16)),
            ("FRESNEL_TINT", Value::U32(1)),
            ("TEXTURE_CHECKERBOARD", Value::U32(2)),
            ("WRAP_CLAMP", Value::U32(2)),
            ("CHANNEL_B", Value::U32(3)),
            ("RECORD_VEC4S", Value::U32(4)),
            ("LUMINANCE_G", Value::F32(0.715_160)),
            ("FILTER_MAX_STEPS", Value::U32(filter::MAX_STEPS)),
            ("FILTER_TOLERANCE", Value::F32(filter::TOLERANCE)),
            ("FILTER_GAUSSIAN", Value::U32(1)),
            ("FILTER_MITCHELL", Value::U32(4)),
            ("FILTER_MITCHELL_BREAKS", Value::U32(8)),
            ("FILTER_GL_W3", Value::F32(0.101_228_54)),
            ("F32_EPSILON", Value::F32(f32::EPSILON)),
            ("SAMPLER_INDEPENDENT", Value::U32(0)),
            ("SAMPLER_SOBOL", Value::U32(1)),
            ("ZSOBOL_EPOCH_LOG2", Value::U32(12)),
            ("ZSOBOL_INDEX_DIGITS", Value::U32(12)),
            ("DIM_FIRST_BOUNCE", Value::U32(2)),
            ("DIM_PER_BOUNCE", Value::U32(8)),
            ("DIM_RR", Value::U32(7)),
            ("OWEN_LK_MUL_A", Value::U32(0x3d20_adea)),
        ] {
            assert_eq!(value(name), want, "{name}");
        }
    }

    #[test]
    fn tags_are_consecutive_from_zero() {
        fn check<T: Copy + Into<u32>>(all: &[(T, &str)]) {
            for (i, &(t, name)) in all.iter().enumerate() {
                assert_eq!(t.into(), i as u32, "{name}");
            }
        }
        check(MaterialTag::ALL);
        check(FresnelTag::ALL);
        check(DistributionTag::ALL);
        check(LightTag::ALL);
        check(ShapeTag::ALL);
        check(StrategyTag::ALL);
        check(HeuristicTag::ALL);
        check(LightSamplingTag::ALL);
        check(TextureTag::ALL);
        check(WrapTag::ALL);
        check(ChannelTag::ALL);
        check(FilterTag::ALL);
        check(SamplerTag::ALL);
        check(LightSelectionTag::ALL);
        check(CameraTag::ALL);
    }
}
