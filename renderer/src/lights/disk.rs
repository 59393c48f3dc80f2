//! Emitting disks: area sampling by the concentric map. (No exact solid-angle warp for a disk
//! exists in closed form; the light-sampling method falls back to area here.)
//! WGSL twin: `disk_light.wgsl`.

use super::{LightSample, area_sample};
use crate::geometry::disk::Disk;
use crate::math::Frame;
use crate::sampling::sample_uniform_disk_concentric;
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

    /// Samples a point uniformly by area.
    pub fn sample(&self, p: Vec3, u: Vec2) -> Option<LightSample> {
        if (p - self.disk.center).dot(self.disk.n) <= 0.0 {
            return None;
        }
        let d = sample_uniform_disk_concentric(u) * self.disk.radius;
        let y = self.disk.center + self.frame.s * d.x + self.frame.t * d.y;
        area_sample(p, y, self.disk.n, 1.0 / self.disk.area(), self.le)
    }
}
