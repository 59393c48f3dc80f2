//! Mitsuba XML scenes of lumis' own against references rendered by Mitsuba 3.9.1 from that very
//! XML (issue 18, item 3): each scene in `tests/data/mitsuba/` below, imported by lumis
//! (`lumis::scene::mitsuba::load`), renders with every direct-lighting strategy
//! ([`common::STRATEGIES`]: light, BSDF, the 0.5/0.5 mixture, MIS with the power and the balance
//! heuristic) to the stored `tests/data/refs/NAME.exr` (`tools/make_xml_reference.sh`: two
//! independent halves, `NAME.var.exr` = (A − B)²/4; tests/data/refs/README.md says how each was
//! made). Each XML's opening comment lists the plugins and features it covers; together they
//! cover every supported one whose image lumis renders as Mitsuba does. Plastic is left out: lumis'
//! plastic couples its layers differently (the importer warns), so Mitsuba's image is not lumis'.
//!
//! **Test:** `common::test_against` per render, blocks of [`BLOCK`]×[`BLOCK`] pixels, per block
//! and channel z = (lumis block mean − reference block mean) / sd, sd from lumis' per-pixel sample
//! variances plus the reference's variance image; Šidák-corrected family-wise α = 0.01 per render
//! (80 × 60 px: 5 × 4 blocks × 3 channels = 60 comparisons, critical |z| 3.76). Seeds are fixed:
//! render `i` of a scene uses the scene's seed + `i`, with solid-angle light sampling and the
//! scene's `rr_depth`.
//!
//! **Measured** (`nice cargo test --release -p lumis-renderer --test mitsuba_xml_refs --
//! --nocapture`, 2 shared cores, load ≈ 9: 64 s for the file): every strategy passes at 256 spp
//! with worst |z| 1.55–3.28 (xml_meshes) and 1.85–2.85 (xml_shapes) over 60 comparisons each.
//! The smallest block difference detected (critical |z| × sd / reference block mean, sd from two
//! 256-spp MIS renders by `lumis render` and the reference's variance): xml_meshes 2.1 % of the
//! block mean for the median block (0.12 % to 12 % over blocks and channels), xml_shapes 3.1 %
//! (1.8 % to 9.7 %).
//!
//! **Power:** one deliberate mutation per scene must fail the same test (MIS, power heuristic);
//! each test's doc comment names it and the measured result. Two importer bugs were also tried
//! once (not committed) and caught by the every-strategy tests: `twosided` ignored
//! (`two_sided: false`): xml_meshes fails for every strategy, 45 of 60 blocks, |z| 4779 (the
//! floor turns black); the checkerboard's colours not swapped in a scalar slot (`alpha`):
//! xml_shapes fails for BSDF, mixture and both MIS (3 of 60 blocks, |z| 7.0–13.7) but not for
//! light-only sampling (|z| 2.0), whose direct integrator sees the plate's alpha only through
//! the reflected light's lobe.

mod common;

use common::protocol::decide_against;
use common::*;

use lumis::integrator::{Heuristic, Settings, Strategy};
use lumis::scene::mitsuba::{self, Imported};
use lumis::scene::{Scene, SceneDesc};
use std::sync::Arc;

/// Block size of the z-test.
const BLOCK: u32 = 16;

const MIS: Strategy = Strategy::Mis {
    heuristic: Heuristic::Power,
};

/// Imports `tests/data/mitsuba/NAME.xml` with `-D` parameters `defines`.
fn import(name: &str, defines: &[(&str, &str)]) -> Imported {
    let d: Vec<(String, String)> = defines
        .iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect();
    let path = data_dir().join("mitsuba").join(format!("{name}.xml"));
    mitsuba::load(&path, &d).unwrap_or_else(|e| panic!("{e}"))
}

/// The z-test of one render (`spp`, `seed`) of `desc` with `strategy` against the reference of
/// `name`; `Err` with the worst blocks if it finds a bias. Prints the `z-test|…` line either way.
fn compare(
    name: &str,
    desc: &SceneDesc,
    rr_depth: u32,
    strategy: Strategy,
    spp: u32,
    seed: u32,
) -> Result<(), String> {
    let settings = Settings {
        strategy,
        rr_depth,
        ..Settings::default()
    };
    compare_with(name, desc, settings, spp, seed)
}

/// [`compare`] with any `settings`.
fn compare_with(
    name: &str,
    desc: &SceneDesc,
    settings: Settings,
    spp: u32,
    seed: u32,
) -> Result<(), String> {
    let scene = Arc::new(Scene::from_desc(desc).unwrap_or_else(|e| panic!("{e}")));
    let strategy = settings.strategy;
    // The default (power) selection is not named, so that the decisions' names, and with them
    // their stage-2 seeds, stay those they had before the light BVH's runs were added.
    let selection = match settings.light_selection {
        lumis::lights::LightSelection::Power => String::new(),
        other => format!(" ({} selection)", other.name()),
    };
    let what = format!("{name}.xml {strategy:?}{selection} {spp} spp seed {seed}");
    compare_scene(name, &what, &scene, settings, spp, seed, BLOCK)
}

/// The decision named `what` on one render (`spp`, `seed`) of the built `scene` against the
/// reference of `name`, in `block`×`block` blocks (`u32::MAX`: the whole image per channel).
fn compare_scene(
    name: &str,
    what: &str,
    scene: &Arc<Scene>,
    settings: Settings,
    spp: u32,
    seed: u32,
    block: u32,
) -> Result<(), String> {
    let reference_img = reference(&format!("{name}.exr"));
    let reference_var = reference(&format!("{name}.var.exr"));
    let var = Some(&reference_var);
    decide_against(what, seed, spp, &reference_img, var, block, |seed, n| {
        render(scene, settings, n, seed)
    })
}

/// Power: the MIS (power) render at 256 spp, `seed`, of `m`, a mutated import of `NAME.xml`,
/// must fail against `NAME`'s reference; `what` names the mutation.
fn assert_detected(name: &str, m: &Imported, seed: u32, what: &str) {
    let rr = m.rr_depth.unwrap_or(5);
    assert!(
        compare(name, &m.desc, rr, MIS, 256, seed).is_err(),
        "{name}.xml {what} went undetected"
    );
}

/// Every strategy of [`STRATEGIES`] in this tier with `spp[i]` samples, seed `seed + i`, against the
/// reference; panics with every failure.
fn every_strategy(name: &str, spp: [u32; 5], seed: u32) {
    let m = import(name, &[]);
    let rr = m.rr_depth.unwrap_or(5);
    let failures: Vec<String> = STRATEGIES
        .into_iter()
        .enumerate()
        // The CI tier renders MIS (power) alone (`common/tier.rs`).
        .filter(|(_, s)| tier::runs(*s))
        .filter_map(|(i, s)| compare(name, &m.desc, rr, s, spp[i], seed + i as u32).err())
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `xml_meshes.xml` (obj, ply, serialized, sphere and rectangle shapes, an include with ids and
/// refs, `$name` defaults, a bitmap texture, a preset conductor, a dielectric, twosided, area
/// light and envmap, the default gaussian film filter, fov_axis `smaller`) against its reference,
/// seeds 1830–1834.
#[test]
fn xml_meshes_matches_its_mitsuba_reference() {
    every_strategy("xml_meshes", [256, 256, 256, 256, 256], 1830);
}

/// Power: `xml_meshes.xml` with `-D metal=Cu` (the conductor preset copper instead of the gold
/// the reference was made with) fails, MIS 256 spp, seed 1840. Measured: 7 of 60 blocks, worst
/// |z| 54.8 (critical 3.76).
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_meshes_wrong_preset_is_detected() {
    let m = import("xml_meshes", &[("metal", "Cu")]);
    assert_detected("xml_meshes", &m, 1840, "with metal=Cu");
}

/// `xml_shapes.xml` (rectangle, cube, sphere, disk with flip_normals, a null BSDF, rough
/// conductor with a checkerboard alpha, rough dielectric, a raw clamped bitmap, a checkerboard
/// colour, wavelength-list spectra, a constant sky, the direct integrator, a box filter, fov_axis
/// `diagonal`) against its reference, seeds 1850–1854.
#[test]
fn xml_shapes_matches_its_mitsuba_reference() {
    every_strategy("xml_shapes", [256, 256, 256, 256, 256], 1850);
}

/// Power: `xml_shapes.xml` with `-D flip=false` (the disk light's flip_normals dropped: it faces
/// up, away from the scene) fails, MIS 256 spp, seed 1860. Measured: 60 of 60 blocks, worst
/// |z| 2105 (critical 3.76).
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_shapes_unflipped_light_is_detected() {
    let m = import("xml_shapes", &[("flip", "false")]);
    assert_detected("xml_shapes", &m, 1860, "with flip=false");
}

/// `xml_beckmann.xml` (roughconductor and roughdielectric naming no distribution, i.e. Mitsuba's
/// default Beckmann: a gold sphere, a rough glass sphere, a copper plate with a checkerboard
/// alpha; the path integrator) against its reference, seeds 1870–1874. lumis evaluates the
/// exact Beckmann masking where Mitsuba evaluates its rational fit (within 0.35%): this is the
/// test that the images agree regardless. Measured (2026-12-05): every strategy passes at stage
/// 1, worst |z| 1.91 (MIS power) to 2.60 (light) over 60 comparisons.
#[test]
fn xml_beckmann_matches_its_mitsuba_reference() {
    every_strategy("xml_beckmann", [256, 256, 256, 256, 256], 1870);
}

/// Power: `xml_beckmann.xml` with every Beckmann lobe rendered as GGX of the same α (what an
/// importer that ignored Mitsuba's default distribution would make) fails, MIS 256 spp, seed
/// 1880. Measured: 33 of 60 blocks, worst |z| 27.3 (critical 3.76); stage 2 36 of 60.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_beckmann_as_ggx_is_detected() {
    use lumis::scene::MaterialDesc;
    use lumis::scene::desc::Distribution;
    let mut m = import("xml_beckmann", &[]);
    let mut changed = 0;
    for named in &mut m.desc.materials {
        if let MaterialDesc::Conductor { distribution, .. }
        | MaterialDesc::Dielectric { distribution, .. } = &mut named.material
        {
            assert_eq!(*distribution, Distribution::Beckmann, "{}", named.name);
            *distribution = Distribution::Ggx;
            changed += 1;
        }
    }
    assert_eq!(changed, 3, "the gold, the glass and the copper");
    assert_detected("xml_beckmann", &m, 1880, "rendered with GGX");
}

/// `xml_anisotropic.xml` (roughconductor with alpha_u ≠ alpha_v on an OBJ torus and a PLY sphere
/// with texture coordinates, Beckmann and GGX, and on a rectangle; lumis orients the lobe along
/// ∂p/∂u as Mitsuba does, `geometry/tangent.rs`) against its reference, seeds 1890–1894.
/// Measured (2026-12-05): BSDF, mixture and both MIS pass at stage 1 (worst |z| 1.90–2.68); light
/// sampling, heavy-tailed on these narrow lobes, had one block at |z| 4.06 at stage 1 and
/// passed stage 2 (2.42).
#[test]
fn xml_anisotropic_matches_its_mitsuba_reference() {
    every_strategy("xml_anisotropic", [256, 256, 256, 256, 256], 1890);
}

/// Power: `xml_anisotropic.xml` with the torus's alpha_u and alpha_v swapped (`-D au=0.4
/// av=0.05`: a tangent frame turned by 90°, the mistake an importer or a frame convention
/// would make) fails, MIS 256 spp, seed 1900. Measured: 6 of 60 blocks, worst |z| 11.0
/// (critical 3.76); stage 2 6 of 60, |z| 15.1.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_anisotropic_turned_lobe_is_detected() {
    let m = import("xml_anisotropic", &[("au", "0.4"), ("av", "0.05")]);
    assert_detected("xml_anisotropic", &m, 1900, "with the torus's lobe turned");
}

/// `xml_plastic.xml` (Mitsuba's `plastic` and `roughplastic` in Mitsuba's coupling: smooth and
/// rough, Beckmann by default and GGX, `nonlinear`, a checkerboard base and a specular tint;
/// `materials/plastic_mitsuba.rs`) against its reference, seeds 1910–1914.
#[test]
fn xml_plastic_matches_its_mitsuba_reference() {
    every_strategy("xml_plastic", [256, 256, 256, 256, 256], 1910);
}

/// Power: `xml_plastic.xml` with `-D nonlinear=false` (the floor's internal bounces untinted:
/// what an importer that dropped the flag would render) fails, MIS 256 spp, seed 1920.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_plastic_linear_floor_is_detected() {
    let m = import("xml_plastic", &[("nonlinear", "false")]);
    assert_detected("xml_plastic", &m, 1920, "with nonlinear=false");
}

/// Power: `xml_plastic.xml` with every plastic in lumis' own coupling (what the importer did
/// before Mitsuba's: Schlick Fresnel, GGX, energy-conserving base) fails, MIS 256 spp, seed
/// 1930.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_plastic_in_lumis_coupling_is_detected() {
    use lumis::scene::{MaterialDesc, PlasticModel};
    let mut m = import("xml_plastic", &[]);
    let mut changed = 0;
    for named in &mut m.desc.materials {
        if let MaterialDesc::Plastic { model, .. } = &mut named.material {
            assert_ne!(*model, PlasticModel::Lumis, "{}", named.name);
            *model = PlasticModel::Lumis;
            changed += 1;
        }
    }
    assert_eq!(changed, 4, "the floor, two spheres and the plate");
    assert_detected("xml_plastic", &m, 1930, "in lumis' coupling");
}

/// `xml_anisotropic_textured.xml` (roughconductor and roughdielectric with textured `alpha_u`
/// and `alpha_v`, as the gallery's textured carbon: crossed checkerboards on an OBJ torus, a
/// textured α_u with a numeric α_v on a PLY sphere of rough glass, the reverse on a rectangle)
/// against its reference, seeds 1940–1944.
#[test]
fn xml_anisotropic_textured_matches_its_mitsuba_reference() {
    every_strategy("xml_anisotropic_textured", [256, 256, 256, 256, 256], 1940);
}

/// Power: `xml_anisotropic_textured.xml` with each material's α_u and α_v slots swapped (the
/// textures and the constants: a turned lobe wherever the two differ) fails, MIS 256 spp, seed
/// 1950.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_anisotropic_textured_swapped_slots_are_detected() {
    use lumis::scene::MaterialDesc;
    let mut m = import("xml_anisotropic_textured", &[]);
    let mut swapped = 0;
    for named in &mut m.desc.materials {
        let t = &mut named.textures;
        if t.alpha_v.is_none() {
            continue;
        }
        std::mem::swap(&mut t.alpha, &mut t.alpha_v);
        if let MaterialDesc::Conductor { alpha, alpha_v, .. }
        | MaterialDesc::Dielectric { alpha, alpha_v, .. } = &mut named.material
        {
            let v = alpha_v.expect("a textured pair keeps both constants");
            *alpha_v = Some(*alpha);
            *alpha = v;
        }
        swapped += 1;
    }
    assert_eq!(swapped, 3, "the torus, the sphere and the plate");
    assert_detected(
        "xml_anisotropic_textured",
        &m,
        1950,
        "with alpha_u and alpha_v swapped",
    );
}

/// `xml_thinlens.xml` (Mitsuba's `thinlens`: aperture radius 0.12, focused on the middle sphere,
/// `fov_axis` smaller; a checkerboard floor in and out of focus) against its reference, seeds
/// 1960–1964. Measured (2026-12-06): every strategy passes at stage 1.
///
/// What this test cannot see: defocus moves light by a few pixels, which 16 × 16 blocks average
/// away. Neither half nor twice the aperture was detected (`-D aperture=0.06` and `0.24`, MIS
/// 256 spp, seed 1970: worst |z| 2.06 and 3.15 of 3.76), and 4 × 4 blocks (seeds 2200–2204)
/// are unusable here: blocks of sky only have zero variance in both images, and Mitsuba's
/// constant emitter gives 0.3200044 for 0.32 (its RGB path), which the zero-variance rule calls
/// a bias. The lens itself is tested by `renderer/src/camera_tests.rs` (every lens ray through
/// its focus point, the spread of a defocused point, a χ² of the lens points).
#[test]
fn xml_thinlens_matches_its_mitsuba_reference() {
    every_strategy("xml_thinlens", [256, 256, 256, 256, 256], 1960);
}

/// Power: `xml_thinlens.xml` with the field of view read on the x axis instead of the
/// `smaller` (y) one (`-D fov_axis=x`: the importer bug of ignoring `fov_axis`, a view 25%
/// narrower) fails, MIS 256 spp, seed 1971.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_thinlens_fov_on_the_wrong_axis_is_detected() {
    let m = import("xml_thinlens", &[("fov_axis", "x")]);
    assert_detected("xml_thinlens", &m, 1971, "with fov_axis=x");
}

/// `xml_orthographic.xml` (Mitsuba's `orthographic`: a film sized by a non-uniform scale before
/// the lookat, near_clip 0.5, the gaussian filter) against its reference, seeds 1980–1984.
#[test]
fn xml_orthographic_matches_its_mitsuba_reference() {
    every_strategy("xml_orthographic", [256, 256, 256, 256, 256], 1980);
}

/// Power: `xml_orthographic.xml` with `-D sx=2.3` (a film 4.5% wider: what a film size off by
/// a few pixels' worth would render) fails, MIS 256 spp, seed 1990.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_orthographic_wider_film_is_detected() {
    let m = import("xml_orthographic", &[("sx", "2.3")]);
    assert_detected("xml_orthographic", &m, 1990, "with sx=2.3");
}

/// `xml_principal_point.xml` (Mitsuba's perspective camera with `principal_point_offset_x` 0.15
/// and `principal_point_offset_y` 0.1) against its reference, seeds 2160–2164. The file's first
/// version (`oy` −0.1) moved sky-only blocks into the image and failed every strategy there
/// (zero variance on both sides, Mitsuba's constant emitter 1.4e-5 off: see
/// [`xml_thinlens_matches_its_mitsuba_reference`]); the seeds are the ones fixed before that run.
#[test]
fn xml_principal_point_matches_its_mitsuba_reference() {
    every_strategy("xml_principal_point", [256, 256, 256, 256, 256], 2160);
}

/// Power: `xml_principal_point.xml` with `-D ox=-0.15` (the horizontal offset with the wrong
/// sign) fails, MIS 256 spp, seed 2170.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_principal_point_wrong_sign_is_detected() {
    let m = import("xml_principal_point", &[("ox", "-0.15")]);
    assert_detected("xml_principal_point", &m, 2170, "with ox=-0.15");
}

/// `xml_cylinder.xml` (Mitsuba's `cylinder`: from `to_world` alone and from p0, p1 and radius,
/// a checkerboard over its (u, v), anisotropic rough gold along its ∂p/∂u, two-sided, with
/// `flip_normals`; insides seen through the open ends) against its reference, seeds 2360–2364.
#[test]
fn xml_cylinder_matches_its_mitsuba_reference() {
    every_strategy("xml_cylinder", [256, 256, 256, 256, 256], 2360);
}

/// Power: `xml_cylinder.xml` with `-D turn=30` (the textured tube turned 30° about its own
/// axis: the same surface, its u axis and so its checkerboard turned, what an importer that
/// ignored the rotation in the u axis would render) fails, MIS 256 spp, seed 2370.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_cylinder_turned_texture_is_detected() {
    let m = import("xml_cylinder", &[("turn", "30")]);
    assert_detected("xml_cylinder", &m, 2370, "with turn=30");
}

/// Power: `xml_cylinder.xml` with the gold tube's `alpha_u` and `alpha_v` swapped (its lobe
/// along the axis instead of around it: what ∂p/∂u along the axis would render) fails, MIS
/// 256 spp, seed 2371.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_cylinder_tangent_along_the_axis_is_detected() {
    let m = import("xml_cylinder", &[("alpha_u", "0.35"), ("alpha_v", "0.05")]);
    assert_detected("xml_cylinder", &m, 2371, "with alpha_u and alpha_v swapped");
}

/// `xml_thin.xml` (Mitsuba's `thindielectric`: a tilted pane between a rectangle light and the
/// floor, which it lights only through its delta transmission, and a water bubble with the box
/// and the sky seen through it) against its reference, seeds 2530–2534.
#[test]
fn xml_thin_matches_its_mitsuba_reference() {
    every_strategy("xml_thin", [256, 256, 256, 256, 256], 2530);
}

/// Power: `xml_thin.xml` with `-D ior=1.6` (the pane's index 1.6 for 1.9: its reflectance at
/// normal incidence 0.10 for 0.17, the light it passes 0.90 for 0.83) fails, MIS 256 spp, seed
/// 2540.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_thin_wrong_index_is_detected() {
    let m = import("xml_thin", &[("ior", "1.6")]);
    assert_detected("xml_thin", &m, 2540, "with ior=1.6");
}

/// `xml_mask.xml` (Mitsuba's `mask`: a pane masked by a bilinearly filtered 8-bit grey PNG
/// between a rectangle light and the floor, which shows its patterned shadow, and a sphere at the
/// default opacity ½, its black inside and the box behind seen through it) against its
/// reference, seeds 2770–2774. Mitsuba's shadow rays stop at the pane and the floor under it is
/// lit through it by BSDF sampling only; lumis' pass it with probability 1 − α: the same image.
#[test]
fn xml_mask_matches_its_mitsuba_reference() {
    every_strategy("xml_mask", [256, 256, 256, 256, 256], 2770);
}

/// Power: `xml_mask.xml` with `-D raw=true` (the mask's 8-bit texels read as linear, not
/// sRGB-decoded: a mid-grey texel is 0.50 opaque for 0.22) fails, MIS 256 spp, seed 2780.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_mask_undecoded_opacity_is_detected() {
    let m = import("xml_mask", &[("raw", "true")]);
    assert_detected("xml_mask", &m, 2780, "with raw=true");
}

/// `xml_two_sided.xml` (Mitsuba's `twosided` with two BSDFs: an open cylinder, orange diffuse
/// outside and rough gold inside, and a panel that shows the camera its back, the floor's own
/// one-sided white shared by reference) against its reference, seeds 2870–2874.
#[test]
fn xml_two_sided_matches_its_mitsuba_reference() {
    every_strategy("xml_two_sided", [256, 256, 256, 256, 256], 2870);
}

/// Power: `xml_two_sided.xml` with the cylinder's sides swapped (`-D outside=gold -D
/// inside=orange`: what a front/back convention the wrong way round renders) fails, MIS 256
/// spp, seed 2880.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_two_sided_swapped_sides_are_detected() {
    let m = import(
        "xml_two_sided",
        &[("outside", "gold"), ("inside", "orange")],
    );
    assert_detected("xml_two_sided", &m, 2880, "with the sides swapped");
}

/// `xml_blend.xml` (Mitsuba's `blendbsdf`, imported as lumis' stochastic mix: a sphere of rough
/// plastic and rough copper by a bilinear 8-bit texture weight, a panel of a diffuse and a nested
/// blend at constant weights) against its reference, seeds 2970–2974.
#[test]
fn xml_blend_matches_its_mitsuba_reference() {
    every_strategy("xml_blend", [256, 256, 256, 256, 256], 2970);
}

/// Power: `xml_blend.xml` with `-D w=0.7` (the panel's weight the wrong way round: 0.7 for 0.3)
/// fails, MIS 256 spp, seed 2980.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_blend_reversed_weight_is_detected() {
    let m = import("xml_blend", &[("w", "0.7")]);
    assert_detected("xml_blend", &m, 2980, "with w=0.7");
}

/// `xml_mesh_attribute.xml` (Mitsuba's `mesh_attribute` texture on three spheres of one PLY
/// file: a diffuse of the interpolated `vertex_color`, a two-sided diffuse of the per-face
/// `face_tint` (8-bit, read raw as Mitsuba 3.9.1 reads `uchar`) scaled, and copper whose α is
/// the one-component `vertex_rough`) against its reference, seeds 3070–3074.
#[test]
fn xml_mesh_attribute_matches_its_mitsuba_reference() {
    every_strategy("xml_mesh_attribute", [256, 256, 256, 256, 256], 3070);
}

/// Power: `xml_mesh_attribute.xml` with the left sphere's `vertex_color` read as `face_color`
/// (`-D left=face_color`: what a lookup by the wrong attribute or kind renders) fails, MIS 256
/// spp, seed 3080.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_mesh_attribute_wrong_attribute_is_detected() {
    let m = import("xml_mesh_attribute", &[("left", "face_color")]);
    assert_detected("xml_mesh_attribute", &m, 3080, "with left=face_color");
}

/// `xml_instances.xml` (Mitsuba's `shapegroup` of a tilted torus mesh, a rough copper sphere
/// and a two-sided plate, placed by three `instance`s, rotated, scaled and moved: flattened by
/// the importer) against its reference, seeds 3170–3174.
#[test]
fn xml_instances_matches_its_mitsuba_reference() {
    every_strategy("xml_instances", [256, 256, 256, 256, 256], 3170);
}

/// Power: `xml_instances.xml` with the middle instance unturned (`-D angle=0` for 40°: what an
/// instance transform dropped or applied in the wrong order renders) fails, MIS 256 spp, seed
/// 3180.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_instances_wrong_placement_is_detected() {
    let m = import("xml_instances", &[("angle", "0")]);
    assert_detected("xml_instances", &m, 3180, "with angle=0");
}

/// `xml_blend_delta.xml` (Mitsuba's `blendbsdf` around delta lobes, imported as mixes of model
/// mitsuba: rough plastic and a smooth copper conductor by a texture, a smooth plastic and rough
/// gold at 0.4) against its reference, seeds 3270–3274.
#[test]
fn xml_blend_delta_matches_its_mitsuba_reference() {
    every_strategy("xml_blend_delta", [256, 256, 256, 256, 256], 3270);
}

/// Power: `xml_blend_delta.xml` rendered with its mixes as plain mixes (model lumis: a delta
/// sample keeps its own weight, the unbiased blend Mitsuba does not render) fails, MIS 256 spp,
/// seed 3280.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_blend_delta_as_a_plain_mix_is_detected() {
    let mut m = import("xml_blend_delta", &[]);
    let mut blends = 0;
    for mix in m.desc.materials.iter_mut().filter_map(|x| x.mix.as_mut()) {
        blends += usize::from(mix.mitsuba);
        mix.mitsuba = false;
    }
    assert_eq!(blends, 2);
    assert_detected("xml_blend_delta", &m, 3280, "as plain mixes");
}

/// `xml_principled.xml` (Mitsuba's principled BSDF: a default one, an anisotropic tinted metal,
/// a checkerboard base with sheen, clearcoat, spec_tint and flatness, a mostly transmitting
/// sphere with a textured roughness, a textured metallic and clearcoat gloss with non-default
/// sampling rates) against its reference, seeds 3370–3374.
#[test]
fn xml_principled_matches_its_mitsuba_reference() {
    every_strategy("xml_principled", [256, 256, 256, 256, 256], 3370);
}

/// Power: `xml_principled.xml` with `-D trans=0.7` (the right sphere's spec_trans 0.7 for 0.9:
/// a transmission lobe weighted 22% low) fails, MIS 256 spp, seed 3380.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_principled_wrong_transmission_is_detected() {
    let m = import("xml_principled", &[("trans", "0.7")]);
    assert_detected("xml_principled", &m, 3380, "with trans=0.7");
}

/// `xml_principledthin.xml` (Mitsuba's thin principled BSDF: a default one on the floor, a
/// leaf lit from behind with a checkerboard base colour and diff_trans, sheen and some specular,
/// a thin bubble of spec_trans 0.8 with spec_tint, an anisotropic torus with a checkerboard η and
/// flatness, a plate with a checkerboard spec_trans and every sampling rate changed) against its
/// reference, seeds 3470–3474, 256 spp: per 16×16 block, except light-only, on the whole image
/// per channel. Light-only sampling reaches the light through the bubble's and the torus's thin
/// transmissions (α down to 0.016) only by next-event estimation at a sharp lobe, rare huge
/// samples (docs/testing.md, "Heavy tails"): per block it failed both stages at its first run
/// (stage 1: 3 of 60 blocks, |z| 4.06, all below the reference; stage 2: 4 blocks, |z| 5.16, in
/// other blocks, all below), and two 16384-spp light-only renders deviate from the reference by
/// −2.4% and +1.5% in one block where MIS at 16384 spp stays within 0.4% in every block. This
/// test was made whole-image after that failure; light-only per block is tested on
/// [`xml_principledthin_rough_matches_its_mitsuba_reference`]'s rough copy of the scene, where
/// the same estimator is not heavy-tailed.
#[test]
fn xml_principledthin_matches_its_mitsuba_reference() {
    let name = "xml_principledthin";
    let m = import(name, &[]);
    let rr = m.rr_depth.unwrap_or(5);
    let scene = Arc::new(Scene::from_desc(&m.desc).unwrap_or_else(|e| panic!("{e}")));
    let failures: Vec<String> = STRATEGIES
        .into_iter()
        .enumerate()
        .filter(|(_, s)| tier::runs(*s))
        .filter_map(|(i, strategy)| {
            let seed = 3470 + i as u32;
            let settings = Settings {
                strategy,
                rr_depth: rr,
                ..Settings::default()
            };
            let (block, whole) = match strategy {
                Strategy::Light => (u32::MAX, " (whole image)"),
                _ => (BLOCK, ""),
            };
            let what = format!("{name}.xml {strategy:?} 256 spp seed {seed}{whole}");
            compare_scene(name, &what, &scene, settings, 256, seed, block).err()
        })
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `xml_principledthin_rough.xml` (the thin principled scene with every roughness 0.7: no lobe
/// narrow enough for light-only sampling to be heavy-tailed) against its own reference in every
/// strategy per 16×16 block, seeds 3570–3574: light-only through thin transmissions per block.
#[test]
fn xml_principledthin_rough_matches_its_mitsuba_reference() {
    every_strategy("xml_principledthin_rough", [256, 256, 256, 256, 256], 3570);
}

/// Power of the rough copy's light-only test: its bubble's spec_trans 0.6 for 0.8 (`-D
/// trans=0.6`) fails light-only per block, 256 spp, seed 3580.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_principledthin_rough_light_only_detects_a_wrong_transmission() {
    let name = "xml_principledthin_rough";
    let m = import(name, &[("trans", "0.6")]);
    let rr = m.rr_depth.unwrap_or(5);
    assert!(
        compare(name, &m.desc, rr, Strategy::Light, 256, 3580).is_err(),
        "{name}.xml with trans=0.6 went undetected by light-only"
    );
}

/// Power: `xml_principledthin.xml` with `-D trans=0.6` (the bubble's spec_trans 0.6 for 0.8: its
/// specular lobes weighted 25% low, its diffuse ones doubled) fails, MIS 256 spp, seed 3480.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_principledthin_wrong_transmission_is_detected() {
    let m = import("xml_principledthin", &[("trans", "0.6")]);
    assert_detected("xml_principledthin", &m, 3480, "with trans=0.6");
}

/// `xml_textured_shapes.xml` (Mitsuba's texture coordinates on spheres and disks turned by
/// their `to_world`: a checkered sphere with a tilted pole, a checkered disk turned about its
/// normal, a sphere light with a checkered radiance, anisotropic gold about a tilted pole)
/// against its reference, seeds 2380–2384.
#[test]
fn xml_textured_shapes_matches_its_mitsuba_reference() {
    every_strategy("xml_textured_shapes", [256, 256, 256, 256, 256], 2380);
}

/// Power: `xml_textured_shapes.xml` with `-D turn=20` (the checkered sphere turned 20° about
/// its own pole: the same surface, its texture turned, what a sphere whose uv ignored the
/// rotation would render) fails, MIS 256 spp, seed 2390.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_textured_shapes_turned_sphere_is_detected() {
    let m = import("xml_textured_shapes", &[("turn", "20")]);
    assert_detected("xml_textured_shapes", &m, 2390, "with turn=20");
}

/// [`DELTA_STRATEGIES`] (BSDF-only never finds a delta light:
/// [`delta_lights_are_missing_from_bsdf_only`]) at 256 spp, seed `seed + i`, against the reference, and MIS (power)
/// with the light BVH's selection (which bounds a point light by its position, a spot or
/// projector by its cone, and samples a directional light with the lights at infinity), seed
/// `seed + 5`; panics with every failure.
fn every_strategy_seeing_delta_lights(name: &str, seed: u32) {
    let m = import(name, &[]);
    let rr = m.rr_depth.unwrap_or(5);
    let mut failures: Vec<String> = DELTA_STRATEGIES
        .into_iter()
        .enumerate()
        // The CI tier renders MIS (power) alone (`common/tier.rs`).
        .filter(|(_, s)| tier::runs(*s))
        .filter_map(|(i, s)| compare(name, &m.desc, rr, s, 256, seed + i as u32).err())
        .collect();
    let bvh = Settings {
        strategy: MIS,
        rr_depth: rr,
        light_selection: lumis::lights::LightSelection::Bvh,
        ..Settings::default()
    };
    failures.extend(compare_with(name, &m.desc, bvh, 256, seed + 5).err());
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Power: the MIS (power) render at 256 spp, `seed`, of `name`'s import with its built scene
/// changed by `mutate`, must fail against the reference; `what` names the change.
fn assert_scene_change_detected(
    name: &str,
    seed: u32,
    what: &str,
    mutate: impl FnOnce(&mut Scene),
) {
    let m = import(name, &[]);
    let mut scene = Scene::from_desc(&m.desc).unwrap_or_else(|e| panic!("{e}"));
    mutate(&mut scene);
    let scene = Arc::new(scene);
    let settings = Settings {
        strategy: MIS,
        rr_depth: m.rr_depth.unwrap_or(5),
        ..Settings::default()
    };
    let label = format!("{name}.xml {what} MIS 256 spp seed {seed}");
    let result = compare_scene(name, &label, &scene, settings, 256, seed, BLOCK);
    assert!(result.is_err(), "{label} went undetected");
}

/// `xml_point.xml` (Mitsuba's `point`: one by `position`, one by a `to_world` translation; the
/// camera scene's rectangle light and sky besides) against its reference, seeds 2300–2305.
#[test]
fn xml_point_matches_its_mitsuba_reference() {
    every_strategy_seeing_delta_lights("xml_point", 2300);
}

/// Power: the point lights 5% brighter (an intensity read with a wrong unit or spectrum
/// conversion) fails, seed 2340.
#[test]
fn xml_point_brighter_is_detected() {
    use lumis::lights::Light;
    assert_scene_change_detected("xml_point", 2340, "with intensity × 1.05", |s| {
        for l in &mut s.lights {
            if let Light::Point(p) = l {
                p.intensity *= 1.05;
            }
        }
    });
}

/// `xml_spot.xml` (Mitsuba's `spot`: cutoff 25° with beam width 15°, and cutoff 20° with the
/// default beam width and a bitmap texture projected through the cone) against its reference,
/// seeds 2310–2315.
#[test]
fn xml_spot_matches_its_mitsuba_reference() {
    every_strategy_seeing_delta_lights("xml_spot", 2310);
}

/// Power: the textured spot's texture mirrored left to right (its frame's x turned round: the
/// convention bug of `look_at`'s left-handed x) fails, seed 2341.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_spot_mirrored_texture_is_detected() {
    use lumis::lights::Light;
    assert_scene_change_detected("xml_spot", 2341, "with the texture mirrored", |s| {
        for l in &mut s.lights {
            if let Light::Spot(p) = l
                && p.texture != lumis::geometry::primitive::NONE
            {
                p.frame.s = -p.frame.s;
            }
        }
    });
}

/// `xml_directional.xml` (Mitsuba's `directional`: one by `direction`, one by a `to_world`
/// look-at) against its reference, seeds 2320–2325.
#[test]
fn xml_directional_matches_its_mitsuba_reference() {
    every_strategy_seeing_delta_lights("xml_directional", 2320);
}

/// Power: each directional light turned by 10° about the vertical (an error in the direction a
/// to_world gives) fails, seed 2342. A turn of 3° is not detected (measured 2026-12-06: worst
/// |z| 3.22 of 3.76, same seed): the shadows move by a pixel or two, which 16 × 16 blocks
/// average away.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_directional_turned_is_detected() {
    use lumis::lights::Light;
    let turn = glam::Mat3::from_rotation_y(10f32.to_radians());
    assert_scene_change_detected("xml_directional", 2342, "turned by 10°", |s| {
        for l in &mut s.lights {
            if let Light::Directional(d) = l {
                d.direction = turn * d.direction;
            }
        }
    });
}

/// `xml_projector.xml` (Mitsuba's `projector`: a 48 × 32 bitmap irradiance with `scale` 10 and
/// a horizontal fov of 30°, and a constant irradiance with fov 22°) against its reference, seeds
/// 2330–2335.
#[test]
fn xml_projector_matches_its_mitsuba_reference() {
    every_strategy_seeing_delta_lights("xml_projector", 2330);
}

/// Power: the projected image mirrored vertically (Mitsuba's v running the other way) fails,
/// seed 2343.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn xml_projector_flipped_image_is_detected() {
    use lumis::lights::Light;
    assert_scene_change_detected("xml_projector", 2343, "with the image flipped", |s| {
        for l in &mut s.lights {
            if let Light::Projector(p) = l
                && p.texture != lumis::geometry::primitive::NONE
            {
                p.frame.t = -p.frame.t;
            }
        }
    });
}

/// BSDF sampling alone never finds a delta light (no ray hits a point or a direction), so its
/// image of a scene lit by them lacks their light, by design: the BSDF-only render of
/// `xml_point.xml` fails against Mitsuba's reference (256 spp, seed 2344). This pins the
/// documented exclusion (the CLI and the viewer say so where it applies).
#[test]
fn delta_lights_are_missing_from_bsdf_only() {
    let m = import("xml_point", &[]);
    let rr = m.rr_depth.unwrap_or(5);
    assert!(compare("xml_point", &m.desc, rr, STRATEGIES[1], 256, 2344).is_err());
}
