#!/usr/bin/env python3
"""Writes the textured test assets of tests/unit/io/gltf_test.cpp and tests/cli/assets_test.sh:
a cube whose six faces carry a 4x4 texture of four 2x2 quadrants (red, green, blue, white;
the left half's alpha 0 for the MASK variant), as glTF placed by a two-node tree, and the same
cube in world space as OBJ + MTL. Run it to regenerate; the outputs are committed."""
import base64, json, struct, zlib, os

here = os.path.dirname(os.path.abspath(__file__))
QUAD = {(0, 0): (255, 0, 0), (1, 0): (0, 255, 0), (0, 1): (0, 0, 255), (1, 1): (255, 255, 255)}


def png(width, height, rgba):
    raw = b"".join(b"\0" + bytes(rgba[y * width * 4:(y + 1) * width * 4]) for y in range(height))
    chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xFFFFFFFF)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def texture(mask):
    px = []
    for y in range(4):
        for x in range(4):
            r, g, b = QUAD[(x // 2, y // 2)]
            px += [r, g, b, 0 if (mask and x < 2) else 255]
    return png(4, 4, px)


# Unit cube faces: corners counter-clockwise seen from outside, uv (0,0) at the first corner.
FACES = [((1, 0, 0), [(1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 0, 1)]),
         ((-1, 0, 0), [(0, 1, 0), (0, 0, 0), (0, 0, 1), (0, 1, 1)]),
         ((0, 1, 0), [(1, 1, 0), (0, 1, 0), (0, 1, 1), (1, 1, 1)]),
         ((0, -1, 0), [(0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1)]),
         ((0, 0, 1), [(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]),
         ((0, 0, -1), [(0, 1, 0), (1, 1, 0), (1, 0, 0), (0, 0, 0)])]
UV = [(0, 1), (1, 1), (1, 0), (0, 0)]  # glTF: v runs down the image


def cube_gltf(name, mask):
    pos, nrm, uv, idx = [], [], [], []
    for n, corners in FACES:
        base = len(pos) // 3
        for c, t in zip(corners, UV):
            pos += c; nrm += n; uv += t
        idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    blob = struct.pack("<%df" % len(pos), *pos) + struct.pack("<%df" % len(nrm), *nrm) + \
        struct.pack("<%df" % len(uv), *uv) + struct.pack("<%dH" % len(idx), *idx)
    n = len(pos) // 3
    views = [(0, 12 * n), (12 * n, 12 * n), (24 * n, 8 * n), (32 * n, 2 * len(idx))]
    material = {"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0},
                "name": "quadrants"}
    if mask:
        material.update({"alphaMode": "MASK", "alphaCutoff": 0.5, "doubleSided": True})
    doc = {
        "asset": {"version": "2.0", "generator": "quasiflat tests/data/textured/make.py"},
        "scene": 0, "scenes": [{"nodes": [0]}],
        # The tree: translate (1, 2, 3), then scale 2: the cube spans (1,2,3)..(3,4,5) in the world.
        "nodes": [{"translation": [1, 2, 3], "children": [1]}, {"scale": [2, 2, 2], "mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
                                    "indices": 3, "material": 0}]}],
        "materials": [material],
        "textures": [{"source": 0}],  # the default sampler repeats, as OBJ viewers do
        "images": [{"uri": name + ".png"}],
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": o, "byteLength": l} for o, l in views],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 1]},
            {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": n, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5123, "count": len(idx), "type": "SCALAR"}],
    }
    open(os.path.join(here, name + ".gltf"), "w").write(json.dumps(doc, indent=1) + "\n")
    open(os.path.join(here, name + ".png"), "wb").write(texture(mask))


def cube_obj(name, png_name):
    lines = ["# the cube of cube.gltf in world space, with the same texture", "mtllib " + name + ".mtl", "usemtl quadrants"]
    for n, corners in FACES:
        for c in corners:
            lines.append("v %g %g %g" % (1 + 2 * c[0], 2 + 2 * c[1], 3 + 2 * c[2]))
    for u, v in UV:
        lines.append("vt %g %g" % (u, 1 - v))  # OBJ: v runs up the image
    for f in range(6):
        b = 4 * f + 1
        lines.append("f %d/1 %d/2 %d/3 %d/4" % (b, b + 1, b + 2, b + 3))
    open(os.path.join(here, name + ".obj"), "w").write("\n".join(lines) + "\n")
    open(os.path.join(here, name + ".mtl"), "w").write("newmtl quadrants\nKd 1 1 1\nmap_Kd " + png_name + "\n")


cube_gltf("cube", False)
cube_gltf("cube_mask", True)
cube_obj("cube", "cube.png")
