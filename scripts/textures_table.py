#!/usr/bin/env python3
"""PNG against KTX2 textures (issue 32) on point sets: each baked twice with the defaults, once
with --textures png and once with --textures ktx2, then every level drawn by qf-render eval's
engine method (8 views, truth 4x) at its own size (the PNG level's max_screen_pixels) and at 1/4
and 1/8 of it, with mipmaps (PNG: made by box filtering as WebGL engines do; KTX2: the file's
coverage-preserving ones). Tables: per level, bytes (file, textures), GPU bytes, PSNR / IoU at its
size and their differences, holes at 1/4 and 1/8; per set, bytes, GPU bytes and bake seconds
(whole bake, and the levels' atlas+glb stages).
usage: textures_table.py BIN_DIR WORK_DIR POINTS.xyz..."""
import json
import os
import subprocess
import sys
import time

bin_dir, work = sys.argv[1:3]


def bake(src, out, textures):
    start = time.monotonic()
    subprocess.run([os.path.join(bin_dir, "qf-bake"), "bake", src, "-o", out, "--textures", textures, "--no-cache", "-q"], check=True)
    wall = time.monotonic() - start
    r = json.load(open(os.path.join(out, "report.json")))
    encode = sum(s["seconds"] for s in r["stages"] if s["stage"].endswith("atlas+glb"))
    return json.load(open(os.path.join(out, "manifest.json"))), wall, encode


def measure(src, glb, size):
    out = glb + f".{size}.json"
    subprocess.run([os.path.join(bin_dir, "qf-render"), "eval", src, glb, "-m", "engine", "--no-engine", "--views", "8",
                    "--size", str(size), "--truth", "4", "-o", out], check=True, capture_output=True)
    return json.load(open(out))["mean"]["engine"]


for src in sys.argv[3:]:
    name = os.path.basename(src)
    runs = {t: bake(src, os.path.join(work, f"{name}.{t}"), t) for t in ("png", "ktx2")}
    print(f"\n{name}: per level (engine method, 8 views; sizes from the PNG level's max_screen_pixels)\n")
    print("| level | quads | px | PNG bytes (tex) | KTX2 bytes (tex) | GPU PNG / KTX2 | PSNR PNG / KTX2 (d) | IoU PNG / KTX2 (d) "
          "| holes 1/4 PNG / KTX2 | holes 1/8 PNG / KTX2 |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    png_levels = runs["png"][0]["levels"]
    ktx_levels = {l["level"]: l for l in runs["ktx2"][0]["levels"]}
    for p in png_levels:
        k = ktx_levels[p["level"]]
        px = int(p["max_screen_pixels"])
        e = {}
        for t, l in (("png", p), ("ktx2", k)):
            glb = os.path.join(work, f"{name}.{t}", l["file"])
            e[t] = [measure(src, glb, max(8, round(px / d))) for d in (1, 4, 8)]
        a, b = e["png"], e["ktx2"]
        print(f"| {p['level']} | {p['primitives']} | {px} | {p['bytes']:,} ({p['texture_bytes']:,}) | {k['bytes']:,} ({k['texture_bytes']:,}) "
              f"| {p['gpu_bytes']:,} / {k['gpu_bytes']:,} | {a[0]['psnr']:.2f} / {b[0]['psnr']:.2f} ({b[0]['psnr'] - a[0]['psnr']:+.2f}) "
              f"| {a[0]['iou']:.4f} / {b[0]['iou']:.4f} ({b[0]['iou'] - a[0]['iou']:+.4f}) "
              f"| {100 * a[1]['holes']:.2f}% / {100 * b[1]['holes']:.2f}% | {100 * a[2]['holes']:.2f}% / {100 * b[2]['holes']:.2f}% |")
    print(f"\n{name}: the default level set\n")
    print("| textures | bytes | texture bytes | GPU bytes | bake s (wall) | atlas+glb s |")
    print("|---|---|---|---|---|---|")
    for t, (m, wall, encode) in runs.items():
        ls = m["levels"]
        print(f"| {t} | {sum(l['bytes'] for l in ls):,} | {sum(l['texture_bytes'] for l in ls):,} | {sum(l['gpu_bytes'] for l in ls):,} "
              f"| {wall:.1f} | {encode:.2f} |")
