//! The environment map: radiance from a latitude-longitude RGB image for every direction that
//! hits nothing, exactly as Mitsuba 3.9.1's `envmap` looks it up (scene format Version 2), and
//! importance-sampled.
//!
//! Lookup: a world direction `d` is taken to the map's frame by the inverse of the map's rotation
//! (`to_world`, any proper rotation: Mitsuba's `to_world`, or lumis' `rotate_y_deg`), mapped to
//! `u = atan2(x, −z) / 2π` (wrapped into [0, 1)) and `v = acos(y) / π`, and the image is
//! interpolated bilinearly at column `u·W − 0.5` (periodic) and row `v·(H − 1)` (row 0's centre at
//! the zenith, row H−1's at the nadir, clamped).
//!
//! Sampling: the sphere is cut into the cells of that interpolation, between neighbouring columns
//! (periodic) and neighbouring rows (one band for a single-row map). A cell's weight is the mean
//! luminance of its four corner texels, the exact mean of the bilinear interpolant over the cell,
//! times its solid angle, so any cell whose radiance is not zero everywhere can be sampled; within
//! a cell the direction is uniform in solid angle (uniform in φ and in cos θ). The density is then
//! constant on each cell, with no singularity at the poles, and a constant map is sampled
//! uniformly. The alternative method, [`LightSampling::Area`], samples the whole sphere uniformly.
//! WGSL twin: `lights/envmap.wgsl`.

use super::{LightSample, LightSampling};
use crate::sampling::{Piecewise2D, sample_uniform_sphere, uniform_sphere_pdf};
use glam::{DMat3, Mat3, Vec2, Vec3};
use std::f32::consts::{PI, TAU};

/// An environment map light.
#[derive(Clone, Debug)]
pub struct EnvmapLight {
    width: usize,
    height: usize,
    /// Radiance (times the scene's `scale`), row-major, row 0 at the zenith.
    texels: Vec<Vec3>,
    /// The rotation from the map's frame to the world (a proper rotation).
    to_world: Mat3,
    /// Its inverse, the transpose, kept so both directions are one product each.
    to_map: Mat3,
    /// Cells: `width` columns × `bands()` rows, weights as in the module comment.
    cells: Piecewise2D,
    /// cos θ at the band edges, `bands() + 1` entries from +1 (zenith) down to −1.
    band_cos: Vec<f32>,
    /// ∫ luminance dω over the sphere.
    luminance_integral: f32,
    /// Radius of a sphere bounding the scene (for its power).
    pub scene_radius: f32,
}

impl EnvmapLight {
    /// The rotation from the map's frame to the world: `rotation` (a proper rotation; the identity
    /// if `None`), then `rotate_y_deg` about +y.
    pub fn rotation_matrix(rotate_y_deg: f32, rotation: Option<DMat3>) -> Mat3 {
        match rotation {
            None => {
                let (s, c) = rotate_y_deg.to_radians().sin_cos();
                Mat3::from_cols(Vec3::new(c, 0.0, -s), Vec3::Y, Vec3::new(s, 0.0, c))
            }
            Some(r) => (DMat3::from_rotation_y((rotate_y_deg as f64).to_radians()) * r).as_mat3(),
        }
    }

    /// The map of `width × height` texels (row 0 at the zenith; finite, non-negative) scaled by
    /// `scale`, turned by `to_world` (a proper rotation, [`EnvmapLight::rotation_matrix`]).
    /// `None` if it emits nothing.
    pub fn new(
        width: usize,
        height: usize,
        texels: &[Vec3],
        scale: f32,
        to_world: Mat3,
        scene_radius: f32,
    ) -> Option<EnvmapLight> {
        assert_eq!(texels.len(), width * height, "texel count");
        let texels: Vec<Vec3> = texels.iter().map(|&t| t * scale).collect();
        let bands = height.saturating_sub(1).max(1);
        // Band j spans θ from π·j/bands to π·(j+1)/bands; its edges' cosines, computed once so
        // that sampling and the pdf agree on them exactly.
        let band_cos: Vec<f32> = (0..=bands)
            .map(|j| match j {
                0 => 1.0,
                j if j == bands => -1.0,
                j => (PI * j as f32 / bands as f32).cos(),
            })
            .collect();
        let lum = |x: usize, y: usize| crate::math::luminance(texels[y * width + x]);
        let mut weights = Vec::with_capacity(width * bands);
        let mut luminance_integral = 0.0f64;
        for j in 0..bands {
            let (y0, y1) = (j.min(height - 1), (j + 1).min(height - 1));
            let cell_solid_angle = TAU / width as f32 * (band_cos[j] - band_cos[j + 1]);
            for i in 0..width {
                let i1 = (i + 1) % width;
                let mean = 0.25 * (lum(i, y0) + lum(i1, y0) + lum(i, y1) + lum(i1, y1));
                let w = mean * cell_solid_angle;
                weights.push(w);
                luminance_integral += w as f64;
            }
        }
        let cells = Piecewise2D::new(&weights, width, bands)?;
        Some(EnvmapLight {
            width,
            height,
            texels,
            to_world,
            to_map: to_world.transpose(),
            cells,
            band_cos,
            luminance_integral: luminance_integral as f32,
            scene_radius,
        })
    }

    /// Number of bands of rows the sampling cells form (`height − 1`, or 1 for one row).
    fn bands(&self) -> usize {
        self.band_cos.len() - 1
    }

    /// World direction → the map's frame (the inverse rotation).
    fn to_map(&self, d: Vec3) -> Vec3 {
        self.to_map * d
    }

    /// The map's frame → world.
    fn to_world(&self, d: Vec3) -> Vec3 {
        self.to_world * d
    }

    /// `(u, v)` of a direction in the map's frame (not necessarily unit).
    fn uv(d: Vec3) -> Vec2 {
        let d = d.normalize();
        let mut u = d.x.atan2(-d.z) / TAU;
        if u < 0.0 {
            u += 1.0;
        }
        // u = 1 can come out of rounding just below 0.
        if u >= 1.0 {
            u = 0.0;
        }
        Vec2::new(u, d.y.clamp(-1.0, 1.0).acos() / PI)
    }

    /// Radiance arriving along `-d`, i.e. seen when looking in world direction `d`.
    pub fn eval(&self, d: Vec3) -> Vec3 {
        self.lookup(Self::uv(self.to_map(d)))
    }

    /// Bilinear lookup at `(u, v)`, Mitsuba's pixel-centre conventions (module comment).
    pub fn lookup(&self, uv: Vec2) -> Vec3 {
        let (w, h) = (self.width, self.height);
        let x = uv.x * w as f32 - 0.5;
        let x0 = x.floor();
        let fx = x - x0;
        let i0 = (x0 as i64).rem_euclid(w as i64) as usize;
        let i1 = (i0 + 1) % w;
        let y = (uv.y * (h - 1) as f32).clamp(0.0, (h - 1) as f32);
        let j0 = (y.floor() as usize).min(h - 1);
        let j1 = (j0 + 1).min(h - 1);
        let fy = y - j0 as f32;
        let t = |i: usize, j: usize| self.texels[j * w + i];
        let top = t(i0, j0) * (1.0 - fx) + t(i1, j0) * fx;
        let bottom = t(i0, j1) * (1.0 - fx) + t(i1, j1) * fx;
        top * (1.0 - fy) + bottom * fy
    }

    /// The sampling cell's coordinates in `[0,1)²` of a direction in the map's frame: x along the
    /// cells' columns (shifted half a texel from u), y along the bands, linear in cos θ inside a
    /// band. Also the band index.
    fn cell_point(&self, d: Vec3) -> (Vec2, usize) {
        let uv = Self::uv(d);
        let z = d.normalize().y.clamp(-1.0, 1.0);
        let mut x = uv.x - 0.5 / self.width as f32;
        if x < 0.0 {
            x += 1.0;
        }
        let bands = self.bands();
        let band = ((uv.y * bands as f32) as usize).min(bands - 1);
        let (c0, c1) = (self.band_cos[band], self.band_cos[band + 1]);
        let f = ((c0 - z) / (c0 - c1)).clamp(0.0, 1.0);
        (
            Vec2::new(
                x.min(crate::sampling::ONE_MINUS_EPSILON),
                (band as f32 + f) / bands as f32,
            ),
            band,
        )
    }

    /// Importance sampling: a world direction and its solid-angle pdf.
    pub fn sample_importance(&self, u: Vec2) -> (Vec3, f32) {
        let (p, [_, band], pdf_square) = self.cells.sample(u);
        let bands = self.bands();
        let (c0, c1) = (self.band_cos[band], self.band_cos[band + 1]);
        let f = p.y * bands as f32 - band as f32;
        let z = (c0 + f * (c1 - c0)).clamp(-1.0, 1.0);
        let u_map = p.x + 0.5 / self.width as f32;
        let phi = TAU * u_map;
        let r = (1.0 - z * z).max(0.0).sqrt();
        // u = atan2(x, −z)/2π: φ = 0 looks along −z, φ = π/2 along +x.
        let local = Vec3::new(r * phi.sin(), z, -r * phi.cos());
        (
            self.to_world(local),
            self.pdf_square_to_solid_angle(pdf_square, band),
        )
    }

    /// Solid-angle pdf of [`EnvmapLight::sample_importance`] for world direction `d`.
    pub fn pdf_importance(&self, d: Vec3) -> f32 {
        let (p, band) = self.cell_point(self.to_map(d));
        let pdf_square = self.cells.pdf_cell(self.cells.cell(p));
        self.pdf_square_to_solid_angle(pdf_square, band)
    }

    /// The `u` that [`EnvmapLight::sample_importance`] maps to world direction `d`, if its cell
    /// can be sampled (the inverse twin).
    pub fn invert_importance(&self, d: Vec3) -> Option<Vec2> {
        self.cells.invert(self.cell_point(self.to_map(d)).0)
    }

    /// Area on the cell square → solid angle: dω = dφ d(cos θ), φ = 2π·x and cos θ linear in y
    /// with slope `bands · Δcos θ` inside band `band`.
    fn pdf_square_to_solid_angle(&self, pdf_square: f32, band: usize) -> f32 {
        let dcos = self.band_cos[band] - self.band_cos[band + 1];
        pdf_square / (TAU * self.bands() as f32 * dcos)
    }

    /// Samples a direction towards the map: importance-sampled ([`LightSampling::SolidAngle`]) or
    /// uniform on the sphere ([`LightSampling::Area`], the sphere at infinity's area measure).
    pub fn sample(&self, u: Vec2, method: LightSampling) -> Option<LightSample> {
        let (wi, pdf) = if method.solid_angle() {
            self.sample_importance(u)
        } else {
            (sample_uniform_sphere(u), uniform_sphere_pdf())
        };
        Some(LightSample {
            p: wi,
            p_error: Vec3::ZERO,
            n: -wi,
            wi,
            pdf,
            le: self.eval(wi),
            infinite: true,
            b: Vec2::ZERO,
        })
    }

    /// Solid-angle pdf with which [`EnvmapLight::sample`] yields world direction `d`. Uniform
    /// sampling's samples where the map is black are discarded (a light returns no sample where
    /// it contributes nothing), so its pdf is 0 there.
    pub fn pdf(&self, d: Vec3, method: LightSampling) -> f32 {
        if method.solid_angle() {
            self.pdf_importance(d)
        } else if self.eval(d) == Vec3::ZERO {
            0.0
        } else {
            uniform_sphere_pdf()
        }
    }

    /// Power through a disk of the scene's radius, from all directions (pbrt-v4's
    /// `ImageInfiniteLight::Phi`): π r² ∫ L dω, which for a constant map is the constant
    /// background's 4π² r² L.
    pub fn power(&self) -> f32 {
        PI * self.scene_radius * self.scene_radius * self.luminance_integral
    }

    /// Width and height in texels.
    pub fn size(&self) -> (usize, usize) {
        (self.width, self.height)
    }

    /// The texels (times `scale`), row-major, row 0 at the zenith: the GPU's texture.
    pub(crate) fn texels(&self) -> &[Vec3] {
        &self.texels
    }

    /// The rotation from the map's frame to the world, for the GPU's record.
    pub(crate) fn to_world_matrix(&self) -> Mat3 {
        self.to_world
    }

    /// cos θ at the band edges, for the GPU's tables (so both sides cut the same bands).
    pub(crate) fn band_cos(&self) -> &[f32] {
        &self.band_cos
    }

    /// The sampling cells' distribution, for the GPU's tables.
    pub(crate) fn cells(&self) -> &Piecewise2D {
        &self.cells
    }
}

#[cfg(test)]
#[path = "envmap_tests.rs"]
mod tests;
