#!/usr/bin/env python3
"""Writes a .glb of one N x N grid of quads (2 N^2 triangles) on a gently
curved sheet, placed by K nodes (default 1) on a square layout, for
measuring the octree build over many triangles and instancing:

    tools/make_grid_glb.py N OUT.glb [K]
    tools/make_grid_glb.py 708 /tmp/grid1m.glb          # 1,002,528 triangles
    tools/make_grid_glb.py 187 /tmp/grid400.glb 400     # 69,938 triangles, 400 instances

Bad input (N or K not a whole number >= 1, N too large for 32-bit indices,
OUT in a folder that does not exist) exits with 2. Python standard library only.
"""
import argparse
import json
import math
import struct

import tool_args

MAX_N = 65535  # the largest grid whose (N + 1)^2 vertices 32-bit indices reach


def main():
    parser = tool_args.Parser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("n", metavar="N", type=tool_args.positive_int, help="quads per side of the grid")
    parser.add_argument("out", metavar="OUT.glb", type=tool_args.output_file, help="the .glb to write")
    parser.add_argument("k", metavar="K", type=tool_args.positive_int, nargs="?", default=1,
                        help="nodes placing the grid (instances; default 1)")
    args = parser.parse_args()
    n, out, k = args.n, args.out, args.k
    if n > MAX_N:
        parser.error(f"argument N: at most {MAX_N} (32-bit indices), got {n}")
    side = math.ceil(math.sqrt(k))
    verts = bytearray()
    for y in range(n + 1):
        for x in range(n + 1):
            u, v = x / n, y / n
            verts += struct.pack("<3f", u * 10 - 5, 0.3 * math.sin(6 * u) * math.cos(5 * v), v * 10 - 5)
    idx = bytearray()
    for y in range(n):
        for x in range(n):
            a = y * (n + 1) + x
            idx += struct.pack("<6I", a, a + n + 1, a + 1, a + 1, a + n + 1, a + n + 2)
    lo = [-5.0, -0.3, -5.0]
    hi = [5.0, 0.3, 5.0]
    gltf = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": list(range(k))}],
        "nodes": [{"mesh": 0, "translation": [12.0 * (i % side), 0.0, 12.0 * (i // side)]} for i in range(k)],
        "meshes": [{"name": "grid", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": len(verts) + len(idx)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(verts)},
                        {"buffer": 0, "byteOffset": len(verts), "byteLength": len(idx)}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": (n + 1) ** 2, "type": "VEC3",
                       "min": lo, "max": hi},
                      {"bufferView": 1, "componentType": 5125, "count": 6 * n * n, "type": "SCALAR"}],
    }
    text = json.dumps(gltf).encode()
    text += b" " * (-len(text) % 4)
    binary = bytes(verts + idx)
    binary += b"\0" * (-len(binary) % 4)
    total = 12 + 8 + len(text) + 8 + len(binary)
    with open(out, "wb") as f:
        f.write(struct.pack("<3I", 0x46546C67, 2, total))
        f.write(struct.pack("<2I", len(text), 0x4E4F534A) + text)
        f.write(struct.pack("<2I", len(binary), 0x004E4942) + binary)
    print(f"{out}: {2 * n * n} triangles, {k} instances")


if __name__ == "__main__":
    main()
