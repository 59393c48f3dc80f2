//! Turns a validated [`SceneDesc`] into the render-ready [`Scene`]: f32 primitives in a BVH,
//! materials, one light per emitting shape (per triangle for `triangles` meshes) and per light of
//! `lights`.

use super::desc::{
    BackgroundDesc, CameraDesc, FresnelDesc, GeometryDesc, LightDesc, LookAt, MaterialDesc,
    NamedMaterial, PlasticModel, ProjectionDesc, SceneDesc, TextureDesc,
};
use super::error::SceneError;
use super::parse_shapes::unit;
use crate::camera::Camera;
use crate::geometry::cylinder::Cylinder;
use crate::geometry::disk::Disk;
use crate::geometry::mesh_attributes::{
    AttrMesh, AttrTriangle, HAS_NORMALS, HAS_UVS, MeshAttributes, NamedSlot, normal_matrix,
};
use crate::geometry::primitive::{NONE, Primitive, Shape};
use crate::geometry::sphere::Sphere;
use crate::geometry::{Accel, polygon};
use crate::lights::light_sampler::selection_radiance;
use crate::lights::{
    BackgroundLight, DirectionalLight, DiskLight, EmissionTexture, EnvmapLight, Light, LightBvh,
    LightSampler, PointLight, PolygonLight, ProjectorLight, QuadLight, SphereLight, SpotLight,
    TriangleLight,
};
use crate::materials::normal_map::NormalMap;
use crate::materials::textured::MaterialTextures;
use crate::materials::{
    Conductor, ConductorFresnel, Dielectric, Diffuse, Distribution, Material, Microfacet, Mix,
    Plastic, ThinDielectric, two_sided::TwoSided,
};
use crate::math::Frame;
use crate::textures::Texture;
use glam::{DVec3, Vec2, Vec3};

/// Largest supported extent of a scene's bounding box (on its longest axis). The BVH builder
/// computes surface-area costs in single precision: sizes past ~1e19 overflow them to infinity
/// (and then NaN, which breaks the build); 1e15 also keeps area × primitive-count costs finite.
/// The format promises 1e-3 to 1e5 units.
pub const MAX_SCENE_SIZE: f32 = 1e15;

/// A scene ready to render.
pub struct Scene {
    /// The camera.
    pub camera: Camera,
    /// Longest path (Mitsuba's convention, `-1` = unlimited).
    pub max_depth: i32,
    /// Camera rays do not see emitters ([`crate::scene::SceneDesc::hide_emitters`]).
    pub hide_emitters: bool,
    /// Primitives and their BVH.
    pub accel: Accel,
    /// Materials; the last one is the black diffuse used by shapes without a material.
    pub materials: Vec<Material>,
    /// Per material: whether its back side sees the same BSDF.
    pub two_sided: Vec<bool>,
    /// Material names, parallel to `materials`.
    pub material_names: Vec<String>,
    /// All lights, the background last if present.
    pub lights: Vec<Light>,
    /// Power-proportional light selection; `None` when nothing emits.
    pub light_sampler: Option<LightSampler>,
    /// Light selection by importance at the receiver ([`crate::lights::LightSelection::Bvh`]);
    /// `None` exactly where `light_sampler` is.
    pub light_bvh: Option<LightBvh>,
    /// Index of the background light, if the background is not black.
    pub background_light: Option<u32>,
    /// Shading normals and texture coordinates of the triangles that have them.
    pub attributes: MeshAttributes,
    /// Per material, its textured parameters (`None`: untextured), parallel to `materials`.
    pub material_textures: Vec<Option<MaterialTextures>>,
    /// The emission textures of textured emitters, indexed by [`Light::texture`].
    pub emission_textures: Vec<EmissionTexture>,
    /// Per material, the mix it is (`None`: not a mix), parallel to `materials`; empty when the
    /// scene has no mix. A mix's entry in `materials` is the material its mean weight favours
    /// (for code that reads one BSDF); [`Scene::resolve`] chooses per hit.
    pub mixes: Vec<Option<Mix>>,
    /// Per material, the two-sided pair it is (`None`: not a pair), parallel to `materials`;
    /// empty when the scene has no pair. A pair's entry in `materials` is its front's;
    /// [`Scene::resolve`] chooses per hit.
    pub sides: Vec<Option<TwoSided>>,
    /// Per material, its normal map (`None`: none), parallel to `materials`; empty when no
    /// material has one ([`Scene::shading_at`]).
    pub normal_maps: Vec<Option<NormalMap>>,
    /// Per material, its opacity (`None`: opaque), a scalar texture, parallel to `materials`;
    /// empty when every material is opaque, and then rays meet every surface
    /// ([`Scene::intersect`]).
    pub opacity: Vec<Option<Texture>>,
}

fn v(d: DVec3) -> Vec3 {
    d.as_vec3()
}

fn material(desc: &MaterialDesc) -> Material {
    match desc {
        MaterialDesc::Diffuse { albedo } => Material::Diffuse(Diffuse { albedo: v(*albedo) }),
        MaterialDesc::Conductor {
            alpha,
            alpha_v,
            distribution,
            fresnel,
        } => Material::Conductor(Conductor {
            microfacet: microfacet(*distribution, *alpha, *alpha_v),
            fresnel: match fresnel {
                FresnelDesc::Complex { eta, k, tint } => ConductorFresnel::Complex {
                    eta: v(*eta),
                    k: v(*k),
                    tint: v(*tint),
                },
                FresnelDesc::Reflectance(r) => ConductorFresnel::Tint(v(*r)),
            },
        }),
        MaterialDesc::Plastic {
            albedo,
            alpha,
            ior,
            specular,
            model: PlasticModel::Lumis,
        } => Material::Plastic(Plastic::new(
            v(*albedo),
            *alpha as f32,
            *ior as f32,
            v(*specular),
        )),
        MaterialDesc::Plastic {
            albedo,
            alpha,
            ior,
            specular,
            model:
                PlasticModel::Mitsuba {
                    distribution,
                    nonlinear,
                },
        } => Material::Plastic(Plastic::new_mitsuba(
            v(*albedo),
            *alpha as f32,
            *ior as f32,
            v(*specular),
            *distribution,
            *nonlinear,
        )),
        MaterialDesc::Dielectric {
            ior,
            alpha,
            alpha_v,
            distribution,
        } => Material::Dielectric(Dielectric {
            ior: *ior as f32,
            microfacet: microfacet(*distribution, *alpha, *alpha_v),
        }),
        MaterialDesc::ThinDielectric { ior } => {
            Material::ThinDielectric(ThinDielectric { ior: *ior as f32 })
        }
        MaterialDesc::Principled(p) => Material::Principled(p.material()),
        MaterialDesc::PrincipledThin(p) => Material::PrincipledThin(p.material()),
        MaterialDesc::GltfPbr(p) => Material::GltfPbr(p.material()),
    }
}

/// The microfacets of α (α_u) and `alpha_v` (isotropic where `None`).
fn microfacet(distribution: Distribution, alpha: f64, alpha_v: Option<f64>) -> Microfacet {
    let u = alpha as f32;
    Microfacet::new(distribution, u, alpha_v.map_or(u, |v| v as f32))
}

/// The mixes and two-sided pairs of `desc`'s materials, each parallel to them (empty if there
/// are none). The parser rules out a material that contains itself; a description built
/// otherwise is checked here, so that resolving a material at a hit always ends.
type Composites = (Vec<Option<Mix>>, Vec<Option<TwoSided>>);

fn composites(desc: &SceneDesc) -> Result<Composites, SceneError> {
    let n = desc.materials.len();
    for (i, m) in desc.materials.iter().enumerate() {
        let Some(parts) = m.parts() else { continue };
        // Following either part must leave the mixes and pairs within `n` steps.
        let mut frontier = vec![i];
        for _ in 0..=n {
            if frontier.is_empty() {
                break;
            }
            frontier = frontier
                .iter()
                .filter_map(|&j| desc.materials.get(j).and_then(NamedMaterial::parts))
                .flatten()
                .collect();
            frontier.sort_unstable();
            frontier.dedup();
        }
        if !frontier.is_empty() || parts.iter().any(|&j| j >= n) {
            return Err(SceneError::new(
                format!("materials.{}", m.name),
                "a mix or two_sided pair names a material that does not exist or contains itself",
            ));
        }
    }
    let mixes: Vec<Option<Mix>> = desc
        .materials
        .iter()
        .map(|m| {
            m.mix.as_ref().map(|mix| Mix {
                materials: mix.materials.map(|j| j as u32),
                weight: match &mix.weight_texture {
                    Some(t) => t.texture.clone(),
                    None => Texture::Constant(Vec3::splat(mix.weight as f32)),
                },
                mitsuba: mix.mitsuba,
            })
        })
        .collect();
    let sides: Vec<Option<TwoSided>> = desc
        .materials
        .iter()
        .map(|m| {
            m.sides.map(|[front, back]| TwoSided {
                front: front as u32,
                back: back as u32,
            })
        })
        .collect();
    Ok((with_black(mixes), with_black(sides)))
}

/// `v` with an entry for the black material of shapes without one, or empty if all are `None`.
fn with_black<T>(mut v: Vec<Option<T>>) -> Vec<Option<T>> {
    if v.iter().all(Option::is_none) {
        v.clear();
    } else {
        v.push(None);
    }
    v
}

/// The 6 faces of a box as parallelograms `(corner, edge_u, edge_v)` with outward normals, rotated
/// about +y by `rot_deg` (x' = cos·x + sin·z, z' = −sin·x + cos·z) and translated.
pub fn box_faces(min: DVec3, max: DVec3, rot_deg: f64, translate: DVec3) -> [[DVec3; 3]; 6] {
    let (s, c) = rot_deg.to_radians().sin_cos();
    let rot = |p: DVec3| DVec3::new(c * p.x + s * p.z, p.y, -s * p.x + c * p.z);
    let size = max - min;
    let mut faces = [[DVec3::ZERO; 3]; 6];
    for axis in 0..3 {
        let (ua, va) = ((axis + 1) % 3, (axis + 2) % 3);
        let mut eu = DVec3::ZERO;
        eu[ua] = size[ua];
        let mut ev = DVec3::ZERO;
        ev[va] = size[va];
        // cross(e_u, e_v) = +axis at the max side; swapping the edges flips it for the min side.
        let mut hi = min;
        hi[axis] = max[axis];
        faces[2 * axis] = [rot(hi) + translate, rot(eu), rot(ev)];
        faces[2 * axis + 1] = [rot(min) + translate, rot(ev), rot(eu)];
    }
    faces
}

/// The light of `lights[index]`, `None` where it emits nothing (a black intensity, as a black
/// emitter is no light); a texture joins `emission_textures`.
fn delta_light(
    desc: &LightDesc,
    scene_radius: f32,
    emission_textures: &mut Vec<EmissionTexture>,
    index: usize,
) -> Option<Light> {
    let frame = |f: &LookAt| {
        let (s, t, n) = f.axes();
        Frame {
            s: v(s),
            t: v(t),
            n: v(n),
        }
    };
    let black = |c: Vec3| !c.cmpgt(Vec3::ZERO).any();
    let mut texture_index = |t: &Option<TextureDesc>| match t {
        None => (NONE, Vec3::ONE),
        Some(t) => {
            emission_textures.push(EmissionTexture {
                texture: t.texture.clone(),
                shape: format!("lights[{index}]"),
            });
            (
                emission_textures.len() as u32 - 1,
                selection_radiance(&t.texture),
            )
        }
    };
    match desc {
        LightDesc::Point {
            position,
            intensity,
        } => (!black(v(*intensity))).then(|| {
            Light::Point(PointLight {
                position: v(*position),
                intensity: v(*intensity),
            })
        }),
        LightDesc::Spot {
            frame: f,
            intensity,
            cutoff_angle_deg,
            beam_width_deg,
            texture,
        } => {
            let tex_black = texture.as_ref().is_some_and(|t| black(t.texture.max()));
            if black(v(*intensity)) || tex_black {
                return None;
            }
            let mut l = SpotLight::new(
                v(f.from),
                frame(f),
                v(*intensity),
                cutoff_angle_deg.to_radians() as f32,
                beam_width_deg.to_radians() as f32,
            );
            (l.texture, l.selection) = texture_index(texture);
            Some(Light::Spot(l))
        }
        LightDesc::Directional {
            direction,
            irradiance,
        } => (!black(v(*irradiance))).then(|| {
            Light::Directional(DirectionalLight {
                direction: v(*direction),
                irradiance: v(*irradiance),
                scene_radius,
            })
        }),
        LightDesc::Projector {
            frame: f,
            fov_x_deg,
            irradiance,
            texture,
            scale,
        } => {
            let (w, h) = texture.as_ref().map_or((1, 1), |t| t.texture.resolution());
            let tan_x = (0.5 * fov_x_deg.to_radians()).tan();
            // Mitsuba's perspective projection: the image's aspect sets the vertical extent.
            let tan_y = tan_x * h as f64 / w as f64;
            let k = std::f64::consts::PI * scale;
            let intensity = match texture {
                Some(_) => Vec3::splat(k as f32),
                None => v(*irradiance * k),
            };
            let tex_black = texture.as_ref().is_some_and(|t| black(t.texture.max()));
            if black(intensity) || tex_black {
                return None;
            }
            let (texture, selection) = texture_index(texture);
            Some(Light::Projector(ProjectorLight {
                position: v(f.from),
                frame: frame(f),
                tan_half: glam::Vec2::new(tan_x as f32, tan_y as f32),
                intensity,
                selection,
                texture,
            }))
        }
    }
}

/// A quad's two primitives. [`QuadLight::triangle_point`] finds a textured quad light's sampled
/// points in this split; the two change together (`renderer/tests/textured_emission.rs` checks them).
fn quad_triangles(corner: Vec3, eu: Vec3, ev: Vec3) -> [[Vec3; 3]; 2] {
    [
        [corner, corner + eu, corner + eu + ev],
        [corner, corner + eu + ev, corner + ev],
    ]
}

/// Texture coordinates of a quad's corners `corner`, `+edge_u`, `+edge_u+edge_v`, `+edge_v`:
/// `u` runs along `edge_u`, `v` along `edge_v`; `QUAD_UV_TRIANGLES` indexes them as
/// [`quad_triangles`] orders its vertices.
const QUAD_UVS: [Vec2; 4] = [
    Vec2::new(0.0, 0.0),
    Vec2::new(1.0, 0.0),
    Vec2::new(1.0, 1.0),
    Vec2::new(0.0, 1.0),
];
const QUAD_UV_TRIANGLES: [[u32; 3]; 2] = [[0, 1, 2], [0, 2, 3]];

/// Appends a mesh's vertex normals and texture coordinates; returns its index.
fn add_mesh(
    attributes: &mut MeshAttributes,
    normals: Option<&[Vec3]>,
    uvs: Option<&[Vec2]>,
) -> u32 {
    let mesh = AttrMesh {
        normal_base: attributes.normals.len() as u32,
        uv_base: attributes.uvs.len() as u32,
        flags: normals.map_or(0, |_| HAS_NORMALS) | uvs.map_or(0, |_| HAS_UVS),
        named: NONE,
    };
    attributes
        .normals
        .extend_from_slice(normals.unwrap_or_default());
    attributes.uvs.extend_from_slice(uvs.unwrap_or_default());
    attributes.meshes.push(mesh);
    attributes.meshes.len() as u32 - 1
}

/// Appends the values of mesh `m`'s attributes that textures read (`names`, in slot order), its
/// faces' records to follow from the next triangle record on.
fn add_named(
    attributes: &mut MeshAttributes,
    m: u32,
    mesh: &crate::scene::mesh::MeshData,
    names: &[String],
) {
    attributes.meshes[m as usize].named = attributes.named_slots.len() as u32;
    let first_triangle = attributes.triangles.len() as u32;
    for name in names {
        let slot = match mesh.attributes.iter().find(|a| a.name == *name) {
            Some(a) => {
                let base = attributes.named_values.len() as u32;
                attributes.named_values.extend_from_slice(&a.values);
                NamedSlot {
                    base,
                    first_triangle,
                    per_face: a.kind() == crate::scene::mesh::AttributeKind::Face,
                }
            }
            None => NamedSlot {
                base: NONE,
                first_triangle,
                per_face: false,
            },
        };
        attributes.named_slots.push(slot);
    }
}

/// A quad's light, whose two triangles' vertex attributes start at `attr`.
fn quad_light(c: Vec3, eu: Vec3, ev: Vec3, le: Vec3, attr: u32) -> Option<Light> {
    QuadLight::new(c, eu, ev, le).map(|q| Light::Quad(QuadLight { attr, ..q }))
}

/// A textured quad light looks up the texture coordinates of both its triangles (from `attr`
/// on): an error if single precision dropped one of them (the light would still sample there).
fn check_quad_attrs(
    attributes: &MeshAttributes,
    attr: u32,
    light: u32,
    texture: u32,
    json_path: &str,
) -> Result<(), SceneError> {
    if light == NONE || texture == NONE || attributes.triangles.len() as u32 == attr + 2 {
        return Ok(());
    }
    Err(SceneError::new(
        json_path,
        "textured emitter: a triangle of this quad has zero area in single precision",
    ))
}

impl Scene {
    /// True if a material transmits light (a dielectric): the path tracer then runs its
    /// transmission code ([`crate::integrator::path::radiance_specialised`]).
    pub fn has_transmission(&self) -> bool {
        self.materials.iter().any(Material::transmits)
    }
    /// Builds the scene. Fails only on lights the parser could not rule out (e.g. an emitter that
    /// becomes degenerate in f32).
    pub fn from_desc(desc: &SceneDesc) -> Result<Scene, SceneError> {
        #[cfg(feature = "mutants")]
        let desc = &{
            let mut d = desc.clone();
            crate::mutants::apply_to_desc(&mut d);
            d
        };
        let cam = &desc.camera;
        let camera = camera_of(cam, cam.width, cam.height).with_filter(cam.filter.filter());
        let mut materials: Vec<Material> = desc
            .materials
            .iter()
            .map(|m| material(&m.material))
            .collect();
        let mut two_sided: Vec<bool> = desc.materials.iter().map(|m| m.two_sided).collect();
        let mut material_names: Vec<String> =
            desc.materials.iter().map(|m| m.name.clone()).collect();
        let mut material_textures = Vec::with_capacity(materials.len() + 1);
        for (m, built) in desc.materials.iter().zip(&materials) {
            let t = &m.textures;
            let mut textures = MaterialTextures::new(
                t.albedo.as_ref().map(|d| d.texture.clone()),
                t.reflectance.as_ref().map(|d| d.texture.clone()),
                t.alpha.as_ref().map(|d| d.texture.clone()),
                t.alpha_v.as_ref().map(|d| d.texture.clone()),
                built,
            )
            .map_err(|e| SceneError::new(format!("materials.{}", m.name), e))?;
            textures.principled = t.principled.clone().map(|d| d.map(|d| d.texture));
            material_textures.push((!t.is_empty()).then_some(textures));
        }
        material_textures.push(None);
        let (mixes, sides) = composites(desc)?;
        let normal_maps: Vec<Option<NormalMap>> = with_black(
            desc.materials
                .iter()
                .map(|m| m.normal_map.as_ref().map(|n| n.normal_map()))
                .collect(),
        );
        let opacity: Vec<Option<Texture>> = with_black(
            desc.materials
                .iter()
                .map(|m| m.opacity.as_ref().map(|o| o.texture.clone()))
                .collect(),
        );
        let black = materials.len() as u32;
        materials.push(Material::Diffuse(Diffuse { albedo: Vec3::ZERO }));
        two_sided.push(true);
        material_names.push("(black)".into());

        let mut prims = Vec::new();
        let mut lights = Vec::new();
        let mut emission_textures = Vec::new();
        let mut attributes = MeshAttributes::default();
        let (mut scene_lo, mut scene_hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
        for shape in &desc.shapes {
            let first_prim = prims.len();
            let mat = shape.material.map_or(black, |m| m as u32);
            // A textured emitter's lights hold its texture's index and are weighed by its
            // selection radiance; whether it emits at all is the parser's rule (`max > 0`).
            let (le, emits, texture) = match &shape.emission_texture {
                None => {
                    let le = v(shape.emission);
                    (le, le.cmpgt(Vec3::ZERO).any(), NONE)
                }
                Some(t) if t.texture.max().cmpgt(Vec3::ZERO).any() => {
                    emission_textures.push(EmissionTexture {
                        texture: t.texture.clone(),
                        shape: shape.json_path.clone(),
                    });
                    let index = emission_textures.len() as u32 - 1;
                    (selection_radiance(&t.texture), true, index)
                }
                Some(_) => (Vec3::ZERO, false, NONE),
            };
            let err = |what: &str| SceneError::new(&shape.json_path, what);
            if emits && matches!(opacity.get(mat as usize), Some(Some(_))) {
                return Err(err(
                    "an emitter's material cannot have an opacity: a mask hides the surface, \
                     and Mitsuba masks its BSDF but not its emission",
                ));
            }
            let mut push_light = |light: Option<Light>| -> Result<u32, SceneError> {
                if !emits {
                    return Ok(NONE);
                }
                let mut light = light.ok_or_else(|| {
                    err("emitter has zero area, or an area too large, in single precision")
                })?;
                if texture != NONE {
                    let textured = light.set_texture(texture);
                    debug_assert!(textured, "only area lights come from shapes");
                }
                lights.push(light);
                Ok(lights.len() as u32 - 1)
            };
            // Triangles with attribute indices `attr` (`None`: no attributes) into `attributes`.
            // A triangle given attributes has its record whether it is kept or dropped
            // (degenerate), so that a mesh's face k has record `first + k` (face attributes).
            let mut push_tris =
                |tris: &[[Vec3; 3]],
                 light: u32,
                 attributes: &mut MeshAttributes,
                 attr: &dyn Fn(usize) -> Option<AttrTriangle>| {
                    for (i, t) in tris.iter().enumerate() {
                        let attr = attr(i).map_or(NONE, |a| {
                            attributes.triangles.push(a);
                            attributes.triangles.len() as u32 - 1
                        });
                        if let Some(shape) = Shape::triangle(*t) {
                            prims.push(Primitive {
                                shape,
                                material: mat,
                                light,
                                attr,
                            });
                        }
                    }
                };
            let no_attr = |_: usize| None;
            // A quad's two triangles with their corners' texture coordinates.
            let quad_uvs = |attributes: &mut MeshAttributes| {
                let mesh = add_mesh(attributes, None, Some(&QUAD_UVS));
                move |i: usize| {
                    Some(AttrTriangle {
                        v: QUAD_UV_TRIANGLES[i],
                        mesh,
                    })
                }
            };
            match &shape.geometry {
                GeometryDesc::Quad {
                    corner,
                    edge_u,
                    edge_v,
                } => {
                    let (c, eu, ev) = (v(*corner), v(*edge_u), v(*edge_v));
                    let attr = attributes.triangles.len() as u32;
                    let light = push_light(quad_light(c, eu, ev, le, attr))?;
                    let uvs = quad_uvs(&mut attributes);
                    push_tris(&quad_triangles(c, eu, ev), light, &mut attributes, &uvs);
                    check_quad_attrs(&attributes, attr, light, texture, &shape.json_path)?;
                }
                GeometryDesc::Polygon { vertices } => {
                    let n = polygon::newell_normal(vertices).normalize().as_vec3();
                    let indices: Vec<[u32; 3]> = polygon::triangulate(vertices)
                        .iter()
                        .map(|t| t.map(|i| i as u32))
                        .collect();
                    let verts: Vec<Vec3> = vertices.iter().map(|p| v(*p)).collect();
                    let tris: Vec<[Vec3; 3]> = indices
                        .iter()
                        .map(|t| t.map(|i| verts[i as usize]))
                        .collect();
                    let light =
                        push_light(PolygonLight::new(verts, indices, n, le).map(Light::Polygon))?;
                    push_tris(&tris, light, &mut attributes, &no_attr);
                }
                GeometryDesc::Triangles { .. } | GeometryDesc::Mesh { .. } => {
                    // One primitive, and for an emitter one triangle light, per triangle.
                    let (world, indices): (Vec<Vec3>, &[[u32; 3]]) = match &shape.geometry {
                        GeometryDesc::Triangles { positions, indices } => {
                            (positions.iter().map(|&p| v(p)).collect(), indices)
                        }
                        GeometryDesc::Mesh { to_world, mesh, .. } => (
                            mesh.positions
                                .iter()
                                .map(|p| to_world.transform_point3(p.as_dvec3()).as_vec3())
                                .collect(),
                            &mesh.indices,
                        ),
                        _ => unreachable!("matched above"),
                    };
                    // Vertex attributes, stored once per vertex, normals in world space.
                    let mut attr_mesh = None;
                    if let GeometryDesc::Mesh {
                        to_world,
                        mesh,
                        face_normals,
                        ..
                    } = &shape.geometry
                    {
                        let normals = mesh.normals.as_ref().filter(|_| !face_normals).map(|ns| {
                            let m = normal_matrix(*to_world);
                            ns.iter()
                                .map(|n| (m * n.as_dvec3()).normalize_or_zero().as_vec3())
                                .collect::<Vec<_>>()
                        });
                        let named = !desc.mesh_attributes.is_empty()
                            && mesh
                                .attributes
                                .iter()
                                .any(|a| desc.mesh_attributes.contains(&a.name));
                        if normals.is_some() || mesh.uvs.is_some() || named {
                            let m =
                                add_mesh(&mut attributes, normals.as_deref(), mesh.uvs.as_deref());
                            if named {
                                add_named(&mut attributes, m, mesh, &desc.mesh_attributes);
                            }
                            attr_mesh = Some(m);
                        }
                    }
                    for idx in indices {
                        let t = idx.map(|i| world[i as usize]);
                        // The attributes `push_tris` gives this triangle's primitive: it makes
                        // one exactly when the triangle has a normal, as the light needs.
                        let attr = attr_mesh.map_or(NONE, |_| attributes.triangles.len() as u32);
                        let light =
                            push_light(crate::geometry::triangle::triangle_normal(&t).map(|n| {
                                Light::Triangle(TriangleLight {
                                    v: t,
                                    n,
                                    area: crate::geometry::triangle::triangle_area(&t),
                                    le,
                                    attr,
                                    texture: NONE,
                                })
                            }))?;
                        let attr = |_: usize| attr_mesh.map(|mesh| AttrTriangle { v: *idx, mesh });
                        push_tris(&[t], light, &mut attributes, &attr);
                    }
                }
                GeometryDesc::Disk {
                    center,
                    normal,
                    radius,
                    u_axis,
                } => {
                    let mut disk = Disk::new(v(*center), v(*normal).normalize(), *radius as f32);
                    if let Some(u) = u_axis {
                        let n = unit(*normal);
                        disk.u_axis = Some(v(unit(*u - n * n.dot(*u))));
                    }
                    let light = push_light(Some(Light::Disk(DiskLight::new(disk, le))))?;
                    prims.push(Primitive {
                        shape: Shape::Disk(disk),
                        material: mat,
                        light,
                        attr: NONE,
                    });
                }
                GeometryDesc::Sphere {
                    center,
                    radius,
                    pole,
                    u_axis,
                } => {
                    // The world's axes exactly when neither is given (z = +z, x = +x − 0).
                    let z = unit(pole.unwrap_or(DVec3::Z));
                    let x = u_axis.unwrap_or(DVec3::X);
                    let x = unit(x - z * z.dot(x));
                    let sphere = Sphere {
                        center: v(*center),
                        radius: *radius as f32,
                        pole: v(z),
                        u_axis: v(x),
                    };
                    let light = push_light(Some(Light::Sphere(SphereLight {
                        sphere,
                        le,
                        texture: NONE,
                    })))?;
                    prims.push(Primitive {
                        shape: Shape::Sphere(sphere),
                        material: mat,
                        light,
                        attr: NONE,
                    });
                }
                GeometryDesc::Cylinder {
                    p0,
                    p1,
                    radius,
                    u_axis,
                    flip_normals,
                } => {
                    // Mitsuba's default u axis is the first of the axis' frame
                    // (`to_frame(Frame3f(d))`, the same construction as `Frame::from_normal`).
                    let z = unit(*p1 - *p0);
                    let u = match u_axis {
                        Some(u) => unit(*u - z * z.dot(*u)),
                        None => Frame::from_normal(v(z)).s.as_dvec3(),
                    };
                    prims.push(Primitive {
                        shape: Shape::Cylinder(Cylinder {
                            p0: v(*p0),
                            axis: v(*p1 - *p0),
                            u_axis: v(u),
                            radius: *radius as f32,
                            flip: *flip_normals,
                        }),
                        material: mat,
                        // The parser refuses an emitting cylinder.
                        light: NONE,
                        attr: NONE,
                    });
                }
                GeometryDesc::Box {
                    min,
                    max,
                    rotate_y_deg,
                    translate,
                } => {
                    for [c, eu, ev] in box_faces(*min, *max, *rotate_y_deg, *translate) {
                        let (c, eu, ev) = (v(c), v(eu), v(ev));
                        let attr = attributes.triangles.len() as u32;
                        let light = push_light(quad_light(c, eu, ev, le, attr))?;
                        let uvs = quad_uvs(&mut attributes);
                        push_tris(&quad_triangles(c, eu, ev), light, &mut attributes, &uvs);
                        check_quad_attrs(&attributes, attr, light, texture, &shape.json_path)?;
                    }
                }
            }
            for p in &prims[first_prim..] {
                let (lo, hi) = p.shape.bounds();
                (scene_lo, scene_hi) = (scene_lo.min(lo), scene_hi.max(hi));
            }
            // Infinite sizes compare greater; NaN ones need saying.
            let size = (scene_hi - scene_lo).max_element();
            if first_prim < prims.len() && (size.is_nan() || size > MAX_SCENE_SIZE) {
                return Err(SceneError::new(
                    &shape.json_path,
                    format!(
                        "this shape makes the scene {size:e} units across; at most \
                         {MAX_SCENE_SIZE:e} is supported (single precision)"
                    ),
                ));
            }
        }
        let accel = Accel::new(prims);
        let (lo, hi) = accel.bounds();
        let scene_radius = if lo.is_finite() && hi.is_finite() {
            0.5 * (hi - lo).length().max(1e-6)
        } else {
            1.0
        };
        for (i, l) in desc.lights.iter().enumerate() {
            if let Some(light) = delta_light(l, scene_radius, &mut emission_textures, i) {
                lights.push(light);
            }
        }
        let background = match &desc.background {
            BackgroundDesc::Constant(c) => {
                let le = v(*c);
                le.cmpgt(Vec3::ZERO)
                    .any()
                    .then_some(Light::Background(BackgroundLight { le, scene_radius }))
            }
            BackgroundDesc::Envmap(e) => EnvmapLight::new(
                e.image.width as usize,
                e.image.height as usize,
                &e.image.data,
                e.scale as f32,
                EnvmapLight::rotation_matrix(e.rotate_y_deg as f32, e.rotation),
                scene_radius,
            )
            .map(Light::Envmap),
        };
        let background_light = background.map(|light| {
            lights.push(light);
            lights.len() as u32 - 1
        });
        let light_sampler = LightSampler::new(&lights);
        let light_bvh = LightBvh::new(&lights);
        Ok(Scene {
            camera,
            max_depth: desc.max_depth,
            hide_emitters: desc.hide_emitters,
            accel,
            materials,
            two_sided,
            material_names,
            lights,
            light_sampler,
            light_bvh,
            background_light,
            attributes,
            material_textures,
            emission_textures,
            mixes,
            sides,
            normal_maps,
            opacity,
        })
    }

    /// Parses, validates and builds scene JSON text: the one entry point from text to a
    /// renderable scene, which [`Scene::load`] and the fuzz target use.
    pub fn from_json_str(text: &str) -> Result<Scene, SceneError> {
        Scene::from_desc(&super::parse::parse_scene(text)?)
    }

    /// Loads and builds a scene file; errors name the file.
    pub fn load(path: &std::path::Path) -> Result<Scene, SceneError> {
        Scene::from_desc(&super::parse::load_scene(path)?).map_err(|e| e.in_file(path))
    }
}

/// The render-ready camera of `cam` on a film of `width × height` pixels (its principal point
/// offset in film fractions, so the same on any film) (the scene's own size,
/// or a viewer preview's), with the box filter. The parser checked the view direction and `up`
/// in f64. Rounded to f32, a `to` very close to a distant `from` could coincide with it, and a
/// tiny `up` become zero: the camera gets a look-at point as far away as `from` is from the
/// origin, and a unit `up`.
pub fn camera_of(cam: &CameraDesc, width: u32, height: u32) -> Camera {
    let reach = cam.from.abs().max_element().max(1.0);
    let (from, to, up) = (
        v(cam.from),
        v(cam.from + unit(cam.to - cam.from) * reach),
        v(unit(cam.up)),
    );
    match cam.projection {
        ProjectionDesc::Perspective { vfov_deg } => {
            Camera::new(from, to, up, vfov_deg as f32, width, height)
        }
        ProjectionDesc::ThinLens {
            vfov_deg,
            aperture_radius,
            focus_distance,
        } => Camera::new(from, to, up, vfov_deg as f32, width, height)
            .with_thin_lens(aperture_radius as f32, focus_distance as f32),
        ProjectionDesc::Orthographic { view_size: [w, h] } => {
            Camera::orthographic(from, to, up, w as f32, h as f32, width, height)
        }
    }
    .with_principal_point_offset(
        cam.principal_point_offset[0] as f32,
        cam.principal_point_offset[1] as f32,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn box_faces_point_outwards() {
        let faces = box_faces(
            DVec3::ZERO,
            DVec3::new(1.0, 2.0, 3.0),
            30.0,
            DVec3::new(5.0, 0.0, 0.0),
        );
        let centre = DVec3::new(5.0, 0.0, 0.0) + {
            let (s, c) = 30f64.to_radians().sin_cos();
            let p = DVec3::new(0.5, 1.0, 1.5);
            DVec3::new(c * p.x + s * p.z, p.y, -s * p.x + c * p.z)
        };
        let mut area = 0.0;
        for [c, eu, ev] in faces {
            let n = eu.cross(ev);
            let face_centre = c + 0.5 * (eu + ev);
            assert!(
                n.dot(face_centre - centre) > 0.0,
                "normal must point away from the centre"
            );
            area += n.length();
        }
        assert!((area - 2.0 * (2.0 + 3.0 + 6.0)).abs() < 1e-9);
    }
}
