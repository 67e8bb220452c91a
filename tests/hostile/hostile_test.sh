#!/usr/bin/env bash
# The hostile corpus (make_corpus.py: deep JSON, node chains and DAGs, huge counts, images whose
# headers claim 16384^2, references leading outside the asset's folder, FIFOs, folders) baked, and
# the glb cases drawn by qf-render, each under `ulimit -v`, a timeout and --max-memory 2G: every
# case exits 0 or 1 (never a signal, a timeout or 3, internal error), within the time and a peak
# resident memory of 2.5 GB, and no case that names a file outside its folder bakes (exit 0).
# usage: hostile_test.sh QF_BAKE QF_RENDER SOURCE_DIR [SECONDS]   (QF_RENDER may be "": bake only)
# HOSTILE_REPORT=FILE also writes one line a case: name, program, exit, seconds, peak KB.
set -u
bake=$1
render=$2
source_dir=$3
seconds=${4:-20}
source "$(dirname "$0")/../cli/test_lib.sh"

python3 "$source_dir/tests/hostile/make_corpus.py" "$work/corpus" >/dev/null || { bad "make_corpus.py failed"; exit 1; }
report=${HOSTILE_REPORT:-$work/report.tsv}
: >"$report"
# Address space: what --max-memory 2G allows plus the program's own mappings (libraries, thread
# stacks); past it an allocation fails (std::bad_alloc) instead of taking the machine.
vlimit_kb=$((6 * 1024 * 1024))
peak_limit_kb=$((2560 * 1024))
if [[ -n ${ASAN_OPTIONS:-} ]]; then
  # Under AddressSanitizer (scripts/sanitize.sh): its shadow memory needs terabytes of address
  # space and its bookkeeping inflates the peak; the exits and the time (x5) are still checked.
  vlimit_kb=unlimited peak_limit_kb=$((1 << 40)) seconds=$((seconds * 5))
fi

# run NAME PROGRAM OUTSIDE COMMAND...: runs one case and checks how it ended.
run() {
  local name=$1 program=$2 outside=$3
  shift 3
  local start rc peak
  local -a timer=()
  # GNU time gives the peak resident memory; without it the peak is not checked.
  [[ -x /usr/bin/time ]] && timer=(/usr/bin/time -f %M -o "$work/peak")
  rm -f "$work/peak"
  start=$EPOCHREALTIME
  (ulimit -v "$vlimit_kb"; exec timeout -s KILL "$seconds" "${timer[@]}" "$@") >"$work/out.txt" 2>"$work/err.txt" </dev/null
  rc=$?
  peak=$(tail -1 "$work/peak" 2>/dev/null)
  [[ $peak =~ ^[0-9]+$ ]] || peak=0
  printf '%s\t%s\t%s\t%s\t%s\n' "$name" "$program" "$rc" "$(python3 -c "print(f'{$EPOCHREALTIME - $start:.2f}')")" "$peak" >>"$report"
  # /usr/bin/time reports a signal as "Command terminated by signal N" and exits 128 + N.
  if grep -q "terminated by signal" "$work/peak" 2>/dev/null || ((rc > 3)); then
    bad "$name ($program): killed or timed out (exit $rc): $(tail -c 300 "$work/err.txt")"
    return
  fi
  if [[ $program == render && $rc -eq 3 ]] && grep -qi "EGL\|GL context\|display" "$work/err.txt"; then
    return  # no GL driver here: the renderer cannot run at all, which says nothing of the file
  fi
  ((rc <= 1)) && ok || bad "$name ($program): exit $rc (0 or 1 expected): $(tail -c 300 "$work/err.txt")"
  [[ $outside == outside && $rc -eq 0 ]] && bad "$name ($program): names a file outside its folder, yet exit 0"
  ((peak <= peak_limit_kb)) || bad "$name ($program): peak memory ${peak} KB, past 2.5 GB"
}

while IFS=$'\t' read -r name input outside programs; do
  rm -rf "$work/out"
  run "$name" bake "$outside" "$bake" bake "$work/corpus/$input" -o "$work/out" -q --max-memory 2G --no-cache --no-measure \
    --no-report-html --mesh-lods none --ldi 64
  if [[ $outside == outside && -e $work/out/manifest.json ]]; then bad "$name: an outside reference left a bake behind"; fi
  if [[ -n $render && $programs == *render* ]]; then
    QF_MEMORY_LIMIT=512M run "$name" render "$outside" "$render" "$work/corpus/$input" -o "$work/render.png" --size 64
  fi
done <"$work/corpus/cases.tsv"

# A sampling density whose layers would take more than --max-memory: refused before drawing
# (it was std::bad_alloc inside the depth peeling's OpenMP loop: std::terminate, SIGABRT).
"$bake" generate cube --mesh -o "$work/cube.ply" -q
rm -rf "$work/out"
run ldi_16000 bake inside "$bake" bake "$work/cube.ply" -o "$work/out" -q --max-memory 2G --no-cache --no-measure --ldi 16000
grep -q "sample.memory" "$work/err.txt" && ok || bad "ldi_16000: not refused by the sampling estimate: $(tail -c 300 "$work/err.txt")"

# The corpus holds what the issue lists: at least 40 cases.
(($(wc -l <"$work/corpus/cases.tsv") >= 40)) && ok || bad "the corpus has fewer than 40 cases"
finish hostile
