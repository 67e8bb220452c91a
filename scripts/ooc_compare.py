#!/usr/bin/env python3
"""Compares an out-of-core bake with the in-memory bake of the same input, level by level (issue 35
item 2): quads, texels and bytes of each, and each level drawn by the engine method at its own size
(the in-memory level's geometric max_screen_pixels, clamped to 16..512 px: an out-of-core bake
past the memory its input's drawing needs is not measured) against the input by qf-render
eval: PSNR and IoU of both and their differences (out of core less in memory).
usage: ooc_compare.py INPUT MEM_DIR OOC_DIR [--render build/bin/qf-render] [--views 8] [--truth 4]"""
import argparse
import json
import os
import subprocess
import sys
import tempfile


def evaluate(render, reference, glb, size, views, truth, outliers):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "eval.json")
        subprocess.run([render, "eval", reference, glb, "--size", str(size), "--views", str(views), "--truth", str(truth),
                        "--outliers", outliers, "-m", "engine", "-o", out], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        return json.load(open(out))["mean"]["engine"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("input")
    ap.add_argument("mem")
    ap.add_argument("ooc")
    ap.add_argument("--render", default="build/bin/qf-render")
    ap.add_argument("--views", type=int, default=8)
    ap.add_argument("--truth", type=int, default=4)
    a = ap.parse_args()
    mem, ooc = (json.load(open(os.path.join(d, "manifest.json"))) for d in (a.mem, a.ooc))
    rm, ro = (json.load(open(os.path.join(d, "report.json"))) for d in (a.mem, a.ooc))
    print(f"input {a.input}: {mem['points']} points; out of core on {ooc.get('out_of_core', {}).get('subsample_points', '?')} "
          f"subsample points, scratch {ooc.get('out_of_core', {}).get('scratch_bytes', 0) / 2**20:.0f} MiB; "
          f"peak {rm['memory']['peak_mb']:.0f} MB in memory, {ro['memory']['peak_mb']:.0f} MB out of core")
    # The truth without the outliers the bakes dropped (both bakes' setting, report settings.outliers).
    outliers = str(rm["settings"].get("outliers", 0))
    print()
    print("| level (mem / ooc) | quads mem | quads ooc | Δquads | size px | PSNR mem | PSNR ooc | ΔPSNR dB | IoU mem | IoU ooc | ΔIoU | bytes mem | bytes ooc |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    worst_psnr, worst_iou, worst_quads = 0.0, 0.0, 0.0
    for lm, lo in zip(mem["levels"], ooc["levels"]):
        size = int(min(512, max(16, lm.get("geometric_max_screen_pixels", lm["max_screen_pixels"]))))
        em = evaluate(a.render, a.input, os.path.join(a.mem, lm["file"]), size, a.views, a.truth, outliers)
        eo = evaluate(a.render, a.input, os.path.join(a.ooc, lo["file"]), size, a.views, a.truth, outliers)
        dq = (lo["primitives"] - lm["primitives"]) / lm["primitives"]
        dp, di = eo["psnr"] - em["psnr"], eo["iou"] - em["iou"]
        worst_psnr, worst_iou, worst_quads = min(worst_psnr, dp), max(worst_iou, abs(di)), max(worst_quads, abs(dq))
        print(f"| L{lm['level']} / L{lo['level']} | {lm['primitives']} | {lo['primitives']} | {100 * dq:+.1f}% | {size} | "
              f"{em['psnr']:.2f} | {eo['psnr']:.2f} | {dp:+.2f} | {em['iou']:.4f} | {eo['iou']:.4f} | {di:+.4f} | "
              f"{lm['bytes']} | {lo['bytes']} |")
    print()
    print(f"worst: ΔPSNR {worst_psnr:+.2f} dB (target >= -0.3), |ΔIoU| {worst_iou:.4f} (target <= 0.005), "
          f"|Δquads| {100 * worst_quads:.1f}% (target <= 5%)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
