//! Statistical tests of sampling routines: a χ² goodness-of-fit test of any direction sampler
//! against its own pdf (after Mitsuba 3's `ChiSquareTest` and Nori's warptest).
//!
//! * [`sampler`]: the [`DirectionalSampler`] trait the test checks.
//! * [`domain`]: the histogram's cells — (φ, 1 − cos θ) about an axis, optionally zoomed on a
//!   cap, over directions or half vectors.
//! * [`quadrature`]: adaptive Gauss–Legendre integration of the pdf over a cell.
//! * [`gamma`]: the regularized incomplete gamma function and the χ² tail.
//! * [`chi2`]: the test itself, [`ChiSquareTest`].
//! * [`histogram_image`]: observed | expected | residual pictures.
//! * Adapters: [`warp_sampler`], [`bsdf_sampler`], [`light_directions`], [`mixture_sampler`],
//!   [`selected_lights`] (light selection composed with light sampling).
//! * [`suite`]: every sampler of the project, by name.

pub mod bsdf_sampler;
pub mod chi2;
pub mod domain;
pub mod gamma;
pub mod histogram_image;
pub mod light_directions;
pub mod mixture_sampler;
pub mod precomputed;
pub mod quadrature;
pub mod sampler;
pub mod selected_lights;
pub mod suite;
pub mod warp_sampler;

pub use bsdf_sampler::BsdfSampler;
pub use chi2::{Chi2Result, ChiSquareTest};
pub use domain::Domain;
pub use histogram_image::{histogram_image, write_histogram_png};
pub use light_directions::LightDirections;
pub use mixture_sampler::Mixture;
pub use precomputed::Precomputed;
pub use sampler::{DirectionSample, DirectionalSampler};
pub use selected_lights::SelectedLightDirections;
pub use warp_sampler::Warp;
