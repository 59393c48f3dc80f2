//! The option menus of the Render panel, one table per option: adding a variant to the renderer
//! (a light-sampling method, a sampler, a selection rule) is one line here. The test below stops
//! compiling when an enum gains a variant, pointing here.

use lumis::engine::Backend;
use lumis::integrator::Heuristic;
use lumis::lights::{LightSampling, LightSelection};
use lumis::sampler::SamplerKind;

/// Backends and their names.
pub const BACKENDS: &[(Backend, &str)] = &[(Backend::Cpu, "CPU"), (Backend::Gpu, "GPU (wgpu)")];

/// MIS heuristics.
pub const HEURISTICS: &[(Heuristic, &str)] =
    &[(Heuristic::Balance, "balance"), (Heuristic::Power, "power")];

/// Light-sampling methods (`--light-sampling`).
pub const LIGHT_SAMPLING: &[(LightSampling, &str)] = &[
    (LightSampling::Area, "area (env. map: uniform)"),
    (
        LightSampling::SolidAngle,
        "solid angle (env. map: importance)",
    ),
    (
        LightSampling::SolidAngleCosine,
        "solid angle × cos warp (Hart 2020)",
    ),
    (
        LightSampling::Adaptive,
        "adaptive: area where small, else solid angle",
    ),
    (
        LightSampling::ProjectedSolidAngle,
        "projected solid angle, cos-weighted (Peters 2021)",
    ),
];

/// Light-selection rules (`--light-selection`).
pub const LIGHT_SELECTION: &[(LightSelection, &str)] = &[
    (LightSelection::Power, "power"),
    (LightSelection::Bvh, "bvh"),
];

/// Samplers (`--sampler`).
pub const SAMPLERS: &[(SamplerKind, &str)] = &[
    (SamplerKind::Independent, "independent"),
    (SamplerKind::Sobol, "sobol (Owen-scrambled)"),
];

/// The name of `value` in `table` (`?` if missing, which the tests rule out).
pub fn name_in<T: PartialEq>(table: &[(T, &'static str)], value: &T) -> &'static str {
    table
        .iter()
        .find(|(v, _)| v == value)
        .map_or("?", |(_, n)| n)
}

/// A combo box over `table`; true when the user picked another value.
pub fn menu<T: PartialEq + Copy>(
    ui: &mut egui::Ui,
    label: &str,
    value: &mut T,
    table: &[(T, &'static str)],
) -> bool {
    super::controls::combo(
        ui,
        label,
        value,
        &table.iter().map(|(v, _)| *v).collect::<Vec<_>>(),
        |v| name_in(table, &v).into(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The variants of an enum, listed in a `match` so that a new variant stops this compiling.
    macro_rules! variants {
        ($t:ident: $($v:ident),+) => {{
            let _exhaustive = |x: $t| match x { $($t::$v)|+ => () };
            vec![$($t::$v),+]
        }};
    }

    fn check<T: PartialEq + std::fmt::Debug>(table: &[(T, &'static str)], all: Vec<T>) {
        for v in &all {
            assert!(table.iter().any(|(t, _)| t == v), "{v:?} has no menu entry");
        }
        // Names are unique within a menu (the UI tests pick entries by name).
        let mut names: Vec<_> = table.iter().map(|(_, n)| *n).collect();
        names.sort();
        names.dedup();
        assert_eq!((names.len(), table.len()), (all.len(), all.len()));
    }

    /// Every variant has exactly one menu entry, and a new variant stops this test compiling
    /// until it has its line in the table above.
    #[test]
    fn every_variant_is_in_its_menu() {
        check(
            LIGHT_SAMPLING,
            variants!(
                LightSampling: Area,
                SolidAngle,
                SolidAngleCosine,
                Adaptive,
                ProjectedSolidAngle
            ),
        );
        check(LIGHT_SELECTION, variants!(LightSelection: Power, Bvh));
        check(SAMPLERS, variants!(SamplerKind: Independent, Sobol));
        check(BACKENDS, variants!(Backend: Cpu, Gpu));
        check(HEURISTICS, variants!(Heuristic: Balance, Power));
    }
}
