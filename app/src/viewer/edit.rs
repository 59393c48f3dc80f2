//! Edits of the scene description behind the sliders: a material's roughness, colour and IOR,
//! and a light's shape, size and radiance. The viewer rebuilds the scene from the edited
//! description, so the renderer needs no mutation API. Every edit keeps the description valid
//! for the scene format (what the parser accepts), since nothing re-parses it.

use super::light_shape::{Keep, LightShape, PlanarLight};
use glam::DVec3;
use lumis::materials::gltf_pbr::GltfParam;
use lumis::materials::principled::{PrincipledParam, mitsuba_eta};
use lumis::materials::principled_thin::ThinParam;
use lumis::scene::desc::Distribution;
use lumis::scene::{FresnelDesc, GeometryDesc, MaterialDesc, PlasticModel, SceneDesc};
use std::ops::RangeInclusive;

/// One-click IORs offered for a dielectric.
pub const DIELECTRIC_PRESETS: [(&str, f64); 3] =
    [("water", 1.33), ("glass", 1.5), ("diamond", 2.42)];

/// How close to 1 a dielectric's IOR may get: the format forbids exactly 1 (an interface that
/// does nothing), and a value within a rounding of 1 would become 1 in the renderer's f32.
pub const DIELECTRIC_IOR_GAP: f64 = 0.01;

/// Roughness α of a material, when it has one (α_u of an anisotropic one).
pub fn alpha(m: &MaterialDesc) -> Option<f64> {
    match m {
        MaterialDesc::Conductor { alpha, .. }
        | MaterialDesc::Plastic { alpha, .. }
        | MaterialDesc::Dielectric { alpha, .. } => Some(*alpha),
        // Its roughness is one of its own sliders ([`PRINCIPLED_SLIDERS`], [`THIN_SLIDERS`],
        // [`GLTF_SLIDERS`]).
        MaterialDesc::Diffuse { .. }
        | MaterialDesc::ThinDielectric { .. }
        | MaterialDesc::Principled(_)
        | MaterialDesc::PrincipledThin(_)
        | MaterialDesc::GltfPbr(_) => None,
    }
}

/// Sets the roughness α, clamped to [0, 1] (ignored for diffuse materials, and for a
/// non-finite value). An anisotropic material's α_u takes `value` and its α_v keeps the ratio
/// α_v/α_u (clamped too; from α_u = 0 the material becomes isotropic): one slider scales the
/// lobe without turning it.
pub fn set_alpha(m: &mut MaterialDesc, value: f64) {
    if !value.is_finite() {
        return;
    }
    let value = value.clamp(0.0, 1.0);
    match m {
        MaterialDesc::Conductor { alpha, alpha_v, .. }
        | MaterialDesc::Dielectric { alpha, alpha_v, .. } => {
            *alpha_v = match *alpha_v {
                Some(v) if *alpha > 0.0 => Some((v * value / *alpha).clamp(0.0, 1.0)),
                _ => None,
            }
            .filter(|&v| v != value);
            *alpha = value;
        }
        MaterialDesc::Plastic { alpha, .. } => *alpha = value,
        MaterialDesc::Diffuse { .. }
        | MaterialDesc::ThinDielectric { .. }
        | MaterialDesc::Principled(_)
        | MaterialDesc::PrincipledThin(_)
        | MaterialDesc::GltfPbr(_) => {}
    }
}

/// The range of the anisotropy slider, α_v/α_u: 1:10 to 10:1 (drawn logarithmically).
pub const ASPECT_RANGE: RangeInclusive<f64> = 0.1..=10.0;

/// The aspect α_v/α_u of a microfacet conductor's or dielectric's roughness (1: isotropic);
/// `None` for the others, and at α_u = 0, where it is not defined.
pub fn aspect(m: &MaterialDesc) -> Option<f64> {
    match m {
        MaterialDesc::Conductor { alpha, alpha_v, .. }
        | MaterialDesc::Dielectric { alpha, alpha_v, .. }
            if *alpha > 0.0 =>
        {
            Some(alpha_v.map_or(1.0, |v| v / alpha))
        }
        _ => None,
    }
}

/// Sets α_v = α_u · `ratio` (clamped to [`ASPECT_RANGE`] and α_v to [0, 1]; ignored where
/// [`aspect`] is `None` and for a non-finite ratio). A ratio of 1 is isotropic again.
pub fn set_aspect(m: &mut MaterialDesc, ratio: f64) {
    if !ratio.is_finite() || aspect(m).is_none() {
        return;
    }
    let ratio = ratio.clamp(*ASPECT_RANGE.start(), *ASPECT_RANGE.end());
    if let MaterialDesc::Conductor { alpha, alpha_v, .. }
    | MaterialDesc::Dielectric { alpha, alpha_v, .. } = m
    {
        let v = (*alpha * ratio).clamp(0.0, 1.0);
        *alpha_v = (v != *alpha).then_some(v);
    }
}

/// The microfacet distribution of a conductor, dielectric or Mitsuba-coupled plastic.
pub fn distribution(m: &MaterialDesc) -> Option<Distribution> {
    match m {
        MaterialDesc::Conductor { distribution, .. }
        | MaterialDesc::Dielectric { distribution, .. }
        | MaterialDesc::Plastic {
            model: PlasticModel::Mitsuba { distribution, .. },
            ..
        } => Some(*distribution),
        _ => None,
    }
}

/// Sets the microfacet distribution of a conductor, dielectric or Mitsuba-coupled plastic
/// (ignored for the others).
pub fn set_distribution(m: &mut MaterialDesc, d: Distribution) {
    if let MaterialDesc::Conductor { distribution, .. }
    | MaterialDesc::Dielectric { distribution, .. }
    | MaterialDesc::Plastic {
        model: PlasticModel::Mitsuba { distribution, .. },
        ..
    } = m
    {
        *distribution = d;
    }
}

/// A plastic's coupling of base and coat.
pub fn plastic_model(m: &MaterialDesc) -> Option<PlasticModel> {
    match m {
        MaterialDesc::Plastic { model, .. } => Some(*model),
        _ => None,
    }
}

/// Sets a plastic's coupling (ignored for the other materials).
pub fn set_plastic_model(m: &mut MaterialDesc, value: PlasticModel) {
    if let MaterialDesc::Plastic { model, .. } = m {
        *model = value;
    }
}

/// The material's colour: the albedo, a principled's (thin or not) base colour, or a conductor's reflectance
/// tint. `None` for
/// conductors given by a complex index of refraction (their colour is physics, not a knob).
pub fn colour(m: &MaterialDesc) -> Option<DVec3> {
    match m {
        MaterialDesc::Diffuse { albedo } | MaterialDesc::Plastic { albedo, .. } => Some(*albedo),
        MaterialDesc::Principled(p) => Some(p.base_color),
        MaterialDesc::PrincipledThin(p) => Some(p.base_color),
        MaterialDesc::GltfPbr(p) => Some(p.base_color),
        MaterialDesc::Conductor {
            fresnel: FresnelDesc::Reflectance(r),
            ..
        } => Some(*r),
        MaterialDesc::Conductor { .. }
        | MaterialDesc::Dielectric { .. }
        | MaterialDesc::ThinDielectric { .. } => None,
    }
}

/// Sets the colour (see [`colour`]), clamped to [0, 1] as the format requires.
pub fn set_colour(m: &mut MaterialDesc, value: DVec3) {
    let value = value.clamp(DVec3::ZERO, DVec3::ONE);
    match m {
        MaterialDesc::Diffuse { albedo } | MaterialDesc::Plastic { albedo, .. } => *albedo = value,
        MaterialDesc::Principled(p) => p.base_color = value,
        MaterialDesc::PrincipledThin(p) => p.base_color = value,
        MaterialDesc::GltfPbr(p) => p.base_color = value,
        MaterialDesc::Conductor {
            fresnel: FresnelDesc::Reflectance(r),
            ..
        } => *r = value,
        MaterialDesc::Conductor { .. }
        | MaterialDesc::Dielectric { .. }
        | MaterialDesc::ThinDielectric { .. } => {}
    }
}

/// The index of refraction of a plastic's coating, of a dielectric's inside or of a thin sheet.
pub fn ior(m: &MaterialDesc) -> Option<f64> {
    match m {
        MaterialDesc::Plastic { ior, .. }
        | MaterialDesc::Dielectric { ior, .. }
        | MaterialDesc::ThinDielectric { ior } => Some(*ior),
        MaterialDesc::GltfPbr(p) => Some(p.ior),
        _ => None,
    }
}

/// Sets the IOR, kept valid for the format: a plastic's above 1; a dielectric's in
/// [1/10, 10] (the format's upper bound, and its inverse) and never within
/// [`DIELECTRIC_IOR_GAP`] of 1 (snapped to 1 ± the gap, on the side it came from; exactly 1
/// goes up); a thin sheet's in [1/10, 10], 1 included (a sheet that lets everything through).
/// A non-finite value changes nothing.
pub fn set_ior(m: &mut MaterialDesc, value: f64) {
    if !value.is_finite() {
        return;
    }
    match m {
        MaterialDesc::Plastic { ior, .. } => *ior = value.max(1.0001),
        // Only its f0 depends on it: 1 (no reflection at normal incidence) is allowed.
        MaterialDesc::GltfPbr(p) => p.ior = value.max(1.0),
        MaterialDesc::Dielectric { ior, .. } => *ior = dielectric_ior(value),
        MaterialDesc::ThinDielectric { ior } => {
            let max = f64::from(lumis::materials::dielectric::MAX_IOR);
            *ior = value.clamp(1.0 / max, max);
        }
        _ => {}
    }
}

fn dielectric_ior(value: f64) -> f64 {
    let max = f64::from(lumis::materials::dielectric::MAX_IOR);
    let n = value.clamp(1.0 / max, max);
    if (n - 1.0).abs() >= DIELECTRIC_IOR_GAP {
        n
    } else if n < 1.0 {
        1.0 - DIELECTRIC_IOR_GAP
    } else {
        1.0 + DIELECTRIC_IOR_GAP
    }
}

/// The IOR slider's range: 1 to 3 (a dielectric's 1 is snapped away by [`set_ior`]; a
/// plastic's starts just above), widened to hold `current`, since a slider clamps the value
/// it shows and a loaded IOR outside the range would otherwise change on mere selection.
pub fn ior_slider_range(m: &MaterialDesc, current: f64) -> RangeInclusive<f64> {
    let lo: f64 = match m {
        MaterialDesc::Dielectric { .. }
        | MaterialDesc::ThinDielectric { .. }
        | MaterialDesc::GltfPbr(_) => 1.0,
        _ => 1.01,
    };
    lo.min(current)..=current.max(3.0)
}

/// The IOR presets of a material: [`DIELECTRIC_PRESETS`] for a dielectric or a thin sheet,
/// none otherwise.
pub fn ior_presets(m: &MaterialDesc) -> &'static [(&'static str, f64)] {
    match m {
        MaterialDesc::Dielectric { .. } | MaterialDesc::ThinDielectric { .. } => {
            &DIELECTRIC_PRESETS
        }
        _ => &[],
    }
}

/// A glTF material's scalars offered as sliders (beside its base colour and IOR): all of them.
pub const GLTF_SLIDERS: [GltfParam; 2] = GltfParam::ALL;

/// A glTF material's scalar `param`; `None` for other materials.
pub fn gltf_scalar(m: &MaterialDesc, param: GltfParam) -> Option<f64> {
    match m {
        MaterialDesc::GltfPbr(p) => Some(p.scalars[param as usize]),
        _ => None,
    }
}

/// Sets a glTF material's scalar `param`, clamped to [0, 1].
pub fn set_gltf_scalar(m: &mut MaterialDesc, param: GltfParam, value: f64) {
    if let MaterialDesc::GltfPbr(p) = m
        && value.is_finite()
    {
        p.scalars[param as usize] = value.clamp(0.0, 1.0);
    }
}

/// A principled's parameters offered as sliders (beside its base colour and [`specular`]).
pub const PRINCIPLED_SLIDERS: [PrincipledParam; 6] = [
    PrincipledParam::Roughness,
    PrincipledParam::Metallic,
    PrincipledParam::SpecTrans,
    PrincipledParam::Sheen,
    PrincipledParam::Clearcoat,
    PrincipledParam::ClearcoatGloss,
];

/// A principled's scalar `param`; `None` for other materials.
pub fn principled_scalar(m: &MaterialDesc, param: PrincipledParam) -> Option<f64> {
    match m {
        MaterialDesc::Principled(p) => Some(p.scalars[param as usize]),
        _ => None,
    }
}

/// Sets a principled's scalar `param`, clamped to [0, 1]. `spec_trans` also decides whether it
/// transmits, as the format's parser does (then η = 1 becomes Mitsuba's 1.001); the caller
/// drops `two_sided` of a material that now transmits.
pub fn set_principled_scalar(m: &mut MaterialDesc, param: PrincipledParam, value: f64) {
    let MaterialDesc::Principled(p) = m else {
        return;
    };
    if !value.is_finite() {
        return;
    }
    let value = value.clamp(0.0, 1.0);
    p.scalars[param as usize] = value;
    if param == PrincipledParam::SpecTrans {
        p.transmission = value != 0.0;
        if p.transmission && p.eta == 1.0 {
            p.eta = f64::from(mitsuba_eta(Some(1.0), None, true));
        }
    }
}

/// A thin principled's parameters offered as sliders (beside its base colour), each over its
/// [`thin_slider_range`].
pub const THIN_SLIDERS: [ThinParam; 5] = [
    ThinParam::Roughness,
    ThinParam::SpecTrans,
    ThinParam::DiffTrans,
    ThinParam::Sheen,
    ThinParam::Eta,
];

/// A thin principled slider's range: the parameter's own, η over the indices of real sheets
/// (1 to 3; the format allows (0, 10]).
pub fn thin_slider_range(param: ThinParam) -> RangeInclusive<f64> {
    match param {
        ThinParam::Eta => 1.0..=3.0,
        _ => {
            let (lo, hi) = param.range();
            f64::from(lo)..=f64::from(hi)
        }
    }
}

/// A thin principled's scalar `param`; `None` for other materials.
pub fn thin_scalar(m: &MaterialDesc, param: ThinParam) -> Option<f64> {
    match m {
        MaterialDesc::PrincipledThin(p) => Some(p.scalars[param as usize]),
        _ => None,
    }
}

/// Sets a thin principled's scalar `param`, clamped to its slider's range.
pub fn set_thin_scalar(m: &mut MaterialDesc, param: ThinParam, value: f64) {
    if let MaterialDesc::PrincipledThin(p) = m
        && value.is_finite()
    {
        let range = thin_slider_range(param);
        p.scalars[param as usize] = value.clamp(*range.start(), *range.end());
    }
}

/// A principled's `specular` (Burley's: its η's normal-incidence reflectance / 0.08), in
/// [0, 1] for η in [1, 1.79]; `None` for other materials.
pub fn specular(m: &MaterialDesc) -> Option<f64> {
    match m {
        MaterialDesc::Principled(p) => {
            let r = (p.eta - 1.0) / (p.eta + 1.0);
            Some((r * r / 0.08).min(1.0))
        }
        _ => None,
    }
}

/// Sets a principled's η from `specular` in [0, 1] (Mitsuba's rule, 1e-3 for 0 with
/// transmission).
pub fn set_specular(m: &mut MaterialDesc, value: f64) {
    if let MaterialDesc::Principled(p) = m
        && value.is_finite()
    {
        let s = value.clamp(0.0, 1.0) as f32;
        p.eta = f64::from(mitsuba_eta(None, Some(s), p.transmission));
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
            GeometryDesc::Sphere { center, radius, .. } => LightGeometry::Sphere {
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
            LightGeometry::Planar(p) => {
                // A disk that stays a disk keeps its texture frame.
                let kept = match s.geometry {
                    GeometryDesc::Disk { u_axis, .. } => u_axis,
                    _ => None,
                };
                s.geometry = p.geometry();
                if let GeometryDesc::Disk { u_axis, .. } = &mut s.geometry {
                    *u_axis = kept;
                }
            }
            // Its texture frame stays.
            LightGeometry::Sphere { center, radius } => {
                if let GeometryDesc::Sphere {
                    center: c,
                    radius: r,
                    ..
                } = &mut s.geometry
                {
                    (*c, *r) = (center, radius);
                }
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

#[cfg(test)]
mod tests {
    use super::*;
    use lumis::scene::{load_scene, parse_scene_value};

    trait WithIor {
        fn with_ior(self, ior: f64) -> Self;
    }

    impl WithIor for MaterialDesc {
        /// A dielectric with its `ior` replaced.
        fn with_ior(mut self, n: f64) -> MaterialDesc {
            if let MaterialDesc::Dielectric { ior, .. } = &mut self {
                *ior = n;
            }
            self
        }
    }

    /// Beckmann, not the default, so that the round trips below carry `distribution` too.
    fn glass(alpha: f64) -> MaterialDesc {
        MaterialDesc::Dielectric {
            ior: 1.5,
            alpha,
            alpha_v: None,
            distribution: Distribution::Beckmann,
        }
    }

    /// Writes `m` into a real scene and parses it back: the format's own check of the edit.
    fn reparsed(m: &MaterialDesc) -> Result<MaterialDesc, String> {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../assets/seed_cornell.json");
        let mut desc = load_scene(std::path::Path::new(path)).unwrap();
        desc.materials[0].material = m.clone();
        desc.materials[0].two_sided = false;
        let back = parse_scene_value(&desc.to_json()).map_err(|e| e.to_string())?;
        Ok(back.materials[0].material.clone())
    }

    /// Editing a light keeps what the controls do not change: a disk light's and a sphere
    /// light's texture frames (which a texture on their emission follows).
    #[test]
    fn light_edits_keep_texture_frames() {
        let json = serde_json::json!({
            "camera": {"from": [0, 1, -4], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40,
                       "width": 8, "height": 8},
            "shapes": [
                {"type": "disk", "center": [0, 2, 0], "normal": [0, -1, 0], "radius": 0.5,
                 "u_axis": [1, 0, 1], "emission": [4, 4, 4]},
                {"type": "sphere", "center": [1, 1, 0], "radius": 0.3, "pole": [1, 0, 0],
                 "u_axis": [0, 1, 0], "emission": [2, 2, 2]}
            ]
        });
        let mut desc = parse_scene_value(&json).unwrap();
        let before: Vec<GeometryDesc> = desc.shapes.iter().map(|s| s.geometry.clone()).collect();
        for shape in 0..2 {
            let mut edit = LightEdit::new(&desc, shape);
            edit.radiance *= 2.0;
            edit.apply(&mut desc);
        }
        for (s, g) in desc.shapes.iter().zip(&before) {
            assert_eq!(&s.geometry, g);
        }
        let doubled = [DVec3::splat(8.0), DVec3::splat(4.0)];
        assert!(
            desc.shapes
                .iter()
                .zip(doubled)
                .all(|(s, e)| s.emission == e)
        );
    }

    #[test]
    fn dielectric_ior_and_roughness_are_editable_with_presets() {
        let mut m = glass(0.0);
        assert_eq!(ior(&m), Some(1.5));
        assert_eq!(alpha(&m), Some(0.0));
        assert_eq!(colour(&m), None, "a dielectric has no colour knob");
        assert_eq!(ior_presets(&m), &DIELECTRIC_PRESETS);
        assert!(ior_presets(&MaterialDesc::Diffuse { albedo: DVec3::ONE }).is_empty());
        for (name, n) in DIELECTRIC_PRESETS {
            set_ior(&mut m, n);
            assert_eq!(m, glass(0.0).with_ior(n), "{name}");
            assert_eq!(reparsed(&m), Ok(m.clone()), "{name}");
        }
        set_ior(&mut m, 2.0);
        set_alpha(&mut m, 0.25);
        assert_eq!(m, glass(0.25).with_ior(2.0));
    }

    #[test]
    fn roughness_edits_keep_an_anisotropic_lobes_aspect() {
        let mut m = MaterialDesc::Conductor {
            alpha: 0.1,
            alpha_v: Some(0.4),
            distribution: Distribution::Beckmann,
            fresnel: lumis::scene::FresnelDesc::Reflectance(DVec3::ONE),
        };
        set_alpha(&mut m, 0.2);
        let MaterialDesc::Conductor { alpha, alpha_v, .. } = m.clone() else {
            unreachable!()
        };
        assert_eq!(alpha, 0.2);
        assert!((alpha_v.unwrap() - 0.8).abs() < 1e-12, "{alpha_v:?}");
        assert_eq!(reparsed(&m), Ok(m.clone()));
        // α_v is clamped to 1; α_u = 0 (a mirror) forgets the aspect.
        set_alpha(&mut m, 0.5);
        assert!(matches!(
            m,
            MaterialDesc::Conductor {
                alpha_v: Some(1.0),
                ..
            }
        ));
        set_alpha(&mut m, 0.0);
        set_alpha(&mut m, 0.3);
        assert!(matches!(m, MaterialDesc::Conductor { alpha_v: None, .. }));
    }

    #[test]
    fn aspect_and_distribution_edits() {
        let mut m = glass(0.2);
        assert_eq!(aspect(&m), Some(1.0));
        assert_eq!(distribution(&m), Some(Distribution::Beckmann));
        set_aspect(&mut m, 3.0);
        assert!(
            matches!(m, MaterialDesc::Dielectric { alpha_v: Some(v), .. } if (v - 0.6).abs() < 1e-12)
        );
        assert!((aspect(&m).unwrap() - 3.0).abs() < 1e-12);
        assert_eq!(reparsed(&m), Ok(m.clone()));
        // α_v is clamped to 1, the ratio to the slider's range; 1 is isotropic again.
        set_aspect(&mut m, 50.0);
        assert!(matches!(
            m,
            MaterialDesc::Dielectric {
                alpha_v: Some(1.0),
                ..
            }
        ));
        set_aspect(&mut m, 1.0);
        assert!(matches!(m, MaterialDesc::Dielectric { alpha_v: None, .. }));
        set_distribution(&mut m, Distribution::Ggx);
        assert_eq!(distribution(&m), Some(Distribution::Ggx));
        assert_eq!(reparsed(&m), Ok(m.clone()));
        // A mirror has no aspect; a diffuse or plastic material neither knob.
        assert_eq!(aspect(&glass(0.0)), None);
        let mut d = MaterialDesc::Diffuse { albedo: DVec3::ONE };
        set_aspect(&mut d, 2.0);
        set_distribution(&mut d, Distribution::Ggx);
        assert_eq!(d, MaterialDesc::Diffuse { albedo: DVec3::ONE });
        assert_eq!((aspect(&d), distribution(&d)), (None, None));
    }

    #[test]
    fn a_plastics_coupling_and_its_distribution_are_editable() {
        let mut p = MaterialDesc::Plastic {
            albedo: DVec3::splat(0.5),
            alpha: 0.2,
            ior: 1.5,
            specular: DVec3::ONE,
            model: PlasticModel::Lumis,
        };
        // lumis' coat is GGX only: no menu.
        assert_eq!(distribution(&p), None);
        set_distribution(&mut p, Distribution::Beckmann);
        assert_eq!(plastic_model(&p), Some(PlasticModel::Lumis));
        let mitsuba = PlasticModel::Mitsuba {
            distribution: Distribution::Ggx,
            nonlinear: true,
        };
        set_plastic_model(&mut p, mitsuba);
        assert_eq!(distribution(&p), Some(Distribution::Ggx));
        set_distribution(&mut p, Distribution::Beckmann);
        assert_eq!(
            plastic_model(&p),
            Some(PlasticModel::Mitsuba {
                distribution: Distribution::Beckmann,
                nonlinear: true
            })
        );
        assert_eq!(reparsed(&p), Ok(p.clone()));
        assert_eq!(plastic_model(&glass(0.1)), None);
    }

    #[test]
    fn no_edit_makes_an_invalid_dielectric() {
        let iors = [
            1.0,
            1.0 + 1e-12,
            1.0 - 1e-12,
            1.0 + f64::EPSILON,
            1.0000001, // 1 in f32
            0.999,
            1.009,
            0.0,
            -1.0,
            1e-300,
            9.99,
            10.0,
            10.5,
            1e300,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        let alphas = [-1.0, 0.0, 0.5, 1.0, 1.5, f64::NAN, f64::INFINITY];
        for start in [1.5, 0.75] {
            for &n in &iors {
                for &a in &alphas {
                    let mut m = MaterialDesc::Dielectric {
                        ior: start,
                        alpha: 0.3,
                        alpha_v: None,
                        distribution: Distribution::Ggx,
                    };
                    set_ior(&mut m, n);
                    set_alpha(&mut m, a);
                    let MaterialDesc::Dielectric { ior, alpha, .. } = m else {
                        unreachable!()
                    };
                    assert!(ior != 1.0 && ior as f32 != 1.0, "ior {n} → {ior}");
                    assert!((1.0 - ior).abs() >= DIELECTRIC_IOR_GAP, "ior {n} → {ior}");
                    assert!((0.0..=1.0).contains(&alpha), "alpha {a} → {alpha}");
                    assert_eq!(reparsed(&m), Ok(m.clone()), "ior {n}, alpha {a}");
                }
            }
        }
        // Near 1 the IOR is pushed out on the side it came from; exactly 1 goes up.
        let snapped = |n| {
            let mut m = glass(0.0);
            set_ior(&mut m, n);
            ior(&m).unwrap()
        };
        assert_eq!(snapped(1.0), 1.0 + DIELECTRIC_IOR_GAP);
        assert_eq!(snapped(0.995), 1.0 - DIELECTRIC_IOR_GAP);
        assert_eq!(snapped(1.2), 1.2);
        assert_eq!(snapped(0.8), 0.8, "an inverted interface stays legal");
        assert_eq!(snapped(f64::NAN), 1.5, "a non-finite value changes nothing");
    }

    #[test]
    fn the_ior_slider_shows_a_loaded_value_without_clamping_it() {
        let d = glass(0.0);
        assert_eq!(ior_slider_range(&d, 1.5), 1.0..=3.0);
        assert_eq!(ior_slider_range(&d, 0.75), 0.75..=3.0);
        assert_eq!(ior_slider_range(&d, 4.0), 1.0..=4.0);
        let p = MaterialDesc::Plastic {
            albedo: DVec3::ONE,
            alpha: 0.1,
            ior: 1.5,
            specular: DVec3::ONE,
            model: Default::default(),
        };
        assert_eq!(ior_slider_range(&p, 1.5), 1.01..=3.0);
    }
}
