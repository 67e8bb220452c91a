#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz (Debian's clang, ASan + UBSan, folder build-fuzz, every
# core) and runs each for SECONDS with a memory cap and a per-input timeout, two at a time on two cores.
#
#   scripts/fuzz.sh SECONDS [TARGET...]     targets: ply qsplat off obj xyz las manifest glb cache gltf (default: all)
#
# Prints one line per target (executions, executions/s, corpus size, coverage features) and closes
# with exactly "N passed, N failed" (also when the build fails: 0 passed); exits 1 when any target
# found a crash, leak, timeout or out-of-memory (its input is left in build-fuzz/artifacts/TARGET/,
# its log in build-fuzz/logs/TARGET.log), 2 on bad usage or a failed build. The corpus each run
# grows is kept in build-fuzz/corpus/TARGET and seeded from tests/fuzz/seeds, tests/fuzz/corpus and
# tests/data (valid and malformed files).
# Environment: QF_FUZZ_TIMEOUT (seconds per input, default 10), QF_FUZZ_JOBS (targets at once,
# default: the number of cores), QF_FUZZ_BUILD (build folder, default build-fuzz).
set -uo pipefail

root="$(cd "$(dirname "$0")/.." && pwd)"
all_targets=(ply qsplat off obj xyz las manifest glb cache gltf)

usage() {
  echo "usage: scripts/fuzz.sh SECONDS [TARGET...]   (targets: ${all_targets[*]})" >&2
  exit 2
}
[[ $# -ge 1 && "$1" =~ ^[0-9]+$ && "$1" -gt 0 ]] || usage
seconds="$1"
shift
targets=("$@")
[[ ${#targets[@]} -gt 0 ]] || targets=("${all_targets[@]}")
for t in "${targets[@]}"; do
  [[ " ${all_targets[*]} " == *" $t "* ]] || { echo "fuzz.sh: unknown target '$t'" >&2; usage; }
done

build="${QF_FUZZ_BUILD:-$root/build-fuzz}"
per_input="${QF_FUZZ_TIMEOUT:-10}"
cores="$(nproc)"
jobs="${QF_FUZZ_JOBS:-$cores}"

# 1. Build (clang + libFuzzer: packages clang and libclang-rt-14-dev, scripts/install-deps.sh).
command -v clang++ >/dev/null || { echo "fuzz.sh: clang++ not found (scripts/install-deps.sh installs it)" >&2; echo "0 passed, ${#targets[@]} failed"; exit 2; }
# A failed build still closes with the "N passed, N failed" line (every target failed).
build_failed() { echo "fuzz.sh: $1" >&2; echo "0 passed, ${#targets[@]} failed"; exit 2; }
if [[ ! -f "$build/build.ninja" ]]; then
  cmake -S "$root/tests/fuzz" -B "$build" -G Ninja -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ >"$build.configure.log" 2>&1 ||
    { cat "$build.configure.log" >&2; build_failed "configuring $build failed"; }
  rm -f "$build.configure.log"
fi
build_targets=()
for t in "${targets[@]}"; do build_targets+=("fuzz_$t"); done
cmake --build "$build" -j "$cores" --target "${build_targets[@]}" >"$build/build.log" 2>&1 ||
  { tail -40 "$build/build.log" >&2; build_failed "build failed (log: $build/build.log)"; }

# 2. Seeds: tests/fuzz/seeds/TARGET, the corpus a long run kept (tests/fuzz/corpus/TARGET, merged
#    with -merge=1) and the files of tests/data with the target's extensions.
extensions() {
  case "$1" in
    ply) echo ply ;; qsplat) echo qs ;; off) echo off ;; obj) echo obj ;; xyz) echo "xyz pwn" ;; las) echo "las laz" ;;
    manifest) echo json ;; glb) echo glb ;; cache) echo qfamg ;; gltf) echo "gltf glb" ;;
  esac
}
dictionary() {  # tests/fuzz/dict/NAME.dict, several concatenated (libFuzzer takes one -dict)
  case "$1" in
    ply) echo ply ;; off) echo off ;; obj) echo obj ;; xyz) echo xyz ;; las) echo las ;;
    # The JSON targets also get json_structure.dict: runs of brackets and node-graph fragments
    # that reach the JSON depth limit and the node checks (issue 50).
    manifest) echo "json json_structure" ;; glb) echo "glb json_structure" ;; gltf) echo "gltf json_structure" ;; *) echo "" ;;
  esac
}
max_len() {  # large enough for the seeds; small inputs keep the runs fast
  # glTF/glb: 256 KiB, room for the hostile structures of issue 50 (JSON nested ~14,500 deep is
  # 30 KB, a chain of ~8,100 nodes about 160 KB); libFuzzer's -len_control still starts each run
  # near its seeds' sizes and grows the limit only when longer inputs pay off.
  case "$1" in glb | gltf) echo 262144 ;; cache) echo 8192 ;; *) echo 4096 ;; esac
}
prepare_seeds() {
  local t="$1" dir="$build/seeds/$1"
  rm -rf "$dir" && mkdir -p "$dir" "$build/corpus/$t" "$build/artifacts/$t" "$build/logs"
  [[ -d "$root/tests/fuzz/seeds/$t" ]] && cp "$root/tests/fuzz/seeds/$t"/* "$dir"/ 2>/dev/null
  [[ -d "$root/tests/fuzz/corpus/$t" ]] && cp "$root/tests/fuzz/corpus/$t"/* "$dir"/ 2>/dev/null
  local e f
  for e in $(extensions "$t"); do
    while IFS= read -r -d '' f; do
      cp "$f" "$dir/$(basename "$(dirname "$f")")_$(basename "$f")"
    done < <(find "$root/tests/data" "$root/samples" -type f -name "*.$e" -size -64k -print0 2>/dev/null)
  done
}

run_one() {
  local t="$1" log="$build/logs/$1.log" names d
  names="$(dictionary "$t")"
  local args=(-max_total_time="$seconds" -rss_limit_mb=2048 -malloc_limit_mb=2048 -timeout="$per_input"
              -max_len="$(max_len "$t")" -print_final_stats=1 -artifact_prefix="$build/artifacts/$t/")
  if [[ -n "$names" ]]; then
    mkdir -p "$build/dict"
    for d in $names; do cat "$root/tests/fuzz/dict/$d.dict"; done >"$build/dict/$t.dict"
    args+=(-dict="$build/dict/$t.dict")
  fi
  QF_FUZZ_SCRATCH="$scratch/$t" ASAN_OPTIONS="detect_leaks=1:allocator_may_return_null=0:abort_on_error=0" \
  UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1" \
    "$build/fuzz_$t" "${args[@]}" "$build/corpus/$t" "$build/seeds/$t" >"$log" 2>&1
  echo $? >"$build/logs/$t.rc"
}

for t in "${targets[@]}"; do prepare_seeds "$t"; done
# The .glb loader reads only from paths: its inputs go through a file in memory (/dev/shm).
scratch="$(mktemp -d "$( [[ -d /dev/shm ]] && echo /dev/shm || echo /tmp )/qf-fuzz.XXXXXX")"
trap 'rm -rf "$scratch"' EXIT
start=$(date +%s)
running=0
for t in "${targets[@]}"; do
  run_one "$t" &
  running=$((running + 1))
  if [[ $running -ge $jobs ]]; then
    wait -n
    running=$((running - 1))
  fi
done
wait

# 3. One line per target, in the order asked.
passed=0
failed=0
for t in "${targets[@]}"; do
  log="$build/logs/$t.log"
  rc="$(cat "$build/logs/$t.rc" 2>/dev/null || echo 99)"
  execs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)"
  rate="$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)"
  last="$(grep -E '^#[0-9]+' "$log" | grep -E 'corp: ' | tail -1)"
  corp="$(sed -n 's/.*corp: \([0-9]*\)\/.*/\1/p' <<<"$last")"
  ft="$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$last")"
  status="ok"
  if [[ "$rc" != 0 ]]; then
    status="FAILED (exit $rc; $(grep -m1 -E 'ERROR: |SUMMARY: |ALARM|out-of-memory|fuzz invariant' "$log" | cut -c1-120); log $log)"
    failed=$((failed + 1))
  else
    passed=$((passed + 1))
  fi
  printf '%-9s %10s execs %8s exec/s  corpus %5s  features %6s  %s\n' "$t" "${execs:-?}" "${rate:-?}" "${corp:-?}" "${ft:-?}" "$status"
done
echo "fuzz: ${#targets[@]} target(s), ${seconds} s each, $(( $(date +%s) - start )) s in all"
echo "$passed passed, $failed failed"
[[ $failed -eq 0 ]]
