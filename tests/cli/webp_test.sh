#!/usr/bin/env bash
# WebP textures (issue 32, --textures webp): every texture an EXT_texture_webp WebP image (RIFF/WEBP)
# named in the extension alone, the extension required; the manifest's texture bytes under the PNG
# bake's and its GPU bytes equal to them (both decode to RGBA8, the engine makes the mips); the same
# bytes at OMP_NUM_THREADS=1 and 2; every level drawn by `qf-render eval` (engine method) within
# 0.3 dB PSNR and 0.005 IoU of its PNG level, for a point set and for alpha-masked foliage
# (measured -0.034..+0.037 dB, IoU equal); a level whose WebP bytes are damaged is refused naming
# the file (exit 1, no crash). (With lossy colour, --webp-color 80, the octahedron's finer level
# scored 0.31 dB above PNG: lossy coding smooths its per-point colour noise as the box-filtered
# truth does; the default colour is lossless.)
# usage: webp_test.sh QF_BAKE QF_RENDER
set -u
bake=$1 render=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

"$bake" generate octahedron -o "$work/oct.ply" -q || fail "generate octahedron"
"$bake" generate bush --leaves 300 --seed 2 -o "$work/bush.glb" -q || fail "generate bush"
for t in png webp; do
  OMP_NUM_THREADS=2 "$bake" "$work/oct.ply" -o "$work/oct_$t" --primitives 200,20 --no-measure --textures $t -q || fail "bake oct $t"
  OMP_NUM_THREADS=2 "$bake" "$work/bush.glb" -o "$work/bush_$t" --primitives 100 --ldi 128 --mesh-lods none --no-measure \
    --textures $t -q || fail "bake bush $t"
done
OMP_NUM_THREADS=1 "$bake" "$work/oct.ply" -o "$work/oct_webp1" --primitives 200,20 --no-measure --textures webp -q || fail "bake oct webp, 1 thread"
for f in "$work/oct_webp"/*.glb; do
  cmp -s "$f" "$work/oct_webp1/$(basename "$f")" || fail "WebP output $(basename "$f") differs between 1 and 2 threads"
done

python3 - "$work" <<'PY' || fail "the WebP bakes' files or manifests"
import json, os, struct, sys
work = sys.argv[1]
for bake in ("oct", "bush"):
    png, webp = (json.load(open(os.path.join(work, f"{bake}_{t}", "manifest.json"))) for t in ("png", "webp"))
    assert json.load(open(os.path.join(work, f"{bake}_webp", "report.json")))["settings"]["textures"] == "webp"
    assert len(png["levels"]) == len(webp["levels"]) > 0
    for p, w in zip(png["levels"], webp["levels"]):
        assert p["atlas_sides"] == w["atlas_sides"] and p["gpu_bytes"] == w["gpu_bytes"], (p, w)
        assert 0 < w["texture_bytes"] < p["texture_bytes"] and w["texture_bytes"] < w["bytes"] < p["bytes"], (p, w)
        data = open(os.path.join(work, f"{bake}_webp", w["file"]), "rb").read()
        length = struct.unpack_from("<I", data, 12)[0]
        doc, bin0 = json.loads(data[20:20 + length]), 20 + length + 8
        assert sorted(doc["extensionsRequired"]) == ["EXT_texture_webp", "KHR_mesh_quantization"] and "EXT_texture_webp" in doc["extensionsUsed"]
        images = set()
        for t in doc["textures"]:
            assert "source" not in t, t
            i = t["extensions"]["EXT_texture_webp"]["source"]
            img, images = doc["images"][i], images | {i}
            view = doc["bufferViews"][img["bufferView"]]
            head = data[bin0 + view.get("byteOffset", 0):][:12]
            assert img["mimeType"] == "image/webp" and head[:4] == b"RIFF" and head[8:] == b"WEBP", (w["file"], img, head)
        # colour and normal map per atlas image, as in the PNG level
        assert len(images) == len(doc["images"]) >= 2 * len(doc["materials"]), w["file"]
print("ok   WebP bakes: extension required, RIFF/WEBP images, texture bytes " + ", ".join(
    f'{bake} {sum(l["texture_bytes"] for l in json.load(open(os.path.join(work, f"{bake}_webp", "manifest.json")))["levels"]):,} '
    f'vs PNG {sum(l["texture_bytes"] for l in json.load(open(os.path.join(work, f"{bake}_png", "manifest.json")))["levels"]):,}'
    for bake in ("oct", "bush")))
PY

# Each WebP level against its PNG level, drawn by the engine method at 128 px from 8 views.
status=0
for png in "$work"/oct_png/*_L*.glb "$work"/bush_png/*_L*.glb; do
  ref="$work/oct.ply"; [[ $png == */bush_png/* ]] && ref="$work/bush.glb"
  webp="${png/_png\//_webp/}"
  for f in "$png" "$webp"; do
    "$render" eval "$ref" "$f" --views 8 --size 128 -m engine --truth 2 -o "$f.json" 2>"$work/err" || fail "eval $f: $(tail -2 "$work/err")"
  done
  python3 - "$png.json" "$webp.json" "$(basename "$(dirname "$webp")")/$(basename "$webp")" <<'PY' || status=1
import json, sys
p, w = (json.load(open(f))["mean"]["engine"] for f in sys.argv[1:3])
dp, di = w["psnr"] - p["psnr"], w["iou"] - p["iou"]
ok = abs(dp) <= 0.3 and abs(di) <= 0.005
print(f"{'ok  ' if ok else 'FAIL'} {sys.argv[3]}: {w['psnr']:.3f} dB IoU {w['iou']:.4f} vs PNG {p['psnr']:.3f} dB IoU {p['iou']:.4f} ({dp:+.3f} dB, {di:+.4f})")
sys.exit(0 if ok else 1)
PY
done

# A level whose first WebP image is damaged (its data zeroed after the RIFF header): refused, naming
# the file and the image, exit 1.
level=$(ls "$work"/oct_webp/*_L*.glb | head -n 1)
python3 - "$level" "$work/damaged.glb" <<'PY' || fail "damage a level"
import json, struct, sys
data = bytearray(open(sys.argv[1], "rb").read())
length = struct.unpack_from("<I", data, 12)[0]
doc, bin0 = json.loads(data[20:20 + length]), 20 + length + 8
view = doc["bufferViews"][doc["images"][0]["bufferView"]]
start = bin0 + view.get("byteOffset", 0)
data[start + 12:start + view["byteLength"]] = bytes(view["byteLength"] - 12)
open(sys.argv[2], "wb").write(data)
PY
"$render" render "$work/damaged.glb" -o "$work/damaged.png" -m engine >"$work/out" 2>"$work/err"
rc=$?
[[ $rc == 1 ]] && grep -q "damaged.glb" "$work/err" && grep -qi "webp" "$work/err" && [[ ! -e "$work/damaged.png" ]] ||
  fail "a damaged WebP image: exit $rc, $(head -c 300 "$work/err")"
echo "ok   a damaged WebP image is refused: $(head -c 200 "$work/err")"
exit $status
