#!/usr/bin/env bash
# The engine method is engine-true: baked files of every kind (an impostor level of the bundled
# octahedron, a point set; one of a generated sphere mesh, whose alpha is encoded; both ramped at
# their edges, pipeline/bake.h use_surface_edges; the simplified mesh LOD, a vertex-clustering LOD with thick lines and the point
# impostor of a generated sphere mesh; an impostor level of a generated bush, foliage whose quads
# are drawn from its alpha-masked leaves) rendered by three.js
# r187 in headless Chromium (scripts/three-render) and by `qf-render eval`'s engine method from the
# same 8 cameras with the same lights score the same against the reference: PSNR within 1 dB and
# silhouette IoU within 0.005; and the two renders of each file match each other (PSNR >= 25 dB
# between them, IoU >= 0.99; 1-pixel points rasterise a little differently).
# usage: three_test.sh QF_BAKE QF_RENDER SOURCE_DIR
set -u
bake=$1 render=$2 src=$3
three="$src/scripts/three-render"
[[ -f "$three/node_modules/three/package.json" && -f "$three/node_modules/playwright-core/package.json" ]] ||
  { echo "FAIL: three.js / playwright-core not installed: run scripts/install-deps.sh"; exit 1; }
[[ -x "${QF_CHROMIUM:-/usr/bin/chromium}" ]] || { echo "FAIL: no Chromium at ${QF_CHROMIUM:-/usr/bin/chromium}: run scripts/install-deps.sh"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

"$bake" "$src/samples/octahedron.ply" -o "$work/oct" --primitives 100 -q || fail "bake octahedron"
"$bake" generate sphere --mesh --subdivisions 8 -o "$work/sphere.ply" -q || fail "generate sphere"
"$bake" "$work/sphere.ply" -o "$work/sphere" --primitives 30 --ldi 96 -q || fail "bake sphere"
"$bake" cluster "$work/sphere.ply" -o "$work/cluster" --cells 0.6 -q || fail "cluster sphere"
"$bake" generate bush --leaves 600 --seed 2 -o "$work/bush.glb" -q || fail "generate bush"
"$bake" "$work/bush.glb" -o "$work/bush" --primitives 100 --ldi 128 --mesh-lods none -q || fail "bake bush"
level=$(ls "$work"/oct/octahedron_L*.glb | head -n 1)
mesh_level=$(ls "$work"/sphere/sphere_L*.glb | head -n 1)
cases=("$src/samples/octahedron.ply|$level" "$work/sphere.ply|$mesh_level" "$work/sphere.ply|$work/sphere/sphere_S1.glb"
       "$work/sphere.ply|$work/cluster/sphere_C0.glb"
       "$work/sphere.ply|$work/sphere/sphere_points.glb" "$work/bush.glb|$(ls "$work"/bush/bush_L*.glb | head -n 1)")

jobs="["
for i in "${!cases[@]}"; do
  ref=${cases[$i]%%|*} baked=${cases[$i]#*|}
  "$render" eval "$ref" "$baked" --views 8 --size 128 --no-engine --cameras "$work/cams_$i.json" -o "$work/unused.json" 2>/dev/null ||
    fail "eval --cameras $baked"
  jobs+="$([[ $i -gt 0 ]] && echo ,){\"file\":\"$baked\",\"cameras\":\"$work/cams_$i.json\",\"out\":\"$work/three_$i\"}"
done
echo "$jobs]" >"$work/jobs.json"
node "$three/render.mjs" --jobs "$work/jobs.json" || fail "three.js renders"

status=0
for i in "${!cases[@]}"; do
  ref=${cases[$i]%%|*} baked=${cases[$i]#*|}
  "$render" eval "$ref" "$baked" --views 8 --size 128 --external "$work/three_$i" -o "$work/eval_$i.json" 2>/dev/null ||
    fail "eval --external $baked"
  python3 - "$work/eval_$i.json" "$(basename "$baked")" <<'PY' || status=1
import json, sys
r = json.load(open(sys.argv[1]))["mean"]
e, x, a = r["engine"], r["external"], r["engine_vs_external"]
dp, di = abs(e["psnr"] - x["psnr"]), abs(e["iou"] - x["iou"])
ok = dp <= 1.0 and di <= 0.005 and a["psnr"] >= 25 and a["iou"] >= 0.99
print(f"{'ok  ' if ok else 'FAIL'} {sys.argv[2]}: qf-render engine PSNR {e['psnr']:.3f} dB IoU {e['iou']:.4f}; "
      f"three.js {x['psnr']:.3f} dB IoU {x['iou']:.4f} (|d| {dp:.3f} dB, {di:.4f}); "
      f"qf-render vs three.js {a['psnr']:.1f} dB IoU {a['iou']:.4f}")
sys.exit(0 if ok else 1)
PY
done
[[ $status == 0 ]] && echo "engine method agrees with three.js on ${#cases[@]} files"
exit $status
