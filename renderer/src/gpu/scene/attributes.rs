//! Mesh vertex attributes on the GPU: the scene's [`MeshAttributes`] appended to the `vertex_data`
//! buffer (binding 5, which polygon lights' triangles start), its four arrays one after the other,
//! at the offsets [`AttrOffsets`] that reach the shaders through the per-dispatch uniform
//! (`params.attr`). One shared vec4 buffer rather than four new bindings: the path tracer already
//! binds the 8 storage buffers wgpu's portable limits allow per stage.
//!
//! Records (16 bytes each, u32 fields stored as f32 bits like every record's indices):
//! - triangles, one per attributed triangle, indexed by a primitive's `attr`: bits of
//!   `(v[0], v[1], v[2], mesh)`;
//! - meshes: bits of `(normal_base, uv_base, flags, 0)`;
//! - normals: `(x, y, z, 0)`;
//! - uvs, two per vec4: vertex `i` in `.xy` of vec4 `i/2` where `i` is even, in `.zw` where odd;
//! - named slots (after the uvs, found through the meshes): bits of `(base, first_triangle,
//!   per_face, 0)`, `base` the vec4 index of the slot's first value in `vertex_data` (`NONE`:
//!   the mesh lacks it);
//! - named values: `(x, y, z, 0)`.
//!
//! A mesh record's fourth field is the bits of the `vertex_data` index of its first named slot
//! record, or `NONE`: absolute indices, as no offset is left in `params.attr`.
//!
//! WGSL twin: `geometry/mesh_attributes.wgsl`.

use super::bits;
use crate::geometry::mesh_attributes::MeshAttributes;
use crate::geometry::primitive::NONE;

/// Where the four attribute arrays start in `vertex_data`, in vec4s (`params.attr` in
/// `gpu/bindings.wgsl`): triangles, meshes, normals, uvs.
pub type AttrOffsets = [u32; 4];

/// Appends `a`'s records to `vertex_data`; returns where each array starts.
pub(super) fn encode(a: &MeshAttributes, vertex_data: &mut Vec<[f32; 4]>) -> AttrOffsets {
    let at = |v: &Vec<[f32; 4]>| v.len() as u32;
    let triangles = at(vertex_data);
    vertex_data.extend(a.triangles.iter().map(|t| {
        let [v0, v1, v2] = t.v;
        [bits(v0), bits(v1), bits(v2), bits(t.mesh)]
    }));
    let meshes = at(vertex_data);
    // Where the named slots and values will start: after the meshes, normals and uvs.
    let slots = meshes + (a.meshes.len() + a.normals.len() + a.uvs.len().div_ceil(2)) as u32;
    let values = slots + a.named_slots.len() as u32;
    let absolute = |base: u32, i: u32| if i == NONE { NONE } else { base + i };
    vertex_data.extend(a.meshes.iter().map(|m| {
        [
            bits(m.normal_base),
            bits(m.uv_base),
            bits(m.flags),
            bits(absolute(slots, m.named)),
        ]
    }));
    let normals = at(vertex_data);
    vertex_data.extend(a.normals.iter().map(|n| [n.x, n.y, n.z, 0.0]));
    let uvs = at(vertex_data);
    vertex_data.extend(a.uvs.chunks(2).map(|p| match p {
        [t0, t1] => [t0.x, t0.y, t1.x, t1.y],
        [t0] => [t0.x, t0.y, 0.0, 0.0],
        _ => unreachable!("chunks of two"),
    }));
    debug_assert_eq!(at(vertex_data), slots);
    vertex_data.extend(a.named_slots.iter().map(|s| {
        [
            bits(absolute(values, s.base)),
            bits(s.first_triangle),
            bits(u32::from(s.per_face)),
            0.0,
        ]
    }));
    vertex_data.extend(a.named_values.iter().map(|v| [v.x, v.y, v.z, 0.0]));
    [triangles, meshes, normals, uvs]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::mesh_attributes::{AttrMesh, AttrTriangle, HAS_NORMALS, HAS_UVS};
    use glam::{Vec2, Vec3};

    #[test]
    fn records_follow_the_light_triangles_and_pack_two_uvs_a_vec4() {
        let a = MeshAttributes {
            normals: vec![Vec3::X, Vec3::Y],
            uvs: vec![
                Vec2::new(0.1, 0.2),
                Vec2::new(0.3, 0.4),
                Vec2::new(0.5, 0.6),
            ],
            meshes: vec![AttrMesh {
                normal_base: 0,
                uv_base: 1,
                flags: HAS_NORMALS | HAS_UVS,
                named: NONE,
            }],
            triangles: vec![AttrTriangle {
                v: [0, 1, 2],
                mesh: 0,
            }],
            ..MeshAttributes::default()
        };
        let mut data = vec![[9.0; 4]; 3];
        let o = encode(&a, &mut data);
        assert_eq!(o, [3, 4, 5, 7]);
        assert_eq!(data.len(), 9);
        assert_eq!(data[3].map(f32::to_bits), [0, 1, 2, 0]);
        assert_eq!(data[4].map(f32::to_bits), [0, 1, 3, NONE]);
        assert_eq!(data[6], [0.0, 1.0, 0.0, 0.0]);
        assert_eq!(data[7], [0.1, 0.2, 0.3, 0.4]);
        assert_eq!(data[8], [0.5, 0.6, 0.0, 0.0]);
        // No attributes: nothing appended, every offset at the end.
        let mut data = vec![[0.0; 4]; 2];
        assert_eq!(encode(&MeshAttributes::default(), &mut data), [2; 4]);
        assert_eq!(data.len(), 2);
    }
}
