#!/usr/bin/env bash
# The recommended chain (made by every bake unless --no-chain, baker/measure/chain.h): every candidate of
# a bake and the input itself measured at every size; nearest first the input itself, then per
# band the smallest file that holds there beside the input as drawn (else the input, else the best
# trade of PSNR against bytes with the reason), switch distances for a 1080-px screen at 60
# degrees, the same bytes on a rebake; a batch asset gets the same chain, and none with the setting
# "no-chain"; with --lod-file the combined file holds the chain's files (not the input).
# usage: chain_test.sh QF_BAKE QF_RENDER
set -u
bake=$1 render=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

# A small mesh with mesh LODs (a UV sphere of 1,152 triangles) and a point set.
"$bake" generate sphere --mesh --subdivisions 12 -o "$work/sphere.ply" -q || fail "generate sphere"
"$bake" generate torus -n 8000 -o "$work/torus.ply" -q || fail "generate"

check() {  # check MANIFEST: the chain follows its rule from its own measurements
  python3 - "$1" <<'PY'
import json, math, sys
m = json.load(open(sys.argv[1]))
c = m.get("recommended_chain") or sys.exit("no recommended_chain")
files = {f["name"]: f["bytes"] for f in m["files"]}
want = [l["file"] for l in m.get("mesh_lods", {}).get("levels", [])] + [l["file"] for l in m["levels"]]
if "point_impostor" in m: want.append(m["point_impostor"]["file"])
measured = c["measured"]
if sorted(e["file"] for e in measured) != sorted(want): sys.exit(f"measured {[e['file'] for e in measured]}, the bake made {sorted(want)}")
sizes, asset, h = c["sizes"], c["asset"], c["hold"]
def ev(f): return f is not None and all(f[k] is not None for k in ("psnr", "soft_iou", "coverage"))
def holds(f, a):
    if not ev(f) or not ev(a): return False
    floor = max(h["min_coverage"], min(a["coverage"], 1) - h["coverage_drop"])
    return f["coverage"] >= floor - 1e-6 and f["psnr"] >= a["psnr"] - h["psnr_drop"] - 1e-6 and f["soft_iou"] >= a["soft_iou"] - h["soft_iou_drop"] - 1e-6
def better(f, a): return ev(f) and ev(a) and (f["psnr"] > a["psnr"] or f["soft_iou"] > a["soft_iou"])
# Every file drawn at 256 px and below; above, exactly the files that hold at the size below.
base = sizes.index(256)
for e in measured:
    at = e["at_pixels"]
    if e["bytes"] != files[e["file"]] or len(at) != len(sizes) or None in at[base:]: sys.exit(f"bad measurement {e}")
    for k in range(base):
        if (at[k] is not None) != holds(at[k + 1], asset["at_pixels"][k + 1]): sys.exit(f"{e['file']} drawn at {sizes[k]} px: {at[k] is not None}")
if any(not any(holds(e["at_pixels"][k + 1], asset["at_pixels"][k + 1]) for e in measured) for k in range(base)): sys.exit(f"sizes {sizes} measured above need")
rule, met, last, cap = [], [], None, float("inf")
for k in range(len(sizes)):
    a = asset["at_pixels"][k]
    allowed = [e for e in measured if e["bytes"] <= cap and (e["bytes"] <= asset["bytes"] or better(e["at_pixels"][k], a))]
    good = [e for e in allowed if holds(e["at_pixels"][k], a)]
    if good: pick, ok = min(good, key=lambda e: e["bytes"]), True
    elif asset["bytes"] <= cap: pick, ok = None, True
    else:  # below the bar: the best trade among files that hold at half the size or more, else the input
        trade = [e for e in allowed if ev(e["at_pixels"][k]) and 2 * e["max_screen_pixels"] >= sizes[k]]
        pick = max(trade, key=lambda e: e["at_pixels"][k]["psnr"] - math.log2(max(1, e["bytes"]))) if trade else None
        ok = not trade
    rule.append(pick["file"] if pick else asset["file"])
    met.append(ok)
    last, cap = pick, (pick["bytes"] if pick else float("inf"))
chain = c["chain"]
if chain[0]["kind"] != "asset" or chain[0]["max_pixels"] is not None: sys.exit(f"the chain does not start at the asset: {chain[0]}")
bands, bands_met = [], []  # the file of each measured band, nearest first, from the chain's entries
for k, s in enumerate(sizes):
    lower = sizes[k + 1] if k + 1 < len(sizes) else 0
    e = [e for e in chain if (e["max_pixels"] is None or s <= e["max_pixels"]) and lower >= e["min_pixels"]]
    if len(e) != 1: sys.exit(f"{len(e)} entries for the band at {s} px")
    bands.append(e[0]["file"])
if bands != rule: sys.exit(f"bands {bands}, the rule says {rule}")
for e in chain:  # an entry met the bar where every band of it did
    ks = [k for k, s in enumerate(sizes) if (e["max_pixels"] is None or s <= e["max_pixels"]) and (sizes[k + 1] if k + 1 < len(sizes) else 0) >= e["min_pixels"]]
    if e["bar_met"] != all(met[k] for k in ks): sys.exit(f"bar_met wrong in {e}")
    if not e["bar_met"] and "would" not in e.get("reason", ""): sys.exit(f"no reason in {e}")
    if e["kind"] != "asset":  # a derived file is never shown above twice the largest size at which it holds
        f = next(x for x in measured if x["file"] == e["file"])
        if e["max_pixels"] is None or e["max_pixels"] > 2 * f["max_screen_pixels"] or (e["bar_met"] and e["max_pixels"] > f["max_screen_pixels"]):
            sys.exit(f"{e} shown above where it holds")
if chain[-1]["min_pixels"] != 0 or chain[-1]["switch_distance"] is not None: sys.exit("the chain does not run down to 0")
z0 = 1080 / (2 * math.tan(math.radians(30)))
for a, b in zip(chain, chain[1:]):
    if a["file"] == b["file"] or a["min_pixels"] != b["max_pixels"]: sys.exit(f"entries {a} and {b} do not join")
    d = m["bounding_box_diagonal"] * z0 / a["min_pixels"]
    if abs(a["switch_distance"] - d) > 1e-3 * d: sys.exit(f"switch distance {a['switch_distance']}, expected {d}")
print(" -> ".join(f"{e['file']} (to {e['min_pixels']} px{'' if e['bar_met'] else ', below the bar'})" for e in chain))
PY
}

# 1. A mesh: mesh LODs, impostor levels and the point impostor are all candidates.
"$bake" "$work/sphere.ply" -o "$work/mesh" --ldi 256 --measure-views 3 --points -q || fail "mesh bake"
kinds=$(python3 -c "import json,sys; print(sorted({e['kind'] for e in json.load(open(sys.argv[1]))['recommended_chain']['measured']}))" "$work/mesh/manifest.json")
[[ "$kinds" == "['impostor_level', 'mesh_lod', 'point_impostor']" ]] || fail "mesh candidates: $kinds"
out=$(check "$work/mesh/manifest.json") || fail "mesh chain: $out"
echo "mesh chain: $out"

# With --lod-file, STEM_lods.glb holds the chain's files as its LODs, but for those a Babylon.js
# progressive load could dispose mid-load (more image bytes than a finer part kept: manifest
# lod_file.left_out): each drawn alone (--lod i) gives the same picture as the file itself.
# (A lax bar, --hold-psnr 10, gives the torus a chain of several files: the input near, then mesh
# LODs of its reconstructed surface and impostor levels.)
"$bake" "$work/torus.ply" -o "$work/lod" --measure-views 3 --lod-file --hold-psnr 10 -q || fail "--lod-file"
mapfile -t parts < <(python3 -c "import json,sys; [print(p) for p in json.load(open(sys.argv[1]))['lod_file']['parts']]" "$work/lod/manifest.json")
(( ${#parts[@]} >= 2 )) || fail "a combined file of one part: ${parts[*]}"
python3 - "$work/lod" <<'PY' || fail "the combined file's parts and screen coverages are not the chain's"
import json, struct, sys
d = sys.argv[1]
m = json.load(open(d + "/manifest.json"))
chain, lod = m["recommended_chain"]["chain"], m["lod_file"]
def glb_json(path):
    data = open(path, "rb").read()
    return json.loads(data[20:20 + struct.unpack_from("<I", data, 12)[0]])
def image_bytes(file):
    doc = glb_json(d + "/" + file)
    return sum(doc["bufferViews"][i["bufferView"]]["byteLength"] for i in doc.get("images", []))
files = [e["file"] for e in chain if e["kind"] != "asset"]
kept = [f for f in files if f not in lod["left_out"]]
assert kept == lod["parts"], (kept, lod["parts"])
for f in lod["left_out"]:  # each left out has more image bytes than a finer part kept
    finer = [k for k in kept if files.index(k) < files.index(f)]
    assert finer and image_bytes(f) > min(image_bytes(k) for k in finer), f
doc = glb_json(d + "/torus_lods.glb")
root = doc["nodes"][doc["scenes"][0]["nodes"][0]]
want = [min(1.0, e["min_pixels"] / 1080) for e in chain if e["kind"] != "asset" and e["file"] in kept]
want[-1] = 0.0
got = root["extras"]["MSFT_screencoverage"]
assert len(got) == len(want) and all(abs(a - b) < 1e-6 for a, b in zip(got, want)), (got, want)
PY
for i in "${!parts[@]}"; do
  "$render" render "$work/lod/torus_lods.glb" --lod "$i" -o "$work/lod$i.png" --method engine --size 64 2>/dev/null || fail "render --lod $i"
  "$render" render "$work/lod/${parts[$i]}" -o "$work/part$i.png" --method engine --size 64 --frame "$work/lod/torus_lods.glb" 2>/dev/null || fail "render ${parts[$i]}"
  cmp -s "$work/lod$i.png" "$work/part$i.png" || fail "LOD $i of the combined file does not draw as ${parts[$i]}"
done
"$render" render "$work/lod/torus_lods.glb" --lod "${#parts[@]}" -o "$work/x.png" 2>/dev/null && fail "--lod past the last part"
echo "lod file: ${parts[*]}"

# 2. A point set: the impostor levels and the reconstructed surface's mesh LODs. The bar decides: at
# 0 dB below the asset as drawn few files hold, at 20 dB more do, so the chains differ.
"$bake" "$work/torus.ply" -o "$work/points" --measure-views 3 -q || fail "point-set bake"
out=$(check "$work/points/manifest.json") || fail "point-set chain: $out"
echo "point-set chain: $out"
"$bake" "$work/torus.ply" -o "$work/strict" --measure-views 3 --hold-psnr 0 -q || fail "--hold-psnr 0"
out=$(check "$work/strict/manifest.json") || fail "strict chain: $out"
echo "at 0 dB: $out"
"$bake" "$work/torus.ply" -o "$work/lax" --measure-views 3 --hold-psnr 20 -q || fail "--hold-psnr 20"
out=$(check "$work/lax/manifest.json") || fail "lax chain: $out"
echo "at 20 dB: $out"
python3 -c "import json,sys; a, b = (json.load(open(f))['recommended_chain']['chain'] for f in sys.argv[1:]); sys.exit(a == b)" \
  "$work/strict/manifest.json" "$work/lax/manifest.json" || fail "the hold bar changed nothing"

# 2'. A cheap mesh (an opaque cube of 48 triangles, under --cheap-triangles 256): measured, not
# baked; no file but the manifest and reports, which say why, and the chain is the cube itself.
"$bake" generate cube --mesh --subdivisions 2 -o "$work/cube.ply" -q || fail "generate cube"
"$bake" "$work/cube.ply" -o "$work/cube" --measure-views 2 2>"$work/cube.err" || fail "cheap bake: $(cat "$work/cube.err")"
grep -q "cheaper drawn as it is" "$work/cube.err" || fail "a cheap mesh's bake does not say why it wrote little: $(cat "$work/cube.err")"
python3 - "$work/cube" <<'PY' || fail "the cheap cube's bake"
import json, os, sys
d = sys.argv[1]
m = json.load(open(d + "/manifest.json"))
assert m["levels"] == [] and m["cheap_asset"]["triangles"] == 48, m.get("cheap_asset")
assert m["cheap_asset"]["bytes"] == os.path.getsize(d + "/../cube.ply")
assert not [f for f in os.listdir(d) if f.endswith(".glb")], os.listdir(d)
c = m["recommended_chain"]["chain"]
assert len(c) == 1 and c[0]["kind"] == "asset" and c[0]["min_pixels"] == 0 and c[0]["max_pixels"] is None, c
assert os.path.exists(d + "/report.html")
PY
"$bake" "$work/cube.ply" -o "$work/cube_full" --cheap-triangles 0 --measure-views 2 --primitives 30 -q || fail "--cheap-triangles 0"
ls "$work"/cube_full/cube_L*.glb >/dev/null 2>&1 || fail "--cheap-triangles 0 baked no level"
echo "cheap cube: the asset itself, no levels"

# 3. Same input and settings, same bytes (at 1 and 2 threads); --no-chain: no chain, the same
# levels and sizes.
"$bake" "$work/torus.ply" -o "$work/points2" --measure-views 3 -j 1 -q || fail "rebake"
cmp "$work/points/manifest.json" "$work/points2/manifest.json" || fail "a rebake's chain differs"
"$bake" "$work/torus.ply" -o "$work/plain" --measure-views 3 --no-chain -q || fail "bake with --no-chain"
grep -q recommended_chain "$work/plain/manifest.json" && fail "a chain with --no-chain"
python3 -c "import json,sys; a, b = (json.load(open(f))['levels'] for f in sys.argv[1:]); sys.exit(a != b)" \
  "$work/points/manifest.json" "$work/plain/manifest.json" || fail "--no-chain changed the levels"

# 4. A batch asset gets the same chain; the setting "no-chain" leaves it out.
cat > "$work/batch.json" <<JSON
{"defaults": {"measure-views": 3}, "assets": ["$work/torus.ply", {"input": "$work/torus.ply", "name": "plain", "settings": {"no-chain": true}}]}
JSON
"$bake" batch "$work/batch.json" -o "$work/batch" -q || fail "batch"
python3 -c "import json,sys; a, b = (json.load(open(f))['recommended_chain'] for f in sys.argv[1:]); sys.exit(a != b)" \
  "$work/points/manifest.json" "$work/batch/torus/manifest.json" || fail "the batch's chain differs from the bake's"
grep -q recommended_chain "$work/batch/plain/manifest.json" && fail "a batch asset with no-chain has a chain"
echo "chain: all checks passed"
