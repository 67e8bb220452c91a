#!/usr/bin/env bash
# The LOD examples of docs/engines.md switch a bake's per-level files at the manifest's distances: ENGINE
# three: THREE.LOD (scripts/three-render/impostor-lod.mjs); babylon: Babylon.js's Mesh.addLODLevel
# (scripts/babylon-render/impostor-lod.mjs); each shown in docs/engines.md verbatim. Run in headless
# Chromium on a baked torus, with the camera just inside and just outside every switch distance
# (D z0 / max_screen_pixels, z0 = 512 / (2 tan 30 deg)), the engine draws the level the manifest
# says; with the recommended chain (the default), its files at its max_pixels.
# usage: lod_test.sh ENGINE QF_BAKE SOURCE_DIR
set -u
engine=$1 bake=$2 src=$3
dir="$src/scripts/$engine-render"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
case $engine in
  three) package=three api=THREE.LOD ;;
  babylon) package=@babylonjs/loaders api=Mesh.addLODLevel ;;
  *) fail "unknown engine $engine" ;;
esac
[[ -f "$dir/node_modules/$package/package.json" ]] || fail "$package not installed: run scripts/install-deps.sh"
python3 - "$src/docs/engines.md" "$dir/impostor-lod.mjs" <<'PY' || fail "docs/engines.md does not show scripts/$engine-render/impostor-lod.mjs verbatim"
import sys  # a js block of its own
code = "```js\n" + open(sys.argv[2]).read().strip() + "\n```"
sys.exit(0 if code in open(sys.argv[1]).read() else 1)
PY
"$bake" generate torus -o "$work/torus.ply" -q || fail "generate"
# Plain (--no-chain): the impostor levels. Chain: the recommended chain's files at its max_pixels.
hows=(plain chain) args=()
declare -A distances expected
for how in "${hows[@]}"; do
  opts=(--no-chain); [[ $how == chain ]] && opts=(--measure-views 2)
  "$bake" "$work/torus.ply" -o "$work/$how" "${opts[@]}" -q || fail "bake ($how)"
  read -r "distances[$how]" "expected[$how]" < <(python3 - "$work/$how/manifest.json" <<'PY'
import json, math, sys
m = json.load(open(sys.argv[1]))
z0 = 512 / (2 * math.tan(math.radians(30)))
if "recommended_chain" in m:  # the baked files of the chain (no asset is passed: its entries are left out)
    pixels = [None] + [e["max_pixels"] for e in m["recommended_chain"]["chain"] if e["kind"] != "asset"][1:]
    if len(pixels) < 2: sys.exit("a chain of one file switches nothing")
else:
    pixels = [None] + [l["max_screen_pixels"] for l in sorted(m["levels"], key=lambda l: -l["primitives"]) if l["max_screen_pixels"] > 0][1:]
starts = [0 if p is None else m["bounding_box_diagonal"] * z0 / p for p in pixels]
ds, want = [], []
for i, s in enumerate(starts):
    for d in ([s * 1.05] if i == 0 else [s * 0.95, s * 1.05]) if s > 0 else [0.5 * starts[1] if len(starts) > 1 else 1.0]:
        ds.append(d)
        want.append(max(j for j, t in enumerate(starts) if d >= t))
print(",".join(f"{d:.6g}" for d in ds), ",".join(map(str, want)))
PY
  )
  args+=("$work/$how" "${distances[$how]}")
done
# One browser for both folders: a line of levels each.
shown=$(node "$dir/lod-check.mjs" "${args[@]}") || fail "lod-check: $shown"
mapfile -t lines <<<"$shown"
for i in "${!hows[@]}"; do
  how=${hows[$i]}
  [[ "${lines[$i]:-}" == "[${expected[$how]}]" ]] ||
    fail "$how: at distances ${distances[$how]} $api shows levels ${lines[$i]:-none}, the manifest says [${expected[$how]}]"
  echo "$how: $api shows the manifest's level at every distance: ${distances[$how]} -> ${lines[$i]}"
done
