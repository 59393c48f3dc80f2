#!/usr/bin/env python3
"""Evaluates Mitsuba 3.9.1's `principledthin` BSDF (variant llvm_ad_rgb) at fixed pairs of
directions and writes tests/data/refs/mitsuba_principledthin_values.json, the values lumis'
thin principled material is compared with. Tests never run this; it needs a Python with
mitsuba==3.9.1 and Debian's libllvm19 (the LLVM variant's JIT backend).

    DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so \\
        python3 tools/mitsuba_principledthin_values.py > tests/data/refs/mitsuba_principledthin_values.json

Directions are in the local frame (normal +z); `wo` is lumis' (towards the viewer: Mitsuba's
si.wi), `wi` lumis' (towards the light: the `wo` argument of Mitsuba's eval/pdf). `eval` is
f·|cosθi| (Mitsuba's eval, RGB, the default BSDFContext; principledthin has no η scaling of
transmitted radiance: a thin sheet's two sides are the same medium, its sampled bs.eta is 1),
`pdf` Mitsuba's pdf. `bsdf` is the case as given to mi.load_dict, except that an RGB parameter is
a plain [r, g, b] list (loaded as {"type": "rgb", "value": [r, g, b]}); parameters not named take
Mitsuba's defaults (base_color 0.5, roughness 0.5, eta 1.5, all else 0, sampling rates 1). No
textures. Mitsuba switches a lobe's code off where its parameter is not given or is a float 0
(principledhelpers.h's get_flag): with spec_trans 0 (the default) there is no specular lobe at
all, reflection included, so the default case is the diffuse lobe alone.

principledthin is symmetric: it flips both directions to the viewer's side first, so for every
case the viewer looks from above (cosines MUS) and from below (cosines −MUS, wo.z < 0: the back
side), at azimuths WO_PHIS; the pole (cosine ±1) appears once, not once per azimuth. Each viewer
is paired with lights on both sides (reflection and transmission: diffuse transmission when
diff_trans > 0, the rough "thin" transmission lobe when spec_trans > 0) with cosines ±MUS_T at
azimuths PHIS_T relative to the viewer's (PHIS_T = π holds the mirror plane; absolute azimuths
still differ between the two viewers, which the anisotropic cases need). The thin transmission
lobe is the reflection lobe (of a roughness scaled by 0.65η − 0.35) mirrored through the surface,
so it peaks at the straight-through direction −wo, not at a refracted one; its pairs are 0 where
the microfacet normal faces away from either direction, or where the Fresnel reflectance is 1
(η < 1: total internal reflection at the microfacet), which the data shows too.

Why llvm_ad_rgb and not scalar_rgb: as for tools/mitsuba_principled_values.py, whose lobes are
evaluated inside `if (dr::any_or<true>(...))` blocks (scalar: the block's own mask; JIT variants:
always true, the lobe then masked by its own mask). In principledthin.cpp every lobe inside such a
block is masked by that same mask, so the variants agree here (scalar_rgb gave every value within
a relative 2e-6 when this was written); llvm_ad_rgb is kept because our reference images are made
with it. Each case's pairs are evaluated in one vectorised call.

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
T = "principledthin"
CASES = [
    {"type": T},
    {"type": T, "base_color": C1, "diff_trans": 0.8},
    {"type": T, "base_color": C2, "diff_trans": 2.0},
    {"type": T, "base_color": C1, "spec_trans": 0.6, "eta": 1.5, "roughness": 0.3},
    {"type": T, "base_color": C2, "spec_trans": 1.0, "eta": 1.33, "roughness": 0.2},
    {"type": T, "base_color": C1, "spec_trans": 0.5, "eta": 1.5, "roughness": 0.4,
     "anisotropic": 0.7},
    {"type": T, "base_color": C2, "spec_trans": 0.7, "eta": 1.5, "roughness": 0.3,
     "spec_tint": 0.6},
    {"type": T, "base_color": C1, "sheen": 0.8},
    {"type": T, "base_color": C2, "sheen": 0.6, "sheen_tint": 0.5, "diff_trans": 0.5},
    {"type": T, "base_color": C1, "flatness": 0.5, "roughness": 0.6},
    {"type": T, "base_color": C2, "spec_trans": 0.4, "diff_trans": 0.6, "eta": 1.2,
     "roughness": 0.5},
    {"type": T, "base_color": C1, "spec_trans": 0.5, "eta": 0.8, "roughness": 0.3},
    {"type": T, "base_color": C1, "spec_trans": 0.5, "diff_trans": 1.0, "roughness": 0.3,
     "specular_reflectance_sampling_rate": 0.5, "specular_transmittance_sampling_rate": 2.0,
     "diffuse_reflectance_sampling_rate": 3.0, "diffuse_transmittance_sampling_rate": 0.7},
    {"type": T, "base_color": C2, "spec_trans": 0.5, "roughness": 0.05},
    {"type": T, "base_color": C1, "spec_trans": 0.5, "roughness": 0.0},
    {"type": T, "base_color": C2, "spec_trans": 0.3, "sheen": 0.5, "flatness": 0.3,
     "diff_trans": 0.4, "spec_tint": 0.3, "anisotropic": 0.4, "roughness": 0.45, "eta": 1.4},
]
RGB_KEYS = ("base_color",)
MUS = [0.03, 0.2, 0.5, 0.8, 1.0]
WO_PHIS = [0.0, 0.35 * math.pi]
# Lights, on both sides for every case: denser than the viewers' grid so that more pairs land in
# the narrow lobes (mirror and straight-through directions at the viewers' cosines).
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
SIGNS = [1.0, -1.0]
for case in CASES:
    bsdf = mi.load_dict(mitsuba_dict(case))
    wos = [(wo, phi_o) for sign in SIGNS for phi_o in WO_PHIS
           for wo in directions(sign, MUS, [phi_o]) if phi_o == WO_PHIS[0] or wo[2] ** 2 < 1.0]
    wis = {phi_o: [wi for sign in SIGNS
                   for wi in directions(sign, MUS_T, [phi_o + p for p in PHIS_T])]
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
