#!/usr/bin/env bash
# `qf-bake generate` of issue 49's assets (conifer, grass, pylon, machine): each is deterministic
# (same seed, same bytes; another seed, other bytes), passes the Khronos glTF-Validator with no
# error or warning, and is listed in `generate --help`. Their shapes are checked by the unit tests
# GeneratedShapes.* (tests/unit/shapes/generators_test.cpp).
# usage: shapes_test.sh QF_BAKE VALIDATOR_DIR
set -u
bake=$1 validator=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

help=$("$bake" generate --help 2>&1)
for shape in conifer grass pylon machine; do
  grep -q "^  $shape " <<<"$help" && ok || bad "generate --help does not list $shape"
  "$bake" generate "$shape" --seed 2 -o "$work/a.glb" -q && "$bake" generate "$shape" --seed 2 -o "$work/b.glb" -q &&
    "$bake" generate "$shape" --seed 3 -o "$work/c.glb" -q || { bad "generate $shape failed"; continue; }
  cmp -s "$work/a.glb" "$work/b.glb" && ok || bad "generate $shape --seed 2 twice: different bytes"
  cmp -s "$work/a.glb" "$work/c.glb" && bad "generate $shape: seeds 2 and 3 give the same bytes" || ok
  node "$validator/validate.js" "$work/a.glb" >"$work/v" 2>&1 && grep -q " 0 errors, 0 warnings" "$work/v" && ok ||
    bad "$shape.glb does not validate: $(tail -2 "$work/v")"
done
"$bake" generate pylon -o "$work/pylon.ply" -q 2>/dev/null && bad "generate pylon wrote a .ply" || ok

echo "generated_shapes: $pass passed, $fail failed"
[[ $fail -eq 0 ]]
