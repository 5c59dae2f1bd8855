#!/usr/bin/env python3
"""A layout's copy whose images are to get noise as alpha (scripts/gpu-kit.sh):
  gpu-kit-noisy-layout.py LAYOUT FOLDER
writes FOLDER/layout.json naming FOLDER/image<k>.png for the k-th image and prints one line per
image, SOURCE and TARGET with a tab between, for the caller to make each target (the source's RGB with an alpha)."""
import json
import os
import sys

if len(sys.argv) != 3:
    print(__doc__, file=sys.stderr)
    sys.exit(2)
layout_path, folder = sys.argv[1], sys.argv[2]
with open(layout_path) as f:
    layout = json.load(f)
base = os.path.dirname(os.path.abspath(layout_path))
for k, image in enumerate(layout["images"]):
    source = os.path.join(base, image["file"])
    target = os.path.join(os.path.abspath(folder), f"image{k}.png")
    print(f"{source}\t{target}")
    image["file"] = target
with open(os.path.join(folder, "layout.json"), "w") as f:
    json.dump(layout, f, indent=1)
