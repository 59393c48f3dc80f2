//! How a model opened on its own is lit (`scene/model.rs`): the studio, and the rule that decides
//! whether the file's own emitters light it instead.
//!
//! **The studio** (on by default, `--no-studio` off): a grey ground plane just under the model's
//! bounding box and an environment map made here, a dim sky graded from horizon to zenith with
//! three soft round "softboxes", a key light above the camera's left, a fill on its right and a
//! rim light behind the model. A white model under a uniform white sky is white on white: only
//! its occlusion shows. Lights from a few directions shade each face by its orientation, the
//! rim light separates the silhouette from the background, and the ground's contact shadow
//! places the model. Neutral grey, so the model's own colours are what one sees.
//!
//! **The rule**: the environment (the studio's, or without the studio a white one of radiance
//! one) stays on unless the file's emitters carry most of the power, that is unless
//! `Φ_emitters > Φ_environment` with `Φ_emitters = π Σ area·Y(emission)` (each emitter's flux,
//! one-sided Lambertian, by luminance) plus its lights' flux ([`emitted_flux`]) and `Φ_environment = π·Ȳ·A`, the flux a uniform
//! environment of the map's mean luminance Ȳ sends into the surface `A` of the model's bounding
//! box. So a decorative emissive label (small, at most as bright as the sky) keeps the sky, and
//! a lamp or a lit room, whose light outweighs what the sky would pour onto the whole model, is
//! shown by its own light, without the sky (the studio's ground stays, lit by it).

use super::desc::{GeometryDesc, SceneDesc};
use crate::image_io::Image;
use glam::{DVec3, Vec3};
use serde_json::{Value, json};
use std::f32::consts::PI;

/// The studio map's size (equirectangular, as every environment map: row 0 the zenith).
pub const STUDIO_MAP_SIZE: (u32, u32) = (256, 128);
/// Albedo of the studio's ground: photography's 18% grey card, the middle of the tones a model
/// may have, so that a white model stands out against it and a black one does.
pub const GROUND_ALBEDO: f64 = 0.18;
/// Half the side of the ground square, in radii of the model's bounding sphere: far enough that
/// its edge stays within a tenth of a degree of the horizon seen from the automatic camera.
const GROUND_HALF_SIDE: f64 = 1000.0;
/// The gap between the model's lowest point and the ground, in radii: no coplanar faces.
const GROUND_GAP: f64 = 1e-3;

/// The sky's radiance at the horizon and at the zenith, and below the horizon.
const SKY_HORIZON: f32 = 0.12;
const SKY_ZENITH: f32 = 0.4;
const SKY_BELOW: f32 = 0.05;

/// A round area light of the studio map: its direction (towards the light; world frame, the
/// automatic camera looking along −z from +z, so +x is the image's right), angular radius and
/// radiance. Its edge fades over [`SOFTBOX_EDGE_DEG`].
struct Softbox {
    toward: [f32; 3],
    radius_deg: f32,
    radiance: f32,
}

/// The key (upper left, in front), the fill (right, low) and the rim (behind, above).
const SOFTBOXES: [Softbox; 3] = [
    Softbox {
        toward: [-0.5, 0.75, 0.45],
        radius_deg: 15.0,
        radiance: 6.0,
    },
    Softbox {
        toward: [0.8, 0.25, 0.55],
        radius_deg: 25.0,
        radiance: 0.8,
    },
    Softbox {
        toward: [0.2, 0.55, -0.8],
        radius_deg: 12.0,
        radiance: 4.0,
    },
];
/// Width of a softbox's soft edge, degrees.
const SOFTBOX_EDGE_DEG: f32 = 4.0;

/// The studio's radiance from direction `d` (unit).
fn studio_radiance(d: Vec3) -> f32 {
    let sky = if d.y >= 0.0 {
        SKY_HORIZON + (SKY_ZENITH - SKY_HORIZON) * d.y
    } else {
        SKY_BELOW
    };
    let boxes: f32 = SOFTBOXES
        .iter()
        .map(|b| {
            let angle = d
                .dot(Vec3::from(b.toward).normalize())
                .clamp(-1.0, 1.0)
                .acos()
                .to_degrees();
            let t = ((b.radius_deg + 0.5 * SOFTBOX_EDGE_DEG - angle) / SOFTBOX_EDGE_DEG)
                .clamp(0.0, 1.0);
            b.radiance * t * t * (3.0 - 2.0 * t)
        })
        .sum();
    sky + boxes
}

/// The studio's environment map, computed here (grey: r = g = b), each texel the radiance at its
/// centre's direction by the environment map's convention (`lights/envmap.rs`: `u = atan2(x,
/// −z)/2π` at column centres `(i + ½)/W`, `v = acos(y)/π` at rows `j/(H − 1)`).
pub fn studio_map() -> Image {
    let (w, h) = STUDIO_MAP_SIZE;
    let mut data = Vec::with_capacity((w * h) as usize);
    for j in 0..h {
        let theta = PI * j as f32 / (h - 1) as f32;
        for i in 0..w {
            let phi = 2.0 * PI * (i as f32 + 0.5) / w as f32;
            let d = Vec3::new(
                theta.sin() * phi.sin(),
                theta.cos(),
                -theta.sin() * phi.cos(),
            );
            data.push(Vec3::splat(studio_radiance(d)));
        }
    }
    Image {
        width: w,
        height: h,
        data,
    }
}

/// The mean luminance of an equirectangular map over the sphere (each row weighted by its solid
/// angle, sin θ).
pub fn mean_luminance(map: &Image) -> f64 {
    let (w, h) = (map.width as usize, map.height as usize);
    let (mut sum, mut weight) = (0.0f64, 0.0f64);
    for j in 0..h {
        let theta = std::f64::consts::PI * j as f64 / (h.max(2) - 1) as f64;
        let s = theta.sin();
        for t in &map.data[j * w..(j + 1) * w] {
            sum += s * luminance(t.as_dvec3());
            weight += s;
        }
    }
    if weight > 0.0 {
        sum / weight
    } else {
        map.data
            .iter()
            .map(|t| luminance(t.as_dvec3()))
            .sum::<f64>()
            / map.data.len() as f64
    }
}

/// Rec. 709 luminance.
fn luminance(c: DVec3) -> f64 {
    c.dot(DVec3::new(0.2126, 0.7152, 0.0722))
}

/// The studio's ground: a grey square (material `studio_ground`) just under the box `lo..hi`,
/// facing +y, centred under it.
pub fn ground(lo: DVec3, hi: DVec3) -> (Value, Value) {
    let radius = (0.5 * (hi - lo).length()).max(1e-6);
    let half = GROUND_HALF_SIDE * radius;
    let centre = 0.5 * (lo + hi);
    let y = lo.y - GROUND_GAP * radius;
    let shape = json!({
        "type": "quad",
        "corner": [centre.x - half, y, centre.z - half],
        "edge_u": [0.0, 0.0, 2.0 * half],
        "edge_v": [2.0 * half, 0.0, 0.0],
        "material": GROUND_MATERIAL,
    });
    let material =
        json!({"type": "diffuse", "albedo": [GROUND_ALBEDO, GROUND_ALBEDO, GROUND_ALBEDO]});
    (shape, material)
}

/// The name of the ground's material in the model's scene.
pub const GROUND_MATERIAL: &str = "studio_ground";

/// The flux of the scene's emitting shapes, `π Σ area·Y(emission)` (see the module doc), and
/// of its lights (a glTF file's `KHR_lights_punctual`): a point light's `4π·Y(I)`, a spot's
/// `Y(I)` times the solid angle of the cone halfway between its beam and its cutoff (lumis'
/// own power of a spot, `lights/spot.rs`), a directional light's `Y(E)` times the area of the
/// shadow the box `lo..hi` casts across it (what of its infinite flux reaches the model).
pub fn emitted_flux(desc: &SceneDesc, lo: DVec3, hi: DVec3) -> f64 {
    use super::desc::LightDesc;
    use std::f64::consts::PI;
    let e = (hi - lo).max(DVec3::ZERO);
    let lights: f64 = desc
        .lights
        .iter()
        .map(|l| match l {
            LightDesc::Point { intensity, .. } => 4.0 * PI * luminance(*intensity),
            LightDesc::Spot {
                intensity,
                cutoff_angle_deg,
                beam_width_deg,
                ..
            } => {
                let cos = |deg: f64| deg.to_radians().cos();
                let solid_angle =
                    2.0 * PI * (1.0 - 0.5 * (cos(*cutoff_angle_deg) + cos(*beam_width_deg)));
                solid_angle * luminance(*intensity)
            }
            LightDesc::Directional {
                direction,
                irradiance,
            } => {
                let d = direction.abs();
                let shadow = d.x * e.y * e.z + d.y * e.z * e.x + d.z * e.x * e.y;
                shadow * luminance(*irradiance)
            }
            // A model makes no projector.
            LightDesc::Projector { .. } => 0.0,
        })
        .sum();
    lights
        + desc
            .shapes
            .iter()
            .filter(|s| s.emission != DVec3::ZERO || s.emission_texture.is_some())
            .map(|s| {
                // A texture's emission is its mean over the uv square, or its maximum where that
                // mean is black (the scene description's rule for light selection).
                let y = match &s.emission_texture {
                    Some(t) if s.emission == DVec3::ZERO => luminance(t.texture.max().as_dvec3()),
                    _ => luminance(s.emission),
                };
                std::f64::consts::PI * area(&s.geometry) * y
            })
            .sum::<f64>()
}

/// The flux an environment of mean luminance `mean` sends into the box `lo..hi` (see the module
/// doc): `π · mean · surface area`.
pub fn environment_flux(mean: f64, lo: DVec3, hi: DVec3) -> f64 {
    let e = (hi - lo).max(DVec3::ZERO);
    std::f64::consts::PI * mean * 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
}

/// The surface area of a model's shape: its triangles, placed by `to_world` (a model's shapes are
/// meshes; anything else has none here).
fn area(g: &GeometryDesc) -> f64 {
    let GeometryDesc::Mesh { mesh, to_world, .. } = g else {
        return 0.0;
    };
    mesh.indices
        .iter()
        .map(|t| {
            let [a, b, c] =
                t.map(|i| to_world.transform_point3(mesh.positions[i as usize].as_dvec3()));
            0.5 * (b - a).cross(c - a).length()
        })
        .sum()
}

#[cfg(test)]
#[path = "model_studio_tests.rs"]
mod tests;
