#!/usr/bin/env python3
"""The dense BC3 alpha probe behind data/gpus/nvidia-h100/bc3-alpha.u8 (block_decoding.h).

  scripts/bc3-alpha-probe.py make DIR            a probe request for vt-capture: one 1024 x 1024
                                                 BC3 texture, one block per alpha end-point pair
                                                 (a0 = block & 255, a1 = block >> 8), texel t at
                                                 alpha index t % 8, colour halves random (seed 7);
                                                 texelFetch of every texel
  vt-capture probes DIR -o OUT                   on the GPU
  scripts/bc3-alpha-probe.py table OUT FILE      the alphas at indices 2..7 per pair (a0 slow,
                                                 a1 fast) as bytes, each round(value * 255)

Pure Python (no numpy), so that it runs on a bare machine's python3 too.
"""
import array
import json
import os
import random
import sys

SIDE = 1024


def make(folder):
    os.makedirs(folder, exist_ok=True)
    rng = random.Random(7)
    indices = 0
    for t in range(16):
        indices |= (t % 8) << (3 * t)
    blocks = bytearray()
    for p in range(65536):
        blocks += bytes([p & 255, p >> 8]) + indices.to_bytes(6, "little")
        blocks += bytes(rng.getrandbits(8) for _ in range(8))
    with open(os.path.join(folder, "probe-0000.blocks.bc3"), "wb") as f:
        f.write(blocks)
    inputs = array.array("f")
    for y in range(SIDE):
        for x in range(SIDE):
            inputs.extend((x, y, 0.0, 0.0))
    with open(os.path.join(folder, "probe-0000.inputs.f32"), "wb") as f:
        f.write(inputs.tobytes())
    request = {"format": "vt-probe", "version": 1, "kind": "shader",
               "body": "result = texelFetch(uTexture, ivec2(x.xy), 0);", "width": SIDE,
               "inputs": "probe-0000.inputs.f32", "input_count": SIDE * SIDE,
               "blocks": "probe-0000.blocks.bc3", "block_format": "bc3",
               "texture_size": [SIDE, SIDE], "linear": False, "clipped": True}
    with open(os.path.join(folder, "probe-0000.json"), "w") as f:
        json.dump(request, f, indent=1)


def table(folder, path):
    values = array.array("f")
    with open(os.path.join(folder, "probe-0000.result"), "rb") as f:
        values.frombytes(f.read())
    if len(values) != SIDE * SIDE * 4:
        sys.exit(f"{folder}/probe-0000.result: {len(values)} floats, not {SIDE * SIDE * 4}")
    out = bytearray()
    for p in range(65536):
        bx, by = p % 256, p // 256
        for index in range(2, 8):
            x, y = bx * 4 + index % 4, by * 4 + index // 4
            v = values[(y * SIDE + x) * 4 + 3] * 255
            if abs(v - round(v)) > 1e-3:
                sys.exit(f"{folder}/probe-0000.result: texel ({x}, {y}) alpha {v / 255} is no k/255")
            out.append(round(v))
    # Pairs in the file run a0 slow, a1 fast; the texture's blocks run a0 fast.
    ordered = bytearray(len(out))
    for p in range(65536):
        a0, a1 = p & 255, p >> 8
        ordered[(a0 * 256 + a1) * 6:(a0 * 256 + a1) * 6 + 6] = out[p * 6:p * 6 + 6]
    with open(path, "wb") as f:
        f.write(ordered)


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "make":
        make(sys.argv[2])
    elif len(sys.argv) == 4 and sys.argv[1] == "table":
        table(sys.argv[2], sys.argv[3])
    else:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
