#!/usr/bin/env bash
# Out-of-core bakes (issue 35 item 2): a point set past --max-memory is decomposed on a subsample
# and textured from every point read back from a scratch file. Checks: the path runs and says so
# (report memory, manifest out_of_core), peak memory under the limit, quad counts within 5% of the
# in-memory bake's, the look close to it (qf-render eval of both against the input), the scratch
# file gone afterwards and after a SIGTERM mid-bake, the same bytes at 1 and 2 threads, bad
# --max-memory values refused (exit 2), a mesh past the limit refused (bake.memory, exit 1).
# usage: out_of_core_test.sh QF_BAKE QF_RENDER
set -u
bake=$1 render=$2
source "$(dirname "$0")/test_lib.sh"

# 120k points need ~520 MB in memory (384 + 1.35 x 120k x 840 bytes); 440M leaves the subsample
# 0.65 x 56 MB / 840 bytes = ~45k points (stride ~2.7).
"$bake" generate torus -n 120000 -o "$work/torus.ply" -q
limit=440M
opts=(--primitives 300,100,30 --aim-primitives --no-measure --no-report-html --no-mesh-lods -q)
mkdir -p "$work/tmp" "$work/tmp2"

# --- 1. in memory, then out of core (forced by --max-memory) ---
"$bake" "$work/torus.ply" -o "$work/mem" "${opts[@]}" || bad "the in-memory bake failed"
[[ $(field "$work/mem/report.json" 'r["memory"]["path"]') == in-memory ]] && ok || bad "the plain bake ran in memory"
TMPDIR=$work/tmp "$bake" "$work/torus.ply" -o "$work/ooc" --max-memory $limit "${opts[@]}" --threads 2 || bad "the out-of-core bake failed"
[[ $(field "$work/ooc/report.json" 'r["memory"]["path"], r["memory"]["limit_source"]') == "('out-of-core', '--max-memory')" ]] && ok ||
  bad "the report says out-of-core under --max-memory: $(field "$work/ooc/report.json" 'r["memory"]')"
field "$work/ooc/manifest.json" 'r["out_of_core"]["subsample_points"], r["out_of_core"]["scratch_bytes"]' | grep -q "^([0-9]*, [1-9][0-9]*)$" &&
  ok || bad "the manifest names the subsample and the scratch bytes: $(field "$work/ooc/manifest.json" 'r.get("out_of_core")')"
[[ $(field "$work/ooc/report.json" 'r["memory"]["peak_mb"] < 440') == True ]] && ok ||
  bad "peak memory under the limit: $(field "$work/ooc/report.json" 'r["memory"]["peak_mb"]') MB"
[[ -z $(ls -A "$work/tmp") ]] && ok || bad "the scratch file is removed: $(ls "$work/tmp")"

# --- 2. as close to the in-memory bake as the subsample allows ---
# Both aimed at the counts (--aim-primitives): within 5%, or 2 quads where 5% is less (the aim
# lands within a quad of 30 either side: 31 and 29 here).
python3 - "$work/mem/manifest.json" "$work/ooc/manifest.json" <<'PY' && ok || bad "quad counts within 5% of the in-memory bake's"
import json, sys
a, b = (json.load(open(p))["levels"] for p in sys.argv[1:3])
for x, y in zip(a, b):
    print(f"quads in memory {x['primitives']}, out of core {y['primitives']}")
    assert abs(y["primitives"] - x["primitives"]) <= max(2, 0.05 * x["primitives"]), (x["primitives"], y["primitives"])
PY
for k in 0 1 2; do
  mem=$(field "$work/mem/manifest.json" "r['levels'][$k]['file']")
  ooc=$(field "$work/ooc/manifest.json" "r['levels'][$k]['file']")
  "$render" eval "$work/torus.ply" "$work/mem/$mem" --size 128 --views 6 --truth 4 -m engine -o "$work/em$k.json" 2>/dev/null &&
    "$render" eval "$work/torus.ply" "$work/ooc/$ooc" --size 128 --views 6 --truth 4 -m engine -o "$work/eo$k.json" 2>/dev/null ||
    { bad "eval of level $k"; continue; }
  # A subsample of one point in ~2.7 decomposes into other quads than the whole set: measured
  # here +0.40 / +0.01 / +0.08 dB and +0.003 / -0.008 / +0.010 IoU at 300 / 100 / 30 quads (two
  # in-memory bakes of the torus sampled with seeds 1 and 2, 250k points, differ by up to 0.37 dB
  # and 0.019 IoU at their own sizes: another sampling is another decomposition).
  python3 - "$work/em$k.json" "$work/eo$k.json" <<'PY' && ok || bad "level $k: the out-of-core look is within 1 dB and 0.02 IoU of the in-memory one"
import json, sys
a, b = (json.load(open(p))["mean"]["engine"] for p in sys.argv[1:3])
print(f"in memory {a['psnr']:.2f} dB IoU {a['iou']:.4f}, out of core {b['psnr']:.2f} dB IoU {b['iou']:.4f}")
sys.exit(0 if b["psnr"] >= a["psnr"] - 1.0 and abs(b["iou"] - a["iou"]) <= 0.02 else 1)
PY
done

# --- 3. the same bytes at 1 thread ---
TMPDIR=$work/tmp "$bake" "$work/torus.ply" -o "$work/ooc1" --max-memory $limit "${opts[@]}" --threads 1 || bad "the 1-thread bake failed"
for f in "$work"/ooc/*.glb "$work/ooc/manifest.json"; do
  cmp -s "$f" "$work/ooc1/$(basename "$f")" && ok || bad "$(basename "$f") differs at 1 thread"
done

# --- 4. SIGTERM mid-bake: the scratch file goes with the process, nothing is written ---
TMPDIR=$work/tmp2 "$bake" "$work/torus.ply" -o "$work/killed" --max-memory $limit "${opts[@]}" --no-cache &
pid=$!
for _ in $(seq 1 200); do
  compgen -G "$work/tmp2/qf-bake-*.scratch" >/dev/null && break
  sleep 0.05
done
compgen -G "$work/tmp2/qf-bake-*.scratch" >/dev/null && ok || bad "no scratch file seen in TMPDIR while baking"
kill -TERM $pid
wait $pid; rc=$?
[[ $rc -eq 143 ]] && ok || bad "a bake stopped by SIGTERM ends by it (exit 143), got $rc"
[[ -z $(ls -A "$work/tmp2") ]] && ok || bad "the scratch file is removed on SIGTERM: $(ls "$work/tmp2")"
[[ ! -e $work/killed/manifest.json ]] && ok || bad "a killed bake writes no manifest"

# --- 5. bad limits: usage errors; a mesh past the limit: refused with the figures ---
for v in lots 0 1.5G -4G 4X; do
  "$bake" "$work/torus.ply" -o "$work/bad" --max-memory "$v" "${opts[@]}" 2>"$work/err"; rc=$?
  [[ $rc -eq 2 ]] && grep -q -- "--max-memory" "$work/err" && ok || bad "--max-memory $v: exit 2 naming the option, got $rc: $(cat "$work/err")"
done
"$bake" generate tree -o "$work/tree.glb" -q
"$bake" "$work/tree.glb" -o "$work/tree" --max-memory 390M "${opts[@]}" 2>"$work/err"; rc=$?
[[ $rc -eq 1 ]] && grep -q "not streamed.*\[bake.memory\]" "$work/err" && ok || bad "a mesh past --max-memory: exit 1, bake.memory, got $rc: $(cat "$work/err")"
[[ ! -e $work/bad/manifest.json && ! -e $work/tree/manifest.json ]] && ok || bad "nothing written for a refused bake"

# --- 6. streamed from the file (issue 35 item 1): a PLY or LAS past the limit is never read whole ---
[[ $(field "$work/ooc/report.json" 'r["memory"]["input"]') == streamed ]] && ok ||
  bad "the out-of-core bake of a PLY streamed it: $(field "$work/ooc/report.json" 'r["memory"]')"
[[ $(field "$work/mem/report.json" 'r["memory"]["input"]') == "read whole" ]] && ok || bad "the in-memory bake read its input whole"
# A file that breaks while it streams: exit 1 naming it and the code, nothing written, no scratch left.
head -c 2000000 "$work/torus.ply" >"$work/cut.ply"
TMPDIR=$work/tmp "$bake" "$work/cut.ply" -o "$work/cut" --max-memory $limit "${opts[@]}" 2>"$work/err"; rc=$?
[[ $rc -eq 1 ]] && grep -q "cut.ply.*\[ply.body.truncated\]" "$work/err" && ok || bad "a cut PLY streamed: exit 1, ply.body.truncated, got $rc: $(cat "$work/err")"
[[ ! -e $work/cut/manifest.json && -z $(ls -A "$work/tmp") ]] && ok || bad "a failed streamed bake leaves nothing: $(ls "$work/cut" "$work/tmp" 2>&1)"
# A scan's strays are judged on the subsample and the links: the generator makes 0.2% of its
# points strays (240 of 120k); the in-memory rule drops 222 of them here.
"$bake" generate scan -n 120000 -o "$work/scan.ply" -q
TMPDIR=$work/tmp "$bake" "$work/scan.ply" -o "$work/scan" --max-memory $limit "${opts[@]}" || bad "the streamed scan bake failed"
python3 - "$work/scan/report.json" <<'PY' && ok || bad "the streamed scan drops its strays"
import json, sys
r = json.load(open(sys.argv[1]))
print(f"dropped {r['dropped_outliers']} outliers of {r['points'] + r['dropped_outliers']} points, {r['memory']['input']}")
assert r["memory"]["path"] == "out-of-core" and r["memory"]["input"] == "streamed"
assert 150 <= r["dropped_outliers"] <= 300, r["dropped_outliers"]
PY
finish out_of_core
