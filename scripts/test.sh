#!/usr/bin/env bash
# The whole test suite on a fresh Debian 12 machine: installs what is needed, fetches the real
# models, builds (Release) and runs every test, runs each libFuzzer target for a few seconds, then
# builds the tests and the CLI with AddressSanitizer + UndefinedBehaviorSanitizer and runs every
# test that needs no GL context again (scripts/sanitize.sh: labels unit, readers, cli, gltf, models).
# usage: scripts/test.sh   (env QF_SKIP_FUZZ=1 skips the fuzz run, QF_SKIP_SANITIZE=1 the sanitizer pass)
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)

scripts/install-deps.sh
scripts/fetch-models.sh >/dev/null

echo "== build (Release)"
scripts/build.sh
echo "== tests"
ctest --test-dir build --output-on-failure -j "$jobs"

# A short libFuzzer run over every reader (about 90 s on 2 cores with the build; longer runs are a
# benchmark: scripts/fuzz.sh SECONDS). Each target starts from its seeds, regression inputs included.
if [[ "${QF_SKIP_FUZZ:-0}" != 1 ]]; then
  echo "== fuzz targets, 6 s each (scripts/fuzz.sh)"
  scripts/fuzz.sh 6
fi

if [[ "${QF_SKIP_SANITIZE:-0}" != 1 ]]; then
  echo "== tests under ASan + UBSan (every label without a GL context; scripts/sanitize.sh)"
  scripts/sanitize.sh build-asan
fi
