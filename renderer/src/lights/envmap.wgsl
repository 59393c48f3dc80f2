// The environment map, the twin of `lights/envmap.rs` (its texture and tables are uploaded by
// `gpu/scene/envmap.rs`): Mitsuba 3.9.1's latitude-longitude lookup, bilinear by hand from
// `envmap_texels` (periodic in u, rows clamped at the poles), and importance sampling over the
// cells of that interpolation (uniform in φ and cos θ within a cell); LIGHT_SAMPLING_AREA samples
// the sphere uniformly instead. Compiled only under HAS_ENVMAP.
//
// Record: h = (LIGHT_ENVMAP, width W, height H, offset of the tables in `tables`),
// a.xyz, b.xyz, c.xyz = the columns of the rotation from the map's frame to the world. With
// B = max(H − 1, 1) bands the tables hold, in order: B + 1 band-edge cosines, the marginal CDF
// over bands (B + 1), one conditional CDF over columns per band (W + 1 each), and the density of
// each cell on the unit square (W per band).

fn envmap_bands(l: Light) -> u32 {
    return max(l.h.z, 2u) - 1u;
}

// Offsets of the tables: band cosines, marginal CDF, conditional CDFs, cell densities.
fn envmap_band_cos(l: Light) -> u32 {
    return l.h.w;
}

fn envmap_marginal(l: Light) -> u32 {
    return l.h.w + envmap_bands(l) + 1u;
}

fn envmap_conditional(l: Light) -> u32 {
    return l.h.w + 2u * (envmap_bands(l) + 1u);
}

fn envmap_cells(l: Light) -> u32 {
    return envmap_conditional(l) + envmap_bands(l) * (l.h.y + 1u);
}

// World → the map's frame: the transpose's product, in glam's order (`Mat3 * Vec3`).
fn envmap_to_map(l: Light, d: vec3f) -> vec3f {
    return vec3f(
        l.a.x * d.x + l.a.y * d.y + l.a.z * d.z,
        l.b.x * d.x + l.b.y * d.y + l.b.z * d.z,
        l.c.x * d.x + l.c.y * d.y + l.c.z * d.z
    );
}

// The map's frame → world, in glam's order (columns times components, summed left to right).
fn envmap_to_world(l: Light, d: vec3f) -> vec3f {
    return l.a.xyz * d.x + l.b.xyz * d.y + l.c.xyz * d.z;
}

// `EnvmapLight::uv`: (u, v) of a direction in the map's frame (not necessarily unit).
fn envmap_uv(d_in: vec3f) -> vec2f {
    let d = normalize_glam(d_in);
    var u = atan2_precise(d.x, -d.z) / TAU;
    if u < 0.0 {
        u += 1.0;
    }
    // u = 1 can come out of rounding just below 0.
    if u >= 1.0 {
        u = 0.0;
    }
    return vec2f(u, acos_precise(clamp(d.y, -1.0, 1.0)) / PI);
}

fn envmap_texel(i: u32, j: u32) -> vec3f {
    return textureLoad(envmap_texels, vec2<u32>(i, j), 0).xyz;
}

// `EnvmapLight::lookup`: column u·W − ½ (periodic), row v·(H − 1) (clamped).
fn envmap_lookup(l: Light, uv: vec2f) -> vec3f {
    let w = l.h.y;
    let h = l.h.z;
    let x = uv.x * f32(w) - 0.5;
    let x0 = floor(x);
    let fx = x - x0;
    let wi = i32(w);
    let i0 = u32(((i32(x0) % wi) + wi) % wi);
    let i1 = (i0 + 1u) % w;
    let y = clamp(uv.y * f32(h - 1u), 0.0, f32(h - 1u));
    let j0 = min(u32(floor(y)), h - 1u);
    let j1 = min(j0 + 1u, h - 1u);
    let fy = y - f32(j0);
    let top = envmap_texel(i0, j0) * (1.0 - fx) + envmap_texel(i1, j0) * fx;
    let bottom = envmap_texel(i0, j1) * (1.0 - fx) + envmap_texel(i1, j1) * fx;
    return top * (1.0 - fy) + bottom * fy;
}

// `EnvmapLight::eval`: radiance seen looking in world direction d.
fn envmap_eval(l: Light, d: vec3f) -> vec3f {
    return envmap_lookup(l, envmap_uv(envmap_to_map(l, d)));
}

// An entry picked from a CDF, and u remapped into it.
struct EnvmapPick {
    index: u32,
    remapped: f32,
}

// `DiscreteDistribution::sample` on the f32 CDF of n entries at `offset` in `tables`: the largest
// i with cdf[i] ≤ u (entries of zero weight own empty intervals and are never picked).
fn envmap_pick(offset: u32, n: u32, u_in: f32) -> EnvmapPick {
    let u = clamp(u_in, 0.0, ONE_MINUS_EPSILON);
    var lo = 0u;
    var hi = n;
    // Invariant: cdf[lo] ≤ u < cdf[hi].
    while hi - lo > 1u {
        let mid = (lo + hi) / 2u;
        if tables[offset + mid] <= u {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let c0 = tables[offset + lo];
    let c1 = tables[offset + lo + 1u];
    return EnvmapPick(lo, min((u - c0) / (c1 - c0), ONE_MINUS_EPSILON));
}

// `EnvmapLight::pdf_square_to_solid_angle`: dω = dφ d(cos θ), cos θ linear in y within `band`.
fn envmap_solid_angle_pdf(l: Light, pdf_square: f32, band: u32) -> f32 {
    let o = envmap_band_cos(l);
    let dcos = tables[o + band] - tables[o + band + 1u];
    return pdf_square / (TAU * f32(envmap_bands(l)) * dcos);
}

// `EnvmapLight::sample_importance`: (world direction, solid-angle pdf).
fn envmap_sample_importance(l: Light, u: vec2f) -> vec4f {
    let w = l.h.y;
    let bands = envmap_bands(l);
    let row = envmap_pick(envmap_marginal(l), bands, u.y);
    let column = envmap_pick(envmap_conditional(l) + row.index * (w + 1u), w, u.x);
    let x = (f32(column.index) + column.remapped) / f32(w);
    let y = (f32(row.index) + row.remapped) / f32(bands);
    let p = min(vec2f(x, y), vec2f(ONE_MINUS_EPSILON));
    let pdf_square = tables[envmap_cells(l) + row.index * w + column.index];
    let band = row.index;
    let c0 = tables[envmap_band_cos(l) + band];
    let c1 = tables[envmap_band_cos(l) + band + 1u];
    let f = p.y * f32(bands) - f32(band);
    let z = clamp(c0 + f * (c1 - c0), -1.0, 1.0);
    let phi = TAU * (p.x + 0.5 / f32(w));
    let r = safe_sqrt(1.0 - z * z);
    // φ = 0 looks along −z, φ = π/2 along +x.
    let local = vec3f(r * sin(phi), z, -r * cos(phi));
    return vec4f(envmap_to_world(l, local), envmap_solid_angle_pdf(l, pdf_square, band));
}

// `EnvmapLight::pdf_importance`: the density of the cell holding world direction d (its
// `cell_point`, then `Piecewise2D::cell`).
fn envmap_pdf_importance(l: Light, d_world: vec3f) -> f32 {
    let w = l.h.y;
    let bands = envmap_bands(l);
    let d = envmap_to_map(l, d_world);
    let uv = envmap_uv(d);
    let z = clamp(normalize_glam(d).y, -1.0, 1.0);
    var x = uv.x - 0.5 / f32(w);
    if x < 0.0 {
        x += 1.0;
    }
    let band = min(u32(uv.y * f32(bands)), bands - 1u);
    let c0 = tables[envmap_band_cos(l) + band];
    let c1 = tables[envmap_band_cos(l) + band + 1u];
    let f = clamp((c0 - z) / (c0 - c1), 0.0, 1.0);
    let p = vec2f(min(x, ONE_MINUS_EPSILON), (f32(band) + f) / f32(bands));
    let column = min(u32(p.x * f32(w)), w - 1u);
    let row = min(u32(p.y * f32(bands)), bands - 1u);
    let pdf_square = tables[envmap_cells(l) + row * w + column];
    return envmap_solid_angle_pdf(l, pdf_square, band);
}

// `EnvmapLight::sample`: importance-sampled, or uniform on the sphere for LIGHT_SAMPLING_AREA.
fn envmap_light_sample(l: Light, u: vec2f, method: u32) -> LightSample {
    var wi: vec3f;
    var pdf: f32;
    if method == LIGHT_SAMPLING_AREA {
        wi = sample_uniform_sphere(u);
        pdf = uniform_sphere_pdf();
    } else {
        let s = envmap_sample_importance(l, u);
        wi = s.xyz;
        pdf = s.w;
    }
    return LightSample(wi, vec3f(0.0), -wi, wi, pdf, envmap_eval(l, wi), true, true, vec2f(0.0));
}

// `EnvmapLight::pdf`. Uniform samples where the map is black are discarded (`light_sample`
// returns none where a light contributes nothing), so their density there is 0.
fn envmap_light_pdf(l: Light, wi: vec3f, method: u32) -> f32 {
    if method == LIGHT_SAMPLING_AREA {
        if all(envmap_eval(l, wi) == vec3f(0.0)) {
            return 0.0;
        }
        return uniform_sphere_pdf();
    }
    return envmap_pdf_importance(l, wi);
}
