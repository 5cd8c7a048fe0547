#!/usr/bin/env python3
"""Writes leaf.glb, the leaf the docs use with `dla3d --leaf`: a green blade one unit long
along +Y from its stem at the origin, its face toward +Z and curling that way, double-sided.
Any glb made the same way works: model the leaf with its stem at the origin, pointing up (+Y in
glTF, +Z in Blender, which converts on export), and within a unit sphere about the origin.

    python3 examples/make_leaf.py examples/leaf.glb
"""
import json
import math
import struct
import sys

ROWS, ACROSS = 16, 5  # rows along the blade, vertices across it


def blade():
    """Positions, normals, texture coordinates and triangles of the stem and the blade."""
    positions, uvs = [], []
    for j in range(ROWS + 1):
        t = j / ROWS
        y = 0.12 + 0.86 * t
        half_width = 0.24 * math.sin(math.pi * t) ** 0.7 + 0.012
        for i in range(ACROSS):
            s = i / (ACROSS - 1) * 2 - 1  # -1 at the left edge, 1 at the right
            x = s * half_width
            z = 0.18 * t * t - 0.05 * s * s * math.sin(math.pi * t)  # curls up along, cups across
            positions.append((x, y, z))
            uvs.append(((s + 1) / 2, 1 - t))
    triangles = []
    for j in range(ROWS):
        for i in range(ACROSS - 1):
            a = j * ACROSS + i
            b, c, d = a + 1, a + 1 + ACROSS, a + ACROSS
            triangles += [(a, b, c), (a, c, d)]
    # The stem: a thin strip from the origin to the blade's base.
    base = len(positions)
    for y in (0.0, 0.12):
        for x in (-0.012, 0.012):
            positions.append((x, y, 0.0))
            uvs.append(((x / 0.012 + 1) / 2, 1.0))
    triangles += [(base, base + 1, base + 3), (base, base + 3, base + 2)]
    normals = [[0.0, 0.0, 0.0] for _ in positions]
    for a, b, c in triangles:
        pa, pb, pc = positions[a], positions[b], positions[c]
        u = [pb[k] - pa[k] for k in range(3)]
        v = [pc[k] - pa[k] for k in range(3)]
        n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
        for corner in (a, b, c):
            for k in range(3):
                normals[corner][k] += n[k]
    for n in normals:
        length = math.sqrt(sum(x * x for x in n)) or 1.0
        n[:] = [x / length for x in n]
    return positions, normals, uvs, triangles


def glb(positions, normals, uvs, triangles):
    count = len(positions)
    vertex_data = b"".join(struct.pack("<3f", *p) for p in positions)
    normal_data = b"".join(struct.pack("<3f", *n) for n in normals)
    uv_data = b"".join(struct.pack("<2f", *t) for t in uvs)
    index_data = b"".join(struct.pack("<3H", *t) for t in triangles)
    index_data += b"\0" * (-len(index_data) % 4)
    chunks = [vertex_data, normal_data, uv_data, index_data]
    views, offset = [], 0
    for k, chunk in enumerate(chunks):
        view = {"buffer": 0, "byteOffset": offset, "byteLength": len(chunk),
                "target": 34963 if k == 3 else 34962}
        views.append(view)
        offset += len(chunk)
    views[3]["byteLength"] = len(triangles) * 6
    lo = [min(p[k] for p in positions) for k in range(3)]
    hi = [max(p[k] for p in positions) for k in range(3)]
    gltf = {
        "asset": {"version": "2.0", "generator": "dla3d examples/make_leaf.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "leaf", "mesh": 0}],
        "meshes": [{"name": "leaf", "primitives": [{
            "attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]}],
        "materials": [{"name": "leaf", "doubleSided": True, "pbrMetallicRoughness": {
            "baseColorFactor": [0.22, 0.5, 0.12, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.6}}],
        "buffers": [{"byteLength": offset}],
        "bufferViews": views,
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": count, "type": "VEC3", "min": lo, "max": hi},
            {"bufferView": 1, "componentType": 5126, "count": count, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": count, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5123, "count": 3 * len(triangles), "type": "SCALAR"},
        ],
    }
    text = json.dumps(gltf, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    binary = b"".join(chunks)
    length = 12 + 8 + len(text) + 8 + len(binary)
    return (struct.pack("<4sII", b"glTF", 2, length) + struct.pack("<I4s", len(text), b"JSON") + text +
            struct.pack("<I4s", len(binary), b"BIN\0") + binary)


if __name__ == "__main__":
    with open(sys.argv[1] if len(sys.argv) > 1 else "leaf.glb", "wb") as out:
        out.write(glb(*blade()))
