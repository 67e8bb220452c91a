#!/usr/bin/env bash
# Blender (Debian 12's blender 3.4.1, background mode, its bundled glTF importer) opens every kind
# of file quasiflat writes, and shows an impostor level as the engine method draws it.
# Import (tests/render/blender_check.py import): every .glb of a measured bake of a generated sphere
# mesh (impostor levels, edge-collapse mesh LODs, the point impostor, STEM_lods.glb of the
# recommended chain: chain_LOD0..n), of an unmeasured one (STEM_lods.glb of every level:
# impostor_LOD0..n), a vertex-clustering LOD, arrives with no error or warning: one object per node
# under the node's name (the `_LODn` suffixes), the triangle and point counts, MASK as blend_method
# CLIP at the file's alphaCutoff, doubleSided as backface culling off, the base colour texture on the
# Principled BSDF's Base Color (its alpha on Alpha), the normal texture through a Normal Map node,
# COLOR_0 as a colour attribute, node extras as custom properties. The KTX2 level (KHR_texture_basisu),
# the WebP level (EXT_texture_webp: Blender 3.4's importer does not list it, so a file that requires
# it is refused, though Blender itself reads WebP images) and the Draco copy of the clustering LOD
# must be refused with an error naming what Blender 3.4 lacks (or import and pass the same checks,
# should a later Blender decode them).
# Render: EEVEE draws the sphere's finest level from `qf-render eval`'s 8 cameras at 128 px with the
# engine method's lights; `qf-render eval --external` scores it: within 1 dB PSNR and 0.005 IoU of the
# engine method against the reference (the web engines' bound), and against the engine method's own
# render >= 28 dB PSNR, IoU >= 0.99 (measured 30.9 dB, 0.9967; Cycles, which ignores the alpha clip
# and blends the cut-out texels, gives 24.2 dB and IoU 0.974 at 16 samples: the IoU bound fails it).
# usage: blender_test.sh QF_BAKE QF_RENDER SOURCE_DIR
set -u
bake=$1 render=$2 src=$3
blender=${QF_BLENDER:-blender}
command -v "$blender" >/dev/null ||
  { echo "SKIP: no Blender ($blender) on PATH: run scripts/install-deps.sh (Debian's blender)"; exit 77; }
check=$src/tests/render/blender_check.py
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
start=$SECONDS
# Blender in background mode: no window system; EEVEE gets OpenGL from surfaceless EGL.
run_blender() { env -u DISPLAY "$blender" -b --factory-startup --python-exit-code 1 -P "$check" -- "$@"; }

"$bake" generate sphere --mesh --subdivisions 8 -o "$work/sphere.ply" -q || fail "generate sphere"
"$bake" "$work/sphere.ply" -o "$work/chain" --primitives 30,100 --ldi 96 --lod-file --points --hold-psnr 10 -q || fail "bake sphere (measured)"
"$bake" "$work/sphere.ply" -o "$work/levels" --primitives 30,100 --ldi 96 --mesh-lods none --lod-file --no-measure -q ||
  fail "bake sphere (levels)"
"$bake" "$work/sphere.ply" -o "$work/ktx2" --primitives 30 --ldi 96 --mesh-lods none --no-measure --textures ktx2 -q ||
  fail "bake sphere (ktx2)"
"$bake" "$work/sphere.ply" -o "$work/webp" --primitives 30 --ldi 96 --mesh-lods none --no-measure --textures webp -q ||
  fail "bake sphere (webp)"
"$bake" cluster "$work/sphere.ply" -o "$work/cluster" --cells 0.6 --draco -q || fail "cluster sphere"

# The cases: every .glb the bakes wrote; the combined files with the node names their manifest implies.
python3 - "$work" >"$work/cases.json" <<'PY' || fail "cases"
import glob, json, os, sys
work = sys.argv[1]
def parts(bake):
    return json.load(open(os.path.join(work, bake, "manifest.json")))["lod_file"]["parts"]
cases = []
for path in sorted(glob.glob(os.path.join(work, "*", "*.glb"))):
    bake, name = os.path.basename(os.path.dirname(path)), os.path.basename(path)
    case = {"file": path}
    if name.endswith("_lods.glb"):
        prefix = "chain" if bake == "chain" else "impostor"
        case["nodes"] = [f"{prefix}_LOD{i}" for i in range(len(parts(bake)))]
    if bake in ("ktx2", "webp") and "_L" in name:
        case["expect"] = bake
    if name.endswith(".draco.glb"):
        case["expect"] = "draco"
    cases.append(case)
kinds = {"impostor level": "_L", "mesh LOD": "_S", "point impostor": "_points", "clustering LOD": "_C0.glb",
         "levels' _lods.glb": "levels/", "chain's _lods.glb": "chain/sphere_lods", "KTX2 level": "ktx2/sphere_L", "WebP level": "webp/sphere_L",
         "Draco": ".draco.glb"}
missing = [k for k, s in kinds.items() if not any(s in c["file"] for c in cases)]
if missing:
    sys.exit(f"the bakes wrote no {missing}")
json.dump(cases, sys.stdout, indent=1)
PY
# Blender prints the importer's refusals (tracebacks) on stderr, apart from the checks' lines.
run_blender import "$work/cases.json" >"$work/import.log" 2>"$work/import.err"
import_status=$?
grep -E '^(ok  |FAIL|   [-!] |note|blender import)' "$work/import.log"
[[ $import_status == 0 ]] || { tail -n 20 "$work/import.err"; fail "Blender import checks (exit $import_status)"; }

# One level drawn by EEVEE and scored as the web engines' renders are.
level=$work/chain/$(python3 -c 'import json, sys; print(max(json.load(open(sys.argv[1]))["levels"], key=lambda l: l["primitives"])["file"])' \
  "$work/chain/manifest.json") || fail "the finest level in the manifest"
"$render" eval "$work/sphere.ply" "$level" --views 8 --size 128 -m engine --no-engine --truth 1 --cameras "$work/cams.json" \
  -o "$work/unused.json" 2>/dev/null || fail "eval --cameras"
run_blender render "$level" "$work/cams.json" "$work/out" eevee 1 >"$work/render.log" 2>&1 ||
  { tail -n 20 "$work/render.log"; fail "Blender render"; }
"$render" eval "$work/sphere.ply" "$level" --views 8 --size 128 -m engine --truth 1 --external "$work/out" -o "$work/eval.json" \
  2>/dev/null || fail "eval --external"
python3 - "$work/eval.json" "$(basename "$level")" <<'PY' || fail "Blender's render of $(basename "$level")"
import json, sys
r = json.load(open(sys.argv[1]))["mean"]
e, x, a = r["engine"], r["external"], r["engine_vs_external"]
dp, di = abs(e["psnr"] - x["psnr"]), abs(e["iou"] - x["iou"])
ok = dp <= 1.0 and di <= 0.005 and a["psnr"] >= 28.0 and a["iou"] >= 0.99
print(f"{'ok  ' if ok else 'FAIL'} {sys.argv[2]} in EEVEE: qf-render engine PSNR {e['psnr']:.3f} dB IoU {e['iou']:.4f}; "
      f"Blender {x['psnr']:.3f} dB IoU {x['iou']:.4f} (|d| {dp:.3f} dB, {di:.4f}; limits 1 dB, 0.005); "
      f"qf-render vs Blender {a['psnr']:.2f} dB IoU {a['iou']:.4f} (limits 28 dB, 0.99)")
sys.exit(0 if ok else 1)
PY
echo "Blender imports every kind of output as expected and draws the level as the engine method does ($((SECONDS - start)) s)"
