#!/usr/bin/env python3
"""Mitsuba 3.9.1's answer to each document-grammar case that
renderer/tests/mitsuba_xml/grammar.rs tests lumis on (issue 37 item 1): file resolution
(<path>, <include>, object and spectrum file names), <alias>, top-level declarations and the
integrators' defaults. The test encodes these answers; run this to check them again:

    pip install mitsuba==3.9.1 && python3 tools/mitsuba_grammar_check.py

It writes the cases to a temporary folder, loads each with Mitsuba (scalar_rgb; llvm_ad_rgb for
the Python integrators) and prints one line per case. Each mesh is a triangle whose size names
its folder, so the printed size says which file Mitsuba read.
"""

import os
import sys
import tempfile

import mitsuba as mi

# The triangle size of each mesh file: which folder it came from.
MESHES = {"m.obj": 1, "sub/m.obj": 2, "other/m.obj": 3, "inc/m.obj": 4,
          "inc/deep/m.obj": 5, "inc/only_inc.obj": 6}

SENSOR = ('<sensor type="perspective"><film type="hdrfilm"><integer name="width" value="8"/>'
          '<integer name="height" value="8"/></film></sensor>')


def write(root, name, text):
    path = os.path.join(root, name)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def scene(body):
    return f'<scene version="3.0.0">\n{body}\n</scene>\n'


def obj(shape_id, filename):
    return (f'<shape type="obj" id="{shape_id}">'
            f'<string name="filename" value="{filename}"/></shape>')


def sizes(path):
    s = mi.load_file(path)
    return {sh.id(): int(round(sh.bbox().max[0])) for sh in s.shapes()}


def attempt(label, fn):
    try:
        print(f"{label}: {fn()}")
    except Exception as e:  # Mitsuba's refusal is the answer for some cases
        print(f"{label}: error: {str(e).splitlines()[0][:200]}")


def main():
    mi.set_variant("scalar_rgb")
    root = tempfile.mkdtemp(prefix="mitsuba-grammar-")
    os.chdir(root)
    for name, size in MESHES.items():
        write(root, name, f"v 0 0 0\nv {size} 0 0\nv 0 {size} 0\nf 1 2 3\n")
    write(root, "inc/deep/.keep", "")
    # Case 1: <path>s newest first, wherever they stand; an included file's <path> and folder
    # do not count for object file names; a nested <include> is found in its includer's folder.
    write(root, "inc/a.xml", scene('<path value="deep"/>\n' + obj("in_a", "m.obj")
                                   + '\n<include filename="b.xml"/>'))
    write(root, "inc/b.xml", scene(obj("in_inc_b", "m.obj")))
    write(root, "b.xml", scene(obj("in_main_b", "m.obj")))
    write(root, "case1.xml", scene('<path value="sub"/>\n' + obj("main", "m.obj")
                                   + '\n<include filename="inc/a.xml"/>\n<path value="other"/>'))
    attempt("case1 sizes (2 sub, 3 other, 4 inc, 5 inc/deep; in_inc_b = nested include found "
            "in inc/)", lambda: sizes("case1.xml"))
    # Case 2: without <path>, the main folder; a file only in the includer's folder is not found.
    write(root, "inc/c.xml", scene(obj("in_c", "m.obj")))
    write(root, "case2.xml", scene('<include filename="inc/c.xml"/>'))
    attempt("case2 sizes (1 main folder)", lambda: sizes("case2.xml"))
    write(root, "inc/d.xml", scene(obj("in_d", "only_inc.obj")))
    write(root, "case2b.xml", scene('<include filename="inc/d.xml"/>'))
    attempt("case2b (a file only beside the included file)", lambda: sizes("case2b.xml"))
    # Case 3: <path> only under the root; a missing folder.
    write(root, "case3.xml", scene('<shape type="sphere"><path value="sub"/></shape>'))
    attempt("case3 (path inside an object)", lambda: sizes("case3.xml"))
    write(root, "case3b.xml", scene('<path value="nowhere"/>'))
    attempt("case3b (path to a missing folder)", lambda: sizes("case3b.xml"))
    # Case 4: a spectrum file named in an included file: the main file's folder.
    write(root, "s.spd", "400 0.9\n700 0.9\n")
    write(root, "inc/s.spd", "400 0.1\n700 0.1\n")
    write(root, "inc/spec.xml", scene('<bsdf type="diffuse" id="sp">'
                                      '<spectrum name="reflectance" filename="s.spd"/></bsdf>'))
    write(root, "case4.xml", scene('<include filename="inc/spec.xml"/>\n'
                                   '<shape type="sphere"><ref id="sp"/></shape>'))
    attempt("case4 reflectance (0.9 main folder, 0.1 included file's folder)",
            lambda: mi.traverse(mi.load_file("case4.xml"))["sp.reflectance.value"])
    # Case 5: aliases.
    white = '<bsdf type="diffuse" id="white"/>'
    write(root, "case5a.xml", scene('<alias id="white" as="w2"/>\n' + white))
    attempt("case5a (alias before its source)", lambda: sizes("case5a.xml"))
    write(root, "case5b.xml", scene(white + '\n<bsdf type="conductor" id="c"/>\n'
                                    '<alias id="white" as="c"/>'))
    attempt("case5b (alias onto a taken id)", lambda: sizes("case5b.xml"))
    write(root, "case5c.xml", scene(white + '\n<shape type="sphere" id="s">'
                                    '<alias id="white" as="w3"/><ref id="w3"/></shape>'))
    attempt("case5c (alias inside an object)",
            lambda: [sh.bsdf().id() for sh in mi.load_file("case5c.xml").shapes()])
    # Case 6: area emitters declared at the top level.
    area = '<emitter type="area" id="a"><rgb name="radiance" value="1"/></emitter>'
    write(root, "case6a.xml", scene(area + '\n<shape type="sphere" id="s1"><ref id="a"/></shape>'))
    attempt("case6a emitters (referenced by a shape)",
            lambda: len(mi.load_file("case6a.xml").emitters()))
    write(root, "case6b.xml", scene(area + '\n<shape type="sphere" id="s1"/>'))
    attempt("case6b emitters (referenced by none)",
            lambda: len(mi.load_file("case6b.xml").emitters()))
    write(root, "case6c.xml", scene(area + '\n<shape type="sphere"><ref id="a"/></shape>'
                                    '\n<shape type="sphere"><ref id="a"/></shape>'))
    attempt("case6c (referenced by two shapes)", lambda: len(mi.load_file("case6c.xml").emitters()))
    # Case 7: a sampler declared at the top level, referenced by the sensor.
    write(root, "case7.xml", scene('<sampler type="independent" id="smp">'
                                   '<integer name="sample_count" value="7"/></sampler>\n'
                                   '<sensor type="perspective"><ref id="smp"/></sensor>'))
    attempt("case7 sample_count",
            lambda: mi.load_file("case7.xml").sensors()[0].sampler().sample_count())
    # Case 8: the integrators' defaults (the Python ones need a JIT variant).
    mi.set_variant("llvm_ad_rgb")
    for ty in ["path", "ptracer", "prb", "prb_basic", "prb_projective", "direct_projective"]:
        attempt(f"case8 {ty}", lambda: str(mi.load_dict({"type": ty})).replace("\n", " "))
    attempt("case8 direct_projective with max_depth 5", lambda: str(
        mi.load_dict({"type": "direct_projective", "max_depth": 5})).replace("\n", " "))
    attempt("case8 moment", lambda: str(mi.load_dict(
        {"type": "moment", "a": {"type": "path", "max_depth": 3}})).replace("\n", " "))
    # Case 9: --spp as Mitsuba's spp parameter: used when the scene has $spp, an error if not.
    mi.set_variant("scalar_rgb")
    write(root, "case9.xml", scene('<default name="spp" value="14"/>\n<sensor type="perspective">'
                                   '<sampler type="independent"><integer name="sample_count" '
                                   'value="$spp"/></sampler></sensor>'))
    attempt("case9 spp=3 over a default of 14",
            lambda: mi.load_file("case9.xml", spp=3).sensors()[0].sampler().sample_count())
    attempt("case9b spp=3 for a scene without $spp", lambda: sizes("case2.xml") and
            mi.load_file("case2.xml", spp=3) and "accepted")
    # Case 10: vertex normals of a mesh file without them (renderer/tests/mitsuba_xml/normals.rs).
    write(root, "fan.obj", "v 0 0 0.3\nv 1 0 0\nv 0.2 1.1 0.1\nv -0.9 0.4 -0.2\nv -0.3 -1 0.4\n"
          "v 0.8 -0.7 -0.5\nf 1 2 3\nf 1 3 4\nf 1 4 5\nf 1 5 6\nf 1 6 2\nf 2 6 3\n")
    fan = mi.load_dict({"type": "obj", "filename": "fan.obj", "to_world":
                        mi.ScalarTransform4f().scale([2, 1, 0.5]).rotate([0, 0, 1], 30)})
    n = list(fan.vertex_normals_buffer())
    print("case10 normals:", [["%.7f" % x for x in n[i:i + 3]] for i in range(0, len(n), 3)])


if __name__ == "__main__":
    sys.exit(main())
