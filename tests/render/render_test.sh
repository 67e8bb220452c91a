#!/usr/bin/env bash
# Headless renders of the samples (runtime_gl through EGL on Mesa llvmpipe): golden images with
# per-case tolerances (tests/golden/cases.tsv; regenerate with scripts/update-goldens.sh and review
# the pictures), byte-identical repeats, correctness over any background, eval's report, the
# window under Xvfb, and clear errors.
# usage: render_test.sh QF_BAKE QF_RENDER REPO_ROOT        (QF_UPDATE_GOLDENS=1: rewrite the goldens)
set -u
bake=$1 render=$2 root=$3
golden=$root/tests/golden
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

# Inputs: the octahedron sample baked with its defaults (level 5 and the coarsest) and at its merged
# 8-domain level.
"$bake" "$root/samples/octahedron.ply" -o "$work/oct" --cache "$work/cache" -q || bad "bake defaults"
"$bake" "$root/samples/octahedron.ply" -o "$work/oct8" --merge --levels 8 --cache "$work/cache" -q || bad "bake merged"
declare -A file=([points]="$root/samples/octahedron.ply" [merged]="$work/oct8/octahedron_L8.glb"
                 [level5]="$work/oct/octahedron_L5.glb" [coarsest]="$(ls "$work"/oct/octahedron_L*.glb | sort -V | tail -1)")

# 1. Goldens. cases.tsv: name, input key, size, max channel difference, share of pixels allowed
#    to exceed it (percent), then qf-render options.
while IFS=$'\t' read -r name key size maxdiff share opts; do
  [[ -z "$name" || "$name" == \#* ]] && continue
  out="$work/$name.png"
  # shellcheck disable=SC2086
  if ! "$render" "${file[$key]}" -o "$out" --size "$size" --frame "${file[points]}" $opts 2>"$work/err"; then
    bad "$name: render failed: $(cat "$work/err")"; continue
  fi
  if [[ "${QF_UPDATE_GOLDENS:-0}" == 1 ]]; then
    cp "$out" "$golden/$name.png"; echo "updated $name"; ok; continue
  fi
  if [[ ! -f "$golden/$name.png" ]]; then bad "$name: no golden (scripts/update-goldens.sh)"; continue; fi
  if idiff -q -fail "$maxdiff" -failpercent "$share" "$golden/$name.png" "$out" >"$work/idiff" 2>&1; then ok
  else bad "$name: differs from its golden beyond ($maxdiff, $share%): $(tail -3 "$work/idiff" | tr '\n' ' ')"; fi
done <"$golden/cases.tsv"
[[ "${QF_UPDATE_GOLDENS:-0}" == 1 ]] && { echo "goldens updated: $pass"; exit 0; }

# 2. Byte-identical across runs, for every method.
for m in overlap two-pass backface-hard backface-soft blend-all no-blend engine; do
  "$render" "${file[level5]}" -o "$work/a.png" --size 128 --method "$m" 2>/dev/null
  "$render" "${file[level5]}" -o "$work/b.png" --size 128 --method "$m" 2>/dev/null
  if cmp -s "$work/a.png" "$work/b.png"; then ok; else bad "method $m: two renders differ"; fi
done

# 3. Right over any background: the additive methods composite by coverage, so a render over grey
#    equals the renders over black (B) and white (W) combined, B + (W - B) * 128/255, to 1 LSB.
for m in overlap two-pass backface-soft; do
  for bg in 0,0,0 255,255,255 128,128,128; do
    "$render" "${file[merged]}" -o "$work/bg_${bg//,/_}.png" --size 128 --method "$m" --background "$bg" 2>/dev/null
  done
  maxerr=$(oiiotool "$work/bg_255_255_255.png" "$work/bg_0_0_0.png" --sub --mulc 0.50196 "$work/bg_0_0_0.png" --add \
           "$work/bg_128_128_128.png" --absdiff --printstats 2>/dev/null | awk '/Stats Max/ {m=$3; for(i=4;i<=5;i++) if($i>m) m=$i; print m}')
  # oiiotool prints 0..1 values.
  if awk -v e="$maxerr" 'BEGIN { exit !(e != "" && e * 255 <= 1.01) }'; then ok; else bad "method $m over grey: max error $maxerr (x255)"; fi
  # Far from the object the background shows unchanged.
  corner=$(oiiotool "$work/bg_128_128_128.png" --cut 4x4+0+0 --printstats 2>/dev/null | awk '/Stats Avg/ {print $3}')
  if awk -v c="$corner" 'BEGIN { exit !(c != "" && c * 255 > 127.99 && c * 255 < 128.01) }'; then ok; else bad "method $m: corner is $corner, not the background 128"; fi
done

# 4. eval: 26 views, the report's fields, the difference images; the merged octahedron's figures
#    (measured 19.8 dB, IoU 0.958) guard against regressions.
if "$render" eval "${file[points]}" "${file[merged]}" --size 128 -o "$work/eval.json" 2>"$work/err"; then
  ok
  python3 - "$work/eval.json" <<'PY' && ok || bad "eval report: see above"
import json, sys
r = json.load(open(sys.argv[1]))
assert r["views"] == 26 and len(r["per_view"]) == 26, "26 views"
m = r["mean"]["overlap"]
for k in ("psnr", "iou", "mae", "holes", "see_through"): assert k in m and k in r["mean"]["engine"], k
assert m["psnr"] >= 18.5 and m["iou"] >= 0.95, f"octahedron fidelity regressed: {m}"
e = r["mean"]["engine"]
assert r["engine_alpha_mode"] == "MASK" and e["holes"] <= 0.02 and e["see_through"] == 0, f"engine path: {e}"
PY
  for f in eval_diff.exr eval_diff.png; do [[ -s "$work/$f" ]] && ok || bad "eval wrote no $f"; done
else
  bad "eval failed: $(cat "$work/err")"
fi

# 5. The window (Xvfb): same picture as headless (window surface vs framebuffer object), to 2 LSB
#    with the plain sum. The two rasterise 1 LSB apart at a few silhouette pixels; the overlap
#    method's default normalising composite divides by the coverage there (down to 1/4), so the
#    default frame is held to 4 LSB; at most 0.1% of pixels may exceed the bound (double-sided
#    levels put a few back-facing quads' low-coverage edges at the silhouette: 1 pixel of 16384 at 8 LSB).
if command -v xvfb-run >/dev/null; then
  for case in "plain 0 0.008" "normalised 0.5 0.016"; do
    read -r name t tol <<<"$case"
    if xvfb-run -a -s "-screen 0 640x480x24" "$render" view "${file[merged]}" --frames 3 --size 128 --normalize "$t" -o "$work/win.png" 2>"$work/err"; then
      "$render" "${file[merged]}" -o "$work/head.png" --size 128 --normalize "$t" 2>/dev/null
      if idiff -q -fail "$tol" -failpercent 0.1 -warn "$tol" -warnpercent 0.1 "$work/head.png" "$work/win.png" >/dev/null 2>&1; then ok
      else bad "window frame ($name) differs from the headless render"; fi
    else
      bad "view under Xvfb failed: $(cat "$work/err")"
    fi
  done
  if DISPLAY=:987 "$render" view "${file[merged]}" --frames 1 2>"$work/err"; then bad "view without a display succeeded"
  elif grep -q "X display" "$work/err"; then ok; else bad "view without a display: unclear message: $(cat "$work/err")"; fi
else
  echo "xvfb-run missing (scripts/install-deps.sh installs it): window test not run"; bad "no xvfb-run"
fi

# 5b. A combined LOD file (of the impostor levels: --no-chain) shows exactly one level: the one its
#     screen coverages pick, or --lod N;
#     its nodes carry the _LOD0.._LODn names engines group as LODs.
"$bake" "$root/samples/octahedron.ply" -o "$work/lodf" --lod-file --no-chain --cache "$work/cache" -q || bad "bake --lod-file"
lods="$work/lodf/octahedron_lods.glb"
levels=$(python3 -c 'import json,sys; print(" ".join(str(l["primitives"]) for l in json.load(open(sys.argv[1]))["levels"]))' "$work/lodf/manifest.json")
for n in 0 1 2 3; do
  want=$(echo "$levels" | cut -d' ' -f$((n + 1)))
  if "$render" "$lods" -o "$work/lod.png" --size 64 --lod $n 2>"$work/err" && grep -q "LOD $n of 4 ($want quads" "$work/err"; then ok
  else bad "--lod $n draws level $n alone ($want quads): $(cat "$work/err")"; fi
done
"$render" "$lods" -o "$work/lod.png" --size 64 --distance 1000 2>"$work/err" && grep -q "LOD 3 of 4" "$work/err" && ok ||
  bad "far away the coarsest level is chosen: $(cat "$work/err")"
"$render" "$lods" -o "$work/lod.png" --lod 4 2>"$work/err"; [[ $? -eq 2 ]] && grep -q "4 level" "$work/err" && ok || bad "--lod out of range: $(cat "$work/err")"
python3 - "$lods" <<'PY' && ok || bad "lod file node names"
import json, struct, sys
b = open(sys.argv[1], "rb").read()
n = struct.unpack_from("<I", b, 12)[0]
g = json.loads(b[20:20 + n])
assert sorted(x["name"] for x in g["nodes"]) == [f"impostor_LOD{i}" for i in range(4)], [x["name"] for x in g["nodes"]]
PY

# 6. Errors: exit code, message naming the file, no output left.
expect() {  # expect CODE PATTERN ARGS...
  local code=$1 pattern=$2; shift 2
  rm -f "$work/out.png"
  "$render" "$@" 2>"$work/err"; local rc=$?
  if [[ $rc == "$code" ]] && { [[ -z "$pattern" ]] || grep -q -- "$pattern" "$work/err"; } && [[ ! -e "$work/out.png" ]]; then ok
  else bad "qf-render $*: exit $rc (want $code), stderr: $(cat "$work/err")"; fi
}
expect 1 "no such file" "$work/missing.glb" -o "$work/out.png"
head -c 300 "${file[merged]}" >"$work/truncated.glb"
expect 1 "truncated.glb" "$work/truncated.glb" -o "$work/out.png"
expect 2 "unknown render method" "${file[merged]}" -o "$work/out.png" --method painter
expect 2 "size" "${file[merged]}" -o "$work/out.png" --size 0x10
expect 2 "background" "${file[merged]}" -o "$work/out.png" --background 1,2
expect 2 "REFERENCE must be" eval "${file[merged]}" "${file[points]}"
# A point set against itself as drawn (--truth 1): the metric's own zero (PSNR 99 = identical, IoU
# 1, no holes). Against the truth (the default: drawn 8x and filtered down), the set as drawn at
# the size scores below that, and exactly as the report's as_drawn says.
"$render" eval "${file[points]}" "${file[points]}" --views 3 --size 64 --no-engine --truth 1 -o "$work/self.json" 2>/dev/null &&
  grep -q '"psnr": 99' "$work/self.json" && grep -q '"iou": 1' "$work/self.json" && ok || bad "eval of a point set against itself is not identical"
"$render" eval "${file[points]}" "${file[points]}" --views 3 --size 64 --method engine -o "$work/truth.json" 2>/dev/null &&
  python3 -c '
import json, sys
m = json.load(open(sys.argv[1]))["mean"]
sys.exit(0 if m["engine"] == m["as_drawn"] and m["engine"]["psnr"] < 99 and 0.5 < m["engine"]["soft_iou"] <= 1 else 1)' "$work/truth.json" &&
  ok || bad "eval against the truth: the set as drawn scores otherwise than its as_drawn entry"
# --no-mips: the base texture level alone. Drawn at 12 px, an eighth of its size, the level's
# engine-made mip levels (PNG, box-filtered) open holes that its base level does not (39.5% against
# 1.3% when written): what the holes at a small size owe to mip levels.
for mips in "" --no-mips; do
  "$render" eval "${file[points]}" "${file[level5]}" -m engine --no-engine --views 4 --size 12 --truth 4 $mips -o "$work/mips$mips.json" 2>/dev/null ||
    bad "eval $mips failed"
done
python3 -c '
import json, sys
a, b = (json.load(open(f))["mean"]["engine"] for f in sys.argv[1:3])
sys.exit(0 if a["holes"] > b["holes"] + 0.1 else 1)' "$work/mips.json" "$work/mips--no-mips.json" &&
  ok || bad "eval --no-mips: the base level alone opens fewer holes at an eighth of the size"
expect 0 "" --version
# Options the method does not read are refused (exit 2, naming the option), never silently ignored.
for args in "-m engine --no-lighting" "-m engine --transparency 0.5" "--alpha-mode MASK" "-m overlap --alpha-cutoff 0.3" "--no-mips"; do
  "$render" "${file[points]}" -o "$work/unused.png" --size 32 $args 2>"$work/err"
  rc=$? option=${args##*--}
  [[ $rc == 2 && ! -e "$work/unused.png" ]] && grep -q -- "--${option%% *} applies" "$work/err" && ok || bad "render $args was not refused: $(cat "$work/err")"
done

echo "render tests: $pass passed, $fail failed"
[[ $fail == 0 ]]
