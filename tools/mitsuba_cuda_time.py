#!/usr/bin/env python3
"""Times Mitsuba 3 (cuda_ad_rgb) on a shared scene the way `lumis bench --backend gpu` times lumis:
relMSE against the stored reference at doubling spp, seconds of rendering only.

Usage: python3 tools/mitsuba_cuda_time.py SCENE.json REF.exr CHUNK MAX_SPP
Needs ../shared/tools (scene_to_mitsuba.py, metrics.py) beside the checkout, the `mitsuba`
3.9.1 and `drjit` 1.5.0 packages and an NVIDIA GPU. One warm-up render compiles the kernel; then
CHUNK-spp renders with distinct (opaque, so not recompiled) seeds are summed on the GPU, and the
mean is compared with the reference at CHUNK, 2·CHUNK, 4·CHUNK, … spp. Prints one JSON line each.
"""
import json
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "tools"))
import metrics  # noqa: E402
import scene_to_mitsuba as stm  # noqa: E402

scene_path, ref_path, chunk, max_spp = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
# MI_SAMPLER: another Mitsuba sampler than the converter's `independent` (ldsampler, multijitter,
# orthogonal, ...), for issue 19's "Mitsuba with its best sampler"; each CHUNK-spp render is then
# one scrambled point set of that sampler, and the chunks are averaged like independent renders.
SAMPLER = os.environ.get("MI_SAMPLER")
if SAMPLER:
    _to_dict = stm.scene_to_dict

    def _with_sampler(*args, **kwargs):
        d = _to_dict(*args, **kwargs)
        d["sensor"]["sampler"]["type"] = SAMPLER
        return d

    stm.scene_to_dict = _with_sampler
mi, dr, ms = stm.load(scene_path, chunk, "cuda_ad_rgb")
ref = metrics.read_image(ref_path)
t0 = time.perf_counter()
img = mi.render(ms, spp=chunk, seed=dr.opaque(mi.UInt32, 999999))
dr.eval(img)
dr.sync_thread()
print(json.dumps({"scene": scene_path, "sampler": SAMPLER or "independent", "warmup_seconds": round(time.perf_counter() - t0, 3)}), flush=True)
acc, secs, spp, nxt = None, 0.0, 0, chunk
while spp < max_spp:
    t0 = time.perf_counter()
    img = mi.render(ms, spp=chunk, seed=dr.opaque(mi.UInt32, spp // chunk))
    acc = img if acc is None else acc + img
    dr.eval(acc)
    dr.sync_thread()
    secs += time.perf_counter() - t0
    spp += chunk
    if spp == nxt:
        a = np.array(acc, dtype=np.float64)[:, :, :3] / (spp // chunk)
        h, w = a.shape[:2]
        print(json.dumps({"scene": scene_path, "spp": spp, "seconds": round(secs, 4),
                          "samples_per_second": w * h * spp / secs,
                          "relmse": metrics.relmse(a, ref), "rmse": metrics.rmse(a, ref)}), flush=True)
        nxt *= 2
