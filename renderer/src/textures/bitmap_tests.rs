//! Bitmap lookups against Mitsuba 3.9.1 / Dr.Jit's definitions: texel centres, bilinear
//! weights, the three wrap modes, orientation, and the exact mean against a brute-force one.

use super::bitmap::{BitmapOptions, BitmapTexture, WrapMode, axis_lookup, axis_mean_weights};
use super::{Channel, Texture, UvTransform, luminance};
use crate::image_io::Image;
use glam::{DVec3, Vec2, Vec3};
use std::sync::Arc;

/// A `w × h` image whose texel (i, j) is `(i, j, 10 + i + w·j)`, so every texel is distinct.
fn numbered(w: u32, h: u32) -> Arc<Image> {
    let data = (0..h)
        .flat_map(|j| (0..w).map(move |i| Vec3::new(i as f32, j as f32, (10 + i + w * j) as f32)))
        .collect();
    Arc::new(Image {
        width: w,
        height: h,
        data,
    })
}

fn texture(image: Arc<Image>, wrap: WrapMode, uv: UvTransform) -> BitmapTexture {
    BitmapTexture::new(
        image,
        BitmapOptions {
            wrap,
            uv,
            ..BitmapOptions::default()
        },
    )
}

/// Dr.Jit's `tex_wrap` (include/drjit/texture_impl.h at Mitsuba 3.9.1's Dr.Jit), transcribed
/// with C's truncating division, to check [`WrapMode::index`] against.
fn drjit_wrap(mode: WrapMode, pos: i64, res: i64) -> i64 {
    if mode == WrapMode::Clamp {
        return pos.clamp(0, res - 1);
    }
    let value_shift_neg = if pos < 0 { pos + 1 } else { pos };
    let div = value_shift_neg / res; // truncates, as C does
    let mut m = pos - div * res;
    if m < 0 {
        m += res;
    }
    if mode == WrapMode::Mirror && !(((div & 1) == 0) ^ (pos < 0)) {
        m = res - 1 - m;
    }
    m
}

#[test]
fn wrap_modes_match_drjit() {
    for mode in [WrapMode::Repeat, WrapMode::Mirror, WrapMode::Clamp] {
        for n in 1..6u32 {
            for i in -40..40i64 {
                assert_eq!(
                    mode.index(i, n) as i64,
                    drjit_wrap(mode, i, n as i64),
                    "{mode:?} i={i} n={n}"
                );
            }
        }
    }
    // The sequences spelled out for n = 3 from i = −4.
    let seq = |m: WrapMode| (-4..6).map(|i| m.index(i, 3)).collect::<Vec<_>>();
    assert_eq!(seq(WrapMode::Repeat), [2, 0, 1, 2, 0, 1, 2, 0, 1, 2]);
    assert_eq!(seq(WrapMode::Mirror), [2, 2, 1, 0, 0, 1, 2, 2, 1, 0]);
    assert_eq!(seq(WrapMode::Clamp), [0, 0, 0, 0, 0, 1, 2, 2, 2, 2]);
    assert_eq!(WrapMode::Repeat.index(i64::MAX, 7), (i64::MAX % 7) as u32);
}

#[test]
fn bilinear_weights_at_texel_centres_and_edges() {
    let n = 4;
    for wrap in [WrapMode::Repeat, WrapMode::Mirror, WrapMode::Clamp] {
        // At a texel centre (i + ½)/n: all weight on texel i.
        for i in 0..n {
            let (idx, w) = axis_lookup((i as f32 + 0.5) / n as f32, n, wrap);
            assert_eq!((idx[0], w), (i, [1.0, 0.0]), "{wrap:?} centre {i}");
        }
        // On an inner texel edge i/n: half and half between i − 1 and i.
        for i in 1..n {
            let (idx, w) = axis_lookup(i as f32 / n as f32, n, wrap);
            assert_eq!((idx, w), ([i - 1, i], [0.5, 0.5]), "{wrap:?} edge {i}");
        }
        // A quarter of the way from centre 1 to centre 2.
        let (idx, w) = axis_lookup(1.75 / n as f32, n, wrap);
        assert_eq!((idx, w), ([1, 2], [0.75, 0.25]));
    }
    // The outer edges u = 0 and u = 1 blend texel −1 or n, which each mode maps differently.
    let edge = |t: f32, m| axis_lookup(t, n, m).0;
    assert_eq!(edge(0.0, WrapMode::Repeat), [3, 0]);
    assert_eq!(edge(0.0, WrapMode::Mirror), [0, 0]);
    assert_eq!(edge(0.0, WrapMode::Clamp), [0, 0]);
    assert_eq!(edge(1.0, WrapMode::Repeat), [3, 0]);
    assert_eq!(edge(1.0, WrapMode::Mirror), [3, 3]);
    assert_eq!(edge(1.0, WrapMode::Clamp), [3, 3]);
    assert_eq!(axis_lookup(0.0, n, WrapMode::Repeat).1, [0.5, 0.5]);
    // One texel: every lookup is that texel.
    for t in [-3.3, 0.0, 0.2, 0.99, 7.5] {
        for m in [WrapMode::Repeat, WrapMode::Mirror, WrapMode::Clamp] {
            assert_eq!(axis_lookup(t, 1, m).0, [0, 0]);
        }
    }
}

#[test]
fn lookups_interpolate_the_right_texels() {
    let img = numbered(4, 3);
    let t = texture(img.clone(), WrapMode::Repeat, UvTransform::IDENTITY);
    let texel = |i: u32, j: u32| img.data[(j * 4 + i) as usize];
    // Texel centres return the texel exactly: v = 0 is row 0, the file's top row.
    for j in 0..3 {
        for i in 0..4 {
            let uv = Vec2::new((i as f32 + 0.5) / 4.0, (j as f32 + 0.5) / 3.0);
            assert_eq!(t.eval(uv), texel(i, j), "texel ({i}, {j})");
        }
    }
    // Halfway between four centres: their average.
    let uv = Vec2::new(2.0 / 4.0, 1.0 / 3.0);
    let avg = (texel(1, 0) + texel(2, 0) + texel(1, 1) + texel(2, 1)) / 4.0;
    assert!((t.eval(uv) - avg).abs().max_element() < 1e-5);
    // A general point, against the bilinear formula written out.
    let (u, v) = (0.3f32, 0.55f32);
    let (x, y) = (u * 4.0 - 0.5, v * 3.0 - 0.5);
    let (fx, fy) = (x - x.floor(), y - y.floor());
    let (i, j) = (x.floor() as u32, y.floor() as u32);
    let want = texel(i, j) * (1.0 - fx) * (1.0 - fy)
        + texel(i + 1, j) * fx * (1.0 - fy)
        + texel(i, j + 1) * (1.0 - fx) * fy
        + texel(i + 1, j + 1) * fx * fy;
    assert!((t.eval(Vec2::new(u, v)) - want).abs().max_element() < 1e-5);
}

#[test]
fn each_wrap_mode_outside_the_unit_square() {
    let img = numbered(4, 3);
    let eval = |wrap, uv: Vec2| texture(img.clone(), wrap, UvTransform::IDENTITY).eval(uv);
    let close = |a: Vec3, b: Vec3| (a - b).abs().max_element() < 1e-4;
    for k in 0..40 {
        let uv = Vec2::new(k as f32 * 0.0253 + 0.01, 1.0 - k as f32 * 0.0219);
        // Repeat: period 1 on both axes.
        let r = eval(WrapMode::Repeat, uv);
        assert!(close(eval(WrapMode::Repeat, uv + Vec2::new(1.0, -2.0)), r));
        // Mirror: symmetric about 0 and 1, period 2.
        let m = eval(WrapMode::Mirror, uv);
        assert!(close(eval(WrapMode::Mirror, -uv), m), "{uv}");
        assert!(
            close(eval(WrapMode::Mirror, Vec2::splat(2.0) - uv), m),
            "{uv}"
        );
        assert!(
            close(eval(WrapMode::Mirror, uv + Vec2::splat(2.0)), m),
            "{uv}"
        );
        // Clamp: beyond the edge centres, the edge texels.
        let c = eval(WrapMode::Clamp, Vec2::new(-5.0 - uv.x, uv.y));
        assert!(
            close(c, eval(WrapMode::Clamp, Vec2::new(0.1, uv.y))),
            "{uv}"
        );
    }
    // The seam at u = 0: repeat blends the last and the first column, mirror and clamp do not.
    let v = 0.5 / 3.0;
    let (first, last) = (img.data[0], img.data[3]);
    assert_eq!(
        eval(WrapMode::Repeat, Vec2::new(0.0, v)),
        (first + last) * 0.5
    );
    assert_eq!(eval(WrapMode::Mirror, Vec2::new(0.0, v)), first);
    assert_eq!(eval(WrapMode::Clamp, Vec2::new(0.0, v)), first);
    assert_eq!(eval(WrapMode::Clamp, Vec2::new(7.0, v)), last);
}

#[test]
fn uv_transform_scale_and_channels() {
    let img = numbered(4, 3);
    let uv = UvTransform {
        scale: Vec2::new(2.0, -1.0),
        offset: Vec2::new(0.25, 1.0),
    };
    let base = texture(img.clone(), WrapMode::Repeat, UvTransform::IDENTITY);
    let moved = texture(img.clone(), WrapMode::Repeat, uv);
    for p in [Vec2::new(0.1, 0.2), Vec2::new(0.7, 0.9)] {
        assert_eq!(moved.eval(p), base.eval(p * uv.scale + uv.offset));
    }
    let opts = BitmapOptions {
        scale: Vec3::new(2.0, 0.5, 1.0),
        channel: Channel::G,
        ..BitmapOptions::default()
    };
    let scaled = Texture::Bitmap(BitmapTexture::new(img.clone(), opts));
    let p = Vec2::new(0.4, 0.6);
    assert_eq!(scaled.eval(p), base.eval(p) * opts.scale);
    assert_eq!(scaled.eval_scalar(p), base.eval(p).y * 0.5);
    assert_eq!(scaled.max(), Vec3::new(6.0, 1.0, 21.0));
    assert_eq!(scaled.max_scalar(), 1.0);
    let lum = Texture::Bitmap(base.clone());
    assert_eq!(lum.eval_scalar(p), luminance(base.eval(p)));
    assert_eq!(lum.max_scalar(), luminance(Vec3::new(3.0, 2.0, 21.0)));
}

/// The mean by the midpoint rule on a fine grid of `eval`.
fn brute_mean(t: &BitmapTexture, n: usize) -> DVec3 {
    let mut sum = DVec3::ZERO;
    for j in 0..n {
        for i in 0..n {
            let uv = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
            sum += t.eval(uv).as_dvec3();
        }
    }
    sum / (n * n) as f64
}

#[test]
fn mean_matches_a_brute_force_average() {
    let img = numbered(5, 3);
    let plain: DVec3 = img.data.iter().map(|t| t.as_dvec3()).sum::<DVec3>() / 15.0;
    for wrap in [WrapMode::Repeat, WrapMode::Mirror, WrapMode::Clamp] {
        for (scale, offset) in [
            (Vec2::ONE, Vec2::ZERO),
            (Vec2::new(3.0, 2.0), Vec2::ZERO),
            (Vec2::new(0.37, 0.61), Vec2::new(0.1, 0.05)),
            (Vec2::new(2.7, -1.3), Vec2::new(-0.6, 0.45)),
            (Vec2::new(-4.2, 5.5), Vec2::new(3.3, -7.1)),
            (Vec2::new(0.0, 1.0), Vec2::new(0.33, 0.0)),
        ] {
            let t = texture(img.clone(), wrap, UvTransform { scale, offset });
            let brute = brute_mean(&t, 1500);
            let exact = t.mean().as_dvec3();
            let err = ((exact - brute) / brute.max(DVec3::ONE))
                .abs()
                .max_element();
            assert!(
                err < 2e-4,
                "{wrap:?} scale {scale} offset {offset}: exact {exact} vs brute force {brute}"
            );
        }
        // Over the unit square every mode averages to the plain texel mean (Mitsuba's mean()).
        let t = texture(img.clone(), wrap, UvTransform::IDENTITY);
        assert!(
            (t.mean().as_dvec3() - plain).abs().max_element() < 1e-5,
            "{wrap:?}"
        );
    }
}

#[test]
fn axis_weights_sum_to_one_and_handle_huge_intervals() {
    for wrap in [WrapMode::Repeat, WrapMode::Mirror, WrapMode::Clamp] {
        for iv in [
            (0.0, 1.0),
            (-3.7, 2.2),
            (1e6, 1e6 + 2.5),
            (-1e9, 1e9),
            (0.3, 0.3),
        ] {
            let w = axis_mean_weights(7, wrap, iv);
            let s: f64 = w.iter().sum();
            assert!((s - 1.0).abs() < 1e-9, "{wrap:?} {iv:?}: sum {s}");
            assert!(w.iter().all(|&x| x >= -1e-12), "{wrap:?} {iv:?}: {w:?}");
        }
    }
    // Clamp over a huge interval: nearly all weight on the two edge texels, equally.
    let w = axis_mean_weights(4, WrapMode::Clamp, (-1e9, 1e9 + 1.0));
    assert!(
        (w[0] - 0.5).abs() < 1e-6 && (w[3] - 0.5).abs() < 1e-6,
        "{w:?}"
    );
}

/// `eval_1_grad` against central differences of the luminance of `eval` inside bilinear cells
/// (where the interpolant is smooth: away from texel centres, which its derivative jumps at), on
/// a non-square image with distinct texels, through a uv transform that scales u and v
/// differently and flips v, in each wrap mode. Catches swapped axes, a missing resolution or
/// transform factor, the wrong weights and a wrong sign.
#[test]
fn the_luminance_gradient_is_the_derivative_of_the_lookup() {
    let image = numbered(5, 3);
    let uv = UvTransform {
        scale: Vec2::new(1.7, -0.6),
        offset: Vec2::new(0.1, 0.2),
    };
    let mut checked = 0;
    for wrap in [WrapMode::Repeat, WrapMode::Mirror, WrapMode::Clamp] {
        let t = texture(image.clone(), wrap, uv);
        let lum = |p: Vec2| luminance(t.eval(p)) as f64;
        for i in 0..40 {
            for j in 0..40 {
                let p = Vec2::new(i as f32 / 40.0 + 0.003, j as f32 / 40.0 + 0.007);
                // Skip points within the step of a cell edge (texel centres) on either axis.
                let q = uv.apply(p) * Vec2::new(5.0, 3.0) - 0.5;
                let near = |x: f32, s: f32| (x - x.round()).abs() < 2e-3 * s;
                if near(q.x, 5.0 * 1.7) || near(q.y, 3.0 * 0.6) {
                    continue;
                }
                let h = 1e-4f32;
                let gu =
                    (lum(p + Vec2::new(h, 0.0)) - lum(p - Vec2::new(h, 0.0))) / (2.0 * h as f64);
                let gv =
                    (lum(p + Vec2::new(0.0, h)) - lum(p - Vec2::new(0.0, h))) / (2.0 * h as f64);
                let g = t.eval_1_grad(p);
                let tol = 2e-2 * (gu.abs() + gv.abs() + 1.0);
                assert!(
                    (g.x as f64 - gu).abs() < tol && (g.y as f64 - gv).abs() < tol,
                    "{wrap:?} at {p}: {g} vs ({gu}, {gv})"
                );
                checked += 1;
            }
        }
    }
    assert!(checked > 3000, "{checked}");
    // A constant has no gradient; a checkerboard, whose value jumps, none defined.
    assert_eq!(
        Texture::Constant(Vec3::ONE).eval_1_grad(Vec2::ZERO),
        Some(Vec2::ZERO)
    );
}
