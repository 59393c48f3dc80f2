//! WGSL sources and their specialisation.
//!
//! The maths lives once per side: one WGSL module per concept in `shaders/`, each the twin of the
//! Rust module it names (`ggx.wgsl` ↔ `materials/ggx.rs`, `sphere_light.wgsl` ↔
//! `lights/sphere.rs`, …), kept in step by `tests/gpu_parity.rs`; each names its Rust twin in its
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
use crate::materials::{ConductorFresnel, Material};
use crate::scene::Scene;

/// One WGSL module: its file name and text.
struct Module {
    name: &'static str,
    text: &'static str,
}

macro_rules! module {
    ($name:literal) => {
        Module {
            name: $name,
            text: include_str!(concat!("shaders/", $name)),
        }
    };
}

/// Every module, in concatenation order (WGSL allows any order; this one reads top-down).
const MODULES: &[Module] = &[
    module!("tags.wgsl"),
    module!("math.wgsl"),
    module!("rng.wgsl"),
    module!("warps.wgsl"),
    module!("spherical_triangle.wgsl"),
    module!("spherical_rectangle.wgsl"),
    module!("fresnel.wgsl"),
    module!("ggx.wgsl"),
    module!("mis.wgsl"),
    module!("material.wgsl"),
    module!("diffuse.wgsl"),
    module!("conductor.wgsl"),
    module!("plastic.wgsl"),
    module!("dielectric.wgsl"),
    module!("light.wgsl"),
    module!("light_sampler.wgsl"),
    module!("triangle_light.wgsl"),
    module!("polygon_light.wgsl"),
    module!("quad_light.wgsl"),
    module!("disk_light.wgsl"),
    module!("sphere_light.wgsl"),
    module!("background_light.wgsl"),
    module!("envmap_light.wgsl"),
    module!("ray.wgsl"),
    module!("triangle.wgsl"),
    module!("disk.wgsl"),
    module!("sphere.wgsl"),
    module!("shape.wgsl"),
    module!("mesh_attributes.wgsl"),
    module!("bvh.wgsl"),
    module!("bvh2.wgsl"),
    module!("bindings.wgsl"),
];

/// The render kernel's module (entry point `render`).
const PATH_MODULE: Module = module!("path.wgsl");

/// What a scene uses, deciding which code a pipeline contains.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Features {
    /// Something can be sampled by next-event estimation (the scene has a light sampler).
    pub has_lights: bool,
    /// A background light that rays which miss see: a non-black constant or an environment map.
    pub has_background: bool,
    /// An environment map (its lookup, sampling and texture binding, `envmap_light.wgsl`).
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
    /// A BVH (more than [`crate::geometry::Accel::LINEAR_LIMIT`] primitives).
    pub use_bvh: bool,
    /// With [`Features::use_bvh`]: traverse a BVH2 (`bvh2.wgsl`, built at upload) instead of the
    /// default CWBVH (`bvh.wgsl`). Kept to measure the two against each other; never set by
    /// [`Features::of`], only by an explicit choice ([`crate::gpu::GpuScene::with_bvh2`]).
    pub bvh2: bool,
    /// A microfacet lobe rough enough not to be a mirror (conductor or plastic coat).
    pub has_ggx: bool,
    /// Conductors.
    pub has_conductor: bool,
    /// Conductors with a complex IOR (exact Fresnel).
    pub has_complex_fresnel: bool,
    /// Plastics.
    pub has_plastic: bool,
    /// Dielectrics (glass): transmission in the path tracer.
    pub has_dielectric: bool,
    /// Disk shapes.
    pub has_disk_shape: bool,
    /// Sphere shapes.
    pub has_sphere_shape: bool,
    /// Triangles with vertex normals: the BSDF frame follows the interpolated shading normal and
    /// the shading-normal rule applies (`mesh_attributes.wgsl`, `same_side` in `path.wgsl`).
    pub has_shading_normals: bool,
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
            use_bvh: true,
            bvh2: false,
            has_ggx: true,
            has_conductor: true,
            has_complex_fresnel: true,
            has_plastic: true,
            has_dielectric: true,
            has_disk_shape: true,
            has_sphere_shape: true,
            has_shading_normals: true,
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
            ..Features::default()
        };
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
                }
            }
        }
        f.has_background |= scene.background_light.is_some();
        for m in &scene.materials {
            match m {
                Material::Diffuse(_) => {}
                Material::Conductor(c) => {
                    f.has_conductor = true;
                    f.has_ggx |= !c.is_delta();
                    f.has_complex_fresnel |= matches!(c.fresnel, ConductorFresnel::Complex { .. });
                }
                Material::Plastic(p) => {
                    f.has_plastic = true;
                    f.has_ggx |= !is_smooth(p.alpha());
                }
                Material::Dielectric(d) => {
                    f.has_dielectric = true;
                    f.has_ggx |= !d.is_delta();
                }
            }
        }
        for p in scene.accel.primitives() {
            match p.shape {
                Shape::Triangle { .. } => {}
                Shape::Disk(_) => f.has_disk_shape = true,
                Shape::Sphere(_) => f.has_sphere_shape = true,
            }
        }
        // Area sampling of a sphere light re-traces the sphere.
        f.has_sphere_shape |= f.has_sphere_light;
        f
    }

    /// The `#if` names and their values.
    fn defines(&self) -> [(&'static str, bool); 20] {
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
            ("USE_BVH", self.use_bvh),
            ("USE_CWBVH", self.use_bvh && !self.bvh2),
            ("USE_BVH2", self.use_bvh && self.bvh2),
            ("HAS_GGX", self.has_ggx),
            ("HAS_CONDUCTOR", self.has_conductor),
            ("HAS_COMPLEX_FRESNEL", self.has_complex_fresnel),
            ("HAS_PLASTIC", self.has_plastic),
            ("HAS_DIELECTRIC", self.has_dielectric),
            ("HAS_DISK_SHAPE", self.has_disk_shape),
            ("HAS_SPHERE_SHAPE", self.has_sphere_shape),
            ("HAS_SHADING_NORMALS", self.has_shading_normals),
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
            "spherical_triangle.wgsl" | "light_sampler.wgsl" => lights,
            "spherical_rectangle.wgsl" | "quad_light.wgsl" => lights && self.has_quad_light,
            "triangle_light.wgsl" => lights && self.has_triangle_light,
            "polygon_light.wgsl" => lights && self.has_polygon_light,
            "disk_light.wgsl" => lights && self.has_disk_light,
            "sphere_light.wgsl" => lights && self.has_sphere_light,
            "background_light.wgsl" => lights && self.has_background,
            "envmap_light.wgsl" => self.has_envmap,
            "fresnel.wgsl" => self.has_conductor || self.has_plastic || self.has_dielectric,
            "ggx.wgsl" => self.has_ggx,
            "conductor.wgsl" => self.has_conductor,
            "plastic.wgsl" => self.has_plastic,
            "dielectric.wgsl" => self.has_dielectric,
            "disk.wgsl" => self.has_disk_shape,
            "sphere.wgsl" => self.has_sphere_shape,
            "bvh2.wgsl" => self.use_bvh && self.bvh2,
            // Textures (UV lookups) will need it too.
            "mesh_attributes.wgsl" => self.has_shading_normals,
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
    let mut src = String::from("// ---- prelude ----\n");
    src += &prelude::source(constants);
    for m in MODULES.iter().filter(|m| features.wants(m.name)) {
        src += &format!("// ---- {} ----\n", m.name);
        src += &preprocess(m.name, m.text, features)?;
    }
    src += "// ---- kernel ----\n";
    src += &preprocess("kernel", kernel, features)?;
    Ok(src)
}

/// The path tracer's source for `features` (entry point `render`).
pub fn path_tracer_source(features: &Features) -> Result<String, GpuError> {
    library_source(features, PATH_MODULE.text)
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
mod tests {
    use super::*;

    #[test]
    fn every_prelude_constant_is_used_by_the_shaders() {
        // An unused one is dead, or a module kept a copy under another name.
        let text: String = MODULES
            .iter()
            .chain([&PATH_MODULE])
            .map(|m| m.text)
            .collect();
        let ident = |c: Option<char>| c.is_some_and(|c| c.is_ascii_alphanumeric() || c == '_');
        for c in prelude::constants() {
            let used = text.match_indices(c.name).any(|(i, _)| {
                !ident(text[..i].chars().next_back())
                    && !ident(text[i + c.name.len()..].chars().next())
            });
            assert!(
                used,
                "{} is in the prelude but no WGSL module uses it",
                c.name
            );
        }
    }

    #[test]
    fn preprocessor_keeps_the_right_regions() {
        let f = Features {
            has_ggx: true,
            ..Features::default()
        };
        let text = "a\n// #if HAS_GGX\nb\n// #if HAS_PLASTIC\nc\n// #else\nd\n// #endif\n// #else\ne\n// #endif\n// #if !USE_BVH\nf\n// #endif\n";
        assert_eq!(preprocess("t", text, &f).unwrap(), "a\nb\nd\nf\n");
        assert!(preprocess("t", "// #if NOPE\n// #endif\n", &f).is_err());
        assert!(preprocess("t", "// #if HAS_GGX\n", &f).is_err());
    }

    #[test]
    fn every_specialisation_validates() {
        // The full library and a few sparse feature sets must all be valid WGSL.
        let all = Features::all();
        validate(&path_tracer_source(&all).unwrap()).unwrap();
        for f in [
            Features::default(),
            Features {
                has_lights: true,
                has_disk_light: true,
                ..Features::default()
            },
            Features {
                has_plastic: true,
                has_conductor: true,
                use_bvh: true,
                ..Features::default()
            },
            Features {
                bvh2: true,
                ..Features::all()
            },
            Features {
                bvh2: true,
                has_sphere_shape: true,
                use_bvh: true,
                ..Features::default()
            },
            // Glass on and off: smooth only (no GGX, no lights), rough under a light, and
            // everything but glass.
            Features {
                has_dielectric: true,
                has_sphere_shape: true,
                ..Features::default()
            },
            Features {
                has_dielectric: true,
                has_ggx: true,
                has_lights: true,
                has_quad_light: true,
                ..Features::default()
            },
            Features {
                has_dielectric: false,
                ..Features::all()
            },
            // Environment maps: sampled, seen by rays that miss only, and everything but a map.
            Features {
                has_envmap: true,
                has_background: true,
                has_lights: true,
                ..Features::default()
            },
            Features {
                has_envmap: true,
                has_background: true,
                ..Features::default()
            },
            Features {
                has_envmap: false,
                ..Features::all()
            },
            // Shading normals: alone (no lights: no NEE), lit, with glass, and everything but.
            Features {
                has_shading_normals: true,
                use_bvh: true,
                ..Features::default()
            },
            Features {
                has_shading_normals: true,
                has_lights: true,
                has_quad_light: true,
                ..Features::default()
            },
            Features {
                has_shading_normals: true,
                has_dielectric: true,
                has_lights: true,
                has_triangle_light: true,
                ..Features::default()
            },
            Features {
                has_shading_normals: false,
                ..Features::all()
            },
        ] {
            let src = path_tracer_source(&f).unwrap();
            if let Err(e) = validate(&src) {
                panic!("{f:?}: {e}");
            }
        }
    }

    /// What transmission adds to a program, by name: none of it may be in a program without a
    /// dielectric, which is then the reflection-only path tracer it was before glass existed.
    const TRANSMISSION_CODE: [&str; 7] = [
        "dielectric",
        "refract",
        "transmits",
        "eta_scale",
        "bs.eta",
        "s.eta",
        "    eta: f32,",
    ];

    /// The code of the program without the prelude (which lists every kind tag whatever the
    /// scene) and without comments.
    fn program_body(f: &Features) -> String {
        let src = path_tracer_source(f).unwrap();
        let body = src.find("// ---- tags.wgsl").unwrap();
        src[body..]
            .lines()
            .map(|l| l.split("//").next().unwrap())
            .collect::<Vec<_>>()
            .join("\n")
    }

    #[test]
    fn scenes_without_glass_carry_no_transmission_code() {
        let glass = Features {
            has_dielectric: true,
            has_ggx: true,
            has_lights: true,
            ..Features::default()
        };
        let with = program_body(&glass);
        for name in TRANSMISSION_CODE {
            assert!(with.contains(name), "a glass program lacks {name:?}");
        }
        let without = [
            Features::default(),
            Features {
                has_conductor: true,
                has_plastic: true,
                has_ggx: true,
                has_lights: true,
                has_quad_light: true,
                ..Features::default()
            },
            Features {
                has_dielectric: false,
                ..Features::all()
            },
        ];
        for f in without {
            let body = program_body(&f);
            for name in TRANSMISSION_CODE {
                assert!(
                    !body.contains(name),
                    "{f:?}: {name:?} in a program without glass"
                );
            }
        }
        // Smooth glass alone needs Fresnel and refraction but no GGX.
        let smooth = program_body(&Features {
            has_dielectric: true,
            ..Features::default()
        });
        assert!(
            smooth.contains("fn fresnel_dielectric(") && smooth.contains("fn refract_through(")
        );
        assert!(!smooth.contains("fn ggx_d("));
    }
}

/// Scenes without an environment map compile none of its code (no lookup, no sampling, no
/// texture binding), so their programs are the ones they were before maps existed; a scene with
/// one gets it all, sampling included.
#[cfg(test)]
mod envmap_specialisation {
    use super::*;
    use crate::stats::suite;

    fn body(f: &Features) -> String {
        let src = path_tracer_source(f).unwrap();
        let body = src.find("// ---- tags.wgsl").unwrap();
        src[body..]
            .lines()
            .map(|l| l.split("//").next().unwrap())
            .collect::<Vec<_>>()
            .join("\n")
    }

    #[test]
    fn only_scenes_with_a_map_carry_envmap_code() {
        let map = &suite::envmap_maps()[1];
        let f = Features::of(&suite::envmap_scene(map, 30.0));
        assert!(f.has_envmap && f.has_background && f.has_lights, "{f:?}");
        let with = body(&f);
        for name in [
            "envmap_texels",
            "fn envmap_eval(",
            "case LIGHT_ENVMAP",
            "envmap_light_pdf(",
        ] {
            assert!(with.contains(name), "a scene with a map lacks {name:?}");
        }
        let constant = crate::scene::Scene::from_desc(
            &crate::scene::parse_scene(
                r#"{"camera": {"from": [0, 0, -3], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40,
                    "width": 2, "height": 2}, "background": [0.5, 0.5, 0.5],
                    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1}]}"#,
            )
            .unwrap(),
        )
        .unwrap();
        let f = Features::of(&constant);
        assert!(!f.has_envmap && f.has_background, "{f:?}");
        for f in [
            f,
            Features::default(),
            Features {
                has_envmap: false,
                ..Features::all()
            },
        ] {
            let without = body(&f);
            assert!(
                !without.to_lowercase().contains("envmap"),
                "{f:?}: environment-map code in a program without a map"
            );
        }
    }
}

/// The WGSL twins named in the module docs and headers, for the test that they agree.
#[cfg(test)]
mod twins {
    use std::collections::BTreeSet;
    use std::path::{Path, PathBuf};

    /// The text between backticks in `text` that ends with `ext`.
    fn quoted(text: &str, ext: &str) -> BTreeSet<String> {
        text.split('`')
            .skip(1)
            .step_by(2)
            .filter(|t| t.ends_with(ext) && !t.contains(' '))
            .map(String::from)
            .collect()
    }

    fn src() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
    }

    fn shaders() -> PathBuf {
        src().join("gpu/shaders")
    }

    /// The Rust modules a WGSL file's header (its leading comment lines) names, relative to
    /// `src/`.
    fn wgsl_names(file: &str) -> BTreeSet<String> {
        let text = std::fs::read_to_string(shaders().join(file)).unwrap();
        let header: Vec<&str> = text.lines().take_while(|l| l.starts_with("//")).collect();
        quoted(&header.join("\n"), ".rs")
    }

    /// The WGSL files a Rust module's doc comment names as its twins: the paragraph of `//!`
    /// lines starting at "WGSL twin".
    fn rust_names(text: &str) -> BTreeSet<String> {
        let doc: Vec<&str> = text
            .lines()
            .take_while(|l| l.starts_with("//!"))
            .map(|l| l.trim_start_matches("//!").trim())
            .collect();
        let twin: Vec<&str> = doc
            .iter()
            .skip_while(|l| !l.starts_with("WGSL twin"))
            .take_while(|l| !l.is_empty())
            .copied()
            .collect();
        quoted(&twin.join(" "), ".wgsl")
    }

    fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                rust_files(&p, out);
            } else if p.extension().is_some_and(|x| x == "rs") {
                out.push(p);
            }
        }
    }

    #[test]
    fn every_wgsl_module_and_its_rust_twins_name_each_other() {
        let mut problems = Vec::new();
        let mut wgsl: Vec<String> = std::fs::read_dir(shaders())
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .filter(|n| n.ends_with(".wgsl"))
            .collect();
        wgsl.sort();
        for w in &wgsl {
            let names = wgsl_names(w);
            if names.is_empty() {
                problems.push(format!("{w}: its header names no Rust module"));
            }
            for r in names {
                match std::fs::read_to_string(src().join(&r)) {
                    Err(_) => problems.push(format!("{w}: names `{r}`, which does not exist")),
                    Ok(text) if !rust_names(&text).contains(w) => problems.push(format!(
                        "{r}: named by {w}, its module doc lacks \"WGSL twin: `{w}`\""
                    )),
                    Ok(_) => {}
                }
            }
        }
        let mut files = Vec::new();
        rust_files(&src(), &mut files);
        files.sort();
        for f in files {
            let rel = f.strip_prefix(src()).unwrap().to_str().unwrap().to_string();
            for w in rust_names(&std::fs::read_to_string(&f).unwrap()) {
                if !wgsl.contains(&w) {
                    problems.push(format!("{rel}: its twin {w} does not exist"));
                } else if !wgsl_names(&w).contains(&rel) {
                    problems.push(format!("{w}: twin of {rel}, its header does not name it"));
                }
            }
        }
        assert!(problems.is_empty(), "\n{}", problems.join("\n"));
    }
}

/// Scenes without vertex normals compile no shading-normal code (no attribute lookups, no
/// shading-normal rule), so their programs are the ones they were before meshes had normals; a
/// mesh with normals gets all of it. (A quad's UVs alone do not count: nothing reads them yet.)
#[cfg(test)]
mod shading_normal_specialisation {
    use super::*;
    use crate::scene::mesh::{MeshData, obj};
    use glam::Vec3;

    fn body(f: &Features) -> String {
        let src = path_tracer_source(f).unwrap();
        let body = src.find("// ---- tags.wgsl").unwrap();
        src[body..]
            .lines()
            .map(|l| l.split("//").next().unwrap())
            .collect::<Vec<_>>()
            .join("\n")
    }

    /// A lit quad and a one-triangle mesh, with vertex normals or without.
    fn scene(normals: bool) -> Scene {
        let dir = std::env::temp_dir().join(format!("lumis-shader-sn-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join(format!("tri{}.obj", normals as u8));
        let mesh = MeshData {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            indices: vec![[0, 1, 2]],
            normals: normals.then(|| vec![Vec3::Z, Vec3::new(0.1, 0.0, 1.0), Vec3::Z]),
            uvs: None,
        };
        obj::write(&file, &mesh).unwrap();
        let json = format!(
            r#"{{"camera": {{"from": [0, 0, 3], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40,
                "width": 2, "height": 2}},
                "shapes": [{{"type": "mesh", "file": "{}"}},
                           {{"type": "quad", "corner": [-1, -1, 2], "edge_u": [0, 2, 0],
                             "edge_v": [2, 0, 0], "emission": [1, 1, 1]}}]}}"#,
            file.display()
        );
        let scene = Scene::from_desc(&crate::scene::parse_scene(&json).unwrap()).unwrap();
        std::fs::remove_file(&file).unwrap();
        scene
    }

    const SHADING_CODE: [&str; 6] = [
        "fn shading_normal(",
        "fn same_side(",
        "!same_side(",
        "params.attr",
        "frame_from_normal(ns)",
        "shading",
    ];

    #[test]
    fn only_scenes_with_vertex_normals_carry_shading_normal_code() {
        let f = Features::of(&scene(true));
        assert!(f.has_shading_normals, "{f:?}");
        let with = body(&f);
        for name in SHADING_CODE {
            assert!(with.contains(name), "a scene with normals lacks {name:?}");
        }
        assert_eq!(
            with.matches("!same_side(").count(),
            3,
            "the rule's three uses"
        );
        let flat = Features::of(&scene(false));
        assert!(!flat.has_shading_normals, "{flat:?}");
        for f in [
            flat,
            Features::default(),
            Features {
                has_shading_normals: false,
                ..Features::all()
            },
        ] {
            let without = body(&f);
            for name in SHADING_CODE {
                assert!(
                    !without.contains(name),
                    "{f:?}: {name:?} in a program without shading normals"
                );
            }
        }
    }
}
