#!/usr/bin/env python3
"""Evaluates Mitsuba 3.9.1's `plastic` and `roughplastic` (variant scalar_rgb) at fixed pairs of
directions and writes tests/data/refs/mitsuba_plastic_values.json, the values
renderer/src/materials/plastic_mitsuba_tests.rs compares lumis' Mitsuba coupling with. Tests
never run this; it needs a Python with mitsuba==3.9.1.

    python3 tools/mitsuba_plastic_values.py > tests/data/refs/mitsuba_plastic_values.json

Directions are in the local frame (normal +z); `wo` is lumis' (towards the viewer: Mitsuba's
si.wi), `wi` lumis' (towards the light: Mitsuba's wo). `eval` is f·cosθi (Mitsuba's eval, RGB),
`pdf` Mitsuba's pdf; `delta` (smooth plastic only) is Mitsuba's sample with sample1 = 0, the
specular mirror: its weight (RGB) and pdf (the probability of choosing it)."""
import json
import math
import mitsuba as mi

mi.set_variant("scalar_rgb")

CASES = [
    {"type": "plastic"},
    {"type": "plastic", "int_ior": 1.9, "diffuse_reflectance": [0.1, 0.27, 0.36]},
    {"type": "plastic", "nonlinear": True, "diffuse_reflectance": [0.8, 0.5, 0.2],
     "specular_reflectance": [0.8, 0.9, 1.0]},
    {"type": "roughplastic", "alpha": 0.15, "diffuse_reflectance": [0.8, 0.5, 0.2]},
    {"type": "roughplastic", "alpha": 0.5, "nonlinear": True,
     "diffuse_reflectance": [0.8, 0.5, 0.2], "int_ior": 1.6},
    {"type": "roughplastic", "distribution": "ggx", "alpha": 0.05,
     "diffuse_reflectance": [0.3, 0.6, 0.9]},
    {"type": "roughplastic", "distribution": "ggx", "alpha": 0.3, "nonlinear": True,
     "diffuse_reflectance": [0.7, 0.7, 0.7], "specular_reflectance": [0.8, 0.9, 1.0],
     "int_ior": 1.3},
]
MUS = [0.03, 0.2, 0.5, 0.8, 1.0]
PHIS = [0.0, 0.5 * math.pi, 0.75 * math.pi, math.pi]


def direction(mu, phi):
    s = math.sqrt(max(0.0, 1.0 - mu * mu))
    return [s * math.cos(phi), s * math.sin(phi), mu]


def mitsuba_dict(case):
    d = {"type": case["type"]}
    for key in ("int_ior", "alpha", "distribution", "nonlinear"):
        if key in case:
            d[key] = case[key]
    for key in ("diffuse_reflectance", "specular_reflectance"):
        if key in case:
            d[key] = {"type": "rgb", "value": case[key]}
    return d


def interaction(wo):
    si = mi.SurfaceInteraction3f()
    si.p = mi.Point3f(0, 0, 0)
    si.n = mi.Normal3f(0, 0, 1)
    si.sh_frame = mi.Frame3f(si.n)
    si.uv = mi.Point2f(0.5, 0.5)
    si.wi = mi.Vector3f(wo)
    return si


out = []
ctx = mi.BSDFContext()
for case in CASES:
    bsdf = mi.load_dict(mitsuba_dict(case))
    values = []
    for mu_o in MUS:
        si = interaction(direction(mu_o, 0.0))
        entry = {"wo": direction(mu_o, 0.0), "pairs": []}
        for mu_i in MUS:
            for phi in PHIS:
                wi = direction(mu_i, phi)
                v = bsdf.eval(ctx, si, mi.Vector3f(wi))
                p = bsdf.pdf(ctx, si, mi.Vector3f(wi))
                entry["pairs"].append({"wi": wi, "eval": [float(v[0]), float(v[1]), float(v[2])],
                                       "pdf": float(p)})
        if case["type"] == "plastic":
            bs, w = bsdf.sample(ctx, si, 0.0, mi.Point2f(0.5, 0.5))
            entry["delta"] = {"weight": [float(w[0]), float(w[1]), float(w[2])],
                              "pdf": float(bs.pdf)}
        values.append(entry)
    out.append({"bsdf": case, "values": values})

print(json.dumps({"mitsuba": mi.__version__, "variant": "scalar_rgb", "cases": out}))
