#!/usr/bin/env python3
"""The fidelity league (scripts/bench.sh fidelity): per model and primitive budget, the impostor
level (engine method and the paper's overlap method) against meshoptimizer's simplify at twice as
many triangles (a quad is two triangles; flat and smooth normals) and the vertex-clustering LOD
nearest that triangle count, all measured by `qf-render eval` against the input drawn the same way
(the engine method: as three.js r187 draws glTF; tests/render/three_test.sh holds it to three.js).
Prints one table per image size and a summary of the issue's targets. The size "own" draws each
impostor level, and its peers, at the level's own max_screen_pixels (at least 16): the largest
size it is meant for, where a LOD chain switching by the manifest shows it.

usage: fidelity_table.py BIN_DIR MODELS_DIR WORK_DIR [--sizes 256,64,own] [--views 8]
                         [--budgets 30,100,300,1000] [--models bunny00.off,...]
"""
import argparse
import json
import math
import os
import subprocess
import sys


def run(*cmd):
    r = subprocess.run([str(c) for c in cmd], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"fidelity_table: {' '.join(map(str, cmd))} failed ({r.returncode}):\n{r.stderr}")
    return r


def evaluate(bins, ref, baked, size, views, engine_only):
    out = baked + f".eval{size}.json"
    cmd = [f"{bins}/qf-render", "eval", ref, baked, "--views", views, "--size", size, "-o", out, "--diff", baked + ".diff"]
    if engine_only:
        cmd += ["--method", "engine"]
    run(*cmd)
    mean = json.load(open(out))["mean"]
    return mean["engine"], mean.get("overlap")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("bins")
    ap.add_argument("models")
    ap.add_argument("work")
    ap.add_argument("--sizes", default="256,64,own")
    ap.add_argument("--views", default="8")
    ap.add_argument("--budgets", default="30,100,300,1000")
    ap.add_argument("--models", dest="names", default="bunny00.off,fandisk.off,elephant.off,ChineseDragon-10kv.off,b9_training.ply")
    a = ap.parse_args()
    sizes = a.sizes.split(",")
    rows = []  # one per model x level x size
    for name in a.names.split(","):
        src = os.path.join(a.models, name)  # an absolute name stands for itself
        stem = os.path.splitext(os.path.basename(name))[0]
        out = os.path.join(a.work, stem)
        run(f"{a.bins}/qf-bake", src, "-o", out, "--primitives", a.budgets, "--no-cache", "--mesh-lods", "clustering", "-q")
        manifest = json.load(open(os.path.join(out, "manifest.json")))
        is_mesh = "mesh_lods" in manifest
        clusters = manifest["mesh_lods"]["levels"] if is_mesh else []
        for level in manifest["levels"]:
            quads = level["primitives"]
            glb = os.path.join(out, level["file"])
            peers = {}
            if is_mesh:
                for normals in ("flat", "smooth"):
                    d = os.path.join(out, f"simplify_{normals}_{quads}")
                    run(f"{a.bins}/qf-bake", "simplify", src, "-o", d, "--triangles", 2 * quads, "--normals", normals, "-q")
                    lod = json.load(open(os.path.join(d, "manifest.json")))["levels"][0]
                    peers[f"simplify {normals}"] = (os.path.join(d, lod["file"]), lod["triangles"])
                c = min(clusters, key=lambda l: abs(l["triangles"] - 2 * quads))
                peers["cluster"] = (os.path.join(out, c["file"]), c["triangles"])
            for size in sizes:
                px = str(max(16, min(1024, level["max_screen_pixels"]))) if size == "own" else size
                engine, overlap = evaluate(a.bins, src, glb, px, a.views, False)
                row = {"model": stem, "quads": quads, "size": size, "pixels": px, "bytes": os.path.getsize(glb), "engine": engine,
                       "overlap": overlap, "bundled": not os.path.isabs(name)}
                for peer, (f, tris) in peers.items():
                    m, _ = evaluate(a.bins, src, f, px, a.views, True)
                    row[peer] = dict(m, triangles=tris, bytes=os.path.getsize(f))
                rows.append(row)

    def cell(m):
        if m is None:  # a glTF asset reference is scored by the engine method only
            return "-"
        return f"{m['psnr']:5.2f} {m['iou']:.3f} {100 * m['holes']:4.1f}%"

    for size in sizes:
        what = "each level at its own max_screen_pixels (px)" if size == "own" else f"{size}x{size}"
        print(f"\n### {what}, {a.views} views: PSNR dB, IoU, holes; bytes (engine method unless named)\n")
        print("| model | quads | px | impostor (engine) | overlap | bytes | simplify flat (tris) | simplify smooth | bytes | cluster (tris) |")
        print("|---|---|---|---|---|---|---|---|---|---|")
        for r in (r for r in rows if r["size"] == size):
            sf, ss, cl = r.get("simplify flat"), r.get("simplify smooth"), r.get("cluster")
            print(f"| {r['model']} | {r['quads']} | {r['pixels']} | {cell(r['engine'])} | {cell(r['overlap'])} | {r['bytes']:,} | "
                  + (f"{cell(sf)} ({sf['triangles']}) | {cell(ss)} | {ss['bytes']:,} | {cell(cl)} ({cl['triangles']}) |" if sf else "- | - | - | - |"))
    # The targets are set on the CGAL models (the MODELS_DIR ones); a model named by an
    # absolute path (the generated tree) keeps its rows above but stays out of these means.
    print("\n### impostor (engine) vs the better of simplify flat/smooth (CGAL meshes)\n")
    print("| size | budget | cases | impostor wins PSNR | wins IoU | wins both | mean dPSNR dB | mean dIoU |")
    print("|---|---|---|---|---|---|---|---|")
    bands = [int(b) for b in a.budgets.split(",")]
    for size in sizes:
        for b in bands:
            # Per model, the level the bake chose for budget b (nearest in ratio).
            sel = []
            for model in dict.fromkeys(r["model"] for r in rows):
                cand = [r for r in rows if r["size"] == size and r["model"] == model and "simplify flat" in r and r["bundled"]]
                if cand:
                    sel.append(min(cand, key=lambda r: abs(math.log(r["quads"] / b))))
            if not sel:
                continue
            dp = [r["engine"]["psnr"] - max(r["simplify flat"]["psnr"], r["simplify smooth"]["psnr"]) for r in sel]
            di = [r["engine"]["iou"] - max(r["simplify flat"]["iou"], r["simplify smooth"]["iou"]) for r in sel]
            both = sum(1 for p, i in zip(dp, di) if p > 0 and i > 0)
            print(f"| {size} | ~{b} | {len(sel)} | {sum(p > 0 for p in dp)} | {sum(i > 0 for i in di)} | {both} | "
                  f"{sum(dp) / len(dp):+.2f} | {sum(di) / len(di):+.4f} |")
    # The other targets: holes at levels of >= 100 quads (<= 2% closed, 3% open), and how much
    # darker each coarser level is than the finest (mean grey over covered pixels; <= 3).
    print("\n### holes at >= 100 quads (worst level) and darkening vs the finest level (grey levels, worst level)\n")
    print("| model | size | holes % | darker by |")
    print("|---|---|---|---|")
    for size in sizes:
        for model in dict.fromkeys(r["model"] for r in rows if r["bundled"]):
            levels = sorted((r for r in rows if r["size"] == size and r["model"] == model), key=lambda r: r["quads"])
            big = [100 * r["engine"]["holes"] for r in levels if r["quads"] >= 100]
            finest = levels[-1]["engine"]["brightness"]
            darker = max(finest - r["engine"]["brightness"] for r in levels)
            print(f"| {model} | {size} | {max(big) if big else float('nan'):.1f} | {darker:.1f} |")
    json.dump(rows, open(os.path.join(a.work, "league.json"), "w"), indent=1)


if __name__ == "__main__":
    main()
