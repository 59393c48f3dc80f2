#!/usr/bin/env python3
"""Neutral JSON scene  ->  Mitsuba 3 scene dict, and render it.

ORIGIN: a copy of the shared converter `../shared/tools/scene_to_mitsuba.py` (shared/tools/, not
in this repository; that file is not edited), extended here for lumis' textured mesh reference
(issue 17, tests/data/scenes/textured_mesh.json, tools/make_mesh_reference.sh). Everything the
shared file converts is converted the same way here (same Mitsuba dicts, seeds and passes), so
its references stay reproducible with either copy. Added (each mapping checked numerically
against Mitsuba 3.9.1 or by renders compared with lumis; see tests/data/refs/README.md):
  * textures (scene format version 2, docs/scene-format.md "Textures") in the slots lumis
    textures: diffuse 'albedo' -> 'reflectance', conductor 'reflectance' ->
    'specular_reflectance', conductor / dielectric 'alpha' -> 'alpha' (a textured alpha always
    makes the rough variant).
      - 'bitmap': 'file' (relative to the scene file) -> 'filename', filter_type 'bilinear',
        'wrap' -> 'wrap_mode' (repeat / mirror / clamp, the same texel-index rules), 'raw' ->
        'raw', 'uv_scale' [su, sv] + 'uv_offset' [ou, ov] -> to_uv =
        [[su,0,0,ou],[0,sv,0,ov],[0,0,1,0],[0,0,0,1]]. A scalar slot reads the luminance
        (Mitsuba's eval_1 of an RGB bitmap, lumis' default 'channel'). Mitsuba's bitmap has
        neither 'scale' nor 'channel': a bitmap with scale != 1 or channel r/g/b is baked here
        into a linear float EXR (decoded as lumis decodes it, times scale, the channel copied to
        R, G and B, whose luminance is the channel itself) that Mitsuba then filters the same way.
      - 'checkerboard': color0/color1 (number or [r,g,b]; defaults 0.4, 0.2) -> color0/color1,
        same to_uv. Mitsuba's eval_1 (what its scalar slots read) picks color0 where eval picks
        color1 and vice versa, while lumis has one rule for both: so in a SCALAR slot (alpha)
        color0 and color1 are written swapped. An [r,g,b] colour in a scalar slot is written as
        its luminance by lumis' rule (0.212671 R + 0.715160 G + 0.072169 B, grey exact).
  * texture coordinates of quads and box faces: the PLY written for them carries u along
    edge_u and v along edge_v (lumis' convention; the shared converter wrote none, which gives
    Mitsuba's barycentric uv). A textured material on a shape whose uv lumis and Mitsuba define
    differently (sphere, disk, polygon, triangles, a mesh file without texture coordinates) is
    rejected by name here rather than converted into a different image.
  * a textured emission is rejected by name (lumis refuses it too, for now).

Usage:
    python scene_to_mitsuba.py SCENE.json SPP VARIANT OUT.exr SEED [--threads N]

VARIANT is 'scalar_rgb' or 'llvm_ad_rgb' (the latter needs libLLVM >= 16 with
x86 fminimum support; on Debian bookworm: `apt-get install libllvm19`).

Conventions implemented here (they define the neutral format's semantics):
  * camera: pinhole at `from`, looking at `to`, `up` hint, vertical FOV
    `vfov_deg`, `width` x `height` pixels.  Image left->right runs along
    cross(forward, up), top->bottom along -up (Mitsuba look_at).  Each pixel
    is the plain average of radiance over the pixel square (box filter,
    radius 0.5), uniform random positions in the pixel ('independent').
  * integrator: Mitsuba 'path' (unidirectional PT, NEE + BSDF sampling
    combined with the power heuristic, Russian roulette from depth 5),
    hide_emitters = false, max_depth as in the JSON (1 = directly visible
    emission only, 2 = direct lighting, -1 = unlimited).
  * materials are TWO-SIDED (wrapped in Mitsuba's 'twosided') unless the
    material says "two_sided": false; emitters are one-sided: only the side
    the normal points to emits.  (The references in shared/refs were made
    one-sided; their scenes never show a back face, so the images agree.)
    A 'dielectric' is never wrapped: its two sides are the two media
    ("two_sided" on a dielectric is rejected).
  * "background": a colour [r,g,b] is constant environment radiance (Mitsuba
    'constant' emitter).  An object {"envmap": FILE, "scale": s,
    "rotate_y_deg": a} is Mitsuba's 'envmap' emitter (lat-long EXR), FILE
    resolved relative to the folder of the scene file, `scale` s (default 1),
    to_world = rotation by a degrees about +y (default 0; Mitsuba's rotate,
    i.e. the box convention x' = cos*x + sin*z, z' = -sin*x + cos*z).
  * materials: 'diffuse' -> diffuse; 'conductor' with alpha == 0 -> smooth
    'conductor', alpha > 0 -> 'roughconductor' (isotropic GGX, visible-normal
    sampling, separable Smith G1(wi)G1(wo)); eta/k -> exact complex Fresnel;
    'reflectance' -> material='none' (Fresnel = 1) * specular_reflectance.
    'dielectric' (ior default 1.5, alpha default 0): alpha == 0 -> smooth
    'dielectric' (int_ior = ior, ext_ior = 1); alpha > 0 -> 'roughdielectric'
    (distribution ggx, the same alpha, sample_visible true, same iors).
  * shapes: quad/polygon/triangles/box become flat-shaded triangle meshes
    (face normals); disk and sphere use Mitsuba's analytic shapes.
    'mesh': FILE (.obj or .ply, relative to the scene file's folder) ->
    Mitsuba 'obj' / 'ply' shape, `to_world` a 4x4 row-major matrix (list of
    4 rows; default identity), `face_normals` passed through.  The format
    says a file WITHOUT vertex normals is shaded flat, whereas Mitsuba would
    compute smooth vertex normals for it; so such a file is loaded with
    face_normals = true.  glTF files have no Mitsuba 3.9.1 loader and are
    rejected here.
    Shapes with 'emission' get an 'area' emitter (radiance, front side only,
    spheres emit outward).  Shapes without 'material' get black diffuse.
"""
import argparse
import json
import math
import os
import sys
import tempfile
import time

import numpy as np


# ----------------------------------------------------------------------------
# Geometry helpers (pure numpy, no Mitsuba needed)
# ----------------------------------------------------------------------------

def _a(x):
    return np.asarray(x, dtype=np.float64)


def _normalize(v):
    v = _a(v)
    return v / np.linalg.norm(v)


def rotate_y(p, deg):
    """Rotate points (N,3) about the +y axis through the origin, RTNW convention:
    x' = cos*x + sin*z ; z' = -sin*x + cos*z."""
    t = math.radians(deg)
    c, s = math.cos(t), math.sin(t)
    p = _a(p).copy()
    x, z = p[:, 0].copy(), p[:, 2].copy()
    p[:, 0] = c * x + s * z
    p[:, 2] = -s * x + c * z
    return p


def box_mesh(bmin, bmax, rot_deg=0.0, translate=(0, 0, 0)):
    """12 triangles with outward normals."""
    bmin, bmax = _a(bmin), _a(bmax)
    tris = []
    for axis in range(3):
        u_ax, v_ax = (axis + 1) % 3, (axis + 2) % 3   # cross(e_u, e_v) = +e_axis
        for side, coord in ((+1, bmax[axis]), (-1, bmin[axis])):
            c = np.zeros(3)
            c[axis] = coord
            c[u_ax], c[v_ax] = bmin[u_ax], bmin[v_ax]
            eu = np.zeros(3); eu[u_ax] = bmax[u_ax] - bmin[u_ax]
            ev = np.zeros(3); ev[v_ax] = bmax[v_ax] - bmin[v_ax]
            if side < 0:
                eu, ev = ev, eu                       # flip -> normal -e_axis
                c = c.copy()
            p0, p1, p2, p3 = c, c + eu, c + eu + ev, c + ev
            tris += [(p0, p1, p2), (p0, p2, p3)]
    P = np.array([v for t in tris for v in t], dtype=np.float64)
    P = rotate_y(P, rot_deg) + _a(translate)
    F = np.arange(len(P)).reshape(-1, 3)
    return P, F


# A face (corner, corner+edge_u, corner+edge_u+edge_v, corner+edge_v) as triangles (0,1,2),
# (0,2,3): u runs along edge_u, v along edge_v (lumis' QUAD_UVS in renderer/src/scene/build.rs).
_QUAD_UV = np.array([[0, 0], [1, 0], [1, 1], [0, 0], [1, 1], [0, 1]], dtype=np.float64)


def shape_uvs(shape, P, F):
    """Texture coordinates (one per row of P) for a quad or box built by shape_to_mesh, else None.
    box_mesh emits each face's triangles (p0,p1,p2),(p0,p2,p3) as 6 separate vertices."""
    t = shape["type"]
    if t == "quad":
        return np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=np.float64)
    if t == "box":
        return np.tile(_QUAD_UV, (len(P) // 6, 1))
    return None


def shape_to_mesh(shape):
    """Return (positions (N,3), faces (M,3)) for mesh-like shapes, else None."""
    t = shape["type"]
    if t == "quad":
        c, eu, ev = _a(shape["corner"]), _a(shape["edge_u"]), _a(shape["edge_v"])
        P = np.array([c, c + eu, c + eu + ev, c + ev])
        F = np.array([[0, 1, 2], [0, 2, 3]])
        return P, F
    if t == "polygon":
        P = _a(shape["vertices"])
        F = np.array([[0, i, i + 1] for i in range(1, len(P) - 1)])
        return P, F
    if t == "triangles":
        return _a(shape["positions"]), np.asarray(shape["indices"], dtype=np.int64)
    if t == "box":
        return box_mesh(shape["min"], shape["max"], shape.get("rotate_y_deg", 0.0),
                        shape.get("translate", [0, 0, 0]))
    return None


def write_ply(path, P, F, UV=None):
    """Binary PLY, one separate vertex triple per triangle (no sharing); with UV (one (u, v) per
    entry of P) the vertices also carry texture coordinates u, v (PLY: stored as is)."""
    F = np.asarray(F).reshape(-1)
    P = _a(P)[F]
    nf = len(P) // 3
    uv_props = "property float u\nproperty float v\n" if UV is not None else ""
    header = ("ply\nformat binary_little_endian 1.0\n"
              f"element vertex {len(P)}\nproperty float x\nproperty float y\nproperty float z\n"
              + uv_props +
              f"element face {nf}\nproperty list uchar int vertex_indices\nend_header\n")
    faces = np.zeros(nf, dtype=[("n", "u1"), ("i", "<i4", 3)])
    faces["n"] = 3
    faces["i"] = np.arange(3 * nf, dtype=np.int32).reshape(-1, 3)
    verts = P.astype("<f4")
    if UV is not None:
        verts = np.concatenate([verts, _a(UV)[F].astype("<f4")], axis=1)
    with open(path, "wb") as f:
        f.write(header.encode("ascii"))
        f.write(np.ascontiguousarray(verts).tobytes())
        f.write(faces.tobytes())


# ----------------------------------------------------------------------------
# Mitsuba dict construction
# ----------------------------------------------------------------------------

def _rgb(v):
    return {"type": "rgb", "value": [float(x) for x in v]}


def _lum(c):
    """lumis' scalar reading of a colour (textures/mod.rs `luminance`: Mitsuba's coefficients,
    a grey value exact)."""
    c = [float(x) for x in c]
    if c[0] == c[1] == c[2]:
        return c[0]
    return 0.212671 * c[0] + 0.715160 * c[1] + 0.072169 * c[2]


def _srgb_decode(c):
    c = np.asarray(c, dtype=np.float64)
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def _to_uv(t, mi):
    su, sv = [float(x) for x in t.get("uv_scale", [1, 1])]
    ou, ov = [float(x) for x in t.get("uv_offset", [0, 0])]
    return mi.ScalarTransform4f([[su, 0, 0, ou], [0, sv, 0, ov], [0, 0, 1, 0], [0, 0, 0, 1]])


_BITMAP_KEYS = {"type", "file", "wrap", "raw", "uv_scale", "uv_offset", "scale", "channel"}
_CHECKER_KEYS = {"type", "color0", "color1", "uv_scale", "uv_offset"}


def _bake_bitmap(path, raw, scale, channel, tmpdir, mi):
    """The texels lumis filters (linear RGB: 8/16-bit files sRGB-decoded unless raw, float files
    as they are), times scale, the channel copied to R, G and B if one is chosen: a float EXR."""
    bmp = mi.Bitmap(path)
    is_float = bmp.component_format() in (mi.Struct.Type.Float16, mi.Struct.Type.Float32,
                                          mi.Struct.Type.Float64)
    a = np.array(bmp, dtype=np.float64)
    if a.ndim == 2:
        a = a[:, :, None]
    if not is_float:
        a = a / float(np.iinfo(np.array(bmp).dtype).max)
        if not raw:
            a = _srgb_decode(a)
    if a.shape[2] in (1, 2):                       # grey (+ alpha): grey to R, G and B
        a = np.repeat(a[:, :, :1], 3, axis=2)
    a = a[:, :, :3] * np.asarray(scale, dtype=np.float64).reshape(1, 1, -1)
    if channel in ("r", "g", "b"):
        a = np.repeat(a[:, :, "rgb".index(channel)][:, :, None], 3, axis=2)
    out = os.path.join(tmpdir, "baked_%d.exr" % len(os.listdir(tmpdir)))
    write_exr(out, a.astype(np.float32))
    return out


def texture_to_mitsuba(t, scalar, ctx, where):
    """A texturable value: a constant (number or [r, g, b]) or a texture object -> Mitsuba.
    scalar: the slot is a scalar (alpha). ctx: (mi, base_dir, tmpdir). where: JSON path."""
    mi, base_dir, tmpdir = ctx
    if not isinstance(t, dict):
        if scalar:
            return float(t) if not isinstance(t, list) else _lum(t)
        return _rgb(t if isinstance(t, list) else [t, t, t])
    kind = t.get("type")
    if kind == "bitmap":
        unknown = set(t) - _BITMAP_KEYS
        if unknown:
            raise ValueError("%s: unknown keys %r" % (where, sorted(unknown)))
        path = os.path.join(base_dir, t["file"])
        if not os.path.isfile(path):
            raise ValueError("%s.file: %r not found" % (where, t["file"]))
        wrap = t.get("wrap", "repeat")
        if wrap not in ("repeat", "mirror", "clamp"):
            raise ValueError("%s.wrap: %r" % (where, wrap))
        raw = bool(t.get("raw", False))
        scale = t.get("scale", 1.0)
        scale = [float(scale)] * 3 if not isinstance(scale, list) else [float(x) for x in scale]
        channel = t.get("channel", "luminance")
        if channel != "luminance" and not scalar:
            raise ValueError("%s.channel: only in a scalar slot" % where)
        if channel not in ("luminance", "r", "g", "b"):
            raise ValueError("%s.channel: %r" % (where, channel))
        if scale != [1.0, 1.0, 1.0] or channel != "luminance":
            path, raw = _bake_bitmap(path, raw, scale, channel, tmpdir, mi), False
        return {"type": "bitmap", "filename": path, "filter_type": "bilinear",
                "wrap_mode": wrap, "raw": raw, "to_uv": _to_uv(t, mi)}
    if kind == "checkerboard":
        unknown = set(t) - _CHECKER_KEYS
        if unknown:
            raise ValueError("%s: unknown keys %r" % (where, sorted(unknown)))
        c0 = texture_to_mitsuba(t.get("color0", 0.4), scalar, ctx, where + ".color0")
        c1 = texture_to_mitsuba(t.get("color1", 0.2), scalar, ctx, where + ".color1")
        if scalar:
            c0, c1 = c1, c0            # Mitsuba's eval_1 swaps them (see the header)
        return {"type": "checkerboard", "color0": c0, "color1": c1, "to_uv": _to_uv(t, mi)}
    raise ValueError("%s.type: unknown texture type %r" % (where, kind))


def is_textured(m):
    """Does the material (a dict, or None) have a texture in any slot?"""
    return m is not None and any(isinstance(m.get(k), dict) for k in ("albedo", "reflectance", "alpha"))


def material_to_bsdf(m, ctx=None, where="material"):
    """Scene-format materials are two-sided unless "two_sided": false (Mitsuba's are one-sided).
    A dielectric is never wrapped: its two sides are the two media.
    ctx = (mi, base_dir, tmpdir), needed only for textures."""
    if m is None:
        return {"type": "diffuse", "reflectance": _rgb([0, 0, 0])}
    if is_textured(m) and ctx is None:
        raise ValueError("%s: a textured material needs the scene's folder (ctx)" % where)
    b = _material_to_bsdf(m, ctx, where)
    if m["type"] == "dielectric":
        if "two_sided" in m:
            raise ValueError("'two_sided' is an error on a dielectric (its two sides are the two media)")
        return b
    return b if m.get("two_sided", True) is False else {"type": "twosided", "bsdf": b}


def _alpha(m, ctx, where):
    """(is rough, Mitsuba alpha): a constant 0 is the smooth variant, a texture always rough."""
    a = m.get("alpha", 0.0)
    if isinstance(a, dict):
        return True, texture_to_mitsuba(a, True, ctx, where + ".alpha")
    return float(a) != 0.0, float(a)


def _material_to_bsdf(m, ctx, where):
    tex = lambda key, scalar=False: texture_to_mitsuba(m[key], scalar, ctx, where + "." + key)
    if m["type"] == "plastic":
        raise ValueError("'plastic' has no exact Mitsuba counterpart; reference it by other means")
    if m["type"] == "diffuse":
        return {"type": "diffuse", "reflectance": tex("albedo")}
    if m["type"] == "conductor":
        rough, alpha = _alpha(m, ctx, where)
        d = {"type": "conductor"} if not rough else {
            "type": "roughconductor", "distribution": "ggx", "alpha": alpha,
            "sample_visible": True}
        if "reflectance" in m:
            d["material"] = "none"
            d["specular_reflectance"] = tex("reflectance")
        else:
            d["eta"] = _rgb(m["eta"])
            d["k"] = _rgb(m["k"])
            d["specular_reflectance"] = _rgb([1, 1, 1])
        return d
    if m["type"] == "dielectric":
        ior = float(m.get("ior", 1.5))
        rough, alpha = _alpha(m, ctx, where)
        if not (ior > 0.0 and ior != 1.0):
            raise ValueError("dielectric ior must be > 0 and != 1, got %r" % ior)
        d = {"type": "dielectric"} if not rough else {
            "type": "roughdielectric", "distribution": "ggx", "alpha": alpha,
            "sample_visible": True}
        d["int_ior"] = ior
        d["ext_ior"] = 1.0
        return d
    raise ValueError("unknown material type %r" % m["type"])


def _frame_matrix(center, normal, radius):
    n = _normalize(normal)
    a = np.array([1.0, 0, 0]) if abs(n[0]) < 0.9 else np.array([0, 1.0, 0])
    t1 = _normalize(np.cross(a, n))
    t2 = np.cross(n, t1)                     # (t1, t2, n) right-handed
    M = np.eye(4)
    M[:3, 0], M[:3, 1], M[:3, 2], M[:3, 3] = t1 * radius, t2 * radius, n * radius, _a(center)
    return M


def _mesh_file_has_normals(path):
    """Does an OBJ / PLY file carry vertex normals ('vn' lines / an 'nx' vertex property)?"""
    ext = os.path.splitext(path)[1].lower()
    if ext == ".obj":
        with open(path, "rb") as f:
            return any(line.lstrip().startswith(b"vn ") or line.lstrip().startswith(b"vn\t")
                       for line in f)
    if ext == ".ply":
        with open(path, "rb") as f:
            element = None
            for raw in f:
                w = raw.decode("ascii", "replace").split()
                if not w:
                    continue
                if w[0] == "end_header":
                    break
                if w[0] == "element":
                    element = w[1]
                elif w[0] == "property" and element == "vertex" and w[-1] == "nx":
                    return True
        return False
    raise ValueError("mesh file %r: only .obj and .ply have a Mitsuba counterpart here" % path)


def _mesh_file_has_uvs(path):
    """Does an OBJ / PLY file carry texture coordinates ('vt' lines / a u,v s,t or
    texture_u,texture_v vertex property pair)?"""
    ext = os.path.splitext(path)[1].lower()
    if ext == ".obj":
        with open(path, "rb") as f:
            return any(line.lstrip().startswith(b"vt ") or line.lstrip().startswith(b"vt\t")
                       for line in f)
    with open(path, "rb") as f:
        element, props = None, set()
        for raw in f:
            w = raw.decode("ascii", "replace").split()
            if not w:
                continue
            if w[0] == "end_header":
                break
            if w[0] == "element":
                element = w[1]
            elif w[0] == "property" and element == "vertex":
                props.add(w[-1])
    return any({a, b} <= props for a, b in (("u", "v"), ("s", "t"), ("texture_u", "texture_v")))


def _transform(mi, rows):
    M = _a(rows)
    if M.shape != (4, 4):
        raise ValueError("to_world must be 4x4 (a list of 4 rows), got shape %r" % (M.shape,))
    return mi.ScalarTransform4f(M.tolist())          # row-major: rows are matrix rows


def background_to_emitter(bg, base_dir, mi):
    """[r,g,b] -> 'constant' (None if black); {"envmap", "scale", "rotate_y_deg"} -> 'envmap'."""
    if isinstance(bg, dict):
        unknown = set(bg) - {"envmap", "scale", "rotate_y_deg"}
        if unknown:
            raise ValueError("background: unknown keys %r" % sorted(unknown))
        return {"type": "envmap",
                "filename": os.path.join(base_dir, bg["envmap"]),
                "scale": float(bg.get("scale", 1.0)),
                "to_world": mi.ScalarTransform4f().rotate(
                    axis=[0, 1, 0], angle=float(bg.get("rotate_y_deg", 0.0)))}
    if any(float(x) != 0.0 for x in bg):
        return {"type": "constant", "radiance": _rgb(bg)}
    return None


def scene_to_dict(scene, spp, tmpdir, mi, base_dir="."):
    """Build the Mitsuba scene dict. Meshes are written as PLY into tmpdir.
    base_dir: the folder of the scene file (files named in the scene are relative to it)."""
    base_dir = os.path.abspath(base_dir)
    cam = scene["camera"]
    W, H = int(cam["width"]), int(cam["height"])
    d = {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": int(scene["max_depth"]),
                       "hide_emitters": False},
        "sensor": {
            "type": "perspective",
            "fov": float(cam["vfov_deg"]), "fov_axis": "y",
            "near_clip": 1e-3, "far_clip": 1e7,
            "to_world": mi.ScalarTransform4f().look_at(
                origin=[float(x) for x in cam["from"]],
                target=[float(x) for x in cam["to"]],
                up=[float(x) for x in cam["up"]]),
            "sampler": {"type": "independent", "sample_count": int(spp)},
            "film": {"type": "hdrfilm", "width": W, "height": H,
                     "rfilter": {"type": "box"}, "pixel_format": "rgb",
                     "component_format": "float32", "sample_border": False},
        },
    }
    em = background_to_emitter(scene.get("background", [0, 0, 0]), base_dir, mi)
    if em is not None:
        d["background"] = em
    mats = scene.get("materials", {})
    ctx = (mi, base_dir, tmpdir)
    for i, s in enumerate(scene["shapes"]):
        mname = s.get("material")
        mat = mats[mname] if mname is not None else None
        bsdf = material_to_bsdf(mat, ctx, "materials.%s" % mname)
        if isinstance(s.get("emission"), dict):
            raise ValueError("shapes[%d].emission: textured emission is not converted" % i)
        textured = is_textured(mat)
        if textured and (s["type"] in ("sphere", "disk", "polygon", "triangles") or (
                s["type"] == "mesh" and not _mesh_file_has_uvs(os.path.join(base_dir, s["file"])))):
            raise ValueError("shapes[%d]: material %r is textured, but lumis and Mitsuba define "
                             "the texture coordinates of this shape (%s%s) differently"
                             % (i, mname, s["type"], " without uv" if s["type"] == "mesh" else ""))
        mesh = shape_to_mesh(s)
        if mesh is not None:
            path = os.path.join(tmpdir, "shape_%04d.ply" % i)
            # uv only where textures read them, so untextured scenes convert byte for byte as
            # the shared converter converts them.
            write_ply(path, *mesh, UV=shape_uvs(s, *mesh) if textured else None)
            sd = {"type": "ply", "filename": path, "face_normals": True}
        elif s["type"] == "sphere":
            sd = {"type": "sphere", "center": [float(x) for x in s["center"]],
                  "radius": float(s["radius"])}
        elif s["type"] == "disk":
            sd = {"type": "disk", "to_world": mi.ScalarTransform4f(
                _frame_matrix(s["center"], s["normal"], float(s["radius"])).tolist())}
        elif s["type"] == "mesh":
            path = os.path.join(base_dir, s["file"])
            ext = os.path.splitext(path)[1].lower()
            if ext not in (".obj", ".ply"):
                raise ValueError("shapes[%d].file: %r has no Mitsuba 3.9.1 loader (only .obj, .ply)"
                                 % (i, s["file"]))
            if not os.path.isfile(path):
                raise ValueError("shapes[%d].file: %r not found" % (i, s["file"]))
            # The format: vertex normals of the file are shading normals unless face_normals;
            # a file without them is flat (Mitsuba would otherwise compute smooth ones).
            face_normals = bool(s.get("face_normals", False)) or not _mesh_file_has_normals(path)
            sd = {"type": ext[1:], "filename": path, "face_normals": face_normals}
            if "to_world" in s:
                sd["to_world"] = _transform(mi, s["to_world"])
        else:
            raise ValueError("unknown shape type %r" % s["type"])
        sd["bsdf"] = bsdf
        if "emission" in s and any(float(x) != 0.0 for x in s["emission"]):
            sd["emitter"] = {"type": "area", "radiance": _rgb(s["emission"])}
        d["shape_%04d" % i] = sd
    return d


# ----------------------------------------------------------------------------
# Rendering
# ----------------------------------------------------------------------------

def setup(variant, threads=None):
    import mitsuba as mi
    import drjit as dr
    mi.set_variant(variant)
    if threads:
        dr.set_thread_count(int(threads))
    return mi, dr


def _scene_and_dir(scene_json, base_dir=None):
    """(scene dict, folder its file names are relative to): a path's own folder, else base_dir or '.'."""
    if isinstance(scene_json, str):
        return json.load(open(scene_json)), (base_dir or os.path.dirname(os.path.abspath(scene_json)))
    return scene_json, (base_dir or ".")


def load(scene_json, spp, variant="scalar_rgb", threads=None, spp_per_pass=None, base_dir=None):
    mi, dr = setup(variant, threads)
    scene, base_dir = _scene_and_dir(scene_json, base_dir)
    with tempfile.TemporaryDirectory(prefix="mts_") as td:
        d = scene_to_dict(scene, spp, td, mi, base_dir)
        if spp_per_pass and variant.startswith("llvm") and spp > spp_per_pass:
            assert spp % spp_per_pass == 0
            d["integrator"]["samples_per_pass"] = int(spp_per_pass)
        ms = mi.load_dict(d)
    return mi, dr, ms


def default_spp_per_pass(scene, spp, max_lanes=1 << 22):
    """Largest power of two dividing spp with W*H*chunk <= max_lanes (LLVM memory)."""
    cam = scene["camera"]
    px = int(cam["width"]) * int(cam["height"])
    p = 1
    while spp % (2 * p) == 0 and px * 2 * p <= max_lanes:
        p *= 2
    return p


def render(scene_json, spp, variant="scalar_rgb", out_path=None, seed=0,
           threads=None, spp_per_pass=None, base_dir=None):
    """Render; returns (image float32 (H,W,3), seconds of mi.render only).

    For the LLVM variant a large spp is split into independent single-pass renders
    (distinct seeds) that are averaged here.  (A first veach_mis reference made with
    Mitsuba's multi-pass mode disagreed with fresh renders by up to 3% near its sides;
    a later re-run of the same setup agreed, so the cause is not established.)"""
    scene, base_dir = _scene_and_dir(scene_json, base_dir)
    chunk = int(spp)
    if variant.startswith("llvm"):
        chunk = spp_per_pass or default_spp_per_pass(scene, spp)
    mi, dr, ms = load(scene, chunk, variant, threads, None, base_dir)
    acc, secs, n = None, 0.0, int(spp) // chunk
    for i in range(n):
        s = int(seed) * 100003 + i
        seed_arg = dr.opaque(mi.UInt32, s) if variant.startswith("llvm") else s
        t0 = time.perf_counter()
        img = mi.render(ms, spp=chunk, seed=seed_arg)
        dr.eval(img)
        dr.sync_thread()
        secs += time.perf_counter() - t0
        a = np.array(img, dtype=np.float64)[:, :, :3]
        acc = a if acc is None else acc + a
    arr = (acc / n).astype(np.float32)
    if out_path:
        write_exr(out_path, arr)
    return arr, secs


def write_exr(path, arr):
    import mitsuba as mi
    import drjit as dr
    if mi.variant() is None:
        mi.set_variant("scalar_rgb")
    bmp = mi.Bitmap(np.ascontiguousarray(arr, dtype=np.float32), mi.Bitmap.PixelFormat.RGB)
    # Bitmap.write() of an EXR deadlocks when the drjit thread pool has 1 thread
    # (mitsuba 3.9.1 / drjit 1.5.0; PNG is fine), so give it 2 while writing.
    n = dr.thread_count()
    if n < 2:
        dr.set_thread_count(2)
    try:
        bmp.write(path)
    finally:
        if n < 2:
            dr.set_thread_count(n)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene")
    ap.add_argument("spp", type=int)
    ap.add_argument("variant", choices=["scalar_rgb", "llvm_ad_rgb"])
    ap.add_argument("out")
    ap.add_argument("seed", type=int)
    ap.add_argument("--threads", type=int, default=None,
                    help="worker threads (drjit.set_thread_count); default: all cores")
    ap.add_argument("--spp-per-pass", type=int, default=None,
                    help="LLVM only: spp of each independent single-pass render that is averaged (memory bound)")
    a = ap.parse_args()
    arr, secs = render(a.scene, a.spp, a.variant, a.out, a.seed, a.threads, a.spp_per_pass)
    print(json.dumps({"scene": a.scene, "spp": a.spp, "variant": a.variant, "seed": a.seed,
                      "seconds": round(secs, 3), "out": a.out,
                      "mean_rgb": [float(x) for x in arr.reshape(-1, 3).mean(0)]}))


if __name__ == "__main__":
    main()
