//! Lights: every emitting shape is a one-sided area light; a constant background and an
//! environment map are lights at infinity; point, spot, directional lights and projectors are
//! deltas (Mitsuba's; [`Light::is_delta`]), which only light sampling finds. Each light samples a point (by area, or by solid angle where that is better) and reports
//! the solid-angle pdf of any direction, so every strategy and MIS can weigh the same events.
//!
//! Textured emission: an area light whose shape's `emission` is a texture holds the index of
//! that texture in [`crate::scene::Scene::emission_textures`] (`texture`; [`NONE`] for a
//! constant radiance). Its `le` is then only the radiance its selection weight assumes
//! ([`light_sampler::selection_radiance`]): a light does not know the scene's texture
//! coordinates, so the scene evaluates the texture at the sampled or hit point
//! ([`crate::scene::Scene::sample_light`], [`crate::scene::Scene::emitted`]), with the one rule
//! for "the uv of a point on a primitive" that materials use ([`crate::scene::Scene::uv_at`]).
//! The path tracer goes through those two functions only. Untextured lights do no extra work
//! beyond one comparison. The GPU backend mirrors it (`lights/mod.wgsl`).
//! WGSL twin: `lights/mod.wgsl`.

pub mod background;
pub mod directional;
pub mod disk;
pub mod envmap;
pub mod light_bounds;
pub mod light_bvh;
pub mod light_sampler;
pub mod light_selection;
pub mod point;
pub mod polygon;
pub mod projected;
pub mod projector;
pub mod quad;
pub mod sphere;
pub mod spot;
pub mod triangle;

pub use background::BackgroundLight;
pub use directional::DirectionalLight;
pub use disk::DiskLight;
pub use envmap::EnvmapLight;
pub use light_bounds::LightBounds;
pub use light_bvh::LightBvh;
pub use light_sampler::LightSampler;
pub use light_selection::LightSelection;
pub use point::PointLight;
pub use polygon::PolygonLight;
pub use projector::ProjectorLight;
pub use quad::QuadLight;
pub use sphere::SphereLight;
pub use spot::SpotLight;
pub use triangle::TriangleLight;

use crate::geometry::primitive::NONE;
use crate::geometry::ray::gamma;
use crate::textures::Texture;
use glam::{Vec2, Vec3};

/// How lights pick the point to sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum LightSampling {
    /// Uniform by area, pdf converted to solid angle (`d² / (|cos| · A)`); the infinite lights
    /// uniformly over the sphere of directions.
    Area,
    /// Uniform by solid angle where a shape supports it (spherical triangles and rectangles,
    /// spherical ellipses for disks, cones for spheres), by area elsewhere and where the solid
    /// angle is too small or too large for the spherical warps to be accurate. An environment map
    /// is importance-sampled.
    #[default]
    SolidAngle,
    /// [`LightSampling::SolidAngle`], with the spherical triangles and rectangles (of triangle,
    /// polygon and quad lights) sampled through a bilinear warp towards the receiver's |cos θ| at
    /// the light's corners first (Hart et al. 2020; pbrt-v4 does this whenever it knows the
    /// shading normal), so that the density is nearly proportional to cos θ dω: the cosine
    /// factor of the integrand is then mostly sampled away. Without a receiver normal (a zero
    /// `ns`), and for disks (whose ellipse warp has no corners to weight), spheres and infinite
    /// lights, the same as `SolidAngle`.
    SolidAngleCosine,
    /// Per light and shading point, whichever of area and solid-angle sampling pays: a planar
    /// light (triangle, quad, polygon, disk) is sampled by area where it looks small from the shading
    /// point ([`planar_solid_angle_estimate`] below [`ADAPTIVE_MIN_SOLID_ANGLE`]), since there
    /// the area density is nearly uniform in solid angle already and costs a fraction of the
    /// spherical warp, and by its spherical warp elsewhere. A polygon then samples one spherical
    /// triangle of its triangulation, picked in proportion to that triangle's estimated solid
    /// angle, instead of computing every triangle's exact solid angle per sample and per pdf.
    /// Spheres and infinite lights as with `SolidAngle`.
    Adaptive,
    /// Triangle, quad and polygon lights sampled in proportion to the receiver's cos θ over the
    /// part of the light above its horizon (Peters 2021: uniform in the light's orthographic
    /// projection onto the tangent disk, [`crate::sampling::projected_solid_angle`]), density
    /// `cos θ / Ω⊥`: a Lambertian receiver's direct light from a constant-radiance polygon has
    /// no variance outside penumbrae. A polygon picks a triangle of its triangulation in
    /// proportion to that triangle's clipped projected solid angle. Where the light is too small
    /// or too close to the horizon for f32 to sample it accurately
    /// ([`crate::sampling::projected_solid_angle::conditioned`]), without a receiver normal (a
    /// zero `ns`; see [`LightSampling::receiver_normal`]), and for disks, spheres and infinite
    /// lights, the same as `SolidAngle`.
    ProjectedSolidAngle,
}

/// [`LightSampling::Adaptive`] samples a planar light by area where its
/// [`planar_solid_angle_estimate`] is below this many steradians: there the area density seen
/// from the shading point is within about ±25% of uniform in solid angle (it varies as
/// `(1 ± r/d)²` for a light of radius `r` at distance `d`, `π r²/d² ≈ 0.05`), which costs little
/// variance next to the rest of the integrand, while solid-angle sampling costs several times as
/// much. Chosen among 0, 0.01, 0.05, 0.2 and 1 by equal-time efficiency on three scenes
/// (`docs/performance.md`, "Adaptive light sampling"); 0.2 already loses variance on
/// `analytic_polygon`.
pub const ADAPTIVE_MIN_SOLID_ANGLE: f32 = 0.05;

/// The solid angle (sr) a planar light of area `area`, centroid `c` and unit normal `n` would
/// subtend from `p` if it were small: `area · |cos θ| / d²` with `d` the distance to the centroid
/// and `θ` the angle there between `n` and the direction to `p` (the area density at the centroid
/// converted to solid angle, inverted). Infinite or NaN where `p` is at the centroid.
#[inline(always)]
pub fn planar_solid_angle_estimate(p: Vec3, c: Vec3, n: Vec3, area: f32) -> f32 {
    let d = p - c;
    let d2 = d.length_squared();
    area * n.dot(d).abs() / (d2 * d2.sqrt())
}

impl LightSampling {
    /// Whether shapes with a spherical warp use it (every method but [`LightSampling::Area`]).
    #[inline(always)]
    pub fn solid_angle(self) -> bool {
        self != LightSampling::Area
    }

    /// Whether a planar light of area `area`, centroid `c` and unit normal `n` is sampled from
    /// `p` by its spherical warp (where that warp is accurate) rather than by area: always for
    /// `SolidAngle` and `SolidAngleCosine`, never for `Area`, and for `Adaptive` where the light's
    /// [`planar_solid_angle_estimate`] reaches [`ADAPTIVE_MIN_SOLID_ANGLE`] (`sample` and `pdf`
    /// decide alike, from the same `p`).
    #[inline(always)]
    pub fn spherical_for(self, p: Vec3, c: Vec3, n: Vec3, area: f32) -> bool {
        match self {
            LightSampling::Area => false,
            LightSampling::SolidAngle
            | LightSampling::SolidAngleCosine
            | LightSampling::ProjectedSolidAngle => true,
            // NaN (p at the centroid) compares false: area, as for any method there.
            LightSampling::Adaptive => {
                planar_solid_angle_estimate(p, c, n, area) >= ADAPTIVE_MIN_SOLID_ANGLE
            }
        }
    }

    /// Whether planar lights are sampled by their projected solid angle for a receiver with
    /// shading normal `ns`: [`LightSampling::ProjectedSolidAngle`] with a normal.
    #[inline(always)]
    pub fn projects(self, ns: Vec3) -> bool {
        self == LightSampling::ProjectedSolidAngle && ns != Vec3::ZERO
    }

    /// The shading normal a receiver passes to [`Light::sample`] and [`Light::pdf`]: its own,
    /// except that a receiver that transmits light (a dielectric) passes none (zero) to
    /// [`LightSampling::ProjectedSolidAngle`], which samples only the hemisphere above the normal
    /// and would miss the light arriving from below; such a receiver is sampled by solid angle.
    #[inline(always)]
    pub fn receiver_normal(self, ns: Vec3, transmits: bool) -> Vec3 {
        if transmits && self == LightSampling::ProjectedSolidAngle {
            Vec3::ZERO
        } else {
            ns
        }
    }

    /// Whether spherical samples are warped towards the cosine for a receiver with shading
    /// normal `ns`: [`LightSampling::SolidAngleCosine`] with a normal.
    #[inline(always)]
    pub fn warps(self, ns: Vec3) -> bool {
        self == LightSampling::SolidAngleCosine && ns != Vec3::ZERO
    }

    /// `u` through the cosine warp of a receiver at `p` with shading normal `ns`, for a spherical
    /// warp whose sample square's corners go to the points `corners`
    /// ([`crate::sampling::cosine_corner_weights`]), and the warp's density there; `u` and 1
    /// where the method does not warp ([`LightSampling::warps`]).
    #[inline(always)]
    pub(crate) fn warp(self, p: Vec3, ns: Vec3, corners: [Vec3; 4], u: Vec2) -> (Vec2, f32) {
        if !self.warps(ns) {
            return (u, 1.0);
        }
        let w = crate::sampling::cosine_corner_weights(ns, corners.map(|c| c - p));
        let u = crate::sampling::sample_bilinear(u, w);
        (u, crate::sampling::bilinear_pdf(u, w))
    }

    /// The density of [`LightSampling::warp`] at the warped point `warped()` (the inverse of the
    /// spherical warp at the direction in question), 1 where the method does not warp; `warped`
    /// runs only where it does.
    #[inline(always)]
    pub(crate) fn warp_pdf(
        self,
        p: Vec3,
        ns: Vec3,
        corners: [Vec3; 4],
        warped: impl FnOnce() -> Vec2,
    ) -> f32 {
        if !self.warps(ns) {
            return 1.0;
        }
        let w = crate::sampling::cosine_corner_weights(ns, corners.map(|c| c - p));
        crate::sampling::bilinear_pdf(warped(), w)
    }
}

/// A point sampled on a light, as seen from a reference point.
#[derive(Clone, Copy, Debug)]
pub struct LightSample {
    /// Point on the light (meaningless for the background).
    pub p: Vec3,
    /// Error bound of `p`.
    pub p_error: Vec3,
    /// Unit normal of the light at `p` (towards its emitting side).
    pub n: Vec3,
    /// Unit direction from the reference point to `p`.
    pub wi: Vec3,
    /// Solid-angle pdf of `wi` (light selection not included).
    pub pdf: f32,
    /// Radiance arriving along `-wi` (for a textured light, see the module doc: its selection
    /// radiance until [`crate::scene::Scene::sample_light`] evaluates the texture).
    pub le: Vec3,
    /// Whether this is the background (shadow ray to infinity).
    pub infinite: bool,
    /// Barycentrics `(b1, b2)` of `p` in the sampled triangle of a triangle or polygon light
    /// (`p = (1−b1−b2)·v0 + b1·v1 + b2·v2`, as [`crate::geometry::SurfaceHit::b`]), for its
    /// texture coordinates; zero for the other lights, whose `p` says where the sample is.
    pub b: Vec2,
}

/// An emission texture of the scene, with the shape it belongs to (for messages).
#[derive(Clone, Debug)]
pub struct EmissionTexture {
    /// The radiance as a function of the shape's texture coordinates.
    pub texture: Texture,
    /// JSON path of the shape (`shapes[3]`).
    pub shape: String,
}

/// Every kind of light. The variant order is mirrored by the GPU backend's `switch`.
#[derive(Clone, Debug)]
pub enum Light {
    /// An emitting triangle (from `triangles` shapes).
    Triangle(TriangleLight),
    /// An emitting planar polygon, convex or not.
    Polygon(PolygonLight),
    /// An emitting parallelogram.
    Quad(QuadLight),
    /// An emitting disk.
    Disk(DiskLight),
    /// An emitting sphere (outwards).
    Sphere(SphereLight),
    /// The constant background.
    Background(BackgroundLight),
    /// An environment map.
    Envmap(EnvmapLight),
    /// A point light (a delta in position: [`Light::is_delta`]).
    Point(PointLight),
    /// A spot light (a delta in position).
    Spot(SpotLight),
    /// A directional light (a delta in direction, at infinity).
    Directional(DirectionalLight),
    /// A projector (a delta in position).
    Projector(ProjectorLight),
}

impl Light {
    /// Samples a direction towards the light from `p`, a receiver with shading normal `ns` (zero
    /// where there is none; only [`LightSampling::SolidAngleCosine`] and
    /// [`LightSampling::ProjectedSolidAngle`] read it); `None` when it
    /// contributes nothing from `p` (behind a one-sided emitter, a degenerate configuration).
    pub fn sample(&self, p: Vec3, ns: Vec3, u: Vec2, method: LightSampling) -> Option<LightSample> {
        let s = match self {
            Light::Triangle(l) => l.sample(p, ns, u, method),
            Light::Polygon(l) => l.sample(p, ns, u, method),
            Light::Quad(l) => l.sample(p, ns, u, method),
            Light::Disk(l) => l.sample(p, u, method),
            Light::Sphere(l) => l.sample(p, u, method),
            Light::Background(l) => l.sample(u),
            Light::Envmap(l) => l.sample(u, method),
            Light::Point(l) => l.sample(p),
            Light::Spot(l) => l.sample(p),
            Light::Directional(l) => l.sample(),
            Light::Projector(l) => l.sample(p),
        }?;
        let s = LightSample {
            pdf: s.pdf * crate::mutants::light_pdf(self.kind_tag()),
            ..s
        };
        (s.pdf > 0.0 && s.pdf.is_finite() && s.le.cmpgt(Vec3::ZERO).any()).then_some(s)
    }

    /// Solid-angle pdf with which [`Light::sample`] from `p` (shading normal `ns`) yields
    /// direction `wi` hitting the light at `y` with normal `ny` (`y`, `ny` unused for the infinite
    /// lights).
    pub fn pdf(
        &self,
        p: Vec3,
        ns: Vec3,
        wi: Vec3,
        y: Vec3,
        ny: Vec3,
        method: LightSampling,
    ) -> f32 {
        self.pdf_unmutated(p, ns, wi, y, ny, method) * crate::mutants::light_pdf(self.kind_tag())
    }

    /// Index of the light's emission texture in [`crate::scene::Scene::emission_textures`], or
    /// [`NONE`] where it emits its constant `le` (always for the infinite lights).
    #[inline(always)]
    pub fn texture(&self) -> u32 {
        match self {
            Light::Triangle(l) => l.texture,
            Light::Polygon(l) => l.texture,
            Light::Quad(l) => l.texture,
            Light::Disk(l) => l.texture,
            Light::Sphere(l) => l.texture,
            Light::Spot(l) => l.texture,
            Light::Projector(l) => l.texture,
            Light::Background(_) | Light::Envmap(_) | Light::Point(_) | Light::Directional(_) => {
                NONE
            }
        }
    }

    /// Makes an area light emit emission texture `texture` ([`Light::texture`]), or a spot or
    /// projector project it; `false` (and no change) for the other lights, which have no texture
    /// coordinates.
    pub fn set_texture(&mut self, texture: u32) -> bool {
        let slot = match self {
            Light::Triangle(l) => &mut l.texture,
            Light::Polygon(l) => &mut l.texture,
            Light::Quad(l) => &mut l.texture,
            Light::Disk(l) => &mut l.texture,
            Light::Sphere(l) => &mut l.texture,
            Light::Spot(l) => &mut l.texture,
            Light::Projector(l) => &mut l.texture,
            Light::Background(_) | Light::Envmap(_) | Light::Point(_) | Light::Directional(_) => {
                return false;
            }
        };
        *slot = texture;
        true
    }

    /// Whether the light is at infinity (a background, an environment map, a directional
    /// light): its samples are directions, not points.
    pub fn is_infinite(&self) -> bool {
        matches!(
            self,
            Light::Background(_) | Light::Envmap(_) | Light::Directional(_)
        )
    }

    /// Whether the light is a delta in position or direction (point, spot, directional,
    /// projector): light sampling finds it with "pdf" 1 and no other technique can (no ray hits
    /// it, [`Light::pdf`] is zero), so its samples take MIS weight 1, and BSDF sampling alone
    /// never sees it. Mitsuba's `EmitterFlags::Delta`.
    #[inline(always)]
    pub fn is_delta(&self) -> bool {
        matches!(
            self,
            Light::Point(_) | Light::Spot(_) | Light::Directional(_) | Light::Projector(_)
        )
    }

    /// The kind's name in the scene format (`triangle`, …, `point`, `spot`, `directional`,
    /// `projector`; `background` and `envmap` for the two at infinity), for messages and counts.
    pub fn kind_name(&self) -> &'static str {
        match self {
            Light::Triangle(_) => "triangle",
            Light::Polygon(_) => "polygon",
            Light::Quad(_) => "quad",
            Light::Disk(_) => "disk",
            Light::Sphere(_) => "sphere",
            Light::Background(_) => "background",
            Light::Envmap(_) => "envmap",
            Light::Point(_) => "point",
            Light::Spot(_) => "spot",
            Light::Directional(_) => "directional",
            Light::Projector(_) => "projector",
        }
    }

    /// This light's kind tag, for [`crate::mutants`].
    #[inline(always)]
    fn kind_tag(&self) -> u32 {
        crate::gpu::scene::LightTag::of(self).gpu_tag()
    }

    #[inline(always)]
    fn pdf_unmutated(
        &self,
        p: Vec3,
        ns: Vec3,
        wi: Vec3,
        y: Vec3,
        ny: Vec3,
        method: LightSampling,
    ) -> f32 {
        match self {
            Light::Triangle(l) => l.pdf(p, ns, wi, y, ny, method),
            Light::Polygon(l) => l.pdf(p, ns, wi, y, ny, method),
            Light::Quad(l) => l.pdf(p, ns, wi, y, ny, method),
            Light::Disk(l) => l.pdf(p, y, ny, method),
            Light::Sphere(l) => l.pdf(p, y, ny, method),
            Light::Background(_) => crate::sampling::uniform_sphere_pdf(),
            Light::Envmap(l) => l.pdf(wi, method),
            // No direction finds a delta light except the one its sample takes.
            Light::Point(_) | Light::Spot(_) | Light::Directional(_) | Light::Projector(_) => 0.0,
        }
    }

    /// Emitted power (luminance), used to pick lights in proportion to it (for a textured light,
    /// that of its selection radiance: [`light_sampler::selection_radiance`]).
    pub fn power(&self) -> f32 {
        let area_power =
            |area: f32, le: Vec3| std::f32::consts::PI * area * crate::math::luminance(le);
        match self {
            Light::Triangle(l) => area_power(l.area, l.le),
            Light::Polygon(l) => area_power(l.area, l.le),
            Light::Quad(l) => area_power(l.area, l.le),
            Light::Disk(l) => area_power(l.disk.area(), l.le),
            Light::Sphere(l) => area_power(l.sphere.area(), l.le),
            Light::Background(l) => l.power(),
            Light::Envmap(l) => l.power(),
            Light::Point(l) => l.power(),
            Light::Spot(l) => l.power(),
            Light::Directional(l) => l.power(),
            Light::Projector(l) => l.power(),
        }
    }

    /// Radiance the light emits along `-w_in` at a point with normal `n` (one-sided; `n` unused
    /// for the infinite lights, which emit along `-w_in` from direction `w_in`). For a textured
    /// light, its selection radiance where it faces `-w_in`: [`crate::scene::Scene::emitted`]
    /// evaluates the texture.
    pub fn radiance(&self, n: Vec3, w_in: Vec3) -> Vec3 {
        let le = match self {
            Light::Triangle(l) => l.le,
            Light::Polygon(l) => l.le,
            Light::Quad(l) => l.le,
            Light::Disk(l) => l.le,
            Light::Sphere(l) => l.le,
            Light::Background(l) => return l.le,
            Light::Envmap(l) => return l.eval(w_in),
            Light::Point(_) | Light::Spot(_) | Light::Directional(_) | Light::Projector(_) => {
                return Vec3::ZERO;
            }
        };
        if n.dot(w_in) < 0.0 { le } else { Vec3::ZERO }
    }
}

/// Converts an area density at `y` (normal `ny`) to a solid-angle density seen from `p`:
/// `pdf_A · d² / |cos θ_y|`. Zero where the conversion is singular (grazing or coincident points),
/// which only happens on sets of measure zero.
#[inline]
pub fn area_to_solid_angle(pdf_area: f32, p: Vec3, y: Vec3, ny: Vec3) -> f32 {
    let d = y - p;
    let dist2 = d.length_squared();
    let cos = ny.dot(d).abs() / dist2.sqrt();
    let pdf = pdf_area * dist2 / cos;
    if pdf.is_finite() && dist2 > 0.0 {
        pdf
    } else {
        0.0
    }
}

/// The light sample at barycentrics `b` of triangle `v` (normal `n`, radiance `le`), reached
/// along `wi` with solid-angle density `pdf`: spherical-triangle and projected-solid-angle
/// samples of triangles, quads' fans and polygons' triangles alike.
#[inline]
pub(crate) fn triangle_sample(
    v: &[Vec3; 3],
    b: [f32; 3],
    n: Vec3,
    le: Vec3,
    wi: Vec3,
    pdf: f32,
) -> LightSample {
    let y = b[0] * v[0] + b[1] * v[1] + b[2] * v[2];
    let err = gamma(6) * ((b[0] * v[0]).abs() + (b[1] * v[1]).abs() + (b[2] * v[2]).abs());
    LightSample {
        p: y,
        p_error: err,
        n,
        wi,
        pdf,
        le,
        infinite: false,
        b: Vec2::new(b[1], b[2]),
    }
}

/// Builds a light sample for a point `y` (normal `ny`) chosen with area density `pdf_area`.
#[inline]
pub(crate) fn area_sample(
    p: Vec3,
    y: Vec3,
    ny: Vec3,
    pdf_area: f32,
    le: Vec3,
) -> Option<LightSample> {
    let d = y - p;
    let dist = d.length();
    let wi = d / dist;
    // One-sided: the light must face p.
    // Written to also reject NaN.
    if ny.dot(wi).partial_cmp(&0.0) != Some(std::cmp::Ordering::Less) {
        return None;
    }
    let pdf = area_to_solid_angle(pdf_area, p, y, ny);
    Some(LightSample {
        p: y,
        p_error: gamma(6) * y.abs(),
        n: ny,
        wi,
        pdf,
        le,
        infinite: false,
        b: Vec2::ZERO,
    })
}
