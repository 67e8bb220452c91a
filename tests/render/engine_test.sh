#!/usr/bin/env bash
# The engine method is engine-true: baked files of every kind rendered by a web engine in headless
# Chromium (ENGINE three: three.js r187, scripts/three-render; babylon: Babylon.js 9.31,
# scripts/babylon-render; both through scripts/web-render) and by `qf-render eval`'s engine method
# from the same 8 cameras with the same lights score the same against the reference: PSNR within
# 1 dB and silhouette IoU within 0.005; the two renders of each file match each other (PSNR >= 25 dB
# between them, IoU >= 0.99; 1-pixel points rasterise a little differently); and the engine's
# loader says nothing (no warning, no error) about any file.
# The files: an impostor level of the bundled octahedron, a point set; one of a generated sphere
# mesh, whose alpha is encoded; both ramped at their edges (pipeline/bake.h use_surface_edges); the
# simplified mesh LOD, a vertex-clustering LOD with thick lines, the same compressed with Draco and
# the point impostor of the sphere; an impostor level of a generated bush, foliage whose quads are
# drawn from its alpha-masked leaves (also with WebP textures, and in three.js with KTX2 ones); the material plate and its level, whose roughness, metallic
# and emission vary (metallicRoughness, ORM and emissive textures); a torus's combined STEM_lods.glb (MSFT_lod) of its levels and
# that of its recommended chain. Neither engine switches MSFT_lod levels by screen coverage: each
# shows one level of a combined file, and the test holds it to that level's own file and checks
# that only the finest level's node (impostor_LOD0, chain_LOD0) was drawn or is left in the scene.
# usage: engine_test.sh ENGINE QF_BAKE QF_RENDER SOURCE_DIR
set -u
engine=$1 bake=$2 render=$3 src=$4
dir="$src/scripts/$engine-render"
case $engine in
  three) package=three name="three.js" ;;
  babylon) package=@babylonjs/loaders name="Babylon.js" ;;
  *) echo "FAIL: unknown engine $engine"; exit 1 ;;
esac
[[ -f "$dir/node_modules/$package/package.json" && -f "$dir/node_modules/playwright-core/package.json" ]] ||
  { echo "FAIL: $name / playwright-core not installed: run scripts/install-deps.sh"; exit 1; }
[[ -x "${QF_CHROMIUM:-/usr/bin/chromium}" ]] || { echo "FAIL: no Chromium at ${QF_CHROMIUM:-/usr/bin/chromium}: run scripts/install-deps.sh"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

# --no-measure: measuring sets the levels' screen sizes, which only the LOD switch reads (lod_test.sh);
# the files draw the same. The chain needs the measurements.
"$bake" "$src/samples/octahedron.ply" -o "$work/oct" --primitives 100 --no-measure -q || fail "bake octahedron"
"$bake" generate sphere --mesh --subdivisions 8 -o "$work/sphere.ply" -q || fail "generate sphere"
"$bake" "$work/sphere.ply" -o "$work/sphere" --primitives 30 --ldi 96 --points --no-measure -q || fail "bake sphere"
"$bake" cluster "$work/sphere.ply" -o "$work/cluster" --cells 0.6 --draco -q || fail "cluster sphere"
"$bake" generate bush --leaves 600 --seed 2 -o "$work/bush.glb" -q || fail "generate bush"
"$bake" "$work/bush.glb" -o "$work/bush" --primitives 100 --ldi 128 --mesh-lods none --no-measure -q || fail "bake bush"
# three.js also draws the bush's level with KTX2 textures (KTX2Loader; Babylon.js fetches its KTX2
# decoder from a CDN, so it is not asked to): within 0.5 dB of the PNG level's PSNR (issue 32).
[[ $engine == three ]] && { "$bake" "$work/bush.glb" -o "$work/bushk" --primitives 100 --ldi 128 --mesh-lods none --no-measure --textures ktx2 -q ||
  fail "bake bush ktx2"; }
# Both engines draw it with WebP textures (EXT_texture_webp, decoded by the browser without setup):
# within 0.5 dB of the PNG level's PSNR too (issue 32).
"$bake" "$work/bush.glb" -o "$work/bushw" --primitives 100 --ldi 128 --mesh-lods none --no-measure --textures webp -q || fail "bake bush webp"
"$bake" generate plate -o "$work/plate.glb" -q || fail "generate plate"
"$bake" "$work/plate.glb" -o "$work/plate" --primitives 30 --ldi 96 --mesh-lods none --no-measure --cheap-triangles 0 -q || fail "bake plate"
"$bake" generate torus -o "$work/torus.ply" -q || fail "generate torus"
"$bake" "$work/torus.ply" -o "$work/torus" --lod-file --no-measure -q || fail "bake torus"
"$bake" "$work/torus.ply" -o "$work/chain" --lod-file --measure-views 2 -q || fail "bake torus chain"
finest=$(python3 -c 'import json, sys; print(max(json.load(open(sys.argv[1]))["levels"], key=lambda l: l["primitives"])["file"])' "$work/torus/manifest.json")
chain0=$(python3 -c 'import json, sys; print(next(e["file"] for e in json.load(open(sys.argv[1]))["recommended_chain"]["chain"] if e["kind"] != "asset"))' "$work/chain/manifest.json")
# REFERENCE|FILE the engine loads|the file the engine method draws for it (default: the same)|the
# node the engine must draw (default: any)
cases=("$src/samples/octahedron.ply|$(ls "$work"/oct/octahedron_L*.glb | head -n 1)"
       "$work/sphere.ply|$(ls "$work"/sphere/sphere_L*.glb | head -n 1)"
       "$work/sphere.ply|$work/sphere/sphere_S1.glb"
       "$work/sphere.ply|$work/cluster/sphere_C0.glb"
       "$work/sphere.ply|$work/cluster/sphere_C0.draco.glb|$work/cluster/sphere_C0.glb"
       "$work/sphere.ply|$work/sphere/sphere_points.glb"
       "$work/bush.glb|$(ls "$work"/bush/bush_L*.glb | head -n 1)"
       "$work/plate.glb|$work/plate.glb"
       "$work/plate.glb|$(ls "$work"/plate/plate_L*.glb | head -n 1)"
       "$work/torus.ply|$work/torus/torus_lods.glb|$work/torus/$finest|impostor_LOD0"
       "$work/torus.ply|$work/chain/torus_lods.glb|$work/chain/$chain0|chain_LOD0")
bush_png=6
[[ $engine == three ]] && cases+=("$work/bush.glb|$(ls "$work"/bushk/bush_L*.glb | head -n 1)") && bush_ktx2=$((${#cases[@]} - 1))
cases+=("$work/bush.glb|$(ls "$work"/bushw/bush_L*.glb | head -n 1)") && bush_webp=$((${#cases[@]} - 1))

# The cameras frame the reference: one eval per reference writes them.
declare -A cams
jobs="["
for i in "${!cases[@]}"; do
  IFS='|' read -r ref baked shown node <<<"${cases[$i]}"
  if [[ -z "${cams[$ref]:-}" ]]; then
    cams[$ref]="$work/cams_$i.json"
    "$render" eval "$ref" "${shown:-$baked}" --views 8 --size 128 -m engine --no-engine --truth 1 --cameras "${cams[$ref]}" -o "$work/unused.json" 2>/dev/null ||
      fail "eval --cameras $ref"
  fi
  jobs+="$([[ $i -gt 0 ]] && echo ,){\"file\":\"$baked\",\"cameras\":\"${cams[$ref]}\",\"out\":\"$work/out_$i\"}"
done
echo "$jobs]" >"$work/jobs.json"
node "$dir/render.mjs" --jobs "$work/jobs.json" || fail "$name renders"

status=0
for i in "${!cases[@]}"; do
  IFS='|' read -r ref baked shown node <<<"${cases[$i]}"
  # An asset drawn against itself is scored against its truth (8 x, box-filtered), where the two
  # engines' renders of it can differ; as drawn at the size, qf-render's would be identical (99 dB).
  truth=1; [[ "$ref" == "${shown:-$baked}" ]] && truth=8
  "$render" eval "$ref" "${shown:-$baked}" --views 8 --size 128 -m engine --truth $truth --external "$work/out_$i" -o "$work/eval_$i.json" 2>/dev/null ||
    fail "eval --external $baked"
  python3 - "$work/eval_$i.json" "$work/out_$i/load.json" "$name" "$(basename "$(dirname "$baked")")/$(basename "$baked")" "${shown:+$(basename "$shown")}" "$node" <<'PY' || status=1
import json, sys
r = json.load(open(sys.argv[1]))["mean"]
load = json.load(open(sys.argv[2]))
name, file, shown, node = sys.argv[3:7]
e, x, a = r["engine"], r["external"], r["engine_vs_external"]
dp, di = abs(e["psnr"] - x["psnr"]), abs(e["iou"] - x["iou"])
# A KTX2 level (issue 32): three.js transcodes it to the GPU's block format (BC7 in SwiftShader),
# qf-render to RGBA8; BC7's alpha from ETC1S differs by a few levels, which flips the thin leaves'
# pixels at the cutoff (qf-render vs three.js 24 dB, IoU 0.95 on the bush; 29 dB, 0.986 with UASTC
# colour): both renders still score alike against the reference, which is what is held.
pair = "bushk/" in file or (a["psnr"] >= 25 and a["iou"] >= 0.99)
problems = [] if dp <= 1.0 and di <= 0.005 and pair else ["renders differ"]
if load["warnings"]: problems.append(f"loader says: {load['warnings']}")
if not load["drawn"]: problems.append("nothing drawn")
# A combined file: only its finest level drawn, and no other level kept in the scene to switch to.
if node and any(not d.startswith(node) for d in load["drawn"] + load["loaded"]):
    problems.append(f"drew {load['drawn']} of {load['loaded']}, not only {node}")
print(f"{'FAIL' if problems else 'ok  '} {file}{f' (shows {shown})' if shown else ''}: qf-render engine PSNR {e['psnr']:.3f} dB IoU {e['iou']:.4f}; "
      f"{name} {x['psnr']:.3f} dB IoU {x['iou']:.4f} (|d| {dp:.3f} dB, {di:.4f}); "
      f"qf-render vs {name} {a['psnr']:.1f} dB IoU {a['iou']:.4f}" + "".join(f"; {p}" for p in problems))
sys.exit(1 if problems else 0)
PY
done
# The compressed levels as the engine draws them, against its PNG level: within 0.5 dB.
for kind in ktx2 webp; do
  var=bush_$kind
  [[ -n "${!var:-}" ]] || continue
  python3 - "$work/eval_$bush_png.json" "$work/eval_${!var}.json" "$name" "$kind" <<'PY' || status=1
import json, sys
png, other = (json.load(open(f))["mean"]["external"] for f in sys.argv[1:3])
name, kind = sys.argv[3:5]
d = other["psnr"] - png["psnr"]
ok = abs(d) <= 0.5
print(f"{'ok  ' if ok else 'FAIL'} {name} {kind.upper()} level {other['psnr']:.3f} dB IoU {other['iou']:.4f} vs its PNG level {png['psnr']:.3f} dB IoU {png['iou']:.4f} ({d:+.3f} dB)")
sys.exit(0 if ok else 1)
PY
done
[[ $status == 0 ]] && echo "engine method agrees with $name on ${#cases[@]} files"
exit $status
