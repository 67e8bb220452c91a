#!/usr/bin/env python3
"""The fidelity league (scripts/bench.sh fidelity, issues 15 and 31): impostor levels against their
peers, everything scored by `qf-render eval` against the truth (the input drawn at 8x and box-filtered;
the engine method: as three.js r187 draws glTF, held to three.js by tests/render/engine_test.sh).

Two groups of models, told apart by how they are named:
- the CGAL models (named relative to MODELS_DIR): per budget, the impostor level (engine and the
  paper's overlap method) against meshoptimizer's simplify at twice as many triangles (a quad is two
  triangles; flat and smooth normals) and the vertex-clustering LOD nearest that count, at --sizes
  (256, 64 and "own"); then the summary against the better simplify, and holes and darkening;
- the assets (named by an absolute path: foliage, lattices, textured game assets): per level, the
  impostor against the asset itself as drawn, simplify and simplifySloppy at twice the quads in
  triangles and the crossed billboard at equal bytes (all by the engine method), and the octahedral
  impostor at equal bytes (scripts/octahedral_peer.py: its own shader, frames lit as the truth is,
  so an upper bound of what a view-dependent representation gives), at --asset-sizes ("own" and
  "half"); then per asset the figures issue 31's targets are set on.
The size "own" is the level's own max_screen_pixels (16..512): the largest size it is meant for,
where a LOD chain switching by the manifest shows it; "half" is half of that (at least 16 px).
Cells read PSNR dB, IoU, [soft IoU,] holes %. A peer the baker cannot make (an older --baker) is
left out with a note. Writes WORK_DIR/league.json (the rows).

usage: fidelity_table.py BIN_DIR MODELS_DIR WORK_DIR [--models bunny00.off,...,/abs/tree.glb]
                         [--sizes 256,64,own] [--asset-sizes own,half] [--views 8]
                         [--budgets 30,100,300,1000] [--baker BIN_DIR/qf-bake]
"""
import argparse
import json
import math
import os
import subprocess
import sys

NOTES = []  # peers that could not be made


def run(*cmd, fatal=True):
    r = subprocess.run([str(c) for c in cmd], capture_output=True, text=True)
    if r.returncode != 0:
        msg = f"{' '.join(map(str, cmd))} failed ({r.returncode}): {r.stderr.strip()[-300:]}"
        if fatal:
            sys.exit("fidelity_table: " + msg)
        NOTES.append(msg)
        print("fidelity_table: " + msg, file=sys.stderr)
    return r.returncode == 0


def evaluate(a, ref, baked, px, engine_only):
    """qf-render eval's mean scores: (engine, overlap or None, as_drawn)."""
    out = f"{baked}.eval{px}.json"
    cmd = [f"{a.bins}/qf-render", "eval", ref, baked, "--views", a.views, "--size", px, "-o", out, "--diff", f"{baked}.diff{px}"]
    run(*(cmd + (["--method", "engine"] if engine_only else [])))
    mean = json.load(open(out))["mean"]
    return mean["engine"], mean.get("overlap"), mean.get("as_drawn")


def pixels(size, level):
    own = max(16, min(512, level["max_screen_pixels"]))
    return {"own": own, "half": max(16, own // 2)}.get(size, size)


def simplified(a, src, d, triangles, *options):
    """A simplify LOD as (file, triangles), or None where the baker cannot make it."""
    if not run(a.baker, "simplify", src, "-o", d, "--triangles", triangles, *options, "-q", fatal=False):
        return None
    lod = json.load(open(os.path.join(d, "manifest.json")))["levels"][0]
    return os.path.join(d, lod["file"]), lod["triangles"]


def cgal_peers(a, src, out, quads, manifest):
    peers = {f"simplify {n}": simplified(a, src, os.path.join(out, f"simplify_{n}_{quads}"), 2 * quads, "--normals", n)
             for n in ("flat", "smooth")}
    clusters = manifest.get("mesh_lods", {}).get("levels", [])
    if clusters:
        c = min(clusters, key=lambda l: abs(l["triangles"] - 2 * quads))
        peers["cluster"] = (os.path.join(out, c["file"]), c["triangles"])
    return peers


def asset_peers(a, src, out, quads, level_bytes):
    peers = {"simplify": simplified(a, src, os.path.join(out, f"simplify_{quads}"), 2 * quads),
             "sloppy": simplified(a, src, os.path.join(out, f"sloppy_{quads}"), 2 * quads, "--method", "sloppy")}
    bb = os.path.join(out, f"billboard_{quads}.glb")
    peers["billboard"] = (bb, None) if run(a.baker, "billboard", src, "-o", bb, "--bytes", level_bytes, "-q", fatal=False) else None
    return peers


def octahedral(a, src, out, level_bytes, px):
    """The octahedral impostor of the level's bytes at px: its mean scores and bytes, or None."""
    r = subprocess.run(["/usr/bin/python3", os.path.join(os.path.dirname(os.path.abspath(__file__)), "octahedral_peer.py"), a.bins, src,
                        os.path.join(out, "octahedral"), "--bytes", str(level_bytes), "--size", str(px), "--views", str(a.views)],
                       capture_output=True, text=True)
    if r.returncode != 0:
        NOTES.append(f"octahedral peer of {src} at {px} px: {r.stderr.strip()[-300:]}")
        return None
    made = json.loads(r.stdout)
    return dict(made["metrics"], bytes=made["bytes"])


def league_model(a, name):
    """Bake one model and score each level and its peers at each size: rows."""
    src = os.path.join(a.models, name)  # an absolute name stands for itself
    bundled = not os.path.isabs(name)
    stem = os.path.splitext(os.path.basename(name))[0]
    out = os.path.join(a.work, stem)
    lods = ["--mesh-lods", "clustering"] if bundled else ["--mesh-lods", "none"]
    run(a.baker, src, "-o", out, "--primitives", a.budgets, "--no-cache", *lods, "-q")
    manifest = json.load(open(os.path.join(out, "manifest.json")))
    is_mesh = "mesh_lods" in manifest or not bundled
    rows, most = [], max(l["primitives"] for l in manifest["levels"])
    for level in manifest["levels"]:
        quads, glb = level["primitives"], os.path.join(out, level["file"])
        peers = {}
        if is_mesh:
            peers = cgal_peers(a, src, out, quads, manifest) if bundled else asset_peers(a, src, out, quads, level["bytes"])
        for size in (a.sizes if bundled else a.asset_sizes):
            px = pixels(size, level)
            engine, overlap, as_drawn = evaluate(a, src, glb, px, not bundled)
            row = {"model": stem, "quads": quads, "size": size, "pixels": px, "bytes": os.path.getsize(glb), "engine": engine,
                   "overlap": overlap, "bundled": bundled, "finest": quads == most,
                   "as drawn": dict(as_drawn, bytes=os.path.getsize(src)) if as_drawn else None}
            for peer, made in peers.items():
                if made:
                    m = evaluate(a, src, made[0], px, True)[0]
                    row[peer] = dict(m, triangles=made[1], bytes=os.path.getsize(made[0]))
            if is_mesh and not bundled:
                row["octahedral"] = octahedral(a, src, out, level["bytes"], px)
            rows.append(row)
    if not bundled:  # issue 31's mechanical target: the finest level at 128 px
        finest = next(l for l in manifest["levels"] if l["primitives"] == most)
        engine = evaluate(a, src, os.path.join(out, finest["file"]), 128, True)[0]
        rows.append({"model": stem, "quads": finest["primitives"], "size": "128", "pixels": 128, "engine": engine,
                     "bundled": False, "finest": True, "bytes": finest["bytes"]})
    return rows


def cell(m, soft=False):
    if m is None:  # a glTF asset reference is scored by the engine method only; a peer not made
        return "-"
    return f"{m['psnr']:5.2f} {m['iou']:.3f}" + (f" {m['soft_iou']:.3f}" if soft else "") + f" {100 * m['holes']:4.1f}%"


def print_cgal_tables(rows, sizes, views):
    for size in sizes:
        what = "each level at its own max_screen_pixels (px)" if size == "own" else f"{size}x{size}"
        print(f"\n### CGAL models, {what}, {views} views: PSNR dB, IoU, holes; bytes (engine method unless named)\n")
        print("| model | quads | px | impostor (engine) | overlap | bytes | simplify flat (tris) | simplify smooth | bytes | cluster (tris) |")
        print("|---|---|---|---|---|---|---|---|---|---|")
        for r in (r for r in rows if r["size"] == size):
            sf, ss, cl = r.get("simplify flat"), r.get("simplify smooth"), r.get("cluster")
            print(f"| {r['model']} | {r['quads']} | {r['pixels']} | {cell(r['engine'])} | {cell(r['overlap'])} | {r['bytes']:,} | "
                  + (f"{cell(sf)} ({sf['triangles']}) | " if sf else "- | ")
                  + (f"{cell(ss)} | {ss['bytes']:,} | " if ss else "- | - | ")
                  + (f"{cell(cl)} ({cl['triangles']}) |" if cl else "- |"))


def nearest_level(rows, model, size, budget):
    cand = [r for r in rows if r["size"] == size and r["model"] == model]
    return min(cand, key=lambda r: abs(math.log(r["quads"] / budget))) if cand else None


def print_cgal_summary(rows, sizes, budgets):
    print("\n### impostor (engine) vs the better of simplify flat/smooth (CGAL meshes)\n")
    print("| size | budget | cases | impostor wins PSNR | wins IoU | wins both | mean dPSNR dB | mean dIoU |")
    print("|---|---|---|---|---|---|---|---|")
    meshes = [r for r in rows if r.get("simplify flat") and r.get("simplify smooth")]
    for size in sizes:
        for b in budgets:
            sel = [nearest_level(meshes, m, size, b) for m in dict.fromkeys(r["model"] for r in meshes)]
            sel = [r for r in sel if r]
            if not sel:
                continue
            dp = [r["engine"]["psnr"] - max(r["simplify flat"]["psnr"], r["simplify smooth"]["psnr"]) for r in sel]
            di = [r["engine"]["iou"] - max(r["simplify flat"]["iou"], r["simplify smooth"]["iou"]) for r in sel]
            both = sum(1 for p, i in zip(dp, di) if p > 0 and i > 0)
            print(f"| {size} | ~{b} | {len(sel)} | {sum(p > 0 for p in dp)} | {sum(i > 0 for i in di)} | {both} | "
                  f"{sum(dp) / len(dp):+.2f} | {sum(di) / len(di):+.4f} |")
    # Holes at levels of >= 100 quads (<= 2% closed, 3% open), and how much darker each coarser
    # level is than the finest (mean grey over covered pixels; <= 3).
    print("\n### holes at >= 100 quads (worst level) and darkening vs the finest level (grey levels, worst level)\n")
    print("| model | size | holes % | darker by |")
    print("|---|---|---|---|")
    for size in sizes:
        for model in dict.fromkeys(r["model"] for r in rows):
            levels = sorted((r for r in rows if r["size"] == size and r["model"] == model), key=lambda r: r["quads"])
            big = [100 * r["engine"]["holes"] for r in levels if r["quads"] >= 100]
            finest = levels[-1]["engine"]["brightness"]
            darker = max(finest - r["engine"]["brightness"] for r in levels)
            print(f"| {model} | {size} | {max(big) if big else float('nan'):.1f} | {darker:.1f} |")


ASSET_PEERS = ("as drawn", "simplify", "sloppy", "billboard", "octahedral")


def peer_cell(m):
    if m is None:
        return "-"
    made = f", {m['triangles']} tris" if m.get("triangles") is not None else ""
    return f"{cell(m, soft=True)} ({m['bytes'] / 1000:.1f} kB{made})"


def print_asset_tables(rows, sizes, views):
    for size in sizes:
        what = "each level at its own max_screen_pixels (px)" if size == "own" else "each level at half its own size (px, >= 16)"
        print(f"\n### assets, {what}, {views} views, engine method: PSNR dB, IoU, soft IoU, holes (bytes)\n")
        print("| model | quads | px | impostor | " + " | ".join(ASSET_PEERS) + " |")
        print("|---|---|---|---|" + "---|" * len(ASSET_PEERS))
        for r in (r for r in rows if r["size"] == size):
            print(f"| {r['model']} | {r['quads']} | {r['pixels']} | {cell(r['engine'], soft=True)} ({r['bytes'] / 1000:.1f} kB) | "
                  + " | ".join(peer_cell(r.get(p)) for p in ASSET_PEERS) + " |")


def ahead(r, peer):
    p = r.get(peer)
    return f"{r['engine']['psnr'] - p['psnr']:+.2f} / {r['engine']['iou'] - p['iou']:+.3f}" if p else "-"


def print_asset_targets(rows):
    """Issue 31's targets, at each level's own size: foliage and lattices (every level IoU >= 0.85
    and >= as drawn, PSNR >= as drawn - 1 dB, finest own size >= 128 px, ~30 quads ahead of simplify
    and sloppy by 3 dB and 0.1 IoU and of the billboard); a mechanical asset's finest level at 128 px."""
    print("\n### assets against issue 31's targets (own size; d = impostor - peer: PSNR dB / IoU)\n")
    print("| model | finest own px | worst IoU | worst IoU - as drawn | worst PSNR - as drawn | ~30 quads | "
          "d simplify | d sloppy | d billboard | d octahedral | finest @128 px |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for model in dict.fromkeys(r["model"] for r in rows):
        own = [r for r in rows if r["model"] == model and r["size"] == "own"]
        finest = next(r for r in own if r["finest"])
        at128 = next((r for r in rows if r["model"] == model and r["size"] == "128"), None)
        drawn = [r for r in own if r["as drawn"]]
        di = min((r["engine"]["iou"] - r["as drawn"]["iou"] for r in drawn), default=float("nan"))
        dp = min((r["engine"]["psnr"] - r["as drawn"]["psnr"] for r in drawn), default=float("nan"))
        c = nearest_level(own, model, "own", 30)
        print(f"| {model} | {finest['pixels']} | {min(r['engine']['iou'] for r in own):.3f} | {di:+.3f} | {dp:+.2f} | "
              f"{c['quads']} | {ahead(c, 'simplify')} | {ahead(c, 'sloppy')} | {ahead(c, 'billboard')} | {ahead(c, 'octahedral')} | "
              f"{cell(at128['engine']) if at128 else '-'} |")


def main():
    ap = argparse.ArgumentParser(description="the fidelity league: impostor levels against their peers")
    ap.add_argument("bins")
    ap.add_argument("models")
    ap.add_argument("work")
    ap.add_argument("--sizes", default="256,64,own", help="sizes for the CGAL models: pixels, own or half")
    ap.add_argument("--asset-sizes", default="own,half", help="sizes for the assets (absolute paths)")
    ap.add_argument("--views", default="8")
    ap.add_argument("--budgets", default="30,100,300,1000")
    ap.add_argument("--models", dest="names", default="bunny00.off,fandisk.off,elephant.off,ChineseDragon-10kv.off,b9_training.ply")
    ap.add_argument("--baker", help="the qf-bake that bakes the levels and peers (default: BIN_DIR/qf-bake)")
    a = ap.parse_args()
    a.baker = a.baker or os.path.join(a.bins, "qf-bake")
    a.sizes, a.asset_sizes = a.sizes.split(","), a.asset_sizes.split(",")
    rows = [r for name in a.names.split(",") for r in league_model(a, name)]
    cgal, assets = [r for r in rows if r["bundled"]], [r for r in rows if not r["bundled"]]
    if cgal:
        print_cgal_tables(cgal, a.sizes, a.views)
        print_cgal_summary(cgal, a.sizes, [int(b) for b in a.budgets.split(",")])
    if assets:
        print_asset_tables(assets, a.asset_sizes, a.views)
        print_asset_targets(assets)
    for note in NOTES:
        print(f"\nnote: {note}")
    json.dump(rows, open(os.path.join(a.work, "league.json"), "w"), indent=1)


if __name__ == "__main__":
    main()
