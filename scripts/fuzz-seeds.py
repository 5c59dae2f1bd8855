#!/usr/bin/env python3
"""Seed corpora for the fuzz programs (scripts/fuzz.sh), made from real files and kept small.

  fuzz-seeds.py BASEOA RETEXTURED TEXTURES OUT

BASEOA is the folder of OpenArena's .pk3 archives (scripts/fetch-openarena.sh), RETEXTURED the
output folder of `vt retexture q3dm6ish`, TEXTURES a folder of small `vt build` outputs (*.vt,
*.json). Writes OUT/<target>/<seed> for each target of tests/fuzz/fuzz_targets.h; every seed is
at most MAX_SEED bytes. The files the project ships (data/) seed the model, probe and
configuration targets.
"""

import io
import json
import math
import os
import struct
import sys
import tarfile
import zipfile

MAX_SEED = 200 * 1024  # each seed's cap; most are cut smaller, for more executions a second
LUMPS = 17
ENTITIES, SHADERS, VERTICES, INDICES, SURFACES = 0, 1, 10, 11, 13
SHADER_SIZE, VERTEX_SIZE, SURFACE_SIZE = 72, 44, 104
POLYGON, PATCH = 1, 2


DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data")
PROBE_SEPARATOR = b"\n#vt-fuzz-file "  # tests/fuzz/fuzz_targets.h: kProbeFileSeparator
PROBE_PIXELS = 48  # pixels (inputs, or viewport texels) a probe seed keeps


def write(out, target, name, data):
    assert len(data) <= MAX_SEED, f"{target}/{name}: {len(data)} bytes"
    os.makedirs(os.path.join(out, target), exist_ok=True)
    with open(os.path.join(out, target, name), "wb") as f:
        f.write(data)


def lump(bsp, index):
    offset, length = struct.unpack_from("<ii", bsp, 8 + 8 * index)
    return bsp[offset:offset + length]


def surfaces_of(bsp):
    data = lump(bsp, SURFACES)
    return [data[i:i + SURFACE_SIZE] for i in range(0, len(data), SURFACE_SIZE)]


def cut_bsp(bsp, keep):
    """A map of the surfaces `keep` (indices) only, with the entity and shader lumps, their
    vertices and indices copied and renumbered; the lumps vt does not read are left empty."""
    vertices, indices, surfaces = bytearray(), bytearray(), bytearray()
    all_vertices, all_indices = lump(bsp, VERTICES), lump(bsp, INDICES)
    for record in (surfaces_of(bsp)[k] for k in keep):
        first_vertex, vertex_count, first_index, index_count = struct.unpack_from("<4i", record, 12)
        new = bytearray(record)
        struct.pack_into("<4i", new, 12, len(vertices) // VERTEX_SIZE, vertex_count,
                         len(indices) // 4, index_count)
        vertices += all_vertices[first_vertex * VERTEX_SIZE:(first_vertex + vertex_count) * VERTEX_SIZE]
        indices += all_indices[first_index * 4:(first_index + index_count) * 4]
        surfaces += new
    lumps = {ENTITIES: lump(bsp, ENTITIES), SHADERS: lump(bsp, SHADERS), VERTICES: vertices,
             INDICES: indices, SURFACES: surfaces}
    header = bytearray(b"IBSP" + struct.pack("<i", 46) + bytes(8 * LUMPS))
    body = bytearray()
    for index in range(LUMPS):
        data = lumps.get(index, b"")
        struct.pack_into("<ii", header, 8 + 8 * index, len(header) + len(body), len(data))
        body += data
    return bytes(header + body)


def cut_to_size(bsp, order, budget):
    """The longest prefix of `order` whose cut fits `budget` bytes."""
    size = len(cut_bsp(bsp, []))
    surfaces, keep = surfaces_of(bsp), []
    for k in order:
        vertex_count, _, index_count = struct.unpack_from("<3i", surfaces[k], 16)
        size += SURFACE_SIZE + vertex_count * VERTEX_SIZE + index_count * 4
        if size > budget:
            break
        keep.append(k)
    return cut_bsp(bsp, keep)


def surface_type(record):
    return struct.unpack_from("<i", record, 8)[0]


def read_package(baseoa, entry):
    """The entry from the last archive (in name order) that holds it, as the game loads them."""
    for name in sorted(os.listdir(baseoa), reverse=True):
        if name.endswith(".pk3"):
            with zipfile.ZipFile(os.path.join(baseoa, name)) as archive:
                if entry in archive.namelist():
                    return archive.read(entry)
    raise SystemExit(f"fuzz-seeds: {entry} is in no archive of {baseoa}")


def find_patch_map(baseoa):
    """The smallest map of the archives that has patch surfaces."""
    candidates = []
    for name in sorted(os.listdir(baseoa)):
        if not name.endswith(".pk3"):
            continue
        with zipfile.ZipFile(os.path.join(baseoa, name)) as archive:
            for info in archive.infolist():
                if info.filename.lower().endswith(".bsp"):
                    candidates.append((info.file_size, name, info.filename))
    for _, name, entry in sorted(candidates):
        with zipfile.ZipFile(os.path.join(baseoa, name)) as archive:
            bsp = archive.read(entry)
        if any(surface_type(s) == PATCH for s in surfaces_of(bsp)):
            return entry, bsp
    return None, None


def bsp_seeds(baseoa, out):
    q3dm6ish = read_package(baseoa, "maps/q3dm6ish.bsp")
    small = cut_to_size(q3dm6ish, range(len(surfaces_of(q3dm6ish))), MAX_SEED // 2)
    write(out, "bsp", "q3dm6ish-cut.bsp", small)
    tiny = cut_bsp(q3dm6ish, range(20))
    write(out, "bsp", "q3dm6ish-20-surfaces.bsp", tiny)
    entry, patched = find_patch_map(baseoa)
    if patched:
        surfaces = surfaces_of(patched)
        patches = [k for k, s in enumerate(surfaces) if surface_type(s) == PATCH]
        others = [k for k, s in enumerate(surfaces) if surface_type(s) != PATCH]
        name = os.path.splitext(os.path.basename(entry))[0]
        write(out, "bsp", f"{name}-patches.bsp",
              cut_to_size(patched, patches[:40] + others, MAX_SEED // 3))
    return small, tiny


def pk3_seeds(baseoa, out, small_bsp, tiny_bsp):
    scripts = {}
    with zipfile.ZipFile(os.path.join(baseoa, "pak0.pk3")) as archive:
        infos = sorted((i for i in archive.infolist() if i.filename.endswith(".shader")),
                       key=lambda i: i.file_size)
        for info in infos:
            text = archive.read(info)
            if b"map " in text and sum(len(t) for t in scripts.values()) + len(text) < 24 * 1024:
                scripts[info.filename] = text
        images = sorted((i for i in archive.infolist()
                         if i.filename.lower().endswith((".tga", ".jpg")) and i.file_size > 0),
                        key=lambda i: i.file_size)
        image = (images[0].filename, archive.read(images[0])) if images else None
    for compression, name in ((zipfile.ZIP_DEFLATED, "deflated.pk3"),
                              (zipfile.ZIP_STORED, "stored.pk3")):
        data = io.BytesIO()
        with zipfile.ZipFile(data, "w", compression) as archive:
            archive.writestr("maps/", b"")
            archive.writestr("maps/q3dm6ish.bsp",
                             tiny_bsp if compression == zipfile.ZIP_STORED else small_bsp)
            for script, text in scripts.items():
                archive.writestr(script, text)
            if image:
                archive.writestr(*image)
        write(out, "pk3", name, data.getvalue())


def cut_obj(text, faces):
    """The first `faces` faces of an OBJ with the vertices and coordinates they use, renumbered."""
    positions, coordinates, kept, used_v, used_vt = [], [], [], {}, {}
    lines = text.splitlines()
    for line in lines:
        if line.startswith("v "):
            positions.append(line)
        elif line.startswith("vt "):
            coordinates.append(line)
    out_v, out_vt, out_f = [], [], []
    for line in lines:
        if line.startswith(("g ", "o ", "usemtl ")):
            out_f.append(line)
        elif line.startswith("f "):
            corners = []
            for corner in line.split()[1:]:
                v, vt = (int(x) for x in corner.split("/")[:2])
                if v not in used_v:
                    used_v[v] = len(out_v) + 1
                    out_v.append(positions[v - 1])
                if vt not in used_vt:
                    used_vt[vt] = len(out_vt) + 1
                    out_vt.append(coordinates[vt - 1])
                corners.append(f"{used_v[v]}/{used_vt[vt]}")
            out_f.append("f " + " ".join(corners))
            kept.append(line)
            if len(kept) == faces:
                break
    return "\n".join(out_v + out_vt + out_f) + "\n"


def obj_seeds(out, retextured, bsp):
    with open(os.path.join(retextured, "q3dm6ish.obj")) as f:
        text = f.read()
    faces = 400
    seed = cut_obj(text, faces)
    while len(seed) > MAX_SEED // 8:
        faces //= 2
        seed = cut_obj(text, faces)
    write(out, "obj", "q3dm6ish-retextured.obj", seed.encode())

    # The map's own surfaces as an OBJ scene with one material per shader (its map_Kd the
    # shader's image), the MTL after the separator line of fuzz_targets.h.
    shaders = lump(bsp, SHADERS)
    names = [shaders[i:i + 64].split(b"\0")[0].decode("latin-1")
             for i in range(0, len(shaders), SHADER_SIZE)]
    vertices, indices = lump(bsp, VERTICES), lump(bsp, INDICES)
    obj, count = ["mtllib q3dm6ish.mtl"], 0
    for record in surfaces_of(bsp)[:30]:
        shader, _, kind, first_vertex, vertex_count, first_index, index_count = \
            struct.unpack_from("<7i", record, 0)
        if kind != POLYGON:
            continue
        obj.append(f"usemtl m{shader}")
        for v in range(first_vertex, first_vertex + vertex_count):
            x, y, z, s, t = struct.unpack_from("<5f", vertices, v * VERTEX_SIZE)
            obj.append(f"v {x:g} {z:g} {-y:g}")
            obj.append(f"vt {s:g} {1 - t:g}")
        for i in range(first_index, first_index + index_count, 3):
            a, b, c = (count + 1 + struct.unpack_from("<i", indices, (i + k) * 4)[0]
                       for k in range(3))
            obj.append(f"f {a}/{a} {b}/{b} {c}/{c}")
        count += vertex_count
    mtl = [f"newmtl m{k}\nKd 1 1 1\nmap_Kd {name}.tga" for k, name in enumerate(names)]
    seed = "\n".join(obj) + "\n#vt-fuzz-mtl\n" + "\n".join(mtl) + "\n"
    write(out, "obj", "q3dm6ish-surfaces.obj", seed.encode()[:MAX_SEED])


def layout_seeds(out, retextured, textures):
    with open(os.path.join(retextured, "q3dm6ish.layout.json")) as f:
        layout = json.load(f)
    images = layout["images"]
    count = len(images)
    while True:
        layout["images"] = images[:count]
        seed = json.dumps(layout, indent=1).encode()
        if len(seed) <= MAX_SEED // 6:
            break
        count //= 2
    write(out, "layout", "q3dm6ish.layout.json", seed)
    for name in sorted(os.listdir(textures)):
        if name.endswith(".json"):
            with open(os.path.join(textures, name), "rb") as f:
                write(out, "layout", name, f.read())


def camera_path_seeds(out, retextured):
    with open(os.path.join(retextured, "q3dm6ish.path.json"), "rb") as f:
        text = f.read()
    write(out, "camera_path", "q3dm6ish.path.json", text[:MAX_SEED])
    path = json.loads(text)
    path["keyframes"] = path["keyframes"][:3]
    write(out, "camera_path", "q3dm6ish-3-keyframes.path.json", json.dumps(path).encode())
    # The storyboards the project ships (data/paths/).
    shipped = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "paths")
    for name in sorted(os.listdir(shipped)) if os.path.isdir(shipped) else []:
        if name.endswith(".json"):
            with open(os.path.join(shipped, name), "rb") as f:
                write(out, "camera_path", name, f.read())


def need_value(px, py, m, need8):
    if need8:
        return (px % 256, py % 256, m, px // 256 + (py // 256) * 16)
    return (px, py, m, 1)


def needbuffer_seeds(out):
    """Readbacks of a floor receding to the horizon, the shader's encodings (shader/needbuffer.h):
    finer levels near the bottom rows, no geometry above the horizon."""
    width, height = 64, 32
    for need8 in (False, True):
        flags = (1 if need8 else 0) | 2 | 4
        data = bytearray([flags]) + struct.pack("<H", width - 1)
        for y in range(height):
            for x in range(width):
                if y >= 24:
                    value = (0, 0, 255, 0) if need8 else (0, 0, 0, 0)
                else:
                    m = max(0, 6 - y // 4)
                    value = need_value(x * (1 << m) // width, y * (1 << m) // 24, m, need8)
                data += struct.pack("<4I", *value)
        write(out, "needbuffer", "floor-need8.bin" if need8 else "floor-need32.bin", bytes(data))


def vt_file_seeds(out, textures):
    for name in sorted(os.listdir(textures)):
        if name.endswith(".vt"):
            with open(os.path.join(textures, name), "rb") as f:
                write(out, "vt_file", name, f.read())


def precision_model_seeds(out):
    """The measured model the project ships; the named models are stored regression inputs
    (tests/fuzz/regressions/precision_model/), which scripts/fuzz.sh adds."""
    with open(os.path.join(DATA, "gpus", "nvidia-h100", "model.json"), "rb") as f:
        write(out, "precision_model", "nvidia-h100.json", f.read())


def probe_seed(request, files):
    """One draw as the probe_folder target reads it (fuzz_targets.h): the request, then each
    data file after a separator line naming it."""
    seed = json.dumps(request, indent=1).encode()
    for name, data in files.items():
        seed += PROBE_SEPARATOR + name.encode() + b"\n" + data
    return seed


def cut_probe(request, files):
    """The draw cut to at most PROBE_PIXELS inputs or viewport pixels, its counts adjusted."""
    request, files = dict(request), dict(files)
    if request["kind"] == "triangles":
        width, height = request["viewport"]
        width, height = min(width, 8), min(height, PROBE_PIXELS // 8)
        request["viewport"] = [width, height]
        files["result"] = files["result"][:width * height * 32]  # int32 and 7 float32 a pixel
        return request, files
    width = min(request["width"], 16)
    count = min(request["input_count"], PROBE_PIXELS) // width * width
    request.update(width=width, input_count=count)
    files["inputs.f32"] = files["inputs.f32"][:count * 16]
    files["result"] = files["result"][:count * (16 if request["kind"] == "shader" else 4)]
    return request, files


def probe_folder_seeds(out):
    """Each kind of draw from the H100's recorded probes (data/gpus/nvidia-h100/probes.tar.gz),
    small ones whole and the rest cut, renumbered as draw 0; the first with the folder's
    probes.json."""
    with tarfile.open(os.path.join(DATA, "gpus", "nvidia-h100", "probes.tar.gz")) as archive:
        members = {os.path.basename(m.name): m for m in archive.getmembers() if m.isfile()}
        read = lambda name: archive.extractfile(members[name]).read()
        description = read("probes.json")
        kept = set()
        for name in sorted(members):
            if not (name.startswith("probe-") and name.endswith(".json")):
                continue
            stem = name[:-len(".json")]
            request = json.loads(read(name))
            kind = (request["kind"], request.get("block_format"), "texels" in request,
                    request.get("depth"))
            if kind in kept or request.get("vertex_count", 0) > 64:
                continue
            kept.add(kind)
            files = {m[len(stem) + 1:]: read(m) for m in members
                     if m.startswith(stem + ".") and m != name}
            request, files = cut_probe(request, files)
            for key in ("inputs", "texels", "blocks", "vertices", "indices"):
                if key in request:  # named by the draw's index, which becomes 0
                    request[key] = request[key].replace(stem, "probe-0000")
            if len(kept) == 1:
                files["probes.json"] = description
            seed = probe_seed(request, files)
            if len(seed) <= MAX_SEED // 8:
                write(out, "probe_folder", stem + ".probe", seed)
    # The probe pack's sweeps (capture/sweep_files.h), beside the first draw: the first row of
    # log2 over [0.5, 2), its results delta-coded, and a sqrt asked for but not drawn.
    first, count = 0x3F000000, 4096
    sweeps = {"format": "vt-sweeps", "version": 1, "sweeps": [
        {"name": "log2", "expression": "log2(x)", "first": first, "count": count},
        {"name": "sqrt", "expression": "sqrt(x)", "first": 0x3F800000, "count": count}]}
    previous, deltas = 0, bytearray()
    for i in range(count):
        x = struct.unpack("<f", struct.pack("<I", first + i))[0]
        bits = struct.unpack("<I", struct.pack("<f", math.log2(x)))[0]
        deltas += struct.pack("<I", (bits - previous) % 2**32)
        previous = bits
    files = {"probes.json": description, "sweeps.json": json.dumps(sweeps, indent=1).encode(),
             "sweep-log2.delta": bytes(deltas)}
    write(out, "probe_folder", "sweeps.probe", probe_seed({"kind": "shader"}, files))


def config_seeds(out):
    """The configurations files of chapter 4's runs (data/chapter4/)."""
    folder = os.path.join(DATA, "chapter4")
    for name in sorted(os.listdir(folder)):
        if name.endswith(".json"):
            with open(os.path.join(folder, name), "rb") as f:
                write(out, "config", name, f.read())


def main():
    if len(sys.argv) != 5:
        raise SystemExit(__doc__)
    baseoa, retextured, textures, out = sys.argv[1:]
    small_bsp, tiny_bsp = bsp_seeds(baseoa, out)
    pk3_seeds(baseoa, out, small_bsp, tiny_bsp)
    obj_seeds(out, retextured, small_bsp)
    layout_seeds(out, retextured, textures)
    camera_path_seeds(out, retextured)
    needbuffer_seeds(out)
    vt_file_seeds(out, textures)
    precision_model_seeds(out)
    probe_folder_seeds(out)
    config_seeds(out)


if __name__ == "__main__":
    main()
