#!/usr/bin/env python3
"""A hostile scene for judging a GPU (data/gpus/nvidia-h100/README.md): 1,500 random triangles of
every size from 10^-3 to 10^2 around the origin (a fifth of them slivers, a fifth with texture
coordinates wrapped 64 times), a ground plane 2 x 10^5 wide at y = -1 and a wall 2 x 10^5 wide
nearly edge-on, as an OBJ, and an 11-keyframe camera path through it (every third keyframe looks
along the horizon; fields of view 30 to 120 degrees). Deterministic (seed 11).

  scripts/stress-scene.py OUT_DIR     writes OUT_DIR/stress.obj and OUT_DIR/stress.path.json
Then: vt-capture scenes TEXTURE --mesh OUT_DIR/stress.obj --path OUT_DIR/stress.path.json ...
"""
import json
import math
import os
import random
import sys

if len(sys.argv) != 2:
    print(__doc__, file=sys.stderr)
    sys.exit(2)
out = sys.argv[1]
os.makedirs(out, exist_ok=True)
rng = random.Random(11)
vertices, uvs, faces = [], [], []


def triangle(p0, p1, p2, uv):
    base = len(vertices)
    vertices.extend([p0, p1, p2])
    uvs.extend(uv)
    faces.append((base + 1, base + 2, base + 3))


for k in range(1500):
    centre = [rng.uniform(-20, 20) for _ in range(3)]
    size = 10 ** rng.uniform(-3, 2)
    kind = k % 5
    points = []
    for i in range(3):
        d = [rng.gauss(0, 1) for _ in range(3)]
        if kind == 1 and i == 2:
            d = [x * 1e-4 for x in d]
        points.append([centre[j] + size * d[j] for j in range(3)])
    if kind == 1:  # a sliver: the third corner almost on the first edge
        points[2] = [points[0][j] + (points[1][j] - points[0][j]) * 0.5 + 1e-4 * size * rng.gauss(0, 1)
                     for j in range(3)]
    uv = [(rng.random(), rng.random()) for _ in range(3)]
    if kind == 2:
        uv = [(u * 64 % 1.0, v * 64 % 1.0) for u, v in uv]
    triangle(*points, uv)
W = 1e5
triangle([-W, -1, -W], [W, -1, -W], [W, -1, W], [(0, 0), (1, 0), (1, 1)])
triangle([-W, -1, -W], [W, -1, W], [-W, -1, W], [(0, 0), (1, 1), (0, 1)])
x0 = 0.07
triangle([x0, -W, -W], [x0 + 1e-3 * W, W, -W], [x0 + 1e-3 * W, W, W], [(0, 0), (1, 0), (1, 1)])
with open(os.path.join(out, "stress.obj"), "w") as f:
    f.write("# stress: random triangles of every size, slivers, a ground plane and a wall to the "
            "horizon\n")
    for p in vertices:
        f.write("v %.9g %.9g %.9g\n" % tuple(p))
    for t in uvs:
        f.write("vt %.9g %.9g\n" % t)
    for a, b, c in faces:
        f.write("f %d/%d %d/%d %d/%d\n" % (a, a, b, b, c, c))
keyframes = []
for i in range(11):
    p = [rng.uniform(-6, 6), rng.uniform(-0.5, 6), rng.uniform(-6, 6)]
    target = [p[j] + rng.gauss(0, 1) for j in range(3)]
    if i % 3 == 0:
        target = [p[0] + 1, p[1] - 0.02, p[2]]
    keyframes.append({"frame": i * 10, "position": p, "target": target,
                      "fov": rng.choice([30.0, 60.0, 90.0, 120.0])})
with open(os.path.join(out, "stress.path.json"), "w") as f:
    json.dump({"keyframes": keyframes}, f, indent=1)
