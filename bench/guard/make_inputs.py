#!/usr/bin/env python3
"""Writes the generated inputs of scripts/bench-guard.sh into OUTDIR (plain Python,
no NumPy, every byte the same on every run):

- textured.gltf + checker.png + textured.bin: a glTF 2.0 scene of a textured floor
  and a textured tilted card (baseColorTexture, repeat wrap, UVs), with a camera,
  a point light and a directional light;
- with --bunny MESH.obj: bunny_origins.npy, bunny_directions.npy: float32 (N, 3)
  rays for `lamplight raycast`, 64x64 primary camera rays at the mesh's bounding
  box (as ../shared/anchors/embree/raycast_bench.py's `primary` set, smaller) and
  4096 incoherent rays (origins in the box enlarged by 10 %, uniform directions,
  a fixed seed), bench/gen_rays.py's two kinds of rays.

    python3 bench/guard/make_inputs.py OUTDIR [--bunny ../shared/data/meshes/stanford-bunny.obj]
"""
import argparse
import json
import math
import random
import struct
import zlib
from pathlib import Path


def png_rgb(width, height, pixel):
    """An 8-bit RGB PNG; pixel(x, y) gives (r, g, b), row 0 at the top."""
    rows = b"".join(b"\0" + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b"")


def write_gltf(out: Path):
    # 32 x 32 texels: an 8 x 8 checker of two colours with a gradient, so filtering has work to do.
    def texel(x, y):
        on = (x // 4 + y // 4) % 2
        return (40 + 6 * x, 200 - 5 * y, 60) if on else (230, 220 - 3 * x, 90 + 4 * y)

    (out / "checker.png").write_bytes(png_rgb(32, 32, texel))
    # Two quads: a floor (y = 0, 4 x 4, UVs 0..4 repeat) and a card (tilted, 1.2 x 1.6, UVs 0..1).
    floor = [(-2, 0, -2), (2, 0, -2), (2, 0, 2), (-2, 0, 2)]
    floor_uv = [(0, 0), (4, 0), (4, 4), (0, 4)]
    card = [(-0.6, 0.1, 0.0), (0.6, 0.1, 0.0), (0.6, 1.7, -0.5), (-0.6, 1.7, -0.5)]
    card_uv = [(0, 1), (1, 1), (1, 0), (0, 0)]
    positions = floor + card
    uvs = floor_uv + card_uv
    normals = [(0, 1, 0)] * 4 + [(0, 0.298, 0.955)] * 4
    indices = [0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7]
    pos_bytes = b"".join(struct.pack("<3f", *p) for p in positions)
    nor_bytes = b"".join(struct.pack("<3f", *n) for n in normals)
    uv_bytes = b"".join(struct.pack("<2f", *t) for t in uvs)
    idx_bytes = b"".join(struct.pack("<H", i) for i in indices)
    buffer = pos_bytes + nor_bytes + uv_bytes + idx_bytes
    (out / "textured.bin").write_bytes(buffer)
    offsets = [0, len(pos_bytes), len(pos_bytes) + len(nor_bytes), len(pos_bytes) + len(nor_bytes) + len(uv_bytes)]
    lo = [min(p[k] for p in positions) for k in range(3)]
    hi = [max(p[k] for p in positions) for k in range(3)]
    n = len(positions)
    doc = {
        "asset": {"version": "2.0", "generator": "lamplight bench/guard/make_inputs.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2, 3]}],
        "nodes": [
            {"mesh": 0},
            {"camera": 0, "translation": [0, 1.6, 4.2], "rotation": [-0.17, 0, 0, 0.985]},
            {"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [1.5, 3, 2]},
            {"extensions": {"KHR_lights_punctual": {"light": 1}}, "rotation": [-0.38, 0.3, 0, 0.87]},
        ],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.7, "znear": 0.1}}],
        "meshes": [{"name": "floor-and-card", "primitives": [
            {"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0,
                                                "roughnessFactor": 0.6}}],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{"wrapS": 10497, "wrapT": 10497, "magFilter": 9729, "minFilter": 9987}],
        "images": [{"uri": "checker.png"}],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "point", "color": [1, 0.95, 0.9], "intensity": 30},
            {"type": "directional", "color": [0.8, 0.85, 1], "intensity": 1.5},
        ]}},
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3", "min": lo, "max": hi},
            {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": n, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5123, "count": len(indices), "type": "SCALAR"},
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": offsets[0], "byteLength": len(pos_bytes)},
            {"buffer": 0, "byteOffset": offsets[1], "byteLength": len(nor_bytes)},
            {"buffer": 0, "byteOffset": offsets[2], "byteLength": len(uv_bytes)},
            {"buffer": 0, "byteOffset": offsets[3], "byteLength": len(idx_bytes)},
        ],
        "buffers": [{"uri": "textured.bin", "byteLength": len(buffer)}],
    }
    (out / "textured.gltf").write_text(json.dumps(doc, indent=1) + "\n")


def write_npy_f32_rows3(path: Path, rows):
    """A little-endian float32 (N, 3) .npy file (format version 1.0)."""
    header = "{'descr': '<f4', 'fortran_order': False, 'shape': (%d, 3), }" % len(rows)
    header += " " * (63 - (10 + len(header)) % 64) + "\n"  # pads the preamble to a multiple of 64 bytes
    data = b"".join(struct.pack("<3f", *r) for r in rows)
    path.write_bytes(b"\x93NUMPY\x01\x00" + struct.pack("<H", len(header)) + header.encode("latin1") + data)


def obj_vertices(path: Path):
    return [tuple(float(t) for t in line.split()[1:4]) for line in path.open() if line.startswith("v ")]


def unit(v):
    n = math.sqrt(sum(c * c for c in v))
    return tuple(c / n for c in v)


def write_bunny_rays(out: Path, mesh: Path, side=64, incoherent=4096, seed=20240601):
    verts = obj_vertices(mesh)
    lo = [min(v[k] for v in verts) for k in range(3)]
    hi = [max(v[k] for v in verts) for k in range(3)]
    c = [(a + b) / 2 for a, b in zip(lo, hi)]
    radius = 0.5 * math.sqrt(sum((b - a) ** 2 for a, b in zip(lo, hi)))
    # A camera on +z looking along -z at the box's centre, 40 degrees, far enough that the box fits.
    tan_half = math.tan(math.radians(40) / 2)
    eye = (c[0], c[1], c[2] + radius / math.sin(math.radians(20)))
    origins, directions = [], []
    for i in range(side):
        for j in range(side):
            x = (2 * (j + 0.5) / side - 1) * tan_half
            y = (1 - 2 * (i + 0.5) / side) * tan_half
            origins.append(eye)
            directions.append(unit((x, y, -1.0)))
    rng = random.Random(seed)
    for _ in range(incoherent):
        origins.append(tuple(ck + (rng.random() - 0.5) * (h - l) * 1.1 for ck, l, h in zip(c, lo, hi)))
        directions.append(unit(tuple(rng.gauss(0, 1) for _ in range(3))))
    write_npy_f32_rows3(out / "bunny_origins.npy", origins)
    write_npy_f32_rows3(out / "bunny_directions.npy", directions)


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("outdir", type=Path)
    ap.add_argument("--bunny", type=Path, help="the Stanford bunny .obj; writes the raycast case's rays")
    args = ap.parse_args()
    args.outdir.mkdir(parents=True, exist_ok=True)
    write_gltf(args.outdir)
    if args.bunny:
        write_bunny_rays(args.outdir, args.bunny)
