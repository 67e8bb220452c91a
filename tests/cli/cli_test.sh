#!/usr/bin/env bash
# qf-bake end to end: exit codes (0 ok, 1 bad input, 2 usage), messages naming the file and the
# error code, help texts listing every option, and no output (not even a temporary) on failure.
# usage: cli_test.sh QF_BAKE TEST_DATA_DIR   (QSplat vectors under TEST_DATA_DIR/qsplat)
set -u
bake=$1 data=$2 qsplat=$2/qsplat
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

# expect CODE DESCRIPTION -- command...
expect() {
  local want=$1 what=$2; shift 3
  "$@" >"$work/out" 2>"$work/err"
  local rc=$?
  if [[ $rc -eq $want ]]; then ok; else bad "$what: exit $rc, expected $want; stderr: $(head -c 400 "$work/err")"; fi
}

# --- help and version ---
expect 0 "--version" -- "$bake" --version
grep -q '^qf-bake [0-9]' "$work/out" && ok || bad "--version prints 'qf-bake X.Y.Z'"
expect 0 "--help" -- "$bake" --help
cp "$work/out" "$work/overview"
for cmd in info convert generate billboard analyze decompose bake cluster simplify batch merge-reports tile join; do
  grep -q "^  $cmd " "$work/overview" && ok || bad "--help lists $cmd"
  expect 0 "$cmd --help" -- "$bake" "$cmd" --help
  grep -q "usage: qf-bake $cmd" "$work/out" && ok || bad "$cmd --help shows usage"
done
"$bake" convert --help >"$work/out"
grep -q -- "--radius-k K .*(default: 6)" "$work/out" && ok || bad "convert --help gives --radius-k's default"
"$bake" generate --help >"$work/out"
grep -q -- "--points N .*(default: 16000)" "$work/out" && ok || bad "generate --help gives --points' default"
grep -q "octahedron" "$work/out" && ok || bad "generate --help lists the shapes"

# --- usage errors: exit 2 ---
expect 2 "no arguments" -- "$bake"
expect 2 "unknown command" -- "$bake" frobnicate
expect 2 "unknown option" -- "$bake" info "$qsplat/pyr.qs" --bogus
expect 2 "missing positional" -- "$bake" convert "$qsplat/pyr.qs"
expect 2 "unknown input extension" -- "$bake" info "$work/thing.stl"
expect 2 "unknown output extension" -- "$bake" convert "$qsplat/pyr.qs" "$work/out.stl"
expect 2 "bad number" -- "$bake" generate sphere -o "$work/s.ply" --points many
expect 2 "unknown shape" -- "$bake" generate teapot -o "$work/s.ply"
expect 2 "missing output folder" -- "$bake" generate sphere -o "$work/no/such/dir/s.ply" --points 100
[[ "$(ls "$work" | tr '\n' ' ')" == "err out overview " ]] && ok || bad "usage errors leave no files: $(ls "$work")"

# --- good files ---
for f in tet.qs pyr.qs sphere_col.qs sphere_nocol.qs multi.qs sphere_col.ply pyr.ply; do
  expect 0 "info $f" -- "$bake" info "$qsplat/$f"
done
"$bake" info "$qsplat/sphere_col.qs" >"$work/out"
grep -q "points: *2498" "$work/out" && ok || bad "info counts 2498 points"
grep -q "attributes: *position normal color radius" "$work/out" && ok || bad "info lists attributes"
"$bake" info --json "$qsplat/multi.qs" >"$work/out"
grep -q '"fragments": 3' "$work/out" && ok || bad "info --json reports fragments"
grep -q '"points": 2507' "$work/out" && ok || bad "info --json counts multi.qs leaves"

# info --json follows schemas/info.schema.json, for point sets and meshes alike
schema="$(dirname "$0")/../../schemas/info.schema.json"
for f in "$qsplat/multi.qs" "$qsplat/sphere_col.ply"; do
  "$bake" info --json "$f" >"$work/info.json"
  /usr/bin/python3 -c 'import json, sys, jsonschema
jsonschema.validate(json.load(open(sys.argv[1])), json.load(open(sys.argv[2])))' "$work/info.json" "$schema" 2>"$work/err" \
    && ok || bad "info --json of $f does not follow the schema: $(tail -3 "$work/err")"
done

# generate -> convert through every point format -> info
expect 0 "generate" -- "$bake" generate octahedron -o "$work/oct.ply" -q
for ext in qs xyz pwn ply; do
  expect 0 "convert to $ext" -- "$bake" convert "$work/oct.ply" "$work/oct2.$ext" -q
  "$bake" info --json "$work/oct2.$ext" >"$work/out"
  grep -q '"points": 16000' "$work/out" && ok || bad "oct2.$ext has 16000 points"
done
# xyz has no radii: converting it to ply estimates them and says so
expect 0 "xyz -> ply" -- "$bake" convert "$work/oct2.xyz" "$work/oct3.ply"
grep -q "radii estimated for 16000" "$work/err" && ok || bad "convert reports estimated radii"
"$bake" info "$work/oct3.ply" | grep -q "radius" && ok || bad "estimated radii are written"
# determinism: the same command twice gives the same bytes
"$bake" generate torus -o "$work/t1.qs" -q && "$bake" generate torus -o "$work/t2.qs" -q
cmp -s "$work/t1.qs" "$work/t2.qs" && ok || bad "generate is byte-identical across runs"
# a mesh is sampled into a point set (depth peeling), by either backend, with the same count
expect 0 "convert a mesh" -- "$bake" convert "$qsplat/pyr.ply" "$work/pyr.xyz" --ldi 64 --sampler gl
grep -q "sampled (gl" "$work/err" && ok || bad "convert reports the GL sampling: $(cat "$work/err")"
expect 0 "convert a mesh on the CPU" -- "$bake" convert "$qsplat/pyr.ply" "$work/pyr_cpu.xyz" --ldi 64 --sampler cpu
n_gl=$(wc -l <"$work/pyr.xyz") n_cpu=$(wc -l <"$work/pyr_cpu.xyz")
(( n_gl > 5000 && n_gl - n_cpu < 20 && n_cpu - n_gl < 20 )) && ok || bad "GL and CPU sample counts: $n_gl vs $n_cpu"
# --vertices: a mesh's vertices as the point set (an OFF with a blank line after its counts keeps all three)
printf "OFF\n3 1 0\n\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n" >"$work/blank.off"
expect 0 "convert a mesh's vertices" -- "$bake" convert "$work/blank.off" "$work/blank.xyz" --vertices
[[ $(wc -l <"$work/blank.xyz") == 3 && $(tail -1 "$work/blank.xyz") == "0 1 0" ]] && ok || bad "convert --vertices: $(cat "$work/blank.xyz")"
expect 2 "convert bad sampler" -- "$bake" convert "$qsplat/pyr.ply" "$work/pyr.xyz" --sampler vulkan
expect 0 "generate a mesh" -- "$bake" generate cube --mesh --subdivisions 2 -o "$work/cube_mesh.ply" -q
printf "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n" >"$work/notris.off"
expect 1 "convert a mesh without triangles" -- "$bake" convert "$work/notris.off" "$work/x.ply"
grep -q "mesh.no_triangles" "$work/err" && grep -q "notris.off" "$work/err" && ok || bad "mesh without triangles: $(cat "$work/err")"
# xyz has no normals: .qs needs them
printf "0 0 0\n1 0 0\n0 1 0\n" >"$work/p.xyz"
expect 1 "xyz without normals -> qs" -- "$bake" convert "$work/p.xyz" "$work/x.qs"
grep -q "convert.needs_normals" "$work/err" && ok || bad "qs output without normals names its error code"

# --- analyze: debug point set, Matrix Market output, thread independence ---
expect 0 "analyze" -- "$bake" analyze "$work/oct.ply" -o "$work/an.ply" --matrix "$work/a.mtx"
grep -q "fans: mean" "$work/err" && grep -q "time: neighbourhoods" "$work/err" && ok || bad "analyze prints its summary"
head -c 2000 "$work/an.ply" | grep -q "property float classifier" && ok || bad "analyze writes the classifier property"
head -c 2000 "$work/an.ply" | grep -q "property float variation" && ok || bad "analyze writes the variation property"
head -1 "$work/a.mtx" | grep -q "^%%MatrixMarket matrix coordinate real general" && ok || bad "matrix is Matrix Market"
/usr/bin/python3 - "$work/a.mtx" <<'PY' 2>"$work/err" && ok || bad "matrix: $(tail -2 "$work/err")"
import sys
rows = {}
with open(sys.argv[1]) as f:
    lines = [l for l in f if not l.startswith('%')]
n, m, nnz = map(int, lines[0].split())
assert n == m == 16000 and len(lines) - 1 == nnz, (n, m, nnz, len(lines))
entries = {}
for l in lines[1:]:
    i, j, v = l.split()
    entries[(int(i), int(j))] = float(v)
for (i, j), v in entries.items():
    assert entries.get((j, i)) == v, "not symmetric at %d %d" % (i, j)
sums, scale = {}, {}
for (i, j), v in entries.items():
    sums[i] = sums.get(i, 0.0) + v
    scale[i] = max(scale.get(i, 0.0), abs(v))
assert all(abs(sums[i]) <= 1e-12 * scale[i] for i in sums), "a row does not sum to 0"
PY
expect 0 "analyze 1 thread" -- "$bake" analyze "$work/oct.ply" -o "$work/an1.ply" --matrix "$work/a1.mtx" --threads 1 -q
cmp -s "$work/an.ply" "$work/an1.ply" && cmp -s "$work/a.mtx" "$work/a1.mtx" && ok || bad "analyze output differs between 1 and 2 threads"
expect 0 "analyze variation" -- "$bake" analyze "$work/oct.ply" -o "$work/anv.ply" --classifier variation -k 30 -q
cut -d' ' -f1-3 "$work/oct2.xyz" >"$work/bare.xyz"
expect 0 "analyze xyz without normals" -- "$bake" analyze "$work/bare.xyz" -o "$work/anx.ply"
grep -q "normals: estimated (PCA)" "$work/err" && ok || bad "analyze reports estimated normals"
expect 0 "analyze a mesh" -- "$bake" analyze "$qsplat/pyr.ply" -o "$work/m.ply" --ldi 32 -q
expect 2 "analyze bad classifier" -- "$bake" analyze "$work/oct.ply" -o "$work/x.ply" --classifier magic
expect 2 "analyze k out of range" -- "$bake" analyze "$work/oct.ply" -o "$work/x.ply" -k 1
printf "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n" >"$work/empty.ply"
expect 1 "analyze empty" -- "$bake" analyze "$work/empty.ply" -o "$work/x.ply"
grep -q "analyze.empty" "$work/err" && ok || bad "empty input names its error"
[[ ! -e "$work/x.ply" ]] && ok || bad "failed analyze left an output"

# --- decompose: levels, summary, basis dump, cache, merging ---
export QF_CACHE="$work/cache"
expect 0 "decompose" -- "$bake" decompose "$work/oct.ply" -o "$work/d1.ply" --summary "$work/l1.json" --basis-dump "$work/b1.txt" --level 5
grep -q "cache: miss (missing)" "$work/err" && ok || bad "first decompose misses the cache: $(cat "$work/err")"
expect 0 "decompose again" -- "$bake" decompose "$work/oct.ply" -o "$work/d2.ply" --summary "$work/l2.json" --basis-dump "$work/b2.txt" --level 5 --threads 1
grep -q "cache: hit" "$work/err" && ok || bad "second decompose hits the cache"
cmp -s "$work/d1.ply" "$work/d2.ply" && cmp -s "$work/b1.txt" "$work/b2.txt" && ok || bad "decompose outputs differ between a cache miss and a hit (1 vs 2 threads)"
diff <(grep -v '"hierarchy":\|"basis":' "$work/l1.json") <(grep -v '"hierarchy":\|"basis":' "$work/l2.json") >/dev/null && ok || bad "summaries differ beyond their times"
expect 0 "decompose without cache" -- "$bake" decompose "$work/oct.ply" -o "$work/d3.ply" --level 5 --no-cache -q
cmp -s "$work/d1.ply" "$work/d3.ply" && ok || bad "a rebuilt hierarchy gives other output"
/usr/bin/python3 - "$work/l1.json" "$work/b1.txt" <<'PY' 2>"$work/err" && ok || bad "summary or basis dump: $(tail -2 "$work/err")"
import json, sys
s = json.load(open(sys.argv[1]))
levels = s["levels"]
assert s["points"] == 16000 and levels[0]["functions"] == 16000 and s["chosen_level"] == 5
for a, b in zip(levels, levels[1:]):
    assert 1.8 <= a["functions"] / b["functions"] <= 3.5, (a["functions"], b["functions"])
    for key in ("ratio", "theta", "domain_points", "shared_points", "graph_edges", "uncovered_points"):
        assert key in b, key
n = 0
for line in open(sys.argv[2]):
    if line.startswith("#"):
        continue
    parts = line.split()
    assert int(parts[0]) == n
    weights = [float(p.split(":")[1]) for p in parts[1:]]
    assert all(w >= 0 for w in weights) and abs(sum(weights) - 1) < 1e-12, line
    n += 1
assert n == 16000
PY
/usr/bin/python3 -c 'import json, sys, jsonschema
jsonschema.validate(json.load(open(sys.argv[1])), json.load(open(sys.argv[2])))' "$work/l1.json" "$(dirname "$0")/../../schemas/levels.schema.json" 2>"$work/err" \
  && ok || bad "decompose --summary does not follow schemas/levels.schema.json: $(tail -3 "$work/err")"
corrupt=$(ls "$work/cache"/*.qfamg | head -1)
head -c 500 "$corrupt" >"$work/half" && cp "$work/half" "$corrupt"
expect 0 "decompose with a truncated cache" -- "$bake" decompose "$work/oct.ply" -o "$work/d4.ply" --level 5
grep -q "cache: miss (truncated)" "$work/err" && cmp -s "$work/d1.ply" "$work/d4.ply" && ok || bad "a truncated cache must be rebuilt: $(grep cache "$work/err")"
expect 0 "decompose --merge" -- "$bake" decompose "$work/oct.ply" -o "$work/m.ply" --level -1 --merge
grep -q "level [0-9]*: 8 basis functions" "$work/err" && ok || bad "merged octahedron has 8 domains: $(grep level "$work/err")"
expect 0 "decompose --level L" -- "$bake" decompose "$work/oct.ply" -o "$work/x.ply" --level L -q
expect 0 "decompose --primitives" -- "$bake" decompose "$work/oct.ply" -o "$work/x.ply" --primitives 40 --strict --tau 0.01 -q
expect 2 "decompose level out of range" -- "$bake" decompose "$work/oct.ply" -o "$work/x.ply" --level 99
expect 2 "decompose bad level" -- "$bake" decompose "$work/oct.ply" -o "$work/x.ply" --level abc
expect 2 "decompose level and primitives" -- "$bake" decompose "$work/oct.ply" -o "$work/x.ply" --level 2 --primitives 9

# --- bake (the main job): .glb per level, manifest, report; deterministic; nothing half-written ---
expect 0 "bake" -- "$bake" "$work/oct.ply" -o "$work/out1" --primitives 200,20
ls "$work/out1"/oct_L*.glb >/dev/null 2>&1 && [[ -f "$work/out1/manifest.json" && -f "$work/out1/report.json" ]] && ok || bad "bake outputs: $(ls "$work/out1")"
[[ -z "$(ls -A "$work/out1" | grep -v -E '^oct_[LS][0-9]+\.glb$|^manifest\.json$|^report\.(json|html)$')" ]] && ok || bad "bake left other files: $(ls -A "$work/out1")"
# a point set's mesh LODs: its surface reconstructed, then simplified; the manifest says so
ls "$work/out1"/oct_S*.glb >/dev/null 2>&1 && grep -q '"advancing front (CGAL)"' "$work/out1/manifest.json" && ok || bad "a point set's reconstruction LODs: $(ls "$work/out1")"
expect 0 "bake again, 1 thread" -- "$bake" bake "$work/oct.ply" -o "$work/out2" --primitives 200,20 --threads 1 -q
for f in "$work/out1"/*.glb "$work/out1/manifest.json"; do
  cmp -s "$f" "$work/out2/$(basename "$f")" && ok || bad "bake output $(basename "$f") differs between runs"
done
/usr/bin/python3 - "$work/out1/manifest.json" <<'PY' 2>"$work/err" && ok || bad "manifest: $(tail -2 "$work/err")"
import json, os, sys
m = json.load(open(sys.argv[1]))
assert m["points"] == 16000 and len(m["levels"]) == 2
for l in m["levels"]:
    assert os.path.getsize(os.path.join(os.path.dirname(sys.argv[1]), l["file"])) > 1000
    assert l["primitives"] > 0 and l["texels"] > 0 and l["error"] > 0 and l["max_screen_pixels"] > 0
assert m["levels"][0]["primitives"] > m["levels"][1]["primitives"]
# the input's facts: a point set's format, bytes and points as read
s = m["source"]
assert s["format"].startswith("ply") and s["points"] == 16000 and s["files"] == 1, s
assert s["bytes"] == os.path.getsize(os.path.join(os.path.dirname(sys.argv[1]), "..", "oct.ply")), s
assert "triangles" not in s and "tool_version" not in m and "gl" not in m, m.keys()
PY
# KTX2 textures (issue 32): every texture a KHR_texture_basisu KTX2 image, the extension required;
# the manifest's GPU bytes a quarter of the PNG levels' (1 byte a texel instead of 4), texture bytes
# within the file's; the same bytes at 1 thread; its options refused without it.
expect 0 "bake --textures ktx2" -- "$bake" "$work/oct.ply" -o "$work/ktx1" --primitives 200,20 --textures ktx2 --no-measure -q
expect 0 "bake --textures ktx2, 1 thread" -- "$bake" "$work/oct.ply" -o "$work/ktx2" --primitives 200,20 --textures ktx2 --no-measure --threads 1 -q
for f in "$work/ktx1"/*.glb; do
  cmp -s "$f" "$work/ktx2/$(basename "$f")" && ok || bad "KTX2 output $(basename "$f") differs at 1 thread"
done
/usr/bin/python3 - "$work/out1/manifest.json" "$work/ktx1/manifest.json" "$work/ktx1/report.json" <<'PY' 2>"$work/err" && ok || bad "KTX2 bake: $(tail -2 "$work/err")"
import json, os, struct, sys
png, ktx = (json.load(open(f)) for f in sys.argv[1:3])
assert json.load(open(sys.argv[3]))["settings"]["textures"] == "ktx2"
for p, k in zip(png["levels"], ktx["levels"]):
    # A quarter, plus the whole 4x4 blocks of the levels under 4 texels a side.
    assert p["atlas_sides"] == k["atlas_sides"] and p["gpu_bytes"] <= 4 * k["gpu_bytes"] <= 1.001 * p["gpu_bytes"], (p, k)
    assert 0 < k["texture_bytes"] < k["bytes"] and 0 < p["texture_bytes"] < p["bytes"]
    data = open(os.path.join(os.path.dirname(sys.argv[2]), k["file"]), "rb").read()
    doc = json.loads(data[20:20 + struct.unpack_from("<I", data, 12)[0]])
    assert sorted(doc["extensionsRequired"]) == ["KHR_mesh_quantization", "KHR_texture_basisu"], doc["extensionsRequired"]
    for t in doc["textures"]:
        assert "source" not in t and doc["images"][t["extensions"]["KHR_texture_basisu"]["source"]]["mimeType"] == "image/ktx2"
PY
expect 2 "--ktx2-color needs --textures ktx2" -- "$bake" "$work/oct.ply" -o "$work/ktx_x" --ktx2-color uastc -q
expect 2 "--textures takes png, ktx2 or webp" -- "$bake" "$work/oct.ply" -o "$work/ktx_x" --textures jpeg -q
# WebP (the webp test checks its bakes): its options need it, and take lossless or a quality 1..100.
expect 2 "--webp-color needs --textures webp" -- "$bake" "$work/oct.ply" -o "$work/ktx_x" --webp-color 80 -q
expect 2 "--webp-normal takes lossless or 1..100" -- "$bake" "$work/oct.ply" -o "$work/ktx_x" --textures webp --webp-normal 101 -q
[[ ! -e "$work/ktx_x" ]] && ok || bad "a refused --textures left $work/ktx_x"
"$bake" bake --help >"$work/out"
grep -A8 -- "--textures png|ktx2|webp" "$work/out" | grep -q "(default: png)" && ok || bad "bake --help gives --textures' default"
grep -A1 -- "--webp-normal Q|lossless" "$work/out" | grep -q "(default: " && ok || bad "bake --help gives --webp-normal's default"

# Texels sized for the screen (--texel-density, default 1): each level's texel is at least one screen
# pixel where it is drawn largest, so it holds at most (4 x max_screen_pixels)^2 texels; the manifest
# gives texel, atlas sides and bytes. --texel alone fixes the texel at every level instead.
# (The 7-quad level's domains straddle creases: a large error, drawn small.)
expect 0 "bake, default texels" -- "$bake" "$work/oct.ply" -o "$work/tx0" --primitives 200,8 -q
expect 0 "bake --texel (fixed texels)" -- "$bake" "$work/oct.ply" -o "$work/tx1" --primitives 200,8 --texel 1 -q
expect 0 "bake --texel-density 4" -- "$bake" "$work/oct.ply" -o "$work/tx4" --primitives 200,8 --texel-density 4 -q
/usr/bin/python3 - "$work/tx0" "$work/tx1" "$work/tx4" <<'PY' 2>"$work/err" && ok || bad "texel budget: $(tail -2 "$work/err")"
import json, os, struct, sys
def load(d):
    return json.load(open(os.path.join(d, "manifest.json"))), json.load(open(os.path.join(d, "report.json")))
(m1, r1), (mx, rx), (m4, r4) = (load(d) for d in sys.argv[1:4])
diag = m1["bounding_box_diagonal"]
assert r1["settings"]["texel_density"] == 1 and rx["settings"]["texel_density"] == 0 and r4["settings"]["texel_density"] == 4
for l in m1["levels"]:
    # Textures are sized before the level is measured: for its geometric size (rounded down), at
    # most 1024 px, the largest size the measuring draws.
    px = min(l["geometric_max_screen_pixels"], 1024)
    assert diag / (px + 1) <= l["texel"] <= diag / px * (1 + 1e-6), (l["texel"], diag, px)
    assert l["quad_texels"] <= (4 * px) ** 2, (l["quad_texels"], px)
    assert l["bytes"] == os.path.getsize(os.path.join(sys.argv[1], l["file"]))
    assert len(l["atlas_sides"]) == l["atlas_images"] and all(w & (w - 1) == 0 and h & (h - 1) == 0 for w, h in l["atlas_sides"])
assert all(l["texel"] == 0 for l in mx["levels"])
coarse = [m["levels"][1] for m in (m1, mx, m4)]
assert coarse[0]["quad_texels"] < coarse[2]["quad_texels"] < coarse[1]["quad_texels"], [c["quad_texels"] for c in coarse]
# texels: every image of the file as uploaded (the colour atlas and its half-size normal map)
assert all(l["texels"] == sum(w * h + (w // 2) * (h // 2) for w, h in l["atlas_sides"]) for l in m1["levels"]), m1["levels"]
assert coarse[0]["bytes"] < coarse[1]["bytes"]
# PNG colour types in the finest level: colour atlases RGBA (6), normal maps RGB (2, no unused alpha).
b = open(os.path.join(sys.argv[1], m1["levels"][0]["file"]), "rb").read()
n = struct.unpack("<I", b[12:16])[0]
g, binary = json.loads(b[20:20 + n]), 20 + n + 8
def colour_type(texture):
    v = g["bufferViews"][g["images"][g["textures"][texture]["source"]]["bufferView"]]
    png = b[binary + v.get("byteOffset", 0):]
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and png[12:16] == b"IHDR"
    return png[25]
mat = g["materials"][0]
assert colour_type(mat["pbrMetallicRoughness"]["baseColorTexture"]["index"]) == 6
assert colour_type(mat["normalTexture"]["index"]) == 2
PY
# a mesh input: sampled, then baked; the report carries the sampling
expect 0 "generate a finer mesh" -- "$bake" generate sphere --mesh --subdivisions 8 -o "$work/ball_mesh.ply" -q
expect 0 "bake a mesh" -- "$bake" "$work/ball_mesh.ply" -o "$work/meshbake" --primitives 50 --ldi 64 --points -q
[[ ! -s "$work/err" ]] && ok || bad "bake -q prints nothing: $(head -c 300 "$work/err")"
# without -q, a log (not a terminal) gets a progress line every QF_PROGRESS_SECONDS, then the summary
QF_PROGRESS_SECONDS=0.05 expect 0 "bake with progress" -- "$bake" "$work/ball_mesh.ply" -o "$work/meshbake_p" --primitives 50 --ldi 64 --no-chain
# (any step: which ones last past 0.05 s depends on the machine and the hierarchy cache)
grep -qE '^qf-bake bake: [0-9]+ s, (sampling|analysis|basis functions|level [0-9]+: )' "$work/err" && ok || bad "bake shows its progress: $(head -c 300 "$work/err")"
grep -q $'\r' "$work/err" && bad "progress in a log has no carriage returns" || ok
grep -q "^qf-bake: .* -> " "$work/err" && ok || bad "bake prints its summary after the progress"
# mesh-only options on a point set: said, not silently ignored
expect 0 "generate points" -- "$bake" generate octahedron --points 4000 -o "$work/octp.ply" -q
expect 0 "bake points with mesh options" -- "$bake" "$work/octp.ply" -o "$work/octp" --ldi 64 --points --primitives 30 --no-measure
grep -q "warning: --ldi, --points apply to mesh inputs only; this input is a point set: ignored" "$work/err" && ok || bad "mesh-only options on a point set warned: $(head -c 300 "$work/err")"
grep -q "mesh inputs only" "$work/octp/report.json" && ok || bad "the report keeps the mesh-only options' warning"
QF_PROGRESS_SECONDS=soon expect 2 "QF_PROGRESS_SECONDS malformed" -- "$bake" "$work/ball_mesh.ply" -o "$work/meshbake_bad" -q
grep -q "QF_PROGRESS_SECONDS" "$work/err" && [[ ! -e "$work/meshbake_bad" ]] && ok || bad "malformed QF_PROGRESS_SECONDS named, nothing written"
/usr/bin/python3 -c 'import json,sys; s=json.load(open(sys.argv[1]))["sampling"]; assert s["ldi_size"]==64 and s["backend"]=="cpu" and sum(s["points_per_axis"])>1000' \
  "$work/meshbake/report.json" 2>"$work/err" && ok || bad "bake report sampling: $(tail -1 "$work/err")"
/usr/bin/python3 - "$work/meshbake" <<'PY' 2>"$work/err" && ok || bad "mesh bake outputs: $(tail -1 "$work/err")"
import json, os, sys
d = sys.argv[1]
m = json.load(open(os.path.join(d, "manifest.json")))
assert os.path.getsize(os.path.join(d, m["point_impostor"]["file"])) > 1000
lods = m["mesh_lods"]["levels"]
assert m["mesh_lods"]["method"] == "simplify" and len(lods) >= 2, m["mesh_lods"]
assert all(os.path.exists(os.path.join(d, l["file"])) and l["file"].endswith(f"_S{i}.glb") for i, l in enumerate(lods))
assert all(a["triangles"] > b["triangles"] and a["error"] <= b["error"] and a["geometric_max_screen_pixels"] >= b["geometric_max_screen_pixels"]
           for a, b in zip(lods, lods[1:])), lods
PY
# --mesh-lods clustering: seed 002's vertex-clustering LODs instead (cell widths d/128..d/8)
expect 0 "bake a mesh with clustering LODs" -- "$bake" "$work/ball_mesh.ply" -o "$work/meshbake_c" --primitives 50 --ldi 64 --mesh-lods clustering -q
expect 0 "a mesh too small to simplify" -- "$bake" "$work/cube_mesh.ply" -o "$work/meshbake_s" --primitives 20 --ldi 64 --cheap-triangles 0 -q
# simplify: a budget above the mesh's triangles keeps it whole; simplifySloppy's 1 triangle of a
# cube leaves nothing, a usage error naming the budget, with nothing written.
expect 0 "simplify above the mesh's budget" -- "$bake" simplify "$work/cube_mesh.ply" -o "$work/simp_big" --triangles 100000 -q
expect 0 "simplify --method sloppy" -- "$bake" simplify "$work/cube_mesh.ply" -o "$work/simp_sloppy" --triangles 24 --method sloppy -q
expect 2 "sloppy budget that leaves nothing" -- "$bake" simplify "$work/cube_mesh.ply" -o "$work/simp_none" --triangles 1 --method sloppy -q
grep -q "budget of 1 triangles" "$work/err" && [[ ! -e "$work/simp_none" ]] && ok || bad "an empty LOD: $(cat "$work/err")"
# The generated impostor cases are seeded (same seed, same bytes; another seed, another asset), and
# the crossed billboard peer keeps within a byte budget; a point set has no triangles to draw.
for shape in bush lattice; do
  expect 0 "generate $shape" -- "$bake" generate "$shape" --seed 5 -o "$work/$shape.glb" -q
  "$bake" generate "$shape" --seed 5 -o "$work/${shape}2.glb" -q && cmp -s "$work/$shape.glb" "$work/${shape}2.glb" && ok ||
    bad "generate $shape is not deterministic"
  "$bake" generate "$shape" --seed 6 -o "$work/${shape}3.glb" -q && ! cmp -s "$work/$shape.glb" "$work/${shape}3.glb" && ok ||
    bad "generate $shape: the seed changes nothing"
done
expect 0 "billboard" -- "$bake" billboard "$work/lattice.glb" -o "$work/bb.glb" --bytes 20000 -q
[[ -s "$work/bb.glb" && $(stat -c %s "$work/bb.glb") -le 20000 ]] && ok || bad "billboard over its byte budget: $(stat -c %s "$work/bb.glb")"
expect 1 "billboard of a point set" -- "$bake" billboard "$work/oct.ply" -o "$work/bb_points.glb" -q
grep -q "billboard.needs_mesh" "$work/err" && [[ ! -e "$work/bb_points.glb" ]] && ok || bad "billboard of a point set: $(cat "$work/err")"
/usr/bin/python3 -c 'import json,sys; m=json.load(open(sys.argv[1])); assert "mesh_lods" not in m' "$work/meshbake_s/manifest.json" 2>"$work/err" && ok ||
  bad "48 triangles get no simplify LODs: $(tail -1 "$work/err")"
/usr/bin/python3 - "$work/meshbake_c" <<'PY' 2>"$work/err" && ok || bad "clustering mesh LODs: $(tail -1 "$work/err")"
import json, os, sys
d = sys.argv[1]
m = json.load(open(os.path.join(d, "manifest.json")))
lods = m["mesh_lods"]["levels"]
assert m["mesh_lods"]["method"] == "clustering" and len(lods) == 5 and all(os.path.exists(os.path.join(d, l["file"])) for l in lods)
assert lods[0]["cell_width"] < lods[-1]["cell_width"] and lods[0]["triangles"] >= lods[-1]["triangles"]
assert not any(f.endswith("_S0.glb") for f in os.listdir(d))
PY
expect 2 "--mesh-lods takes a known method" -- "$bake" "$work/cube_mesh.ply" -o "$work/meshbake_x" --mesh-lods decimate -q
# cluster: vertex-clustering LODs of a mesh, a manifest with cell widths, same bytes twice
expect 0 "cluster" -- "$bake" cluster "$work/cube_mesh.ply" -o "$work/cl1" --cells 0.2,0.5,1 --draco
expect 0 "cluster again" -- "$bake" cluster "$work/cube_mesh.ply" -o "$work/cl2" --cells 0.2,0.5,1 --draco -q
[[ $(ls "$work/cl1"/*.draco.glb | wc -l) == 3 ]] && ok || bad "cluster --draco writes a Draco variant per level"
for f in "$work/cl1"/*.glb; do cmp -s "$f" "$work/cl2/$(basename "$f")" && ok || bad "cluster output $(basename "$f") differs between runs"; done
/usr/bin/python3 -c 'import json,sys; m=json.load(open(sys.argv[1])); assert [l["cell_width"] for l in m["levels"]]==[0.2,0.5,1.0] and m["levels"][0]["triangles"]>=m["levels"][2]["triangles"]' \
  "$work/cl1/manifest.json" 2>"$work/err" && ok || bad "cluster manifest: $(tail -1 "$work/err")"
expect 1 "cluster a point set" -- "$bake" cluster "$work/oct.ply" -o "$work/cl3"
grep -q "cluster.needs_mesh" "$work/err" && ok || bad "cluster of points names its error"
expect 2 "cluster bad shape" -- "$bake" cluster "$work/cube_mesh.ply" -o "$work/cl3" --shape blob
# --lod-file: every level in one MSFT_lod file beside the level files, deterministic too
expect 0 "bake --lod-file" -- "$bake" "$work/oct.ply" -o "$work/lod1" --primitives 200,20 --lod-file -q
expect 0 "bake --lod-file, 1 thread" -- "$bake" "$work/oct.ply" -o "$work/lod2" --primitives 200,20 --lod-file --threads 1 -q
cmp -s "$work/lod1/oct_lods.glb" "$work/lod2/oct_lods.glb" && ok || bad "the MSFT_lod file differs between runs"
grep -q '"file": "oct_lods.glb"' "$work/lod1/manifest.json" && ok || bad "the manifest names the MSFT_lod file"
# without input normals: estimated ones light the normal maps, also after a cache hit
expect 0 "bake without normals" -- "$bake" "$work/bare.xyz" -o "$work/nb1" --primitives 100 -q
expect 0 "bake without normals, cached" -- "$bake" "$work/bare.xyz" -o "$work/nb2" --primitives 100
grep -q "cache: hit" "$work/err" && ok || bad "second bake of bare.xyz hits the cache"
for f in "$work"/nb1/*.glb; do cmp -s "$f" "$work/nb2/$(basename "$f")" || bad "cache hit and miss bake different bytes: $(basename "$f")"; done; ok
grep -aq '"normalTexture"' "$(ls "$work"/nb1/*_L*.glb)" && ok || bad "no normal map for a set without normals"
printf "0 0 0\n1 0 0\n0 1 0\n" >"$work/tiny.xyz"
expect 1 "bake too few points" -- "$bake" "$work/tiny.xyz" -o "$work/out3"
grep -q "bake.too_small" "$work/err" && ok || bad "tiny input names its error"
[[ -z "$(ls -A "$work/out3" 2>/dev/null)" ]] && ok || bad "a failed bake left files: $(ls -A "$work/out3")"
for i in $(seq 0 99); do echo "$i $((2 * i)) 0"; done >"$work/line.xyz"
expect 1 "bake collinear points" -- "$bake" "$work/line.xyz" -o "$work/out4"
[[ -z "$(ls -A "$work/out4" 2>/dev/null)" ]] && ok || bad "a failed bake left files"
expect 2 "bake bad primitives" -- "$bake" "$work/oct.ply" -o "$work/out5" --primitives 10,x
expect 2 "bake level out of range" -- "$bake" "$work/oct.ply" -o "$work/out5" --levels 99
# Outliers (--outliers, default 10): the scan-like sample's strays (every 500th point, anywhere in
# the scene's box; a few land near a surface and stay) are dropped and reported; 0 keeps them all.
"$bake" generate scan -n 20000 -o "$work/scan.ply" -q
lean=(--primitives 100,30 --no-measure --no-report-html --no-mesh-lods -q)
expect 0 "bake a scan" -- "$bake" "$work/scan.ply" -o "$work/scan_out" "${lean[@]}"
/usr/bin/python3 -c 'import json, sys; r = json.load(open(sys.argv[1]))
assert 30 <= r["dropped_outliers"] <= 40 and r["points"] + r["dropped_outliers"] == 20000 and r["settings"]["outliers"] == 10, r["dropped_outliers"]' \
  "$work/scan_out/report.json" 2>"$work/err" && ok || bad "the scan's strays dropped: $(tail -1 "$work/err")"
expect 0 "bake a scan keeping its outliers" -- "$bake" "$work/scan.ply" -o "$work/scan_all" "${lean[@]}" --outliers 0
/usr/bin/python3 -c 'import json, sys; r = json.load(open(sys.argv[1])); assert (r["dropped_outliers"], r["points"]) == (0, 20000), r["points"]' \
  "$work/scan_all/report.json" 2>"$work/err" && ok || bad "--outliers 0 keeps every point: $(tail -1 "$work/err")"
expect 2 "bake a negative outlier factor" -- "$bake" "$work/scan.ply" -o "$work/out5" --outliers -1
# A factor that takes clean points too (1.5 x the median spacing cuts into the scan's far, sparse
# ground) is baked, with a warning that names the count and the way back.
expect 0 "bake a scan with a tight outlier factor" -- "$bake" "$work/scan.ply" -o "$work/scan_tight" "${lean[@]}" --outliers 1.5
/usr/bin/python3 -c 'import json, sys; r = json.load(open(sys.argv[1]))
assert r["dropped_outliers"] > 200 and any("more than 1%" in w and "--outliers" in w for w in r["warnings"]), (r["dropped_outliers"], r["warnings"])' \
  "$work/scan_tight/report.json" 2>"$work/err" && ok || bad "a tight --outliers warns past 1%: $(tail -1 "$work/err")"
unset QF_CACHE

# --- LAS and LAZ (issue 35): info with the header's facts, convert carries the classification, bake end to end ---
las=$data/las
expect 0 "info LAZ" -- "$bake" info "$las/points_f7.laz"
grep -q "format: *laz 1.4 (point format 7)" "$work/out" && grep -q "scalars: *classification" "$work/out" \
  && grep -q "origin: *512" "$work/out" && ok || bad "info of a LAZ file: $(cat "$work/out")"
"$bake" info --json "$las/points_f3.laz" >"$work/info.json"
/usr/bin/python3 -c 'import json, sys, jsonschema
j = json.load(open(sys.argv[1])); jsonschema.validate(j, json.load(open(sys.argv[2])))
assert j["points"] == 2000 and j["header"]["point_format"] == "3" and j["scalars"] == ["classification"], j' \
  "$work/info.json" "$schema" 2>"$work/err" && ok || bad "info --json of a LAZ file: $(tail -3 "$work/err")"
"$bake" info --json "$las/points_f3.las" >"$work/info_las.json"
/usr/bin/python3 -c 'import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
assert a["bounds"] == b["bounds"] and a["points"] == b["points"], (a["bounds"], b["bounds"])' \
  "$work/info_las.json" "$work/info.json" 2>"$work/err" && ok || bad "the LAS and the LAZ of one point set differ: $(tail -2 "$work/err")"
cp "$las/points_f3.laz" "$work/compressed.las"  # the header, not the extension, says LAZ
"$bake" info "$work/compressed.las" | grep -q "format: *laz 1.2 (point format 3)" && ok || bad "a LAZ file named .las"
expect 0 "convert LAS to PLY" -- "$bake" convert "$las/points_f6.las" "$work/las.ply"
head -c 400 "$work/las.ply" | grep -q "property float classification" && ok || bad "converted LAS keeps its classification"
expect 0 "bake a LAS file" -- "$bake" "$las/points_f3.las" -o "$work/las_out" --primitives 100,30
ls "$work/las_out"/points_f3_L*.glb >/dev/null 2>&1 && [[ -f "$work/las_out/manifest.json" ]] && ok || bad "bake of a LAS file: $(ls "$work/las_out")"
expect 0 "bake a LAZ file" -- "$bake" "$las/points_f7.laz" -o "$work/laz_out" --primitives 100,30
ls "$work/laz_out"/points_f7_L*.glb >/dev/null 2>&1 && ok || bad "bake of a LAZ file: $(ls "$work/laz_out")"

# --- every malformed file: exit 1, message names file and code, no output ---
while IFS=$'\t' read -r file code; do
  [[ -z "$file" || "$file" == \#* ]] && continue
  mkdir -p "$work/m"
  expect 1 "info $file" -- "$bake" info "$data/malformed/$file"
  grep -qF "$file" "$work/err" && grep -qF "[$code]" "$work/err" && ok || bad "$file: message lacks file or [$code]: $(cat "$work/err")"
  expect 1 "convert $file" -- "$bake" convert "$data/malformed/$file" "$work/m/out.ply"
  [[ -z "$(ls -A "$work/m")" ]] && ok || bad "$file: convert left files behind: $(ls -A "$work/m")"
done <"$data/malformed/EXPECTED.tsv"
# non-finite coordinates can be dropped on request, and are reported
expect 0 "--drop-nonfinite" -- "$bake" convert "$data/malformed/nan_coordinate.ply" "$work/ok.xyz" --drop-nonfinite
grep -q "1 non-finite points dropped" "$work/err" && ok || bad "dropped points are reported"

# an existing output survives a failed conversion untouched
echo "keep me" >"$work/keep.ply"
"$bake" convert "$data/malformed/count_lies_binary.ply" "$work/keep.ply" 2>/dev/null
[[ "$(cat "$work/keep.ply")" == "keep me" ]] && ok || bad "a failed convert must not touch an existing output"

echo "$pass passed, $fail failed"
[[ $fail -eq 0 ]]
