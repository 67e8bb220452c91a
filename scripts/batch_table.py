#!/usr/bin/env python3
"""Rows of the batch benchmark table (scripts/bench.sh batch) from a qf-bake batch report.

usage: batch_table.py --header
       batch_table.py REPORT LABEL                 a run that baked: assets/min, time, peak memory
       batch_table.py --rerun REPORT LABEL WALL_S  a run with nothing to do: overhead per asset
"""
import json
import sys

if sys.argv[1] == "--header":
    print(f"{'run':<26} {'jobs':>4} {'assets':>6} {'wall s':>8} {'assets/min':>10} {'slowest':>22} {'peak MB max':>11}")
elif sys.argv[1] == "--rerun":
    r = json.load(open(sys.argv[2]))
    n = len(r["assets"])
    wall = float(sys.argv[4])
    checks = [a["seconds"] for a in r["assets"]]
    print(f"{sys.argv[3]:<16} {n:>4} assets, all {r['totals']['up to date'] == n and 'up to date' or 'NOT up to date'}: "
          f"{wall:.3f} s wall = {1000 * wall / n:.1f} ms/asset; inside the batch {1000 * r['seconds'] / n:.2f} ms/asset "
          f"(key + check: mean {1000 * sum(checks) / n:.2f} ms, max {1000 * max(checks):.2f} ms)")
else:
    r = json.load(open(sys.argv[1]))
    baked = [a for a in r["assets"] if a["status"] == "baked"]
    slow = max(baked, key=lambda a: a["seconds"])
    wall = r["seconds"]
    print(f"{sys.argv[2]:<26} {r['jobs']:>4} {len(baked):>6} {wall:>8.2f} {60 * len(baked) / wall:>10.1f} "
          f"{slow['name'][:14] + ' ' + format(slow['seconds'], '.2f'):>22} {max(a['peak_mb'] for a in baked):>11.0f}")
