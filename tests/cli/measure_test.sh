#!/usr/bin/env bash
# Honest screen sizes (tools/measure.h, pipeline/screen_sizes.h): every bake measures its impostor
# levels on screen; each level's max_screen_pixels follows the rule from its own figures, and those
# figures are qf-render eval's at the same size; a foliage asset's finest level holds far above its
# geometric size; without a GL driver the bake still succeeds with geometric sizes and a warning;
# --no-measure skips it and options that need it are refused.
# usage: measure_test.sh QF_BAKE QF_RENDER
set -u
bake=$1 render=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

# 1. The rule, checked from the manifest's own figures (a generated tree: alpha-tested leaves).
"$bake" generate tree --leaves 300 -o "$work/tree.glb" -q || fail "generate tree"
"$bake" "$work/tree.glb" -o "$work/tree" --primitives 300,30 --no-mesh-lods --no-points -q || fail "bake the tree"
python3 - "$work/tree/manifest.json" <<'PY' || fail "the levels' max_screen_pixels do not follow the measured rule"
import json, sys
m = json.load(open(sys.argv[1]))
r = m["measuring"]
assert r["method"] == "engine" and r["sizes"] == [256, 128, 64, 32, 16] and r["views"] == 4, r
levels = sorted(m["levels"], key=lambda l: l["level"])  # finest first
honest = []
for l in levels:
    f = l["measured"]
    assert [e["pixels"] for e in f] == r["sizes"]
    best = max(range(len(f)), key=lambda i: (f[i]["psnr"], -i))
    holds = lambda i: f[i]["psnr"] >= f[best]["psnr"] - r["psnr_drop"] - 1e-9 and f[i]["iou"] >= f[best]["iou"] - r["iou_drop"] - 1e-9
    first = best
    while first > 0 and holds(first - 1): first -= 1
    v = f[first]["pixels"]
    if first == 0: v = max(v, l["geometric_max_screen_pixels"])
    while honest and v >= honest[-1] and v >= 1: v /= 2
    honest.append(v)
    assert l["max_screen_pixels"] == int(v), (l["file"], l["max_screen_pixels"], v, f)
print("tree: " + ", ".join(f'{l["primitives"]} quads {l["geometric_max_screen_pixels"]} -> {l["max_screen_pixels"]} px' for l in levels))
# Foliage keeps its look above its geometric size (mipmaps do not eat it there).
assert levels[0]["max_screen_pixels"] > levels[0]["geometric_max_screen_pixels"], levels[0]
PY

# 2. The figures are qf-render eval's: the same views, the candidate drawn at the size, the truth
#    drawn at 512 px (2 x 256) and box-filtered down (eval --truth 512/S).
finest=$(python3 -c "import json,sys; print(min(json.load(open(sys.argv[1]))['levels'], key=lambda l: l['level'])['file'])" "$work/tree/manifest.json")
"$render" eval "$work/tree.glb" "$work/tree/$finest" --size 32 --views 4 --truth 16 -m engine -o "$work/eval.json" 2>/dev/null || fail "eval"
python3 - "$work/tree/manifest.json" "$work/eval.json" "$finest" <<'PY' || fail "the bake's figure differs from qf-render eval's"
import json, sys
m, e, name = json.load(open(sys.argv[1])), json.load(open(sys.argv[2])), sys.argv[3]
level = next(l for l in m["levels"] if l["file"] == name)
at = next(x for x in level["measured"] if x["pixels"] == 32)
ev = e["mean"]["engine"]
assert abs(at["psnr"] - ev["psnr"]) <= 0.1 and abs(at["iou"] - ev["iou"]) <= 0.005, (at, ev)
print(f"bake {at['psnr']} dB IoU {at['iou']}, eval {ev['psnr']:.2f} dB IoU {ev['iou']:.3f} at 32 px")
PY

# 3. The same bytes on a rebake, at another thread count.
"$bake" "$work/tree.glb" -o "$work/tree1" --primitives 300,30 --no-mesh-lods --no-points --threads 1 -q || fail "rebake"
cmp "$work/tree/manifest.json" "$work/tree1/manifest.json" || fail "a rebake's measurements differ"

# 4. No GL driver (no EGL vendor library): the bake succeeds, geometric sizes, a warning.
"$bake" generate octahedron -n 4000 -o "$work/oct.ply" -q || fail "generate"
__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json "$bake" "$work/oct.ply" -o "$work/nogl" --primitives 100 2>"$work/err" \
  || fail "a bake without a GL driver failed: $(cat "$work/err")"
grep -q "not measured" "$work/err" || fail "no warning without a GL driver: $(cat "$work/err")"
python3 -c "import json,sys; m = json.load(open(sys.argv[1])); sys.exit('measuring' in m or 'recommended_chain' in m or any('measured' in l for l in m['levels']))" \
  "$work/nogl/manifest.json" || fail "measurements without a GL driver"

# 5. --no-measure: geometric sizes, no figures; options that need measuring are refused.
"$bake" "$work/oct.ply" -o "$work/plain" --primitives 100 --no-measure -q || fail "--no-measure"
python3 -c "import json,sys; m = json.load(open(sys.argv[1])); sys.exit('measuring' in m or 'geometric_max_screen_pixels' in m['levels'][0])" \
  "$work/plain/manifest.json" || fail "--no-measure measured"
for opt in "--measure-views 2" "--chain-psnr 20"; do
  "$bake" "$work/oct.ply" -o "$work/bad" --no-measure $opt -q 2>"$work/err"
  [[ $? == 2 ]] && grep -q -- "--no-measure" "$work/err" || fail "--no-measure $opt was not refused: $(cat "$work/err")"
done
echo "measure: all checks passed"
