#!/usr/bin/env python3
"""Where the bake says each file holds, checked independently (scripts/bench.sh holds, issue 48).

Per asset: a default bake (wall and CPU seconds, bytes written); then every file that claims a size
(max_screen_pixels > 0) drawn there by `qf-render eval` with the engine method from --views
directions against the truth (the input drawn at --truth x the size, at most 4096 px, and box-
filtered), beside the input itself as drawn at that size. A claim passes when the file covers at
least half of what the truth covers and its footprint PSNR is at most 3 dB below the input as
drawn (issue 48's targets). Then the chain: every entry with the sizes it is shown at, and whether
a derived file is open-ended or shown above 2x its own max_screen_pixels.
usage: holds_table.py BIN_DIR WORK_DIR ASSET... [--views 8] [--truth 8]"""
import argparse
import json
import os
import resource
import subprocess
import time

p = argparse.ArgumentParser()
p.add_argument("bin_dir")
p.add_argument("work")
p.add_argument("assets", nargs="+")
p.add_argument("--views", type=int, default=8)
p.add_argument("--truth", type=int, default=8)
a = p.parse_args()


def timed(*cmd):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    subprocess.run([str(c) for c in cmd], check=True, capture_output=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return time.monotonic() - start, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def fmt(v, digits):
    return "-" if v is None else f"{v:.{digits}f}"


claims, chains, failed = [], [], 0
print("| asset | bake wall / CPU s | files written (bytes) | input bytes |")
print("|---|---|---|---|")
for src in a.assets:
    name = os.path.basename(src)
    out = os.path.join(a.work, name + ".out")
    wall, cpu = timed(os.path.join(a.bin_dir, "qf-bake"), "bake", src, "-o", out, "--no-cache", "-q")
    m = json.load(open(os.path.join(out, "manifest.json")))
    written = sum(f["bytes"] for f in m["files"])
    chain = m.get("recommended_chain") or {}
    print(f"| {name} | {wall:.1f} / {cpu:.1f} | {len(m['files'])} ({written:,}) | {chain.get('asset', {}).get('bytes', 0):,} |")
    entries = list(m["levels"]) + list(m.get("mesh_lods", {}).get("levels", []))
    if "point_impostor" in m: entries.append(m["point_impostor"])
    for e in entries:
        size = e.get("max_screen_pixels", 0)
        if not size or "measured" not in e: continue
        truth = max(1, min(a.truth, 4096 // size))
        ev = os.path.join(a.work, name + "." + e["file"] + ".json")
        subprocess.run([os.path.join(a.bin_dir, "qf-render"), "eval", src, os.path.join(out, e["file"]), "--size", str(size), "--views", str(a.views),
                        "--truth", str(truth), "-m", "engine", "-o", ev], check=True, capture_output=True)
        r = json.load(open(ev))["mean"]
        f, d = r["engine"], r.get("as_drawn", {})
        ok = f["coverage"] is not None and f["coverage"] >= 0.5 and d.get("psnr") is not None and f["psnr"] >= d["psnr"] - 3
        failed += not ok
        claims.append(f"| {name} | {e['file']} | {e.get('primitives', e.get('triangles', e.get('points')))} | {e['bytes']:,} | {size} (from {e['holds_from_pixels']}) | "
                      f"{fmt(f['psnr'], 2)} / {fmt(d.get('psnr'), 2)} | {fmt(f['coverage'], 3)} / {fmt(d.get('coverage'), 3)} | "
                      f"{fmt(f['soft_iou'], 3)} / {fmt(d.get('soft_iou'), 3)} | {'yes' if ok else 'NO'} |")
    for e in chain.get("chain", []):
        shown = f"{e['min_pixels']}+" if e["max_pixels"] is None else f"{e['min_pixels']}-{e['max_pixels']}"
        own = next((x.get("max_screen_pixels") for x in entries if x["file"] == e["file"]), None)
        bad = e["kind"] != "asset" and (e["max_pixels"] is None or (own is not None and e["max_pixels"] > 2 * own))
        failed += bad
        err = e["error"] or {}
        chains.append(f"| {name} | {e['file'] if e['kind'] != 'asset' else 'the input'} | {shown} | {e['bytes']:,} | {fmt(err.get('psnr'), 2)} | "
                      f"{fmt(err.get('coverage'), 3)} | {'yes' if e['bar_met'] else 'no'} | {'NO' if bad else 'yes'} | {e.get('reason', '')} |")
print(f"\nEvery claimed size checked by qf-render eval ({a.views} views, truth {a.truth}x, engine method): the file / the input as drawn.\n")
print("| asset | file | quads, triangles or points | bytes | max_screen_pixels | PSNR dB | coverage | soft IoU | holds (coverage >= 0.5, PSNR >= input - 3) |")
print("|---|---|---|---|---|---|---|---|---|")
print("\n".join(claims) if claims else "| (no file claims a size) |")
print("\nThe recommended chains, nearest first:\n")
print("| asset | file | shown at px | bytes | PSNR dB | coverage | bar met | derived file within 2x its size, not open-ended | reason |")
print("|---|---|---|---|---|---|---|---|---|")
print("\n".join(chains))
print(f"\n{failed} claim(s) or chain entries fail")
