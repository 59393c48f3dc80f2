#!/usr/bin/env python3
"""Writes the mesh and texture files of tests/data/scenes/textured_mesh.json (issue 17):

  textured_mesh_torus.obj    a coarse torus (32 x 16 quads = 1024 triangles), exact vertex
                             normals ('vn') and texture coordinates ('vt', OBJ's bottom-up v)
  textured_mesh_sphere.ply   a coarse unit UV sphere (24 segments x 12 stacks = 528 triangles),
                             binary little-endian PLY with x y z nx ny nz u v per vertex
                             (v = 0 at the north pole: the image-row convention, stored as is)
  textured_mesh_albedo.png   a 64 x 32 8-bit RGB (sRGB) image, asymmetric in both axes, so a
                             flipped or shifted texture coordinate shows

Deterministic (no randomness; only the Python standard library): running it again rewrites the
same bytes. The meshes are coarse on purpose: their facets are 11.25 deg (torus) and 15 deg
(sphere) apart, so interpolated vertex normals and flat facets give visibly different images.

Usage: python3 tools/make_textured_mesh.py [OUT_DIR]   (default tests/data/scenes)
"""
import math
import os
import struct
import sys
import zlib

# ----------------------------------------------------------------------------
# Torus (OBJ)
# ----------------------------------------------------------------------------

TORUS_MAJOR, TORUS_MINOR = 0.5, 0.2      # radii, axis +y, centred at the origin
TORUS_NU, TORUS_NV = 32, 16              # segments around the axis, around the tube


def torus():
    """Vertices (position, normal, (u, v_image)) on an (NU+1) x (NV+1) grid (the seams are
    repeated so the texture coordinates are continuous) and triangles wound so that the
    right-hand rule gives the outward normal."""
    verts = []
    for i in range(TORUS_NU + 1):
        phi = 2 * math.pi * i / TORUS_NU                  # around +y
        for j in range(TORUS_NV + 1):
            theta = 2 * math.pi * j / TORUS_NV            # around the tube, 0 = outer equator
            c = (math.cos(phi), 0.0, -math.sin(phi))      # direction of the tube's centre
            n = (math.cos(theta) * c[0], math.sin(theta), math.cos(theta) * c[2])
            r = TORUS_MAJOR + TORUS_MINOR * math.cos(theta)
            p = (r * c[0], TORUS_MINOR * math.sin(theta), r * c[2])
            verts.append((p, n, (i / TORUS_NU, j / TORUS_NV)))
    idx = lambda i, j: i * (TORUS_NV + 1) + j
    tris = []
    for i in range(TORUS_NU):
        for j in range(TORUS_NV):
            a, b, c, d = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
            tris += [(a, b, c), (a, c, d)]
    return verts, tris


def write_obj(path, verts, tris):
    """OBJ with v/vt/vn per corner; vt holds OBJ's bottom-up v = 1 - v_image (readers that
    follow Mitsuba, lumis included, flip it back)."""
    lines = ["# torus, tools/make_textured_mesh.py: R = %g, r = %g, %d x %d quads, axis +y"
             % (TORUS_MAJOR, TORUS_MINOR, TORUS_NU, TORUS_NV)]
    for p, _, _ in verts:
        lines.append("v %.7f %.7f %.7f" % p)
    for _, _, (u, v) in verts:
        lines.append("vt %.7f %.7f" % (u, 1.0 - v))
    for _, n, _ in verts:
        lines.append("vn %.7f %.7f %.7f" % n)
    for t in tris:
        lines.append("f " + " ".join("%d/%d/%d" % (k + 1, k + 1, k + 1) for k in t))
    with open(path, "w", newline="\n") as f:
        f.write("\n".join(lines) + "\n")


# ----------------------------------------------------------------------------
# UV sphere (PLY)
# ----------------------------------------------------------------------------

SPHERE_NU, SPHERE_NV = 24, 12            # segments (azimuth), stacks (polar angle)


def sphere():
    """Unit sphere; vertex (i, j) at polar angle pi*j/NV from +y, azimuth 2*pi*i/NU; uv
    (i/NU, j/NV), v = 0 at the north pole (+y). Each pole has one vertex per segment, at the u of
    the middle of the one pole triangle that uses it, so that the texture coordinates are
    continuous; the degenerate halves of the pole quads are left out."""
    verts = []
    for j in range(SPHERE_NV + 1):
        theta = math.pi * j / SPHERE_NV
        for i in range(SPHERE_NU + 1):
            u = i / SPHERE_NU
            if j == 0:
                u = (i - 0.5) / SPHERE_NU      # the top triangle of segment i - 1 uses it
            elif j == SPHERE_NV:
                u = (i + 0.5) / SPHERE_NU      # the bottom triangle of segment i uses it
            phi = 2 * math.pi * u
            d = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
            if j in (0, SPHERE_NV):
                d = (0.0, math.cos(theta), 0.0)
            verts.append((d, d, (u, j / SPHERE_NV)))
    idx = lambda i, j: j * (SPHERE_NU + 1) + i
    tris = []
    for j in range(SPHERE_NV):
        for i in range(SPHERE_NU):
            a, b = idx(i, j), idx(i + 1, j)               # upper row (towards +y)
            c, d = idx(i + 1, j + 1), idx(i, j + 1)       # lower row
            # Seen from outside, increasing azimuth runs towards -z from +x: (d, c, b) and
            # (d, b, a) are counter-clockwise there, so the right-hand rule points outward.
            if j != 0:
                tris.append((d, b, a))
            if j != SPHERE_NV - 1:
                tris.append((d, c, b))
    return verts, tris


def write_ply(path, verts, tris):
    header = ("ply\nformat binary_little_endian 1.0\n"
              "comment unit UV sphere, tools/make_textured_mesh.py: %d segments x %d stacks\n"
              "element vertex %d\n"
              "property float x\nproperty float y\nproperty float z\n"
              "property float nx\nproperty float ny\nproperty float nz\n"
              "property float u\nproperty float v\n"
              "element face %d\nproperty list uchar int vertex_indices\nend_header\n"
              % (SPHERE_NU, SPHERE_NV, len(verts), len(tris)))
    body = bytearray()
    for p, n, uv in verts:
        body += struct.pack("<8f", *p, *n, *uv)
    for t in tris:
        body += struct.pack("<B3i", 3, *t)
    with open(path, "wb") as f:
        f.write(header.encode("ascii"))
        f.write(bytes(body))


# ----------------------------------------------------------------------------
# Texture (PNG)
# ----------------------------------------------------------------------------

TEX_W, TEX_H = 64, 32


def texture():
    """8-bit sRGB rows, top first: a warm-to-cool ramp along u, darker towards the bottom
    (v), with a bright 'F'-shaped mark in the upper left quarter (no mirror symmetry)."""
    rows = []
    for y in range(TEX_H):
        row = []
        for x in range(TEX_W):
            u, v = (x + 0.5) / TEX_W, (y + 0.5) / TEX_H
            r = 0.85 - 0.55 * u
            g = 0.35 + 0.35 * math.sin(math.pi * u) * (1.0 - 0.6 * v)
            b = 0.15 + 0.65 * u * (1.0 - 0.5 * v)
            s = 1.0 - 0.55 * v
            rgb = [r * s, g * s, b * s]
            # 'F': a vertical bar and two arms of different lengths, pixels (6..25, 4..27).
            mark = (6 <= x < 10 and 4 <= y < 28) or (10 <= x < 26 and 4 <= y < 8) \
                or (10 <= x < 20 and 14 <= y < 18)
            if mark:
                rgb = [0.95, 0.92, 0.55]
            # Thin dark stripes every 8 columns in the right half.
            if x >= 32 and x % 8 == 0:
                rgb = [c * 0.25 for c in rgb]
            row.append(bytes(max(0, min(255, int(round(255 * c)))) for c in rgb))
        rows.append(b"".join(row))
    return rows


def write_png(path, rows, width, height):
    def chunk(kind, data):
        c = struct.pack(">I", len(data)) + kind + data
        return c + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + r for r in rows)          # filter type 0 on every row
    ihdr = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)   # 8-bit RGB
    # sRGB chunk (rendering intent 0): the file is sRGB-encoded, as readers assume anyway.
    data = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"sRGB", b"\x00")
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
    with open(path, "wb") as f:
        f.write(data)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "tests", "data", "scenes")
    v, t = torus()
    write_obj(os.path.join(out, "textured_mesh_torus.obj"), v, t)
    print("torus: %d vertices, %d triangles" % (len(v), len(t)))
    v, t = sphere()
    write_ply(os.path.join(out, "textured_mesh_sphere.ply"), v, t)
    print("sphere: %d vertices, %d triangles" % (len(v), len(t)))
    write_png(os.path.join(out, "textured_mesh_albedo.png"), texture(), TEX_W, TEX_H)
    print("texture: %d x %d" % (TEX_W, TEX_H))


if __name__ == "__main__":
    main()
