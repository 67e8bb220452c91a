#!/usr/bin/env bash
# One scan baked by many machines, at small scale (docs/farm.md, "One scan over many machines"): a
# 40k-point torus split by qf-bake tile into 4 tiles, each baked as a task of scripts/slurm/bake-array.sbatch
# (run here with the environment Slurm gives an --array=1-4 task; tests/cli/slurm_test.sh runs the
# script on a real cluster), joined by qf-bake join into one level set: every tile in every level,
# the quads summing to the targets, the same bytes on a second join, the joined levels drawn within
# reach of the whole scan's bake; a missing tile is named and nothing is written.
# usage: tiles_test.sh QF_BAKE QF_RENDER SOURCE_DIR
set -u
bake=$1 render=$2 src=$3
source "$(dirname "$0")/test_lib.sh"
unset QF_SHARDS $(compgen -e | grep -E '^(SLURM|SBATCH)_')
cd "$work"

"$bake" generate torus --points 40000 -o torus.ply -q || { bad "generate"; finish tiles; }

# 1. The tiles, their plan and the batch that bakes them.
"$bake" tile torus.ply -o T --tiles 0 2>err && bad "--tiles 0 accepted" || ok
[[ ! -e T ]] && ok || bad "--tiles 0 wrote T"
"$bake" tile torus.ply -o T --tiles 4 --primitives 200,50 -q 2>err && ok || bad "tile: $(cat err)"
/usr/bin/python3 - T <<'PY' && ok || bad "the tile plan"
import json, sys
plan = json.load(open(sys.argv[1] + "/tiles.json")); batch = json.load(open(sys.argv[1] + "/batch.json"))
assert len(plan["tiles"]) == 4 and sum(t["points"] for t in plan["tiles"]) == 40000, plan["tiles"]
assert all(9000 <= t["points"] <= 11000 for t in plan["tiles"])
assert [a["input"] for a in batch["assets"]] == [t["file"] for t in plan["tiles"]]
assert batch["defaults"]["primitives"] == [50, 13], batch["defaults"]
PY

# 2. Each tile a task of the Slurm array (1-based task ids, as sbatch --array=1-4 gives them).
mkdir -p bin && ln -s "$bake" bin/qf-bake
for i in 1 2 3 4; do
  PATH="$work/bin:$PATH" SLURM_ARRAY_TASK_ID=$i SLURM_ARRAY_TASK_MIN=1 SLURM_ARRAY_TASK_MAX=4 SLURM_ARRAY_TASK_COUNT=4 \
    bash "$src/scripts/slurm/bake-array.sbatch" T/batch.json baked 2>"err$i" >/dev/null || bad "array task $i: $(tail -2 "err$i")"
done
[[ $(ls baked/*/manifest.json 2>/dev/null | wc -l) -eq 4 ]] && ok || bad "4 tiles baked: $(ls baked)"

# 3. The join: every tile in each level, the quads near the targets, the same bytes twice.
"$bake" join T/tiles.json baked -o J 2>err && ok || bad "join: $(cat err)"
"$bake" join T/tiles.json baked -o J2 -q && ok || bad "second join"
for f in J/*.glb; do cmp -s "$f" "J2/$(basename "$f")" || bad "join differs between runs: $f"; done
/usr/bin/python3 - J <<'PY' 2>"$work/jerr" && ok || bad "the joined manifest: $(tail -2 "$work/jerr")"
import json, sys
m = json.load(open(sys.argv[1] + "/manifest.json"))
levels = m["levels"]
assert m["tiles"] == 4 and len(levels) == 2, m
for level, target in zip(levels, [200, 50]):
    assert len(level["parts"]) == 4 and len({p.split("/")[0] for p in level["parts"]}) == 4, level
    assert 0.75 * target <= level["primitives"] <= 1.25 * target, (level, target)
    # A joined level holds as far as its worst tile: a tile's size scaled by its share of the diagonal
    # (0 where a tile's level holds at no size measured).
    diagonals = {t["name"]: t["bounding_box_diagonal"] for t in json.load(open("T/tiles.json"))["tiles"]}
    def scaled(part):  # the tile level's size, across the whole scan's diagonal
        tile, file = part.split("/")
        l = next(x for x in json.load(open(f"baked/{tile}/manifest.json"))["levels"] if x["file"] == file)
        return l["max_screen_pixels"] * m["bounding_box_diagonal"] / diagonals[tile]
    want = min(scaled(p) for p in level["parts"])
    assert abs(level["max_screen_pixels"] - int(want)) <= 1, (level["max_screen_pixels"], want)
PY
/usr/bin/python3 - J/torus_J0.glb <<'PY' && ok || bad "the joined level's nodes"
import json, struct, sys
b = open(sys.argv[1], "rb").read()
g = json.loads(b[20:20 + struct.unpack("<I", b[12:16])[0]])
root = g["nodes"][g["scenes"][0]["nodes"][0]]
assert root["name"] == "torus_J0" and len(root["children"]) == 4, root
assert [g["nodes"][c]["name"] for c in root["children"]] == [f"torus_J0_{i}" for i in range(4)]
assert len(g["materials"]) == 4 and "QF_impostor_level" not in g.get("extensionsUsed", [])
PY

# 4. Drawn as an engine draws it (8 views, 64 px): the joined finest level against the whole scan's
#    bake at the same targets (measured: 20.7 dB / IoU 0.923 joined, 21.7 / 0.935 whole; 203 quads
#    against 248). One tile alone would cover a quarter of the torus.
"$bake" torus.ply -o whole --primitives 200,50 --no-chain --mesh-lods none --no-report-html -q --no-cache || bad "whole bake"
score() { "$render" eval torus.ply "$1" --views 8 --truth 4 --size 64 -m engine -o "$2" >/dev/null 2>&1; }
score J/torus_J0.glb joined.json && score "$(ls whole/torus_L*.glb | head -n 1)" whole.json || bad "eval"
/usr/bin/python3 - joined.json whole.json <<'PY' && ok || bad "the joined level against the whole bake"
import json, sys
j, w = (json.load(open(f))["mean"]["engine"] for f in sys.argv[1:3])
print(f"joined {j['psnr']:.2f} dB IoU {j['iou']:.4f}, whole {w['psnr']:.2f} dB IoU {w['iou']:.4f}")
assert j["psnr"] >= w["psnr"] - 2.0 and j["iou"] >= w["iou"] - 0.03
PY

# 5. A tile whose task failed: named, nothing written.
rm -rf baked/torus_t2
"$bake" join T/tiles.json baked -o J3 2>err; rc=$?
[[ $rc -eq 1 ]] && grep -q "torus_t2" err && [[ ! -e J3 ]] && ok || bad "join without tile 2: exit $rc, $(cat err)"
finish tiles
