#!/usr/bin/env bash
# Honest screen sizes (baker/measure/measure.h, screen_sizes.h): every bake measures its files on
# screen beside the input as drawn; each file's max_screen_pixels follows the hold rule from its own
# figures, and those figures are qf-render eval's at the same size; a lattice of beams and a bare
# tree of twigs thinner than a pixel claim no size at which they cover under half of the truth
# (checked by qf-render eval);
# without a GL driver the bake still succeeds with geometric sizes and a warning; --no-measure skips
# it and options that need it are refused.
# usage: measure_test.sh QF_BAKE QF_RENDER
set -u
bake=$1 render=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

# 1. The rule, checked from the manifest's own figures (a generated tree: alpha-tested leaves):
#    every file holds, beside the input as drawn, exactly where the manifest says, and its
#    max_screen_pixels is the largest of those sizes.
"$bake" generate tree --leaves 300 -o "$work/tree.glb" -q || fail "generate tree"
"$bake" "$work/tree.glb" -o "$work/tree" --primitives 300,30 --no-mesh-lods -q || fail "bake the tree"
cat >"$work/rule.py" <<'PY'
import json, math, sys
m = json.load(open(sys.argv[1]))
r = m["measuring"]
assert r["method"] == "engine" and r["views"] == 4 and r["sizes"][-1] == 16 and r["sizes"][0] in (256, 512, 1024), r
assert all(a == 2 * b for a, b in zip(r["sizes"], r["sizes"][1:])) and 256 in r["sizes"], r["sizes"]
h, asset = r["hold"], r["asset"]
assert [e["pixels"] for e in asset] == r["sizes"]
def holds(f, a):
    if any(f[k] is None or a[k] is None for k in ("psnr", "soft_iou", "coverage")): return False
    floor = max(h["min_coverage"], min(a["coverage"], 1) - h["coverage_drop"])
    return f["coverage"] >= floor - 1e-6 and f["psnr"] >= a["psnr"] - h["psnr_drop"] - 1e-6 and f["soft_iou"] >= a["soft_iou"] - h["soft_iou_drop"] - 1e-6
files = list(m["levels"]) + list(m.get("mesh_lods", {}).get("levels", []))
for l in files:
    f = l["measured"]
    assert [e["pixels"] for e in f] == r["sizes"]
    held = [holds(x, a) for x, a in zip(f, asset)]
    assert held == [x["holds"] for x in f], (l["file"], held, f)
    want = next((x["pixels"] for x in f if holds(x, asset[f.index(x)])), 0)
    assert l["max_screen_pixels"] == want, (l["file"], l["max_screen_pixels"], want)
    assert l["holds_from_pixels"] <= l["max_screen_pixels"], l
    # Never a claimed size at which it covers under half the truth or falls 3 dB below the asset.
    if want:
        at = next(x for x in f if x["pixels"] == want)
        a = asset[r["sizes"].index(want)]
        assert at["coverage"] >= 0.5 and at["psnr"] >= a["psnr"] - 3 - 1e-6, (l["file"], at, a)
print(", ".join(f'{l["file"]} {l.get("primitives", l.get("triangles"))}: {l["geometric_max_screen_pixels"]} -> {l["max_screen_pixels"]} px (from {l["holds_from_pixels"]})' for l in files))
PY
python3 "$work/rule.py" "$work/tree/manifest.json" || fail "the tree's max_screen_pixels do not follow the measured rule"

# 1'. Thin parts: a lattice tower of beams and a bare tree whose twigs are thinner than a pixel at
#     small sizes. A level that draws nothing there must not claim the size: each level's claimed
#     size is checked again by qf-render eval, independently of the bake's figures: it covers at
#     least half of the truth there.
thin() {  # thin NAME GENERATE-ARGS...: bake it, check the rule and every level's claimed size
  local name=$1; shift
  "$bake" generate "$@" -o "$work/$name.glb" -q || fail "generate $name"
  "$bake" "$work/$name.glb" -o "$work/$name" --primitives 300,100,30 -q || fail "bake $name"
  python3 "$work/rule.py" "$work/$name/manifest.json" || fail "$name's sizes do not follow the rule"
  while read -r file size; do
    [[ $size == 0 ]] && continue
    "$render" eval "$work/$name.glb" "$work/$name/$file" --size "$size" --views 4 --truth 2 -m engine -o "$work/le.json" 2>/dev/null || fail "eval $file"
    python3 -c "import json,sys; e = json.load(open(sys.argv[1]))['mean']['engine']; c = e['coverage']; print(sys.argv[2], sys.argv[3], 'px: coverage', c); sys.exit(c is None or c < 0.5)" \
      "$work/le.json" "$file" "$size" || fail "$file claims $size px, where it covers under half of the truth"
  done < <(python3 -c "import json,sys; [print(l['file'], l['max_screen_pixels']) for l in json.load(open(sys.argv[1]))['levels']]" "$work/$name/manifest.json")
}
thin lattice lattice --seed 3
thin bare bare-tree --seed 2

# 2. The figures are qf-render eval's: the same views, the candidate drawn at the size, the truth
#    drawn at 512 px (2 x 256, the largest size every file is drawn at) and box-filtered down (eval
#    --truth 512/S); a size above 256 px has its own truth at 2 x.
finest=$(python3 -c "import json,sys; print(min(json.load(open(sys.argv[1]))['levels'], key=lambda l: l['level'])['file'])" "$work/tree/manifest.json")
"$render" eval "$work/tree.glb" "$work/tree/$finest" --size 32 --views 4 --truth 16 -m engine -o "$work/eval.json" 2>/dev/null || fail "eval"
python3 - "$work/tree/manifest.json" "$work/eval.json" "$finest" <<'PY' || fail "the bake's figure differs from qf-render eval's"
import json, sys
m, e, name = json.load(open(sys.argv[1])), json.load(open(sys.argv[2])), sys.argv[3]
level = next(l for l in m["levels"] if l["file"] == name)
at = next(x for x in level["measured"] if x["pixels"] == 32)
ev = e["mean"]["engine"]
assert abs(at["psnr"] - ev["psnr"]) <= 0.1 and abs(at["iou"] - ev["iou"]) <= 0.005 and abs(at["coverage"] - ev["coverage"]) <= 0.005, (at, ev)
print(f"bake {at['psnr']} dB IoU {at['iou']}, eval {ev['psnr']:.2f} dB IoU {ev['iou']:.3f} at 32 px")
PY

# 3. The same bytes on a rebake, at another thread count.
"$bake" "$work/tree.glb" -o "$work/tree1" --primitives 300,30 --no-mesh-lods --threads 1 -q || fail "rebake"
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
for opt in "--measure-views 2" "--hold-psnr 2"; do
  "$bake" "$work/oct.ply" -o "$work/bad" --no-measure $opt -q 2>"$work/err"
  [[ $? == 2 ]] && grep -q -- "--no-measure" "$work/err" || fail "--no-measure $opt was not refused: $(cat "$work/err")"
done
echo "measure: all checks passed"
