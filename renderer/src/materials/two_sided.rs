//! A two-sided pair: a front material and a back material on one surface, Mitsuba's `twosided`
//! with two BSDFs (`src/bsdfs/twosided.cpp`). A path that arrives on the surface's front sees the
//! front material; one that arrives on its back sees the back material, as if from that
//! material's own front: Mitsuba negates the z of both directions before the back BSDF sees
//! them, lumis flips the normals (`integrator/path.rs`), the same mirror. A material with
//! `"two_sided": true` is the pair of itself with itself.
//!
//! The side is the geometric normal's, which decides sides everywhere in lumis
//! (docs/shading-normals.md); Mitsuba takes the shading normal's. The two differ only where the
//! shading and geometric normals disagree about the viewing direction, where lumis' rule already
//! ends the path. Neither part transmits (Mitsuba refuses that too): a transmitting material's
//! two sides are its two media, and a pair would have no back to give it.
//!
//! A pair holds material indices and is resolved with the mixes, before textures
//! ([`crate::scene::Scene::resolve`]): parts may be mixes, mixes may hold pairs.
//!
//! WGSL twin: `materials/two_sided.wgsl` (the record and the choice; `materials/mix.wgsl`'s
//! resolve loop calls it).

/// A two-sided pair of a scene: indices into its materials.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TwoSided {
    /// The material seen from the front (the side the geometric normal points to).
    pub front: u32,
    /// The material seen from the back.
    pub back: u32,
}

impl TwoSided {
    /// The material a path sees that arrives on the back (`back`) or on the front.
    #[inline]
    pub fn choose(&self, back: bool) -> u32 {
        if back { self.back } else { self.front }
    }
}
