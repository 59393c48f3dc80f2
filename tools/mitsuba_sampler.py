#!/usr/bin/env python3
"""Runs ../shared/tools/scene_to_mitsuba.py with another Mitsuba sampler than `independent`.

Usage: python3 tools/mitsuba_sampler.py SAMPLER SCENE.json SPP VARIANT OUT.exr SEED
SAMPLER: independent, ldsampler, multijitter, orthogonal, stratified (Mitsuba 3 plugin names).
For issue 19's "Mitsuba with its best sampler" comparison (tools/mitsuba_vs_lumis.sh); the
converter itself fixes `independent`, the sampler the references were made with.
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
sys.argv = [CONVERTER] + sys.argv[2:]
s2m.main()
