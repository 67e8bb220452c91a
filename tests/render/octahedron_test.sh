#!/usr/bin/env bash
# The paper's figure 1 as an engine draws it (issue 15's octahedron target): for random samplings
# of 8k, 16k and 64k points other than the bundled sample, `--merge --primitives 8`
# bakes 8 quads whose engine-method picture (8 views, 256 px) is within 1 dB of the metric's floor
# (a second sampling of the same surface, scored the same way) and covers the silhouette with
# IoU >= 0.97. The 64k sampling is the hard case: its splats are small, so alpha edges that step
# with the texels (no edge ramp on point sets) scored 1.25 dB below the floor there.
# usage: octahedron_test.sh QF_BAKE QF_RENDER
set -u
bake=$1 render=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail=0
for case in 8000:4 16000:5 64000:1; do
  n=${case%:*} seed=${case#*:} dir="$work/o$n"
  "$bake" generate octahedron -n "$n" --seed "$seed" -o "$dir.ply" -q &&
    "$bake" generate octahedron -n "$n" --seed $((seed + 100)) -o "$dir-floor.ply" -q &&
    "$bake" "$dir.ply" -o "$dir" --merge --primitives 8 --no-cache -q || { echo "FAIL: $n points: bake"; fail=1; continue; }
  glb=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['levels'][0]['file'])" "$dir/manifest.json")
  "$render" eval "$dir.ply" "$dir/$glb" --views 8 -o "$dir-eval.json" 2>/dev/null &&
    "$render" eval "$dir.ply" "$dir-floor.ply" --views 8 -o "$dir-floor.json" 2>/dev/null || { echo "FAIL: $n points: eval"; fail=1; continue; }
  python3 - "$n" "$dir/manifest.json" "$dir-eval.json" "$dir-floor.json" <<'PY' || fail=1
import json, sys
n, manifest, level, floor = sys.argv[1], *(json.load(open(p)) for p in sys.argv[2:])
quads = manifest["levels"][0]["primitives"]
e, f = level["mean"]["engine"], floor["mean"]["engine"]
print(f"{n} points: {quads} quads, engine {e['psnr']:.2f} dB IoU {e['iou']:.4f}; floor {f['psnr']:.2f} dB IoU {f['iou']:.4f}")
ok = quads == 8 and e["psnr"] >= f["psnr"] - 1 and e["iou"] >= 0.97
if not ok: print(f"FAIL: {n} points: want 8 quads, PSNR >= floor - 1 dB, IoU >= 0.97")
sys.exit(0 if ok else 1)
PY
done
exit $fail
