#!/usr/bin/env bash
# The sanitizer pass of scripts/test.sh: builds the tests and the CLI with AddressSanitizer +
# UndefinedBehaviorSanitizer (gcc, -O1 -g1, -DQF_SANITIZE=ON) and runs every test label that
# needs no GL context of its own: unit, readers, cli, gltf, models. Left out: the labels render and
# engine (qf-render, qf-diff: EGL/OpenGL), the tests of the mesh sampler's GL backend (qf_test_sample's
# Sample.* tests that draw with OpenGL, SampleModels.*; its CPU backend runs in the tests kept and
# in every bake), and three scale tests (scale_tests below). GL users remain, headless through EGL
# on llvmpipe: every bake's measuring (baker/measure/measure.h: our code sanitized, Mesa's not),
# cli_test.sh's `convert --sampler gl` and batch_test.sh's `--eval` (qf-render eval); Mesa and
# LeakSanitizer: tests/lsan.supp, baker/gl/egl.cpp.
#
#   scripts/sanitize.sh [BUILD_DIR]     (default build-asan)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build-asan}"
jobs=$(nproc 2>/dev/null || echo 2)

# The executables the kept tests run (qf-bake for the CLI scripts, qf-render for batch --eval,
# qf_write_test_levels for the glTF validator); qf-diff, qf_test_points and the benchmarks are not built.
targets=(qf-bake qf-render qf_test_io qf_test_core qf_test_sample qf_test_clustering qf_test_fans_cgal
         qf_write_test_levels qf_test_render_cpu qf_test_compressed)
# Tests of the GL sampler backend (by name: they share qf_test_sample with CPU-only tests).
gl_tests='^SampleModels\.|^Sample\.(CountsMatchProjectedAreaOnAnalyticMeshes|PointsLieOnTheSurface|ClosedMeshesHaveEvenLayerCounts|GlMatchesTheCpuReference|PerAxisTrianglesGiveTheSamePointsWithFewerLayers|GlIsDeterministic)$'
# Scale tests whose code paths the smaller tests kept here already run, left out for the CI's time
# (seconds under ASan, 2 cores): AmgLarge.* (a million points through the AMG, 106 s), cgal_batch
# (a batch of CGAL's models: the batch code runs in `batch`, the models in `cgal_models`, 150 s)
# and slurm (the same bakes scheduled by Slurm, 130 s). gltf_transform_qf runs node alone (no code
# of ours to sanitize: tools/gltf-transform-qf).
scale_tests='^AmgLarge\.|^cgal_batch$|^slurm$|^gltf_transform_qf$'

# -O1 -g1 (line tables only), not RelWithDebInfo's -O2 -g: the sanitizers' own advice is -O1, and
# line tables are all their stack traces use. Measured on baker/pipeline/batch_manifest.cpp (one
# of the heaviest files): 20.6 s of CPU at -O2 -g, 10.2 s at -O1 -g1, an object of 4.2 MB for 9.7.
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DQF_SANITIZE=ON \
      "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" >/dev/null
cmake --build "$build" -j "$jobs" --target "${targets[@]}"
# -L keeps labelled tests only (so the NOT_BUILT placeholders of unbuilt gtest executables are out).
# intercept_tls_get_addr=0: LeakSanitizer's own record of dynamic TLS blocks goes stale when the
# image plug-in's OpenImageIO threads (baker/gltf/png_loader.cpp dlopens it) exit at process exit:
# its exit-time check then read a block at 0x31ce and crashed ("Tracer caught signal 11",
# "DTLS 15 at 0x0000000031ce" with log_threads=1) on every mesh bake. Static TLS and every
# thread's stack are still scanned; no leak is reported with it.
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:intercept_tls_get_addr=0 \
LSAN_OPTIONS=suppressions=$PWD/tests/lsan.supp:print_suppressions=0 \
UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir "$build" --output-on-failure -j "$jobs" -L 'unit|readers|cli|gltf|models' -LE 'render|engine' -E "$gl_tests|$scale_tests"
