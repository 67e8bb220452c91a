#!/usr/bin/env python3
"""The recommended chain (qf-bake bake --chain) on a set of models: per model the chain, nearest
first (file, the sizes it is shown at, bytes, PSNR / IoU where measured), the bytes of every file
the bake made, and the seconds the bake and the chain took.
usage: chain_table.py BIN_DIR MODELS_DIR WORK_DIR MODEL..."""
import json
import os
import subprocess
import sys

bin_dir, models, work = sys.argv[1:4]
print("| model | recommended chain (file: px shown, bytes, PSNR / IoU) | chain bytes | all files | bake s | chain s |")
print("|---|---|---|---|---|---|")
for model in sys.argv[4:]:
    src = model if os.path.isabs(model) else os.path.join(models, model)
    out = os.path.join(work, os.path.basename(model) + ".chain")
    subprocess.run([os.path.join(bin_dir, "qf-bake"), "bake", src, "-o", out, "--chain", "--no-cache", "-q"], check=True)
    m = json.load(open(os.path.join(out, "manifest.json")))
    r = json.load(open(os.path.join(out, "report.json")))
    chain = m["recommended_chain"]["chain"]
    steps = []
    for e in chain:
        shown = f"{e['min_pixels']}+" if e["max_pixels"] is None else f"{e['min_pixels']}-{e['max_pixels']}"
        steps.append(f"{e['file']}: {shown} px, {e['bytes']:,} B, {e['error']['psnr']} / {e['error']['iou']}")
    chain_s = sum(s["seconds"] for s in r["stages"] if s["stage"] == "chain")
    bake_s = sum(s["seconds"] for s in r["stages"]) - chain_s + (r["sampling"] or {}).get("seconds", 0)
    every = sum(f["bytes"] for f in m["files"])
    print(f"| {os.path.basename(model)} | {'; '.join(steps)} | {sum(e['bytes'] for e in chain):,} | {every:,} | {bake_s:.1f} | {chain_s:.1f} |")
