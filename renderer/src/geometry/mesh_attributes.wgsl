// Vertex attributes of mesh triangles (shading normals, texture coordinates) found from a hit's
// barycentrics, the twin of `geometry/mesh_attributes.rs` (and of the lookup of
// `textures/mesh_attribute.rs`), same expressions in the same order,
// same fallbacks. The records live in `vertex_data` at the offsets `params.attr` (written by
// `gpu/scene/attributes.rs`):
//   triangles (params.attr.x), indexed by a primitive's attr: bits of (v0, v1, v2, mesh);
//   meshes (params.attr.y): bits of (normal_base, uv_base, flags, first named slot or NONE);
//   normals (params.attr.z): (x, y, z, 0), unit and in world space;
//   uvs (params.attr.w): two per vec4, vertex i in .xy of vec4 i/2 if i is even, .zw if odd;
//   named slots and values, at the absolute indices the meshes and slots hold.
// Only in programs that need it: shading normals under HAS_SHADING_NORMALS, texture coordinates
// under HAS_MESH_UVS (textures, or the tangents of anisotropic materials), their interpolation
// under HAS_TEXTURES.

fn attr_triangle(attr: u32) -> vec4<u32> {
    return bitcast<vec4<u32>>(vertex_data[params.attr.x + attr]);
}

fn attr_mesh(mesh: u32) -> vec4<u32> {
    return bitcast<vec4<u32>>(vertex_data[params.attr.y + mesh]);
}

// #if HAS_SHADING_NORMALS
fn attr_normal(i: u32) -> vec3f {
    return vertex_data[params.attr.z + i].xyz;
}

// #endif

// #if HAS_MESH_UVS
fn attr_uv(i: u32) -> vec2f {
    let q = vertex_data[params.attr.w + i / 2u];
    return select(q.xy, q.zw, (i & 1u) == 1u);
}

// `MeshAttributes::triangle_uvs`: triangle `attr`'s vertex UVs, `found` false where it has none
// (also for NONE).
struct TriangleUvs {
    found: bool,
    t0: vec2f,
    t1: vec2f,
    t2: vec2f,
}

fn triangle_uvs(attr: u32) -> TriangleUvs {
    if attr == NONE {
        return TriangleUvs(false, vec2f(0.0), vec2f(0.0), vec2f(0.0));
    }
    let tri = attr_triangle(attr);
    let mesh = attr_mesh(tri.w);
    if (mesh.z & ATTR_HAS_UVS) == 0u {
        return TriangleUvs(false, vec2f(0.0), vec2f(0.0), vec2f(0.0));
    }
    return TriangleUvs(true, attr_uv(mesh.y + tri.x), attr_uv(mesh.y + tri.y), attr_uv(mesh.y + tri.z));
}
// #endif

// #if HAS_SHADING_NORMALS
// `MeshAttributes::shading_normal`'s `Option`: `found` false (and n = ng) where the triangle has
// no vertex normals.
struct ShadingNormal {
    found: bool,
    n: vec3f,
}

// `MeshAttributes::shading_normal`: the shading normal at barycentrics b = (b1, b2) of triangle
// `attr` (NONE: none) with geometric normal ng.
fn shading_normal(attr: u32, b: vec2f, ng: vec3f) -> ShadingNormal {
    if attr == NONE {
        return ShadingNormal(false, ng);
    }
    let tri = attr_triangle(attr);
    let mesh = attr_mesh(tri.w);
    if (mesh.z & ATTR_HAS_NORMALS) == 0u {
        return ShadingNormal(false, ng);
    }
    let n0 = attr_normal(mesh.x + tri.x);
    let n1 = attr_normal(mesh.x + tri.y);
    let n2 = attr_normal(mesh.x + tri.z);
    return ShadingNormal(true, interpolate_normal(n0, n1, n2, b, ng));
}

// #endif

// #if HAS_MESH_ATTRIBUTES
// `MeshAttributes::named`: named attribute `slot` at barycentrics b of triangle `attr`, a vertex
// attribute interpolated, a face attribute the face's; black where the mesh lacks it or attr is
// NONE. A mesh record's w and a slot record's x are absolute `vertex_data` indices
// (`gpu/scene/attributes.rs`).
fn mesh_named(slot: u32, attr: u32, b: vec2f) -> vec3f {
    if attr == NONE {
        return vec3f(0.0);
    }
    let tri = attr_triangle(attr);
    let mesh = attr_mesh(tri.w);
    if mesh.w == NONE {
        return vec3f(0.0);
    }
    let s = bitcast<vec4<u32>>(vertex_data[mesh.w + slot]);
    if s.x == NONE {
        return vec3f(0.0);
    }
    if s.z != 0u {
        return vertex_data[s.x + attr - s.y].xyz;
    }
    let v0 = vertex_data[s.x + tri.x].xyz;
    let v1 = vertex_data[s.x + tri.y].xyz;
    let v2 = vertex_data[s.x + tri.z].xyz;
    return (1.0 - b.x - b.y) * v0 + b.x * v1 + b.y * v2;
}
// #endif

// #if HAS_TEXTURES
// `MeshAttributes::uv`: interpolated where the triangle has UVs, else b itself (also for NONE).
fn mesh_uv(attr: u32, b: vec2f) -> vec2f {
    let t = triangle_uvs(attr);
    if !t.found {
        return b;
    }
    return (1.0 - b.x - b.y) * t.t0 + b.x * t.t1 + b.y * t.t2;
}
// #endif

// #if HAS_SHADING_NORMALS

// `interpolate_normal`: normalize((1−b1−b2)·n0 + b1·n1 + b2·n2), turned to ng's side; ng where
// that is not a direction (squared length not above 1e-20, or not finite: tested by its bits, as
// a shader compiler may assume comparisons never see a NaN).
fn interpolate_normal(n0: vec3f, n1: vec3f, n2: vec3f, b: vec2f, ng: vec3f) -> vec3f {
    let sum = (1.0 - b.x - b.y) * n0 + b.x * n1 + b.y * n2;
    let len2 = dot(sum, sum);
    if !(len2 > 1e-20f && is_finite_f(len2)) {
        return ng;
    }
    let ns = sum / sqrt(len2);
    if dot(ns, ng) < 0.0 {
        return -ns;
    }
    return ns;
}
// #endif
