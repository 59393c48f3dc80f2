//! Textures: a value that varies over a surface's texture coordinates `(u, v)`, for a material's
//! albedo, reflectance and roughness and a shape's emission. A closed set, dispatched by `match`:
//! a constant, a bitmap (PNG, JPEG, EXR), a procedural checkerboard, and a mesh's own attribute
//! (which varies over the mesh's triangles, not over `uv`: a lookup is at a [`TexPoint`]).
//!
//! Conventions (those of Mitsuba 3.9.1's `bitmap` and `checkerboard` plugins, so that a Mitsuba
//! reference of a textured scene can agree with lumis):
//!
//! * **Texture space.** A lookup first maps `uv' = uv · uv_scale + uv_offset` per axis (a subset
//!   of Mitsuba's `to_uv`: the 3×3 affine matrix `[[su, 0, ou], [0, sv, ov], [0, 0, 1]]`, i.e. the
//!   4×4 `[[su,0,0,ou], [0,sv,0,ov], [0,0,1,0], [0,0,0,1]]` of which Mitsuba drops the z row and
//!   column). [`UvTransform`].
//! * **Orientation.** `u` runs along a row, left to right; `v` runs down the columns: `v = 0` is
//!   the image file's *top* row (row 0, as every image here), `v = 1` its bottom edge. This is
//!   Mitsuba's (its texture tensor is the bitmap's rows in file order) and glTF's convention.
//!   OBJ's texture coordinates have `v = 0` at the bottom; Mitsuba flips them when it loads an
//!   OBJ (`flip_tex_coords`, default true) and not when it loads a PLY (default false).
//! * **Texel centres.** Texel `(i, j)` (column, row) of a `W × H` bitmap has its centre at
//!   `uv' = ((i + ½)/W, (j + ½)/H)`: the continuous texel coordinate is `x = u'·W − ½`,
//!   `y = v'·H − ½`, and bilinear filtering blends the texels `⌊x⌋, ⌊x⌋+1` (weights
//!   `1 − {x}, {x}`) and likewise in `y`. [`bitmap::axis_lookup`].
//! * **Wrap modes** act on those integer texel indices, per axis ([`WrapMode`]): `repeat`
//!   (index mod W), `mirror` (… 1 0 | 0 1 … W−1 | W−1 … : every other period reflected, the edge
//!   texel repeated) and `clamp` (to [0, W−1]).
//! * **Colour.** Texels are linear RGB `f32`, decoded once at load ([`load`]): 8- and 16-bit
//!   files (PNG, JPEG) are sRGB-decoded unless loaded `raw` (data such as roughness); float files
//!   (EXR, PFM) are linear. Alpha is dropped, grey is copied to R, G and B.
//! * **Scalar slots** (roughness) read one value: by default the luminance of the RGB value with
//!   Mitsuba's coefficients ([`luminance`]: what Mitsuba's `eval_1` returns for an RGB bitmap),
//!   or one chosen channel ([`Channel`]; glTF keeps roughness in G and metallic in B).
//!
//! A texture never changes after it is built; bitmaps share their texels through an `Arc`.
//!
//! WGSL twin: `textures/mod.wgsl` (uploaded by `gpu/scene/textures.rs`).

pub mod bitmap;
pub mod checkerboard;
pub mod load;
pub mod mesh_attribute;

#[cfg(test)]
mod bitmap_tests;

pub use bitmap::{BitmapOptions, BitmapTexture, WrapMode};
pub use checkerboard::Checkerboard;
pub use mesh_attribute::MeshAttributeTexture;

use crate::geometry::mesh_attributes::MeshAttributes;
use glam::{DVec2, Vec2, Vec3};

/// Where a texture is looked up: the texture coordinates, and on a mesh triangle that has an
/// attribute record, that record and the barycentrics (what [`Texture::MeshAttribute`] reads).
/// A bare `uv` converts into one off any mesh.
#[derive(Clone, Copy, Debug)]
pub struct TexPoint<'a> {
    /// Texture coordinates.
    pub uv: Vec2,
    /// The mesh triangle, if the point is on one with attributes.
    pub mesh: Option<MeshPoint<'a>>,
}

/// A point of a mesh triangle, in the terms its attributes are found by.
#[derive(Clone, Copy, Debug)]
pub struct MeshPoint<'a> {
    /// The scene's mesh attributes.
    pub attributes: &'a MeshAttributes,
    /// The triangle's index into [`MeshAttributes::triangles`].
    pub attr: u32,
    /// Barycentrics `(b1, b2)`.
    pub b: Vec2,
}

impl From<Vec2> for TexPoint<'static> {
    fn from(uv: Vec2) -> TexPoint<'static> {
        TexPoint { uv, mesh: None }
    }
}

/// A texture: RGB (linear) as a function of the texture coordinates.
#[derive(Clone, Debug, PartialEq)]
pub enum Texture {
    /// The same value everywhere.
    Constant(Vec3),
    /// An image, bilinearly filtered.
    Bitmap(BitmapTexture),
    /// Two colours in a checkerboard of 2 × 2 squares per unit of `uv'`.
    Checkerboard(Checkerboard),
    /// A mesh's vertex or face attribute.
    MeshAttribute(MeshAttributeTexture),
}

impl Texture {
    /// Its resolution in texels, Mitsuba's `Texture::resolution`: a bitmap's size, `(1, 1)` for
    /// the others (a projector's aspect ratio).
    pub fn resolution(&self) -> (u32, u32) {
        match self {
            Texture::Bitmap(b) => b.size(),
            Texture::Constant(_) | Texture::Checkerboard(_) | Texture::MeshAttribute(_) => (1, 1),
        }
    }

    /// The linear RGB value at `at` (a [`TexPoint`], or texture coordinates off any mesh).
    #[inline]
    pub fn eval<'a>(&self, at: impl Into<TexPoint<'a>>) -> Vec3 {
        let at = at.into();
        match self {
            Texture::Constant(c) => *c,
            Texture::Bitmap(b) => b.eval(at.uv),
            Texture::Checkerboard(c) => c.eval(at.uv),
            Texture::MeshAttribute(m) => m.eval(at),
        }
    }

    /// The gradient of the luminance at `uv` with respect to (u, v): a bitmap's
    /// [`BitmapTexture::eval_1_grad`]; 0 for a constant; `None` for a checkerboard, whose value
    /// jumps, and a mesh attribute (Mitsuba's have no gradient either; the front ends refuse
    /// them as bump maps).
    #[inline]
    pub fn eval_1_grad(&self, uv: Vec2) -> Option<Vec2> {
        match self {
            Texture::Constant(_) => Some(Vec2::ZERO),
            Texture::Bitmap(b) => Some(b.eval_1_grad(uv)),
            Texture::Checkerboard(_) | Texture::MeshAttribute(_) => None,
        }
    }

    /// The value at `at` for a scalar parameter (roughness): a bitmap's [`Channel`], else the
    /// [`luminance`] (a one-component mesh attribute's component: it is stored grey).
    #[inline]
    pub fn eval_scalar<'a>(&self, at: impl Into<TexPoint<'a>>) -> f32 {
        self.channel().pick(self.eval(at))
    }

    /// The average of [`Texture::eval`] over the unit square of `uv` (exact, not sampled), for
    /// display and light power. A surface whose texture coordinates cover another region
    /// averages differently.
    pub fn mean(&self) -> Vec3 {
        match self {
            Texture::Constant(c) => *c,
            Texture::Bitmap(b) => b.mean(),
            Texture::Checkerboard(c) => c.mean(),
            Texture::MeshAttribute(m) => m.mean,
        }
    }

    /// The average of [`Texture::eval_scalar`] over the unit square (channels are linear, so
    /// this is the channel of [`Texture::mean`]).
    pub fn mean_scalar(&self) -> f32 {
        self.channel().pick(self.mean())
    }

    /// Per channel, the largest value [`Texture::eval`] returns at any `uv`, inside the unit
    /// square or not (a bound for lights and range checks).
    pub fn max(&self) -> Vec3 {
        match self {
            Texture::Constant(c) => *c,
            Texture::Bitmap(b) => b.max(),
            Texture::Checkerboard(c) => c.color0.max(c.color1),
            Texture::MeshAttribute(m) => m.max,
        }
    }

    /// The largest value [`Texture::eval_scalar`] returns at any `uv`.
    pub fn max_scalar(&self) -> f32 {
        match self {
            Texture::Constant(c) => Channel::Luminance.pick(*c),
            Texture::Bitmap(b) => b.max_scalar(),
            Texture::Checkerboard(c) => luminance(c.color0).max(luminance(c.color1)),
            // Stored grey where scalar slots may read it.
            Texture::MeshAttribute(m) => luminance(m.max),
        }
    }

    /// Whether the value is the same everywhere.
    pub fn is_constant(&self) -> bool {
        matches!(self, Texture::Constant(_))
    }

    /// Whether the value depends on the texture coordinates (not a constant, not a mesh
    /// attribute): what a shape's texture coordinates matter for.
    pub fn reads_uv(&self) -> bool {
        matches!(self, Texture::Bitmap(_) | Texture::Checkerboard(_))
    }

    /// The channel read by [`Texture::eval_scalar`].
    pub fn channel(&self) -> Channel {
        match self {
            Texture::Bitmap(b) => b.options().channel,
            _ => Channel::Luminance,
        }
    }
}

/// `uv' = uv · scale + offset`, per axis: the texture-space map of every non-constant texture.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UvTransform {
    /// `[su, sv]`; any finite values (negative flips, 0 freezes an axis).
    pub scale: Vec2,
    /// `[ou, ov]`, added after scaling.
    pub offset: Vec2,
}

impl UvTransform {
    /// `uv' = uv`.
    pub const IDENTITY: UvTransform = UvTransform {
        scale: Vec2::ONE,
        offset: Vec2::ZERO,
    };

    /// `uv · scale + offset`.
    #[inline]
    pub fn apply(&self, uv: Vec2) -> Vec2 {
        uv * self.scale + self.offset
    }

    /// Per axis, the interval `[lo, hi]` of `uv'` that the unit square of `uv` maps onto.
    fn unit_square_image(&self) -> [(f64, f64); 2] {
        let (s, o) = (self.scale.as_dvec2(), self.offset.as_dvec2());
        let ends = |s: f64, o: f64| (o.min(o + s), o.max(o + s));
        let DVec2 { x: su, y: sv } = s;
        [ends(su, o.x), ends(sv, o.y)]
    }
}

impl Default for UvTransform {
    fn default() -> Self {
        UvTransform::IDENTITY
    }
}

/// What a scalar parameter reads of an RGB texture.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Channel {
    /// [`luminance`] (Mitsuba 3's rule for an RGB bitmap in a scalar slot).
    #[default]
    Luminance,
    /// Red.
    R,
    /// Green (glTF's roughness).
    G,
    /// Blue (glTF's metallic).
    B,
}

impl Channel {
    /// The scalar of `c`.
    #[inline]
    pub fn pick(self, c: Vec3) -> f32 {
        match self {
            Channel::Luminance => luminance(c),
            Channel::R => c.x,
            Channel::G => c.y,
            Channel::B => c.z,
        }
    }

    /// The name in the scene format (`"luminance"`, `"r"`, `"g"`, `"b"`).
    pub fn name(self) -> &'static str {
        match self {
            Channel::Luminance => "luminance",
            Channel::R => "r",
            Channel::G => "g",
            Channel::B => "b",
        }
    }
}

/// Mitsuba 3's luminance coefficients for R, G and B ([`luminance`]; the GPU's prelude too).
pub const LUMINANCE_WEIGHTS: [f32; 3] = [0.212_671, 0.715_160, 0.072_169];

/// Luminance with Mitsuba 3's coefficients (`0.212671, 0.715160, 0.072169`, its
/// `luminance()`), so that a scalar slot reads what Mitsuba's `eval_1` reads; a grey value is
/// returned exactly (Mitsuba keeps a grey image as one channel and reads it unchanged).
/// [`crate::math::luminance`] (rounded Rec. 709) stays what light power uses.
#[inline]
pub fn luminance(c: Vec3) -> f32 {
    if c.x == c.y && c.y == c.z {
        c.x
    } else {
        let [r, g, b] = LUMINANCE_WEIGHTS;
        c.x * r + c.y * g + c.z * b
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn luminance_is_mitsubas_and_exact_on_grey() {
        assert_eq!(luminance(Vec3::new(1.0, 0.0, 0.0)), 0.212_671);
        assert_eq!(luminance(Vec3::new(0.0, 1.0, 0.0)), 0.715_160);
        assert_eq!(luminance(Vec3::new(0.0, 0.0, 1.0)), 0.072_169);
        for x in [0.3f32, 0.1, 0.7, 1e-7] {
            assert_eq!(luminance(Vec3::splat(x)), x);
        }
        let c = Vec3::new(0.2, 0.5, 0.9);
        assert_eq!(Channel::G.pick(c), 0.5);
        assert_eq!(Channel::B.pick(c), 0.9);
        assert_eq!(Channel::R.pick(c), 0.2);
    }

    #[test]
    fn constant_texture() {
        let t = Texture::Constant(Vec3::new(0.25, 0.5, 1.0));
        for uv in [Vec2::ZERO, Vec2::new(3.7, -2.2)] {
            assert_eq!(t.eval(uv), Vec3::new(0.25, 0.5, 1.0));
        }
        assert_eq!(t.mean(), t.max());
        assert!(t.is_constant());
        assert_eq!(t.eval_scalar(Vec2::ZERO), luminance(t.mean()));
    }

    #[test]
    fn uv_transform_scales_then_offsets() {
        let t = UvTransform {
            scale: Vec2::new(4.0, -2.0),
            offset: Vec2::new(0.5, 1.0),
        };
        assert_eq!(t.apply(Vec2::new(0.25, 0.5)), Vec2::new(1.5, 0.0));
        assert_eq!(t.unit_square_image(), [(0.5, 4.5), (-1.0, 1.0)]);
        assert_eq!(UvTransform::default(), UvTransform::IDENTITY);
    }
}
