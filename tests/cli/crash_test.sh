#!/usr/bin/env bash
# An output folder is at every instant the old bake or the new one (core/output_folder.h): bakes
# SIGKILLed at each step of the swap (stopped there by QF_TEST_SWAP, then killed: exact, not timed)
# and at a few moments mid-bake leave the old files or the new ones, never a mix; the next run
# leaves nothing of the killed one and writes the same bytes as an uninterrupted bake. Also: a
# second bake into a folder being written is refused (exit 5); an output that cannot be written
# exits 4, one that names a file as its folder 2; a cache that cannot be written warns and bakes;
# a batch whose asset is a folder or takes the report's name fails that asset alone, in the report.
# usage: crash_test.sh QF_BAKE
set -u
bake=$1
source "$(dirname "$0")/test_lib.sh"

# Every file of folder $1 with its checksum; report.json (it holds times) left out.
listing() { (cd "$1" 2>/dev/null && find . -type f ! -name report.json -print0 | sort -z | xargs -0 -r sha256sum); }
# The old bake (settings A) and the new one (settings B), small enough for a few tenths of a second
# (WebP: the PNG encoder's libraries take 0.35 s to load).
"$bake" generate octahedron -n 1000 -o "$work/octa.ply" -q
common=(--no-measure --no-report-html --mesh-lods none -q --no-cache --textures webp)
old=(--primitives 30,8) new=(--primitives 12)
"$bake" bake "$work/octa.ply" -o "$work/ref-old" "${common[@]}" "${old[@]}" || bad "reference bake A"
"$bake" bake "$work/octa.ply" -o "$work/ref-new" "${common[@]}" "${new[@]}" || bad "reference bake B"
listing "$work/ref-old" >"$work/old.sums"
listing "$work/ref-new" >"$work/new.sums"
cmp -s "$work/old.sums" "$work/new.sums" && bad "settings A and B must give different bakes"

# state: "old", "new", "absent" or "mixed" for the folder $work/out.
state() {
  [[ -e $work/out ]] || { echo absent; return; }
  listing "$work/out" >"$work/now.sums"
  if cmp -s "$work/now.sums" "$work/old.sums"; then echo old; elif cmp -s "$work/now.sums" "$work/new.sums"; then echo new; else echo mixed; fi
}
# leftovers: what a killed writer may leave beside or inside the folder.
leftovers() { find "$work" -maxdepth 2 \( -name '.out.qf-*' -o -name '*.tmp-*' -o -name '.qf-*' \) -not -path "$work/cache*"; }
# Waits until process $1 has stopped itself (SIGSTOP at its QF_TEST_SWAP point).
wait_stopped() {
  for _ in $(seq 1 1500); do
    [[ $(awk '{print $3}' "/proc/$1/stat" 2>/dev/null) == T ]] && return 0
    kill -0 "$1" 2>/dev/null || return 1
    sleep 0.01
  done
  return 1
}
reset_old() { rm -rf "$work/out"; cp -a "$work/ref-old" "$work/out"; }

# --- 1. SIGKILL at each step of the swap, on both paths (one exchange; two renames, as on NFS;
# before the swap, "filled", the two paths are one) ---
for point in filled swapped two-renames,aside two-renames,swapped; do
  reset_old
  QF_TEST_SWAP="stop:${point##*,},$point" "$bake" bake "$work/octa.ply" -o "$work/out" "${common[@]}" "${new[@]}" &
  pid=$!
  wait_stopped $pid || bad "$point: the bake never reached its stop"
  s=$(state)
  case $point in
    *filled) [[ $s == old ]] && ok || bad "$point: while stopped the folder is $s, expected old" ;;
    *swapped) [[ $s == new ]] && ok || bad "$point: while stopped the folder is $s, expected new" ;;
    *aside) [[ $s == absent ]] && ok || bad "$point: while stopped the folder is $s, expected absent (between two renames)" ;;
  esac
  if [[ $point == filled ]]; then
    # The lock: a second bake into the folder is refused at once, naming it, and writes nothing.
    "$bake" bake "$work/octa.ply" -o "$work/out" "${common[@]}" "${old[@]}" 2>"$work/err"; rc=$?
    [[ $rc -eq 5 ]] && grep -q "another bake is writing this folder" "$work/err" && ok || bad "a second bake: exit $rc: $(cat "$work/err")"
    [[ $(state) == old ]] && ok || bad "the refused bake changed the folder"
  fi
  kill -9 $pid; wait $pid 2>/dev/null
  s=$(state)
  [[ $s == old || $s == new || ($s == absent && $point == *aside) ]] && ok || bad "$point: after SIGKILL the folder is $s"
  if [[ $point == *aside ]]; then
    # The next run that takes the lock puts the old folder back, even one that then fails.
    "$bake" bake "$work/none.ply" -o "$work/out" "${common[@]}" 2>/dev/null
    [[ $(state) == old ]] && ok || bad "$point: the next lock did not put the old folder back: $(state)"
  fi
  "$bake" bake "$work/octa.ply" -o "$work/out" "${common[@]}" "${new[@]}"; rc=$?
  [[ $rc -eq 0 && $(state) == new ]] && ok || bad "$point: the rerun (exit $rc) left $(state)"
  [[ -z $(leftovers) ]] && ok || bad "$point: left after the rerun: $(leftovers)"
done

# --- 2. SIGKILL at moments mid-bake (wherever it is then) ---
for delay in 0.3; do
  reset_old
  "$bake" bake "$work/octa.ply" -o "$work/out" "${common[@]}" "${new[@]}" &
  pid=$!
  sleep $delay
  kill -9 $pid 2>/dev/null; wait $pid 2>/dev/null
  s=$(state)
  [[ $s == old || $s == new ]] && ok || bad "killed after $delay s: the folder is $s"
  "$bake" bake "$work/octa.ply" -o "$work/out" "${common[@]}" "${new[@]}"
  [[ $(state) == new && -z $(leftovers) ]] && ok || bad "killed after $delay s, rerun: $(state), left: $(leftovers)"
done

# --- 3. Files a user put in the folder survive a rebake; a stale level does not ---
reset_old
echo note >"$work/out/notes.txt"
"$bake" bake "$work/octa.ply" -o "$work/out" "${common[@]}" "${new[@]}"
[[ $(cat "$work/out/notes.txt" 2>/dev/null) == note ]] && ok || bad "a user's file in the folder was lost"
rm -f "$work/out/notes.txt"
[[ $(state) == new ]] && ok || bad "the rebake kept files of the old one: $(ls "$work/out")"

# --- 4. Exit codes: output not writable (4), an output path through a file (2), a cache that
# cannot be written (a warning; the bake goes on) ---
rm -rf "$work/full"
(trap '' XFSZ; ulimit -f 8; exec "$bake" bake "$work/octa.ply" -o "$work/full" "${common[@]}" "${old[@]}") 2>"$work/err"; rc=$?
[[ $rc -eq 4 && ! -e $work/full ]] && grep -q "cannot write output" "$work/err" && ok || bad "a full output: exit $rc, expected 4: $(cat "$work/err")"
[[ -z $(find "$work" -maxdepth 1 -name '.full.qf-*') ]] && ok || bad "a full output left $(find "$work" -maxdepth 1 -name '.full.qf-*')"
"$bake" bake "$work/octa.ply" -o "$work/octa.ply/out" "${common[@]}" 2>"$work/err"; rc=$?
[[ $rc -eq 2 ]] && ok || bad "an output folder under a file: exit $rc, expected 2: $(cat "$work/err")"
rm -rf "$work/out"
"$bake" bake "$work/octa.ply" -o "$work/out" --no-measure --no-report-html --mesh-lods none --textures webp "${old[@]}" --cache /dev/null/amg 2>"$work/err"; rc=$?
[[ $rc -eq 0 && $(state) == old ]] && grep -q "could not be written, baked without it" "$work/err" && ok ||
  bad "an unwritable cache: exit $rc: $(cat "$work/err")"

# --- 5. A batch: an asset that is a folder, or takes the report's name, fails alone ---
mkdir -p "$work/b/folder.ply"
cp "$work/octa.ply" "$work/b/octa.ply"
printf '{"assets": ["folder.ply", {"input": "octa.ply", "name": "batch-report.json"}, "octa.ply"], "defaults": {"primitives": [20], "ldi": 64}}' >"$work/b/m.json"
"$bake" batch "$work/b/m.json" -o "$work/b/out" -q -k --no-cache 2>"$work/err"; rc=$?
[[ $rc -eq 1 && -f $work/b/out/batch-report.json ]] && ok || bad "batch with bad assets: exit $rc, report: $(ls "$work/b/out" 2>&1): $(cat "$work/err")"
[[ $(field "$work/b/out/batch-report.json" '[(a["status"], a.get("exit_code")) for a in r["assets"]]') == "[('failed', 1), ('failed', 1), ('baked', 0)]" ]] && ok ||
  bad "batch statuses: $(field "$work/b/out/batch-report.json" '[(a["status"], a.get("exit_code"), a.get("error")) for a in r["assets"]]')"
[[ $(field "$work/b/out/batch-report.json" 'r["assets"][1]["error"]["code"]') == batch.name ]] && ok || bad "the report's name: not batch.name"

finish crash
