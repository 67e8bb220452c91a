#!/usr/bin/env python3
"""Prints one bake's report.json as a table: every stage's time and memory, the resampler's
texels per second per level, and the whole run (scripts/bench.sh bake).
usage: bake_table.py REPORT NAME THREADS WALL_SECONDS"""
import json
import sys

report, name, threads, wall = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])
r = json.load(open(report))
texels = {str(l["level"]): l["quad_texels"] for l in r["levels"]}  # what the resampler made (before packing)
prims = {str(l["level"]): l["primitives"] for l in r["levels"]}
print(f"\n{name}: {r['points']} points, {threads} thread(s), {r['hierarchy_levels']} AMG levels, wall {wall:.2f} s")
print(f"{'stage':<24}{'seconds':>9}{'RSS MB':>9}{'peak MB':>9}   notes")
for s in r["stages"]:
    note = ""
    parts = s["stage"].split()
    if len(parts) == 3 and parts[0] == "level" and parts[2] == "textures":
        t = texels[parts[1]]
        rate = t / s["seconds"] / 1e6 if s["seconds"] > 0 else float("inf")
        note = f"{prims[parts[1]]} quads, {t / 1e6:.2f} M texels, {rate:.2f} M texels/s"
    print(f"{s['stage']:<24}{s['seconds']:>9.3f}{s['resident_mb']:>9.0f}{s['peak_mb']:>9.0f}   {note}")
total = sum(s["seconds"] for s in r["stages"])
peak = max(s["peak_mb"] for s in r["stages"])
print(f"{'bake (stages)':<24}{total:>9.3f}{'':>9}{peak:>9.0f}   read + write: {wall - total:.2f} s")
