#!/usr/bin/env python3
"""Measures the power of lumis' image tests: runs the real test binaries with one deliberate, local
bias (a "mutant", renderer/src/mutants.rs) switched on at a time and records which z-tests catch it.

Every z-test in tests/ prints one line `z-test|WHAT|ok or BIASED|failed blocks|blocks|worst |z||critical`
(renderer/tests/common/mod.rs, check_unbiased); this script collects those lines per mutant, and the names of
the test functions that failed (other kinds of test, e.g. χ², report only pass/fail).

Usage (from the repository root; builds the test binaries with `--features mutants` first):

    python3 tools/power_table.py [--cpu-only] [--only SCENE] [-o docs/testing.md]

It rewrites the section between `<!-- power-table:begin -->` and `<!-- power-table:end -->` of the
output file and keeps the raw lines in out/power_table.log. Runtime on 2 cores: about 1 h for CPU
and GPU (lavapipe) together.
"""

import argparse
import json
import os
import re
import subprocess
import sys
import time

# Per scene: the test functions that render it (binary, filter) on each backend, and the local
# biases to inject. Indices are shape indices in the scene file; names are material names.
SCENES = {
    "analytic_polygon": {
        "cpu": [("reference_scenes", "analytic_polygon_matches_reference"),
                ("reference_scenes", "analytic_polygon_matches_closed_form")],
        "gpu": [("gpu", "images::gpu_analytic_polygon_matches_reference")],
        "mutants": ["emission:1", "albedo:floor", "light_pdf:polygon", "bsdf_pdf:diffuse"],
        # A bug in the WGSL twin alone: the GPU tests' comparisons with the CPU must see it too.
        "gpu_mutants": ["light_pdf:polygon@gpu"],
    },
    "analytic_disk": {
        "cpu": [("reference_scenes", "analytic_disk_matches_reference"),
                ("reference_scenes", "analytic_disk_matches_closed_form")],
        "gpu": [("gpu", "images::gpu_analytic_disk_matches_reference")],
        "mutants": ["emission:1", "albedo:floor", "light_pdf:disk", "bsdf_pdf:diffuse"],
        "gpu_mutants": ["light_pdf:disk@gpu"],
    },
    "seed_cornell": {
        "cpu": [("reference_scenes", "seed_cornell_matches_reference"),
                ("reference_scenes", "seed_cornell_with_area_sampling_matches_reference")],
        "gpu": [("gpu", "images::gpu_seed_cornell_matches_reference")],
        # Shape 3 is one of the two small disk lights; red is the left wall.
        "mutants": ["emission:3", "albedo:red", "light_pdf:polygon", "bsdf_pdf:conductor"],
        "gpu_mutants": ["light_pdf:polygon@gpu", "bsdf_pdf:conductor@gpu"],
    },
    "veach_mis": {
        "cpu": [("reference_scenes", "veach_mis_matches_reference"),
                ("reference_scenes", "veach_mis_with_area_sampling_matches_reference")],
        "gpu": [("gpu", "images::gpu_veach_mis_matches_reference")],
        # Shape 7 is the second-smallest sphere light; diffuse is the floor and back wall.
        "mutants": ["emission:7", "albedo:diffuse", "light_pdf:sphere", "bsdf_pdf:conductor"],
        "gpu_mutants": ["light_pdf:sphere@gpu", "bsdf_pdf:conductor@gpu"],
    },
    "plastic_lights": {
        # plastic_furnace builds scenes of its own: only the plastic's own mutants apply there.
        "cpu": [("strategy_agreement", "plastic_scene_strategies_agree"),
                ("plastic_furnace", "", ["bsdf_pdf:plastic", "plastic_eval"])],
        "gpu": [],
        # Shape 6 is the triangle light; plastic_green the α = 0.3 sphere.
        "mutants": ["emission:6", "albedo:plastic_green", "light_pdf:triangle", "bsdf_pdf:plastic",
                    "plastic_eval"],
    },
}

# The combinations tested on the whole image only (heavy tails): every emission scaled by a factor,
# to measure the smallest bias each detects. Rows of the z-test lines whose WHAT contains one of the
# `rows` strings are kept.
SWEEPS = {
    "veach_mis": {
        "factors": ["1.03", "1.05", "1.1", "1.2", "1.5"],
        "cpu": [("reference_scenes", "veach_mis_matches_reference")],
        "gpu": [("gpu", "images::gpu_veach_mis_matches_reference")],
        "rows": ["veach_mis Light ", "veach_mis Bsdf "],
    },
    "plastic_lights": {
        "factors": ["1.005", "1.01", "1.02", "1.03"],
        "cpu": [("strategy_agreement", "plastic_scene_strategies_agree")],
        "gpu": [],
        "rows": ["plastic_lights Light SolidAngle max_depth None", "plastic_lights Light Area max_depth None"],
    },
}

ZLINE = re.compile(r"^z-test\|(.*)\|(ok|BIASED)\|(\d+)\|(\d+)\|([^|]*)\|([^|]*)$")
FAILED_FN = re.compile(r"^test (\S+) \.\.\. FAILED$")
SECONDS = re.compile(r", [0-9.]+ s\)")


def build(binaries):
    """Builds the test binaries with the mutation points compiled in; returns {name: executable}.
    They are then run directly, so edits made while the table runs cannot change what is measured."""
    cmd = ["cargo", "test", "--release", "-p", "lumis-renderer", "--features", "mutants full-suite", "--no-run",
           "--message-format=json"]
    for b in binaries:
        cmd += ["--test", b]
    p = subprocess.run(cmd, check=True, capture_output=True, text=True)
    exes = {}
    for line in p.stdout.splitlines():
        msg = json.loads(line)
        if msg.get("reason") == "compiler-artifact" and msg.get("executable"):
            exes[msg["target"]["name"]] = msg["executable"]
    missing = set(binaries) - set(exes)
    if missing:
        sys.exit(f"power_table: no executable for {sorted(missing)}")
    return exes


def run_test(exe, binary, filt, mutant, log):
    """Runs one test binary with LUMIS_MUTANT=mutant; returns (z lines, failed test functions)."""
    env = dict(os.environ, LUMIS_MUTANT=mutant)
    cmd = [exe, "--nocapture", "--test-threads=1"] + ([filt] if filt else [])
    t = time.time()
    p = subprocess.run(cmd, env=env, capture_output=True, text=True, cwd="renderer")
    out = p.stdout + p.stderr
    log.write(f"### {mutant or '(none)'} {binary} {filt} rc={p.returncode} {time.time() - t:.0f}s\n{out}\n")
    log.flush()
    zs, failed = [], []
    for line in out.splitlines():
        m = ZLINE.match(line.strip())
        if m:
            what = SECONDS.sub(")", m.group(1))
            zs.append((what, m.group(2), int(m.group(3)), int(m.group(4)), float(m.group(5)),
                       float(m.group(6))))
        m = FAILED_FN.match(line.strip())
        if m:
            failed.append(f"{binary}::{m.group(1)}")
    if p.returncode != 0 and not failed:
        failed.append(f"{binary} (rc {p.returncode})")
    return zs, failed


def cell(z):
    """One table cell: caught (✗) or not (·), with the worst |z| against the critical value."""
    _, status, nfail, nblocks, worst, crit = z
    if status == "BIASED":
        return f"**caught** {worst:.1f} ({nfail}/{nblocks})"
    return f"· {worst:.1f}"


# The mutations "Done when" of issue 14 names: the plastic's f, and each light kind's pdf. Every one
# must make some test of `cargo test --release --workspace` fail.
MUTATION_CHECK = ["plastic_eval"] + [f"light_pdf:{k}" for k in
                                     ["triangle", "polygon", "quad", "disk", "sphere", "background"]]
# The binaries that test the light samplers and the plastic directly (a few minutes for all
# mutants); the image tests' view of the same mutants is the power table.
CHECK_BINARIES = ["irradiance", "furnace", "plastic_furnace", "chi2_samplers", "strategy_agreement"]


def mutation_check(out):
    """Runs every CPU test binary of CHECK_BINARIES under each mutant; writes a markdown table of the
    failing test functions between `<!-- mutation-check:begin/end -->` of `out`."""
    exes = build(CHECK_BINARIES)
    lines = ["| mutant | failing test functions |", "|---|---|"]
    with open("out/mutation_check.log", "w") as log:
        for binary in CHECK_BINARIES:  # the unmutated suite passes
            _, failed = run_test(exes[binary], binary, "", "", log)
            if failed:
                sys.exit(f"unmutated {binary} fails: {failed}")
        for mutant in MUTATION_CHECK:
            failed = []
            for binary in CHECK_BINARIES:
                failed += run_test(exes[binary], binary, "", mutant, log)[1]
            print(f"{mutant}: {failed}", file=sys.stderr)
            lines.append(f"| `{mutant}` | {', '.join(failed) or '**none**'} |")
    replace_section(out, "mutation-check", "\n".join(lines))


def sweep(out, backends):
    """Every emission × F for the whole-image combinations of SWEEPS; a table of |z| per factor."""
    bins = sorted({b for sp in SWEEPS.values() for be in backends for b, _ in sp[be]})
    exes = build(bins)
    lines = []
    with open("out/power_sweep.log", "w") as log:
        for scene, spec in SWEEPS.items():
            factors = spec["factors"]
            rows = {}
            for f in factors:
                for be in backends:
                    for binary, filt in spec[be]:
                        for z in run_test(exes[binary], binary, filt, f"emission_all:{f}", log)[0]:
                            if any(r in z[0] for r in spec["rows"]):
                                rows.setdefault(z[0], {})[f] = z
            lines += ["", f"{scene}:", "", "| z-test (whole image) | " + " | ".join(
                f"× {f}" for f in factors) + " |", "|---|" + "---|" * len(factors)]
            for what, by_f in rows.items():
                lines.append(f"| {what} | " + " | ".join(
                    cell(by_f[f]) if f in by_f else "" for f in factors) + " |")
    replace_section(out, "power-sweep", "\n".join(lines).strip())


def replace_section(path, name, body):
    """Rewrites the text between `<!-- NAME:begin -->` and `<!-- NAME:end -->` of `path`."""
    begin, end = f"<!-- {name}:begin -->", f"<!-- {name}:end -->"
    text = open(path).read() if os.path.exists(path) else ""
    if begin not in text:
        text += f"\n{begin}\n{end}\n"
    pre, rest = text.split(begin, 1)
    _, post = rest.split(end, 1)
    open(path, "w").write(f"{pre}{begin}\n{body}\n{end}{post}")
    print(f"wrote {path}", file=sys.stderr)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cpu-only", action="store_true")
    ap.add_argument("--only", action="append", help="scene name (repeatable)")
    ap.add_argument("-o", default="docs/testing.md")
    ap.add_argument("--sweep", action="store_true",
                    help="instead of the table: the smallest global bias the whole-image tests detect")
    ap.add_argument("--mutation-check", action="store_true",
                    help="instead of the table: run every CPU test binary with each mutant of "
                         "MUTATION_CHECK and list the test functions that fail")
    args = ap.parse_args()
    if args.mutation_check:
        return mutation_check(args.o)
    if args.sweep:
        return sweep(args.o, ["cpu"] if args.cpu_only else ["cpu", "gpu"])
    os.makedirs("out", exist_ok=True)
    backends = ["cpu"] if args.cpu_only else ["cpu", "gpu"]
    scenes = [s for s in SCENES if not args.only or s in args.only]
    bins = sorted({t[0] for s in scenes for be in backends for t in SCENES[s][be]})
    exes = build(bins)
    sections = []
    with open("out/power_table.log", "w") as log:
        for scene, spec in SCENES.items():
            if args.only and scene not in args.only:
                continue
            mutants = [""] + spec["mutants"] + (spec.get("gpu_mutants", []) if "gpu" in backends else [])
            # rows[what][mutant] = z line; fails[mutant] = failed test functions
            rows, fails = {}, {}
            for mutant in mutants:
                for be in (["gpu"] if mutant.endswith("@gpu") else backends):
                    for binary, filt, *only in spec[be]:
                        if mutant and only and mutant not in only[0]:
                            continue
                        zs, failed = run_test(exes[binary], binary, filt, mutant, log)
                        for z in zs:
                            rows.setdefault(z[0], {})[mutant] = z
                        fails.setdefault(mutant, []).extend(failed)
                print(f"{scene} {mutant or '(none)'}: failed {fails[mutant]}", file=sys.stderr)
            head = "| z-test | none | " + " | ".join(f"`{m}`" for m in mutants[1:]) + " |"
            lines = [f"### {scene}", "", head, "|" + "---|" * (len(mutants) + 1)]
            for what, by_mutant in rows.items():
                cells = [cell(by_mutant[m]) if m in by_mutant else "" for m in mutants]
                lines.append(f"| {what} | " + " | ".join(cells) + " |")
            lines.append("| **failing test functions** | " + " | ".join(
                ", ".join(sorted(set(fails.get(m, [])))) or "none" for m in mutants) + " |")
            sections.append("\n".join(lines))
    table = "\n\n".join(sections)
    begin, end = "<!-- power-table:begin -->", "<!-- power-table:end -->"
    text = open(args.o).read() if os.path.exists(args.o) else f"{begin}\n{end}\n"
    if begin not in text:
        text += f"\n{begin}\n{end}\n"
    pre, rest = text.split(begin, 1)
    _, post = rest.split(end, 1)
    if args.only:
        # A partial run keeps the other scenes' sections.
        old = rest.split(end, 1)[0]
        kept = [s for s in re.split(r"\n(?=### )", old.strip()) if s.startswith("### ")
                and s.split("\n", 1)[0][4:] not in args.only]
        table = "\n\n".join(kept + sections)
    open(args.o, "w").write(f"{pre}{begin}\n{table}\n{end}{post}")
    print(f"wrote {args.o}", file=sys.stderr)


if __name__ == "__main__":
    main()
