#!/usr/bin/env bash
# Benchmarks (tables, not tests): reader throughput on 1M points.
# usage: scripts/bench.sh [points] [repeats]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh >/dev/null
build/bin/qf-bench-io "$@"
