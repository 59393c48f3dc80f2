//! Tests of `gpu/shader.rs`: the prelude's constants are used, the preprocessor, every
//! specialisation validates, each feature's code appears only in the programs that need it, and
//! every WGSL module and its Rust twins name each other.

use super::*;

mod tests {
    use super::*;

    #[test]
    fn every_prelude_constant_is_used_by_the_shaders() {
        // An unused one is dead, or a module kept a copy under another name.
        let text: String = MODULES.iter().chain(PATH_MODULES).map(|m| m.text).collect();
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
            // Textures: on diffuse triangles alone, with every material kind and both analytic
            // shapes under a light, and everything but.
            Features {
                has_textures: true,
                ..Features::default()
            },
            Features {
                has_textures: true,
                has_conductor: true,
                has_plastic: true,
                has_dielectric: true,
                has_ggx: true,
                has_disk_shape: true,
                has_sphere_shape: true,
                has_lights: true,
                has_quad_light: true,
                ..Features::default()
            },
            Features {
                has_textures: false,
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
        let body = src.find("// ---- gpu/prelude.wgsl").unwrap();
        src[body..]
            .lines()
            .map(|l| l.split("//").next().unwrap())
            .collect::<Vec<_>>()
            .join("\n")
    }

    /// Only a scene with a filter with negative lobes carries their piecewise sampling (it made
    /// every lavapipe compile slower when all programs had it).
    #[test]
    fn only_signed_filters_carry_their_sampling_code() {
        let signed = Features {
            has_signed_filter: true,
            ..Features::default()
        };
        let names = [
            "fn filter_sample_signed",
            "fn filter_quadrature",
            "FILTER_LANCZOS: {",
        ];
        let with = program_body(&signed);
        for name in names {
            assert!(
                with.contains(name),
                "a signed filter's program lacks {name:?}"
            );
        }
        let without = program_body(&Features {
            has_signed_filter: false,
            ..Features::all()
        });
        for name in names {
            assert!(
                !without.contains(name),
                "{name:?} in a program without a signed filter"
            );
        }
    }

    #[test]
    fn only_normal_maps_carry_their_code() {
        let names = [
            "fn normal_map_perturb",
            "fn perturbation_factor",
            "vertex_perturbation = pert.p",
        ];
        let with = program_body(&Features {
            has_normal_maps: true,
            has_textures: true,
            ..Features::default()
        });
        for name in names {
            assert!(with.contains(name), "a normal map's program lacks {name:?}");
        }
        let without = program_body(&Features {
            has_normal_maps: false,
            ..Features::all()
        });
        for name in names {
            assert!(
                !without.contains(name),
                "{name:?} in a program without normal maps"
            );
        }
    }

    /// The masked traversal exists only in programs for scenes with masks; without, the
    /// primitive test is the shape's alone.
    #[test]
    fn only_masks_carry_their_code() {
        let names = [
            "fn mask_meets",
            "mask_meets(id, ray, t)",
            "shape_intersect_t_beyond(prims[id]",
        ];
        let with = program_body(&Features {
            has_masks: true,
            use_bvh: true,
            ..Features::default()
        });
        for name in names {
            assert!(with.contains(name), "a masked program lacks {name:?}");
        }
        let without = program_body(&Features {
            has_masks: false,
            ..Features::all()
        });
        for name in names {
            assert!(
                !without.contains(name),
                "{name:?} in a program without masks"
            );
        }
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
            // Mitsuba's plastic reads the dielectric Fresnel (checked below).
            // So does the principled (checked below).
            Features {
                has_dielectric: false,
                has_thin_dielectric: false,
                has_mitsuba_plastic: false,
                has_principled: false,
                has_principled_transmission: false,
                has_principled_thin: false,
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
        // A thin sheet alone: the transmission code (a crossing, η' = 1) without refraction.
        let thin = program_body(&Features {
            has_thin_dielectric: true,
            has_lights: true,
            ..Features::default()
        });
        for name in TRANSMISSION_CODE.iter().filter(|n| **n != "refract") {
            assert!(thin.contains(name), "a thin sheet's program lacks {name:?}");
        }
        assert!(
            !thin.contains("refract"),
            "refraction in a thin sheet's program"
        );
        // A thin principled alone: like a thin sheet, the transmission code without refraction,
        // and the principled's helpers it shares.
        let thin_principled = program_body(&Features {
            has_principled_thin: true,
            has_ggx: true,
            has_lights: true,
            ..Features::default()
        });
        for name in TRANSMISSION_CODE.iter().filter(|n| **n != "refract") {
            assert!(
                thin_principled.contains(name),
                "a thin principled's program lacks {name:?}"
            );
        }
        assert!(!thin_principled.contains("refract"));
        assert!(thin_principled.contains("fn principled_thin_eval("));
        // Mitsuba's plastic coat: the dielectric Fresnel, nothing of transmission.
        let coat = program_body(&Features {
            has_mitsuba_plastic: true,
            has_ggx: true,
            has_lights: true,
            ..Features::default()
        });
        assert!(coat.contains("fn fresnel_dielectric("));
        for name in &TRANSMISSION_CODE[1..] {
            assert!(
                !coat.contains(name),
                "{name:?} in a Mitsuba plastic's program"
            );
        }
        // A principled without transmission: its dielectric Fresnel, nothing of transmission.
        let principled = program_body(&Features {
            has_principled: true,
            has_ggx: true,
            has_lights: true,
            ..Features::default()
        });
        assert!(principled.contains("fn principled_eval("));
        for name in &TRANSMISSION_CODE[1..] {
            assert!(
                !principled.contains(name),
                "{name:?} in a reflection-only principled's program"
            );
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
mod envmap_specialisation {
    use super::*;
    use crate::stats::suite;

    fn body(f: &Features) -> String {
        let src = path_tracer_source(f).unwrap();
        let body = src.find("// ---- gpu/prelude.wgsl").unwrap();
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
mod twins {
    use super::*;
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

    /// The Rust modules a WGSL file's header (its leading comment lines) names, relative to
    /// `src/`.
    fn wgsl_names(file: &str) -> BTreeSet<String> {
        let text = std::fs::read_to_string(src().join(file)).unwrap();
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

    /// The files under `dir` whose name ends with `ext`.
    fn files(dir: &Path, ext: &str, out: &mut Vec<PathBuf>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                files(&p, ext, out);
            } else if p.extension().is_some_and(|x| x == ext) {
                out.push(p);
            }
        }
    }

    fn relative(files: Vec<PathBuf>) -> Vec<String> {
        let mut rel: Vec<String> = files
            .iter()
            .map(|f| f.strip_prefix(src()).unwrap().to_str().unwrap().to_string())
            .collect();
        rel.sort();
        rel
    }

    /// GPU plumbing with no Rust twin of the same stem: the bindings, the render kernel, the u64
    /// emulation WGSL lacks and the BVH2 traversal kept for measurements. They live in `gpu/`.
    const GPU_ONLY: [&str; 4] = [
        "gpu/bindings.wgsl",
        "gpu/film.wgsl",
        "gpu/u64.wgsl",
        "gpu/bvh2.wgsl",
    ];

    #[test]
    fn every_wgsl_module_and_its_rust_twins_name_each_other() {
        let mut problems = Vec::new();
        let mut found = Vec::new();
        files(&src(), "wgsl", &mut found);
        let wgsl = relative(found);
        let modules: BTreeSet<&str> = MODULES.iter().chain(PATH_MODULES).map(|m| m.name).collect();
        for w in &wgsl {
            if !modules.contains(w.as_str()) {
                problems.push(format!("{w}: in no program (MODULES or PATH_MODULES)"));
            }
            let names = wgsl_names(w);
            if names.is_empty() {
                problems.push(format!("{w}: its header names no Rust module"));
            }
            // The twin beside it: same folder, same stem.
            let stem_twin = w.replace(".wgsl", ".rs");
            if !GPU_ONLY.contains(&w.as_str()) && !names.contains(&stem_twin) {
                problems.push(format!(
                    "{w}: its header does not name `{stem_twin}`, the Rust file of the same stem"
                ));
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
        for m in &modules {
            if !wgsl.iter().any(|w| w == m) {
                problems.push(format!(
                    "{m}: a module of the programs, not a file under src/"
                ));
            }
        }
        let mut rust = Vec::new();
        files(&src(), "rs", &mut rust);
        for rel in relative(rust) {
            for w in rust_names(&std::fs::read_to_string(src().join(&rel)).unwrap()) {
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
/// mesh with normals gets all of it. (A quad's UVs alone do not count: only textures read them.)
mod shading_normal_specialisation {
    use super::*;
    use crate::scene::mesh::{MeshData, obj};
    use glam::Vec3;

    fn body(f: &Features) -> String {
        let src = path_tracer_source(f).unwrap();
        let body = src.find("// ---- gpu/prelude.wgsl").unwrap();
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
            attributes: Vec::new(),
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
                // Texture coordinates read the attribute arrays too.
                if name == "params.attr" && f.has_textures {
                    continue;
                }
                assert!(
                    !without.contains(name),
                    "{f:?}: {name:?} in a program without shading normals"
                );
            }
        }
    }
}

/// Scenes without textured materials compile no texture code (no lookups, no texel binding, no
/// texture coordinates), so their programs are the ones they were before textures reached the
/// GPU; a textured scene gets all of it, and a textured α brings the GGX code.
mod texture_specialisation {
    use super::*;
    use crate::materials::textured::MaterialTextures;
    use crate::textures::{Checkerboard, Texture};

    fn body(f: &Features) -> String {
        let src = path_tracer_source(f).unwrap();
        let body = src.find("// ---- gpu/prelude.wgsl").unwrap();
        src[body..]
            .lines()
            .map(|l| l.split("//").next().unwrap())
            .collect::<Vec<_>>()
            .join("\n")
    }

    const TEXTURE_CODE: [&str; 7] = [
        "texture_texels",
        "fn texture_eval(",
        "fn material_at(",
        "material_textured(m)",
        "fn surface_uv(",
        "params.textures",
        "fn mesh_uv(",
    ];

    #[test]
    fn only_textured_scenes_carry_texture_code() {
        let json = r#"{"camera": {"from": [0, 0, -3], "to": [0, 0, 0], "up": [0, 1, 0],
            "vfov_deg": 40, "width": 2, "height": 2},
            "materials": {"glass": {"type": "dielectric", "ior": 1.5, "alpha": 0}},
            "shapes": [{"type": "quad", "corner": [-1, -1, 0], "edge_u": [2, 0, 0],
                        "edge_v": [0, 2, 0], "material": "glass"}]}"#;
        let mut scene = Scene::from_desc(&crate::scene::parse_scene(json).unwrap()).unwrap();
        let plain = Features::of(&scene);
        assert!(!plain.has_textures && !plain.has_ggx, "{plain:?}");
        scene.material_textures[0] = Some(MaterialTextures {
            alpha: Some(Texture::Checkerboard(Checkerboard::default())),
            ..Default::default()
        });
        let f = Features::of(&scene);
        assert!(f.has_textures && f.has_ggx, "{f:?}");
        let with = body(&f);
        for name in TEXTURE_CODE {
            assert!(with.contains(name), "a textured scene lacks {name:?}");
        }
        for f in [
            plain,
            Features::default(),
            // Normal maps and masks look textures up too.
            Features {
                has_textures: false,
                has_normal_maps: false,
                has_masks: false,
                ..Features::all()
            },
        ] {
            let without = body(&f);
            for name in TEXTURE_CODE {
                if name == "fn mesh_uv(" && f.has_shading_normals {
                    continue;
                }
                assert!(
                    !without.contains(name),
                    "{f:?}: {name:?} in a program without textures"
                );
            }
        }
    }
}

/// `check_param_tags` (`gpu/bindings.wgsl`) knows every tag `gpu/scene/params.rs` can write.
mod param_tags {
    use crate::gpu::scene::params::{HeuristicTag, LightSamplingTag, StrategyTag};

    /// Every tag of the strategy, heuristic and light-sampling enums is a case of the
    /// validation's `switch`, so a new variant cannot reach the GPU as "unknown" (the shader then
    /// flags every sample non-finite). Catches the omission that `LightSampling::Adaptive` had
    /// until 2026-12-03: every GPU render with `--light-sampling adaptive` was NaN, while its
    /// χ² and parity tests (which call the light functions directly) passed.
    #[test]
    fn check_param_tags_accepts_every_tag() {
        let text = include_str!("bindings.wgsl");
        let start = text
            .find("fn check_param_tags(")
            .expect("check_param_tags in gpu/bindings.wgsl");
        let body = &text[start..];
        let body = &body[..body.find("\n}\n").expect("end of check_param_tags")];
        let names = StrategyTag::ALL
            .iter()
            .map(|t| t.1)
            .chain(HeuristicTag::ALL.iter().map(|t| t.1))
            .chain(LightSamplingTag::ALL.iter().map(|t| t.1));
        for name in names {
            assert!(
                body.split(|c: char| !c.is_ascii_alphanumeric() && c != '_')
                    .any(|w| w == name),
                "check_param_tags does not accept {name}"
            );
        }
    }
}
