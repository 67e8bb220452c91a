#!/usr/bin/env python3
"""Far levels on foliage and thin parts (scripts/bench.sh far, issue 49).

Per asset, a default bake (PNG; with --textures, that format); then every impostor level drawn by
`qf-render eval` (engine method, --views views, truth --truth x the size and box-filtered) at its
own size (its geometric_max_screen_pixels, at most 256) and at half of it, beside the asset itself
drawn there as an engine draws it. Issue 49's targets, per level and size: footprint PSNR at least
the asset's - 1 dB, soft IoU at least the asset's - 0.02, coverage 0.8..1.25 of the truth's.
usage: far_table.py BIN_DIR WORK_DIR ASSET... [--views 8] [--truth 8] [--textures png]"""
import argparse
import json
import os
import subprocess
import time

p = argparse.ArgumentParser()
p.add_argument("bin_dir")
p.add_argument("work")
p.add_argument("assets", nargs="+")
p.add_argument("--views", type=int, default=8)
p.add_argument("--truth", type=int, default=8)
p.add_argument("--textures", default="png")
a = p.parse_args()


def fmt(v, digits):
    return "-" if v is None else f"{v:.{digits}f}"


def meets(f, d):
    """Which of the three targets the level (f) meets against the asset as drawn (d)."""
    psnr = f["psnr"] is not None and d["psnr"] is not None and f["psnr"] >= d["psnr"] - 1
    soft = f["soft_iou"] is not None and d["soft_iou"] is not None and f["soft_iou"] >= d["soft_iou"] - 0.02
    cov = f["coverage"] is not None and 0.8 <= f["coverage"] <= 1.25
    return psnr, soft, cov


rows, totals = [], [0, 0, 0, 0]
for src in a.assets:
    name = os.path.basename(src)
    out = os.path.join(a.work, name + ".far")
    start = time.monotonic()
    subprocess.run([os.path.join(a.bin_dir, "qf-bake"), "bake", src, "-o", out, "--no-cache", "--textures", a.textures, "-q"], check=True)
    seconds = time.monotonic() - start
    m = json.load(open(os.path.join(out, "manifest.json")))
    for level in m["levels"]:
        own = min(256, max(16, level.get("geometric_max_screen_pixels") or level.get("max_screen_pixels") or 64))
        for size in sorted({own, max(16, own // 2)}, reverse=True):
            ev = os.path.join(a.work, f"{name}.{level['file']}.{size}.json")
            subprocess.run([os.path.join(a.bin_dir, "qf-render"), "eval", src, os.path.join(out, level["file"]), "--size", str(size),
                            "--views", str(a.views), "--truth", str(max(1, min(a.truth, 4096 // size))), "-m", "engine", "-o", ev],
                           check=True, capture_output=True)
            r = json.load(open(ev))["mean"]
            f, d = r["engine"], r["as_drawn"]
            ok = meets(f, d)
            totals = [t + x for t, x in zip(totals, ok + (1,))]
            rows.append(f"| {name} ({seconds:.1f} s) | {level['file']} | {level['primitives']} | {level['bytes']:,} | {size} | "
                        f"{fmt(f['psnr'], 2)} / {fmt(d['psnr'], 2)} | {fmt(f['soft_iou'], 3)} / {fmt(d['soft_iou'], 3)} | "
                        f"{fmt(f['coverage'], 3)} / {fmt(d['coverage'], 3)} | {' '.join('yes' if x else 'no' for x in ok)} |")
print(f"Each impostor level ({a.textures}) at its own size and half of it: the level / the asset as drawn, against the truth "
      f"({a.views} views, {a.truth}x, engine method).\n")
print("| asset (bake s) | level | quads | bytes | px | PSNR dB | soft IoU | coverage | targets met: PSNR, soft IoU, coverage |")
print("|---|---|---|---|---|---|---|---|---|")
print("\n".join(rows))
print(f"\n{totals[3]} level-sizes: PSNR within 1 dB of the asset {totals[0]}, soft IoU within 0.02 {totals[1]}, coverage 0.8-1.25 {totals[2]}")
