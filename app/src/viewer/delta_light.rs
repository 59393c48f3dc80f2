//! The delta lights' controls: the scene's `lights` (point, spot, directional, projector), one
//! picked from a list, and its strength and colour, position and aim (a directional light's
//! direction), a spot's cone and a projector's field of view and scale. Edits go into the scene
//! description, which is then rebuilt; every edit keeps the light valid for the scene format
//! (`renderer/src/scene/parse_lights.rs`), since nothing re-parses it.

use super::app::ViewerApp;
use super::controls::combo;
use glam::DVec3;
use lumis::scene::desc::{LightDesc, LookAt};
use lumis::scene::parse::MAX_RADIANCE;
use std::ops::RangeInclusive;

/// Largest coordinate a light's position may have (the supported scene size).
const MAX_COORD: f64 = lumis::scene::build::MAX_SCENE_SIZE as f64;
/// Smallest cone and field-of-view angle the sliders reach (degrees; the format's bounds are open).
const MIN_ANGLE: f64 = 0.1;
/// The largest cutoff of a textured spot (the format wants it below 90°), and the largest field
/// of view of a projector (below 180°).
const TEXTURED_MAX_CUTOFF: f64 = 89.9;
const MAX_FOV: f64 = 179.9;
/// The strength and scale sliders' usual range (logarithmic), widened to hold the current value.
const STRENGTH_RANGE: RangeInclusive<f64> = 1e-3..=1e5;

/// The light's type in the scene format.
pub fn kind(l: &LightDesc) -> &'static str {
    match l {
        LightDesc::Point { .. } => "point",
        LightDesc::Spot { .. } => "spot",
        LightDesc::Directional { .. } => "directional",
        LightDesc::Projector { .. } => "projector",
    }
}

/// What the strength slider and the colour edit: a point's or spot's intensity, a directional
/// light's or untextured projector's irradiance; `None` for a textured projector (its texture
/// holds the colour; its `scale` the strength).
pub fn emission(l: &LightDesc) -> Option<DVec3> {
    match l {
        LightDesc::Point { intensity, .. } | LightDesc::Spot { intensity, .. } => Some(*intensity),
        LightDesc::Directional { irradiance, .. } => Some(*irradiance),
        LightDesc::Projector {
            irradiance,
            texture: None,
            ..
        } => Some(*irradiance),
        LightDesc::Projector { .. } => None,
    }
}

fn emission_mut(l: &mut LightDesc) -> Option<&mut DVec3> {
    match l {
        LightDesc::Point { intensity, .. } | LightDesc::Spot { intensity, .. } => Some(intensity),
        LightDesc::Directional { irradiance, .. } => Some(irradiance),
        LightDesc::Projector {
            irradiance,
            texture: None,
            ..
        } => Some(irradiance),
        LightDesc::Projector { .. } => None,
    }
}

/// Sets the strength (the largest channel of [`emission`]) to `value`, clamped to
/// [0, 1e30], keeping the colour (white for a black light). A non-finite value changes nothing.
pub fn set_strength(l: &mut LightDesc, value: f64) {
    let Some(e) = emission_mut(l).filter(|_| value.is_finite()) else {
        return;
    };
    let value = value.clamp(0.0, MAX_RADIANCE);
    let colour = if e.max_element() > 0.0 {
        *e / e.max_element()
    } else {
        DVec3::ONE
    };
    *e = (colour * value).min(DVec3::splat(MAX_RADIANCE));
}

/// Sets the colour (each channel in [0, 1], rescaled so that its largest is 1), keeping the
/// strength; a black or non-finite colour changes nothing.
pub fn set_colour(l: &mut LightDesc, colour: DVec3) {
    let Some(e) = emission_mut(l) else { return };
    let c = colour.clamp(DVec3::ZERO, DVec3::ONE);
    if c.is_finite() && c.max_element() > 0.0 {
        *e = c / c.max_element() * e.max_element();
    }
}

/// Where the light is: a point's position, a spot's or projector's `from`; `None` for a
/// directional light.
pub fn position(l: &LightDesc) -> Option<DVec3> {
    match l {
        LightDesc::Point { position, .. } => Some(*position),
        LightDesc::Spot { frame, .. } | LightDesc::Projector { frame, .. } => Some(frame.from),
        LightDesc::Directional { .. } => None,
    }
}

/// Moves the light to `p` (clamped to the supported scene size). A spot or projector keeps
/// aiming at its `to`; a move onto `to` is refused (the axis would be undefined).
pub fn set_position(l: &mut LightDesc, p: DVec3) {
    let p = p.clamp(DVec3::splat(-MAX_COORD), DVec3::splat(MAX_COORD));
    match l {
        LightDesc::Point { position, .. } => *position = p,
        LightDesc::Spot { frame, .. } | LightDesc::Projector { frame, .. } => {
            if let Some(f) = look_at(p, frame.to, frame.up) {
                *frame = f;
            }
        }
        LightDesc::Directional { .. } => {}
    }
}

/// The point a spot or projector aims at (`to`).
pub fn target(l: &LightDesc) -> Option<DVec3> {
    match l {
        LightDesc::Spot { frame, .. } | LightDesc::Projector { frame, .. } => Some(frame.to),
        _ => None,
    }
}

/// Aims a spot or projector at `t` (clamped to the supported scene size); aiming at its own
/// position is refused.
pub fn set_target(l: &mut LightDesc, t: DVec3) {
    let t = t.clamp(DVec3::splat(-MAX_COORD), DVec3::splat(MAX_COORD));
    if let LightDesc::Spot { frame, .. } | LightDesc::Projector { frame, .. } = l
        && let Some(f) = look_at(frame.from, t, frame.up)
    {
        *frame = f;
    }
}

/// The frame `from` → `to` as the format accepts it (`parse_lights.rs`'s checks): `None` where
/// the axis is undefined; an `up` parallel to the new axis is replaced by a perpendicular one.
fn look_at(from: DVec3, to: DVec3, up: DVec3) -> Option<LookAt> {
    let axis = to - from;
    let scale = from.abs().max(to.abs()).max_element();
    if !axis.is_finite() || axis == DVec3::ZERO || axis.length() <= 1e-12 * scale {
        return None;
    }
    let axis = axis.normalize();
    let up = if up == DVec3::ZERO || axis.cross(up.normalize()).length() < 1e-6 {
        axis.any_orthonormal_vector()
    } else {
        up
    };
    Some(LookAt { from, to, up })
}

/// A directional light's direction as (azimuth about +y from +z, elevation above the xz plane),
/// in degrees.
pub fn direction_angles(l: &LightDesc) -> Option<(f64, f64)> {
    match l {
        LightDesc::Directional { direction: d, .. } => Some((
            d.x.atan2(d.z).to_degrees(),
            d.y.clamp(-1.0, 1.0).asin().to_degrees(),
        )),
        _ => None,
    }
}

/// Sets a directional light's direction from its azimuth and elevation (degrees).
pub fn set_direction_angles(l: &mut LightDesc, azimuth: f64, elevation: f64) {
    if let LightDesc::Directional { direction, .. } = l
        && azimuth.is_finite()
        && elevation.is_finite()
    {
        let (az, el) = (
            azimuth.to_radians(),
            elevation.clamp(-90.0, 90.0).to_radians(),
        );
        *direction = DVec3::new(el.cos() * az.sin(), el.sin(), el.cos() * az.cos()).normalize();
    }
}

/// The cutoff slider's range: (0, 180], below 90 for a textured spot, widened to hold `current`.
fn cutoff_range(textured: bool, current: f64) -> RangeInclusive<f64> {
    let hi = if textured { TEXTURED_MAX_CUTOFF } else { 180.0 };
    MIN_ANGLE.min(current)..=hi.max(current)
}

/// Sets a spot's cutoff angle (degrees): in (0, 180], below 90 with a texture; the beam width
/// shrinks with it where it would exceed it.
pub fn set_cutoff(l: &mut LightDesc, deg: f64) {
    if let LightDesc::Spot {
        cutoff_angle_deg,
        beam_width_deg,
        texture,
        ..
    } = l
        && deg.is_finite()
    {
        let hi = if texture.is_some() {
            TEXTURED_MAX_CUTOFF
        } else {
            180.0
        };
        *cutoff_angle_deg = deg.clamp(MIN_ANGLE.min(*cutoff_angle_deg), hi);
        *beam_width_deg = beam_width_deg.min(*cutoff_angle_deg);
    }
}

/// Sets a spot's beam width (degrees), clamped to [0, its cutoff angle].
pub fn set_beam_width(l: &mut LightDesc, deg: f64) {
    if let LightDesc::Spot {
        cutoff_angle_deg,
        beam_width_deg,
        ..
    } = l
        && deg.is_finite()
    {
        *beam_width_deg = deg.clamp(0.0, *cutoff_angle_deg);
    }
}

/// Sets a projector's horizontal field of view (degrees), in (0, 180).
pub fn set_fov(l: &mut LightDesc, deg: f64) {
    if let LightDesc::Projector { fov_x_deg, .. } = l
        && deg.is_finite()
    {
        *fov_x_deg = deg.clamp(MIN_ANGLE.min(*fov_x_deg), MAX_FOV.max(*fov_x_deg));
    }
}

/// Sets a projector's scale, in [0, 1e30].
pub fn set_scale(l: &mut LightDesc, s: f64) {
    if let LightDesc::Projector { scale, .. } = l
        && s.is_finite()
    {
        *scale = s.clamp(0.0, MAX_RADIANCE);
    }
}

/// A logarithmic slider's range: [`STRENGTH_RANGE`] widened to hold `current`.
fn strength_range(current: f64) -> RangeInclusive<f64> {
    STRENGTH_RANGE.start().min(current)..=STRENGTH_RANGE.end().max(current)
}

/// Three drag values in a row, `label` after them; true when one changed.
fn drag_vec3(ui: &mut egui::Ui, label: &str, v: &mut DVec3, speed: f64) -> bool {
    ui.horizontal(|ui| {
        let mut changed = false;
        for (c, name) in [(&mut v.x, "x"), (&mut v.y, "y"), (&mut v.z, "z")] {
            changed |= ui
                .add(
                    egui::DragValue::new(c)
                        .speed(speed)
                        .range(-MAX_COORD..=MAX_COORD)
                        .prefix(format!("{name} ")),
                )
                .changed();
        }
        ui.label(label);
        changed
    })
    .inner
}

impl ViewerApp {
    /// The "Delta lights" section (nothing when the scene has none).
    pub(crate) fn delta_light_controls(&mut self, ui: &mut egui::Ui) {
        let Some(desc) = &self.desc else { return };
        if desc.lights.is_empty() {
            return;
        }
        ui.separator();
        ui.heading("Delta lights");
        ui.label("point, spot, directional and projector lights: only light sampling finds them");
        let names: Vec<String> = (desc.lights.iter().enumerate())
            .map(|(i, l)| format!("lights[{i}] {}", kind(l)))
            .collect();
        let options: Vec<Option<usize>> = std::iter::once(None)
            .chain((0..names.len()).map(Some))
            .collect();
        let mut sel = self.selected_delta_light.filter(|&i| i < names.len());
        combo(ui, "Delta light", &mut sel, &options, |s| {
            s.map_or("(none)".into(), |i| names[i].clone())
        });
        self.selected_delta_light = sel;
        let Some(i) = sel else { return };
        // Drag speed: a two-hundredth of the scene per point dragged.
        let speed = self.output.scene.as_ref().map_or(0.01, |s| {
            let (lo, hi) = s.accel.bounds();
            ((hi - lo).length() as f64 * 5e-3).clamp(1e-6, 1e6)
        });
        let Some(desc) = &mut self.desc else { return };
        let light = &mut desc.lights[i];
        let before = light.clone();
        if let Some(e) = emission(light) {
            let mut strength = e.max_element();
            let name = match light {
                LightDesc::Point { .. } | LightDesc::Spot { .. } => "Light intensity",
                _ => "Light irradiance",
            };
            let range = strength_range(strength);
            if ui
                .add(
                    egui::Slider::new(&mut strength, range)
                        .logarithmic(true)
                        .text(name),
                )
                .changed()
            {
                set_strength(light, strength);
            }
            let colour = if e.max_element() > 0.0 {
                e / e.max_element()
            } else {
                DVec3::ONE
            };
            let mut rgb = colour.as_vec3().to_array();
            ui.horizontal(|ui| {
                if egui::color_picker::color_edit_button_rgb(ui, &mut rgb).changed() {
                    set_colour(light, DVec3::from(rgb.map(f64::from)));
                }
                ui.label("Delta light colour");
            });
        }
        if let Some(mut p) = position(light)
            && drag_vec3(ui, "Position", &mut p, speed)
        {
            set_position(light, p);
        }
        if let Some(mut t) = target(light)
            && drag_vec3(ui, "Aim at", &mut t, speed)
        {
            set_target(light, t);
        }
        if let Some((mut az, mut el)) = direction_angles(light) {
            let a =
                ui.add(egui::Slider::new(&mut az, -180.0..=180.0).text("Direction azimuth (°)"));
            let e =
                ui.add(egui::Slider::new(&mut el, -90.0..=90.0).text("Direction elevation (°)"));
            if a.changed() || e.changed() {
                set_direction_angles(light, az, el);
            }
        }
        if let LightDesc::Spot {
            cutoff_angle_deg,
            beam_width_deg,
            texture,
            ..
        } = light
        {
            let (mut cutoff, mut beam) = (*cutoff_angle_deg, *beam_width_deg);
            let range = cutoff_range(texture.is_some(), cutoff);
            let c = ui.add(egui::Slider::new(&mut cutoff, range).text("Spot cutoff (°)"));
            let b = ui
                .add(
                    egui::Slider::new(&mut beam, 0.0..=*cutoff_angle_deg)
                        .text("Spot beam width (°)"),
                )
                .on_hover_text("the full-intensity cone inside the cutoff; at most the cutoff");
            if c.changed() {
                set_cutoff(light, cutoff);
            }
            if b.changed() {
                set_beam_width(light, beam);
            }
        }
        if let LightDesc::Projector {
            fov_x_deg, scale, ..
        } = light
        {
            let (mut fov, mut s) = (*fov_x_deg, *scale);
            let fov_range = MIN_ANGLE.min(fov)..=MAX_FOV.max(fov);
            let f =
                ui.add(egui::Slider::new(&mut fov, fov_range).text("Projector field of view (°)"));
            let scale_range = strength_range(s);
            let k = ui.add(
                egui::Slider::new(&mut s, scale_range)
                    .logarithmic(true)
                    .text("Projector scale"),
            );
            if f.changed() {
                set_fov(light, fov);
            }
            if k.changed() {
                set_scale(light, s);
            }
        }
        if *light != before {
            self.scene_changed();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spot(textured: bool) -> LightDesc {
        LightDesc::Spot {
            frame: LookAt {
                from: DVec3::new(1.0, 2.0, 0.0),
                to: DVec3::new(1.0, 0.0, 0.0),
                up: DVec3::Z,
            },
            intensity: DVec3::new(0.0, 8.0, 4.0),
            cutoff_angle_deg: 30.0,
            beam_width_deg: 22.5,
            texture: textured.then_some(lumis::scene::TextureDesc {
                texture: lumis::textures::Texture::Constant(glam::Vec3::ONE),
            }),
        }
    }

    fn cone(l: &LightDesc) -> (f64, f64) {
        match l {
            LightDesc::Spot {
                cutoff_angle_deg,
                beam_width_deg,
                ..
            } => (*cutoff_angle_deg, *beam_width_deg),
            _ => unreachable!(),
        }
    }

    #[test]
    fn the_cone_stays_valid() {
        let mut l = spot(false);
        set_cutoff(&mut l, 10.0);
        assert_eq!(cone(&l), (10.0, 10.0), "the beam shrinks with the cutoff");
        set_beam_width(&mut l, 50.0);
        assert_eq!(cone(&l), (10.0, 10.0), "the beam is at most the cutoff");
        set_cutoff(&mut l, 500.0);
        assert_eq!(cone(&l), (180.0, 10.0));
        set_cutoff(&mut l, -1.0);
        assert!(cone(&l).0 > 0.0 && cone(&l).1 <= cone(&l).0);
        let mut t = spot(true);
        set_cutoff(&mut t, 120.0);
        assert!(cone(&t).0 < 90.0, "a textured spot stays below 90°");
    }

    #[test]
    fn strength_and_colour_are_separate() {
        let mut l = spot(false);
        set_strength(&mut l, 2.0);
        assert_eq!(emission(&l), Some(DVec3::new(0.0, 2.0, 1.0)));
        set_colour(&mut l, DVec3::new(1.0, 0.5, 0.0));
        assert_eq!(emission(&l), Some(DVec3::new(2.0, 1.0, 0.0)));
        set_colour(&mut l, DVec3::ZERO);
        assert_eq!(
            emission(&l),
            Some(DVec3::new(2.0, 1.0, 0.0)),
            "black refused"
        );
        set_strength(&mut l, 0.0);
        set_strength(&mut l, 3.0);
        assert_eq!(emission(&l), Some(DVec3::splat(3.0)), "from black: white");
    }

    #[test]
    fn the_frame_stays_valid() {
        let mut l = spot(false);
        set_position(&mut l, DVec3::new(1.0, 0.0, 0.0));
        assert_eq!(
            position(&l),
            Some(DVec3::new(1.0, 2.0, 0.0)),
            "onto `to`: refused"
        );
        // Aiming along `up` (+z) replaces it by a perpendicular one.
        set_target(&mut l, DVec3::new(1.0, 2.0, 5.0));
        let LightDesc::Spot { frame, .. } = &l else {
            unreachable!()
        };
        assert_eq!(frame.to, DVec3::new(1.0, 2.0, 5.0));
        assert!(frame.up.dot(DVec3::Z).abs() < 1e-9, "{:?}", frame.up);
    }

    #[test]
    fn direction_angles_round_trip() {
        let mut l = LightDesc::Directional {
            direction: DVec3::new(1.0, -1.0, 0.0).normalize(),
            irradiance: DVec3::ONE,
        };
        let (az, el) = direction_angles(&l).unwrap();
        assert!(
            (az - 90.0).abs() < 1e-9 && (el + 45.0).abs() < 1e-9,
            "{az} {el}"
        );
        set_direction_angles(&mut l, az, el);
        let LightDesc::Directional { direction, .. } = l else {
            unreachable!()
        };
        assert!((direction - DVec3::new(1.0, -1.0, 0.0).normalize()).length() < 1e-12);
    }
}
