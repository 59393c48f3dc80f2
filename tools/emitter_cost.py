#!/usr/bin/env python3
"""Issue 17, item 6: the cost per sample of an emitting mesh of many triangles against one quad
light of the same shape and power. Writes, into OUT_DIR, the Cornell scene of tests/data/scenes
with its three lights replaced by a 130 x 130 ceiling light: `quad_light.json` (one `quad`) and
`mesh_light.json` (the same square as a binary PLY of 2*N*N triangles, N = 71 by default:
10,082 triangles, each one light picked by power). Then time both with `lumis render`:

    python3 tools/emitter_cost.py /tmp/emitters
    for i in 1 2 3; do for s in quad mesh; do
      target/release/lumis render /tmp/emitters/${s}_light.json --spp 64 -o /tmp/emitters/$s.exr
    done; done
"""
import json
import struct
import sys
from pathlib import Path

root = Path(__file__).resolve().parent.parent
out = Path(sys.argv[1])
n = int(sys.argv[2]) if len(sys.argv) > 2 else 71
out.mkdir(parents=True, exist_ok=True)
scene = json.loads((root / "tests/data/scenes/seed_cornell.json").read_text())
scene["shapes"] = [s for s in scene["shapes"] if "emission" not in s]
corner, size, y, le = (213.0, 213.0), 130.0, 548.0, [15, 15, 15]

quad = {"type": "quad", "corner": [corner[0], y, corner[1]], "edge_u": [0, 0, size],
        "edge_v": [size, 0, 0], "emission": le}
(out / "quad_light.json").write_text(json.dumps({**scene, "shapes": scene["shapes"] + [quad]}))

# The same square, normal -y (edge_u = +z, edge_v = +x as for the quad), as an N x N grid.
verts = [(corner[0] + size * i / n, y, corner[1] + size * j / n)
         for j in range(n + 1) for i in range(n + 1)]
tris = []
for j in range(n):
    for i in range(n):
        a, b = j * (n + 1) + i, j * (n + 1) + i + 1
        c, d = a + n + 1, b + n + 1
        # cross(+z, +x) = -y: wind (a, c, d) and (a, d, b).
        tris += [(a, c, d), (a, d, b)]
header = (f"ply\nformat binary_little_endian 1.0\nelement vertex {len(verts)}\n"
          "property float x\nproperty float y\nproperty float z\n"
          f"element face {len(tris)}\nproperty list uchar int vertex_indices\nend_header\n")
with open(out / "ceiling.ply", "wb") as f:
    f.write(header.encode())
    for v in verts:
        f.write(struct.pack("<3f", *v))
    for t in tris:
        f.write(struct.pack("<B3i", 3, *t))
mesh = {"type": "mesh", "file": "ceiling.ply", "emission": le}
(out / "mesh_light.json").write_text(json.dumps({**scene, "shapes": scene["shapes"] + [mesh]}))
print(f"{len(tris)} triangles in {out / 'ceiling.ply'}")
