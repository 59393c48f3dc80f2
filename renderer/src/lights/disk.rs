//! Emitting disks: area sampling by the concentric map, or uniform solid-angle sampling of the
//! spherical ellipse the disk subtends (Guillén et al. 2017, [`SphericalEllipse`]) where the
//! method asks for it and the ellipse suits the warp (its solid angle within
//! `[MIN_ELLIPSE_SOLID_ANGLE, MAX_ELLIPSE_SOLID_ANGLE]`; by area otherwise). `sample` and `pdf`
//! decide alike from the same receiver point. [`LightSampling::Adaptive`] samples by area where
//! the disk looks small, as it does for the other planar lights; the cosine warp has no corners
//! to weight here, so [`LightSampling::SolidAngleCosine`] samples the ellipse as `SolidAngle`
//! does.
//! WGSL twin: `lights/disk.wgsl`.

use super::{LightSample, LightSampling, area_sample, area_to_solid_angle};
use crate::geometry::disk::Disk;
use crate::geometry::ray::Ray;
use crate::math::Frame;
use crate::sampling::{SphericalEllipse, sample_uniform_disk_concentric};
use glam::{Vec2, Vec3};

/// A one-sided emitting disk.
#[derive(Clone, Debug)]
pub struct DiskLight {
    /// The disk; emits on the side of its normal.
    pub disk: Disk,
    frame: Frame,
    /// Emitted radiance (a textured light's selection radiance: see the module doc of
    /// [`super`]).
    pub le: Vec3,
    /// Emission texture ([`super::Light::texture`]).
    pub texture: u32,
}

impl DiskLight {
    /// A disk light.
    pub fn new(disk: Disk, le: Vec3) -> DiskLight {
        DiskLight {
            disk,
            frame: Frame::from_normal(disk.n),
            le,
            texture: crate::geometry::primitive::NONE,
        }
    }

    /// The spherical ellipse seen from `p`, where `method` samples by it
    /// ([`LightSampling::spherical_for`]) and it suits the warp.
    fn ellipse(&self, p: Vec3, method: LightSampling) -> Option<SphericalEllipse> {
        let d = &self.disk;
        if !method.spherical_for(p, d.center, d.n, d.area()) {
            return None;
        }
        SphericalEllipse::new(p, d.center, d.n, d.radius)
    }

    /// Samples a point as seen from `p`: uniformly by solid angle through the spherical ellipse
    /// where [`DiskLight::ellipse`] allows, uniformly by area otherwise.
    pub fn sample(&self, p: Vec3, u: Vec2, method: LightSampling) -> Option<LightSample> {
        let d = &self.disk;
        let height = (p - d.center).dot(d.n);
        if height <= 0.0 {
            return None;
        }
        if let Some(e) = self.ellipse(p, method) {
            let wi = e.sample(u);
            let cos = -wi.dot(d.n);
            // The cone lies in front of p; a direction at its rim may round to grazing.
            if cos.is_nan() || cos <= 0.0 {
                return None;
            }
            // Where wi meets the plane, projected onto it as a traced hit is (same error bound).
            let ray = Ray::new(p, wi);
            let (y, p_error) = d.surface_point(&ray, height / cos);
            return Some(LightSample {
                p: y,
                p_error,
                n: d.n,
                wi,
                pdf: e.pdf(),
                le: self.le,
                infinite: false,
                b: Vec2::ZERO,
            });
        }
        let q = sample_uniform_disk_concentric(u) * d.radius;
        let y = d.center + self.frame.s * q.x + self.frame.t * q.y;
        area_sample(p, y, d.n, 1.0 / d.area(), self.le)
    }

    /// Solid-angle pdf of hitting `y` (normal `ny`) from `p`.
    pub fn pdf(&self, p: Vec3, y: Vec3, ny: Vec3, method: LightSampling) -> f32 {
        match self.ellipse(p, method) {
            Some(e) => e.pdf(),
            None => area_to_solid_angle(1.0 / self.disk.area(), p, y, ny),
        }
    }
}
