#!/usr/bin/env bash
# The CGAL models (scripts/fetch-models.sh: meshes and point sets) as one batch with -j 2: all bake,
# the report matches its schema, a second run does no work. Exits 77 (skipped) without the models.
# usage: batch_models_test.sh QF_BAKE SCHEMA_DIR
set -u
bake=$1 schemas=$2
dir=${QF_MODELS:-$HOME/.cache/quasiflat/models}
[[ -f "$dir/bunny00.off" ]] || { echo "models not fetched (scripts/fetch-models.sh); skipping"; exit 77; }
source "$(dirname "$0")/test_lib.sh"
models=(bunny00.off fandisk.off elephant.off ChineseDragon-10kv.off sphere.ply kitten.xyz ball.ply b9_training.ply oni.pwn sphere_20k.xyz)
list=$(for m in "${models[@]}"; do printf '"%s/%s",' "$dir" "$m"; done)
printf '{"output": "out", "defaults": {"points": true}, "assets": [%s]}\n' "${list%,}" >"$work/cgal.json"
"$bake" batch "$work/cgal.json" -j 2 2>"$work/err"; rc=$?
[[ $rc -eq 0 ]] && ok || bad "CGAL batch: exit $rc: $(tail -5 "$work/err")"
[[ $(field "$work/out/batch-report.json" 'r["totals"]["baked"]') == ${#models[@]} ]] && ok || bad "every model baked"
validate "$work/out/batch-report.json" "$schemas/batch-report.schema.json"
[[ -f $work/out/bunny00/bunny00_points.glb && -f $work/out/bunny00/bunny00_S4.glb && -f $work/out/kitten/manifest.json ]] && ok || bad "mesh and point outputs"
"$bake" batch "$work/cgal.json" -j 2 -q; rc=$?
[[ $rc -eq 0 && $(field "$work/out/batch-report.json" 'r["totals"]["up to date"]') == ${#models[@]} ]] && ok || bad "second run does no work"
finish batch_models
