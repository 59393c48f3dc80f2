//! What a BSDF-only estimate leaves out: delta lights (point, spot, directional, projector;
//! [`lumis::lights::Light::is_delta`]) occupy no area and no solid angle, so no BSDF-sampled
//! ray ever hits one and only next-event estimation finds them. A render whose strategy never
//! samples lights (`bsdf`, or a mixture of weight 0) therefore excludes their light entirely.
//! [`missed_delta_lights`] decides that, once, for `lumis render` and `lumis bench` (their
//! [`note`] on stderr) and for the viewer (the pane's caption, [`CAPTION`]).

use lumis::integrator::Strategy;
use lumis::scene::Scene;

/// What the viewer adds to the caption of a pane that [`missed_delta_lights`] applies to.
pub const CAPTION: &str = "delta lights excluded";

/// Whether `strategy` never samples a light: BSDF sampling alone, or a one-sample mixture that
/// picks light sampling with probability 0.
pub fn bsdf_only(strategy: Strategy) -> bool {
    match strategy {
        Strategy::Bsdf => true,
        Strategy::Mixture { light_weight } => light_weight <= 0.0,
        Strategy::Light | Strategy::Mis { .. } | Strategy::MisOptimal => false,
    }
}

/// The kinds (`point`, `spot`, `directional`, `projector`; one entry per light, in the scene's
/// order) of the delta lights of `scene` that a render with `strategy` never finds: all of them
/// when the strategy is [`bsdf_only`], none otherwise. Lights that emit nothing are not in the
/// built scene and so not here.
pub fn missed_delta_lights(strategy: Strategy, scene: &Scene) -> Vec<&'static str> {
    if !bsdf_only(strategy) {
        return Vec::new();
    }
    (scene.lights.iter())
        .filter(|l| l.is_delta())
        .map(|l| l.kind_name())
        .collect()
}

/// The command line's one-line note for the lights [`missed_delta_lights`] returned (`None`
/// when it returned none): how many, their kinds (each once, in order), what lacks their light
/// (`missing_from`: "this image", "the bsdf curve"), and what to use instead.
pub fn note(missed: &[&str], missing_from: &str) -> Option<String> {
    let mut kinds: Vec<&str> = Vec::new();
    for &k in missed {
        if !kinds.contains(&k) {
            kinds.push(k);
        }
    }
    let kinds = kinds.join(", ");
    let (lights, their) = match missed.len() {
        0 => return None,
        1 => ("delta light".to_owned(), "its"),
        n => (format!("{n} delta lights"), "their"),
    };
    Some(format!(
        "note: BSDF sampling alone never finds the scene's {lights} ({kinds}): {their} light is \
         missing from {missing_from}; use light, mis, mixture (with a weight above 0) or \
         mis-optimal"
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use lumis::integrator::Heuristic;

    #[test]
    fn only_strategies_that_never_sample_lights_miss_them() {
        assert!(bsdf_only(Strategy::Bsdf));
        assert!(bsdf_only(Strategy::Mixture { light_weight: 0.0 }));
        assert!(!bsdf_only(Strategy::Mixture { light_weight: 0.1 }));
        assert!(!bsdf_only(Strategy::Light));
        assert!(!bsdf_only(Strategy::MisOptimal));
        assert!(!bsdf_only(Strategy::Mis {
            heuristic: Heuristic::Power
        }));
    }

    #[test]
    fn the_note_counts_the_lights_and_names_each_kind_once() {
        assert_eq!(note(&[], "this image"), None);
        let one = note(&["directional"], "the bsdf curve").unwrap();
        assert!(
            one.contains(
                "the scene's delta light (directional): its light is missing from the \
                          bsdf curve;"
            ),
            "{one}"
        );
        let three = note(&["point", "spot", "point"], "this image").unwrap();
        assert!(
            three.starts_with("note: ")
                && three.contains(
                    "the scene's 3 delta lights (point, spot): their light is \
                                   missing from this image;"
                )
                && !three.contains('\n'),
            "{three}"
        );
    }
}
