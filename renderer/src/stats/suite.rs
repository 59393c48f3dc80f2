//! The samplers of the statistical suite, by name: every warp, every material at several
//! incidence angles (the rough dielectric from outside and from inside), every light shape from
//! several points with every sampling method that changes it, environment maps with both
//! methods, and the strategy mixture. Each list entry is one line; the tests and
//! `examples/warptest.rs` share them.
//!
//! Light geometry: the receiver sits at the origin with normal +z (so BSDF and world frames
//! coincide for the mixture). Plane lights have circumradius 1, the sphere radius 1.

use super::bsdf_sampler::BsdfSampler;
use super::light_directions::LightDirections;
use super::mixture_sampler::Mixture;
use super::sampler::DirectionalSampler;
use super::selected_lights::{self, SelectedLightDirections};
use super::warp_sampler::Warp;
use crate::lights::LightSampling;
use crate::materials::{
    Conductor, ConductorFresnel, Dielectric, Diffuse, Material, Microfacet, Plastic,
};
use crate::math::Frame;
use crate::scene::{Scene, parse_scene};
use glam::Vec3;
use serde_json::json;
use std::f32::consts::TAU;
use std::sync::Arc;

/// A named sampler of the suite.
pub struct Case {
    /// Unique name, e.g. `conductor/a0.05/tint/th60`.
    pub name: String,
    /// The sampler.
    pub sampler: Box<dyn DirectionalSampler + Send>,
}

fn case(name: String, sampler: impl DirectionalSampler + Send + 'static) -> Case {
    Case {
        name,
        sampler: Box::new(sampler),
    }
}

/// Incidence angles every material is tested at (degrees from the normal).
pub const THETAS_DEG: [f32; 5] = [0.0, 30.0, 60.0, 85.0, 89.0];
/// Conductor roughnesses.
pub const CONDUCTOR_ALPHAS: [f32; 6] = [0.01, 0.05, 0.1, 0.3, 0.6, 1.0];
/// Plastic roughnesses.
pub const PLASTIC_ALPHAS: [f32; 3] = [0.05, 0.3, 1.0];
/// Plastic coat IORs.
pub const PLASTIC_IORS: [f32; 3] = [1.1, 1.5, 3.0];
/// Rough dielectric roughnesses (the smooth one is delta only: no density to histogram).
pub const DIELECTRIC_ALPHAS: [f32; 6] = [0.01, 0.05, 0.1, 0.3, 0.6, 1.0];
/// Dielectric IORs (inside relative to outside).
pub const DIELECTRIC_IORS: [f32; 3] = [1.1, 1.5, 2.4];
/// Incidence angles of the dielectric, from outside and from inside (degrees from the normal on
/// the viewer's side). Inside, the critical angles are 65.4° (η 1.1), 41.8° (1.5) and 24.6°
/// (2.4): 30° and 60° fall on both sides of them.
pub const DIELECTRIC_THETAS_DEG: [f32; 5] = [0.0, 30.0, 60.0, 85.0, 89.0];
/// Mixture weights of light sampling.
pub const MIX_WEIGHTS: [f32; 4] = [0.0, 0.25, 0.5, 1.0];

/// A gold-like conductor (`complex`) or a tinted one.
pub fn conductor(alpha: f32, complex: bool) -> Material {
    let fresnel = if complex {
        ConductorFresnel::Complex {
            eta: Vec3::new(0.143, 0.374, 1.442),
            k: Vec3::new(3.983, 2.385, 1.603),
            tint: Vec3::ONE,
        }
    } else {
        ConductorFresnel::Tint(Vec3::new(0.95, 0.64, 0.54))
    };
    Material::Conductor(Conductor {
        microfacet: Microfacet::ggx(alpha),
        fresnel,
    })
}

/// An orange plastic with a white coat.
pub fn plastic(alpha: f32, ior: f32) -> Material {
    Material::Plastic(Plastic::new(
        Vec3::new(0.8, 0.4, 0.1),
        alpha,
        ior,
        Vec3::ONE,
    ))
}

/// A rough (or smooth, α < 1e-3) dielectric.
pub fn dielectric(alpha: f32, ior: f32) -> Material {
    Material::Dielectric(Dielectric {
        ior,
        microfacet: Microfacet::ggx(alpha),
    })
}

/// A coloured Lambertian.
pub fn diffuse() -> Material {
    Material::Diffuse(Diffuse {
        albedo: Vec3::new(0.8, 0.5, 0.2),
    })
}

/// The light shapes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    /// Equilateral triangle.
    Triangle,
    /// Regular hexagon (convex polygon).
    Hexagon,
    /// Five-pointed star (concave polygon).
    Star,
    /// Square quad.
    Quad,
    /// Disk.
    Disk,
    /// Sphere.
    Sphere,
}

/// Where the light is, seen from the receiver at the origin.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Placement {
    /// Distance 1.5 (about the light's size), 20° off the normal, seen 30° off the light's normal.
    Near,
    /// Distance 200 (100× the light's size).
    Far,
    /// Seen 5° above the light's plane (a sphere: from 1.05 radii, near-tangent directions).
    Grazing,
    /// Centred on the receiver's horizon: about half of the light is below it.
    BelowHorizon,
    /// Distance 8 (4× the light's size), otherwise as `Near`: a disk's spherical ellipse of
    /// 0.04 sr, small but above `MIN_ELLIPSE_SOLID_ANGLE` (`Far` samples disks by area).
    Middle,
    /// Seen 89° off the light's normal from distance 1.5: a disk's ellipse 43 times longer than
    /// wide (0.047 sr).
    EdgeOn,
    /// 0.05 above the light's plane, over its rim (the centre 1.00125 away, 87.1° off its
    /// normal): a disk's ellipse spans 154° along the rim (tangent semi-axes 0.98 and 4.4,
    /// 2.9 sr).
    OverRim,
    /// 0.1 straight above the light's centre: a disk's ellipse of 5.66 sr, near the hemisphere.
    Overhead,
    /// Wholly above the horizon but low: centre 70° off the normal at distance 3, elevations
    /// from about 1° to 40° (a grazing receiver; projected-solid-angle cases only).
    Low,
}

/// Every shape and placement.
pub const SHAPES: [Shape; 6] = [
    Shape::Triangle,
    Shape::Hexagon,
    Shape::Star,
    Shape::Quad,
    Shape::Disk,
    Shape::Sphere,
];
/// Every placement of every shape.
pub const PLACEMENTS: [Placement; 4] = [
    Placement::Near,
    Placement::Far,
    Placement::Grazing,
    Placement::BelowHorizon,
];
/// The placements only disks are tested at besides [`PLACEMENTS`], where their spherical
/// ellipse is small, thin, long, or nearly a hemisphere.
pub const DISK_PLACEMENTS: [Placement; 4] = [
    Placement::Middle,
    Placement::EdgeOn,
    Placement::OverRim,
    Placement::Overhead,
];

/// A scene holding only `shape` as a light, placed as `placement` says.
pub fn light_scene(shape: Shape, placement: Placement) -> Arc<Scene> {
    // (angle of the centre from the receiver normal, distance, view angle off the light normal)
    let (gamma, dist, beta) = match (placement, shape) {
        (Placement::Near, _) => (20f32, 1.5, 30f32),
        (Placement::Far, _) => (20.0, 200.0, 30.0),
        (Placement::Grazing, Shape::Sphere) => (20.0, 1.05, 0.0),
        (Placement::Grazing, _) => (20.0, 2.0, 85.0),
        (Placement::BelowHorizon, _) => (90.0, 1.5, 30.0),
        (Placement::Middle, _) => (20.0, 8.0, 30.0),
        (Placement::EdgeOn, _) => (20.0, 1.5, 89.0),
        (Placement::OverRim, _) => (20.0, 1.001_25, 87.137_5),
        (Placement::Overhead, _) => (20.0, 0.1, 0.0),
        (Placement::Low, _) => (70.0, 3.0, 30.0),
    };
    let dir = |a: f32| Vec3::new(a.to_radians().sin(), 0.0, a.to_radians().cos());
    let c = dist * dir(gamma);
    let n = -dir(gamma + beta);
    let f = Frame::from_normal(n);
    let at = |x: f32, y: f32| {
        let q = c + f.s * x + f.t * y;
        json!([q.x, q.y, q.z])
    };
    // Counter-clockwise about n (s × t = n) so the right-hand rule faces the receiver.
    let ring = |k: usize, r: &dyn Fn(usize) -> f32| -> Vec<serde_json::Value> {
        (0..k)
            .map(|i| {
                let a = TAU * i as f32 / k as f32 + 0.25 * TAU;
                at(r(i) * a.cos(), r(i) * a.sin())
            })
            .collect()
    };
    let e = json!([1.0, 1.0, 1.0]);
    let shape_json = match shape {
        Shape::Triangle => json!({"type": "triangles", "positions": ring(3, &|_| 1.0),
            "indices": [[0, 1, 2]], "emission": e}),
        Shape::Hexagon => json!({"type": "polygon", "vertices": ring(6, &|_| 1.0), "emission": e}),
        Shape::Star => json!({"type": "polygon",
            "vertices": ring(10, &|i| if i % 2 == 0 { 1.0 } else { 0.4 }), "emission": e}),
        Shape::Quad => {
            let (u, v) = (1.4 * f.s, 1.4 * f.t);
            json!({"type": "quad", "corner": at(-0.7, -0.7), "edge_u": [u.x, u.y, u.z],
                "edge_v": [v.x, v.y, v.z], "emission": e})
        }
        Shape::Disk => json!({"type": "disk", "center": [c.x, c.y, c.z],
            "normal": [n.x, n.y, n.z], "radius": 1.0, "emission": e}),
        Shape::Sphere => json!({"type": "sphere", "center": [c.x, c.y, c.z], "radius": 1.0,
            "emission": e}),
    };
    let scene = json!({
        "camera": {"from": [0, -5, 0], "to": [0, 0, 0], "up": [0, 0, 1], "vfov_deg": 40,
            "width": 2, "height": 2},
        "shapes": [shape_json],
    });
    let desc = parse_scene(&scene.to_string()).unwrap_or_else(|e| panic!("{shape:?}: {e}"));
    Arc::new(Scene::from_desc(&desc).unwrap_or_else(|e| panic!("{shape:?}: {e}")))
}

/// Sampling the (only) light of `light_scene(shape, placement)` from the origin, a receiver
/// with normal +z.
pub fn light_sampler(shape: Shape, placement: Placement, method: LightSampling) -> LightDirections {
    LightDirections {
        scene: light_scene(shape, placement),
        light: 0,
        p: Vec3::ZERO,
        method,
        ns: Vec3::Z,
    }
}

/// The planar shapes with a spherical warp, whose samples the cosine warp
/// ([`LightSampling::SolidAngleCosine`]) and [`LightSampling::Adaptive`] change (disks and spheres
/// sample with them as with `SolidAngle`).
pub const PLANAR_SPHERICAL_SHAPES: [Shape; 4] =
    [Shape::Triangle, Shape::Hexagon, Shape::Star, Shape::Quad];

/// The warps.
pub fn warp_cases() -> Vec<Case> {
    vec![
        case("warp/cosine_hemisphere".into(), Warp::CosineHemisphere),
        case("warp/uniform_sphere".into(), Warp::UniformSphere),
        case("warp/cone_60deg".into(), Warp::Cone(0.5)),
        case("warp/cone_2deg".into(), Warp::Cone(2f32.to_radians().cos())),
    ]
}

/// Every material configuration at every angle of [`THETAS_DEG`].
pub fn material_cases() -> Vec<Case> {
    let mut materials = vec![("diffuse".to_string(), diffuse())];
    for a in CONDUCTOR_ALPHAS {
        materials.push((format!("conductor/a{a}/complex"), conductor(a, true)));
        materials.push((format!("conductor/a{a}/tint"), conductor(a, false)));
    }
    for a in PLASTIC_ALPHAS {
        for ior in PLASTIC_IORS {
            materials.push((format!("plastic/a{a}/ior{ior}"), plastic(a, ior)));
        }
    }
    let mut out = Vec::new();
    for (name, m) in materials {
        for th in THETAS_DEG {
            let s = BsdfSampler::at_angle(m.clone(), th);
            out.push(case(format!("{name}/th{th}"), s));
        }
    }
    out
}

/// The rough dielectric at every α × IOR × side × angle of the `DIELECTRIC_*` lists, named
/// `dielectric/a{α}/ior{η}/{out|in}/th{θ}`, as BSDF samplers (the GPU suite builds its own
/// samplers from their `material` and `wo`, and uses these as the density).
pub fn dielectric_samplers() -> Vec<(String, BsdfSampler)> {
    let mut out = Vec::new();
    for a in DIELECTRIC_ALPHAS {
        for ior in DIELECTRIC_IORS {
            let m = dielectric(a, ior);
            for (side, inside) in [("out", false), ("in", true)] {
                for th in DIELECTRIC_THETAS_DEG {
                    let s = if inside {
                        BsdfSampler::inside_at_angle(m.clone(), th)
                    } else {
                        BsdfSampler::at_angle(m.clone(), th)
                    };
                    out.push((format!("dielectric/a{a}/ior{ior}/{side}/th{th}"), s));
                }
            }
        }
    }
    out
}

/// [`dielectric_samplers`] as cases.
pub fn dielectric_cases() -> Vec<Case> {
    dielectric_samplers()
        .into_iter()
        .map(|(name, s)| case(name, s))
        .collect()
}

/// The placements of the projected-solid-angle cases: every one of [`PLACEMENTS`] (the far light
/// exercises the fallback to solid angle) and [`Placement::Low`].
pub const PROJECTED_PLACEMENTS: [Placement; 5] = [
    Placement::Near,
    Placement::Far,
    Placement::Grazing,
    Placement::BelowHorizon,
    Placement::Low,
];

/// Every light shape × placement × method (the cosine warp and adaptive sampling for the shapes
/// they change; adaptive sampling also for disks), the disk's spherical ellipse at
/// [`DISK_PLACEMENTS`], then projected-solid-angle sampling of the planar shapes at
/// [`PROJECTED_PLACEMENTS`].
pub fn light_cases() -> Vec<Case> {
    let mut out = Vec::new();
    let mut push = |shape: Shape, placement: Placement, method: LightSampling| {
        let name = format!("light/{shape:?}/{placement:?}/{method:?}").to_lowercase();
        out.push(case(name, light_sampler(shape, placement, method)));
    };
    for shape in SHAPES {
        for placement in PLACEMENTS {
            let mut methods = vec![LightSampling::Area, LightSampling::SolidAngle];
            if PLANAR_SPHERICAL_SHAPES.contains(&shape) {
                methods.push(LightSampling::SolidAngleCosine);
            }
            if PLANAR_SPHERICAL_SHAPES.contains(&shape) || shape == Shape::Disk {
                methods.push(LightSampling::Adaptive);
            }
            for method in methods {
                push(shape, placement, method);
            }
        }
    }
    for placement in DISK_PLACEMENTS {
        push(Shape::Disk, placement, LightSampling::SolidAngle);
    }
    let method = LightSampling::ProjectedSolidAngle;
    for shape in PLANAR_SPHERICAL_SHAPES {
        for placement in PROJECTED_PLACEMENTS {
            push(shape, placement, method);
        }
    }
    out
}

/// Light selection composed with light sampling on [`selected_lights::several_lights_scene`]
/// from the origin: the BVH with the receiver normal +z, tilted, and none, with a transmitting
/// receiver's view of the light below (the |cos| normal term; same +z normal, the light below
/// counts because the sampler does not know the BSDF), with a background (the infinite lights'
/// share), and power selection for comparison.
pub fn light_selection_cases() -> Vec<Case> {
    use crate::lights::LightSelection::{Bvh, Power};
    let tilted = Vec3::new(0.6, -0.3, 0.74).normalize();
    let setups = [
        ("bvh/normal_z", Bvh, Vec3::Z, false),
        ("bvh/normal_tilted", Bvh, tilted, false),
        ("bvh/no_normal", Bvh, Vec3::ZERO, false),
        ("bvh/background", Bvh, Vec3::Z, true),
        ("power/normal_z", Power, Vec3::Z, false),
    ];
    setups
        .into_iter()
        .map(|(name, selection, ns, background)| {
            let sampler = SelectedLightDirections {
                scene: selected_lights::several_lights_scene(background),
                selection,
                p: Vec3::ZERO,
                ns,
                method: LightSampling::SolidAngle,
            };
            case(format!("light_selection/{name}"), sampler)
        })
        .collect()
}

/// A test environment map: name, width, height, texels (row 0 at the zenith).
pub type TestMap = (&'static str, usize, usize, Vec<Vec3>);

/// The environment maps of the suite: a constant one, a sun-like texel 1e5 times brighter than
/// the rest, black rows and columns, and one and two texels.
pub fn envmap_maps() -> Vec<TestMap> {
    let sun: Vec<Vec3> = (0..32 * 16)
        .map(|k| Vec3::splat(if k == 5 * 32 + 20 { 1e5 } else { 1.0 }))
        .collect();
    let stripes: Vec<Vec3> = (0..12 * 7)
        .map(|k| {
            let (i, j) = (k % 12, k / 12);
            if i % 3 == 0 || j == 2 || j == 3 {
                Vec3::ZERO
            } else {
                Vec3::new(0.2, 1.0, 3.0)
            }
        })
        .collect();
    vec![
        ("constant", 6, 4, vec![Vec3::splat(0.7); 24]),
        ("sun", 32, 16, sun),
        ("stripes", 12, 7, stripes),
        ("1x1", 1, 1, vec![Vec3::new(0.5, 1.0, 2.0)]),
        ("2x1", 2, 1, vec![Vec3::ONE, Vec3::new(0.0, 0.0, 4.0)]),
    ]
}

/// A scene lit only by `map`, rotated by `rotate_y_deg`, with nothing in it but a tiny sphere far
/// below (a scene needs a shape; it hides almost nothing).
pub fn envmap_scene(map: &TestMap, rotate_y_deg: f64) -> Arc<Scene> {
    envmap_scene_rotated(map, rotate_y_deg, None)
}

/// [`envmap_scene`] with the map turned by `rotation` (scene format Version 3's `rotation`)
/// before `rotate_y_deg`.
pub fn envmap_scene_rotated(
    map: &TestMap,
    rotate_y_deg: f64,
    rotation: Option<glam::DMat3>,
) -> Arc<Scene> {
    use crate::image_io::Image;
    use crate::scene::{BackgroundDesc, EnvmapDesc};
    let (name, w, h, texels) = map;
    let scene = json!({
        "camera": {"from": [0, -5, 0], "to": [0, 0, 0], "up": [0, 0, 1], "vfov_deg": 40,
            "width": 2, "height": 2},
        "shapes": [{"type": "sphere", "center": [0, -1000, 0], "radius": 1e-3}],
    });
    let mut desc = parse_scene(&scene.to_string()).expect("the envmap test scene parses");
    desc.background = BackgroundDesc::Envmap(EnvmapDesc {
        file: format!("<test map {name}>").into(),
        image: Arc::new(Image {
            width: *w as u32,
            height: *h as u32,
            data: texels.clone(),
        }),
        scale: 1.0,
        rotate_y_deg,
        rotation,
    });
    Arc::new(Scene::from_desc(&desc).unwrap_or_else(|e| panic!("{name}: {e}")))
}

/// A rotation that is about no coordinate axis: a z-up map (Mitsuba scenes turn theirs by −90°
/// about +x) then tilted 50° about (1, 2, 3), so the map's poles and seam lie off every axis.
pub fn envmap_tilt() -> glam::DMat3 {
    use glam::{DMat3, DVec3};
    DMat3::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 50f64.to_radians())
        * DMat3::from_rotation_x(-90f64.to_radians())
}

/// The scenes of [`envmap_cases`], named: every test map rotated by 30° about +y (the maps'
/// features are then off the grid of the χ² histogram), and the sun and stripes maps also turned
/// by [`envmap_tilt`] (`NAME_tilted`).
pub fn envmap_case_scenes() -> Vec<(String, Arc<Scene>)> {
    let maps = envmap_maps();
    let mut out: Vec<(String, Arc<Scene>)> = maps
        .iter()
        .map(|m| (m.0.to_string(), envmap_scene(m, 30.0)))
        .collect();
    for m in maps.iter().filter(|m| matches!(m.0, "sun" | "stripes")) {
        let scene = envmap_scene_rotated(m, 0.0, Some(envmap_tilt()));
        out.push((format!("{}_tilted", m.0), scene));
    }
    out
}

/// Every scene of [`envmap_case_scenes`] × method.
pub fn envmap_cases() -> Vec<Case> {
    let mut out = Vec::new();
    for (map, scene) in envmap_case_scenes() {
        let light = scene.background_light.expect("the map emits") as usize;
        for method in [LightSampling::Area, LightSampling::SolidAngle] {
            let name = format!("envmap/{map}/{method:?}").to_lowercase();
            let sampler = LightDirections {
                scene: scene.clone(),
                light,
                p: Vec3::ZERO,
                method,
                ns: Vec3::ZERO,
            };
            out.push(case(name, sampler));
        }
    }
    out
}

/// The mixture at every weight, for a rough plastic under a near quad (solid-angle sampling) and
/// for a diffuse receiver with a star half below its horizon (area sampling).
pub fn mixture_cases() -> Vec<Case> {
    let mut out = Vec::new();
    for w in MIX_WEIGHTS {
        let m = Mixture {
            light: light_sampler(Shape::Quad, Placement::Near, LightSampling::SolidAngle),
            bsdf: BsdfSampler::at_angle(plastic(0.3, 1.5), 30.0),
            weight: w,
        };
        out.push(case(format!("mixture/plastic_quad/w{w}"), m));
        let m = Mixture {
            light: light_sampler(Shape::Star, Placement::BelowHorizon, LightSampling::Area),
            bsdf: BsdfSampler::at_angle(diffuse(), 60.0),
            weight: w,
        };
        out.push(case(format!("mixture/diffuse_star_horizon/w{w}"), m));
    }
    out
}

/// Beckmann's visible-normal sampler and anisotropic lobes (issue 39): the Beckmann conductor at
/// α ∈ {0.05, 0.3, 1} at every angle of [`THETAS_DEG`]; anisotropic conductors, GGX and Beckmann,
/// 1:10 and 10:1, at θo ∈ {30°, 85°} and three azimuths (the lobe is not symmetric about the
/// plane of incidence there); the Beckmann dielectric at α ∈ {0.05, 0.3}, η = 1.5, from outside
/// and inside at θo ∈ {30°, 85°}, and an anisotropic one at θo = 30°, φo = 45°.
pub fn microfacet_cases() -> Vec<Case> {
    use crate::materials::Distribution::{Beckmann, Ggx};
    let at = sampler_at;
    let conductor = |mf: Microfacet| {
        Material::Conductor(Conductor {
            microfacet: mf,
            fresnel: ConductorFresnel::Tint(Vec3::new(0.95, 0.64, 0.54)),
        })
    };
    let mut out = Vec::new();
    for a in [0.05, 0.3, 1.0] {
        let m = conductor(Microfacet::new(Beckmann, a, a));
        for th in THETAS_DEG {
            out.push(case(
                format!("beckmann/conductor/a{a}/th{th}"),
                at(&m, th, 0.0, false),
            ));
        }
    }
    for d in [Ggx, Beckmann] {
        for (u, v) in [(0.05, 0.5), (0.5, 0.05)] {
            let m = conductor(Microfacet::new(d, u, v));
            for th in [30.0, 85.0] {
                for ph in [0.0, 45.0, 120.0] {
                    let name = format!("{}/conductor/a{u}x{v}/th{th}/ph{ph}", d.name());
                    out.push(case(name, at(&m, th, ph, false)));
                }
            }
        }
    }
    let glass = |mf: Microfacet| {
        Material::Dielectric(Dielectric {
            ior: 1.5,
            microfacet: mf,
        })
    };
    for a in [0.05, 0.3] {
        let m = glass(Microfacet::new(Beckmann, a, a));
        for (side, inside) in [("out", false), ("in", true)] {
            for th in [30.0, 85.0] {
                let name = format!("beckmann/dielectric/a{a}/ior1.5/{side}/th{th}");
                out.push(case(name, at(&m, th, 0.0, inside)));
            }
        }
    }
    let m = glass(Microfacet::new(Beckmann, 0.05, 0.5));
    for (side, inside) in [("out", false), ("in", true)] {
        let name = format!("beckmann/dielectric/a0.05x0.5/ior1.5/{side}/th30/ph45");
        out.push(case(name, at(&m, 30.0, 45.0, inside)));
    }
    out
}

/// Plastics in Mitsuba's coupling (`materials/plastic_mitsuba.rs`), rough GGX and Beckmann
/// coats at every angle of [`THETAS_DEG`] (the smooth coat's non-delta lobe is the cosine
/// warp's, tested as such), named `mitsuba_plastic/{distribution}/a{α}/th{θ}`.
pub fn mitsuba_plastic_cases() -> Vec<Case> {
    use crate::materials::Distribution::{Beckmann, Ggx};
    let mut out = Vec::new();
    for (d, a, nonlinear) in [
        (Ggx, 0.05, false),
        (Ggx, 0.3, true),
        (Beckmann, 0.05, false),
        (Beckmann, 0.3, false),
        (Beckmann, 1.0, true),
    ] {
        let albedo = Vec3::new(0.8, 0.4, 0.1);
        let m = Material::Plastic(Plastic::new_mitsuba(
            albedo,
            a,
            1.5,
            Vec3::ONE,
            d,
            nonlinear,
        ));
        for th in THETAS_DEG {
            let name = format!("mitsuba_plastic/{}/a{a}/th{th}", d.name());
            out.push(case(name, BsdfSampler::at_angle(m.clone(), th)));
        }
    }
    out
}

/// `m` seen from θo `theta` and φo `phi` (degrees), from below the surface where `inside`.
fn sampler_at(m: &Material, theta: f32, phi: f32, inside: bool) -> BsdfSampler {
    let (t, p) = (theta.to_radians(), phi.to_radians());
    let z = if inside { -t.cos() } else { t.cos() };
    BsdfSampler {
        material: m.clone(),
        wo: Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), z),
    }
}

/// Mitsuba's principled BSDF (`materials/principled.rs`), its lobes chosen with Mitsuba's
/// probabilities: the defaults at every angle of [`THETAS_DEG`]; an anisotropic tinted metal at
/// θo ∈ {30°, 85°} × φo ∈ {0°, 45°}; clearcoat, sheen, flatness and non-default sampling rates at
/// every angle; a mostly transmitting one (η 1.5) and a fully transmitting one with clearcoat
/// (η 0.8) from outside and inside. Named `principled/{what}/…/th{θ}`.
pub fn principled_cases() -> Vec<Case> {
    use crate::materials::Principled;
    use crate::materials::principled::SamplingRates;
    let at = sampler_at;
    // At every angle of THETAS_DEG, from outside.
    let every_angle = |what: &str, m: &Material| -> Vec<Case> {
        THETAS_DEG
            .iter()
            .map(|&th| case(format!("principled/{what}/th{th}"), at(m, th, 0.0, false)))
            .collect()
    };
    let default = Material::Principled(Principled::default());
    let mut out = every_angle("default", &default);
    let metal = Material::Principled(Principled {
        base_color: Vec3::new(0.9, 0.6, 0.3),
        roughness: 0.35,
        anisotropic: 0.7,
        metallic: 0.8,
        spec_tint: 0.5,
        ..Principled::default()
    });
    for th in [30.0, 85.0] {
        for ph in [0.0, 45.0] {
            let name = format!("principled/anisotropic/th{th}/ph{ph}");
            out.push(case(name, at(&metal, th, ph, false)));
        }
    }
    let coated = Material::Principled(Principled {
        base_color: Vec3::new(0.8, 0.2, 0.15),
        roughness: 0.2,
        spec_tint: 0.4,
        sheen: 0.8,
        sheen_tint: 0.6,
        clearcoat: 0.8,
        clearcoat_gloss: 0.5,
        flatness: 0.4,
        rates: SamplingRates {
            specular: 0.5,
            clearcoat: 3.0,
            diffuse: 2.0,
        },
        ..Principled::default()
    });
    out.extend(every_angle("clearcoat", &coated));
    let glass = Material::Principled(Principled {
        base_color: Vec3::new(0.8, 0.9, 1.0),
        roughness: 0.3,
        spec_trans: 0.9,
        eta: 1.5,
        transmission: true,
        ..Principled::default()
    });
    let thin = Material::Principled(Principled {
        base_color: Vec3::new(0.2, 0.6, 0.9),
        roughness: 0.5,
        spec_trans: 1.0,
        eta: 0.8,
        clearcoat: 0.5,
        transmission: true,
        ..Principled::default()
    });
    for (what, m, thetas) in [
        ("glass", &glass, &[30.0, 85.0][..]),
        ("eta0.8", &thin, &[30.0]),
    ] {
        for (side, inside) in [("out", false), ("in", true)] {
            for &th in thetas {
                let name = format!("principled/{what}/{side}/th{th}");
                out.push(case(name, at(m, th, 0.0, inside)));
            }
        }
    }
    out
}

/// Mitsuba's thin principled BSDF (`materials/principled_thin.rs`), its lobes chosen with
/// Mitsuba's probabilities, over the whole sphere of directions (its transmission mirrors its
/// reflection; every lobe here has α ≥ 0.19, wide enough for direction cells): the defaults and a
/// leaf (diffuse transmission, sheen, some specular) at every angle of [`THETAS_DEG`]; a glossy
/// anisotropic tinted sheet at θo ∈ {30°, 85°} × φo ∈ {0°, 45°}; flatness and non-default
/// sampling rates from both sides at 30°; a fully specular one of η 1.2 from below at 60°. Named
/// `principled_thin/{what}/…/th{θ}`.
pub fn principled_thin_cases() -> Vec<Case> {
    use crate::materials::PrincipledThin;
    use crate::materials::principled_thin::ThinRates;
    let at = sampler_at;
    let every_angle = |what: &str, m: &Material| -> Vec<Case> {
        THETAS_DEG
            .iter()
            .map(|&th| {
                case(
                    format!("principled_thin/{what}/th{th}"),
                    at(m, th, 0.0, false),
                )
            })
            .collect()
    };
    let mut out = every_angle(
        "default",
        &Material::PrincipledThin(PrincipledThin::default()),
    );
    let leaf = Material::PrincipledThin(PrincipledThin {
        base_color: Vec3::new(0.3, 0.7, 0.2),
        roughness: 0.7,
        spec_trans: 0.3,
        diff_trans: 1.2,
        sheen: 0.6,
        sheen_tint: 0.5,
        ..PrincipledThin::default()
    });
    out.extend(every_angle("leaf", &leaf));
    let glossy = Material::PrincipledThin(PrincipledThin {
        base_color: Vec3::new(0.9, 0.85, 0.7),
        roughness: 0.7,
        anisotropic: 0.5,
        spec_trans: 0.8,
        spec_tint: 0.5,
        ..PrincipledThin::default()
    });
    for th in [30.0, 85.0] {
        for ph in [0.0, 45.0] {
            let name = format!("principled_thin/glossy/th{th}/ph{ph}");
            out.push(case(name, at(&glossy, th, ph, false)));
        }
    }
    let rates = Material::PrincipledThin(PrincipledThin {
        base_color: Vec3::new(0.8, 0.5, 0.2),
        roughness: 0.6,
        spec_trans: 0.5,
        diff_trans: 0.8,
        flatness: 0.5,
        rates: ThinRates::from_array([0.5, 2.0, 3.0, 0.7]),
        ..PrincipledThin::default()
    });
    for (side, inside) in [("out", false), ("in", true)] {
        let name = format!("principled_thin/rates/{side}/th30");
        out.push(case(name, at(&rates, 30.0, 0.0, inside)));
    }
    let specular = Material::PrincipledThin(PrincipledThin {
        base_color: Vec3::new(0.2, 0.6, 0.9),
        roughness: 0.8,
        spec_trans: 1.0,
        eta: 1.2,
        ..PrincipledThin::default()
    });
    out.push(case(
        "principled_thin/eta1.2/in/th60".into(),
        at(&specular, 60.0, 0.0, true),
    ));
    out
}

/// glTF's metallic-roughness material (`materials/gltf_pbr.rs`), its specular lobe by visible
/// normals and its diffuse lobe by the cosine, picked by their Fresnel estimates: a white rough
/// metal and a coloured rough dielectric at every angle of [`THETAS_DEG`], a half-metallic one at
/// θo ∈ {30°, 85°}, a narrow metal (roughness 0.25, α 0.0625: half vectors zoomed on the normal)
/// at θo ∈ {0°, 60°, 89°}, and a dielectric of ior 1 (the specular lobe's floor rate) at θo ∈
/// {0°, 60°}, and one with `KHR_materials_specular` (weight ½, a colour clamped in one channel)
/// at θo ∈ {30°, 85°}. Named `gltf_pbr/{what}/th{θ}`.
pub fn gltf_pbr_cases() -> Vec<Case> {
    use crate::materials::GltfPbr;
    let mut out = Vec::new();
    let mut add = |what: &str, m: GltfPbr, thetas: &[f32]| {
        let m = Material::GltfPbr(m);
        for &th in thetas {
            let name = format!("gltf_pbr/{what}/th{th}");
            out.push(case(name, sampler_at(&m, th, 0.0, false)));
        }
    };
    let metal = GltfPbr {
        roughness: 0.5,
        ..GltfPbr::default()
    };
    add("metal", metal, &THETAS_DEG);
    let dielectric = GltfPbr {
        base_color: Vec3::new(0.8, 0.3, 0.1),
        metallic: 0.0,
        roughness: 0.7,
        ..GltfPbr::default()
    };
    add("dielectric", dielectric, &THETAS_DEG);
    let half = GltfPbr {
        base_color: Vec3::new(0.9, 0.6, 0.2),
        metallic: 0.4,
        roughness: 0.5,
        ..GltfPbr::default()
    };
    add("half_metal", half, &[30.0, 85.0]);
    let narrow = GltfPbr {
        base_color: Vec3::new(0.95, 0.64, 0.54),
        roughness: 0.25,
        ..GltfPbr::default()
    };
    add("narrow_metal", narrow, &[0.0, 60.0, 89.0]);
    let ior1 = GltfPbr {
        base_color: Vec3::new(0.5, 0.5, 0.5),
        metallic: 0.0,
        roughness: 0.6,
        ior: 1.0,
        ..GltfPbr::default()
    };
    add("ior1", ior1, &[0.0, 60.0]);
    let specular = GltfPbr {
        base_color: Vec3::new(0.6, 0.6, 0.3),
        metallic: 0.2,
        roughness: 0.5,
        specular: 0.5,
        specular_color: Vec3::new(1.5, 0.5, 20.0),
        ..GltfPbr::default()
    };
    add("specular", specular, &[30.0, 85.0]);
    out
}

/// Every case of the suite.
pub fn all_cases() -> Vec<Case> {
    let mut v = warp_cases();
    v.extend(material_cases());
    v.extend(dielectric_cases());
    v.extend(microfacet_cases());
    v.extend(mitsuba_plastic_cases());
    v.extend(principled_cases());
    v.extend(principled_thin_cases());
    v.extend(gltf_pbr_cases());
    v.extend(light_cases());
    v.extend(envmap_cases());
    v.extend(mixture_cases());
    v.extend(light_selection_cases());
    v
}

/// The case called `name`, if any.
pub fn case_by_name(name: &str) -> Option<Case> {
    all_cases().into_iter().find(|c| c.name == name)
}
