#!/usr/bin/env bash
# Mesh references drawn with their materials (baker/measure/reference_scene.cpp): the textured cube as
# OBJ + MTL and as glTF (tests/data/textured) scores one bake alike under qf-render eval (engine
# PSNR within 0.05 dB), renders with its texture's red, green and blue (not the grey of an
# uncoloured mesh) and like the glTF; one primitive per material; meshes without materials keep
# the old reference (grey, scored by --method as well as the engine method).
# usage: textured_ref_test.sh QF_BAKE QF_RENDER DATA_DIR
set -u
bake=$1 render=$2 data=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
cube=$data/textured
# Counts of pixels that are clearly red, green, blue (one channel > 150, the others < 80) and of
# coloured pixels at all (channels more than 40 apart), of a PNG, via oiiotool's PPM.
colours() {
  oiiotool "$1" -d uint8 --ch R,G,B -o "$work/c.ppm" >/dev/null 2>&1 || { echo "unreadable"; return; }
  /usr/bin/python3 - "$work/c.ppm" <<'PY'
import sys
d = open(sys.argv[1], "rb").read()
head = d.split(b"\n", 3); px = head[3]
n = {"r": 0, "g": 0, "b": 0, "coloured": 0}
for i in range(0, len(px) - 2, 3):
    p = px[i:i + 3]
    for k, c in zip("rgb", range(3)):
        if p[c] > 150 and all(p[o] < 80 for o in range(3) if o != c): n[k] += 1
    if max(p) - min(p) > 40: n["coloured"] += 1
print(n["r"], n["g"], n["b"], n["coloured"])
PY
}
engine_psnr() { /usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["mean"]["engine"]["psnr"])' "$1"; }

# 1. One bake of the glTF, scored against the glTF and against the OBJ + MTL of the same cube.
"$bake" bake "$cube/cube.gltf" -o "$work/bake" --no-cache --cheap-triangles 0 -q || bad "cube.gltf did not bake"
finest=$(ls "$work"/bake/cube_L*.glb | sort -V | head -1)
"$render" eval "$cube/cube.gltf" "$finest" --views 8 --size 128 -o "$work/gltf.json" >/dev/null 2>&1 || bad "eval cube.gltf"
"$render" eval "$cube/cube.obj" "$finest" --views 8 --size 128 -o "$work/obj.json" >/dev/null 2>&1 || bad "eval cube.obj"
g=$(engine_psnr "$work/gltf.json") o=$(engine_psnr "$work/obj.json")
/usr/bin/python3 -c "import sys; sys.exit(0 if abs($g - $o) <= 0.05 else 1)" && ok || bad "engine PSNR: glTF $g dB, OBJ $o dB (more than 0.05 dB apart)"
echo "cube: engine PSNR of one bake against cube.gltf $g dB, against cube.obj $o dB"

# 2. The OBJ's picture shows the texture (by default: the engine method) and matches the glTF's.
"$render" "$cube/cube.obj" -o "$work/obj.png" --size 128 2>"$work/err" || bad "render cube.obj: $(cat "$work/err")"
grep -q "engine, 1 primitives" "$work/err" && ok || bad "cube.obj renders by the engine method as 1 primitive: $(cat "$work/err")"
read -r r gr b c < <(colours "$work/obj.png")
[[ $r -gt 50 && $gr -gt 50 && $b -gt 50 ]] && ok || bad "cube.obj: red/green/blue pixels $r/$gr/$b (expected > 50 each)"
"$render" "$cube/cube.gltf" -o "$work/gltf.png" --size 128 -m engine 2>/dev/null || bad "render cube.gltf"
idiff -q -fail 0.02 -failpercent 0.5 "$work/gltf.png" "$work/obj.png" >/dev/null 2>&1 && ok || bad "cube.obj and cube.gltf render differently"

# 3. One primitive per material: a second material (plain red Kd) on two of the six faces.
cp "$cube"/cube.{png,mtl} "$work/"
printf 'newmtl plain\nKd 1 0 0\n' >>"$work/cube.mtl"
awk '/^f / && ++n == 5 { print "usemtl plain" } { print }' "$cube/cube.obj" >"$work/two.obj"
"$render" "$work/two.obj" -o "$work/two.png" --size 128 2>"$work/err" || bad "render two.obj: $(cat "$work/err")"
grep -q "engine, 2 primitives" "$work/err" && ok || bad "two materials, two primitives: $(cat "$work/err")"

# 4. Without materials: the old reference, grey, and eval scores --method besides the engine.
grep -v "^mtllib\|^usemtl" "$cube/cube.obj" >"$work/plain.obj"
"$render" "$work/plain.obj" -o "$work/plain.png" --size 128 2>"$work/err" || bad "render plain.obj"
grep -q "overlap)" "$work/err" && ok || bad "plain.obj keeps the default method: $(cat "$work/err")"
read -r r gr b c < <(colours "$work/plain.png")
[[ $c -eq 0 ]] && ok || bad "plain.obj is grey: $c coloured pixels"
"$render" eval "$work/plain.obj" "$finest" --views 2 --size 64 -o "$work/plain.json" >/dev/null 2>&1 &&
  [[ $(/usr/bin/python3 -c 'import json,sys; print(sorted(json.load(open(sys.argv[1]))["mean"]))' "$work/plain.json") == "['as_drawn', 'engine', 'overlap']" ]] &&
  ok || bad "plain.obj: eval scores overlap and engine"

echo "textured_ref: $pass passed, $fail failed"
[[ $fail -eq 0 ]]
