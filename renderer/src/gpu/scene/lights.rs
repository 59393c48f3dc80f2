//! Light records (`Light` in `lights/mod.wgsl`), one per [`Light`], the triangles of polygon lights,
//! the power-proportional selection tables, and the lights' kind tags. An environment map's
//! texture and tables are in [`super::envmap`].
//! WGSL twin: `lights/mod.wgsl` (the record layout and the `switch` on [`LightTag`]).

use super::v4;
use crate::geometry::primitive::NONE;
use crate::gpu::prelude::gpu_tags;
use crate::lights::Light;
use crate::scene::Scene;
use bytemuck::{Pod, Zeroable};

/// A light record (`Light` in `lights/mod.wgsl`): `h` = (kind, first triangle or a triangle's or
/// quad's vertex attributes, triangle count, emission texture) (an environment map: kind, width,
/// height, offset of its tables), four vec4 of geometry per kind and `le` = (radiance, area) (see
/// the top of `lights/mod.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuLight {
    pub(crate) h: [u32; 4],
    pub(crate) a: [f32; 4],
    pub(crate) b: [f32; 4],
    pub(crate) c: [f32; 4],
    pub(crate) d: [f32; 4],
    pub(crate) le: [f32; 4],
}

gpu_tags! {
    /// A light record's kind (`h.x`), in the variant order of [`Light`].
    pub enum LightTag {
        /// [`Light::Triangle`].
        Triangle => "LIGHT_TRIANGLE",
        /// [`Light::Polygon`].
        Polygon => "LIGHT_POLYGON",
        /// [`Light::Quad`].
        Quad => "LIGHT_QUAD",
        /// [`Light::Disk`].
        Disk => "LIGHT_DISK",
        /// [`Light::Sphere`].
        Sphere => "LIGHT_SPHERE",
        /// [`Light::Background`].
        Background => "LIGHT_BACKGROUND",
        /// [`Light::Envmap`].
        Envmap => "LIGHT_ENVMAP",
        /// [`Light::Point`].
        Point => "LIGHT_POINT",
        /// [`Light::Spot`].
        Spot => "LIGHT_SPOT",
        /// [`Light::Directional`].
        Directional => "LIGHT_DIRECTIONAL",
        /// [`Light::Projector`].
        Projector => "LIGHT_PROJECTOR",
    }
}

impl LightTag {
    /// The tag of `l`.
    pub fn of(l: &Light) -> LightTag {
        match l {
            Light::Triangle(_) => LightTag::Triangle,
            Light::Polygon(_) => LightTag::Polygon,
            Light::Quad(_) => LightTag::Quad,
            Light::Disk(_) => LightTag::Disk,
            Light::Sphere(_) => LightTag::Sphere,
            Light::Background(_) => LightTag::Background,
            Light::Envmap(_) => LightTag::Envmap,
            Light::Point(_) => LightTag::Point,
            Light::Spot(_) => LightTag::Spot,
            Light::Directional(_) => LightTag::Directional,
            Light::Projector(_) => LightTag::Projector,
        }
    }
}

/// A prefix sum in f64 normalised to end at exactly 1, rounded to f32 (the CPU's
/// `DiscreteDistribution` keeps it in f64; f32 is all the GPU has).
fn cdf(weights: &[f32]) -> Vec<f32> {
    let total: f64 = weights.iter().map(|&w| w as f64).sum();
    let mut acc = 0.0f64;
    let mut out = vec![0.0f32];
    for &w in weights {
        acc += w as f64;
        out.push((acc / total) as f32);
    }
    out
}

/// The records of `scene`'s lights; polygon lights append their triangles to `vertex_data` (three
/// vec4 each, the first two w's holding the triangle's interval of the by-area CDF, the third its
/// area), an
/// environment map its sampling tables to `tables`. `emission[i]` is the texture id of the
/// scene's emission texture `i` (`textures::encode`), which textured area lights name.
pub(super) fn encode(
    scene: &Scene,
    vertex_data: &mut Vec<[f32; 4]>,
    tables: &mut Vec<f32>,
    emission: &[u32],
) -> Vec<GpuLight> {
    scene
        .lights
        .iter()
        .map(|l| {
            let z = [0.0; 4];
            // The infinite lights have no texture (and use h.w otherwise).
            let texture = match l.texture() {
                NONE => NONE,
                t => emission[t as usize],
            };
            let mut g = GpuLight {
                h: [LightTag::of(l).gpu_tag(), 0, 0, texture],
                a: z,
                b: z,
                c: z,
                d: z,
                le: z,
            };
            match l {
                Light::Triangle(t) => {
                    g.h[1] = t.attr;
                    g.a = v4(t.v[0], 0.0);
                    g.b = v4(t.v[1], 0.0);
                    g.c = v4(t.v[2], 0.0);
                    g.d = v4(t.n, 0.0);
                    g.le = v4(t.le, t.area);
                }
                Light::Polygon(p) => {
                    let areas: Vec<f32> = p
                        .triangles
                        .iter()
                        .map(crate::geometry::triangle::triangle_area)
                        .collect();
                    let c = cdf(&areas);
                    g.h[1] = (vertex_data.len() / 3) as u32;
                    g.h[2] = p.triangles.len() as u32;
                    for (i, t) in p.triangles.iter().enumerate() {
                        vertex_data.push(v4(t[0], c[i]));
                        vertex_data.push(v4(t[1], c[i + 1]));
                        vertex_data.push(v4(t[2], p.triangle_areas[i]));
                    }
                    g.a = v4(p.origin, 0.0);
                    g.b = v4(p.centroid, 0.0);
                    g.d = v4(p.n, 0.0);
                    g.le = v4(p.le, p.area);
                }
                Light::Quad(q) => {
                    g.h[1] = q.attr;
                    g.a = v4(q.corner, 0.0);
                    g.b = v4(q.edge_u, 0.0);
                    g.c = v4(q.edge_v, 0.0);
                    g.d = v4(q.n, 0.0);
                    g.le = v4(q.le, q.area);
                }
                Light::Disk(k) => {
                    g.a = v4(k.disk.center, k.disk.radius);
                    let [x, y] = k.disk.uv_axes();
                    g.b = v4(x, 0.0);
                    g.c = v4(y, 0.0);
                    g.d = v4(k.disk.n, 0.0);
                    g.le = v4(k.le, k.disk.area());
                }
                Light::Sphere(s) => {
                    g.a = v4(s.sphere.center, s.sphere.radius);
                    // The texture frame (`sphere_uv`).
                    let f = s.sphere.frame();
                    g.b = v4(f.s, 0.0);
                    g.c = v4(f.t, 0.0);
                    g.d = v4(f.n, 0.0);
                    g.le = v4(s.le, s.sphere.area());
                }
                Light::Background(b) => {
                    g.le = v4(b.le, 0.0);
                }
                Light::Envmap(e) => {
                    let (w, h) = e.size();
                    g.h[1] = w as u32;
                    g.h[2] = h as u32;
                    g.h[3] = super::envmap::append_tables(e, tables);
                    // The rotation's columns (`envmap_to_world`, `envmap_to_map`).
                    let r = e.to_world_matrix();
                    g.a = v4(r.x_axis, 0.0);
                    g.b = v4(r.y_axis, 0.0);
                    g.c = v4(r.z_axis, 0.0);
                }
                Light::Point(l) => {
                    g.a = v4(l.position, 0.0);
                    g.le = v4(l.intensity, 0.0);
                }
                Light::Spot(l) => {
                    g.a = v4(l.position, l.cutoff);
                    g.b = v4(l.frame.s, l.cos_cutoff);
                    g.c = v4(l.frame.t, l.cos_beam);
                    g.d = v4(l.frame.n, l.inv_transition);
                    g.le = v4(l.intensity, l.uv_factor);
                }
                Light::Directional(l) => {
                    g.a = v4(l.direction, 0.0);
                    g.le = v4(l.irradiance, 0.0);
                }
                Light::Projector(l) => {
                    g.a = v4(l.position, l.tan_half.x);
                    g.b = v4(l.frame.s, l.tan_half.y);
                    g.c = v4(l.frame.t, 0.0);
                    g.d = v4(l.frame.n, 0.0);
                    g.le = v4(l.intensity, 0.0);
                }
            }
            g
        })
        .collect()
}

/// Light selection: the CPU's power distribution, its CDF and pmf appended side by side to
/// `tables`; their offsets, or `NONE` when the scene has nothing to sample.
pub(super) fn selection(scene: &Scene, tables: &mut Vec<f32>) -> (u32, u32) {
    match &scene.light_sampler {
        Some(sampler) => {
            let powers: Vec<f32> = scene.lights.iter().map(|l| l.power().max(0.0)).collect();
            let c = cdf(&powers);
            let cdf_offset = tables.len() as u32;
            tables.extend_from_slice(&c);
            let pmf_offset = tables.len() as u32;
            tables.extend((0..scene.lights.len()).map(|i| sampler.pmf(i)));
            (cdf_offset, pmf_offset)
        }
        None => (NONE, NONE),
    }
}
