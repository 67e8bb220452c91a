#!/usr/bin/env bash
# An asset that would need more memory than the machine has, even out of core (a subsample of at
# least 10000 points; out_of_core_test.sh tests that path), fails alone, with the estimated need
# and the memory available, instead of being killed by the kernel: QF_MEMORY_LIMIT caps the
# memory the bake assumes available, so a small input triggers the check cheaply. A bake exits 1
# with [bake.memory] and leaves nothing behind; in a batch (--keep-going) the big asset fails with
# that code and the small one still bakes; a malformed limit is a usage error (exit 2).
# usage: memory_test.sh QF_BAKE
set -u
bake=$1
source "$(dirname "$0")/test_lib.sh"

# A small set (~384 MB estimated: the fixed part) and a big one (~1.35 x 200k x 840 bytes = ~220 MB more);
# 390 MB leaves 6 MB above the fixed part, room for a subsample of ~5k points only.
"$bake" generate sphere -n 600 -o "$work/small.ply" -q
"$bake" generate torus -n 200000 -o "$work/big.ply" -q
limit=390M

# --- 1. one bake: exit 1, the figures, no output ---
QF_MEMORY_LIMIT=$limit "$bake" "$work/big.ply" -o "$work/out-big" 2>"$work/err1"; rc=$?
[[ $rc -eq 1 ]] && ok || bad "a bake past the limit exits 1, got $rc: $(cat "$work/err1")"
grep -q "big.ply: its 200000 points need about [0-9.]* [MG]B to bake (estimated), but only 390 MB is available (QF_MEMORY_LIMIT).*\[bake.memory\]" "$work/err1" &&
  ok || bad "the message names the file, the estimated need and the memory available: $(cat "$work/err1")"
[[ ! -e $work/out-big/manifest.json ]] && ok || bad "nothing is written for the failed bake"
QF_MEMORY_LIMIT=$limit "$bake" "$work/small.ply" -o "$work/out-small" -q; rc=$?
[[ $rc -eq 0 && -f $work/out-small/manifest.json ]] && ok || bad "a bake under the limit succeeds (exit $rc)"

# --- 2. a batch: the big asset fails with its code, the small one bakes ---
printf '{"assets": ["small.ply", "big.ply"], "defaults": {"primitives": [30]}}\n' >"$work/batch.json"
QF_MEMORY_LIMIT=$limit "$bake" batch "$work/batch.json" -o "$work/batch" -k -j 2 2>"$work/err2"; rc=$?
[[ $rc -eq 1 ]] && ok || bad "a batch with an asset past the limit exits 1, got $rc: $(tail -5 "$work/err2")"
[[ $(field "$work/batch/batch-report.json" '{a["name"]: (a["status"], a.get("error", {}).get("code")) for a in r["assets"]}') == \
   "{'small': ('baked', None), 'big': ('failed', 'bake.memory')}" ]] && ok ||
  bad "big fails with bake.memory, small bakes: $(field "$work/batch/batch-report.json" 'r["assets"]')"
[[ -f $work/batch/small/manifest.json && ! -e $work/batch/big/manifest.json ]] && ok || bad "small's files are there, none of big's"
grep -q "FAILED big: .*available (QF_MEMORY_LIMIT)" "$work/err2" && ok || bad "the batch names the failure and the figures: $(cat "$work/err2")"

# --- 3. without the cap the big one fits (this machine has the few hundred MB it needs) ---
"$bake" batch "$work/batch.json" -o "$work/batch" -k -q; rc=$?
[[ $rc -eq 0 && -f $work/batch/big/manifest.json ]] && ok || bad "without QF_MEMORY_LIMIT the big asset bakes (exit $rc)"

# --- 4. a malformed limit is a usage error ---
QF_MEMORY_LIMIT=lots "$bake" "$work/small.ply" -o "$work/out-bad" 2>"$work/err4"; rc=$?
[[ $rc -eq 2 ]] && grep -q "QF_MEMORY_LIMIT" "$work/err4" && ok || bad "QF_MEMORY_LIMIT=lots: exit 2 naming it, got $rc: $(cat "$work/err4")"
finish memory
