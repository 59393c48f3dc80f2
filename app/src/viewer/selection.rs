//! The selected material's and light's controls, and selection by clicking the image. Edits go
//! into the scene description, which is then rebuilt.

use super::app::ViewerApp;
use super::controls::combo;
use super::edit::{self, LightEdit};
use super::light_shape::{DISK_STOP, Keep, LightShape, MAX_SIDES};
use super::pick::pick;
use glam::DVec3;
use lumis::scene::PlasticModel;
use lumis::scene::desc::Distribution;

impl ViewerApp {
    /// Selects what the camera sees through film position (`x`, `y`): its material, and the
    /// light if it emits. Clicking the background clears the selection.
    pub fn select_at(&mut self, x: f32, y: f32) {
        let (Some(scene), Some(desc)) = (&self.output.scene, &self.desc) else {
            return;
        };
        if self.output.desc_version != self.desc_version {
            // The scene on screen is older than the description; the indices may not match.
            return;
        }
        match pick(scene, desc, x, y) {
            Some(p) => {
                self.selected_material = p.material;
                self.select_light(p.light_shape);
            }
            None => {
                self.selected_material = None;
                self.light = None;
            }
        }
    }

    /// Selects emitting shape `shape` (or none) for the light controls.
    pub fn select_light(&mut self, shape: Option<usize>) {
        if self.light.as_ref().map(|l| l.shape) == shape {
            return;
        }
        self.light = match (shape, &self.desc) {
            (Some(s), Some(desc)) => Some(LightEdit::new(desc, s)),
            _ => None,
        };
    }

    /// Applies the light editor to the description and restarts.
    pub fn light_changed(&mut self) {
        if let (Some(l), Some(desc)) = (&self.light, &mut self.desc) {
            l.apply(desc);
            self.scene_changed();
        }
    }

    pub(crate) fn selection_controls(&mut self, ui: &mut egui::Ui) {
        let Some(desc) = &self.desc else { return };
        ui.heading("Material");
        ui.label("click an object in the image, or pick one here");
        let names: Vec<String> = desc.materials.iter().map(|m| m.name.clone()).collect();
        let mut sel = self.selected_material;
        let options: Vec<Option<usize>> = std::iter::once(None)
            .chain((0..names.len()).map(Some))
            .collect();
        combo(ui, "Material", &mut sel, &options, |m| {
            m.map_or("(none)".into(), |i| names[i].clone())
        });
        self.selected_material = sel;
        match sel.map(|i| (i, desc.materials[i].parts())) {
            // A mix or pair has no parameters of its own (its stand-in BSDF is not what renders):
            // its parts are edited instead.
            Some((i, Some(parts))) => {
                let what = match desc.materials[i].mix {
                    Some(_) => "A mix of",
                    None => "Two-sided: front and back",
                };
                ui.label(format!("{what} (pick one to edit it):"));
                ui.horizontal(|ui| {
                    for p in parts {
                        if ui.button(&names[p]).clicked() {
                            self.selected_material = Some(p);
                        }
                    }
                });
            }
            Some((i, None)) => self.material_controls(ui, i),
            None => {}
        }
        ui.separator();
        ui.heading("Light");
        self.light_controls(ui);
    }

    fn material_controls(&mut self, ui: &mut egui::Ui, i: usize) {
        let Some(desc) = &mut self.desc else { return };
        let named = &mut desc.materials[i];
        let (m, textures) = (&mut named.material, &mut named.textures);
        let mut changed = false;
        // A textured slot shows its texture's mean; editing it replaces the texture by that
        // constant (so an edit is never silently ignored).
        let textured_colour = textures.albedo.is_some() || textures.reflectance.is_some();
        if !textures.is_empty() {
            ui.label("Textured: editing a textured value replaces its texture by a constant.");
        }
        if let Some(mut a) = edit::alpha(m)
            && ui
                .add(
                    egui::Slider::new(&mut a, 0.0..=1.0).text(if textures.alpha.is_some() {
                        "Roughness α (texture mean)"
                    } else {
                        "Roughness α"
                    }),
                )
                .changed()
        {
            edit::set_alpha(m, a);
            textures.alpha = None;
            textures.alpha_v = None;
            changed = true;
        }
        // Anisotropy beside the roughness: α_v/α_u (α_u is the slider above), and the
        // distribution.
        if let Some(mut r) = edit::aspect(m)
            && ui
                .add(
                    egui::Slider::new(&mut r, edit::ASPECT_RANGE)
                        .logarithmic(true)
                        .text("Anisotropy α_v/α_u"),
                )
                .changed()
        {
            edit::set_aspect(m, r);
            textures.alpha = None;
            textures.alpha_v = None;
            changed = true;
        }
        // A plastic's coupling: lumis' (energy conserving) or Mitsuba's, with its nonlinear
        // internal bounces. Mitsuba's tabulates one α, so a textured α becomes its mean.
        if let Some(mut model) = edit::plastic_model(m) {
            let mitsuba = PlasticModel::Mitsuba {
                distribution: Distribution::Ggx,
                nonlinear: false,
            };
            let is_mitsuba = |p: &PlasticModel| matches!(p, PlasticModel::Mitsuba { .. });
            let mut choice = is_mitsuba(&model);
            if combo(ui, "Coupling", &mut choice, &[false, true], |c| {
                if c {
                    "Mitsuba 3"
                } else {
                    "lumis (energy conserving)"
                }
                .into()
            }) {
                edit::set_plastic_model(m, if choice { mitsuba } else { PlasticModel::Lumis });
                if choice {
                    textures.alpha = None;
                    textures.alpha_v = None;
                }
                changed = true;
            }
            if let PlasticModel::Mitsuba { nonlinear, .. } = &mut model
                && ui
                    .checkbox(nonlinear, "Nonlinear (tinted internal bounces)")
                    .changed()
            {
                edit::set_plastic_model(m, model);
                changed = true;
            }
        }
        if let Some(mut d) = edit::distribution(m) {
            let all = [Distribution::Ggx, Distribution::Beckmann];
            if combo(ui, "Microfacets", &mut d, &all, |d| d.name().into()) {
                edit::set_distribution(m, d);
                changed = true;
            }
        }
        if let Some(c) = edit::colour(m) {
            let mut rgb = c.as_vec3().to_array();
            let r = ui
                .horizontal(|ui| {
                    let r = egui::color_picker::color_edit_button_rgb(ui, &mut rgb);
                    ui.label(if textured_colour {
                        "Colour (texture mean)"
                    } else {
                        "Colour"
                    });
                    r
                })
                .inner;
            if r.changed() {
                edit::set_colour(m, DVec3::from(rgb.map(f64::from)));
                textures.albedo = None;
                textures.reflectance = None;
                changed = true;
            }
        }
        // A principled's main parameters (Mitsuba's keys), a textured one showing its mean.
        for param in edit::PRINCIPLED_SLIDERS {
            let Some(mut v) = edit::principled_scalar(m, param) else {
                break;
            };
            let slot = &mut textures.principled[param as usize];
            let label = match slot {
                Some(_) => format!("{} (texture mean)", param.name()),
                None => param.name().to_owned(),
            };
            if ui
                .add(egui::Slider::new(&mut v, 0.0..=1.0).text(label))
                .changed()
            {
                edit::set_principled_scalar(m, param, v);
                *slot = None;
                changed = true;
            }
        }
        // A thin principled's, likewise.
        for param in edit::THIN_SLIDERS {
            let Some(mut v) = edit::thin_scalar(m, param) else {
                break;
            };
            let slot = &mut textures.principled[param as usize];
            let label = match slot {
                Some(_) => format!("{} (texture mean)", param.name()),
                None => param.name().to_owned(),
            };
            if ui
                .add(egui::Slider::new(&mut v, edit::thin_slider_range(param)).text(label))
                .changed()
            {
                edit::set_thin_scalar(m, param, v);
                *slot = None;
                changed = true;
            }
        }
        // A glTF material's, likewise.
        for param in edit::GLTF_SLIDERS {
            let Some(mut v) = edit::gltf_scalar(m, param) else {
                break;
            };
            let slot = &mut textures.principled[param as usize];
            let label = match slot {
                Some(_) => format!("{} (texture mean)", param.name()),
                None => param.name().to_owned(),
            };
            if ui
                .add(egui::Slider::new(&mut v, 0.0..=1.0).text(label))
                .changed()
            {
                edit::set_gltf_scalar(m, param, v);
                *slot = None;
                changed = true;
            }
        }
        if let Some(mut s) = edit::specular(m)
            && ui
                .add(egui::Slider::new(&mut s, 0.0..=1.0).text("specular (sets η)"))
                .changed()
        {
            edit::set_specular(m, s);
            changed = true;
        }
        if let Some(mut n) = edit::ior(m) {
            let range = edit::ior_slider_range(m, n);
            if ui
                .add(egui::Slider::new(&mut n, range).text("IOR"))
                .changed()
            {
                edit::set_ior(m, n);
                changed = true;
            }
            let presets = edit::ior_presets(m);
            if !presets.is_empty() {
                ui.horizontal(|ui| {
                    for &(name, value) in presets {
                        let on = edit::ior(m) == Some(value);
                        // Re-picking the current preset changes nothing: no restart.
                        if ui.selectable_label(on, format!("{name} {value}")).clicked() && !on {
                            edit::set_ior(m, value);
                            changed = true;
                        }
                    }
                });
            }
        }
        // A normal or bump map: on or off (kept aside while off), a bump map's scale, and
        // Mitsuba's two switches.
        let off = &mut self.normal_maps_off;
        let mut on = named.normal_map.is_some();
        let bump = named
            .normal_map
            .as_ref()
            .or(off.get(&i))
            .is_some_and(|m| m.height_scale.is_some());
        let label = if bump { "Bump map" } else { "Normal map" };
        if (on || off.contains_key(&i)) && ui.checkbox(&mut on, label).changed() {
            if on {
                named.normal_map = off.remove(&i);
            } else if let Some(map) = named.normal_map.take() {
                off.insert(i, map);
            }
            changed = true;
        }
        if let Some(map) = &mut named.normal_map {
            if let Some(scale) = &mut map.height_scale {
                // The height's scale: its sign turns bumps into dents; 0 is a flat surface.
                let speed = (scale.abs() * 0.01).max(1e-4);
                changed |= ui
                    .horizontal(|ui| {
                        ui.label("Bump scale");
                        ui.add(egui::DragValue::new(scale).speed(speed).max_decimals(5))
                    })
                    .inner
                    .changed();
            }
            changed |= ui
                .checkbox(&mut map.shadowing, "Shadowing term (normal map)")
                .changed();
            changed |= ui
                .checkbox(&mut map.flip_invalid_normals, "Flip invalid normals")
                .changed();
        }
        // An alpha mask: on or off (kept aside while off), and a constant opacity's value.
        let off = &mut self.masks_off;
        let mut on = named.opacity.is_some();
        if (on || off.contains_key(&i)) && ui.checkbox(&mut on, "Mask").changed() {
            if on {
                named.opacity = off.remove(&i);
            } else if let Some(opacity) = named.opacity.take() {
                off.insert(i, opacity);
            }
            changed = true;
        }
        if let Some(lumis::scene::TextureDesc {
            texture: lumis::textures::Texture::Constant(c),
        }) = &mut named.opacity
        {
            let mut alpha = c.x;
            if ui
                .add(egui::Slider::new(&mut alpha, 0.0..=1.0).text("Opacity"))
                .changed()
            {
                *c = glam::Vec3::splat(alpha);
                changed = true;
            }
        }
        if changed {
            // A principled whose transmission the sliders turned on has no sides.
            named.two_sided &= !named.material.transmits();
            self.scene_changed();
        }
    }

    fn light_controls(&mut self, ui: &mut egui::Ui) {
        let Some(desc) = &self.desc else { return };
        let emitters: Vec<Option<usize>> = std::iter::once(None)
            .chain(
                desc.shapes
                    .iter()
                    .enumerate()
                    .filter(|(_, s)| s.emission.cmpgt(DVec3::ZERO).any())
                    .map(|(i, _)| Some(i)),
            )
            .collect();
        let paths: Vec<String> = desc.shapes.iter().map(|s| s.json_path.clone()).collect();
        // Size range: from a thousandth of the scene to the whole scene.
        let extent = self.output.scene.as_ref().map_or(1.0, |s| {
            let (lo, hi) = s.accel.bounds();
            (hi - lo).length().max(1e-6) as f64
        });
        let mut sel = self.light.as_ref().map(|l| l.shape);
        if combo(ui, "Light", &mut sel, &emitters, |s| {
            s.map_or("(none)".into(), |i| paths[i].clone())
        }) {
            self.select_light(sel);
        }
        let Some(light) = &mut self.light else { return };
        let before = light.clone();
        ui.horizontal(|ui| {
            ui.label("Keep");
            ui.radio_value(&mut light.keep, Keep::Area, "area");
            ui.radio_value(&mut light.keep, Keep::Power, "power");
        });
        if let Some(shape) = light.planar_shape() {
            let mut s = shape;
            let kinds = [
                polygon_entry(shape),
                LightShape::Disk,
                LightShape::Quad,
                LightShape::Triangle,
            ];
            combo(ui, "Light shape", &mut s, &kinds, |k| match k {
                LightShape::Polygon(_) => "polygon".into(),
                k => k.label(),
            });
            let mut sides = s.slider_value();
            let r = ui.add(
                egui::Slider::new(&mut sides, 3..=DISK_STOP)
                    .text("Light sides")
                    .custom_formatter(|v, _| {
                        if v as u32 >= DISK_STOP {
                            "disk".into()
                        } else {
                            format!("{v}")
                        }
                    }),
            );
            if r.changed() {
                s = LightShape::from_slider(sides);
            }
            if s != shape {
                light.set_shape(s);
            }
        }
        if let Some(mut size) = light.size() {
            let r = ui.add(
                egui::Slider::new(&mut size, extent * 1e-3..=extent)
                    .logarithmic(true)
                    .text("Light size"),
            );
            if r.changed() {
                light.set_size(size);
            }
        }
        let mut radiance = light.radiance;
        if ui
            .add(
                egui::Slider::new(&mut radiance, 1e-3..=1e5)
                    .logarithmic(true)
                    .text("Radiance"),
            )
            .changed()
        {
            light.radiance = radiance;
        }
        let mut rgb = light.colour.as_vec3().to_array();
        ui.horizontal(|ui| {
            if egui::color_picker::color_edit_button_rgb(ui, &mut rgb).changed() {
                let c = DVec3::from(rgb.map(f64::from));
                // Brightness lives in the radiance slider; the colour keeps its largest
                // component at 1.
                if c.max_element() > 0.0 {
                    light.colour = c / c.max_element();
                }
            }
            ui.label("Light colour");
        });
        if let Some(p) = light.power() {
            ui.label(format!("power (largest channel): {p:.4e}"));
        }
        // The keep toggle alone changes nothing in the scene.
        if (light.geometry, light.colour, light.radiance)
            != (before.geometry, before.colour, before.radiance)
        {
            self.light_changed();
        }
    }
}

/// The polygon entry of the shape menu: the current polygon, or a hexagon when switching from
/// another shape.
fn polygon_entry(current: LightShape) -> LightShape {
    match current {
        LightShape::Polygon(n) => LightShape::Polygon(n.min(MAX_SIDES)),
        _ => LightShape::Polygon(6),
    }
}
