#!/usr/bin/env python3
"""Evaluates Mitsuba 3.9.1's `principled` BSDF (variant llvm_ad_rgb) at fixed pairs of directions
and writes tests/data/refs/mitsuba_principled_values.json, the values lumis' principled material
is compared with. Tests never run this; it needs a Python with mitsuba==3.9.1 and Debian's
libllvm19 (the LLVM variant's JIT backend).

    DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so \\
        python3 tools/mitsuba_principled_values.py > tests/data/refs/mitsuba_principled_values.json

Directions are in the local frame (normal +z); `wo` is lumis' (towards the viewer: Mitsuba's
si.wi), `wi` lumis' (towards the light: the `wo` argument of Mitsuba's eval/pdf). `eval` is
f·|cosθi| (Mitsuba's eval, RGB, TransportMode::Radiance: the default BSDFContext, so
transmission carries Mitsuba's 1/η² radiance scaling), `pdf` Mitsuba's pdf. `bsdf` is the case as
given to mi.load_dict, except that an RGB parameter is a plain [r, g, b] list (loaded as
{"type": "rgb", "value": [r, g, b]}); parameters not named take Mitsuba's defaults
(base_color 0.5, roughness 0.5, specular 0.5, all else 0, sampling rates 1). No textures.

Viewing directions have cosines MUS at azimuths WO_PHIS; lights cosines MUS at azimuths PHIS
relative to the viewer's (so PHIS = π holds the mirror and refraction planes; absolute azimuths
still differ between the two viewers, which the anisotropic case needs); the pole (cosine ±1)
appears once, not once per azimuth. For the cases with spec_trans > 0 the viewer also looks from
below (cosines −MUS, wo.z < 0: the back side, inside the material), and each viewer is paired with
lights on both sides (cosines ±MUS_T at azimuths PHIS_T, a denser grid so that more pairs land in
the transmission lobe; many transmission pairs are still 0: the microfacet normal that would join
them faces the wrong way, or total internal reflection, which the data should show too).

Why llvm_ad_rgb and not scalar_rgb: in principled.cpp the sheen lobe is evaluated inside
`if (dr::any_or<true>(diffuse_active))`. In the scalar variant that skips sheen wherever the
diffuse lobe is off (spec_trans = 1 with sheen > 0), while in the JIT variants any_or<true> is
always true and sheen is masked only by its own sheen_active. lumis follows the JIT variants, as
do our reference images (made with llvm_ad_rgb). Each case's pairs are evaluated in one
vectorised call.

A pair at which Mitsuba's eval or pdf is not finite would be left out (and counted on stderr);
with these cases and directions none is."""
import json
import math
import sys

import drjit as dr
import mitsuba as mi

VARIANT = "llvm_ad_rgb"
mi.set_variant(VARIANT)

C1 = [0.8, 0.5, 0.2]
C2 = [0.2, 0.6, 0.9]
CASES = [
    {"type": "principled"},
    {"type": "principled", "base_color": C1, "metallic": 0.3},
    {"type": "principled", "base_color": [0.9, 0.6, 0.3], "metallic": 1.0, "roughness": 0.3},
    {"type": "principled", "base_color": C2, "spec_tint": 0.7, "roughness": 0.3},
    {"type": "principled", "base_color": C1, "anisotropic": 0.7, "roughness": 0.4},
    {"type": "principled", "base_color": C2, "sheen": 0.8},
    {"type": "principled", "base_color": C1, "sheen": 0.6, "sheen_tint": 0.5},
    {"type": "principled", "base_color": C2, "clearcoat": 0.7, "clearcoat_gloss": 0.0},
    {"type": "principled", "base_color": C1, "clearcoat": 1.0, "clearcoat_gloss": 0.8},
    {"type": "principled", "base_color": C1, "flatness": 0.5, "roughness": 0.6},
    {"type": "principled", "base_color": C2, "specular": 0.8},
    {"type": "principled", "base_color": C1, "eta": 1.33},
    {"type": "principled", "base_color": C2, "eta": 0.8, "spec_trans": 0.5, "roughness": 0.3},
    {"type": "principled", "base_color": C1, "spec_trans": 0.6, "eta": 1.5, "roughness": 0.3},
    {"type": "principled", "base_color": C2, "spec_trans": 1.0, "eta": 1.5, "sheen": 0.5},
    {"type": "principled", "base_color": C1, "clearcoat": 0.5, "clearcoat_gloss": 0.3,
     "main_specular_sampling_rate": 0.5, "clearcoat_sampling_rate": 3.0,
     "diffuse_reflectance_sampling_rate": 2.0},
    {"type": "principled", "base_color": C2, "roughness": 0.05},
    {"type": "principled", "base_color": C1, "roughness": 0.0},
]
RGB_KEYS = ("base_color",)
MUS = [0.03, 0.2, 0.5, 0.8, 1.0]
WO_PHIS = [0.0, 0.35 * math.pi]
PHIS = [0.0, 0.5 * math.pi, 0.75 * math.pi, math.pi]
# Lights of the cases with transmission: denser near the refracted directions (cosines 0.75 to
# 0.92 below for viewers above at η = 1.5; around 0.4 above for viewers inside).
MUS_T = [0.03, 0.2, 0.35, 0.5, 0.65, 0.75, 0.8, 0.9, 1.0]
PHIS_T = [0.0, 0.5 * math.pi, 0.75 * math.pi, 0.875 * math.pi, math.pi]


def direction(mu, phi):
    s = math.sqrt(max(0.0, 1.0 - mu * mu))
    return [s * math.cos(phi), s * math.sin(phi), mu]


def directions(sign, mus, phis):
    """Directions with cosines sign·mus at azimuths phis; the pole (|μ| = 1) only once."""
    return [direction(sign * mu, phi) for mu in mus for phi in (phis if mu < 1.0 else phis[:1])]


def mitsuba_dict(case):
    return {k: ({"type": "rgb", "value": v} if k in RGB_KEYS else v) for k, v in case.items()}


def vec3(dirs):
    return mi.Vector3f([d[0] for d in dirs], [d[1] for d in dirs], [d[2] for d in dirs])


def interaction(wos):
    n = len(wos)
    si = dr.zeros(mi.SurfaceInteraction3f, n)
    si.p = mi.Point3f(0, 0, 0)
    si.n = mi.Normal3f(0, 0, 1)
    si.sh_frame = mi.Frame3f(si.n)
    si.uv = mi.Point2f(0.5, 0.5)
    si.wi = vec3(wos)
    return si


def finite(x):
    return math.isfinite(x)


out = []
dropped = 0
ctx = mi.BSDFContext()
for case in CASES:
    bsdf = mi.load_dict(mitsuba_dict(case))
    both = case.get("spec_trans", 0.0) > 0.0
    signs = [1.0, -1.0] if both else [1.0]
    mus, phis = (MUS_T, PHIS_T) if both else (MUS, PHIS)
    wos = [(wo, phi_o) for sign in signs for phi_o in WO_PHIS
           for wo in directions(sign, MUS, [phi_o]) if phi_o == WO_PHIS[0] or wo[2] ** 2 < 1.0]
    wis = {phi_o: [wi for sign in signs for wi in directions(sign, mus, [phi_o + p for p in phis])]
           for phi_o in WO_PHIS}
    flat_wo = [wo for wo, phi_o in wos for _ in wis[phi_o]]
    flat_wi = [wi for _, phi_o in wos for wi in wis[phi_o]]
    si = interaction(flat_wo)
    v = bsdf.eval(ctx, si, vec3(flat_wi))
    p = bsdf.pdf(ctx, si, vec3(flat_wi))
    r, g, b = (list(map(float, v[k].numpy())) for k in range(3))
    pdf = list(map(float, p.numpy()))
    values = []
    k = 0
    for wo, phi_o in wos:
        entry = {"wo": wo, "pairs": []}
        for wi in wis[phi_o]:
            e = [r[k], g[k], b[k]]
            if all(map(finite, e + [pdf[k]])):
                assert min(e) >= 0.0 and pdf[k] >= 0.0, (case, wo, wi, e, pdf[k])
                entry["pairs"].append({"wi": wi, "eval": e, "pdf": pdf[k]})
            else:
                dropped += 1
                print(f"dropped {case} wo={wo} wi={wi}: eval={e} pdf={pdf[k]}", file=sys.stderr)
            k += 1
        values.append(entry)
    out.append({"bsdf": case, "values": values})

if dropped:
    print(f"{dropped} pairs dropped (not finite)", file=sys.stderr)
print(json.dumps({"mitsuba": mi.__version__, "variant": VARIANT, "cases": out}))
