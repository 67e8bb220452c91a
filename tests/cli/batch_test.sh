#!/usr/bin/env bash
# qf-bake batch end to end, on small generated inputs: a second run does no work; changing one
# input's bytes rebakes only it (touching its time does not); a corrupt input fails alone with
# its file and reason; shards 1/3..3/3 together write exactly the unsharded files; a batch killed
# with SIGKILL and rerun ends with the same files as an uninterrupted one; merge-reports; the
# manifest and report against their schemas; bad manifests are rejected with their location.
# usage: batch_test.sh QF_BAKE SCHEMA_DIR
set -u
bake=$1 schemas=$2
source "$(dirname "$0")/test_lib.sh"
# Every file of the asset folders under DIR with its checksum; report.json (times) left out.
listing() { (cd "$1" && find . -path ./batch-report\* -prune -o -type f ! -name report.json -print0 | sort -z | xargs -0 sha256sum); }

# --- inputs: point sets and meshes ---
mkdir -p "$work/in"
"$bake" generate octahedron -n 3000 -o "$work/in/octa.ply" -q
"$bake" generate sphere -n 2500 --seed 2 -o "$work/in/ball.xyz" -q
"$bake" generate torus -n 3000 -o "$work/in/ring.ply" -q
"$bake" generate cube --mesh --subdivisions 6 -o "$work/in/box.ply" -q
"$bake" generate sphere --mesh --subdivisions 5 -o "$work/in/globe.ply" -q
"$bake" generate cube -n 2000 -o "$work/in/cube.qs" -q
cat >"$work/batch.json" <<JSON
{"\$schema": "../schemas/batch.schema.json", "output": "out",
 "defaults": {"primitives": [100, 20], "ldi": 96, "cheap-triangles": 0},
 "assets": ["in/octa.ply", "in/ball.xyz", {"input": "in/ring.ply", "settings": {"merge": true, "tau": 0.1}},
            {"input": "in/box.ply", "name": "box-mesh"}, {"input": "in/globe.ply", "settings": {"points": true}},
            {"input": "in/cube.qs", "settings": {"levels": "-1,-2"}}]}
JSON
validate "$work/batch.json" "$schemas/batch.schema.json"

# --- 1. first run bakes everything; the report says so ---
"$bake" batch "$work/batch.json" -j 2 2>"$work/err1"; rc=$?
[[ $rc -eq 0 ]] && ok || bad "first batch: exit $rc: $(tail -5 "$work/err1")"
[[ $(field "$work/out/batch-report.json" 'r["totals"]["baked"]') == 6 ]] && ok || bad "first batch bakes 6 assets"
validate "$work/out/batch-report.json" "$schemas/batch-report.schema.json"
[[ -f $work/out/box-mesh/box_S0.glb && ! -f $work/out/box-mesh/box_points.glb && -f $work/out/globe/globe_points.glb ]] && ok ||
  bad "per-asset settings and names apply (box-mesh without points, globe with: --points)"
[[ $(field "$work/out/batch-report.json" 'min(a["primitives"] for a in r["assets"])') -gt 0 ]] && ok || bad "every asset has primitives"
[[ $(field "$work/out/batch-report.json" 'all(a["peak_mb"] > 10 for a in r["assets"])') == True ]] && ok || bad "peak memory per asset"
# bytes: every file an asset wrote; chain_bytes: the files its recommended chain ships (globe's
# point impostor is written, never shipped); the totals add them up.
python3 - "$work/out" <<'PY' 2>"$work/err" && ok || bad "bytes shipped and written: $(tail -3 "$work/err")"
import json, os, sys
out = sys.argv[1]
r = json.load(open(os.path.join(out, "batch-report.json")))
for a in r["assets"]:
    m = json.load(open(os.path.join(out, a["name"], "manifest.json")))
    listed = {f["name"]: f["bytes"] for f in m["files"]}
    assert a["bytes"] == sum(listed.values()) == sum(os.path.getsize(os.path.join(out, a["name"], f)) for f in listed), a["name"]
    shipped = {e["file"] for e in m["recommended_chain"]["chain"] if e["kind"] != "asset"}
    assert a["chain_bytes"] == sum(listed[f] for f in shipped), (a["name"], a["chain_bytes"], shipped)
    assert a["chain_bytes"] <= a["bytes"], a["name"]
globe = next(a for a in r["assets"] if a["name"] == "globe")
points = os.path.getsize(os.path.join(out, "globe", "globe_points.glb"))
assert globe["chain_bytes"] <= globe["bytes"] - points, (globe["chain_bytes"], globe["bytes"], points)
assert r["totals"]["bytes"] == sum(a["bytes"] for a in r["assets"]) and r["totals"]["chain_bytes"] == sum(a["chain_bytes"] for a in r["assets"])
PY
listing "$work/out" >"$work/full.sums"
totals=$(field "$work/out/batch-report.json" '[r["totals"]["bytes"], r["totals"]["chain_bytes"]]')

# --- 2. a second run does no work ---
"$bake" batch "$work/batch.json" -j 2 2>"$work/err2"; rc=$?
[[ $rc -eq 0 && $(field "$work/out/batch-report.json" 'r["totals"]["up to date"]') == 6 ]] && ok || bad "second batch: all up to date (exit $rc)"
[[ $(field "$work/out/batch-report.json" '[r["totals"]["bytes"], r["totals"]["chain_bytes"]]') == "$totals" ]] && ok ||
  bad "up-to-date assets weigh what they weighed baked: $(field "$work/out/batch-report.json" 'r["totals"]') vs $totals"
listing "$work/out" | cmp -s - "$work/full.sums" && ok || bad "second batch leaves the files as they were"

# --- 3. content decides, not timestamps ---
touch "$work/in/ball.xyz"
"$bake" batch "$work/batch.json" -q; [[ $(field "$work/out/batch-report.json" 'r["totals"]["baked"]') == 0 ]] && ok || bad "touch alone rebakes nothing"
"$bake" generate sphere -n 2600 --seed 2 -o "$work/in/ball.xyz" -q   # new bytes
"$bake" batch "$work/batch.json" --dry-run 2>"$work/err3"
grep -q "would bake ball$" "$work/err3" && ok || bad "--dry-run lists the changed asset: $(cat "$work/err3")"
"$bake" batch "$work/batch.json" -q
[[ $(field "$work/out/batch-report.json" '[a["name"] for a in r["assets"] if a["status"] == "baked"]') == "['ball']" ]] && ok ||
  bad "changed input rebakes only it: $(field "$work/out/batch-report.json" '[(a["name"], a["status"]) for a in r["assets"]]')"
# a changed setting rebakes only that asset; its old levels do not linger
sed -i 's/"tau": 0.1/"tau": 0.2/' "$work/batch.json"
"$bake" batch "$work/batch.json" -q
[[ $(field "$work/out/batch-report.json" '[a["name"] for a in r["assets"] if a["status"] == "baked"]') == "['ring']" ]] && ok || bad "changed setting rebakes only ring"
ls "$work/out/ring"/*_L*.glb | wc -l | grep -qx 2 && ok || bad "ring keeps exactly its 2 current levels: $(ls "$work/out/ring")"
sed -i 's/"tau": 0.2/"tau": 0.1/' "$work/batch.json"
"$bake" batch "$work/batch.json" -q --force
[[ $(field "$work/out/batch-report.json" 'r["totals"]["baked"]') == 6 ]] && ok || bad "--force rebakes everything"
listing "$work/out" >"$work/full.sums"   # reference for the shard and kill checks (ball changed)

# --- 4. a corrupt input fails alone, named, with its reason ---
head -c 700 "$work/in/octa.ply" >"$work/in/broken.ply"
sed 's|"in/octa.ply",|"in/octa.ply", "in/broken.ply",|' "$work/batch.json" >"$work/bad.json"
"$bake" batch "$work/bad.json" -o "$work/out" -k 2>"$work/err4"; rc=$?
[[ $rc -eq 1 ]] && ok || bad "a batch with a corrupt input exits 1, got $rc"
grep -q "FAILED broken: .*broken.ply: byte [0-9]*: .*\[ply\." "$work/err4" && ok || bad "the failure names file, byte and code: $(cat "$work/err4")"
[[ $(field "$work/out/batch-report.json" '[(a["status"], a["exit_code"], a["error"]["code"][:4]) for a in r["assets"] if a["name"] == "broken"]') == "[('failed', 1, 'ply.')]" ]] && ok ||
  bad "the report has the failure: $(field "$work/out/batch-report.json" '[a for a in r["assets"] if a["name"] == "broken"]')"
[[ $(field "$work/out/batch-report.json" 'r["totals"]["up to date"]') == 6 && ! -e $work/out/broken/manifest.json ]] && ok || bad "the others are untouched, nothing half-written for broken"
# without --keep-going, assets after the failure are not started (one job: strictly in order)
rm -rf "$work/out2"
"$bake" batch "$work/bad.json" -o "$work/out2" -j 1 -q; rc=$?
[[ $rc -eq 1 && $(field "$work/out2/batch-report.json" '[a["status"] for a in r["assets"]][:3]') == "['baked', 'failed', 'skipped']" ]] && ok ||
  bad "stop after the first failure without -k (exit $rc)"

# --- 5. shards together write exactly the unsharded files ---
for i in 1 2 3; do "$bake" batch "$work/batch.json" -o "$work/sharded" --shard $i/3 -j 1 -q || bad "shard $i/3 failed"; done
listing "$work/sharded" | cmp -s - "$work/full.sums" && ok || bad "shards 1..3/3 differ from the unsharded run: $(listing "$work/sharded" | diff - "$work/full.sums" | head -5)"
[[ $(field "$work/sharded/batch-report-2-of-3.json" '[a["index"] for a in r["assets"]]') == "[1, 4]" ]] && ok || bad "shard 2/3 bakes assets 1 and 4"
"$bake" merge-reports "$work"/sharded/batch-report-{1,2,3}-of-3.json -o "$work/merged.json" -q; rc=$?
[[ $rc -eq 0 && $(field "$work/merged.json" '(r["totals"]["baked"], [a["index"] for a in r["assets"]], r["missing_shards"])') == "(6, [0, 1, 2, 3, 4, 5], [])" ]] && ok ||
  bad "merge-reports joins the shards (exit $rc)"
validate "$work/merged.json" "$schemas/batch-report.schema.json"
# the joined report's page beside it: a row per asset, each linking its page (docs/reports.md)
[[ $(grep -c '<tr data-name=' "$work/merged.html") -eq $(field "$work/merged.json" 'len(r["assets"])') &&
   $(grep -c 'report.html">' "$work/merged.html") -eq $(field "$work/merged.json" 'len(r["assets"])') ]] && ok ||
  bad "merge-reports' page: a linked row per asset"
"$bake" merge-reports "$work"/sharded/batch-report-{1,3}-of-3.json -o "$work/merged2.json" 2>"$work/err5"; rc=$?
[[ $rc -eq 1 ]] && grep -q "missing shards: \[2\]" "$work/err5" && ok || bad "merge-reports names a missing shard (exit $rc)"
"$bake" merge-reports "$work"/sharded/batch-report-1-of-3.json "$work"/sharded/batch-report-1-of-3.json -o "$work/m3.json" 2>"$work/err6"; rc=$?
[[ $rc -eq 2 ]] && grep -q "shard 1 is in two reports" "$work/err6" && ok || bad "merge-reports rejects a shard twice (exit $rc)"

# --- 6. SIGKILL mid-batch, rerun: the same files as an uninterrupted run ---
cp "$work/batch.json" "$work/kill.json"
export QF_CACHE=$work/cache-kill   # cold: the bakes take long enough to be interrupted
"$bake" batch "$work/kill.json" -o "$work/killed" -j 2 -q &
pid=$!
for _ in $(seq 1 500); do compgen -G "$work/killed/*/manifest.json" >/dev/null && break; sleep 0.01; done
kill -9 $pid; wait $pid 2>/dev/null
sleep 0.2
pgrep -f "$work/kill.json" >/dev/null && bad "bake processes outlive a killed batch" || ok
done_before=$(compgen -G "$work/killed/*/manifest.json" | wc -l)
[[ $done_before -ge 1 && $done_before -lt 6 && ! -f $work/killed/batch-report.json ]] && ok || bad "the kill landed mid-batch ($done_before of 6 assets done)"
"$bake" batch "$work/kill.json" -o "$work/killed" -j 2 -q; rc=$?
[[ $rc -eq 0 ]] && ok || bad "rerun after a kill: exit $rc"
[[ $(field "$work/killed/batch-report.json" 'r["totals"]["up to date"]') -ge 1 ]] && ok || bad "the rerun keeps what the killed run finished"
listing "$work/killed" | cmp -s - "$work/full.sums" && ok || bad "killed + rerun differs from an uninterrupted run: $(listing "$work/killed" | diff - "$work/full.sums" | head -5)"
leftovers() { find "$work/killed" -name '.qf-*' -o -name '*.tmp-*' -o -name '.*.qf-*'; }
[[ -z $(leftovers) ]] && ok || bad "no staging left after the rerun: $(leftovers)"
export QF_CACHE=$work/cache

# --- 7. --eval: fidelity per level from qf-render eval (beside qf-bake) ---
printf '{"assets": ["in/octa.ply"], "defaults": {"primitives": 20}}' >"$work/eval.json"
"$bake" batch "$work/eval.json" -o "$work/out-eval" --eval --eval-views 2 -q; rc=$?
[[ $rc -eq 0 && $(field "$work/out-eval/batch-report.json" 'all(10 < e["psnr"] < 99 and 0.5 < e["iou"] <= 1 for e in r["assets"][0]["eval"])') == True ]] && ok ||
  bad "--eval puts PSNR and IoU per level into the report (exit $rc)"

# --- 8. bad manifests: the file, the location and what was expected ---
badm() {  # badm JSON PATTERN
  printf '%s' "$1" >"$work/m.json"
  "$bake" batch "$work/m.json" -o "$work/out3" 2>"$work/err"; local rc=$?
  [[ $rc -eq 1 ]] && grep -q -- "$2" "$work/err" && ok || bad "manifest $1: exit $rc, expected 1 and '$2': $(cat "$work/err")"
}
badm '{"assets": []}' "m.json: assets: expected a non-empty list"
badm '{"assets": ["a.ply", "b/a.ply"]}' "assets\[1\].name: 'a' names two assets"
badm '{"assets": [{"input": "in/octa.ply", "settings": {"tua": 1}}]}' "'tua' is not a bake option"
badm '{"assets": [{"input": "in/octa.ply", "settings": {"threads": 1}}]}' "'threads' is not a bake option a manifest can set"
badm '{"assets": [{"input": "in/octa.ply", "settings": {"tau": "x"}}]}' "assets\[0\] (octa): .*--tau"
badm '{"assets": ["in/octa.ply"], "defaults": {"merge": 1}}' "'merge' is a switch"
badm '{"assets": [' "m.json: byte [0-9]*: not valid JSON"
# Valid JSON beyond what it can hold (found by tests/fuzz/fuzz_manifest): an input error, not an internal one.
badm '{"assets": ["in/octa.ply"], "defaults": {"tau": 1e400}}' "m.json: unreadable JSON: .*number overflow"
"$bake" batch "$work/batch.json" --shard 4/3 2>"$work/err"; [[ $? -eq 2 ]] && ok || bad "--shard 4/3 is a usage error"

finish batch
