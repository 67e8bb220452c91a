#!/usr/bin/env python3
"""The scan league (scripts/bench.sh scans, issue 35 item 3): on point sets, the impostor levels
against the peer a scan user would pick, the surface reconstructed (CGAL's advancing front) and
simplified by meshoptimizer (the bake's STEM_S<i>.glb of a point set). Every file is scored as the
bake's recommended chain scores it (engine method against the splats drawn at 2x, box-filtered;
manifest recommended_chain.measured): a mesh LOD only where the chain may choose it (up to 2x its
max_screen_pixels), an impostor level at every size.

Per scan: each file's bytes and PSNR dB / IoU per size; then, per reconstruction LOD and size, the
best impostor level of no more bytes ("equal bytes": the peer's own bytes or fewer) and the margin
(impostor minus reconstruction, dB); then the chain's choice per band.

usage: scan_table.py QF_BAKE MODELS_DIR WORK_DIR --models building.ply,kitten.xyz,...
"""
import argparse
import json
import os
import subprocess
import sys
import time


def bake(qf_bake, path, out):
    start = time.time()
    r = subprocess.run([qf_bake, "bake", path, "-o", out, "--no-cache", "-q"], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"scan_table: {path}: qf-bake failed ({r.returncode}): {r.stderr.strip()[-300:]}")
    return time.time() - start


def table(name, seconds, m):
    c = m["recommended_chain"]
    sizes = c["sizes"]
    rec = m["mesh_lods"]["reconstruction"]
    print(f"\n### {name}: {m['points']} points, bake {seconds:.1f} s; reconstruction from {rec['points_used']} points, "
          f"{rec['triangles']} triangles\n")
    print("| file | KB | " + " | ".join(f"{s} px" for s in sizes) + " |")
    print("|---|---|" + "---|" * len(sizes))
    rows = c["measured"]
    for e in rows:
        cells = [f"{v['psnr']:.1f} / {v['iou']:.3f}" if v else "–" for v in e["at_pixels"]]
        print(f"| {e['file']} | {e['bytes'] / 1024:.0f} | " + " | ".join(cells) + " |")
    levels = [e for e in rows if e["kind"] == "impostor_level"]
    lods = [e for e in rows if e["kind"] == "mesh_lod"]
    print("\nAt equal bytes (the best impostor level of no more bytes than the reconstruction's LOD; "
          "margin = impostor - reconstruction, dB):\n")
    print("| reconstruction LOD | KB | size | its PSNR / IoU | best impostor of <= bytes | PSNR / IoU | margin dB |")
    print("|---|---|---|---|---|---|---|")
    wins = [0, 0]
    for lod in lods:
        for i, s in enumerate(sizes):
            v = lod["at_pixels"][i]
            if not v:
                continue
            cands = [l for l in levels if l["bytes"] <= lod["bytes"] and l["at_pixels"][i]]
            if not cands:
                print(f"| {lod['file']} | {lod['bytes'] / 1024:.0f} | {s} | {v['psnr']:.1f} / {v['iou']:.3f} | (none this small) | – | – |")
                continue
            best = max(cands, key=lambda l: l["at_pixels"][i]["psnr"])
            b = best["at_pixels"][i]
            margin = b["psnr"] - v["psnr"]
            wins[0 if margin > 0 else 1] += 1
            print(f"| {lod['file']} | {lod['bytes'] / 1024:.0f} | {s} | {v['psnr']:.1f} / {v['iou']:.3f} | {best['file']} "
                  f"({best['bytes'] / 1024:.0f} KB) | {b['psnr']:.1f} / {b['iou']:.3f} | {margin:+.1f} |")
    print(f"\nImpostor ahead in {wins[0]} of {wins[0] + wins[1]} comparisons.")
    print("Chain: " + ", ".join(f"{e['file']} down to {e['min_pixels']} px ({(e['error'] or {}).get('psnr')} dB"
                                + ("" if e["bar_met"] else ", under the bar") + ")" for e in c["chain"]))
    return wins


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("qf_bake")
    ap.add_argument("models_dir")
    ap.add_argument("work_dir")
    ap.add_argument("--models", required=True)
    a = ap.parse_args()
    total = [0, 0]
    for name in a.models.split(","):
        out = os.path.join(a.work_dir, os.path.splitext(name)[0])
        seconds = bake(a.qf_bake, os.path.join(a.models_dir, name), out)
        with open(os.path.join(out, "manifest.json")) as f:
            m = json.load(f)
        if "mesh_lods" not in m or "recommended_chain" not in m:
            sys.exit(f"scan_table: {name}: the bake made no reconstruction LODs or no chain (GL driver?)")
        w = table(name, seconds, m)
        total = [total[0] + w[0], total[1] + w[1]]
    print(f"\nIn all: impostor ahead at equal bytes in {total[0]} of {total[0] + total[1]} comparisons.")


if __name__ == "__main__":
    main()
