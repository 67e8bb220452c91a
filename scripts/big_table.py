#!/usr/bin/env python3
"""Prints the big-asset benchmark (scripts/bench.sh big) as a markdown table: per bake, the wall
time of every stage group from its report.json, the whole command's wall and CPU (user + sys)
time and peak memory from GNU time -v, memory per point, and the growth exponents between the
smallest and the largest bake of each family (a family = the name before the first space).
usage: big_table.py NAME REPORT TIME_V_OUTPUT [NAME REPORT TIME_V_OUTPUT ...]"""
import json
import math
import re
import sys


def gnu_time(path):
    """Wall seconds, user + sys seconds and max RSS bytes from the output of /usr/bin/time -v."""
    text = open(path).read()
    def field(label):
        m = re.search(r"^\s*" + re.escape(label) + r":\s*(.+)$", text, re.M)
        return m.group(1).strip() if m else None
    wall = 0.0
    for part in field("Elapsed (wall clock) time (h:mm:ss or m:ss)").split(":"):
        wall = wall * 60 + float(part)
    cpu = float(field("User time (seconds)")) + float(field("System time (seconds)"))
    return wall, cpu, int(field("Maximum resident set size (kbytes)")) * 1024


def stage_groups(report):
    """Seconds per stage group: analysis and AMG apart, every level's steps summed."""
    groups = {"sample": 0.0, "prepare": 0.0, "analysis": 0.0, "amg": 0.0, "basis": 0.0, "levels": 0.0, "mesh lods": 0.0}
    # An out-of-core bake's own steps (pipeline/out_of_core.h): the scratch file and the links
    # count as its preparation.
    if report.get("sampling"):
        groups["sample"] = report["sampling"]["seconds"]
    for s in report["stages"]:
        name = s["stage"]
        if name.startswith("level ") and name.endswith(" basis"):  # each level's basis, as it is made
            groups["basis"] += s["seconds"]
        elif name.startswith("level ") or name == "lod file":
            groups["levels"] += s["seconds"]
        elif name == "hierarchy":  # reports from before the split: analysis + AMG in one
            groups["amg"] += s["seconds"]
        elif name in ("spill", "link"):
            groups["prepare"] += s["seconds"]
        elif name in groups:
            groups[name] += s["seconds"]
    return groups


rows = []
args = sys.argv[1:]
for i in range(0, len(args), 3):
    name, report_path, time_path = args[i:i + 3]
    report = json.load(open(report_path))
    wall, cpu, rss = gnu_time(time_path)
    memory = report.get("memory", {})
    rows.append({"name": name, "points": report["points"], "groups": stage_groups(report), "wall": wall, "cpu": cpu, "rss": rss,
                 "path": memory.get("path", "in-memory"), "subsample": memory.get("subsample_points"),
                 "scratch": memory.get("scratch_bytes", 0)})

cols = ["sample", "prepare", "analysis", "amg", "basis", "levels", "mesh lods"]
print("| asset | points | path (subsample) | " + " | ".join(c + " s" for c in cols) + " | read+write s | wall s | CPU s | peak MB | B/pt | scratch MB |")
print("|---|---:|---|" + "---:|" * len(cols) + "---:|---:|---:|---:|---:|---:|")
for r in rows:
    g = r["groups"]
    other = r["wall"] - sum(g.values())
    cells = [f"{g[c]:.2f}" for c in cols]
    path = r["path"] + (f" ({r['subsample']:,})" if r["subsample"] else "")
    print(f"| {r['name']} | {r['points']:,} | {path} | " + " | ".join(cells) +
          f" | {other:.2f} | {r['wall']:.1f} | {r['cpu']:.1f} | {r['rss'] / 2**20:,.0f} | {r['rss'] / r['points']:.0f} | "
          f"{r['scratch'] / 2**20:,.0f} |")

# Growth exponents: cost ~ n^e between the smallest and largest bake of a family.
families = {}
for r in rows:
    families.setdefault(r["name"].split(" ")[0], []).append(r)
lines = []
for fam, rs in families.items():
    rs = sorted(rs, key=lambda r: r["points"])
    a, b = rs[0], rs[-1]
    if b["points"] <= a["points"]:
        continue
    ln = math.log(b["points"] / a["points"])
    e = lambda x, y: math.log(y / x) / ln if x > 0 and y > 0 else float("nan")
    lines.append(f"| {fam} | {a['points']:,} -> {b['points']:,} | {e(a['wall'], b['wall']):.2f} | {e(a['cpu'], b['cpu']):.2f} | "
                 f"{e(a['rss'], b['rss']):.2f} |")
if lines:
    print()
    print("| growth | points | wall exponent | CPU exponent | peak memory exponent |")
    print("|---|---|---:|---:|---:|")
    print("\n".join(lines))
