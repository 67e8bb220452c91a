#!/usr/bin/env bash
# The README's THREE.LOD example (scripts/three-render/impostor-lod.mjs, shown there verbatim)
# switches a bake's per-level files in three.js at the manifest's distances: run in headless
# Chromium on a baked torus, with the camera just inside and just outside every switch distance
# (D z0 / max_screen_pixels, z0 = 512 / (2 tan 30 deg)), it shows the level the manifest says.
# usage: three_lod_test.sh QF_BAKE SOURCE_DIR
set -u
bake=$1 src=$2
three="$src/scripts/three-render"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
[[ -f "$three/node_modules/three/package.json" ]] || fail "three.js not installed: run scripts/install-deps.sh"
python3 - "$src/README.md" "$three/impostor-lod.mjs" <<'PY' || fail "the README does not show scripts/three-render/impostor-lod.mjs verbatim"
import sys  # shown in a list item of the README: indented by two spaces
code = "\n".join("  " + l if l else "" for l in open(sys.argv[2]).read().strip().split("\n"))
sys.exit(0 if code in open(sys.argv[1]).read() else 1)
PY
"$bake" generate torus -o "$work/torus.ply" -q || fail "generate"
"$bake" "$work/torus.ply" -o "$work/bake" -q || fail "bake"
read -r distances expected < <(python3 - "$work/bake/manifest.json" <<'PY'
import json, math, sys
m = json.load(open(sys.argv[1]))
z0 = 512 / (2 * math.tan(math.radians(30)))
levels = sorted(m["levels"], key=lambda l: -l["primitives"])
starts = [0] + [m["bounding_box_diagonal"] * z0 / l["max_screen_pixels"] for l in levels[1:]]
ds, want = [], []
for i, s in enumerate(starts):
    for d in ([s * 1.05] if i == 0 else [s * 0.95, s * 1.05]) if s > 0 else [0.5 * starts[1]]:
        ds.append(d)
        want.append(max(j for j, t in enumerate(starts) if d >= t))
print(",".join(f"{d:.6g}" for d in ds), ",".join(map(str, want)))
PY
)
shown=$(node "$three/lod-check.mjs" "$work/bake" ${distances//,/ }) || fail "lod-check: $shown"
[[ "$shown" == "[$expected]" ]] || fail "at distances $distances THREE.LOD shows levels $shown, the manifest says [$expected]"
echo "THREE.LOD shows the manifest's level at every distance: $distances -> $shown"
