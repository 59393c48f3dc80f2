//! WGSL sources and their specialisation.
//!
//! The maths lives once per side: one WGSL module per concept in `shaders/`, each the twin of the
//! Rust module it names (`materials/ggx.wgsl` ↔ `materials/ggx.rs`, `lights/sphere.wgsl` ↔
//! `lights/sphere.rs`, …), kept in step by `renderer/tests/gpu/parity.rs`; each names its Rust twin in its
//! header and the twin names it back (checked below). WGSL has no includes, so a program is the
//! concatenation of the modules it needs, after the generated prelude of shared constants and kind
//! tags ([`super::prelude`]).
//!
//! Specialisation is by generated source, not by branches on uniforms: a scene's [`Features`]
//! decide which modules are concatenated and which `// #if NAME` … `// #else` … `// #endif`
//! regions survive, so a scene without lights carries no light-sampling code, one without rough
//! microfacets no GGX, one of a handful of primitives no BVH traversal. Compiling only what a
//! scene uses keeps register pressure and driver compile time down (the whole program is one
//! megakernel).

use super::GpuError;
use super::prelude::{self, Constant};
use crate::lights::Light;
use crate::materials::{ConductorFresnel, Distribution, Material};
use crate::scene::Scene;

/// One WGSL module: its path under `src/` (beside its Rust twin) and text.
struct Module {
    name: &'static str,
    text: &'static str,
}

macro_rules! module {
    ($name:literal) => {
        Module {
            name: $name,
            text: include_str!(concat!("../", $name)),
        }
    };
}

/// Every module, in concatenation order (WGSL allows any order; this one reads top-down).
const MODULES: &[Module] = &[
    module!("gpu/prelude.wgsl"),
    module!("math.wgsl"),
    module!("erf.wgsl"),
    module!("rng.wgsl"),
    module!("gpu/u64.wgsl"),
    module!("sampler/morton.wgsl"),
    module!("sampler/sobol.wgsl"),
    module!("sampler/owen.wgsl"),
    module!("sampler/zsobol.wgsl"),
    module!("sampler/mod.wgsl"),
    module!("camera/filter.wgsl"),
    module!("sampling/disk.wgsl"),
    module!("sampling/hemisphere.wgsl"),
    module!("sampling/sphere.wgsl"),
    module!("sampling/triangle.wgsl"),
    module!("sampling/spherical_triangle.wgsl"),
    module!("sampling/spherical_rectangle.wgsl"),
    module!("sampling/elliptic.wgsl"),
    module!("sampling/spherical_ellipse.wgsl"),
    module!("sampling/bilinear.wgsl"),
    module!("sampling/projected_solid_angle.wgsl"),
    module!("materials/fresnel.wgsl"),
    module!("materials/ggx.wgsl"),
    module!("materials/beckmann.wgsl"),
    module!("materials/microfacet.wgsl"),
    module!("integrator/mis.wgsl"),
    module!("integrator/optimal.wgsl"),
    module!("materials/mod.wgsl"),
    module!("materials/diffuse.wgsl"),
    module!("materials/conductor.wgsl"),
    module!("materials/plastic.wgsl"),
    module!("materials/plastic_mitsuba.wgsl"),
    module!("materials/dielectric.wgsl"),
    module!("materials/thin_dielectric.wgsl"),
    module!("materials/gtr1.wgsl"),
    module!("materials/principled.wgsl"),
    module!("materials/principled_thin.wgsl"),
    module!("materials/gltf_pbr.wgsl"),
    module!("lights/mod.wgsl"),
    module!("lights/light_sampler.wgsl"),
    module!("lights/light_bvh.wgsl"),
    module!("lights/projected.wgsl"),
    module!("lights/triangle.wgsl"),
    module!("lights/polygon.wgsl"),
    module!("lights/quad.wgsl"),
    module!("lights/disk.wgsl"),
    module!("lights/sphere.wgsl"),
    module!("lights/background.wgsl"),
    module!("lights/envmap.wgsl"),
    module!("lights/point.wgsl"),
    module!("lights/spot.wgsl"),
    module!("lights/directional.wgsl"),
    module!("lights/projector.wgsl"),
    module!("geometry/ray.wgsl"),
    module!("geometry/triangle.wgsl"),
    module!("geometry/disk.wgsl"),
    module!("geometry/sphere.wgsl"),
    module!("geometry/cylinder.wgsl"),
    module!("geometry/primitive.wgsl"),
    module!("geometry/mesh_attributes.wgsl"),
    module!("geometry/tangent.wgsl"),
    module!("textures/mod.wgsl"),
    module!("materials/mix.wgsl"),
    module!("materials/two_sided.wgsl"),
    module!("materials/mask.wgsl"),
    module!("materials/normal_map.wgsl"),
    module!("geometry/bvh.wgsl"),
    module!("gpu/bvh2.wgsl"),
    module!("gpu/bindings.wgsl"),
];

/// The path tracer's modules after the library: the integrator, the camera's primary ray and the
/// render kernel (entry points `render` and `fold`), which the parity kernels do without.
const PATH_MODULES: &[Module] = &[
    module!("integrator/path.wgsl"),
    module!("camera.wgsl"),
    module!("gpu/film.wgsl"),
];

/// What a scene uses, deciding which code a pipeline contains.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Features {
    /// Something can be sampled by next-event estimation (the scene has a light sampler).
    pub has_lights: bool,
    /// A background light that rays which miss see: a non-black constant or an environment map.
    pub has_background: bool,
    /// An environment map (its lookup, sampling and texture binding, `lights/envmap.wgsl`).
    pub has_envmap: bool,
    /// Emitting triangles (`triangles` meshes).
    pub has_triangle_light: bool,
    /// Emitting polygons.
    pub has_polygon_light: bool,
    /// Emitting quads or boxes.
    pub has_quad_light: bool,
    /// Emitting disks.
    pub has_disk_light: bool,
    /// Emitting spheres.
    pub has_sphere_light: bool,
    /// Point lights.
    pub has_point_light: bool,
    /// Spot lights.
    pub has_spot_light: bool,
    /// Directional lights.
    pub has_directional_light: bool,
    /// Projectors.
    pub has_projector_light: bool,
    /// A BVH (more than [`crate::geometry::Accel::LINEAR_LIMIT`] primitives).
    pub use_bvh: bool,
    /// With [`Features::use_bvh`]: traverse a BVH2 (`gpu/bvh2.wgsl`, built at upload) instead of the
    /// default CWBVH (`geometry/bvh.wgsl`). Kept to measure the two against each other; never set by
    /// [`Features::of`], only by an explicit choice ([`crate::gpu::GpuScene::with_bvh2`]).
    pub bvh2: bool,
    /// A microfacet lobe rough enough not to be a mirror (conductor, dielectric or plastic coat;
    /// any distribution: the GGX functions and the distribution dispatch).
    pub has_ggx: bool,
    /// A conductor, dielectric or Mitsuba-coupled plastic with Beckmann microfacets
    /// (`materials/beckmann.wgsl`).
    pub has_beckmann: bool,
    /// A rough material with α_u ≠ α_v: shading frames along the surface's ∂p/∂u
    /// (`geometry/tangent.wgsl`, mesh UVs).
    pub has_anisotropic: bool,
    /// Conductors.
    pub has_conductor: bool,
    /// Conductors with a complex IOR (exact Fresnel).
    pub has_complex_fresnel: bool,
    /// Plastics with lumis' coupling.
    pub has_plastic: bool,
    /// Plastics with Mitsuba's coupling (`materials/plastic_mitsuba.wgsl`).
    pub has_mitsuba_plastic: bool,
    /// Dielectrics (glass).
    pub has_dielectric: bool,
    /// Thin dielectric sheets (`materials/thin_dielectric.wgsl`).
    pub has_thin_dielectric: bool,
    /// Mitsuba's principled BSDF (`materials/principled.wgsl`, `materials/gtr1.wgsl`).
    pub has_principled: bool,
    /// A principled with specular transmission (its back side is the inside).
    pub has_principled_transmission: bool,
    /// Mitsuba's thin principled BSDF (`materials/principled_thin.wgsl`, with the principled's
    /// helpers).
    pub has_principled_thin: bool,
    /// glTF's metallic-roughness material (`materials/gltf_pbr.wgsl`).
    pub has_gltf_pbr: bool,
    /// Disk shapes.
    pub has_disk_shape: bool,
    /// Sphere shapes.
    pub has_sphere_shape: bool,
    /// Cylinder shapes (`geometry/cylinder.wgsl`).
    pub has_cylinder_shape: bool,
    /// Triangles with vertex normals: the BSDF frame follows the interpolated shading normal and
    /// the shading-normal rule applies (`geometry/mesh_attributes.wgsl`, `same_side` in `integrator/path.wgsl`).
    pub has_shading_normals: bool,
    /// Textured materials or emission: texture lookups at each hit's texture coordinates
    /// (`textures/mod.wgsl`, `material_at` in `materials/mod.wgsl`, `surface_uv` in `geometry/primitive.wgsl`), at
    /// points sampled on textured lights (`light_sample_textured` in `lights/mod.wgsl`) and the
    /// texel binding.
    pub has_textures: bool,
    /// Mixes of materials or two-sided pairs, resolved at each hit (`materials/mix.wgsl`,
    /// `materials/two_sided.wgsl`; a textured weight also sets [`Features::has_textures`]).
    pub has_mixes: bool,
    /// A pixel filter with negative lobes (Lanczos, Mitchell): its piecewise sampling in
    /// `camera/filter.wgsl`, which programs without one leave out.
    pub has_signed_filter: bool,
    /// Normal maps (`materials/normal_map.wgsl`): texture lookups (as with
    /// [`Features::has_textures`]) and frames along ∂p/∂u (`geometry/tangent.wgsl`).
    pub has_normal_maps: bool,
    /// Alpha masks (`materials/mask.wgsl`): the traversals' any-hit test, with texture lookups
    /// (as with [`Features::has_textures`]) and `materials/mix.wgsl`'s hash. Like the BVH flags
    /// it follows the scene's data (the opacity records lead `tables` only in a scene with
    /// masks), so a program with it reads that scene's records only.
    pub has_masks: bool,
    /// `mesh_attribute` textures: the named attribute lookup of `geometry/mesh_attributes.wgsl`
    /// (texture lookups as with [`Features::has_textures`]).
    pub has_mesh_attributes: bool,
}

impl Features {
    /// Everything on: the kernels of the parity tests, which call every function.
    pub fn all() -> Features {
        Features {
            has_lights: true,
            has_background: true,
            has_envmap: true,
            has_triangle_light: true,
            has_polygon_light: true,
            has_quad_light: true,
            has_disk_light: true,
            has_sphere_light: true,
            has_point_light: true,
            has_spot_light: true,
            has_directional_light: true,
            has_projector_light: true,
            use_bvh: true,
            bvh2: false,
            has_ggx: true,
            has_beckmann: true,
            has_anisotropic: true,
            has_conductor: true,
            has_complex_fresnel: true,
            has_plastic: true,
            has_mitsuba_plastic: true,
            has_dielectric: true,
            has_thin_dielectric: true,
            has_principled: true,
            has_principled_transmission: true,
            has_principled_thin: true,
            has_gltf_pbr: true,
            has_disk_shape: true,
            has_sphere_shape: true,
            has_cylinder_shape: true,
            has_shading_normals: true,
            has_textures: true,
            has_mixes: true,
            has_signed_filter: true,
            has_normal_maps: true,
            has_masks: true,
            has_mesh_attributes: true,
        }
    }

    /// What `scene` needs.
    pub fn of(scene: &Scene) -> Features {
        use crate::geometry::Shape;
        use crate::materials::ggx::is_smooth;
        let mut f = Features {
            has_lights: scene.light_sampler.is_some(),
            // Needed by rays that miss whether or not the map can be sampled.
            has_envmap: scene.lights.iter().any(|l| matches!(l, Light::Envmap(_))),
            use_bvh: scene.accel.cwbvh().is_some(),
            // The CPU's test too (`integrator/path.rs`).
            has_shading_normals: scene.attributes.has_normals(),
            has_textures: scene.material_textures.iter().any(Option::is_some)
                || !scene.emission_textures.is_empty(),
            has_mixes: scene.mixes.iter().any(Option::is_some) || !scene.sides.is_empty(),
            has_signed_filter: scene.camera.filter.is_signed(),
            has_normal_maps: !scene.normal_maps.is_empty(),
            has_masks: !scene.opacity.is_empty(),
            has_mesh_attributes: !scene.attributes.named_slots.is_empty(),
            ..Features::default()
        };
        // A mix's textured weight is looked up like a material's texture.
        f.has_textures |= scene
            .mixes
            .iter()
            .flatten()
            .any(|m| !matches!(m.weight, crate::textures::Texture::Constant(_)));
        // Light kinds matter only for sampling; emission seen by rays needs no per-kind code.
        if f.has_lights {
            for l in &scene.lights {
                match l {
                    Light::Triangle(_) => f.has_triangle_light = true,
                    Light::Polygon(_) => f.has_polygon_light = true,
                    Light::Quad(_) => f.has_quad_light = true,
                    Light::Disk(_) => f.has_disk_light = true,
                    Light::Sphere(_) => f.has_sphere_light = true,
                    Light::Background(_) | Light::Envmap(_) => f.has_background = true,
                    Light::Point(_) => f.has_point_light = true,
                    Light::Spot(_) => f.has_spot_light = true,
                    Light::Directional(_) => f.has_directional_light = true,
                    Light::Projector(_) => f.has_projector_light = true,
                }
            }
        }
        f.has_background |= scene.background_light.is_some();
        for m in &scene.materials {
            f.has_anisotropic |= m.is_anisotropic();
            match m {
                Material::Diffuse(_) => {}
                Material::Conductor(c) => {
                    f.has_conductor = true;
                    f.has_ggx |= !c.is_delta();
                    // Even where smooth: a textured α may make it rough at a hit.
                    f.has_beckmann |= c.microfacet.distribution == Distribution::Beckmann;
                    f.has_complex_fresnel |= matches!(c.fresnel, ConductorFresnel::Complex { .. });
                }
                Material::Plastic(p) => {
                    let mitsuba = p.mitsuba_coat().is_some();
                    f.has_plastic |= !mitsuba;
                    f.has_mitsuba_plastic |= mitsuba;
                    f.has_ggx |= !is_smooth(p.alpha());
                    f.has_beckmann |= p.distribution() == Distribution::Beckmann;
                }
                Material::Dielectric(d) => {
                    f.has_dielectric = true;
                    f.has_ggx |= !d.is_delta();
                    f.has_beckmann |= d.microfacet.distribution == Distribution::Beckmann;
                }
                Material::ThinDielectric(_) => f.has_thin_dielectric = true,
                // Always rough (α ≥ 0.001), always GGX.
                Material::Principled(p) => {
                    f.has_principled = true;
                    f.has_principled_transmission |= p.transmission;
                    f.has_ggx = true;
                }
                Material::PrincipledThin(_) => {
                    f.has_principled_thin = true;
                    f.has_ggx = true;
                }
                // Always rough (α ≥ 0.001), always GGX.
                Material::GltfPbr(_) => {
                    f.has_gltf_pbr = true;
                    f.has_ggx = true;
                }
            }
        }
        // A textured α may be rough where the material's constant (its mean) is smooth; a
        // textured pair anisotropic where its means are equal.
        for (t, m) in scene.material_textures.iter().zip(&scene.materials) {
            let Some(t) = t else { continue };
            f.has_ggx |= t.alpha.is_some();
            f.has_anisotropic |= t.alpha_v.is_some();
            // A textured anisotropy may be non-zero where its mean is (a glTF material's slot 1
            // is its metallic).
            f.has_anisotropic |= t.principled[1].is_some() && !matches!(m, Material::GltfPbr(_));
        }
        for p in scene.accel.primitives() {
            match p.shape {
                Shape::Triangle { .. } => {}
                Shape::Disk(_) => f.has_disk_shape = true,
                Shape::Sphere(_) => f.has_sphere_shape = true,
                Shape::Cylinder(_) => f.has_cylinder_shape = true,
            }
        }
        // Area sampling of a sphere light re-traces the sphere.
        f.has_sphere_shape |= f.has_sphere_light;
        f
    }

    /// Texture lookups: textured parameters or emission, normal maps, or masks (whose constant
    /// opacities are texture records too).
    fn textures(&self) -> bool {
        self.has_textures || self.has_normal_maps || self.has_masks
    }

    /// A principled, thin or not.
    fn principled_family(&self) -> bool {
        self.has_principled || self.has_principled_thin
    }

    /// A material that light passes through ([`Material::transmits`]).
    pub fn has_transmission(&self) -> bool {
        self.has_dielectric
            || self.has_thin_dielectric
            || self.has_principled_transmission
            || self.has_principled_thin
    }

    /// Whether the scene has a delta light (point, spot, directional, projector).
    pub fn has_delta_light(&self) -> bool {
        self.has_point_light
            || self.has_spot_light
            || self.has_directional_light
            || self.has_projector_light
    }

    /// The `#if` names and their values.
    fn defines(&self) -> [(&'static str, bool); 43] {
        [
            ("HAS_LIGHTS", self.has_lights),
            ("HAS_BACKGROUND", self.has_background),
            ("HAS_ENVMAP", self.has_envmap),
            (
                "HAS_TRIANGLE_LIGHT",
                self.has_lights && self.has_triangle_light,
            ),
            (
                "HAS_POLYGON_LIGHT",
                self.has_lights && self.has_polygon_light,
            ),
            ("HAS_QUAD_LIGHT", self.has_lights && self.has_quad_light),
            ("HAS_DISK_LIGHT", self.has_lights && self.has_disk_light),
            ("HAS_SPHERE_LIGHT", self.has_lights && self.has_sphere_light),
            ("HAS_POINT_LIGHT", self.has_lights && self.has_point_light),
            ("HAS_SPOT_LIGHT", self.has_lights && self.has_spot_light),
            (
                "HAS_DIRECTIONAL_LIGHT",
                self.has_lights && self.has_directional_light,
            ),
            (
                "HAS_PROJECTOR_LIGHT",
                self.has_lights && self.has_projector_light,
            ),
            // Next-event estimation's delta branch (`delta_light` in `integrator/path.wgsl`).
            ("HAS_DELTA_LIGHT", self.has_lights && self.has_delta_light()),
            ("USE_BVH", self.use_bvh),
            ("USE_CWBVH", self.use_bvh && !self.bvh2),
            ("USE_BVH2", self.use_bvh && self.bvh2),
            ("HAS_GGX", self.has_ggx),
            ("HAS_BECKMANN", self.has_ggx && self.has_beckmann),
            ("HAS_ANISOTROPIC", self.has_anisotropic),
            ("HAS_MESH_UVS", self.textures() || self.has_anisotropic),
            ("HAS_CONDUCTOR", self.has_conductor),
            ("HAS_COMPLEX_FRESNEL", self.has_complex_fresnel),
            ("HAS_PLASTIC", self.has_plastic),
            ("HAS_MITSUBA_PLASTIC", self.has_mitsuba_plastic),
            ("HAS_DIELECTRIC", self.has_dielectric),
            ("HAS_THIN_DIELECTRIC", self.has_thin_dielectric),
            ("HAS_PRINCIPLED", self.has_principled),
            ("HAS_PRINCIPLED_THIN", self.has_principled_thin),
            ("HAS_GLTF_PBR", self.has_gltf_pbr),
            // A material that light passes through: the path tracer's transmission code.
            ("HAS_TRANSMISSION", self.has_transmission()),
            // A material that refracts (glass, a transmitting principled; not a thin sheet).
            (
                "HAS_REFRACTION",
                self.has_dielectric || self.has_principled_transmission,
            ),
            // The exact dielectric Fresnel: glass, thin sheets, Mitsuba's plastic coat and the
            // principled's main lobe (thin or not).
            (
                "HAS_DIELECTRIC_FRESNEL",
                self.has_dielectric
                    || self.has_thin_dielectric
                    || self.has_mitsuba_plastic
                    || self.principled_family(),
            ),
            ("HAS_DISK_SHAPE", self.has_disk_shape),
            ("HAS_SPHERE_SHAPE", self.has_sphere_shape),
            ("HAS_CYLINDER_SHAPE", self.has_cylinder_shape),
            ("HAS_SHADING_NORMALS", self.has_shading_normals),
            ("HAS_TEXTURES", self.textures()),
            ("HAS_MIXES", self.has_mixes),
            ("HAS_SIGNED_FILTER", self.has_signed_filter),
            ("HAS_NORMAL_MAPS", self.has_normal_maps),
            ("HAS_MASKS", self.has_masks),
            (
                "HAS_MESH_ATTRIBUTES",
                self.textures() && self.has_mesh_attributes,
            ),
            // The mutation points of `crate::mutants` (only with the `mutants` feature).
            ("MUTANTS", cfg!(feature = "mutants")),
        ]
    }

    fn define(&self, name: &str) -> Option<bool> {
        self.defines()
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, v)| *v)
    }

    /// Whether module `name` belongs in the program.
    fn wants(&self, name: &str) -> bool {
        let lights = self.has_lights;
        match name {
            "sampling/spherical_triangle.wgsl"
            | "lights/light_sampler.wgsl"
            | "lights/light_bvh.wgsl"
            | "sampling/bilinear.wgsl" => lights,
            "sampling/projected_solid_angle.wgsl" | "lights/projected.wgsl" => {
                lights && (self.has_triangle_light || self.has_quad_light || self.has_polygon_light)
            }
            "sampling/spherical_rectangle.wgsl" | "lights/quad.wgsl" => {
                lights && self.has_quad_light
            }
            "lights/triangle.wgsl" => lights && self.has_triangle_light,
            "lights/polygon.wgsl" => lights && self.has_polygon_light,
            "lights/disk.wgsl" | "sampling/elliptic.wgsl" | "sampling/spherical_ellipse.wgsl" => {
                lights && self.has_disk_light
            }
            "lights/sphere.wgsl" => lights && self.has_sphere_light,
            "lights/point.wgsl" => lights && self.has_delta_light(),
            "lights/spot.wgsl" => lights && self.has_spot_light,
            "lights/directional.wgsl" => lights && self.has_directional_light,
            "lights/projector.wgsl" => lights && self.has_projector_light,
            "lights/background.wgsl" => lights && self.has_background,
            "lights/envmap.wgsl" => self.has_envmap,
            "materials/fresnel.wgsl" => {
                self.has_conductor
                    || self.has_plastic
                    || self.has_mitsuba_plastic
                    || self.has_dielectric
                    || self.has_thin_dielectric
                    || self.principled_family()
                    || self.has_gltf_pbr
            }
            "materials/ggx.wgsl" => self.has_ggx,
            "materials/beckmann.wgsl" => self.has_ggx && self.has_beckmann,
            "materials/microfacet.wgsl" => {
                self.has_conductor
                    || self.has_dielectric
                    || self.has_mitsuba_plastic
                    || self.principled_family()
            }
            "materials/conductor.wgsl" => self.has_conductor,
            "materials/plastic.wgsl" => self.has_plastic,
            "materials/plastic_mitsuba.wgsl" => self.has_mitsuba_plastic,
            "materials/dielectric.wgsl" => self.has_dielectric,
            "materials/thin_dielectric.wgsl" => self.has_thin_dielectric,
            // The thin one shares the principled's helpers (which call GTR1's).
            "materials/gtr1.wgsl" | "materials/principled.wgsl" => self.principled_family(),
            "materials/principled_thin.wgsl" => self.has_principled_thin,
            "materials/gltf_pbr.wgsl" => self.has_gltf_pbr,
            // A disk light's ellipse samples find their point as a disk hit does.
            "geometry/disk.wgsl" => self.has_disk_shape || (lights && self.has_disk_light),
            // A cylinder's intersection solves the sphere's quadratic (`careful_roots`).
            "geometry/sphere.wgsl" => self.has_sphere_shape || self.has_cylinder_shape,
            "gpu/bvh2.wgsl" => self.use_bvh && self.bvh2,
            // Texture coordinates of mesh triangles too.
            "geometry/mesh_attributes.wgsl" => {
                self.has_shading_normals || self.textures() || self.has_anisotropic
            }
            "geometry/tangent.wgsl" => self.has_anisotropic || self.has_normal_maps,
            "textures/mod.wgsl" => self.textures(),
            // Masks draw their decisions with the mixes' hash (the resolve loop beside it calls
            // the pairs' choice).
            "materials/mix.wgsl" | "materials/two_sided.wgsl" => self.has_mixes || self.has_masks,
            "materials/mask.wgsl" => self.has_masks,
            _ => true,
        }
    }
}

/// Keeps the lines of `text` whose `// #if` conditions hold under `features`. Conditions are a
/// name or `!name`; regions nest.
fn preprocess(file: &str, text: &str, features: &Features) -> Result<String, GpuError> {
    let mut out = String::with_capacity(text.len());
    // (this region is emitted, the enclosing region is emitted)
    let mut stack: Vec<(bool, bool)> = Vec::new();
    let active = |stack: &[(bool, bool)]| stack.last().is_none_or(|s| s.0);
    for (i, line) in text.lines().enumerate() {
        let t = line.trim();
        let err = |what: &str| GpuError::Shader(format!("{file}:{}: {what}", i + 1));
        if let Some(cond) = t.strip_prefix("// #if ") {
            let cond = cond.trim();
            let (neg, name) = match cond.strip_prefix('!') {
                Some(n) => (true, n),
                None => (false, cond),
            };
            let value = features
                .define(name)
                .ok_or_else(|| err(&format!("unknown feature {name}")))?;
            let outer = active(&stack);
            stack.push((outer && (value != neg), outer));
        } else if t == "// #else" {
            let (on, outer) = stack.pop().ok_or_else(|| err("#else without #if"))?;
            stack.push((outer && !on, outer));
        } else if t == "// #endif" {
            stack.pop().ok_or_else(|| err("#endif without #if"))?;
        } else if active(&stack) {
            out.push_str(line);
            out.push('\n');
        }
    }
    if !stack.is_empty() {
        return Err(GpuError::Shader(format!("{file}: unterminated #if")));
    }
    Ok(out)
}

/// The prelude, the library (every module `features` wants) and `kernel`, the program's entry
/// points.
pub fn library_source(features: &Features, kernel: &str) -> Result<String, GpuError> {
    library_source_with(&prelude::constants(), features, kernel)
}

/// [`library_source`] with the prelude written from `constants` (a test's altered table).
pub(crate) fn library_source_with(
    constants: &[Constant],
    features: &Features,
    kernel: &str,
) -> Result<String, GpuError> {
    let mut src = library(constants, features)?;
    src += "// ---- kernel ----\n";
    src += &preprocess("kernel", kernel, features)?;
    Ok(src)
}

/// The prelude and every module `features` wants.
fn library(constants: &[Constant], features: &Features) -> Result<String, GpuError> {
    let mut src = String::from("// ---- prelude ----\n");
    src += &prelude::source(constants);
    let wanted = MODULES.iter().filter(|m| features.wants(m.name));
    append_modules(&mut src, wanted, features)?;
    Ok(src)
}

/// Appends each of `modules`, preprocessed for `features`, under a line naming it.
fn append_modules<'a>(
    src: &mut String,
    modules: impl IntoIterator<Item = &'a Module>,
    features: &Features,
) -> Result<(), GpuError> {
    for m in modules {
        *src += &format!("// ---- {} ----\n", m.name);
        *src += &preprocess(m.name, m.text, features)?;
    }
    Ok(())
}

/// The path tracer's source for `features` (entry points `render` and `fold`): the library and
/// [`PATH_MODULES`].
pub fn path_tracer_source(features: &Features) -> Result<String, GpuError> {
    let mut src = library(&prelude::constants(), features)?;
    append_modules(&mut src, PATH_MODULES, features)?;
    Ok(src)
}

/// Parses and validates `source` with naga, so a broken shader is a [`GpuError::Shader`] with
/// the offending line instead of a wgpu panic.
pub fn validate(source: &str) -> Result<(), GpuError> {
    use wgpu::naga;
    let module = naga::front::wgsl::parse_str(source)
        .map_err(|e| GpuError::Shader(e.emit_to_string(source)))?;
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::empty(),
    )
    .validate(&module)
    .map_err(|e| GpuError::Shader(e.emit_to_string(source)))?;
    Ok(())
}

/// Creates a shader module from validated source.
pub fn create_module(
    device: &wgpu::Device,
    label: &str,
    source: &str,
) -> Result<wgpu::ShaderModule, GpuError> {
    validate(source)?;
    let desc = wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    };
    Ok(device.create_shader_module(desc))
}

#[cfg(test)]
#[path = "shader_tests.rs"]
mod shader_tests;
