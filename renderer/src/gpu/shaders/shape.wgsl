// The shapes the BVH holds, the twin of `geometry/primitive.rs`: a `switch` in the variant order
// of `Shape` (Triangle, Disk, Sphere).
//
// Record layout (see `gpu/scene/shapes.rs`): a.w, b.w, c.w = bits of (kind, material, light).
//   Triangle: a, b, c = vertices, d.xyz = unit normal, d.w = bits of its attribute index (NONE
//             without vertex attributes; `mesh_attributes.wgsl`).
//   Disk:     a.xyz = centre, d.xyz = unit normal, d.w = radius.
//   Sphere:   a.xyz = centre, d.w = radius.

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

// `Primitive::attr`: only triangles have attributes (a disk's or sphere's d.w is its radius).
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
    // Barycentrics (b1, b2) of a triangle hit, for vertex attributes; zero on disks and spheres.
    b: vec2f,
}

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
