#!/usr/bin/env bash
# The runtime loaders (tools/qf-runtime: three.mjs, babylon.mjs) in headless Chromium, ENGINE three or
# babylon: loadImpostorLOD on a bake's manifest.json (the recommended chain with and without the app's
# model for its "asset" entries; the impostor levels of a bake without a chain), on a `_lods.glb`
# (MSFT_lod), and on a chain of every kind of output (mesh LOD, impostor levels, point impostor; the
# test writes it beside a bake's files), in PNG and (three.js) KTX2 textures. The camera moves out
# from the object's centre by steps of 5% and back; at every position the file shown must be the one
# the manifest gives, each switch within one step of the manifest's distance (switch_distance, for
# 1080 px at 60 degrees, scaled to the canvas), and the engine's memory (three.js:
# renderer.info.memory; Babylon.js: its textures, geometries and meshes) the same every time a file
# is shown (what is no longer shown was freed), and back to the start after lod.dispose(). Files
# through the toolchain load with the decoders passed in; three.js refuses a file whose decoder was
# not passed with the option's name. docs/engines.md's call names only options the module takes.
# usage: runtime_test.sh ENGINE QF_BAKE SOURCE_DIR
set -u
engine=$1 bake=$2 src=$3
dir="$src/scripts/$engine-render"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
case $engine in
  three) package=three ;;
  babylon) package=@babylonjs/loaders ;;
  *) fail "unknown engine $engine" ;;
esac
[[ -f "$dir/node_modules/$package/package.json" ]] || fail "$package not installed: run scripts/install-deps.sh"
# docs/engines.md's one-line call for this engine names only options the module takes.
python3 - "$src/docs/engines.md" "$src/tools/qf-runtime/$engine.mjs" <<'PY' || fail "docs/engines.md's call of tools/qf-runtime/$engine.mjs"
import re, sys
doc, module = open(sys.argv[1]).read(), open(sys.argv[2]).read()
taken = set(re.findall(r"\b(\w+)\s*(?:=[^,}]*)?[,}]", re.search(r"const \{([^}]*)\} = options;", module).group(1) + "}"))
name = sys.argv[2].rsplit("/", 1)[1]
calls = [c for block in re.findall(r"```js\n(.*?)```", doc, re.S) if f"qf-runtime/{name}" in block
         for c in re.findall(r"loadImpostorLOD\([^,]+,\s*\{([^}]*)\}\)", block)]
if not calls: sys.exit(f"no call of {name}'s loadImpostorLOD in a js block")
for c in calls:
    unknown = [o.strip() for o in c.split(",") if o.strip().split(":")[0] not in taken]
    if unknown: sys.exit(f"the call names {unknown}, which {name} does not take ({sorted(taken)})")
print(f"docs/engines.md: {name}'s call takes " + "; ".join(c.strip() for c in calls))
PY
start=$SECONDS
"$bake" generate torus -o "$work/torus.ply" -q || fail "generate torus"
"$bake" generate octahedron --mesh --subdivisions 8 -o "$work/octa.ply" -q || fail "generate octahedron"
# torus: a point set whose chain (2 views) runs through impostor levels and a mesh LOD; its
# _lods.glb; octa: a mesh with every kind of output, measured by geometry alone (no chain).
"$bake" "$work/torus.ply" -o "$work/torus" --measure-views 2 --lod-file -q || fail "bake torus"
"$bake" "$work/octa.ply" -o "$work/octa" --points --no-measure --primitives 100,30 -q || fail "bake octa"
dirs=(torus octa)
# Files through the toolchain (tools/gltf-transform-qf, installed by scripts/install-deps.sh): the
# octahedron's mesh LODs compressed with meshopt (quantized positions too) and Draco, to load with
# the decoders passed in.
gt="$src/tools/gltf-transform-qf/node_modules/.bin/gltf-transform"
if [[ -x $gt ]]; then
  "$gt" draco "$work/octa/octa_S0.glb" "$work/octa/octa_S0_draco.glb" --config "$src/tools/gltf-transform-qf/gltf-transform.config.mjs" > /dev/null ||
    fail "gltf-transform draco"
  "$gt" meshopt "$work/octa/octa_S1.glb" "$work/octa/octa_S1_meshopt.glb" --config "$src/tools/gltf-transform-qf/gltf-transform.config.mjs" > /dev/null ||
    fail "gltf-transform meshopt"
else
  echo "note: no tools/gltf-transform-qf/node_modules: the meshopt and Draco cases are left out (scripts/install-deps.sh installs it)"
fi
if [[ $engine == three ]]; then
  # KTX2 (three.js's KTX2Loader; Babylon.js fetches its KTX2 decoder from a CDN): the impostor levels
  # by their geometric sizes (measured, a KTX2 level of the torus holds at no size) and their _lods.glb.
  "$bake" "$work/torus.ply" -o "$work/torusk" --no-measure --no-mesh-lods --lod-file --textures ktx2 -q || fail "bake torus ktx2"
  dirs+=(torusk)
fi
echo "bakes: $((SECONDS - start)) s"
python3 - "$engine" "$work" "${dirs[@]}" > "$work/cases.json" <<'PY' || fail "cases"
# The cases, each with what the manifest says: the files from near to far and where each takes over.
import json, math, os, struct, sys
engine, work, dirs = sys.argv[1], sys.argv[2], sys.argv[3:]
size = 256                                            # the canvas, px
z0 = size / (2 * math.tan(math.radians(30)))          # fov 60
scale = size / 1080                                   # the manifest's distances are for 1080 px at 60 degrees
ratio = 1.05                                          # the camera's step
def manifest(d): return json.load(open(f"{work}/{d}/manifest.json"))
def lod_starts(d, m):
    # A _lods.glb's levels take over where the level before reaches its MSFT_screencoverage (of a
    # lod_file.screen_height screen): the chain's min_pixels, or the next level's unrounded geometric
    # size (the manifest rounds it: 79 px where the file has 79.58).
    glb = open(f"{work}/{d}/{m['lod_file']['file']}", "rb").read()
    root_json = json.loads(glb[20:20 + struct.unpack("<I", glb[12:16])[0]])
    root = root_json["nodes"][root_json["scenes"][0]["nodes"][0]]
    pixels = [c * m["lod_file"]["screen_height"] for c in root["extras"]["MSFT_screencoverage"]]
    return [f"level {i}" for i in range(len(pixels))], [0] + [m["bounding_box_diagonal"] * z0 / p for p in pixels[:-1]]
def chain_expect(m, asset):
    # The chain's entries nearest first; without the app's model, its "asset" entries are left out
    # and their band goes to the nearer file (the first file from 0). A file starts where the entry
    # before it ends (its switch_distance).
    files, starts = [], []
    for i, e in enumerate(m["recommended_chain"]["chain"]):
        if e["kind"] == "asset" and not asset: continue
        name = "asset" if e["kind"] == "asset" else e["file"]
        if files and files[-1] == name: continue
        files.append(name)
        starts.append(0 if not starts else m["recommended_chain"]["chain"][i - 1]["switch_distance"] * scale)
    return files, starts
def levels_expect(m):
    levels = sorted((l for l in m["levels"] if l["max_screen_pixels"] > 0), key=lambda l: -l["primitives"])
    return [l["file"] for l in levels], [0] + [m["bounding_box_diagonal"] * z0 / l["max_screen_pixels"] for l in levels[1:]]
def distances(starts):
    first = min(s for s in starts if s > 0) if len(starts) > 1 else 1.0
    d, out = first / 2, []
    while d < 2 * max(starts + [first]):
        out.append(round(d, 6)); d *= ratio
    return out
cases = []
def add(name, url, files, starts, asset=False, ktx2=False, diagonal=None, decoders=False, error=None, left_handed=False, asset_url=None):
    cases.append({"name": name, "url": url, "asset": asset, "assetUrl": asset_url, "ktx2": ktx2, "diagonal": diagonal, "decoders": decoders, "leftHanded": left_handed,
                  "error": error, "files": files, "starts": starts, "distances": distances(starts)})
def write_chain(m, d, name, entries):
    # A chain of the given (file, kind, max_pixels, min_pixels) beside a bake's files, each entry's
    # switch_distance by the manifest's formula, as baker/measure/chain.cpp writes it.
    D = m["bounding_box_diagonal"]
    m = dict(m, recommended_chain={"screen_height": 1080, "fov_degrees": 60, "chain": [
        {"file": f, "kind": k, "max_pixels": mx, "min_pixels": mn,
         "switch_distance": D * 1080 / (2 * math.tan(math.radians(30)) * mn) if mn else None} for f, k, mx, mn in entries]})
    json.dump(m, open(f"{work}/{d}/{name}", "w"), indent=1)
    return m
t = manifest("torus")
add("torus chain", "/files/torus/manifest.json", *chain_expect(t, False))
add("torus chain + app model", "/files/torus/manifest.json", *chain_expect(t, True), asset=True)
# The app's model by URL (here the torus's coarsest mesh LOD stands in for it): loaded where shown,
# disposed where not, like the baked files.
add("torus chain + app model by URL", "/files/torus/manifest.json", *chain_expect(t, True), asset_url="/files/torus/torus_S4.glb")
if engine == "babylon":  # the loader's centre through the glTF loader's turn into a left-handed scene
    add("torus chain, left-handed scene", "/files/torus/manifest.json", *chain_expect(t, False), left_handed=True)
# _lods.glb: its levels are the chain's files it keeps, each shown down to its chain entry's
# min_pixels; the loader is given the manifest's diagonal, which the file does not carry.
entry = {e["file"]: e for e in t["recommended_chain"]["chain"]}
parts = t["lod_file"]["parts"]
files, starts = lod_starts("torus", t)
if any(abs(a - entry[p]["switch_distance"] * scale) > 1e-3 * a for a, p in zip(starts[1:], parts)):
    sys.exit(f"torus_lods.glb's coverages {starts} are not its chain's distances")
add("torus _lods.glb", "/files/torus/torus_lods.glb", files, starts, diagonal=t["bounding_box_diagonal"])
# Every kind of output in one chain, written beside the octahedron's files: the app's model, the mesh
# LOD, the two impostor levels, the point impostor, from 256 px down.
o = manifest("octa")
kinds = [("octa.ply", "asset", None, 256), (o["mesh_lods"]["levels"][0]["file"], "mesh_lod", 256, 128)]
kinds += [(l["file"], "impostor_level", p, p // 2) for l, p in zip(sorted(o["levels"], key=lambda l: -l["primitives"]), (128, 64))]
kinds += [(o["point_impostor"]["file"], "point_impostor", 32, 0)]
add("octa every kind + app model", "/files/octa/manifest-kinds.json", *chain_expect(write_chain(o, "octa", "manifest-kinds.json", kinds), True), asset=True)
# The toolchain's files: an impostor level, the Draco mesh LOD, the meshopt one (quantized: the
# farthest file, the one the loader reads the centre from).
if os.path.exists(f"{work}/octa/octa_S1_meshopt.glb"):
    finest = sorted(o["levels"], key=lambda l: -l["primitives"])[0]["file"]
    tc = write_chain(o, "octa", "manifest-toolchain.json", [(finest, "impostor_level", None, 128), ("octa_S0_draco.glb", "mesh_lod", 128, 32),
                                                            ("octa_S1_meshopt.glb", "mesh_lod", 32, 0)])
    add("octa meshopt + Draco", "/files/octa/manifest-toolchain.json", *chain_expect(tc, False), decoders=True)
    if engine == "three":  # Babylon.js fetches decoders it is not given from its CDN
        add("octa meshopt + Draco, no decoders passed", "/files/octa/manifest-toolchain.json", *chain_expect(tc, False),
            error="KHR_draco_mesh_compression: pass dracoLoader")
if "torusk" in dirs:
    k = manifest("torusk")
    add("torus KTX2 levels (no chain)", "/files/torusk/manifest.json", *levels_expect(k), ktx2=True)
    add("torus KTX2 _lods.glb", "/files/torusk/torus_lods.glb", *lod_starts("torusk", k), ktx2=True, diagonal=k["bounding_box_diagonal"])
    add("torus KTX2, no ktx2Loader passed", "/files/torusk/manifest.json", *levels_expect(k), error="KHR_texture_basisu: pass ktx2Loader")
json.dump({"size": size, "ratio": ratio, "dirs": {d: f"{work}/{d}" for d in dirs}, "cases": cases}, sys.stdout)
PY
start=$SECONDS
node "$dir/runtime-check.mjs" "$work/cases.json" > "$work/shown.jsonl" 2> "$work/stderr.txt" ||
  fail "runtime-check: $(tail -n 5 "$work/stderr.txt")"
echo "$engine in Chromium: $((SECONDS - start)) s"
python3 - "$work/cases.json" "$work/shown.jsonl" <<'PY' || fail "the loader did not switch or free as the manifest says"
import json, math, sys
spec = json.load(open(sys.argv[1]))
results = [json.loads(l) for l in open(sys.argv[2])]
step = math.log(spec["ratio"]) + 1e-9
bad = 0
def complain(case, msg):
    global bad
    bad += 1
    print(f"  {case['name']}: {msg}")
for case, r in zip(spec["cases"], results, strict=True):
    # 0. A file that needs a decoder not passed: refused with a message naming the option.
    if case["error"] or "error" in r:
        if not case["error"] or case["error"] not in r.get("error", ""):
            complain(case, f"error {r.get('error')!r}, expected one naming {case['error']!r}")
        else:
            print(f"{case['name']}: refused: {r['error']}")
        continue
    files, starts, n = case["files"], case["starts"], len(case["distances"])
    out, back = r["samples"][:n], r["samples"][n:]
    # 1. The file shown at every distance is the manifest's, but within one step of a switch.
    for s in r["samples"]:
        want = max(j for j, t in enumerate(starts) if s["d"] >= t)
        near = [j for j, t in enumerate(starts) if j and abs(math.log(s["d"] / t)) <= step]
        if s["file"] != files[want] and not any(s["file"] == files[j] or s["file"] == files[j - 1] for j in near):
            complain(case, f"at {s['d']:.4g} shows {s['file']}, the manifest says {files[want]}")
    # 2. Each switch, out and back, where the manifest puts it.
    found = []
    for j in range(1, len(files)):
        o = next((s["d"] for s in out if files.index(s["file"]) >= j), None) if all(s["file"] in files for s in out) else None
        b = next((s["d"] for s in back if files.index(s["file"]) < j), None) if all(s["file"] in files for s in back) else None
        found.append((starts[j], o, b))
        if o is None or abs(math.log(o / starts[j])) > step: complain(case, f"switch to {files[j]} outward at {o}, the manifest says {starts[j]:.4g}")
        if b is None or abs(math.log(b / starts[j])) > step: complain(case, f"switch back from {files[j]} at {b}, the manifest says {starts[j]:.4g}")
    # 3. Memory: the same every time a file is shown (the one before it was freed), and after
    # dispose() no more than before the first file (the app's own model kept).
    memory = {}
    for s in r["samples"]:
        m = memory.setdefault(s["file"], s["memory"])
        if m != s["memory"]: complain(case, f"{s['file']} at {s['d']:.4g}: memory {s['memory']}, {m} when first shown")
    if any(r["after"][k] > r["before"][k] + (r["appAsset"].get(k, 0) if case["asset"] else 0) for k in r["before"]):
        complain(case, f"after dispose(): {r['after']}, before loading {r['before']}")
    if case["asset"] and not r["assetAlive"]: complain(case, "the app's model was disposed")
    print(f"{case['name']}: {len(r['samples'])} positions in {r['ms'] / 1000:.1f} s (first file {r['loadMs']:.0f} ms)")
    for target, o, b in found:
        print(f"  switch at {target:.4g}: out {o}, back {b}")
    print("  memory per file: " + "; ".join(f"{f} {m}" for f, m in memory.items()) + f"; before {r['before']}, after dispose {r['after']}")
sys.exit(1 if bad else 0)
PY
