// Textures, the twin of `textures/mod.rs`, `textures/bitmap.rs`, `textures/checkerboard.rs` and
// `textures/mesh_attribute.rs`
// (records and texels uploaded by `gpu/scene/textures.rs`): a `switch` in the variant order of
// `Texture` (Constant, Bitmap, Checkerboard, MeshAttribute); bitmaps filtered bilinearly by hand from
// `texture_texels` with the CPU's wrap modes on integer texel indices, the same expressions in
// the same order; the checkerboard; a scalar slot's channel. Compiled only under HAS_TEXTURES.
// `texture_eval` and `texture_eval_scalar` are what materials (and later emission) call.
//
// Record (RECORD_VEC4S = 4 vec4 in `vertex_data` from `params.textures`; a texture's id is its
// index):
//   h  = bits of (kind TEXTURE_*, wrap WRAP_*, channel CHANNEL_*, first texel);
//   uv = (su, sv, ou, ov): uv' = uv · (su, sv) + (ou, ov);
//   c0 = (the constant, the bitmap's scale or the checkerboard's color0; bits of the width);
//   c1 = (the checkerboard's color1; bits of the bitmap's height).
// Texel k of the linear array lies at (k % W, k / W), W the texture's width.

struct TextureRecord {
    h: vec4<u32>,
    uv: vec4f,
    c0: vec4f,
    c1: vec4f,
}

fn texture_record(id: u32) -> TextureRecord {
    let base = params.textures + RECORD_VEC4S * id;
    return TextureRecord(
        bitcast<vec4<u32>>(vertex_data[base]),
        vertex_data[base + 1u],
        vertex_data[base + 2u],
        vertex_data[base + 3u],
    );
}

// `TexPoint`: where a texture is looked up, the texture coordinates and, on a mesh triangle
// with attributes, its record `attr` (NONE: off any) and barycentrics `b`.
struct TexPoint {
    uv: vec2f,
    attr: u32,
    b: vec2f,
}

// `TexPoint::from(uv)`: texture coordinates off any mesh.
fn tex_uv(uv: vec2f) -> TexPoint {
    return TexPoint(uv, NONE, vec2f(0.0));
}

// `Texture::eval`: the linear RGB value of texture `id` at `at`.
fn texture_eval(id: u32, at: TexPoint) -> vec3f {
    return texture_value(texture_record(id), at);
}

// `Texture::eval_scalar`: what a scalar slot (α) reads of texture `id` at `at`.
fn texture_eval_scalar(id: u32, at: TexPoint) -> f32 {
    let t = texture_record(id);
    return channel_pick(t.h.z, texture_value(t, at));
}

fn texture_value(t: TextureRecord, at: TexPoint) -> vec3f {
    switch t.h.x {
        case TEXTURE_CONSTANT: {
            return t.c0.xyz;
        }
        case TEXTURE_BITMAP: {
            return bitmap_eval(t, at.uv);
        }
        case TEXTURE_CHECKERBOARD: {
            return checkerboard_eval(t, at.uv);
        }
// #if HAS_MESH_ATTRIBUTES
        // `MeshAttributeTexture::eval`: black off a mesh triangle (`mesh_named` of NONE).
        case TEXTURE_MESH_ATTRIBUTE: {
            return mesh_named(t.h.w, at.attr, at.b) * t.c0.x;
        }
// #endif
        default: {
            return vec3f(unknown_tag());
        }
    }
}

// `UvTransform::apply`.
fn texture_uv(t: TextureRecord, uv: vec2f) -> vec2f {
    return uv * t.uv.xy + t.uv.zw;
}

// `Channel::pick`.
fn channel_pick(channel: u32, c: vec3f) -> f32 {
    switch channel {
        case CHANNEL_LUMINANCE: {
            return mitsuba_luminance(c);
        }
        case CHANNEL_R: {
            return c.x;
        }
        case CHANNEL_G: {
            return c.y;
        }
        case CHANNEL_B: {
            return c.z;
        }
        default: {
            return unknown_tag();
        }
    }
}

// `Checkerboard::eval`.
fn checkerboard_eval(t: TextureRecord, uv: vec2f) -> vec3f {
    let p = texture_uv(t, uv);
    let color1 = (p.x - floor(p.x) > 0.5) != (p.y - floor(p.y) > 0.5);
    return select(t.c0.xyz, t.c1.xyz, color1);
}

// `BitmapTexture::eval`: Dr.Jit's corner order and per-corner weight wx·wy, then the scale.
fn bitmap_eval(t: TextureRecord, uv: vec2f) -> vec3f {
    let p = texture_uv(t, uv);
    let w = bitcast<u32>(t.c0.w);
    let h = bitcast<u32>(t.c1.w);
    let x = bitmap_axis(p.x, w, t.h.y);
    let y = bitmap_axis(p.y, h, t.h.y);
    var out = bitmap_texel(t.h.w, w, x.i.x, y.i.x) * (x.w.x * y.w.x);
    out += bitmap_texel(t.h.w, w, x.i.y, y.i.x) * (x.w.y * y.w.x);
    out += bitmap_texel(t.h.w, w, x.i.x, y.i.y) * (x.w.x * y.w.y);
    out += bitmap_texel(t.h.w, w, x.i.y, y.i.y) * (x.w.y * y.w.y);
    return out * t.c0.xyz;
}

// `BitmapTexture::eval_1_grad`: the gradient of the scaled corner texels' luminance over the
// bilinear cell at `uv`, through the uv transform's scale, times the resolution. What a bump map
// (`materials/bump_map.rs`) differentiates; only bitmaps have one (the scene refuses others).
fn texture_eval_1_grad(id: u32, uv: vec2f) -> vec2f {
    let t = texture_record(id);
    let p = texture_uv(t, uv);
    let w = bitcast<u32>(t.c0.w);
    let h = bitcast<u32>(t.c1.w);
    let x = bitmap_axis(p.x, w, t.h.y);
    let y = bitmap_axis(p.y, h, t.h.y);
    let f00 = mitsuba_luminance(bitmap_texel(t.h.w, w, x.i.x, y.i.x) * t.c0.xyz);
    let f10 = mitsuba_luminance(bitmap_texel(t.h.w, w, x.i.y, y.i.x) * t.c0.xyz);
    let f01 = mitsuba_luminance(bitmap_texel(t.h.w, w, x.i.x, y.i.y) * t.c0.xyz);
    let f11 = mitsuba_luminance(bitmap_texel(t.h.w, w, x.i.y, y.i.y) * t.c0.xyz);
    let dx = y.w.x * (f10 - f00) + y.w.y * (f11 - f01);
    let dy = x.w.x * (f01 - f00) + x.w.y * (f11 - f10);
    return vec2f(dx * t.uv.x * f32(w), dy * t.uv.y * f32(h));
}

// Texel (i, j) of a bitmap of width w whose texels start at `first`.
fn bitmap_texel(first: u32, w: u32, i: u32, j: u32) -> vec3f {
    let k = first + j * w + i;
    let row = textureDimensions(texture_texels).x;
    return textureLoad(texture_texels, vec2<u32>(k % row, k / row), 0).xyz;
}

// `bitmap::axis_lookup`: the two texels and weights of coordinate t on an axis of n texels.
struct AxisLookup {
    i: vec2<u32>,
    w: vec2f,
}

fn bitmap_axis(t: f32, n: u32, wrap: u32) -> AxisLookup {
    let x = t * f32(n) - 0.5;
    let fl = floor(x);
    let f = x - fl;
    return AxisLookup(wrap_pair(fl, n, wrap), vec2f(1.0 - f, f));
}

// (wrap.index(i, n), wrap.index(i.saturating_add(1), n)) for i = `fl as i64`, fl integral:
// directly in i32 below 2^24 in magnitude (every index a lookup of a sensible uv reaches),
// exactly by `wrap_index_far` beyond, so that no uv gives another texel than on the CPU.
fn wrap_pair(fl: f32, n: u32, wrap: u32) -> vec2<u32> {
    if abs(fl) < 16777216.0 {
        let i = i32(fl);
        return vec2<u32>(wrap_index(i, n, wrap), wrap_index(i + 1, n, wrap));
    }
    let k = wrap_index_far(fl, n, wrap);
    // From 2^23 on every f32 is an integer: the coordinate's fraction, the second texel's
    // weight, is exactly 0, so any valid index does for it.
    return vec2<u32>(k, k);
}

// `WrapMode::index` for |i| ≤ 2^24 + 1 (n ≤ 2^27, the largest bitmap: nothing overflows).
fn wrap_index(i: i32, n: u32, wrap: u32) -> u32 {
    let m = i32(n);
    switch wrap {
        case WRAP_REPEAT: {
            return u32(((i % m) + m) % m);
        }
        case WRAP_MIRROR: {
            let k = ((i % (2 * m)) + 2 * m) % (2 * m);
            return u32(select(2 * m - 1 - k, k, k < m));
        }
        case WRAP_CLAMP: {
            return u32(clamp(i, 0, m - 1));
        }
        default: {
            _ = unknown_tag();
            return 0u;
        }
    }
}

// `WrapMode::index(fl as i64, n)` for |fl| ≥ 2^24 or NaN, from fl's bits: Rust's saturating
// cast gives 0 for NaN and i64::MAX or i64::MIN from ±2^63 on; otherwise i = ±mantissa·2^shift,
// whose residue mod the period (n, or 2n for mirror) is found by doubling.
fn wrap_index_far(fl: f32, n: u32, wrap: u32) -> u32 {
    let b = bitcast<u32>(fl);
    let e = (b >> 23u) & 0xffu;
    let negative = (b >> 31u) == 1u;
    if e == 255u && (b & 0x7fffffu) != 0u {
        return wrap_index(0, n, wrap);
    }
    if wrap == WRAP_CLAMP {
        return select(n - 1u, 0u, negative);
    }
    let m = select(n, 2u * n, wrap == WRAP_MIRROR);
    // |fl| ≥ 2^63 (e ≥ 190, infinity included): |i| = 2^63 (i64::MIN) or 2^63 − 1 (i64::MAX).
    let saturated = e >= 190u;
    var r: u32;
    if saturated {
        r = residue_times_pow2(1u, 63u, m);
    } else {
        r = residue_times_pow2((b & 0x7fffffu) | 0x800000u, max(e, 150u) - 150u, m);
    }
    if negative {
        return mirror_fold((m - r) % m, n, wrap);
    } else if saturated {
        return mirror_fold((r + m - 1u) % m, n, wrap);
    }
    return mirror_fold(r, n, wrap);
}

// (x · 2^shift) mod m for m ≤ 2^28 (2r never overflows).
fn residue_times_pow2(x: u32, shift: u32, m: u32) -> u32 {
    var r = x % m;
    for (var k = 0u; k < shift; k++) {
        r = (2u * r) % m;
    }
    return r;
}

// A residue mod 2n to the mirrored index (repeat's residue mod n is the index).
fn mirror_fold(k: u32, n: u32, wrap: u32) -> u32 {
    if wrap == WRAP_MIRROR && k >= n {
        return 2u * n - 1u - k;
    }
    if wrap != WRAP_MIRROR && wrap != WRAP_REPEAT {
        _ = unknown_tag();
        return 0u;
    }
    return k;
}
