#!/usr/bin/env python3
"""Writes a glTF test scene of alpha-tested foliage: a ground quad and N leaf cards (two triangles
each, a 64 x 64 RGBA texture whose alpha is a leaf-shaped ellipse, ~62 % of the card's texels
transparent) in a 6 x 3 x 6 m volume, a camera looking at them, no lights (add --sun).

    scripts/leaf_cards.py OUT.gltf [--cards 2000] [--alpha-mode MASK|BLEND|OPAQUE] [--seed 1]
                          [--solid]

--solid makes every texel opaque (alpha 255): MASK then draws exactly the OPAQUE image, so the
time difference is the alpha test's own cost, without the longer rays through the holes.

Used by docs/benchmarks.md "Alpha-tested geometry" to time MASK against the same geometry drawn
OPAQUE. Only the standard library: the PNG is written with zlib, the buffers as a data URI.
"""
import argparse
import base64
import json
import math
import random
import struct
import zlib


def leaf_png(size=64, solid=False):
    """RGBA8 PNG: green, alpha 255 inside the ellipse (x/0.45)^2 + (y/0.3)^2 < 1 (centred), else 0."""
    rows = []
    for j in range(size):
        row = bytearray([0])  # filter type 0
        for i in range(size):
            x = (i + 0.5) / size - 0.5
            y = (j + 0.5) / size - 0.5
            inside = (x / 0.45) ** 2 + (y / 0.3) ** 2 < 1.0
            row += bytes([60, 140, 40, 255 if inside or solid else 0])
        rows.append(bytes(row))
    raw = b"".join(rows)

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", size, size, 8, 6, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9))
            + chunk(b"IEND", b""))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--cards", type=int, default=2000)
    parser.add_argument("--alpha-mode", default="MASK", choices=["MASK", "BLEND", "OPAQUE"])
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--solid", action="store_true", help="alpha 255 everywhere")
    args = parser.parse_args()
    rng = random.Random(args.seed)

    positions, uvs, indices = [], [], []

    def quad(corners, quad_uvs):
        base = len(positions)
        positions.extend(corners)
        uvs.extend(quad_uvs)
        indices.extend([base, base + 1, base + 2, base, base + 2, base + 3])

    ground = [(-6, 0, -6), (-6, 0, 6), (6, 0, 6), (6, 0, -6)]  # counter-clockwise from +y
    quad(ground, [(0, 0), (0, 1), (1, 1), (1, 0)])
    ground_indices = len(indices)
    for _ in range(args.cards):
        cx, cy, cz = rng.uniform(-3, 3), rng.uniform(0.5, 3.5), rng.uniform(-3, 3)
        yaw, pitch = rng.uniform(0, 2 * math.pi), rng.uniform(-1.2, 1.2)
        u = (math.cos(yaw) * 0.2, 0.0, math.sin(yaw) * 0.2)  # half extents: 0.4 x 0.4 m card
        v = (-math.sin(yaw) * math.sin(pitch) * 0.2, math.cos(pitch) * 0.2,
             math.cos(yaw) * math.sin(pitch) * 0.2)
        corner = lambda a, b: (cx + a * u[0] + b * v[0], cy + a * u[1] + b * v[1],
                               cz + a * u[2] + b * v[2])
        quad([corner(-1, -1), corner(1, -1), corner(1, 1), corner(-1, 1)],
             [(0, 1), (1, 1), (1, 0), (0, 0)])

    blob = bytearray()
    for p in positions:
        blob += struct.pack("<3f", *p)
    uv_offset = len(blob)
    for t in uvs:
        blob += struct.pack("<2f", *t)
    index_offset = len(blob)
    for i in indices:
        blob += struct.pack("<I", i)
    n = len(positions)
    lo = [min(p[k] for p in positions) for k in range(3)]
    hi = [max(p[k] for p in positions) for k in range(3)]
    leaf = {"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0},
            "doubleSided": True, "alphaMode": args.alpha_mode, "name": "leaf"}
    gltf = {
        "asset": {"version": "2.0", "generator": "fovea scripts/leaf_cards.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"mesh": 0},
                  {"camera": 0, "translation": [0, 2.0, 8.5], "rotation": [-0.0499, 0, 0, 0.9988]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.05}}],
        "meshes": [{"primitives": [
            {"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0},
            {"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 3, "material": 1}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.45, 0.4, 1],
                                                "metallicFactor": 0}, "name": "ground"}, leaf],
        "textures": [{"source": 0}],
        "images": [{"uri": "data:image/png;base64," + base64.b64encode(leaf_png(solid=args.solid)).decode()}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3", "min": lo,
             "max": hi},
            {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC2"},
            {"bufferView": 2, "componentType": 5125, "count": ground_indices, "type": "SCALAR"},
            {"bufferView": 2, "byteOffset": 4 * ground_indices, "componentType": 5125,
             "count": len(indices) - ground_indices, "type": "SCALAR"}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": uv_offset},
            {"buffer": 0, "byteOffset": uv_offset, "byteLength": index_offset - uv_offset},
            {"buffer": 0, "byteOffset": index_offset, "byteLength": len(blob) - index_offset}],
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," +
                            base64.b64encode(bytes(blob)).decode()}],
    }
    with open(args.out, "w") as f:
        json.dump(gltf, f)
    print(f"{args.out}: {args.cards} cards ({2 * args.cards + 2} triangles), {args.alpha_mode}"
          + (", solid texels" if args.solid else ""))


if __name__ == "__main__":
    main()
