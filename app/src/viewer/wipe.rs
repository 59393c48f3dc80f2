//! The wipe: two renders, or a render and the reference, in one image split by a draggable
//! divider (Falcor's split screen). Each render side is a lane of its own, accumulating on its
//! own; the divider and what the halves show (image, relative error, or the signed difference
//! A − B over the whole image) are display settings and never restart accumulation.

use super::params::StrategyKind;
use lumis::engine::Backend;

/// One side of the wipe.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WipeSide {
    /// A render with this strategy, on this backend (`None`: the viewer's backend).
    Render(StrategyKind, Option<Backend>),
    /// The loaded reference image.
    Reference,
}

/// Width (points) either side of the divider that grabs it.
pub const GRAB: f32 = 6.0;

impl WipeSide {
    /// Parses a `--wipe` side: `STRATEGY`, `STRATEGY:cpu`, `STRATEGY:gpu` or `reference`.
    pub fn parse(s: &str) -> Result<WipeSide, String> {
        let s = s.trim();
        if s == "reference" || s == "ref" {
            return Ok(WipeSide::Reference);
        }
        let (name, backend) = match s.split_once(':') {
            Some((n, "cpu")) => (n, Some(Backend::Cpu)),
            Some((n, "gpu")) => (n, Some(Backend::Gpu)),
            Some((_, b)) => return Err(format!("'{b}' is not a backend (cpu or gpu)")),
            None => (s, None),
        };
        let kind = StrategyKind::ALL
            .into_iter()
            .find(|k| k.name() == name)
            .ok_or_else(|| {
                let names: Vec<&str> = StrategyKind::ALL.iter().map(|k| k.name()).collect();
                format!(
                    "'{name}' is not a strategy ({}) or 'reference'",
                    names.join(", ")
                )
            })?;
        Ok(WipeSide::Render(kind, backend))
    }

    /// Its name in menus and captions.
    pub fn name(self) -> String {
        match self {
            WipeSide::Reference => "reference".into(),
            WipeSide::Render(k, None) => k.name().into(),
            WipeSide::Render(k, Some(Backend::Cpu)) => format!("{} (CPU)", k.name()),
            WipeSide::Render(k, Some(Backend::Gpu)) => format!("{} (GPU)", k.name()),
        }
    }

    /// Every side the menus offer: each strategy on the viewer's backend, on the CPU and on the
    /// GPU, and the reference.
    pub fn menu() -> Vec<WipeSide> {
        let mut out = Vec::new();
        for backend in [None, Some(Backend::Cpu), Some(Backend::Gpu)] {
            out.extend(StrategyKind::ALL.map(|k| WipeSide::Render(k, backend)));
        }
        out.push(WipeSide::Reference);
        out
    }
}

/// What each side of the wipe draws from: a lane's index, or the reference.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Source {
    /// Lane `i` of the render thread's output.
    Lane(usize),
    /// The loaded reference image.
    Reference,
}

/// The sources of `sides`: render sides are lanes in order (as `RenderParams::lanes` makes
/// them), the reference side is the reference.
pub fn sources(sides: &[WipeSide; 2]) -> [Source; 2] {
    let mut lane = 0;
    sides.map(|s| match s {
        WipeSide::Reference => Source::Reference,
        WipeSide::Render(..) => {
            lane += 1;
            Source::Lane(lane - 1)
        }
    })
}

/// The divider's x (points) in `cell` at `position` (0 = left edge, 1 = right edge).
pub fn divider_x(cell: egui::Rect, position: f32) -> f32 {
    cell.min.x + position.clamp(0.0, 1.0) * cell.width()
}

/// The position of a divider dragged to screen x `x` in `cell`.
pub fn position_at(cell: egui::Rect, x: f32) -> f32 {
    ((x - cell.min.x) / cell.width().max(1.0)).clamp(0.0, 1.0)
}

/// The halves of `cell` left and right of the divider at `position`: A is drawn clipped to the
/// first, B to the second.
pub fn halves(cell: egui::Rect, position: f32) -> [egui::Rect; 2] {
    let x = divider_x(cell, position);
    [
        egui::Rect::from_min_max(cell.min, egui::pos2(x, cell.max.y)),
        egui::Rect::from_min_max(egui::pos2(x, cell.min.y), cell.max),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sides_parse_strategies_backends_and_the_reference() {
        assert_eq!(
            WipeSide::parse("light"),
            Ok(WipeSide::Render(StrategyKind::Light, None))
        );
        assert_eq!(
            WipeSide::parse("mis:gpu"),
            Ok(WipeSide::Render(StrategyKind::Mis, Some(Backend::Gpu)))
        );
        assert_eq!(WipeSide::parse("reference"), Ok(WipeSide::Reference));
        assert!(WipeSide::parse("mis:tpu").unwrap_err().contains("tpu"));
        assert!(WipeSide::parse("lite").unwrap_err().contains("lite"));
        for side in WipeSide::menu() {
            let text = match side {
                WipeSide::Render(k, Some(b)) => {
                    format!(
                        "{}:{}",
                        k.name(),
                        if b == Backend::Cpu { "cpu" } else { "gpu" }
                    )
                }
                WipeSide::Render(k, None) => k.name().into(),
                WipeSide::Reference => "reference".into(),
            };
            assert_eq!(WipeSide::parse(&text), Ok(side));
        }
    }

    #[test]
    fn render_sides_are_lanes_in_order() {
        let mis = WipeSide::Render(StrategyKind::Mis, None);
        assert_eq!(sources(&[mis, mis]), [Source::Lane(0), Source::Lane(1)]);
        assert_eq!(
            sources(&[WipeSide::Reference, mis]),
            [Source::Reference, Source::Lane(0)]
        );
    }

    #[test]
    fn divider_round_trips_and_splits_the_cell() {
        let cell = egui::Rect::from_min_size(egui::pos2(10.0, 20.0), egui::vec2(200.0, 100.0));
        assert_eq!(divider_x(cell, 0.25), 60.0);
        assert_eq!(position_at(cell, 60.0), 0.25);
        assert_eq!(position_at(cell, -5.0), 0.0);
        let [a, b] = halves(cell, 0.25);
        assert_eq!(
            (a.max.x, b.min.x, a.width() + b.width()),
            (60.0, 60.0, 200.0)
        );
    }
}
