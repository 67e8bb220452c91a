#!/usr/bin/env bash
# The pages for people, opened in headless Chromium (scripts/web-render/check-page.mjs): a bake's
# report.html (a small mesh with impostor levels, mesh LODs, the point impostor and the recommended
# chain), qf-diff --html of a change of one level (the page shows that level and the manifest only,
# with old / new / difference images per view), and a batch's page (one asset baked, one failed
# with its message). Each loads with no console error and no request outside itself, every image
# decodes, and its figures equal the JSON's (manifest.json, report.json, qf-diff --json, the batch
# report). A bake with --no-report-html writes none (and removes an earlier one); without a GL
# driver the page says it has no images. QF_PAGE_SHOTS=DIR keeps a screenshot of each page there.
# usage: pages_test.sh QF_BAKE QF_DIFF SOURCE_DIR
set -u
bake=$1 diff=$2 src=$3
source "$src/tests/cli/test_lib.sh"
check_page="$src/scripts/web-render/check-page.mjs"
[[ -f "$src/scripts/three-render/node_modules/playwright-core/package.json" ]] ||
  { echo "FAIL: playwright-core not installed: run scripts/install-deps.sh"; exit 1; }
[[ -x "${QF_CHROMIUM:-/usr/bin/chromium}" ]] || { echo "FAIL: no Chromium at ${QF_CHROMIUM:-/usr/bin/chromium}: run scripts/install-deps.sh"; exit 1; }
shots=${QF_PAGE_SHOTS:-$work/shots}
mkdir -p "$shots"
page() {  # page KIND PAGE [JSON]: checked in Chromium, screenshot in $shots
  node "$check_page" "$@" --shot "$shots/$1.png" >"$work/page.out" 2>&1 && ok || bad "$1 page: $(cat "$work/page.out")"
}

# --- a bake's page: every kind of output and the chain (one view measured: cheap) ---
"$bake" generate sphere --mesh --subdivisions 8 -o "$work/m.ply" -q
args=(-n 100,30 --ldi 96 --measure-views 1 -q)
"$bake" "$work/m.ply" -o "$work/a" "${args[@]}" || bad "bake a"
[[ -s $work/a/report.html ]] && ok || bad "the bake wrote no report.html: $(ls "$work/a")"
page bake "$work/a/report.html"
[[ $(field "$work/a/report.json" '[s["stage"] for s in r["stages"]][-1]') == "report page" ]] && ok || bad "the page's time is not in report.json"

# --- qf-diff --html: one level changed (--max-texture 16 reaches only the finer level's textures) ---
"$bake" "$work/m.ply" -o "$work/b" "${args[@]}" --max-texture 16 || bad "bake b"
"$diff" "$work/a" "$work/b" --json --html "$work/diff" >"$work/diff.json"
[[ $? -eq 1 && -s $work/diff/index.html ]] && ok || bad "qf-diff --html: no page, or not 'different'"
changed=$(field "$work/diff.json" 'sorted(f["name"] for f in r["files"] if f["status"] != "identical")')
[[ $changed == "['m_L7.glb', 'manifest.json']" ]] && ok || bad "expected one level and the manifest to change, got $changed"
page diff "$work/diff/index.html" "$work/diff.json"
n=$(grep -c '<section class="changed"' "$work/diff/index.html")
[[ $n -eq 2 ]] && ! grep -q 'data-file="m_L9.glb"' "$work/diff/index.html" && ok || bad "the diff page shows files that did not change ($n sections)"

# --- the batch's page: one asset baked, one failing with its message (--keep-going) ---
printf 'ply\nformat ascii 1.0\nelement vertex 3\n' >"$work/broken.ply"
cat >"$work/batch.json" <<EOF
{"output": "out", "defaults": {"primitives": [30], "ldi": 64, "mesh-lods": "none", "measure-views": 1},
 "assets": ["m.ply", "broken.ply"]}
EOF
"$bake" batch "$work/batch.json" -k -q -j 2
[[ $? -eq 1 && -s $work/out/batch-report.html && -s $work/out/m/report.html ]] && ok || bad "batch: no page, or not exit 1: $(ls "$work/out")"
page batch "$work/out/batch-report.html" "$work/out/batch-report.json"

# --- no page when asked for none; an earlier one is not left behind ---
small=(-n 30 --ldi 64 --mesh-lods none -q)
"$bake" "$work/m.ply" -o "$work/a" "${small[@]}" --no-measure --no-report-html
[[ ! -e $work/a/report.html ]] && ok || bad "--no-report-html left a report.html"

# --- no GL driver: the figures without images, and a note saying so ---
__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json "$bake" "$work/m.ply" -o "$work/nogl" "${small[@]}" 2>/dev/null
grep -q 'id="no-images"' "$work/nogl/report.html" && ! grep -q '<img' "$work/nogl/report.html" && ok || bad "a page without GL has images or no note"
finish pages
