#!/usr/bin/env bash
# The recommended chain (made by every bake unless --no-chain, pipeline/chain.h): every candidate of
# a bake measured against the input where it is valid (impostor levels at every size), per band the
# smallest file valid there (at most 2 x its max_screen_pixels)
# that reaches the quality bar (else the best trade of PSNR against bytes),
# switch distances for a 1080-px screen at 60 degrees, the same bytes on a rebake; a batch asset
# gets the same chain, and none with the setting "no-chain"; with --lod-file the combined file
# holds the chain's files.
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
measured = {e["file"]: e for e in c["measured"]}
if sorted(measured) != sorted(want): sys.exit(f"measured {sorted(measured)}, the bake made {sorted(want)}")
sizes = c["sizes"]
def within_limit(e, k):  # at most shown_above x its own max_screen_pixels
    return e["max_screen_pixels"] is None or sizes[k] <= c["shown_above"] * e["max_screen_pixels"]
for e in measured.values():
    if e["bytes"] != files[e["file"]] or len(e["at_pixels"]) != len(sizes): sys.exit(f"bad measurement {e}")
    # Drawn exactly where it may be chosen: impostor levels everywhere, the others up to their limit.
    drawn = [x is not None for x in e["at_pixels"]]
    if drawn != [e["kind"] == "impostor_level" or within_limit(e, k) for k in range(len(sizes))]: sys.exit(f"drawn at the wrong sizes: {e}")
def valid(e, k): return e["at_pixels"][k] is not None and within_limit(e, k)
def ok(e, k): return e["at_pixels"][k]["psnr"] >= c["min_psnr"] and e["at_pixels"][k]["iou"] >= c["min_iou"]
def limit(e): return 0 if e["max_screen_pixels"] is None else c["shown_above"] * e["max_screen_pixels"]
def pick(k, cap):  # among valid files of at most cap bytes (the nearer band's choice), else valid ones, else the files made for the largest sizes
    drawn = [e for e in c["measured"] if e["at_pixels"][k] is not None]
    largest = max(limit(e) for e in drawn)
    for within in ([e for e in drawn if valid(e, k) and e["bytes"] <= cap], [e for e in drawn if valid(e, k)],
                   [e for e in drawn if limit(e) == largest]):
        if not within: continue
        good = [e for e in within if ok(e, k)]
        if good: return min(good, key=lambda e: e["bytes"])
        trade = [e["at_pixels"][k]["psnr"] - math.log2(e["bytes"]) for e in within]
        return within[trade.index(max(trade))]
rule, cap = [], float("inf")
for k in range(len(sizes)):
    e = pick(k, cap)
    rule.append(e["file"])
    cap = e["bytes"]
bands = []  # the file of each band, nearest first, from the chain's entries
for e in c["chain"]:
    for k, s in enumerate(sizes):
        lower = sizes[k + 1] if k + 1 < len(sizes) else 0
        if (e["max_pixels"] is None or s <= e["max_pixels"]) and lower >= e["min_pixels"]: bands.append(e["file"])
if bands != rule: sys.exit(f"bands {bands}, the rule says {rule}")
for e in c["chain"]:  # each entry says whether it met the bar at its nearest band
    if e["bar_met"] != ok(measured[e["file"]], sizes.index(e["measured_at_pixels"])): sys.exit(f"bar_met wrong in {e}")
if c["chain"][0]["max_pixels"] is not None or c["chain"][-1]["min_pixels"] != 0 or c["chain"][-1]["switch_distance"] is not None:
    sys.exit("the chain does not run from any size down to 0")
z0 = 1080 / (2 * math.tan(math.radians(30)))
for a, b in zip(c["chain"], c["chain"][1:]):
    if a["file"] == b["file"] or a["min_pixels"] != b["max_pixels"]: sys.exit(f"entries {a} and {b} do not join")
    d = m["bounding_box_diagonal"] * z0 / a["min_pixels"]
    if abs(a["switch_distance"] - d) > 1e-3 * d: sys.exit(f"switch distance {a['switch_distance']}, expected {d}")
print(" -> ".join(f"{e['file']} (to {e['min_pixels']} px, {e['error']['psnr']} dB)" for e in c["chain"]))
PY
}

# 1. A mesh: mesh LODs, impostor levels and the point impostor are all candidates.
"$bake" "$work/sphere.ply" -o "$work/mesh" --ldi 256 --measure-views 3 -q || fail "mesh bake"
kinds=$(python3 -c "import json,sys; print(sorted({e['kind'] for e in json.load(open(sys.argv[1]))['recommended_chain']['measured']}))" "$work/mesh/manifest.json")
[[ "$kinds" == "['impostor_level', 'mesh_lod', 'point_impostor']" ]] || fail "mesh candidates: $kinds"
out=$(check "$work/mesh/manifest.json") || fail "mesh chain: $out"
echo "mesh chain: $out"

# With --lod-file, STEM_lods.glb holds the chain's files as its LODs, but for those a Babylon.js
# progressive load could dispose mid-load (more image bytes than a finer part kept: manifest
# lod_file.left_out): each drawn alone (--lod i) gives the same picture as the file itself.
# (The sphere's chain is an impostor level near, then its finest mesh LOD.)
"$bake" "$work/sphere.ply" -o "$work/lod" --ldi 256 --measure-views 3 --lod-file -q || fail "--lod-file"
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
files = [e["file"] for e in chain]
kept = [f for f in files if f not in lod["left_out"]]
assert kept == lod["parts"], (kept, lod["parts"])
for f in lod["left_out"]:  # each left out has more image bytes than a finer part kept
    finer = [k for k in kept if files.index(k) < files.index(f)]
    assert finer and image_bytes(f) > min(image_bytes(k) for k in finer), f
doc = glb_json(d + "/sphere_lods.glb")
root = doc["nodes"][doc["scenes"][0]["nodes"][0]]
want = [min(1.0, e["min_pixels"] / 1080) for e in chain if e["file"] in kept]
want[-1] = 0.0
got = root["extras"]["MSFT_screencoverage"]
assert len(got) == len(want) and all(abs(a - b) < 1e-6 for a, b in zip(got, want)), (got, want)
PY
for i in "${!parts[@]}"; do
  "$render" render "$work/lod/sphere_lods.glb" --lod "$i" -o "$work/lod$i.png" --method engine --size 64 2>/dev/null || fail "render --lod $i"
  "$render" render "$work/lod/${parts[$i]}" -o "$work/part$i.png" --method engine --size 64 --frame "$work/lod/sphere_lods.glb" 2>/dev/null || fail "render ${parts[$i]}"
  cmp -s "$work/lod$i.png" "$work/part$i.png" || fail "LOD $i of the combined file does not draw as ${parts[$i]}"
done
"$render" render "$work/lod/sphere_lods.glb" --lod "${#parts[@]}" -o "$work/x.png" 2>/dev/null && fail "--lod past the last part"
echo "lod file: ${parts[*]}"

# 2. A point set: the impostor levels alone. The bar decides: at 99 dB (an identical picture) nothing
# reaches it and each band takes its best trade; at 15 dB the smallest level that reaches it (and
# IoU 0.9) serves the far bands.
"$bake" "$work/torus.ply" -o "$work/points" --measure-views 3 -q || fail "point-set bake"
out=$(check "$work/points/manifest.json") || fail "point-set chain: $out"
echo "point-set chain: $out"
"$bake" "$work/torus.ply" -o "$work/strict" --measure-views 3 --chain-psnr 99 -q || fail "--chain-psnr 99"
out=$(check "$work/strict/manifest.json") || fail "strict chain: $out"
echo "at 99 dB: $out"
"$bake" "$work/torus.ply" -o "$work/lax" --measure-views 3 --chain-psnr 15 -q || fail "--chain-psnr 15"
out=$(check "$work/lax/manifest.json") || fail "lax chain: $out"
echo "at 15 dB: $out"
python3 -c "import json,sys; a, b = (json.load(open(f))['recommended_chain']['chain'] for f in sys.argv[1:]); sys.exit(a == b)" \
  "$work/strict/manifest.json" "$work/lax/manifest.json" || fail "the quality bar changed nothing"

# 3. Same input and settings, same bytes (at 1 and 2 threads); --no-chain: no chain, the same
# levels and sizes.
"$bake" "$work/torus.ply" -o "$work/points2" --measure-views 3 -j 1 -q || fail "rebake"
cmp "$work/points/manifest.json" "$work/points2/manifest.json" || fail "a rebake's chain differs"
"$bake" "$work/torus.ply" -o "$work/plain" --measure-views 3 --no-chain -q || fail "bake with --no-chain"
grep -q recommended_chain "$work/plain/manifest.json" && fail "a chain with --no-chain"
python3 -c "import json,sys; a, b = (json.load(open(f))['levels'] for f in sys.argv[1:]); sys.exit(a != b)" \
  "$work/points/manifest.json" "$work/plain/manifest.json" || fail "--no-chain changed the levels"
"$bake" "$work/torus.ply" -o "$work/x" --no-chain --chain-psnr 20 -q 2>/dev/null; [[ $? == 2 ]] || fail "--no-chain --chain-psnr not refused"

# 4. A batch asset gets the same chain; the setting "no-chain" leaves it out.
cat > "$work/batch.json" <<JSON
{"defaults": {"measure-views": 3}, "assets": ["$work/torus.ply", {"input": "$work/torus.ply", "name": "plain", "settings": {"no-chain": true}}]}
JSON
"$bake" batch "$work/batch.json" -o "$work/batch" -q || fail "batch"
python3 -c "import json,sys; a, b = (json.load(open(f))['recommended_chain'] for f in sys.argv[1:]); sys.exit(a != b)" \
  "$work/points/manifest.json" "$work/batch/torus/manifest.json" || fail "the batch's chain differs from the bake's"
grep -q recommended_chain "$work/batch/plain/manifest.json" && fail "a batch asset with no-chain has a chain"
echo "chain: all checks passed"
