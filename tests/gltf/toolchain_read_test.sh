#!/usr/bin/env bash
# What the glTF toolchain writes, read by our own programs (issue 51 item 2). The fixtures of
# tests/data/toolchain/ go through glTF-Transform 4.5.1 (tools/gltf-transform-qf, with its config):
# `meshopt` (EXT_meshopt_compression + KHR_mesh_quantization, the dequantization in the node),
# `quantize` and `draco` (KHR_draco_mesh_compression). Then:
#  - qf-diff: the meshopt level draws exactly as the `quantize` one (its decoding is exact); each
#    original against its compressed file has the same quads, within quantization (section 2);
#  - qf-render draws the meshopt level, the Draco LOD file and gltfpack -cc's level as it draws their
#    originals (section 3);
#  - qf-bake reads a meshopt + quantized source asset with WebP textures and one with KTX2 textures
#    (a --textures ktx2 level of the octahedron through `meshopt`) as their originals, and bakes them;
#  - a file requiring a made-up extension is refused by qf-render and qf-bake (exit 1) and qf-diff
#    (exit 2, its unreadable input), naming it; a meshopt stream cut short and a Draco stream whose count disagrees are refused
#    naming the file and what broke (exit 1, no crash).
# usage: toolchain_read_test.sh QF_BAKE QF_RENDER QF_DIFF PACKAGE_DIR DATA_DIR
set -u
bake=$1 render=$2 diff=$3 pkg=$4 data=$5
source "$(dirname "$0")/../cli/test_lib.sh"
gt="$pkg/node_modules/.bin/gltf-transform"
[[ -x $gt ]] || { echo "tools/gltf-transform-qf not installed (scripts/install-deps.sh)"; exit 1; }
command -v oiiotool >/dev/null || { echo "oiiotool missing (scripts/install-deps.sh)"; exit 1; }
cfg=(--config "$pkg/gltf-transform.config.mjs")
transform() { "$gt" "$@" "${cfg[@]}" >"$work/gt.log" 2>&1 && ok || bad "gltf-transform $*: $(tail -2 "$work/gt.log")"; }

# 1. Through the toolchain.
transform meshopt "$data/octahedron_png_L6.glb" "$work/level_meshopt.glb"
transform quantize "$data/octahedron_png_L6.glb" "$work/level_quantize.glb"
transform meshopt "$data/octahedron_webp_L6.glb" "$work/webp_meshopt.glb"
transform meshopt "$data/sphere_points.glb" "$work/points_meshopt.glb"
transform draco "$data/sphere_lods.glb" "$work/lods_draco.glb"
# gltfpack 1.3.0 -cc (meshopt, its own quantization; it drops QF_impostor_level, so the file is a
# plain textured mesh to our readers).
"$pkg/node_modules/.bin/gltfpack" -i "$data/octahedron_png_L6.glb" -o "$work/level_gltfpack.glb" -cc >"$work/gt.log" 2>&1 && ok ||
  bad "gltfpack -cc: $(tail -2 "$work/gt.log")"
python3 - "$work" <<'PY' && ok || bad "the toolchain's files do not use the extensions this test is about"
import json, struct, sys
def doc(path):
    b = open(path, "rb").read()
    return json.loads(b[20:20 + struct.unpack_from("<I", b, 12)[0]])
for name, ext in (("level_meshopt", "EXT_meshopt_compression"), ("level_quantize", "KHR_mesh_quantization"),
                  ("webp_meshopt", "EXT_meshopt_compression"), ("points_meshopt", "EXT_meshopt_compression"),
                  ("lods_draco", "KHR_draco_mesh_compression")):
    assert ext in doc(f"{sys.argv[1]}/{name}.glb").get("extensionsRequired", []), (name, ext)
PY

# 2. qf-diff. The meshopt level decodes to exactly what `quantize` wrote (meshopt = the same
# quantization + compression): identical draws, qf-diff's default thresholds. Each original against
# its compressed file: the same quads by domain, centres within 1e-4 of the diagonal, normals
# within 0.1 degree; the draws within what quantization costs (measured on these fixtures at
# 128 px, 6 views: PSNR min 40.6 dB levels, 37.3 dB points, 44.0 dB Draco LODs; changed pixels
# up to 6%, the 12-bit texture coordinates moving texel boundaries): PSNR >= 36 dB, <= 10% changed.
diff_check() {  # diff_check OLD NEW [qf-diff options]
  local a=$1 b=$2 summary rc
  shift 2
  "$diff" "$a" "$b" --json "$@" >"$work/d.json" 2>"$work/err"
  rc=$?
  summary=$(python3 - "$work/d.json" <<'PY'
import json, sys
f = json.load(open(sys.argv[1]))["files"][0]
if f["status"] == "identical":
    print("identical bytes"); sys.exit(0)
st, im = f.get("structure", {}), f.get("images", {})
geometry = "no quads"
if "quads" in st:
    assert st["quads_added"] == st["quads_removed"] == 0 and st["quads"][0] == st["quads"][1], st
    assert st["center_shift_max_of_diagonal"] <= 1e-4 and st["normal_angle_max_degrees"] <= 0.1, st
    geometry = f'{st["quads"][1]} quads, centre shift max {st["center_shift_max_of_diagonal"]:.1e} of the diagonal, normals within {st["normal_angle_max_degrees"]:.3f} deg'
else:
    assert st["old"] == st["new"], st
print(f'{geometry}; PSNR min {im["psnr_min"]} dB, changed pixels max {im["changed_share_max"]}')
PY
  ) && [[ $rc -eq 0 ]] && { ok; echo "ok   qf-diff $(basename "$a") -> $(basename "$b"): $summary"; } ||
    bad "qf-diff $(basename "$a") -> $(basename "$b") (exit $rc): $summary $(tail -2 "$work/err")"
}
diff_check "$work/level_quantize.glb" "$work/level_meshopt.glb"
loose=(--min-psnr 36 --max-changed 0.1)
diff_check "$data/octahedron_png_L6.glb" "$work/level_meshopt.glb" "${loose[@]}"
diff_check "$data/octahedron_webp_L6.glb" "$work/webp_meshopt.glb" "${loose[@]}"
diff_check "$data/sphere_points.glb" "$work/points_meshopt.glb" "${loose[@]}"
diff_check "$data/sphere_lods.glb" "$work/lods_draco.glb" "${loose[@]}"

# 3. qf-render at 512 px, its default view: the compressed files drawn as their originals are
# (measured: the meshopt level 50.3 dB by the default method, 39.8 dB by the engine method; the
# Draco LODs 55.8 dB; gltfpack's level 41.1 dB by the engine method; oiiotool's PSNR). Bars: 45 dB
# (default), 36 dB (engine).
for case in "octahedron_png_L6 level_meshopt default" "octahedron_png_L6 level_meshopt engine" "sphere_lods lods_draco default" \
            "octahedron_png_L6 level_gltfpack engine"; do
  set -- $case
  args=(); bar=45
  [[ $3 == engine ]] && args=(-m engine) bar=36
  "$render" render "$data/$1.glb" -o "$work/a.png" "${args[@]}" 2>"$work/err" && "$render" render "$work/$2.glb" -o "$work/b.png" "${args[@]}" 2>>"$work/err" ||
    { bad "qf-render $2 $3: $(tail -2 "$work/err")"; continue; }
  psnr=$(oiiotool "$work/a.png" "$work/b.png" --diff 2>&1 | sed -n 's/.*Peak SNR = \([0-9.inf]*\).*/\1/p')
  [[ -z $psnr ]] && psnr=inf  # identical images print no PSNR
  python3 -c "import sys; sys.exit(0 if sys.argv[1] == 'inf' or float(sys.argv[1]) >= float(sys.argv[2]) else 1)" "$psnr" "$bar" &&
    { ok; echo "ok   qf-render $2 ($3 method): PSNR $psnr dB against $1"; } || bad "qf-render $2 $3: PSNR $psnr dB < $bar"
done

# The Khronos sample 2CylinderEngine compressed with Draco (a .gltf with an external .bin, from
# Debian's assimp-testmodels when installed) against its uncompressed .glb, by the engine method
# (measured 44.0 dB).
models=${QF_ASSIMP_MODELS:-/usr/share/assimp/models}/glTF2
if [[ -f $models/draco/2CylinderEngine.gltf ]]; then
  "$render" render "$models/2CylinderEngine-glTF-Binary/2CylinderEngine.glb" -o "$work/a.png" -m engine 2>"$work/err" &&
    "$render" render "$models/draco/2CylinderEngine.gltf" -o "$work/b.png" -m engine 2>>"$work/err" || bad "qf-render 2CylinderEngine (Draco): $(tail -2 "$work/err")"
  psnr=$(oiiotool "$work/a.png" "$work/b.png" --diff 2>&1 | sed -n 's/.*Peak SNR = \([0-9.inf]*\).*/\1/p')
  python3 -c "import sys; sys.exit(0 if sys.argv[1] in ('', 'inf') or float(sys.argv[1]) >= 40 else 1)" "$psnr" &&
    { ok; echo "ok   qf-render draco/2CylinderEngine.gltf (engine method): PSNR ${psnr:-inf} dB against the .glb"; } || bad "2CylinderEngine (Draco): PSNR $psnr dB < 40"
fi

# 4. qf-bake: compressed source assets (meshopt + quantized, with WebP or KTX2 textures: the
# octahedron's level with WebP, and a 7-quad level baked with --textures ktx2, ktx2/) read as their
# originals (qf-bake info: the same vertices, triangles, materials and texture sizes, bounds within
# 1e-3 of the diagonal), then baked.
transform meshopt "$data/ktx2/octahedron_ktx2_L9.glb" "$work/ktx2_meshopt.glb"
for pair in "$data/octahedron_webp_L6.glb webp_meshopt" "$data/ktx2/octahedron_ktx2_L9.glb ktx2_meshopt"; do
  set -- $pair
  "$bake" info "$1" --json >"$work/a.json" 2>"$work/err" && "$bake" info "$work/$2.glb" --json >"$work/b.json" 2>>"$work/err" ||
    { bad "qf-bake info $2: $(tail -2 "$work/err")"; continue; }
  "$bake" "$work/$2.glb" -o "$work/bake_$2" --primitives 30 --ldi 48 --no-measure --mesh-lods none -q 2>"$work/err" || bad "qf-bake $2: $(tail -2 "$work/err")"
  summary=$(python3 - "$work/a.json" "$work/b.json" "$work/bake_$2/manifest.json" <<'PY'
import json, sys
a, b, m = (json.load(open(f)) for f in sys.argv[1:4])
for key in ("vertices", "triangles", "materials", "textures", "attributes"):
    assert a[key] == b[key], (key, a[key], b[key])
d = a["bounds"]["diagonal"]
shift = max(abs(x - y) for k in ("min", "max") for x, y in zip(a["bounds"][k], b["bounds"][k])) / d
assert shift <= 1e-3, shift
quads = sum(l["primitives"] for l in m["levels"])
assert quads > 0
print(f'{b["triangles"]} triangles, {b["textures"]} texture(s), bounds within {shift:.1e} of the diagonal; baked to {quads} quads')
PY
  ) && { ok; echo "ok   qf-bake reads and bakes $2.glb: $summary"; } || bad "qf-bake $2: $summary"
done

# 5. Refusals: a made-up required extension, a meshopt stream cut short, a Draco count that disagrees.
python3 - "$data/octahedron_png_L6.glb" "$work/level_meshopt.glb" "$work/lods_draco.glb" "$work" <<'PY' || bad "making the refused files"
import json, struct, sys
def parts(path):
    b = open(path, "rb").read()
    n = struct.unpack_from("<I", b, 12)[0]
    return json.loads(b[20:20 + n]), b[20 + n:]
def write(path, doc, rest):
    j = json.dumps(doc).encode()
    j += b" " * (-len(j) % 4)
    body = struct.pack("<II", len(j), 0x4E4F534A) + j + rest
    open(path, "wb").write(struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body)
work = sys.argv[4]
doc, rest = parts(sys.argv[1])
doc["extensionsUsed"] = doc.get("extensionsUsed", []) + ["QF_made_up_extension"]
doc["extensionsRequired"] = doc.get("extensionsRequired", []) + ["QF_made_up_extension"]
write(f"{work}/made_up.glb", doc, rest)
doc, rest = parts(sys.argv[2])  # the TRIANGLES stream of the indices cut to 5 bytes
for v in doc["bufferViews"]:
    e = v.get("extensions", {}).get("EXT_meshopt_compression")
    if e and e["mode"] == "TRIANGLES":
        e["byteLength"] = 5
write(f"{work}/meshopt_cut.glb", doc, rest)
doc, rest = parts(sys.argv[3])  # the first Draco primitive's indices accessor says 3 corners more
p = doc["meshes"][0]["primitives"][0]
doc["accessors"][p["indices"]]["count"] += 3
write(f"{work}/draco_count.glb", doc, rest)
PY
refused() {  # refused NAME EXIT EXPECTED_TEXT COMMAND...
  local name=$1 want=$2 text=$3
  shift 3
  "$@" >"$work/out" 2>"$work/err"
  local rc=$?
  [[ $rc -eq $want ]] && grep -q -- "$text" "$work/err" && ok || bad "$name: exit $rc, expected $want naming '$text': $(tail -2 "$work/err")"
}
refused "qf-render, made-up extension" 1 "made_up.glb.*QF_made_up_extension" "$render" render "$work/made_up.glb" -o "$work/x.png"
refused "qf-bake, made-up extension" 1 "made_up.glb.*QF_made_up_extension" "$bake" "$work/made_up.glb" -o "$work/x" --no-measure -q
# qf-diff's unreadable input is exit 2 (its 1 means "different").
refused "qf-diff, made-up extension" 2 "made_up.glb.*QF_made_up_extension" "$diff" "$data/octahedron_png_L6.glb" "$work/made_up.glb"
for program in render bake; do
  cmd=("$render" render "$work/meshopt_cut.glb" -o "$work/x.png"); [[ $program == bake ]] && cmd=("$bake" "$work/meshopt_cut.glb" -o "$work/x" --no-measure -q)
  refused "qf-$program, meshopt cut short" 1 "meshopt_cut.glb.*EXT_meshopt_compression.*does not decode" "${cmd[@]}"
  cmd=("$render" render "$work/draco_count.glb" -o "$work/x.png"); [[ $program == bake ]] && cmd=("$bake" "$work/draco_count.glb" -o "$work/x" --no-measure -q)
  refused "qf-$program, Draco count" 1 "draco_count.glb.*KHR_draco_mesh_compression.*claims" "${cmd[@]}"
done
finish toolchain_read
