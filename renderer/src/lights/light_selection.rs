//! Which light next-event estimation samples: the two selection rules, dispatched over a closed
//! set ([`crate::scene::Scene::select_light`], [`crate::scene::Scene::light_pmf`]).
//! WGSL twin: `lights/light_bvh.wgsl` (`light_select`, `light_select_pmf`), switching on the same
//! variant order (`LIGHT_SELECTION_*`, [`crate::gpu::scene::LightSelectionTag`]).

/// How a light is chosen for next-event estimation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum LightSelection {
    /// In proportion to emitted power, wherever the receiver is
    /// ([`crate::lights::LightSampler`]).
    #[default]
    Power,
    /// By importance at the receiving point and normal: power, distance and orientation bounds
    /// in a light BVH ([`crate::lights::LightBvh`]). Costs a tree descent per choice; pays off
    /// where many lights are far or face away, e.g. emitting meshes with many triangles.
    Bvh,
}

impl LightSelection {
    /// The name the CLI spells.
    pub fn name(self) -> &'static str {
        match self {
            LightSelection::Power => "power",
            LightSelection::Bvh => "bvh",
        }
    }
}
