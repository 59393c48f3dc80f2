#!/usr/bin/env python3
"""Runs ../shared/tools/scene_to_mitsuba.py with another Mitsuba sampler than `independent`.

Usage: python3 tools/mitsuba_sampler.py SAMPLER SCENE.json SPP VARIANT OUT.exr SEED
SAMPLER: independent, ldsampler, multijitter, orthogonal, stratified (Mitsuba 3 plugin names).
For issue 19's "Mitsuba with its best sampler" comparison (tools/mitsuba_vs_lumis.sh); the
converter itself fixes `independent`, the sampler the references were made with.
With MI_CLOCK=cpu the reported `seconds` are the CPU seconds of the process (all its threads)
during mi.render instead of wall seconds: on a machine shared with other work, CPU time is what
both renderers can be compared by (tools/mitsuba_vs_lumis.sh measures lumis' the same way).
"""
import importlib.util
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
CONVERTER = os.path.join(HERE, "..", "..", "shared", "tools", "scene_to_mitsuba.py")

sampler = sys.argv[1]
spec = importlib.util.spec_from_file_location("scene_to_mitsuba", CONVERTER)
s2m = importlib.util.module_from_spec(spec)
spec.loader.exec_module(s2m)
to_dict = s2m.scene_to_dict


def with_sampler(*args, **kwargs):
    d = to_dict(*args, **kwargs)
    d["sensor"]["sampler"]["type"] = sampler
    return d


s2m.scene_to_dict = with_sampler
if os.environ.get("MI_CLOCK") == "cpu":
    import time
    import types

    # The converter times mi.render with time.perf_counter(); give it the process CPU clock.
    s2m.time = types.SimpleNamespace(perf_counter=time.process_time)
sys.argv = [CONVERTER] + sys.argv[2:]
s2m.main()
