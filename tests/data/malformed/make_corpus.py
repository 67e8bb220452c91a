#!/usr/bin/env python3
"""Writes the malformed-input corpus and EXPECTED.tsv (file, error code).

Run from anywhere: python3 tests/data/malformed/make_corpus.py [path/to/shared]
The files are committed; this script documents how each one was made and regenerates them.
Every file must make every reader fail with the listed code and exit code 1, without a crash.
"""
import os
import struct
import sys

here = os.path.dirname(os.path.abspath(__file__))
shared = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "..", "..", "..", "shared")
pyr_qs = open(os.path.join(shared, "data", "qsplat", "pyr.qs"), "rb").read()
assert len(pyr_qs) == 68

expected = []


def put(name, data, code):
    if isinstance(data, str):
        data = data.encode()
    with open(os.path.join(here, name), "wb") as f:
        f.write(data)
    expected.append((name, code))


ASCII_HEAD = "ply\nformat ascii 1.0\nelement vertex {n}\nproperty float x\nproperty float y\nproperty float z\n"
GOOD_BODY = "0 0 0\n1 0 0\n0 1 0\n"


def binary_vertices(points, fmt="<"):
    head = ("ply\nformat binary_%s_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
            "property float z\nend_header\n") % ("little" if fmt == "<" else "big", len(points))
    return head.encode() + b"".join(struct.pack(fmt + "fff", *p) for p in points)


# --- PLY header -------------------------------------------------------------------------------
put("empty.ply", b"", "ply.header.magic")
put("not_ply.ply", "hello world\n", "ply.header.magic")
put("garbage.ply", bytes((i * 73 + 41) % 256 for i in range(512)), "ply.header.magic")
put("header_truncated.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n", "ply.header.truncated")
put("unknown_format.ply", "ply\nformat binary_middle_endian 1.0\nelement vertex 0\nproperty float x\nend_header\n",
    "ply.header.format")
put("bad_version.ply", "ply\nformat ascii 2.0\nelement vertex 0\nproperty float x\nend_header\n", "ply.header.format")
put("missing_format.ply", "ply\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 3\n",
    "ply.header.format")
put("unsupported_type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n1\n",
    "ply.header.property_type")
put("list_float_count.ply", ASCII_HEAD.format(n=3) + "element face 1\nproperty list float int vertex_indices\nend_header\n"
    + GOOD_BODY + "3 0 1 2\n", "ply.header.property_type")
put("unknown_keyword.ply", "ply\nformat ascii 1.0\nelemnt vertex 3\nend_header\n", "ply.header.syntax")
put("property_before_element.ply", "ply\nformat ascii 1.0\nproperty float x\nelement vertex 0\nend_header\n",
    "ply.header.syntax")
put("negative_count.ply", "ply\nformat ascii 1.0\nelement vertex -5\nproperty float x\nend_header\n", "ply.header.syntax")
put("no_xyz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n1 2\n",
    "ply.header.no_xyz")
put("no_vertex.ply", "ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n",
    "ply.header.no_vertex")

# --- PLY body ---------------------------------------------------------------------------------
pts = [(float(i), float(i % 3), float(i % 5)) for i in range(10)]
put("body_truncated_binary.ply", binary_vertices(pts)[:-7].replace(b"vertex 10", b"vertex 10"), "ply.body.truncated")
put("count_lies_binary.ply", binary_vertices(pts).replace(b"vertex 10", b"vertex 99"), "ply.body.truncated")
put("count_too_small_binary.ply", binary_vertices(pts).replace(b"vertex 10", b"vertex 5"), "ply.body.trailing")
put("body_truncated_ascii.ply", ASCII_HEAD.format(n=5) + "end_header\n" + GOOD_BODY, "ply.body.truncated")
put("ascii_trailing.ply", ASCII_HEAD.format(n=2) + "end_header\n" + GOOD_BODY, "ply.body.trailing")
put("bad_number.ply", ASCII_HEAD.format(n=3) + "end_header\n0 0 0\n1.0 abc 2.0\n0 1 0\n", "ply.body.bad_number")
put("nan_coordinate.ply", ASCII_HEAD.format(n=3) + "end_header\n0 0 0\nnan 0 0\n0 1 0\n", "ply.body.nonfinite")
put("inf_coordinate_binary.ply", binary_vertices([(0, 0, 0), (1, float("inf"), 0), (0, 1, 0)]), "ply.body.nonfinite")
put("inf_coordinate_big_endian.ply", binary_vertices([(0, 0, 0), (1, 0, float("-inf"))], ">"), "ply.body.nonfinite")
face_head = ASCII_HEAD.format(n=4) + "element face 1\nproperty list uchar int vertex_indices\nend_header\n" \
    + GOOD_BODY + "1 1 1\n"
put("face_index_out_of_range.ply", face_head + "3 0 1 7\n", "ply.body.face_index")
put("face_index_negative.ply", face_head + "3 0 -1 2\n", "ply.body.face_index")
put("face_two_corners.ply", face_head + "2 0 1\n", "ply.body.list_length")
bin_face_head = ("ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                 "property float z\nelement face 1\nproperty list char int vertex_indices\nend_header\n").encode()
verts = b"".join(struct.pack("<fff", *p) for p in [(0, 0, 0), (1, 0, 0), (0, 1, 0)])
put("list_length_negative.ply", bin_face_head + verts + struct.pack("<b", -1), "ply.body.list_length")
put("list_length_past_end.ply", bin_face_head + verts + struct.pack("<biii", 100, 0, 1, 2), "ply.body.truncated")
put("list_length_huge.ply", bin_face_head.replace(b"list char int", b"list uint int") + verts
    + struct.pack("<Iiii", 0xFFFFFFF0, 0, 1, 2), "ply.body.list_length")
put("bad_radius.ply", "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
    "property float radius\nend_header\n0 0 0 0.1\n1 0 0 -0.5\n", "ply.body.bad_radius")

# Issue 18 (fuzzing): an element without properties and a count of 2^63-1 (130 bytes) must not make
# the ascii reader loop over the count; values outside their declared type's range are errors.
# (The element is skipped at once, then the body's one value too many is reported.)
put("empty_element_huge_count.ply", "ply\nformat ascii 1.0\nelement pad 9223372036854775807\n"
    + ASCII_HEAD.format(n=3)[len("ply\nformat ascii 1.0\n"):] + "end_header\n" + GOOD_BODY + "9\n", "ply.body.trailing")
put("uchar_color_300.ply", ASCII_HEAD.format(n=2) + "property uchar red\nproperty uchar green\nproperty uchar blue\n"
    "end_header\n0 0 0 10 20 30\n1 0 0 300 0 0\n", "ply.body.out_of_range")
put("uchar_color_negative.ply", ASCII_HEAD.format(n=2) + "property uchar red\nproperty uchar green\nproperty uchar blue\n"
    "end_header\n0 0 0 10 20 30\n1 0 0 -1 0 0\n", "ply.body.out_of_range")
put("face_index_int64_max.ply", face_head + "3 0 1 9223372036854775807\n", "ply.body.out_of_range")
put("face_index_beyond_int64.ply", face_head + "3 0 1 99999999999999999999\n", "ply.body.out_of_range")
put("float_beyond_float_range.ply", ASCII_HEAD.format(n=2) + "end_header\n0 0 0\n1e39 0 0\n", "ply.body.out_of_range")
put("double_radius_beyond_float.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
    "property float z\nproperty double radius\nend_header\n0 0 0 1e300\n", "ply.body.bad_radius")

# --- QSplat -------------------------------------------------------------------------------------
def patch(data, offset, new):
    return data[:offset] + new + data[offset + len(new):]


put("empty.qs", b"", "qsplat.magic")
put("bad_magic.qs", patch(pyr_qs, 0, b"QSplot"), "qsplat.magic")
put("bad_version.qs", patch(pyr_qs, 6, b"12"), "qsplat.version")
put("short_header.qs", pyr_qs[:14], "qsplat.truncated")
put("fragment_length_not_multiple_of_4.qs", patch(pyr_qs, 8, struct.pack(">i", 66)), "qsplat.fragment_length")
put("fragment_length_past_end.qs", patch(pyr_qs, 8, struct.pack(">i", 72)), "qsplat.fragment_length")
put("fragment_length_zero.qs", patch(pyr_qs, 8, struct.pack(">i", 0)), "qsplat.fragment_length")
put("fragment_length_little_endian.qs", patch(pyr_qs, 8, struct.pack("<i", 68)), "qsplat.fragment_length")
put("trailing_garbage.qs", pyr_qs + b"\x00\x01\x02", "qsplat.magic")
put("unknown_options.qs", patch(pyr_qs, 16, struct.pack(">I", 8)), "qsplat.options")
put("root_nan.qs", patch(pyr_qs, 32, struct.pack(">f", float("nan"))), "qsplat.root")
put("root_child_count.qs", patch(pyr_qs, 36, struct.pack(">i", 9)), "qsplat.root")
put("bad_child_offset.qs", patch(pyr_qs, 40, struct.pack(">i", 4000)), "qsplat.child_offset")
put("backward_child_offset.qs", patch(pyr_qs, 40, struct.pack(">i", -8)), "qsplat.child_offset")
# Record 1 of the root group (byte 44) gets sphere index 8191 (0xFFF8 | its flags), as a broken writer emits.
put("invalid_sphere_index.qs", patch(pyr_qs, 44, bytes([0xFF, 0xF8 | (pyr_qs[45] & 7)])), "qsplat.sphere_index")
put("leaf_count_too_high.qs", patch(pyr_qs, 12, struct.pack(">i", 6)), "qsplat.leaf_count")
put("leaf_count_too_low.qs", patch(pyr_qs, 12, struct.pack(">i", 3)), "qsplat.leaf_count")
put("leaf_count_huge.qs", patch(pyr_qs, 12, struct.pack(">i", 1 << 30)), "qsplat.leaf_count")
# A 52-byte fragment whose root claims 4 leaf children: 16 bytes of records, only 12 in the fragment.
overrun = patch(patch(patch(pyr_qs[:52], 8, struct.pack(">i", 52)), 12, struct.pack(">i", 4)), 36, struct.pack(">i", 4))
put("tree_overruns_fragment.qs", overrun, "qsplat.truncated")
put("leaf_with_grandchildren_flag.qs", patch(pyr_qs, 49, bytes([pyr_qs[49] | 4])), "qsplat.node")

# --- OFF / OBJ / XYZ / PWN ---------------------------------------------------------------------------
put("bad_header.off", "FOO\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "off.header")
put("bad_counts.off", "OFF\n3 x 0\n", "off.counts")
put("counts_lie.off", "OFF\n8 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "off.truncated")
put("truncated.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n", "off.truncated")
put("face_index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "off.face_index")
put("face_two_corners.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "off.face")
put("nan.off", "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "off.nonfinite")
put("binary.off", b"OFF\n3 1 0\n\x00\x01\x02\n", "off.binary")
put("face_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "obj.face_index")
put("face_index_zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "obj.face")
put("short_vertex.obj", "v 0 0 0\nv 1 2\n", "obj.vertex")
put("columns.xyz", "0 0 0\n1 0 0\n0 1 0 5\n", "xyz.columns")
put("mixed_columns.xyz", "0 0 0\n1 0 0 0 0 1\n", "xyz.columns")
put("bad_number.xyz", "0 0 0\n1 zero 0\n", "xyz.bad_number")
put("nan.xyz", "0 0 0\n1 0 inf\n", "xyz.nonfinite")
put("binary.xyz", b"\x00\x00\x80\x3f\x00\x00\x00\x40", "xyz.binary")
put("no_normals.pwn", "0 0 0\n1 0 0\n", "xyz.columns")
# Issue 18: empty text files (no data pointer at all) and files without a single vertex.
put("empty.off", b"", "off.empty")
put("empty.obj", b"", "obj.empty")
put("empty.xyz", b"", "xyz.empty")
put("empty.pwn", b"", "xyz.empty")
put("comments_only.obj", "# nothing but a comment\nmtllib none.mtl\n", "obj.no_vertices")
put("comments_only.xyz", "# nothing but a comment\n\n", "xyz.no_points")

# Issue 35: LAS and LAZ. A small LAS 1.2 file of point format 3 written here; LAZ cases patch the
# committed tests/data/las files (written by qf-bench-las, as their README says).
def las_file(points=4, fmt=3, minor=2, count=None, vlrs=0, scale=0.01, record_length=None):
    rl = record_length if record_length is not None else {0: 20, 1: 28, 2: 26, 3: 34}[fmt]
    head = bytearray(227)
    head[0:4] = b"LASF"
    head[24:26] = bytes([1, minor])
    struct.pack_into("<HIIBHI", head, 94, 227, 227, vlrs, fmt, rl, points if count is None else count)
    struct.pack_into("<3d3d", head, 131, scale, scale, scale, 0, 0, 0)
    struct.pack_into("<6d", head, 179, 1, 0, 1, 0, 1, 0)
    body = b"".join(struct.pack("<3iHBBbBH", i, i, 0, 0, 9, 2, 0, 0, 0).ljust(rl, b"\0")[:rl] for i in range(points))
    return bytes(head) + body


las_dir = os.path.join(here, "..", "las")
f3_laz = open(os.path.join(las_dir, "points_f3.laz"), "rb").read()
f7_laz = open(os.path.join(las_dir, "points_f7.laz"), "rb").read()
put("empty.las", b"", "las.header.magic")
put("not_las.las", "hello world\n", "las.header.magic")
put("header_truncated.las", las_file()[:100], "las.header.truncated")
put("bad_version.las", patch(las_file(), 24, b"\x02\x00"), "las.header.version")
put("bad_point_format.las", patch(las_file(), 104, b"\x0c"), "las.header.format")
put("short_record.las", patch(las_file(), 105, struct.pack("<H", 10)), "las.header.record_length")
put("zero_scale.las", las_file(scale=0.0), "las.header.scale")
put("no_points.las", las_file(points=0), "las.empty")
put("count_lies.las", las_file(count=1000), "las.body.truncated")
put("vlr_past_points.las", las_file(vlrs=1), "las.vlr")
put("compressed_without_vlr.laz", patch(las_file(), 104, b"\x83"), "laz.vlr")
# points_f3.laz: header 227, LASzip VLR 54 + 52 bytes (3 items from byte 315), points at 333.
put("chunk_table_missing.laz", patch(f3_laz, 333, struct.pack("<q", -1)), "laz.chunk_table")
put("chunk_table_cut.laz", f3_laz[:len(f3_laz) - 6], "laz.chunk_table")
put("item_version_1.laz", patch(f3_laz, 319, struct.pack("<H", 1)), "laz.unsupported")
# points_f7.laz: header 375, VLR 54 + 46, points at 475, first chunk at 483: its raw point (36
# bytes) and count (4), then the layers' byte counts from 523.
put("layer_sizes_past_chunk.laz", patch(f7_laz, 523, struct.pack("<I", 0x7FFFFFFF)), "laz.chunk")

with open(os.path.join(here, "EXPECTED.tsv"), "w") as f:
    f.write("# file\terror code (every file: exit code 1, no output file)\n")
    for name, code in expected:
        f.write("%s\t%s\n" % (name, code))
print("wrote %d files" % len(expected))
