//! Edits of the scene description behind the sliders: a material's roughness, colour and IOR,
//! and a light's shape, size and radiance. The viewer rebuilds the scene from the edited
//! description, so the renderer needs no mutation API.

use super::light_shape::{Keep, LightShape, PlanarLight};
use glam::DVec3;
use lumis::scene::{FresnelDesc, GeometryDesc, MaterialDesc, SceneDesc};

/// GGX roughness α of a material, when it has one.
pub fn alpha(m: &MaterialDesc) -> Option<f64> {
    match m {
        MaterialDesc::Conductor { alpha, .. } | MaterialDesc::Plastic { alpha, .. } => Some(*alpha),
        MaterialDesc::Diffuse { .. } => None,
    }
}

/// Sets the GGX roughness α (ignored for diffuse materials).
pub fn set_alpha(m: &mut MaterialDesc, value: f64) {
    if let MaterialDesc::Conductor { alpha, .. } | MaterialDesc::Plastic { alpha, .. } = m {
        *alpha = value.clamp(0.0, 1.0);
    }
}

/// The material's colour: the albedo, or a conductor's reflectance tint. `None` for
/// conductors given by a complex index of refraction (their colour is physics, not a knob).
pub fn colour(m: &MaterialDesc) -> Option<DVec3> {
    match m {
        MaterialDesc::Diffuse { albedo } | MaterialDesc::Plastic { albedo, .. } => Some(*albedo),
        MaterialDesc::Conductor {
            fresnel: FresnelDesc::Reflectance(r),
            ..
        } => Some(*r),
        MaterialDesc::Conductor { .. } => None,
    }
}

/// Sets the colour (see [`colour`]), clamped to [0, 1] as the format requires.
pub fn set_colour(m: &mut MaterialDesc, value: DVec3) {
    let value = value.clamp(DVec3::ZERO, DVec3::ONE);
    match m {
        MaterialDesc::Diffuse { albedo } | MaterialDesc::Plastic { albedo, .. } => *albedo = value,
        MaterialDesc::Conductor {
            fresnel: FresnelDesc::Reflectance(r),
            ..
        } => *r = value,
        MaterialDesc::Conductor { .. } => {}
    }
}

/// The index of refraction of a plastic's coating.
pub fn ior(m: &MaterialDesc) -> Option<f64> {
    match m {
        MaterialDesc::Plastic { ior, .. } => Some(*ior),
        _ => None,
    }
}

/// Sets a plastic's IOR (kept above 1, as the format requires).
pub fn set_ior(m: &mut MaterialDesc, value: f64) {
    if let MaterialDesc::Plastic { ior, .. } = m {
        *ior = value.max(1.0001);
    }
}

/// The kind of emitter being edited.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightGeometry {
    /// Planar: can change shape.
    Planar(PlanarLight),
    /// A sphere light: size is its radius.
    Sphere {
        /// Centre.
        center: DVec3,
        /// Radius.
        radius: f64,
    },
    /// Boxes and meshes: only the radiance can change.
    Fixed,
}

/// The selected light's editable state. Kept while the light stays selected, so that repeated
/// reshaping never drifts (the geometry is always regenerated from this).
#[derive(Clone, Debug, PartialEq)]
pub struct LightEdit {
    /// Index of the shape in [`SceneDesc::shapes`].
    pub shape: usize,
    /// Its geometry, reduced to what the controls change.
    pub geometry: LightGeometry,
    /// Whether shape and size changes keep the area or the power.
    pub keep: Keep,
    /// Emission colour, largest component 1.
    pub colour: DVec3,
    /// Largest component of the emitted radiance.
    pub radiance: f64,
}

impl LightEdit {
    /// The editor for emitting shape `shape` of `desc`.
    pub fn new(desc: &SceneDesc, shape: usize) -> LightEdit {
        let s = &desc.shapes[shape];
        let geometry = match &s.geometry {
            GeometryDesc::Sphere { center, radius } => LightGeometry::Sphere {
                center: *center,
                radius: *radius,
            },
            g => PlanarLight::from_geometry(g).map_or(LightGeometry::Fixed, LightGeometry::Planar),
        };
        let radiance = s.emission.max_element();
        LightEdit {
            shape,
            geometry,
            keep: Keep::Area,
            colour: if radiance > 0.0 {
                s.emission / radiance
            } else {
                DVec3::ONE
            },
            radiance,
        }
    }

    /// Writes the geometry and emission into `desc`.
    pub fn apply(&self, desc: &mut SceneDesc) {
        let s = &mut desc.shapes[self.shape];
        match self.geometry {
            LightGeometry::Planar(p) => s.geometry = p.geometry(),
            LightGeometry::Sphere { center, radius } => {
                s.geometry = GeometryDesc::Sphere { center, radius }
            }
            LightGeometry::Fixed => {}
        }
        s.emission = self.colour * self.radiance;
    }

    /// The planar shape, if the light has one.
    pub fn planar_shape(&self) -> Option<LightShape> {
        match self.geometry {
            LightGeometry::Planar(p) => Some(p.shape),
            _ => None,
        }
    }

    /// Changes a planar light's shape (keeping area or power, see [`Keep`]).
    pub fn set_shape(&mut self, shape: LightShape) {
        if let LightGeometry::Planar(p) = self.geometry {
            let (p, scale) = p.reshaped(shape, self.keep);
            self.geometry = LightGeometry::Planar(p);
            self.radiance *= scale;
        }
    }

    /// The light's size: √area for planar lights, the radius for spheres.
    pub fn size(&self) -> Option<f64> {
        match self.geometry {
            LightGeometry::Planar(p) => Some(p.area.sqrt()),
            LightGeometry::Sphere { radius, .. } => Some(radius),
            LightGeometry::Fixed => None,
        }
    }

    /// Sets the size (see [`LightEdit::size`]); in [`Keep::Power`] mode the radiance follows
    /// so that the power stays the same (power ∝ area, and ∝ radius² for spheres).
    pub fn set_size(&mut self, size: f64) {
        let size = size.max(1e-6);
        let Some(old) = self.size() else { return };
        match &mut self.geometry {
            LightGeometry::Planar(p) => {
                let (q, _) = p.resized(size * size, self.keep);
                *p = q;
            }
            LightGeometry::Sphere { radius, .. } => *radius = size,
            LightGeometry::Fixed => return,
        }
        if self.keep == Keep::Power {
            self.radiance *= (old / size).powi(2);
        }
    }

    /// Emitted power of the largest channel: π·A·L for a one-sided planar emitter, 4π²r²·L for
    /// a sphere; `None` for boxes and meshes.
    pub fn power(&self) -> Option<f64> {
        use std::f64::consts::PI;
        match self.geometry {
            LightGeometry::Planar(p) => Some(PI * p.area * self.radiance),
            LightGeometry::Sphere { radius, .. } => {
                Some(4.0 * PI * PI * radius * radius * self.radiance)
            }
            LightGeometry::Fixed => None,
        }
    }
}
