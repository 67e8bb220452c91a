#!/usr/bin/env bash
# Regenerates the golden renders in tests/golden/ from the current build (after scripts/build.sh).
# Review every changed image (git diff --stat tests/golden; open the PNGs) before committing.
set -euo pipefail
cd "$(dirname "$0")/.."
QF_UPDATE_GOLDENS=1 bash tests/render/render_test.sh build/bin/qf-bake build/bin/qf-render "$PWD"
