#!/usr/bin/env bash
# Real models from CGAL's data set (scripts/fetch-models.sh): every one reads with the counts and
# attributes the data set has, and every point set survives ply -> qs -> ply with its point count.
# Exits 77 (skipped) when the models have not been fetched.
# usage: models_test.sh QF_BAKE
set -u
bake=$1
dir=${QF_MODELS:-$HOME/.cache/quasiflat/models}
[[ -f "$dir/bunny00.off" ]] || { echo "models not fetched (scripts/fetch-models.sh); skipping"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
pass=0 fail=0
check() {  # check FILE KEY VALUE: qf-bake info --json FILE has "KEY": VALUE
  if "$bake" info --json "$dir/$1" >"$work/j" 2>"$work/e" && grep -q "\"$2\": $3" "$work/j"; then
    pass=$((pass + 1))
  else
    fail=$((fail + 1)); echo "FAIL: $1: expected \"$2\": $3; $(cat "$work/e")"
  fi
}
check bunny00.off vertices 37706
check bunny00.off triangles 75408
check fandisk.off vertices 6475
check elephant.off triangles 5558
check ChineseDragon-10kv.off vertices 10000
check sphere.ply triangles 320
check kitten.xyz points 5210
check ball.ply points 31374
check b9_training.ply points 22300
check oni.pwn points 1435
check sphere_20k.xyz points 21000
# b9_training has colours, ball and kitten normals
"$bake" info "$dir/b9_training.ply" | grep -q "attributes: *position color$" && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL: b9_training colours"; }
"$bake" info "$dir/ball.ply" | grep -q "attributes: *position normal$" && pass=$((pass + 1)) || { fail=$((fail + 1)); echo "FAIL: ball normals"; }

for m in kitten.xyz ball.ply oni.pwn; do
  n=$("$bake" info --json "$dir/$m" | sed -n 's/.*"points": \([0-9]*\).*/\1/p')
  if "$bake" convert -q "$dir/$m" "$work/a.qs" && "$bake" convert -q "$work/a.qs" "$work/b.ply" &&
     "$bake" info --json "$work/b.ply" | grep -q "\"points\": $n"; then
    pass=$((pass + 1))
  else
    fail=$((fail + 1)); echo "FAIL: $m did not survive ply -> qs -> ply with $n points"
  fi
done
echo "$pass passed, $fail failed"
[[ $fail -eq 0 ]]
