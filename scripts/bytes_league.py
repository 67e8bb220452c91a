#!/usr/bin/env python3
"""The league at equal bytes (issue 32): each input baked with the defaults once per texture format
(--textures png, webp, ktx2; the recommended chain on, so every file is measured by the engine
method at the chain's band sizes against the input supersampled). For each impostor level, at the
largest band no larger than its max_screen_pixels, it is set against the best peer file (mesh LODs:
meshoptimizer's simplify, or a point set's reconstruction) of at most its bytes that is valid at
that band; the table gives both, their bytes and PSNR / IoU, and the impostor's lead in dB.
usage: bytes_league.py BIN_DIR WORK_DIR [--formats png,webp,ktx2] INPUT..."""
import argparse
import json
import os
import subprocess

ap = argparse.ArgumentParser()
ap.add_argument("bin_dir")
ap.add_argument("work")
ap.add_argument("--formats", default="png,webp,ktx2")
ap.add_argument("inputs", nargs="+")
args = ap.parse_args()


def bake(src, out, textures):
    subprocess.run([os.path.join(args.bin_dir, "qf-bake"), "bake", src, "-o", out, "--textures", textures, "--no-cache", "-q"],
                   check=True)
    return json.load(open(os.path.join(out, "manifest.json")))


def league(manifest):
    """Rows (level, band, its bytes and error, the best peer within its bytes and its error)."""
    chain = manifest["recommended_chain"]
    sizes = chain["sizes"]
    files = chain["measured"]
    levels = {l["file"]: l for l in manifest["levels"]}
    rows = []
    for f in files:
        if f["kind"] != "impostor_level":
            continue
        own = levels[f["file"]]["max_screen_pixels"]
        bands = [k for k, s in enumerate(sizes) if s <= own] or [len(sizes) - 1]
        k = bands[0]
        me = f["at_pixels"][k]
        best = None
        for p in files:
            if p["kind"] == "impostor_level" or p["bytes"] > f["bytes"] or p["at_pixels"][k] is None:
                continue
            if best is None or p["at_pixels"][k]["psnr"] > best["at_pixels"][k]["psnr"]:
                best = p
        rows.append((f, sizes[k], me, best, best["at_pixels"][k] if best else None))
    return rows


formats = args.formats.split(",")
print("| input | textures | level | band px | bytes | PSNR / IoU | best peer within its bytes | peer bytes | peer PSNR / IoU | impostor lead dB |")
print("|---|---|---|---|---|---|---|---|---|---|")
wins = {fmt: [0, 0] for fmt in formats}
for src in args.inputs:
    name = os.path.splitext(os.path.basename(src))[0]
    for fmt in formats:
        out = os.path.join(args.work, f"{name}_{fmt}")
        for f, band, me, peer, pe in league(bake(src, out, fmt)):
            if peer is None:
                print(f"| {name} | {fmt} | {f['file']} | {band} | {f['bytes']:,} | {me['psnr']:.2f} / {me['iou']:.3f} | no peer of at most its bytes valid at that size | | | |")
                continue
            lead = me["psnr"] - pe["psnr"]
            wins[fmt][0] += lead > 0
            wins[fmt][1] += 1
            print(f"| {name} | {fmt} | {f['file']} | {band} | {f['bytes']:,} | {me['psnr']:.2f} / {me['iou']:.3f} | {peer['file']} | "
                  f"{peer['bytes']:,} | {pe['psnr']:.2f} / {pe['iou']:.3f} | {lead:+.2f} |")
print()
for fmt in formats:
    print(f"{fmt}: the impostor level ahead in {wins[fmt][0]} of {wins[fmt][1]} comparisons with a peer")
