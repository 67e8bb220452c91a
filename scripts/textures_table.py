#!/usr/bin/env python3
"""PNG against KTX2 and WebP textures (issue 32) on point sets: each baked with the defaults, once
per format (--textures png, ktx2, webp), then every level drawn by qf-render eval's engine method
(8 views, truth 4x) at its own size (the PNG level's max_screen_pixels) and at 1/4 and 1/8 of it,
with mipmaps (PNG and WebP: made by box filtering as WebGL engines do; KTX2: the file's
coverage-preserving ones), and at 1/4 and 1/8 again without mip levels (qf-render --no-mips: the
base level alone), so that the mip levels' own share of the holes shows. Tables: per level and
format against PNG, bytes (file, textures), GPU bytes, PSNR / IoU at its size and their
differences, holes at its size and at 1/4 and 1/8 with and without mips; per set, bytes, GPU
bytes and bake seconds (whole bake, and the levels' atlas+glb stages).
usage: textures_table.py BIN_DIR WORK_DIR [--formats png,ktx2,webp] [--no-holes] [--bake-args "ARGS"] POINTS.xyz...
(--bake-args: more qf-bake options for every format but png, e.g. "--webp-color 80")"""
import argparse
import json
import os
import shlex
import subprocess
import time

ap = argparse.ArgumentParser()
ap.add_argument("bin_dir")
ap.add_argument("work")
ap.add_argument("--formats", default="png,ktx2,webp")
ap.add_argument("--no-holes", action="store_true", help="measure each level at its own size only")
ap.add_argument("--bake-args", default="")
ap.add_argument("inputs", nargs="+")
args = ap.parse_args()
formats = args.formats.split(",")
if formats[0] != "png":
    formats.insert(0, "png")
NAMES = {"png": "PNG", "ktx2": "KTX2", "webp": "WebP"}


def bake(src, out, textures):
    start = time.monotonic()
    extra = shlex.split(args.bake_args) if textures != "png" else []
    subprocess.run([os.path.join(args.bin_dir, "qf-bake"), "bake", src, "-o", out, "--textures", textures, "--no-cache", "-q"] + extra,
                   check=True)
    wall = time.monotonic() - start
    r = json.load(open(os.path.join(out, "report.json")))
    encode = sum(s["seconds"] for s in r["stages"] if s["stage"].endswith("atlas+glb"))
    return json.load(open(os.path.join(out, "manifest.json"))), wall, encode


def measure(src, glb, size, mips=True):
    out = glb + f".{size}{'' if mips else '.nomips'}.json"
    subprocess.run([os.path.join(args.bin_dir, "qf-render"), "eval", src, glb, "-m", "engine", "--no-engine", "--views", "8",
                    "--size", str(size), "--truth", "4", "-o", out] + ([] if mips else ["--no-mips"]), check=True, capture_output=True)
    return json.load(open(out))["mean"]["engine"]


for src in args.inputs:
    name = os.path.basename(src)
    runs = {t: bake(src, os.path.join(args.work, f"{name}.{t}"), t) for t in formats}
    png_levels = runs["png"][0]["levels"]
    # Every format's levels measured at the PNG level's sizes: its own, 1/4 and 1/8 (at least 8 px).
    scores = {}
    for t in formats:
        levels = {l["level"]: l for l in runs[t][0]["levels"]}
        for p in png_levels:
            px = int(p["max_screen_pixels"])
            glb = os.path.join(args.work, f"{name}.{t}", levels[p["level"]]["file"])
            divisors = (1,) if args.no_holes else (1, 4, 8)
            scores[t, p["level"]] = [measure(src, glb, max(8, round(px / d))) for d in divisors]
            if not args.no_holes:
                scores[t, p["level"]] += [measure(src, glb, max(8, round(px / d)), mips=False) for d in (4, 8)]
    for t in formats[1:]:
        n = NAMES[t]
        levels = {l["level"]: l for l in runs[t][0]["levels"]}
        print(f"\n{name}: PNG / {n} per level (engine method, 8 views; sizes from the PNG level's max_screen_pixels)\n")
        print(f"| level | quads | px | PNG bytes (tex) | {n} bytes (tex) | GPU PNG / {n} | PSNR PNG / {n} (d) | IoU PNG / {n} (d) "
              + ("" if args.no_holes else f"| holes at px PNG / {n} | holes 1/4 PNG / {n} (no mips) | holes 1/8 PNG / {n} (no mips) ") + "|")
        print("|---" * (7 if args.no_holes else 10) + "|")
        for p in png_levels:
            k = levels[p["level"]]
            a, b = scores["png", p["level"]], scores[t, p["level"]]
            row = (f"| {p['level']} | {p['primitives']} | {int(p['max_screen_pixels'])} | {p['bytes']:,} ({p['texture_bytes']:,}) "
                   f"| {k['bytes']:,} ({k['texture_bytes']:,}) | {p['gpu_bytes']:,} / {k['gpu_bytes']:,} "
                   f"| {a[0]['psnr']:.2f} / {b[0]['psnr']:.2f} ({b[0]['psnr'] - a[0]['psnr']:+.2f}) "
                   f"| {a[0]['iou']:.4f} / {b[0]['iou']:.4f} ({b[0]['iou'] - a[0]['iou']:+.4f}) ")
            if not args.no_holes:
                row += (f"| {100 * a[0]['holes']:.2f}% / {100 * b[0]['holes']:.2f}% "
                        f"| {100 * a[1]['holes']:.2f}% / {100 * b[1]['holes']:.2f}% ({100 * a[3]['holes']:.2f}% / {100 * b[3]['holes']:.2f}%) "
                        f"| {100 * a[2]['holes']:.2f}% / {100 * b[2]['holes']:.2f}% ({100 * a[4]['holes']:.2f}% / {100 * b[4]['holes']:.2f}%) ")
            print(row + "|")
    print(f"\n{name}: the default level set\n")
    print("| textures | bytes | texture bytes | GPU bytes | bake s (wall) | atlas+glb s |")
    print("|---|---|---|---|---|---|")
    for t, (m, wall, encode) in runs.items():
        ls = m["levels"]
        print(f"| {t} | {sum(l['bytes'] for l in ls):,} | {sum(l['texture_bytes'] for l in ls):,} | {sum(l['gpu_bytes'] for l in ls):,} "
              f"| {wall:.1f} | {encode:.2f} |")
