//! Adapter: sampling one light of a scene from a point, with the pdf of any direction found by
//! tracing it to the light (as the integrator's MIS does with BSDF-sampled directions).

use super::domain::Domain;
use super::sampler::{DirectionSample, DirectionalSampler};
use crate::geometry::ray::Ray;
use crate::lights::{Light, LightSampling};
use crate::math::Frame;
use crate::scene::Scene;
use glam::{Vec2, Vec3};
use std::sync::Arc;

/// Points on a disk's rim used to bound the cone it subtends.
const DISK_RIM_POINTS: usize = 64;
/// The cap is this much wider than the light's bounding cone, so silhouettes fall inside it.
const CAP_MARGIN: f64 = 1.15;

/// `scene.lights[light].sample(p, ns, ·, method)` as a direction sampler.
#[derive(Clone)]
pub struct LightDirections {
    /// The scene holding the light (ideally nothing else, so no other surface hides it).
    pub scene: Arc<Scene>,
    /// Index of the light in `scene.lights`.
    pub light: usize,
    /// The reference point.
    pub p: Vec3,
    /// Area or solid-angle sampling.
    pub method: LightSampling,
    /// The receiver's shading normal (zero: none), for [`LightSampling::SolidAngleCosine`] and
    /// [`LightSampling::ProjectedSolidAngle`].
    pub ns: Vec3,
}

impl LightDirections {
    /// Points whose directions from `p` bound the light's solid angle (its outline), or for a
    /// sphere its centre and radius.
    fn outline(&self) -> Result<Vec<Vec3>, (Vec3, f32)> {
        match &self.scene.lights[self.light] {
            Light::Triangle(l) => Ok(l.v.to_vec()),
            Light::Polygon(l) => Ok(l.vertices.clone()),
            Light::Quad(l) => Ok(vec![
                l.corner,
                l.corner + l.edge_u,
                l.corner + l.edge_v,
                l.corner + l.edge_u + l.edge_v,
            ]),
            Light::Disk(l) => {
                let f = Frame::from_normal(l.disk.n);
                Ok((0..DISK_RIM_POINTS)
                    .map(|i| {
                        let phi = std::f32::consts::TAU * i as f32 / DISK_RIM_POINTS as f32;
                        l.disk.center + l.disk.radius * (f.s * phi.cos() + f.t * phi.sin())
                    })
                    .collect())
            }
            Light::Sphere(l) => Err((l.sphere.center, l.sphere.radius)),
            Light::Background(_) | Light::Envmap(_) => Ok(Vec::new()),
            // A delta light has no density to test: its "sample" is one direction, pdf 1.
            Light::Point(_) | Light::Spot(_) | Light::Directional(_) | Light::Projector(_) => {
                Ok(Vec::new())
            }
        }
    }
}

impl DirectionalSampler for LightDirections {
    fn sample(&self, _u1: f32, u: Vec2) -> Option<DirectionSample> {
        let s = self.scene.lights[self.light].sample(self.p, self.ns, u, self.method)?;
        Some(DirectionSample {
            w: s.wi,
            pdf: s.pdf,
            delta: false,
        })
    }

    fn pdf(&self, w: Vec3) -> f32 {
        let light = &self.scene.lights[self.light];
        if light.is_infinite() {
            return light.pdf(self.p, self.ns, w, Vec3::ZERO, Vec3::ZERO, self.method);
        }
        let Some(hit) = self.scene.accel.intersect(&Ray::new(self.p, w)) else {
            return 0.0;
        };
        if self.scene.accel.primitives()[hit.prim as usize].light != self.light as u32 {
            return 0.0;
        }
        light.pdf(self.p, self.ns, w, hit.p, hit.n, self.method)
    }

    /// A cap about the light's bounding cone from `p`: a far light covers thousands of cells
    /// instead of one.
    fn domain(&self) -> Domain {
        let p = self.p.as_dvec3();
        match self.outline() {
            Err((c, r)) => {
                let d = c.as_dvec3() - p;
                let sin = (r as f64 / d.length()).min(1.0);
                Domain::cap(d.as_vec3(), CAP_MARGIN * sin.asin())
            }
            Ok(points) if !points.is_empty() => {
                let dirs: Vec<_> = points
                    .iter()
                    .map(|q| (q.as_dvec3() - p).normalize())
                    .collect();
                let axis = dirs.iter().sum::<glam::DVec3>().normalize();
                let theta = dirs
                    .iter()
                    .map(|d| d.dot(axis).clamp(-1.0, 1.0).acos())
                    .fold(0.0, f64::max);
                Domain::cap(axis.as_vec3(), CAP_MARGIN * theta)
            }
            Ok(_) => Domain::sphere(),
        }
    }
}
