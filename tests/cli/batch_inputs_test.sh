#!/usr/bin/env bash
# qf-bake batch keys an asset by the files it reads, not only the file it names: a glTF's external
# image, an OBJ's MTL and map_Kd image (tests/data/textured). Changing the texture rebakes both
# assets that use it, changing the MTL only the OBJ; unchanged (or only touched) files rebake
# nothing; a texture that goes missing fails the asset with the reader's message.
# usage: batch_inputs_test.sh QF_BAKE DATA_DIR
set -u
bake=$1 data=$2
source "$(dirname "$0")/test_lib.sh"
mkdir -p "$work/in"
cp "$data"/textured/cube.{gltf,obj,mtl,png} "$work/in/"
cat >"$work/batch.json" <<JSON
{"output": "out", "defaults": {"primitives": [20], "ldi": 32},
 "assets": [{"input": "in/cube.gltf", "name": "gltf"}, {"input": "in/cube.obj", "name": "obj"}]}
JSON
baked() { field "$work/out/batch-report.json" '[a["name"] for a in r["assets"] if a["status"] == "baked"]'; }
# A 4x4 PNG of one colour (the committed one has four quadrants): same size, new bytes.
repaint() {
  /usr/bin/python3 - "$1" <<'PY'
import struct, sys, zlib
raw = b"".join(b"\0" + bytes([10, 200, 30, 255] * 4) for _ in range(4))
chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xFFFFFFFF)
open(sys.argv[1], "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 4, 4, 8, 6, 0, 0, 0)) +
                              chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
PY
}

# 1. First run bakes both; a second run, and one after touching every file, bakes nothing.
"$bake" batch "$work/batch.json" -q 2>"$work/err"; rc=$?
[[ $rc -eq 0 && $(baked) == "['gltf', 'obj']" ]] && ok || bad "first batch bakes both (exit $rc): $(tail -3 "$work/err")"
touch "$work/in"/*
"$bake" batch "$work/batch.json" -q
[[ $(field "$work/out/batch-report.json" 'r["totals"]["up to date"]') == 2 ]] && ok || bad "unchanged files: both up to date: $(baked)"

# 2. A new texture: both assets read it, both rebake, and the rebaked impostor shows its colour.
repaint "$work/in/cube.png"
"$bake" batch "$work/batch.json" --dry-run 2>"$work/err"
grep -q "would bake gltf$" "$work/err" && grep -q "would bake obj$" "$work/err" && ok || bad "--dry-run lists both: $(cat "$work/err")"
"$bake" batch "$work/batch.json" -q
[[ $(baked) == "['gltf', 'obj']" ]] && ok || bad "a changed texture rebakes both assets: $(baked)"
"$bake" batch "$work/batch.json" -q
[[ $(baked) == "[]" ]] && ok || bad "then nothing again: $(baked)"

# 3. The MTL is the OBJ's alone.
echo "# edited" >>"$work/in/cube.mtl"
"$bake" batch "$work/batch.json" -q
[[ $(baked) == "['obj']" ]] && ok || bad "a changed MTL rebakes only the OBJ: $(baked)"

# 4. A texture gone: the glTF's key is still made, and its bake fails naming the image.
rm "$work/in/cube.png"
"$bake" batch "$work/batch.json" -k 2>"$work/err"; rc=$?
[[ $rc -eq 1 ]] && grep -q "FAILED gltf: .*cube.png" "$work/err" && ok || bad "a missing texture fails the asset by name (exit $rc): $(cat "$work/err")"
finish batch_inputs
