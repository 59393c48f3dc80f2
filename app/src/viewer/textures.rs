//! The textures the panes draw, one per [`Picture`] (a lane's image, its error map, the reference,
//! a difference), uploaded only when its pixels or the display settings changed, and dropped when
//! no pane drew it in a frame. GPU lanes showing their image are drawn from their accumulation
//! buffer by the display shader instead (see `gpu_display`). Textures are sampled
//! nearest-neighbour when magnified, so that zooming in shows single pixels, and linearly when
//! minified.

use super::app::ViewerApp;
use super::tonemap::{Content, Display, color_image, difference_rgb, technique_rgb};
use super::wipe::Source;
use glam::Vec3;
use std::collections::{HashMap, HashSet};
use std::sync::Arc;

/// Sampling of every pane texture: nearest when magnified, linear when minified.
pub const PANE_SAMPLING: egui::TextureOptions = egui::TextureOptions {
    magnification: egui::TextureFilter::Nearest,
    ..egui::TextureOptions::LINEAR
};

/// Something a pane draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Picture {
    /// A lane's image or the reference, exposed.
    Image(Source),
    /// Lane `i`'s per-pixel relative error in false colour.
    Error(usize),
    /// The signed difference of the first against the second.
    Difference(Source, Source),
    /// Lane `i`'s technique map.
    Techniques(usize),
}

impl Picture {
    /// The picture that shows `source` with `content` (`base`: what a difference is taken
    /// against; the reference has no error map of its own and shows as an image).
    pub fn of(source: Source, content: Content, base: Option<Source>) -> Picture {
        match (content, source, base) {
            (Content::RelativeError, Source::Lane(i), _) => Picture::Error(i),
            (Content::TechniqueMap, Source::Lane(i), _) => Picture::Techniques(i),
            (Content::Difference, s, Some(b)) if b != s => Picture::Difference(s, b),
            _ => Picture::Image(source),
        }
    }
}

/// What a texture shows: the addresses of the pixel buffers it was made from and the display.
type Key = (usize, usize, Display);

/// The buffers behind a [`Key`]'s addresses, held while the texture shows them: a freed buffer's
/// address can be given to the next image, whose texture would then never be uploaded (the
/// viewer's wipe test saw a side show an older image under load, 2026-12-08).
type Pins = Vec<Arc<dyn std::any::Any + Send + Sync>>;

/// The uploaded textures and what each showed.
#[derive(Default)]
pub struct TextureCache {
    slots: HashMap<Picture, (Key, Pins, egui::TextureHandle)>,
    used: HashSet<Picture>,
}

impl TextureCache {
    /// Drops the textures no pane drew since the last call.
    pub fn end_frame(&mut self) {
        let used = std::mem::take(&mut self.used);
        self.slots.retain(|p, _| used.contains(p));
    }
}

impl ViewerApp {
    /// The pixels of `source` and their size: a lane's latest image (a preview is smaller than
    /// the film) or the reference.
    pub fn source_pixels(&self, source: Source) -> Option<(Arc<Vec<Vec3>>, u32, u32)> {
        match source {
            Source::Lane(i) => {
                let l = self.output.lanes.get(i)?;
                (!l.pixels.is_empty()).then(|| (l.pixels.clone(), l.width, l.height))
            }
            Source::Reference => {
                let (_, r) = self.reference.as_ref()?;
                let c = &self.desc.as_ref()?.camera;
                Some((r.clone(), c.width, c.height))
            }
        }
    }

    /// The texture of `picture`, uploading it if its pixels or the display changed; `None` when
    /// there is nothing to show yet.
    pub(crate) fn texture(
        &mut self,
        ctx: &egui::Context,
        picture: Picture,
    ) -> Option<egui::TextureId> {
        let gain = 2f32.powf(self.display.exposure);
        if let Picture::Image(Source::Lane(i)) = picture
            && let Some(live) = self.output.lanes.get(i).and_then(|l| l.live.clone())
            && let Some(display) = &mut self.gpu_display
        {
            return Some(display.texture(i, &live, gain));
        }
        let ptr = |p: &Arc<Vec<Vec3>>| Arc::as_ptr(p) as usize;
        let pin = |p: &Arc<Vec<Vec3>>| -> Arc<dyn std::any::Any + Send + Sync> { p.clone() };
        let (key, pins, make): (Key, Pins, Box<dyn FnOnce() -> egui::ColorImage>) = match picture {
            Picture::Image(s) => {
                let (px, w, h) = self.source_pixels(s)?;
                let display = Display {
                    content: Content::Image,
                    ..self.display
                };
                let (key, pins) = ((ptr(&px), 0, display), vec![pin(&px)]);
                (
                    key,
                    pins,
                    Box::new(move || color_image(w, h, &px, &[], display)),
                )
            }
            Picture::Error(i) => {
                let l = self.output.lanes.get(i)?;
                let (px, errors, w, h) = (l.pixels.clone(), l.errors.clone(), l.width, l.height);
                if px.is_empty() {
                    return None;
                }
                let display = Display {
                    exposure: 0.0,
                    content: Content::RelativeError,
                };
                // A preview has no errors: it shows as an image, at this exposure.
                let display = if errors.len() == px.len() {
                    display
                } else {
                    self.display
                };
                let key = (ptr(&px), Arc::as_ptr(&errors) as usize, display);
                let pins: Pins = vec![pin(&px), errors.clone()];
                (
                    key,
                    pins,
                    Box::new(move || color_image(w, h, &px, &errors, display)),
                )
            }
            Picture::Techniques(i) => {
                let l = self.output.lanes.get(i)?;
                let (parts, w, h) = (l.techniques.clone(), l.width, l.height);
                if l.pixels.is_empty() {
                    return None;
                }
                let display = Display {
                    content: Content::TechniqueMap,
                    ..self.display
                };
                let key = (Arc::as_ptr(&parts) as usize, 1, display);
                let pins: Pins = vec![parts.clone()];
                (
                    key,
                    pins,
                    Box::new(move || {
                        // A GPU lane or a preview records no split: uniform dark grey, which
                        // the legend explains.
                        let rgb = if parts.len() == (w * h) as usize {
                            technique_rgb(&parts, 2f32.powf(display.exposure))
                        } else {
                            [40u8; 3].repeat((w * h) as usize)
                        };
                        egui::ColorImage::from_rgb([w as usize, h as usize], &rgb)
                    }),
                )
            }
            Picture::Difference(a, b) => {
                let (pa, w, h) = self.source_pixels(a)?;
                let (pb, ..) = self.source_pixels(b)?;
                let display = Display {
                    exposure: 0.0,
                    content: Content::Difference,
                };
                let key = (ptr(&pa), ptr(&pb), display);
                let pins = vec![pin(&pa), pin(&pb)];
                (
                    key,
                    pins,
                    Box::new(move || {
                        egui::ColorImage::from_rgb(
                            [w as usize, h as usize],
                            &difference_rgb(&pa, &pb),
                        )
                    }),
                )
            }
        };
        let cache = &mut self.textures;
        cache.used.insert(picture);
        if let Some((k, p, t)) = cache.slots.get_mut(&picture) {
            if *k != key {
                (*k, *p) = (key, pins);
                t.set(make(), PANE_SAMPLING);
            }
            return Some(t.id());
        }
        let t = ctx.load_texture(format!("{picture:?}"), make(), PANE_SAMPLING);
        let id = t.id();
        cache.slots.insert(picture, (key, pins, t));
        Some(id)
    }
}
