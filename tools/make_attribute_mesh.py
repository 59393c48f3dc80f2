#!/usr/bin/env python3
"""Writes tests/data/mitsuba/attribute_sphere.ply, the mesh of
tests/data/mitsuba/xml_mesh_attribute.xml (Mitsuba's `mesh_attribute` texture):

  a sphere of radius 1 centred at the origin, an icosahedron subdivided twice (each triangle
  into four, new vertices pushed out onto the sphere): 162 vertices, 320 triangles, wound
  counter-clockwise seen from outside (right-hand-rule normals point outwards);
  binary little-endian PLY with, per vertex (in this order)
      float x y z            the position
      float nx ny nz         the unit outward normal (= the position)
      float r g b            a smooth colour: (x + 1)/2 * 0.8 + 0.1, likewise g from y, b from z
      float rough_0          a smooth roughness in [0.05, 0.5]: 0.05 + 0.45 * (y + 1)/2
  and per face (in this order)
      list uchar int vertex_indices
      float color_0 color_1 color_2   a colour that changes strongly from face to face,
                                      uniform in [0.05, 0.95] from a fixed-seed RNG
      uchar tint_0 tint_1 tint_2      bytes uniform in 20..235 from the same RNG

Mitsuba 3.9.1's PLY loader names these attributes `vertex_color` (3 components), `vertex_rough`
(1), `face_color` (3) and `face_tint` (3; 8-bit integers, which it divides by 255 and
sRGB-decodes).

Deterministic (numpy's PCG64 with a fixed seed): running it again rewrites the same bytes.

Usage: python3 tools/make_attribute_mesh.py [OUT]   (default tests/data/mitsuba/attribute_sphere.ply)
"""
import os
import sys

import numpy as np

SEED = 20261207
SUBDIVISIONS = 2


def icosahedron():
    """The 12 vertices (on the unit sphere) and 20 faces of a regular icosahedron."""
    t = (1.0 + 5.0 ** 0.5) / 2.0
    v = np.array([
        [-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0],
        [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t],
        [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1],
    ], dtype=np.float64)
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    f = [
        (0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11),
        (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8),
        (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9),
        (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1),
    ]
    return [tuple(p) for p in v], f


def subdivide(verts, faces):
    """Each triangle (a, b, c) into four through its edges' midpoints, pushed onto the sphere;
    a midpoint shared by two triangles is made once (keyed by its sorted edge)."""
    verts = list(verts)
    mid = {}

    def midpoint(i, j):
        key = (min(i, j), max(i, j))
        if key not in mid:
            p = (np.array(verts[i]) + np.array(verts[j])) / 2.0
            p /= np.linalg.norm(p)
            mid[key] = len(verts)
            verts.append(tuple(p))
        return mid[key]

    out = []
    for a, b, c in faces:
        ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
        out += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
    return verts, out


def sphere():
    verts, faces = icosahedron()
    for _ in range(SUBDIVISIONS):
        verts, faces = subdivide(verts, faces)
    p = np.array(verts, dtype=np.float64)
    f = np.array(faces, dtype=np.int32)
    # Counter-clockwise seen from outside: the right-hand-rule normal points away from the centre.
    n = np.cross(p[f[:, 1]] - p[f[:, 0]], p[f[:, 2]] - p[f[:, 0]])
    assert (np.einsum("ij,ij->i", n, p[f].mean(axis=1)) > 0).all()
    return p, f


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join("tests", "data", "mitsuba",
                                                             "attribute_sphere.ply")
    p, f = sphere()
    assert p.shape == (162, 3) and f.shape == (320, 3)
    p32 = p.astype(np.float32)
    normal = p32 / np.linalg.norm(p32, axis=1, keepdims=True)
    color = ((p32 + 1.0) / 2.0 * 0.8 + 0.1).astype(np.float32)
    rough = (0.05 + 0.45 * (p32[:, 1:2] + 1.0) / 2.0).astype(np.float32)

    rng = np.random.Generator(np.random.PCG64(SEED))
    face_color = rng.uniform(0.05, 0.95, size=(len(f), 3)).astype(np.float32)
    face_tint = rng.integers(20, 236, size=(len(f), 3)).astype(np.uint8)

    vdt = np.dtype([(k, "<f4") for k in
                    ("x", "y", "z", "nx", "ny", "nz", "r", "g", "b", "rough_0")])
    vert = np.empty(len(p), dtype=vdt)
    for k, col in zip(("x", "y", "z"), p32.T):
        vert[k] = col
    for k, col in zip(("nx", "ny", "nz"), normal.T):
        vert[k] = col
    for k, col in zip(("r", "g", "b"), color.T):
        vert[k] = col
    vert["rough_0"] = rough[:, 0]

    fdt = np.dtype([("n", "u1"), ("i", "<i4", (3,)), ("color", "<f4", (3,)),
                    ("tint", "u1", (3,))])
    face = np.empty(len(f), dtype=fdt)
    face["n"] = 3
    face["i"] = f
    face["color"] = face_color
    face["tint"] = face_tint

    header = "\n".join([
        "ply",
        "format binary_little_endian 1.0",
        "comment tools/make_attribute_mesh.py: unit icosphere (2 subdivisions), attributes "
        "vertex_color, vertex_rough, face_color, face_tint",
        "element vertex %d" % len(p),
        "property float x", "property float y", "property float z",
        "property float nx", "property float ny", "property float nz",
        "property float r", "property float g", "property float b",
        "property float rough_0",
        "element face %d" % len(f),
        "property list uchar int vertex_indices",
        "property float color_0", "property float color_1", "property float color_2",
        "property uchar tint_0", "property uchar tint_1", "property uchar tint_2",
        "end_header",
    ]) + "\n"
    with open(out, "wb") as fh:
        fh.write(header.encode("ascii"))
        fh.write(vert.tobytes())
        fh.write(face.tobytes())
    print("wrote %s: %d vertices, %d triangles" % (out, len(p), len(f)))


if __name__ == "__main__":
    main()
