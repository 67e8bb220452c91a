#!/usr/bin/env bash
# The CGAL models (scripts/fetch-models.sh: meshes and point sets) as one batch with -j 2: all bake,
# the report matches its schema, a second run does no work. Exits 77 (skipped) without the models.
# usage: batch_models_test.sh QF_BAKE SCHEMA_DIR
set -u
bake=$1 schemas=$2
dir=${QF_MODELS:-$HOME/.cache/quasiflat/models}
[[ -f "$dir/bunny00.off" ]] || { echo "models not fetched (scripts/fetch-models.sh); skipping"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
field() { /usr/bin/python3 -c 'import json, sys; r = json.load(open(sys.argv[1])); print(eval(sys.argv[2]))' "$1" "$2"; }
export QF_CACHE=$work/cache
models=(bunny00.off fandisk.off elephant.off ChineseDragon-10kv.off sphere.ply kitten.xyz ball.ply b9_training.ply oni.pwn sphere_20k.xyz)
list=$(for m in "${models[@]}"; do printf '"%s/%s",' "$dir" "$m"; done)
printf '{"output": "out", "assets": [%s]}\n' "${list%,}" >"$work/cgal.json"
"$bake" batch "$work/cgal.json" -j 2 2>"$work/err"; rc=$?
[[ $rc -eq 0 ]] && ok || bad "CGAL batch: exit $rc: $(tail -5 "$work/err")"
[[ $(field "$work/out/batch-report.json" 'r["totals"]["baked"]') == ${#models[@]} ]] && ok || bad "every model baked"
/usr/bin/python3 -c 'import json, sys, jsonschema
jsonschema.validate(json.load(open(sys.argv[1])), json.load(open(sys.argv[2])))' "$work/out/batch-report.json" "$schemas/batch-report.schema.json" && ok || bad "report schema"
[[ -f $work/out/bunny00/bunny00_points.glb && -f $work/out/bunny00/bunny00_C4.glb && -f $work/out/kitten/manifest.json ]] && ok || bad "mesh and point outputs"
"$bake" batch "$work/cgal.json" -j 2 -q; rc=$?
[[ $rc -eq 0 && $(field "$work/out/batch-report.json" 'r["totals"]["up to date"]') == ${#models[@]} ]] && ok || bad "second run does no work"
echo "batch_models: $pass passed, $fail failed"
[[ $fail -eq 0 ]]
