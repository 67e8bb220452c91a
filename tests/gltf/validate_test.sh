#!/usr/bin/env bash
# Every .glb the baker writes passes the Khronos glTF-Validator with 0 errors and 0 warnings.
# usage: validate_test.sh WRITE_LEVELS VALIDATOR_DIR
set -u
writer=$1 validator=$2
[[ -f "$validator/node_modules/gltf-validator/package.json" ]] || { echo "validator not installed (scripts/install-deps.sh)"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$writer" "$work" || exit 1
files=("$work"/*.glb)
[[ ${#files[@]} -ge 6 ]] || { echo "expected 6 .glb files, got ${#files[@]}"; exit 1; }
node "$validator/validate.js" "${files[@]}"
