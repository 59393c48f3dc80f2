#!/bin/sh
# Remakes the independent Mitsuba 3 reference of tests/data/mitsuba/gaussian_edges.xml (issue 18,
# the gaussian pixel filter): tests/data/refs/gaussian_edges.exr and .var.exr, two independent
# halves (seeds 1811 and 1812) of SPP samples per pixel each, in passes of 1024 spp, by
# tools/make_xml_reference.sh (its header says how), so with Mitsuba's default film filter
# (gaussian, stddev 0.5, radius 2, sample_border false).
# Tests never run this; it needs a Python with mitsuba==3.9.1 (and Debian's libllvm19):
#   MITSUBA_PY=/path/to/venv/bin/python tools/make_filter_reference.sh
# Environment: MITSUBA_PY (default /tmp/mi/bin/python), SPP (default 131072), OUT (default
# tests/data/refs/gaussian_edges).
set -eu
cd "$(dirname "$0")/.."
SPP=${SPP:-131072} PASS=1024 SEED_A=1811 SEED_B=1812 \
    exec tools/make_xml_reference.sh tests/data/mitsuba/gaussian_edges.xml \
    "${OUT:-tests/data/refs/gaussian_edges}"
