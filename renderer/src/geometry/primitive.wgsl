// The shapes the BVH holds, the twin of `geometry/primitive.rs`: a `switch` in the variant order
// of `Shape` (Triangle, Disk, Sphere, Cylinder).
//
// Record layout (see `gpu/scene/shapes.rs`): a.w, b.w, c.w = bits of (kind, material, light).
//   Triangle: a, b, c = vertices, d.xyz = unit normal, d.w = bits of its attribute index (NONE
//             without vertex attributes; `geometry/mesh_attributes.wgsl`).
//   Disk:     a.xyz = centre, b.xyz, c.xyz = its x and y axes (texture coordinates),
//             d.xyz = unit normal, d.w = radius.
//   Sphere:   a.xyz = centre, b.xyz, c.xyz, d.xyz = its frame's x, y and z (texture
//             coordinates, ∂p/∂u), d.w = radius.
//   Cylinder: a.xyz = p0, b.xyz = axis, c.xyz = unit u axis, d.w = radius (negative: normals
//             towards the axis; `geometry/cylinder.wgsl`).

struct Prim {
    a: vec4f,
    b: vec4f,
    c: vec4f,
    d: vec4f,
}

fn prim_kind(p: Prim) -> u32 {
    return bitcast<u32>(p.a.w);
}

fn prim_material(p: Prim) -> u32 {
    return bitcast<u32>(p.b.w);
}

fn prim_light(p: Prim) -> u32 {
    return bitcast<u32>(p.c.w);
}

// `Primitive::attr`: only triangles have attributes (the analytic shapes' d.w is their radius).
fn prim_attr(p: Prim) -> u32 {
    if prim_kind(p) == SHAPE_TRIANGLE {
        return bitcast<u32>(p.d.w);
    }
    return NONE;
}

// `SurfaceHit`.
struct SurfaceHit {
    t: f32,
    p: vec3f,
    p_error: vec3f,
    n: vec3f,
    prim: u32,
    // Barycentrics (b1, b2) of a triangle hit, for vertex attributes; zero on analytic shapes.
    b: vec2f,
}

// #if HAS_MASKS
// `Shape::intersect_t_beyond`: the next hit in (after, ray.t_max) past a hit at `after` that a
// mask let the ray pass (a sphere's or cylinder's far side), or −1: flat shapes are met once.
fn shape_intersect_t_beyond(p: Prim, ray: Ray, after: f32) -> f32 {
    switch prim_kind(p) {
// #if HAS_SPHERE_SHAPE
        case SHAPE_SPHERE: {
            return sphere_intersect_beyond(p.a.xyz, p.d.w, ray, after);
        }
// #endif
// #if HAS_CYLINDER_SHAPE
        case SHAPE_CYLINDER: {
            return cylinder_intersect_beyond(p.a.xyz, p.b.xyz, p.c.xyz, abs(p.d.w), ray, after);
        }
// #endif
        default: {
            return -1.0;
        }
    }
}
// #endif

// `Shape::intersect_t`: the nearest hit in (0, ray.t_max), or −1.
fn shape_intersect_t(p: Prim, ray: Ray, tri: TriangleRay) -> f32 {
    switch prim_kind(p) {
        case SHAPE_TRIANGLE: {
            return intersect_triangle_prepared(tri, p.a.xyz, p.b.xyz, p.c.xyz, ray.t_max).x;
        }
// #if HAS_DISK_SHAPE
        case SHAPE_DISK: {
            return disk_intersect(p.a.xyz, p.d.xyz, p.d.w, ray);
        }
// #endif
// #if HAS_SPHERE_SHAPE
        case SHAPE_SPHERE: {
            return sphere_intersect(p.a.xyz, p.d.w, ray);
        }
// #endif
// #if HAS_CYLINDER_SHAPE
        case SHAPE_CYLINDER: {
            return cylinder_intersect(p.a.xyz, p.b.xyz, p.c.xyz, abs(p.d.w), ray);
        }
// #endif
        default: {
            // No hit (a NaN t would be no hit either), but the sample is flagged.
            _ = unknown_tag();
            return -1.0;
        }
    }
}

// `Shape::surface_hit` for a hit at t found by `shape_intersect_t`.
fn shape_surface_hit(p: Prim, ray: Ray, t: f32, prim: u32) -> SurfaceHit {
    switch prim_kind(p) {
// #if HAS_DISK_SHAPE
        case SHAPE_DISK: {
            let sp = disk_surface_point(p.a.xyz, p.d.xyz, ray, t);
            return SurfaceHit(t, sp[0], sp[1], p.d.xyz, prim, vec2f(0.0));
        }
// #endif
// #if HAS_SPHERE_SHAPE
        case SHAPE_SPHERE: {
            let sp = sphere_surface_point(p.a.xyz, p.d.w, ray, t);
            return SurfaceHit(t, sp.p, sp.p_error, sp.n, prim, vec2f(0.0));
        }
// #endif
// #if HAS_CYLINDER_SHAPE
        case SHAPE_CYLINDER: {
            let cp = cylinder_surface_point(p.a.xyz, p.b.xyz, p.c.xyz, p.d.w, ray, t);
            return SurfaceHit(t, cp.p, cp.p_error, cp.n, prim, vec2f(0.0));
        }
// #endif
        // SHAPE_TRIANGLE (an unknown kind never gets here: `shape_intersect_t` flags it and misses).
        default: {
            // Barycentrics recomputed once per closest hit, as on the CPU.
            let full = Ray(ray.o, ray.d, inf());
            let h = intersect_triangle_prepared(triangle_ray_new(full), p.a.xyz, p.b.xyz, p.c.xyz, inf());
            var b = vec3f(1.0 / 3.0);
            if h.x >= 0.0 {
                b = h.yzw;
            }
            let tp = triangle_point(p.a.xyz, p.b.xyz, p.c.xyz, b);
            return SurfaceHit(t, tp[0], tp[1], p.d.xyz, prim, b.yz);
        }
    }
}

// #if HAS_TEXTURES
// `Scene::uv` (`scene/surface.rs`): the texture coordinates of `hit` on primitive `p`. Triangles
// interpolate their mesh's UVs, else give their barycentrics (`mesh_uv`; quads and box faces
// carry UVs along their edges); spheres Mitsuba 3's (u = φ/2π from their frame's x towards y,
// v = θ/π from its z); disks (r/radius, φ/2π) from their x axis towards their y; cylinders Mitsuba's (φ/2π from
// their u axis, the fraction of the height).
fn surface_uv(p: Prim, hit: SurfaceHit) -> vec2f {
    switch prim_kind(p) {
// #if HAS_SPHERE_SHAPE
        case SHAPE_SPHERE: {
            return sphere_uv(p.a.xyz, p.d.w, Frame(p.b.xyz, p.c.xyz, p.d.xyz), hit.p);
        }
// #endif
// #if HAS_DISK_SHAPE
        case SHAPE_DISK: {
            return disk_uv(p.a.xyz, p.b.xyz, p.c.xyz, p.d.w, hit.p);
        }
// #endif
// #if HAS_CYLINDER_SHAPE
        case SHAPE_CYLINDER: {
            return cylinder_uv(p.a.xyz, p.b.xyz, p.c.xyz, hit.p);
        }
// #endif
        // SHAPE_TRIANGLE (an unknown kind was flagged when it was intersected).
        default: {
            return mesh_uv(prim_attr(p), hit.b);
        }
    }
}

// #if HAS_TEXTURES
// `Scene::tex_point`: where textures are looked up at `hit` on primitive `p`.
fn surface_tex(p: Prim, hit: SurfaceHit) -> TexPoint {
    let attr = select(NONE, prim_attr(p), prim_kind(p) == SHAPE_TRIANGLE);
    return TexPoint(surface_uv(p, hit), attr, hit.b);
}
// #endif

// `Scene::uv_at` of point y on the sphere (centre, radius, frame): hits and sphere lights'
// samples.
fn sphere_uv(center: vec3f, radius: f32, frame: Frame, y: vec3f) -> vec2f {
    let d = to_local(frame, (y - center) / radius);
    return vec2f(turn_fraction(atan2_precise(d.y, d.x)), acos_precise(clamp(d.z, -1.0, 1.0)) / PI);
}

// `Scene::uv_at` of point y on the disk (centre, its x and y axes, radius): hits and disk
// lights' samples.
fn disk_uv(center: vec3f, x_axis: vec3f, y_axis: vec3f, radius: f32, y: vec3f) -> vec2f {
    let rel = y - center;
    let local = vec2f(dot(rel, x_axis), dot(rel, y_axis));
    let r = min(hypot(local.x, local.y) / radius, 1.0);
    return vec2f(r, turn_fraction(atan2_precise(local.y, local.x)));
}

// An angle in (−π, π] as a fraction of a turn in [0, 1).
fn turn_fraction(phi: f32) -> f32 {
    return select(phi, phi + TAU, phi < 0.0) / TAU;
}

// `f32::hypot`: √(x² + y²) without overflow or underflow of the squares.
fn hypot(x: f32, y: f32) -> f32 {
    let m = max(abs(x), abs(y));
    if m == 0.0 || !is_finite_f(m) {
        return m;
    }
    let a = x / m;
    let b = y / m;
    return m * sqrt(a * a + b * b);
}
// #endif
