#!/usr/bin/env python3
"""The recommended chain, made by every bake, on a set of models: per model the chain, nearest first
(file, the sizes it is shown at, bytes, PSNR / coverage where measured), the bytes of the chain and of
every file the bake made, and what the chain costs: the same bake with --no-chain (which still
measures the impostor levels for their screen sizes) and without, wall seconds and CPU seconds (user
+ system, the bake's threads and GL driver included: the figure to trust on a busy machine), and
their ratio.
usage: chain_table.py BIN_DIR MODELS_DIR WORK_DIR MODEL..."""
import json
import os
import resource
import subprocess
import sys
import time

bin_dir, models, work = sys.argv[1:4]


def bake(src, out, *extra):
    """Bakes src into out; returns (wall s, CPU s)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    subprocess.run([os.path.join(bin_dir, "qf-bake"), "bake", src, "-o", out, "--no-cache", "-q", *extra], check=True)
    wall = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


print("| model | recommended chain (file: px shown, bytes, PSNR / coverage) | chain bytes | all files | --no-chain wall / CPU s | "
      "with chain wall / CPU s | ratio wall / CPU |")
print("|---|---|---|---|---|---|---|")
for model in sys.argv[4:]:
    src = model if os.path.isabs(model) else os.path.join(models, model)
    name = os.path.basename(model)
    plain = bake(src, os.path.join(work, name + ".plain"), "--no-chain")
    out = os.path.join(work, name + ".chain")
    chained = bake(src, out)
    m = json.load(open(os.path.join(out, "manifest.json")))
    chain = m["recommended_chain"]["chain"]
    steps = []
    for e in chain:
        shown = f"{e['min_pixels']}+" if e["max_pixels"] is None else f"{e['min_pixels']}-{e['max_pixels']}"
        err = e["error"] or {}  # the input's first entry, above the largest size measured, has none
        steps.append(f"{e['file'] if e['kind'] != 'asset' else 'the input'}: {shown} px, {e['bytes']:,} B, {err.get('psnr')} / {err.get('coverage')}")
    every = sum(f["bytes"] for f in m["files"])
    print(f"| {name} | {'; '.join(steps)} | {sum(e['bytes'] for e in chain):,} | {every:,} | {plain[0]:.1f} / {plain[1]:.1f} | "
          f"{chained[0]:.1f} / {chained[1]:.1f} | {chained[0] / plain[0]:.2f} / {chained[1] / plain[1]:.2f} |")
