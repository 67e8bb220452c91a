#!/usr/bin/env bash
# The whole test suite on a fresh Debian 12 machine: installs what is needed, fetches the real
# models, builds (Release) and runs every test, then builds the reader tests and the CLI with
# AddressSanitizer + UndefinedBehaviorSanitizer and runs them again ("readers" label).
# usage: scripts/test.sh            (env QF_SKIP_SANITIZE=1 skips the sanitizer pass)
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)

scripts/install-deps.sh
scripts/fetch-models.sh >/dev/null

echo "== build (Release)"
scripts/build.sh
echo "== tests"
ctest --test-dir build --output-on-failure -j "$jobs"

if [[ "${QF_SKIP_SANITIZE:-0}" != 1 ]]; then
  echo "== reader tests under ASan + UBSan"
  cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DQF_SANITIZE=ON >/dev/null
  cmake --build build-asan -j "$jobs" --target qf-bake qf_test_io
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 LSAN_OPTIONS=suppressions=$PWD/tests/lsan.supp:print_suppressions=0 \
    UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir build-asan --output-on-failure -j "$jobs" -L readers
fi
