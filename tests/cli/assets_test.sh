#!/usr/bin/env bash
# Game assets in (Debian's assimp-testmodels, installed by scripts/install-deps.sh, and
# tests/data/textured): every valid glTF 2.0 / OBJ model bakes to files the Khronos validator
# passes; every malformed one exits 1 with one message naming the file, and writes nothing. A
# textured asset's finest level, drawn by the engine method, is within 2 dB of its own sampled
# points' floor against the asset.
# Exits 77 (skipped) when the package is not installed.
# usage: assets_test.sh QF_BAKE QF_RENDER VALIDATOR_DIR DATA_DIR
set -u
bake=$1 render=$2 validator=$3 data=$4
models=${QF_ASSIMP_MODELS:-/usr/share/assimp/models}
[[ -d "$models/glTF2" ]] || { echo "assimp-testmodels not installed (scripts/install-deps.sh); skipping"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

# 1. Valid models read; a few of them bake (small LDI: the point is the reader, not the bake), and
#    their outputs validate.
readable=(glTF2/BoxTextured-glTF-Binary/BoxTextured.glb glTF2/BoxTextured-glTF-Embedded/BoxTextured.gltf
          glTF2/BoxTexcoords-glTF/boxTexcoords.gltf glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb
          glTF2/simple_skin/simple_skin.gltf glTF2/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf
          glTF2/cameras/Cameras.gltf glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_13.gltf
          OBJ/box.obj OBJ/cube_usemtl.obj OBJ/regr01.obj)
for m in "${readable[@]}"; do
  "$bake" info "$models/$m" >"$work/log" 2>&1 && ok || bad "$m does not read: $(tail -1 "$work/log")"
done
grep -q "textures:    1 211x211" < <("$bake" info "$models/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb") && ok || bad "BoxTextured.glb: texture not read"
"$bake" info "$models/glTF2/simple_skin/simple_skin.gltf" 2>&1 | grep -q "warning: .*bind pose" && ok || bad "simple_skin: no skin warning"
valid=(glTF2/BoxTextured-glTF/BoxTextured.gltf glTF2/textureTransform/TextureTransformTest.gltf
       glTF2/draco/2CylinderEngine.gltf OBJ/spider.obj)
for m in "${valid[@]}"; do
  out="$work/ok/$(echo "$m" | tr '/' '_')"
  if "$bake" bake "$models/$m" -o "$out" --ldi 64 --no-cache --cheap-triangles 0 >"$work/log" 2>&1; then
    for f in "$out"/*.glb; do
      if node "$validator/validate.js" "$f" >"$work/v" 2>&1; then ok; else bad "$m: $(basename "$f") does not validate: $(tail -3 "$work/v")"; fi
    done
  else
    bad "$m did not bake: $(tail -2 "$work/log")"
  fi
done

# 2. Malformed models: exit 1, one message naming the file and what was wrong, nothing written.
expect_error() {  # MODEL TEXT
  local out="$work/bad/$(echo "$1" | tr '/' '_')"
  "$bake" bake "$models/$1" -o "$out" --no-cache >"$work/out" 2>"$work/err"
  local rc=$?
  if [[ $rc -ne 1 ]]; then bad "$1: exit $rc, expected 1"; return; fi
  if ! grep -qF "$(basename "$1")" "$work/err" || ! grep -qF "$2" "$work/err"; then bad "$1: message lacks '$2': $(cat "$work/err")"; return; fi
  if [[ -e "$out" && -n "$(ls -A "$out")" ]]; then bad "$1: wrote $(ls "$out")"; return; fi
  ok
}
expect_error glTF2/IndexOutOfRange/IndexOutOfRange.gltf "meshes[0].primitives[0].indices: index 255 out of range (24 vertices)"
expect_error glTF2/IndexOutOfRange/AllIndicesOutOfRange.gltf "out of range"
expect_error glTF2/RecursiveNodes/RecursiveNodes.gltf "is its own ancestor"
expect_error glTF2/MissingBin/BoxTextured.gltf "BoxTextured0.bin"
expect_error glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb "non-finite"
expect_error glTF2/SchemaFailures/sceneWrongType.gltf "scene: expected a non-negative integer"
expect_error glTF2/wrongTypes/badArray.gltf "meshes[0].primitives: expected an array"
expect_error glTF2/wrongTypes/badObject.gltf "pbrMetallicRoughness: expected an object"
expect_error glTF2/wrongTypes/badString.gltf "name: expected a string"
expect_error glTF2/wrongTypes/badUint.gltf "index: expected a non-negative integer, found -1"
expect_error glTF2/wrongTypes/badNumber.gltf "scale: expected a number"
expect_error glTF2/wrongTypes/badExtension.gltf "KHR_texture_transform: expected an object"
expect_error glTF2/BoxTextured-glTF-techniqueWebGL/BoxTextured.gltf "requires the extension KHR_technique_webgl"
expect_error glTF2/TestNoRootNode/NoScene.gltf "nothing to bake"
expect_error glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_00.gltf "point or line primitives skipped"
expect_error OBJ/box_UTF16BE.obj "binary data"
# With --drop-nonfinite the bad vertices go, and with them every triangle of this box: still exit 1.
"$bake" info "$models/glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb" --drop-nonfinite 2>&1 | grep -q "no triangles to bake" &&
  ok || bad "BoxWithInfinites.glb --drop-nonfinite: expected 'no triangles to bake'"

# 3. A textured asset (the Cesium box): its finest level against the asset, within 2 dB of the
#    floor of its own sampled points drawn as splats, both against the asset drawn at the size
#    (--truth 1: supersampled splats are smoother than any engine draws them).
box="$models/glTF2/BoxTextured-glTF/BoxTextured.gltf"
"$bake" bake "$box" -o "$work/box" --no-cache --cheap-triangles 0 >/dev/null 2>&1 || bad "BoxTextured.gltf did not bake"
"$bake" convert "$box" "$work/box_points.ply" >/dev/null 2>&1 || bad "BoxTextured.gltf did not sample"
finest=$(ls "$work"/box/BoxTextured_L*.glb | sort -V | head -1)
psnr() {
  "$render" eval "$box" "$1" --views 8 --size 128 --truth 1 -o "$work/eval.json" >/dev/null 2>&1 &&
    python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["mean"]["engine"]["psnr"])' "$work/eval.json"
}
level=$(psnr "$finest") floor=$(psnr "$work/box_points.ply")
if python3 -c "import sys; sys.exit(0 if $level >= $floor - 2 else 1)"; then ok; else bad "BoxTextured finest level $level dB, points' floor $floor dB"; fi
echo "BoxTextured: finest level $level dB, sampled points (floor) $floor dB"
# By default the cube (12 triangles, opaque) is cheap already: measured, not baked; no file but the
# manifest and reports, and its chain is the cube itself at every size.
"$bake" bake "$box" -o "$work/box_default" --no-cache >/dev/null 2>&1 || bad "BoxTextured.gltf default bake"
python3 - "$work/box_default" <<'PY' && ok || bad "BoxTextured's default bake is not the cube itself"
import json, os, sys
d = sys.argv[1]
m = json.load(open(os.path.join(d, "manifest.json")))
assert m["cheap_asset"]["triangles"] == 12 and not [f for f in os.listdir(d) if f.endswith(".glb")], os.listdir(d)
c = m["recommended_chain"]["chain"]
assert [e["kind"] for e in c] == ["asset"] and c[0]["min_pixels"] == 0, c
PY

echo "assets: $pass passed, $fail failed"
[[ $fail -eq 0 ]]
