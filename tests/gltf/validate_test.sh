#!/usr/bin/env bash
# Every .glb the baker writes passes the Khronos glTF-Validator with 0 errors and 0 warnings.
# usage: validate_test.sh WRITE_LEVELS VALIDATOR_DIR
set -u
writer=$1 validator=$2
[[ -f "$validator/node_modules/gltf-validator/package.json" ]] || { echo "validator not installed (scripts/install-deps.sh)"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$writer" "$work" || exit 1
files=("$work"/*.glb)
[[ ${#files[@]} -ge 19 ]] || { echo "expected 19 .glb files, got ${#files[@]}"; exit 1; }
node "$validator/validate.js" "${files[@]}"
status=$?
# The extension block of every file, and the schema's examples, against the extension's schema.
schema_dir="$(dirname "$0")/../../schemas/QF_impostor_level/schema"
/usr/bin/python3 - "$schema_dir" "${files[@]}" <<'PY' || exit 1
import glob, json, os, struct, sys
import jsonschema
schema_dir, files = sys.argv[1], sys.argv[2:]
schema = json.load(open(os.path.join(schema_dir, "glTF.QF_impostor_level.schema.json")))
check = jsonschema.Draft202012Validator(schema)
bad = 0
point_dir = os.path.join(schema_dir, "..", "..", "QF_point_impostor", "schema")
point_check = jsonschema.Draft202012Validator(json.load(open(os.path.join(point_dir, "glTF.QF_point_impostor.schema.json"))))
for f in sorted(glob.glob(os.path.join(point_dir, "examples", "*.json"))):
    if point_check.is_valid(json.load(open(f))) != os.path.basename(f).startswith("valid"):
        print(f, "is misjudged by the schema"); bad = 1
for f in files:
    data = open(f, "rb").read()
    length = struct.unpack_from("<I", data, 12)[0]
    doc = json.loads(data[20:20 + length])
    if "_ktx2" in f:
        # KTX2 textures (KHR_texture_basisu) without fallback: required, every texture names a
        # KTX2 image (identifier checked) in the extension alone, mip levels written in.
        bin0 = 20 + length + 8
        for t in doc["textures"]:
            img = doc["images"][t.get("extensions", {}).get("KHR_texture_basisu", {}).get("source", -1)]
            view = doc["bufferViews"][img["bufferView"]]
            head = data[bin0 + view.get("byteOffset", 0):bin0 + view.get("byteOffset", 0) + 48]
            if "source" in t or img.get("mimeType") != "image/ktx2" or head[:12] != b"\xabKTX 20\xbb\r\n\x1a\n" \
                    or struct.unpack_from("<I", head, 40)[0] < 2:
                print(f, "KTX2 texture wrong"); bad = 1
        if "KHR_texture_basisu" not in doc.get("extensionsRequired", []) or "KHR_texture_basisu" not in doc["extensionsUsed"]:
            print(f, "KHR_texture_basisu not required"); bad = 1
    if "_webp" in f:
        # WebP textures (EXT_texture_webp) without fallback: required, every texture names a WebP
        # image (RIFF....WEBP) in the extension alone.
        bin0 = 20 + length + 8
        for t in doc["textures"]:
            img = doc["images"][t.get("extensions", {}).get("EXT_texture_webp", {}).get("source", -1)]
            view = doc["bufferViews"][img["bufferView"]]
            head = data[bin0 + view.get("byteOffset", 0):bin0 + view.get("byteOffset", 0) + 12]
            if "source" in t or img.get("mimeType") != "image/webp" or head[:4] != b"RIFF" or head[8:12] != b"WEBP":
                print(f, "WebP texture wrong"); bad = 1
        if "EXT_texture_webp" not in doc.get("extensionsRequired", []) or "EXT_texture_webp" not in doc["extensionsUsed"]:
            print(f, "EXT_texture_webp not required"); bad = 1
    if f.endswith("_lods.glb"):
        # Every level under MSFT_lod: only the finest node in the scene, the others as its ids,
        # one coverage per level, decreasing; no QF extension (a runtime reads the level files).
        root = doc["nodes"][doc["scenes"][0]["nodes"][0]]
        ids = root["extensions"]["MSFT_lod"]["ids"]
        cov = root["extras"]["MSFT_screencoverage"]
        if len(doc["scenes"][0]["nodes"]) != 1 or not ids or len(cov) != len(ids) + 1 or cov != sorted(cov, reverse=True) \
                or "extensions" in doc or set(doc["extensionsUsed"]) - {"KHR_mesh_quantization"} != {"MSFT_lod"} | ({"KHR_texture_basisu"} if "_ktx2" in f else set()) \
                | ({"EXT_texture_webp"} if "_webp" in f else set()) \
                or ("KHR_mesh_quantization" in doc["extensionsUsed"]) != ("KHR_mesh_quantization" in doc.get("extensionsRequired", [])):
            print(f, "MSFT_lod structure wrong"); bad = 1
        continue
    if f.endswith("_cluster_draco.glb"):
        # Draco without fallback: required, accessors without bufferView, the stream in a bufferView.
        tri = [p for p in doc["meshes"][0]["primitives"] if p.get("mode", 4) == 4][0]
        ext = tri["extensions"]["KHR_draco_mesh_compression"]
        if doc.get("extensionsRequired") != ["KHR_draco_mesh_compression"] or "bufferView" in doc["accessors"][tri["attributes"]["POSITION"]] \
                or set(ext["attributes"]) != set(tri["attributes"]) or doc["bufferViews"][ext["bufferView"]]["byteLength"] < 100:
            print(f, "Draco structure wrong"); bad = 1
        continue
    if f.endswith("_cluster.glb"):
        # A clustering LOD: triangles, and thick lines carrying _THICKNESS; plain glTF otherwise.
        modes = {p.get("mode", 4): p for p in doc["meshes"][0]["primitives"]}
        if 4 not in modes or 1 not in modes or "_THICKNESS" not in modes[1]["attributes"] \
                or "cellWidth" not in doc["nodes"][0].get("extras", {}) or doc.get("extensionsUsed"):
            print(f, "cluster LOD structure wrong"); bad = 1
        continue
    if f.endswith("_points.glb"):
        # A point impostor: one POINTS primitive, the extension's count matches the accessor's.
        ext = doc["extensions"]["QF_point_impostor"]
        for e in point_check.iter_errors(ext):
            print(f, "QF_point_impostor:", e.message); bad = 1
        prim = doc["meshes"][0]["primitives"][0]
        count = doc["accessors"][prim["attributes"]["POSITION"]]["count"]
        if prim.get("mode") != 0 or ext["pointCount"] != count or not ext["pixelSize"] > 0 or not ext["switchDistance"] > 0 \
                or "QF_point_impostor" in doc.get("extensionsRequired", []):
            print(f, "QF_point_impostor structure wrong"); bad = 1
        continue
    if f.endswith("_asset.glb"):
        # A game asset with material channels (the plate): metallicRoughness and emissive textures.
        right = doc["materials"][1]
        if "metallicRoughnessTexture" not in right["pbrMetallicRoughness"] or "emissiveTexture" not in right:
            print(f, "material channels missing"); bad = 1
        continue
    if f.startswith(os.path.join(os.path.dirname(f), "plate_")):
        # Its level: one material, ORM and emissive atlas textures beside colour and normals.
        mats = doc["materials"]
        if len(mats) != 1 or "metallicRoughnessTexture" not in mats[0]["pbrMetallicRoughness"] or "emissiveTexture" not in mats[0]:
            print(f, "level material channels missing"); bad = 1
    ext = doc["extensions"]["QF_impostor_level"]
    errors = list(check.iter_errors(ext))
    n = ext["quadCount"]
    # The arrays are accessors of the file's buffer: unsigned integers (floats for the errors),
    # SCALAR, in bufferViews with no target, as many as quadCount says.
    def array(key, float_ok=False):
        a = doc["accessors"][ext[key]]
        kinds = (5126,) if float_ok else (5121, 5123, 5125)
        if a["type"] != "SCALAR" or a["componentType"] not in kinds or "target" in doc["bufferViews"][a["bufferView"]]:
            errors.append(f"{key}: not a SCALAR accessor of the right type outside vertex and index data")
        return a["count"]
    if array("neighborOffsets") != n + 1 or (n and array("domain") != n) or (n and array("error", True) != n):
        errors.append("array lengths do not match quadCount")
    if "neighbors" in ext:
        array("neighbors")
    # Quad k is the k-th pair of triangles of the mesh's primitives: six indices a quad.
    indices = sum(doc["accessors"][p["indices"]]["count"] for m in doc["meshes"] for p in m["primitives"])
    if indices != 6 * n:
        errors.append(f"{indices} indices for quadCount {n}")
    if "QF_impostor_level" in doc.get("extensionsRequired", []):
        errors.append("listed in extensionsRequired")
    if n and "KHR_mesh_quantization" not in doc.get("extensionsRequired", []):
        errors.append("quantized attributes without KHR_mesh_quantization required")
    for e in errors:
        print(f, "extension:", getattr(e, "message", e)); bad = 1
for f in sorted(glob.glob(os.path.join(schema_dir, "examples", "*.json"))):
    valid = os.path.basename(f).startswith("valid")
    ok = check.is_valid(json.load(open(f)))
    if ok != valid:
        print(f, "should be", "valid" if valid else "invalid"); bad = 1
print("extension schema:", len(files), "files and the examples checked")
sys.exit(bad)
PY
exit $status
