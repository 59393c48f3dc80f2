// Lights, the twin of `lights/mod.rs` and `lights/light_sampler.rs`: one record per light, a
// `switch` in the variant order of `Light` (Triangle, Polygon, Quad, Disk, Sphere, Background,
// Envmap, Point, Spot, Directional, Projector), power-proportional selection from a CDF in
// `tables`. The delta lights' records are described in their own files (`lights/point.wgsl`,
// `spot.wgsl`, `directional.wgsl`, `projector.wgsl`).
//
// Record layout (see `gpu/scene/lights.rs`): h = (kind, first triangle, triangle count,
// texture), le = (radiance, area). An area light's h.w is the id of its emission texture
// (`textures/mod.wgsl`), NONE where it emits its constant radiance; a textured light's le.xyz is its
// selection radiance only, the texture is evaluated at the sampled or hit point (the twin of
// `Scene::sample_light` and `Scene::emitted`, below).
//   Triangle:   a, b, c = vertices, d.xyz = normal, h.y = its vertex attributes (NONE: none).
//   Polygon:    a.xyz = a point of the plane, d.xyz = normal; triangles in `vertex_data`
//               (3 vec4 each, v0.w/v1.w = the triangle's interval in the by-area CDF).
//   Quad:       a = corner, b = edge u, c = edge v, d.xyz = normal, h.y = the vertex
//               attributes of its first triangle, the second's following (NONE: none).
//   Disk:       a.xyz = centre, a.w = radius, d.xyz = normal.
//   Sphere:     a.xyz = centre, a.w = radius.
//   Background: le.xyz only.
//   Envmap:     h.yzw = (width, height, offset of its tables), a.xy = (sin, cos) of its
//               rotation; texels in `envmap_texels` (`lights/envmap.wgsl`).

struct Light {
    h: vec4<u32>,
    a: vec4f,
    b: vec4f,
    c: vec4f,
    d: vec4f,
    le: vec4f,
}

// `LightSample`; `ok` = false stands for `None`.
struct LightSample {
    p: vec3f,
    p_error: vec3f,
    n: vec3f,
    wi: vec3f,
    pdf: f32,
    le: vec3f,
    infinite: bool,
    ok: bool,
    // Barycentrics (b1, b2) of p in the sampled triangle of a triangle or polygon light, for its
    // texture coordinates; zero for the other lights.
    b: vec2f,
}

fn no_light_sample() -> LightSample {
    return LightSample(vec3f(0.0), vec3f(0.0), vec3f(0.0), vec3f(0.0), 0.0, vec3f(0.0), false, false, vec2f(0.0));
}

// `LightSampling::projects`: projected-solid-angle sampling with a receiver normal.
fn light_sampling_projects(method: u32, ns: vec3f) -> bool {
    return method == LIGHT_SAMPLING_PROJECTED_SOLID_ANGLE && any(ns != vec3f(0.0));
}

// #if HAS_TRANSMISSION
// `LightSampling::receiver_normal`: the normal a receiver gives the light sampler (none from a
// transmitting one under projected-solid-angle sampling, which sees only the upper hemisphere).
fn light_sampling_receiver_normal(method: u32, ns: vec3f, transmitting: bool) -> vec3f {
    if transmitting && method == LIGHT_SAMPLING_PROJECTED_SOLID_ANGLE {
        return vec3f(0.0);
    }
    return ns;
}
// #endif

// #if HAS_LIGHTS
// `area_to_solid_angle`: pdf_A·d²/|cos θ_y|, 0 where singular.
fn area_to_solid_angle(pdf_area: f32, p: vec3f, y: vec3f, ny: vec3f) -> f32 {
    let d = y - p;
    let dist2 = dot(d, d);
    let cos_y = abs(dot(ny, d)) / sqrt(dist2);
    let pdf = pdf_area * dist2 / cos_y;
    if is_finite_f(pdf) && dist2 > 0.0 {
        return pdf;
    }
    return 0.0;
}

// `triangle_sample`: the sample at barycentrics b of triangle (v0, v1, v2), normal n, reached along
// wi with solid-angle density pdf.
fn triangle_sample(v0: vec3f, v1: vec3f, v2: vec3f, b: vec3f, n: vec3f, le: vec3f, wi: vec3f, pdf: f32) -> LightSample {
    let y = b.x * v0 + b.y * v1 + b.z * v2;
    let err = gamma(6.0) * (abs(b.x * v0) + abs(b.y * v1) + abs(b.z * v2));
    return LightSample(y, err, n, wi, pdf, le, false, true, b.yz);
}

// `area_sample`: a sample for point y (normal ny) chosen with area density pdf_area.
fn area_sample(p: vec3f, y: vec3f, ny: vec3f, pdf_area: f32, le: vec3f) -> LightSample {
    let d = y - p;
    let dist = length(d);
    let wi = d / dist;
    // One-sided, and rejects NaN.
    if !(dot(ny, wi) < 0.0) {
        return no_light_sample();
    }
    let pdf = area_to_solid_angle(pdf_area, p, y, ny);
    return LightSample(y, gamma(6.0) * abs(y), ny, wi, pdf, le, false, true, vec2f(0.0));
}

fn spherical_ok(omega: f32) -> bool {
    return omega >= MIN_SPHERICAL_SAMPLE_AREA && omega <= MAX_SPHERICAL_SAMPLE_AREA;
}

// Whether spherical samples are warped for a receiver with shading normal ns
// (`LightSampling::warps`).
fn light_sampling_warps(method: u32, ns: vec3f) -> bool {
    return method == LIGHT_SAMPLING_SOLID_ANGLE_COSINE && any(ns != vec3f(0.0));
}

// Every method but `Area` (`LightSampling::solid_angle`).
fn light_sampling_solid_angle(method: u32) -> bool {
    return method != LIGHT_SAMPLING_AREA;
}

// `planar_solid_angle_estimate`: area · |cos θ| / d² of a planar light (centroid c, normal n).
fn planar_solid_angle_estimate(p: vec3f, c: vec3f, n: vec3f, area: f32) -> f32 {
    let d = p - c;
    let d2 = dot(d, d);
    return area * abs(dot(n, d)) / (d2 * sqrt(d2));
}

// `LightSampling::spherical_for`: whether a planar light is sampled from p by its spherical warp.
fn light_sampling_spherical_for(method: u32, p: vec3f, c: vec3f, n: vec3f, area: f32) -> bool {
    if method == LIGHT_SAMPLING_ADAPTIVE {
        return planar_solid_angle_estimate(p, c, n, area) >= ADAPTIVE_MIN_SOLID_ANGLE;
    }
    return method != LIGHT_SAMPLING_AREA;
}

// `Light::sample`, including its final validity test; ns is the receiver's shading normal (zero:
// none), read by LIGHT_SAMPLING_SOLID_ANGLE_COSINE and LIGHT_SAMPLING_PROJECTED_SOLID_ANGLE only.
fn light_sample(l: Light, p: vec3f, ns: vec3f, u: vec2f, method: u32) -> LightSample {
    var s = no_light_sample();
    switch l.h.x {
// #if HAS_TRIANGLE_LIGHT
        case LIGHT_TRIANGLE: {
            s = triangle_light_sample(l, p, ns, u, method);
        }
// #endif
// #if HAS_POLYGON_LIGHT
        case LIGHT_POLYGON: {
            s = polygon_light_sample(l, p, ns, u, method);
        }
// #endif
// #if HAS_QUAD_LIGHT
        case LIGHT_QUAD: {
            s = quad_light_sample(l, p, ns, u, method);
        }
// #endif
// #if HAS_DISK_LIGHT
        case LIGHT_DISK: {
            s = disk_light_sample(l, p, u, method);
        }
// #endif
// #if HAS_SPHERE_LIGHT
        case LIGHT_SPHERE: {
            s = sphere_light_sample(l, p, u, method);
        }
// #endif
// #if HAS_BACKGROUND
        case LIGHT_BACKGROUND: {
            s = background_light_sample(l, u);
        }
// #endif
// #if HAS_ENVMAP
        case LIGHT_ENVMAP: {
            s = envmap_light_sample(l, u, method);
        }
// #endif
// #if HAS_POINT_LIGHT
        case LIGHT_POINT: {
            s = point_light_sample(l, p);
        }
// #endif
// #if HAS_SPOT_LIGHT
        case LIGHT_SPOT: {
            s = spot_light_sample(l, p);
        }
// #endif
// #if HAS_DIRECTIONAL_LIGHT
        case LIGHT_DIRECTIONAL: {
            s = directional_light_sample(l);
        }
// #endif
// #if HAS_PROJECTOR_LIGHT
        case LIGHT_PROJECTOR: {
            s = projector_light_sample(l, p);
        }
// #endif
        default: {
            s.pdf = unknown_tag();
        }
    }
// #if MUTANTS
    if l.h.x == MUTANT_LIGHT_PDF_TAG {
        s.pdf *= MUTANT_FACTOR;
    }
// #endif
    if !(s.ok && s.pdf > 0.0 && is_finite_f(s.pdf) && any(s.le > vec3f(0.0))) {
        return no_light_sample();
    }
    return s;
}

// `Light::pdf`: solid-angle pdf of sampling direction wi from p (shading normal ns), hitting y
// with normal ny.
fn light_pdf(l: Light, p: vec3f, ns: vec3f, wi: vec3f, y: vec3f, ny: vec3f, method: u32) -> f32 {
// #if MUTANTS
    let pdf = light_pdf_unmutated(l, p, ns, wi, y, ny, method);
    return select(pdf, pdf * MUTANT_FACTOR, l.h.x == MUTANT_LIGHT_PDF_TAG);
}

fn light_pdf_unmutated(l: Light, p: vec3f, ns: vec3f, wi: vec3f, y: vec3f, ny: vec3f, method: u32) -> f32 {
// #endif
    switch l.h.x {
// #if HAS_TRIANGLE_LIGHT
        case LIGHT_TRIANGLE: {
            return triangle_light_pdf(l, p, ns, wi, y, ny, method);
        }
// #endif
// #if HAS_POLYGON_LIGHT
        case LIGHT_POLYGON: {
            return polygon_light_pdf(l, p, ns, wi, y, ny, method);
        }
// #endif
// #if HAS_QUAD_LIGHT
        case LIGHT_QUAD: {
            return quad_light_pdf(l, p, ns, wi, y, ny, method);
        }
// #endif
// #if HAS_DISK_LIGHT
        case LIGHT_DISK: {
            return disk_light_pdf(l, p, y, ny, method);
        }
// #endif
// #if HAS_SPHERE_LIGHT
        case LIGHT_SPHERE: {
            return sphere_light_pdf(l, p, y, ny, method);
        }
// #endif
        case LIGHT_BACKGROUND: {
            return uniform_sphere_pdf();
        }
// #if HAS_ENVMAP
        case LIGHT_ENVMAP: {
            return envmap_light_pdf(l, wi, method);
        }
// #endif
// #if HAS_DELTA_LIGHT
        // No direction finds a delta light but the one its sample takes.
        case LIGHT_POINT, LIGHT_SPOT, LIGHT_DIRECTIONAL, LIGHT_PROJECTOR: {
            return 0.0;
        }
// #endif
        default: {
            return unknown_tag();
        }
    }
}

// #endif

// `Light::radiance`: one-sided emission towards −w_in at a point with normal n (n unused for
// the lights at infinity, which emit along −w_in from direction w_in).
fn light_radiance(l: Light, n: vec3f, w_in: vec3f) -> vec3f {
// #if HAS_ENVMAP
    if l.h.x == LIGHT_ENVMAP {
        return envmap_eval(l, w_in);
    }
// #endif
    if l.h.x == LIGHT_BACKGROUND || dot(n, w_in) < 0.0 {
        return l.le.xyz;
    }
    return vec3f(0.0);
}

// #if HAS_TEXTURES
// `Light::texture`: the id of the light's emission texture, NONE for a constant radiance
// (always for the lights at infinity, whose h.w means something else).
fn light_texture(l: Light) -> u32 {
// #if HAS_ENVMAP
    if l.h.x == LIGHT_ENVMAP {
        return NONE;
    }
// #endif
    return select(l.h.w, NONE, l.h.x == LIGHT_BACKGROUND);
}

// `Scene::emitted`: what light `l` emits at `hit` (primitive `p`), `le` being its
// `light_radiance` there: that, or where it is not black its texture at the hit's texture
// coordinates (`surface_uv`, the rule materials use).
fn light_emitted(l: Light, p: Prim, hit: SurfaceHit, le: vec3f) -> vec3f {
    let t = light_texture(l);
    if t == NONE || all(le == vec3f(0.0)) {
        return le;
    }
    return texture_eval(t, surface_tex(p, hit));
}

// #if HAS_LIGHTS
// `Scene::light_uv`: the texture coordinates of the point `s` sampled on area light `l`, by the
// rule of the primitive under it (`surface_uv`): a triangle light's attributes, the quad's
// triangle holding the point, a polygon's triangle (no attributes: its barycentrics).
fn light_uv(l: Light, s: LightSample) -> vec2f {
    return light_tex(l, s).uv;
}

// `Scene::light_tex_point`: where textures are looked up at the sample, a triangle light's (or a
// quad's triangle's) record and barycentrics with its texture coordinates.
fn light_tex(l: Light, s: LightSample) -> TexPoint {
    switch l.h.x {
// #if HAS_TRIANGLE_LIGHT
        case LIGHT_TRIANGLE: {
            return TexPoint(mesh_uv(l.h.y, s.b), l.h.y, s.b);
        }
// #endif
// #if HAS_POLYGON_LIGHT
        case LIGHT_POLYGON: {
            return tex_uv(mesh_uv(NONE, s.b));
        }
// #endif
// #if HAS_QUAD_LIGHT
        case LIGHT_QUAD: {
            let tp = quad_light_triangle_point(l, s.p);
            let attr = select(l.h.y + tp.k, NONE, l.h.y == NONE);
            return TexPoint(mesh_uv(attr, tp.b), attr, tp.b);
        }
// #endif
// #if HAS_DISK_LIGHT
        case LIGHT_DISK: {
            return tex_uv(disk_uv(l.a.xyz, l.b.xyz, l.c.xyz, l.a.w, s.p));
        }
// #endif
// #if HAS_SPHERE_LIGHT
        case LIGHT_SPHERE: {
            return tex_uv(sphere_uv(l.a.xyz, l.a.w, Frame(l.b.xyz, l.c.xyz, l.d.xyz), s.p));
        }
// #endif
// #if HAS_DELTA_LIGHT
        // A spot's or projector's sample carries its texture coordinates.
        case LIGHT_SPOT, LIGHT_PROJECTOR: {
            return tex_uv(s.b);
        }
// #endif
        default: {
            return tex_uv(vec2f(unknown_tag()));
        }
    }
}

// The texture step of `Scene::sample_light`: a textured light's sample `s` emits its texture at
// the sampled point; no sample where that is black.
fn light_sample_textured(l: Light, s: LightSample) -> LightSample {
    let t = light_texture(l);
    if !s.ok || t == NONE {
        return s;
    }
    var out = s;
    out.le = texture_eval(t, light_tex(l, s));
// #if HAS_DELTA_LIGHT
    // A delta light's radiance is its intensity and falloff, modulated by the texture.
    if light_is_delta(l) {
        out.le *= s.le;
    }
// #endif
    if !any(out.le > vec3f(0.0)) {
        return no_light_sample();
    }
    return out;
}
// #endif
// #endif
