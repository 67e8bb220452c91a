#!/usr/bin/env python3
"""Writes the hostile corpus of the readers (issue 50): small glTF, glb and OBJ files made to crash,
exhaust memory or read files outside their folder. Seeded: the same seed writes the same files.

usage: make_corpus.py OUTDIR [--seed N]

OUTDIR/cases.tsv lists one case a line: NAME, the input to bake (relative to OUTDIR), whether it
names a file outside its folder ("outside": it must never bake), and the programs to run it with
("bake" or "bake,render"). Every case lives in OUTDIR/cases/NAME/; OUTDIR/outside/ holds the files
the outside cases point at (a triangle's buffer, a PNG, an MTL), which a reader must not take."""
import argparse
import base64
import json
import os
import random
import struct
import zlib

# One triangle: positions (0,0,0) (1,0,0) (0,1,0) as floats, then indices 0 1 2 as u16.
TRIANGLE = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<3H", 0, 1, 2)


def triangle_gltf(nodes=None, scene_nodes=None, uri=None, count=3, extra=None, images=None):
    """A one-triangle glTF; every part can be replaced by a hostile one."""
    g = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": scene_nodes if scene_nodes is not None else [0]}],
        "nodes": nodes if nodes is not None else [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": len(TRIANGLE),
                     "uri": uri if uri is not None else "data:application/octet-stream;base64," + base64.b64encode(TRIANGLE).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": count, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
    }
    if images:
        g["images"] = images
        g["textures"] = [{"source": i} for i in range(len(images))]
        g["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
        g["meshes"][0]["primitives"][0]["material"] = 0
    if extra:
        g.update(extra)
    return g


def cube_gltf(nodes):
    """A unit cube of 24 vertices (4 a face) and 36 u16 indices, placed by `nodes`."""
    positions, indices = [], []
    for axis in range(3):
        for side in (0, 1):
            base = len(positions) // 3
            for a, b in ((0, 0), (1, 0), (1, 1), (0, 1)):
                p = [0, 0, 0]
                p[axis], p[(axis + 1) % 3], p[(axis + 2) % 3] = side, a, b
                positions += p
            indices += [base, base + 1, base + 2, base, base + 2, base + 3] if side else [base, base + 2, base + 1, base, base + 3, base + 2]
    data = struct.pack(f"<{len(positions)}f", *positions) + struct.pack(f"<{len(indices)}H", *indices)
    g = triangle_gltf(nodes=nodes, uri="data:application/octet-stream;base64," + base64.b64encode(data).decode())
    g["buffers"][0]["byteLength"] = len(data)
    g["bufferViews"] = [{"buffer": 0, "byteOffset": 0, "byteLength": 288}, {"buffer": 0, "byteOffset": 288, "byteLength": 72}]
    g["accessors"][0].update(count=24, max=[1, 1, 1])
    g["accessors"][1]["count"] = 36
    return g


def glb(gltf_json, binary=b""):
    """A .glb of this JSON (text or dict) and BIN chunk."""
    text = gltf_json if isinstance(gltf_json, str) else json.dumps(gltf_json, separators=(",", ":"))
    j = text.encode()
    j += b" " * (-len(j) % 4)
    binary += b"\0" * (-len(binary) % 4)
    chunks = struct.pack("<II", len(j), 0x4E4F534A) + j
    if binary:
        chunks += struct.pack("<II", len(binary), 0x004E4942) + binary
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


def png(width, height, rng):
    """A PNG whose header says width x height RGBA; its data is a few random bytes (it does not decode)."""
    ihdr = struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)
    chunk = lambda kind, data: struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", bytes(rng.randrange(256) for _ in range(64))) + chunk(b"IEND", b"")


def small_png():
    """A real 2x2 RGBA PNG."""
    raw = b"".join(b"\0" + b"\xff\x00\x00\xff" * 2 for _ in range(2))
    chunk = lambda kind, data: struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 2, 2, 8, 6, 0, 0, 0)) + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")


def jpeg(width, height):
    """A JPEG header (SOI, SOF0) claiming width x height, then nothing that decodes."""
    sof = struct.pack(">BHHB", 8, height, width, 3) + b"\x01\x11\x00\x02\x11\x00\x03\x11\x00"
    return b"\xff\xd8" + b"\xff\xc0" + struct.pack(">H", len(sof) + 2) + sof + b"\xff\xd9"


def bmp(width, height):
    """A BMP header (BITMAPINFOHEADER, 32 bits) claiming width x height, then a few pixels."""
    info = struct.pack("<IiiHHIIiiII", 40, width, height, 1, 32, 0, 0, 2835, 2835, 0, 0)
    return b"BM" + struct.pack("<IHHI", 14 + len(info) + 16, 0, 0, 14 + len(info)) + info + b"\0" * 16


def tga(width, height):
    """A TGA header (true colour, 32 bits) claiming width x height, then a few pixels."""
    return struct.pack("<BBBHHBHHHHBB", 0, 0, 2, 0, 0, 0, 0, 0, width, height, 32, 8) + b"\0" * 16


def webp(width, height):
    """A lossless WebP (VP8L) header claiming width x height (at most 16384 a side)."""
    bits = (width - 1) | (height - 1) << 14 | 1 << 28
    data = b"\x2f" + struct.pack("<I", bits) + b"\0" * 16
    return b"RIFF" + struct.pack("<I", 4 + 8 + len(data)) + b"WEBP" + b"VP8L" + struct.pack("<I", len(data)) + data


def ktx2(width, height):
    """A KTX2 header (80 bytes, one level) claiming width x height, its level past nothing."""
    ident = b"\xabKTX 20\xbb\r\n\x1a\n"
    head = struct.pack("<IIIIIIIII", 0, 1, width, height, 0, 0, 1, 1, 1)  # vkFormat .. supercompression
    index = struct.pack("<IIIIQQ", 0, 0, 0, 0, 0, 0)  # dfd, kvd offsets/lengths; sgd offset/length
    level = struct.pack("<QQQ", 104, 16, 16)
    return ident + head + index + level + b"\0" * 16


def varint(n):
    """A Draco varUI32 (LEB128)."""
    out = b""
    while True:
        out += bytes([(n & 0x7F) | (0x80 if n > 0x7F else 0)])
        n >>= 7
        if not n:
            return out


def draco_glb(method, faces):
    """A .glb whose one primitive is a KHR_draco_mesh_compression stream (bitstream 2.2) whose
    connectivity header claims `faces` faces and as many points, and holds nothing more."""
    head = b"DRACO" + bytes([2, 2, 1, method]) + b"\0\0"
    counts = varint(faces) + varint(faces) if method == 0 else b"\0" + varint(faces) + varint(faces) + b"\0" + varint(faces) + b"\0"
    stream = head + counts + b"\0" * 16
    draco = {"bufferView": 0, "attributes": {"POSITION": 0}}
    return glb({"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_draco_mesh_compression"],
                "extensionsRequired": ["KHR_draco_mesh_compression"],
                "buffers": [{"byteLength": len(stream)}], "bufferViews": [{"buffer": 0, "byteLength": len(stream)}],
                "accessors": [{"componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                              {"componentType": 5125, "count": 3, "type": "SCALAR"}],
                "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1,
                                            "extensions": {"KHR_draco_mesh_compression": draco}}]}],
                "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0}, stream)


def image_glb(kind, payload):
    """A glb with one triangle textured by an embedded image of `kind` (png, ktx2, webp)."""
    g = triangle_gltf()
    g["buffers"] = [{"byteLength": 0}]
    bin_ = TRIANGLE + b"\0\0"
    g["bufferViews"].append({"buffer": 0, "byteOffset": len(bin_), "byteLength": len(payload)})
    bin_ += payload
    g["buffers"][0]["byteLength"] = len(bin_)
    mime = {"png": "image/png", "ktx2": "image/ktx2", "webp": "image/webp"}[kind]
    g["images"] = [{"bufferView": 2, "mimeType": mime}]
    ext = {"ktx2": "KHR_texture_basisu", "webp": "EXT_texture_webp"}.get(kind)
    g["textures"] = [{"extensions": {ext: {"source": 0}}} if ext else {"source": 0}]
    if ext:
        g["extensionsUsed"] = [ext]
    g["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
    g["meshes"][0]["primitives"][0]["material"] = 0
    return glb(g, bin_)


def compressed_glb(kind, payload, count=3, stride=12, mode="ATTRIBUTES", corners=3):
    """A one-triangle glb whose POSITION is compressed: `kind` "meshopt" (its bufferView an
    EXT_meshopt_compression stream of `count` x `stride` bytes in `mode`, over a fallback buffer) or
    "draco" (a KHR_draco_mesh_compression primitive whose indices accessor declares `corners`);
    `payload` is the compressed bytes."""
    g = triangle_gltf()
    bin_ = TRIANGLE + b"\0\0" + payload
    if kind == "meshopt":
        g["buffers"] = [{"byteLength": len(bin_)}, {"byteLength": count * stride, "extensions": {"EXT_meshopt_compression": {"fallback": True}}}]
        g["bufferViews"][0] = {"buffer": 1, "byteOffset": 0, "byteLength": count * stride,
                               "extensions": {"EXT_meshopt_compression": {"buffer": 0, "byteOffset": len(TRIANGLE) + 2, "byteLength": len(payload),
                                                                          "byteStride": stride, "count": count, "mode": mode}}}
        if mode == "ATTRIBUTES" and stride % 4 == 0:
            g["bufferViews"][0]["byteStride"] = stride
        g["accessors"][0]["count"] = count
    else:
        g["buffers"] = [{"byteLength": len(bin_)}]
        g["bufferViews"].append({"buffer": 0, "byteOffset": len(TRIANGLE) + 2, "byteLength": len(payload)})
        del g["accessors"][0]["bufferView"]
        g["accessors"][1]["count"] = corners
        g["meshes"][0]["primitives"][0]["extensions"] = {"KHR_draco_mesh_compression": {"bufferView": 2, "attributes": {"POSITION": 0}}}
    g["extensionsUsed"] = g["extensionsRequired"] = ["EXT_meshopt_compression" if kind == "meshopt" else "KHR_draco_mesh_compression"]
    return glb(g, bin_)


def varint(n):
    out = b""
    while True:
        out += bytes([(n & 0x7F) | (0x80 if n > 0x7F else 0)])
        n >>= 7
        if not n:
            return out


def draco_header(method, faces, points=3):
    """A Draco 2.2 mesh stream's header claiming `faces` triangles (sequential: and `points` points),
    then nothing that decodes."""
    head = b"DRACO" + bytes([2, 2, 1, method]) + struct.pack("<H", 0)
    if method == 0:
        return head + varint(faces) + varint(points) + b"\0" * 8
    return head + b"\0" + varint(3) + varint(faces) + b"\0" + varint(faces) + varint(0) + b"\0" * 8


class Corpus:
    def __init__(self, out):
        self.out = out
        self.rows = []

    def case(self, name, filename, content, outside=False, programs="bake", files=None, links=None, fifos=None, folders=None):
        folder = os.path.join(self.out, "cases", name)
        os.makedirs(folder, exist_ok=True)
        for sub in folders or []:
            os.makedirs(os.path.join(folder, sub), exist_ok=True)
        for rel, data in (files or {}).items():
            with open(os.path.join(folder, rel), "wb") as f:
                f.write(data)
        for rel, target in (links or {}).items():
            os.symlink(target, os.path.join(folder, rel))
        for rel in fifos or []:
            os.mkfifo(os.path.join(folder, rel))
        data = content if isinstance(content, bytes) else (content if isinstance(content, str) else json.dumps(content)).encode()
        with open(os.path.join(folder, filename), "wb") as f:
            f.write(data)
        self.rows.append((name, os.path.join("cases", name, filename), "outside" if outside else "inside", programs))


def chain(n, twice=False):
    nodes = [{"children": [i + 1, i + 1] if twice else [i + 1]} for i in range(n - 1)]
    return nodes + [{"mesh": 0}]


def write(out, seed):
    rng = random.Random(seed)
    os.makedirs(os.path.join(out, "outside"), exist_ok=True)
    outside = os.path.abspath(os.path.join(out, "outside"))
    for name, data in {"secret.bin": TRIANGLE, "secret.png": small_png(),
                       "secret.mtl": b"newmtl m\nKd 1 0 0\nmap_Kd secret.png\n"}.items():
        with open(os.path.join(outside, name), "wb") as f:
            f.write(data)
    c = Corpus(out)
    # --- Depth: JSON nesting past any parser's stack, node chains past any recursion ---
    for depth in (600, 15000, 200000):
        deep = "[" * depth + "]" * depth
        c.case(f"json_depth_{depth}", "a.gltf", json.dumps(triangle_gltf())[:-1] + ',"extras":' + deep + "}", programs="bake,render")
    c.case("json_depth_glb", "a.glb", glb(json.dumps(triangle_gltf())[:-1] + ',"extras":' + "{\"a\":" * 20000 + "1" + "}" * 20000 + "}"),
           programs="bake,render")
    c.case("json_depth_in_node", "a.gltf", json.dumps(triangle_gltf())[:-1] + ',"asset2":' + "[{\"x\":" * 8000 + "0" + "}]" * 8000 + "}")
    c.case("json_depth_unclosed", "a.gltf", '{"asset":' + "[" * 100000)
    for n in (10000, 100000):
        c.case(f"node_chain_{n}", "a.gltf", triangle_gltf(nodes=chain(n)), programs="bake,render")
    # --- Node graphs that are not trees: instances multiply (qf-render's loader too: it walked a
    #     node once per parent, and 24 nodes each naming the next twice made 2^23 meshes) ---
    c.case("node_dag_2_40", "a.gltf", triangle_gltf(nodes=chain(41, twice=True)), programs="bake,render")
    c.case("node_dag_wide", "a.gltf", triangle_gltf(nodes=[{"children": [1] * 4096}, {"children": [2] * 4096}, {"mesh": 0}]), programs="bake,render")
    c.case("node_two_parents", "a.gltf", triangle_gltf(nodes=[{"children": [2]}, {"children": [2]}, {"mesh": 0}], scene_nodes=[0, 1]), programs="bake,render")
    c.case("node_root_twice", "a.gltf", triangle_gltf(scene_nodes=[0] * 1000), programs="bake,render")
    c.case("node_cycle", "a.gltf", triangle_gltf(nodes=[{"children": [1]}, {"children": [0], "mesh": 0}]), programs="bake,render")
    c.case("node_self", "a.gltf", triangle_gltf(nodes=[{"children": [0], "mesh": 0}]), programs="bake,render")
    c.case("node_index_huge", "a.gltf", triangle_gltf(nodes=[{"children": [2 ** 31 + 5]}, {"mesh": 0}]))
    c.case("node_no_scene_cycle", "a.gltf", {k: v for k, v in triangle_gltf(nodes=[{"children": [1]}, {"children": [0], "mesh": 0}]).items()
                                             if k not in ("scene", "scenes")})
    # 10^6 instances of one cube (24 vertices, 12 triangles) as siblings: a tree, but 2.7 GB of mesh.
    c.case("instances_1e6_cubes", "a.gltf", cube_gltf(nodes=[{"children": list(range(1, 1000001))}] + [{"mesh": 0}] * 1000000))
    # --- Counts past their buffers ---
    for count in (2 ** 62, 2 ** 32 + 3, 10 ** 12):
        c.case(f"accessor_count_{count}", "a.gltf", triangle_gltf(count=count))
    big_stride = triangle_gltf()
    big_stride["bufferViews"][0]["byteStride"] = 252
    big_stride["accessors"][0]["count"] = 2 ** 40
    c.case("accessor_stride", "a.gltf", big_stride)
    offset = triangle_gltf()
    offset["accessors"][0]["byteOffset"] = 2 ** 63
    c.case("accessor_offset_2_63", "a.gltf", offset)
    prims = triangle_gltf()
    prims["meshes"][0]["primitives"] = prims["meshes"][0]["primitives"] * 5000
    prims["accessors"][0]["count"] = 2 ** 31
    c.case("primitives_5000_huge", "a.gltf", prims)
    # Draco streams whose headers claim 2^31 - 1 faces: budgeted from the header, before decoding.
    c.case("draco_sequential_2_31", "a.glb", draco_glb(0, 2 ** 31 - 1))
    c.case("draco_edgebreaker_2_31", "a.glb", draco_glb(1, 2 ** 31 - 1))
    c.case("glb_chunk_length", "a.glb", struct.pack("<4sIIII", b"glTF", 2, 2 ** 32 - 1, 2 ** 32 - 8, 0x4E4F534A) + b"{}")
    c.case("glb_truncated", "a.glb", glb(triangle_gltf())[:40])
    # --- Images whose headers claim more than the memory allows ---
    c.case("png_16384_x8", "a.gltf", triangle_gltf(images=[{"uri": "big.png"}] * 8), files={"big.png": png(16384, 16384, rng)})
    c.case("png_2_31", "a.gltf", triangle_gltf(images=[{"uri": "big.png"}]), files={"big.png": png(2 ** 31 - 1, 2 ** 31 - 1, rng)})
    c.case("jpeg_65535", "a.gltf", triangle_gltf(images=[{"uri": "big.jpg"}] * 4), files={"big.jpg": jpeg(65535, 65535)})
    c.case("png_embedded_16384", "a.glb", image_glb("png", png(16384, 16384, rng)), programs="bake,render")
    c.case("webp_16383", "a.glb", image_glb("webp", webp(16384, 16384)), programs="bake,render")
    c.case("ktx2_16384", "a.glb", image_glb("ktx2", ktx2(16384, 16384)), programs="bake,render")
    # --- Compressed geometry (EXT_meshopt_compression, KHR_draco_mesh_compression): cut short,
    # corrupt, or claiming counts past the memory, checked before the decoders allocate ---
    c.case("meshopt_truncated", "a.glb", compressed_glb("meshopt", b"\xa0" + bytes(rng.randrange(256) for _ in range(5))), programs="bake,render")
    c.case("meshopt_noise", "a.glb", compressed_glb("meshopt", b"\xa0" + bytes(rng.randrange(256) for _ in range(64))), programs="bake,render")
    c.case("meshopt_count_2_40", "a.glb", compressed_glb("meshopt", b"\xa0" + b"\0" * 32, count=2 ** 40, stride=16), programs="bake,render")
    c.case("meshopt_count_2_26", "a.glb", compressed_glb("meshopt", b"\xa0" + b"\0" * 32, count=2 ** 26, stride=64), programs="bake,render")
    c.case("meshopt_stride_6", "a.glb", compressed_glb("meshopt", b"\xa0" + b"\0" * 32, stride=6), programs="bake,render")
    c.case("meshopt_triangles_4", "a.glb", compressed_glb("meshopt", b"\xe1" + b"\0" * 32, count=4, stride=2, mode="TRIANGLES"), programs="bake,render")
    # A stream claiming 2^30 triangles with an indices accessor that agrees (the memory check refuses
    # it), and one the accessor contradicts (refused by the count).
    c.case("draco_faces_2_30", "a.glb", compressed_glb("draco", draco_header(1, 2 ** 30 - 1), corners=3 * (2 ** 30 - 1)), programs="bake,render")
    c.case("draco_sequential_2_30", "a.glb", compressed_glb("draco", draco_header(0, 2 ** 30 - 1, 2 ** 31)), programs="bake,render")
    c.case("draco_noise", "a.glb", compressed_glb("draco", b"DRACO" + bytes(rng.randrange(256) for _ in range(64))), programs="bake,render")
    obj_faces = "usemtl m\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n"
    c.case("obj_bmp_16384_x8", "a.obj", "mtllib a.mtl\n" + obj_faces,
           files={"a.mtl": ("newmtl m\n" + "map_Kd big.bmp\n" * 8).encode(), "big.bmp": bmp(16384, 16384)})
    c.case("obj_tga_65535", "a.obj", "mtllib a.mtl\n" + obj_faces, files={"a.mtl": b"newmtl m\nmap_Kd big.tga\n", "big.tga": tga(65535, 65535)})
    c.case("gltf_bmp_16384_x8", "a.gltf", triangle_gltf(images=[{"uri": "big.bmp"}] * 8), files={"big.bmp": bmp(16384, 16384)})
    c.case("obj_png_16384_x8", "a.obj", "mtllib a.mtl\n" + obj_faces,
           files={"a.mtl": ("newmtl m\n" + "map_Kd big.png\n" * 8).encode(), "big.png": png(16384, 16384, rng)})
    # --- References outside the asset's folder (each names a file that exists) ---
    rel = os.path.relpath(outside, os.path.join(out, "cases", "x"))
    for name, uri in {"uri_dotdot": rel + "/secret.bin", "uri_pct_dotdot": rel.replace("..", "%2e%2e") + "/secret.bin",
                      "uri_pct_slash": rel.replace("/", "%2F") + "%2Fsecret.bin", "uri_pct_nul": "%2e%2e%00/" + rel + "/secret.bin", "uri_absolute": outside + "/secret.bin",
                      "uri_file_scheme": "file://" + outside + "/secret.bin", "uri_etc_passwd": "/etc/passwd",
                      "uri_home": "~/../../" + outside + "/secret.bin", "uri_variable": "$HOME/../.." + outside + "/secret.bin",
                      "uri_dev_zero": "/dev/zero", "uri_proc": "/proc/self/environ"}.items():
        # qf-render's loader confines references as the baker does (runtime_gl/loader.cpp): the
        # ways out tinygltf would follow (the others it never opens: its own rule or no such file).
        render = name in ("uri_dotdot", "uri_pct_dotdot", "uri_absolute", "uri_etc_passwd")
        c.case(name, "a.gltf", triangle_gltf(uri=uri), outside=True, programs="bake,render" if render else "bake")
    c.case("uri_symlink", "a.gltf", triangle_gltf(uri="link.bin"), outside=True, links={"link.bin": outside + "/secret.bin"},
           programs="bake,render")
    c.case("uri_symlink_relative", "a.gltf", triangle_gltf(uri="link.bin"), outside=True, links={"link.bin": rel + "/secret.bin"})
    c.case("uri_symlink_folder", "a.gltf", triangle_gltf(uri="up/secret.bin"), outside=True, links={"up": outside}, programs="bake,render")
    c.case("uri_symlink_dotdot", "a.gltf", triangle_gltf(uri="sub/up/" + rel + "/secret.bin"), outside=True, folders=["sub"],
           links={"sub/up": ".."})
    c.case("uri_symlink_dangling", "a.gltf", triangle_gltf(uri="link.bin"), outside=True, links={"link.bin": outside + "/absent.bin"})
    c.case("image_dotdot", "a.gltf", triangle_gltf(images=[{"uri": rel + "/secret.png"}]), outside=True, programs="bake,render")
    c.case("image_symlink", "a.gltf", triangle_gltf(images=[{"uri": "t.png"}]), outside=True, links={"t.png": outside + "/secret.png"},
           programs="bake,render")
    c.case("obj_mtllib_dotdot", "a.obj", "mtllib " + rel + "/secret.mtl\n" + obj_faces, outside=True)
    c.case("obj_mtllib_absolute", "a.obj", "mtllib " + outside + "/secret.mtl\n" + obj_faces, outside=True)
    c.case("obj_mtllib_backslash", "a.obj", "mtllib " + rel.replace("/", "\\") + "\\secret.mtl\n" + obj_faces, outside=True)
    c.case("obj_map_kd_dotdot", "a.obj", "mtllib a.mtl\n" + obj_faces, outside=True,
           files={"a.mtl": ("newmtl m\nmap_Kd -s 1 1 1 " + rel + "/secret.png\n").encode()})
    c.case("obj_map_kd_symlink", "a.obj", "mtllib a.mtl\n" + obj_faces, outside=True,
           files={"a.mtl": b"newmtl m\nmap_Kd t.png\n"}, links={"t.png": outside + "/secret.png"})
    c.case("obj_mtllib_symlink", "a.obj", "mtllib a.mtl\n" + obj_faces, outside=True, links={"a.mtl": outside + "/secret.mtl"})
    # --- Not regular files ---
    c.case("uri_fifo", "a.gltf", triangle_gltf(uri="fifo.bin"), fifos=["fifo.bin"], programs="bake,render")
    c.case("uri_folder", "a.gltf", triangle_gltf(uri="sub"), folders=["sub"], programs="bake,render")
    c.case("uri_dot", "a.gltf", triangle_gltf(uri="."))
    c.case("uri_empty_name", "a.gltf", triangle_gltf(uri="sub/"), folders=["sub"])
    c.case("image_fifo", "a.gltf", triangle_gltf(images=[{"uri": "fifo.png"}]), fifos=["fifo.png"], programs="bake,render")
    c.case("obj_mtllib_fifo", "a.obj", "mtllib fifo.mtl\n" + obj_faces, fifos=["fifo.mtl"])
    c.case("obj_mtllib_folder", "a.obj", "mtllib sub\n" + obj_faces, folders=["sub"])
    c.case("obj_map_kd_fifo", "a.obj", "mtllib a.mtl\n" + obj_faces, files={"a.mtl": b"newmtl m\nmap_Kd fifo.png\n"}, fifos=["fifo.png"])
    # --- Random bytes where JSON is expected, seeded ---
    for k in range(3):
        noise = bytes(rng.choice(b'{}[]":,0123456789abcdefnulltrue \n') for _ in range(4096))
        c.case(f"json_noise_{k}", "a.gltf", noise)
    with open(os.path.join(out, "cases.tsv"), "w") as f:
        for row in c.rows:
            f.write("\t".join(row) + "\n")
    return len(c.rows)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("out")
    p.add_argument("--seed", type=int, default=50)
    a = p.parse_args()
    n = write(a.out, a.seed)
    print(f"{n} cases in {a.out}")


if __name__ == "__main__":
    main()
