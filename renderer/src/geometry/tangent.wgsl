// The surface tangent ∂p/∂u at a hit and the BSDF frame it orients for an anisotropic BSDF,
// the twin of `geometry/tangent.rs` (Mitsuba 3.9.1's: a mesh triangle's UV map, else its first
// edge; a sphere's azimuth about its frame's pole; a disk's radius; a cylinder's azimuth about its axis). Only
// under HAS_ANISOTROPIC.

// `tangent::dp_du` of `hit` on primitive `p` (not normalised).
fn surface_dp_du(p: Prim, hit: SurfaceHit) -> vec3f {
    switch prim_kind(p) {
// #if HAS_SPHERE_SHAPE
        case SHAPE_SPHERE: {
            return cross(p.d.xyz, hit.p - p.a.xyz);
        }
// #endif
// #if HAS_DISK_SHAPE
        case SHAPE_DISK: {
            return hit.p - p.a.xyz;
        }
// #endif
// #if HAS_CYLINDER_SHAPE
        case SHAPE_CYLINDER: {
            return cross(p.b.xyz, hit.p - p.a.xyz);
        }
// #endif
        // SHAPE_TRIANGLE (an unknown kind was flagged when it was intersected).
        default: {
            let dp0 = p.b.xyz - p.a.xyz;
            let dp1 = p.c.xyz - p.a.xyz;
            let t = triangle_uvs(prim_attr(p));
            if !t.found {
                return dp0;
            }
            let duv0 = t.t1 - t.t0;
            let duv1 = t.t2 - t.t0;
            let det = duv0.x * duv1.y - duv0.y * duv1.x;
            if det == 0.0 {
                return frame_from_normal(hit.n).s;
            }
            return (duv1.y * dp0 - duv0.y * dp1) / det;
        }
    }
}

// #if HAS_NORMAL_MAPS
// `tangent::dp_duv` of a mesh triangle: (∂p/∂u, ∂p/∂v) of its UV map, its edges without one, the
// geometric normal's frame's tangents where the map is degenerate. A bump map's only shapes.
struct Partials {
    du: vec3f,
    dv: vec3f,
}

fn triangle_dp_duv(p: Prim, hit: SurfaceHit) -> Partials {
    let dp0 = p.b.xyz - p.a.xyz;
    let dp1 = p.c.xyz - p.a.xyz;
    let t = triangle_uvs(prim_attr(p));
    if !t.found {
        return Partials(dp0, dp1);
    }
    let duv0 = t.t1 - t.t0;
    let duv1 = t.t2 - t.t0;
    let det = duv0.x * duv1.y - duv0.y * duv1.x;
    if det == 0.0 {
        let f = frame_from_normal(hit.n);
        return Partials(f.s, f.t);
    }
    return Partials((duv1.y * dp0 - duv0.y * dp1) / det, (duv0.x * dp1 - duv1.x * dp0) / det);
}
// #endif

// `tangent::tangent_frame`: the frame of unit normal n whose first axis is dp_du made
// orthogonal to n; the frame of n alone where nothing is left.
fn tangent_frame(n: vec3f, dp_du: vec3f) -> Frame {
    let s = dp_du - n * dot(n, dp_du);
    let len = length(s);
    if !(len > 0.0 && is_finite_f(len)) {
        return frame_from_normal(n);
    }
    let su = s / len;
    return Frame(su, cross(n, su), n);
}
