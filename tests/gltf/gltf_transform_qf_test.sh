#!/usr/bin/env bash
# quasiflat's glTF extensions (QF_impostor_level, QF_point_impostor, MSFT_lod) through glTF-Transform
# and its CLI, with tools/gltf-transform-qf: node's built-in test runner over its tests, which
# read the baked fixtures in tests/data/toolchain/.
# usage: gltf_transform_qf_test.sh PACKAGE_DIR
set -u
pkg=$1
[[ -f "$pkg/node_modules/@gltf-transform/cli/package.json" ]] || { echo "tools/gltf-transform-qf not installed (scripts/install-deps.sh)"; exit 1; }
exec node --test "$pkg"/test/*.test.mjs
