#!/usr/bin/python3
"""Plots `octrace bench --csv` output like the study's figure 4: render time
against sphere count, log axes, one line per accel and radius, the octree's
speedup over brute force written next to its points.

  tools/plot_bench.py bench.csv [more.csv ...] -o bench.png [--title TEXT]

Uses Debian's python3-matplotlib (installed by tools/setup.sh).
"""
import argparse
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv", nargs="+")
    ap.add_argument("-o", "--out", required=True, help="PNG to write")
    ap.add_argument("--title", default=None)
    args = ap.parse_args()

    rows = []
    for path in args.csv:
        with open(path, newline="") as f:
            rows += list(csv.DictReader(f))
    if not rows:
        sys.exit(f"plot_bench: {args.csv}: no rows")

    lines = defaultdict(list)
    for r in rows:
        if r["skipped"] == "1":
            continue
        key = (r["accel"], r["precision"], float(r["radius"]))
        lines[key].append((int(r["spheres"]), float(r["median_ms"]), float(r["min_ms"]), float(r["max_ms"]),
                           float(r["speedup"] or 0)))

    fig, ax = plt.subplots(figsize=(8, 5.5))
    for (accel, precision, radius), pts in sorted(lines.items()):
        pts.sort()
        n = [p[0] for p in pts]
        med = [p[1] for p in pts]
        err = [[p[1] - p[2] for p in pts], [p[3] - p[1] for p in pts]]
        style = "-o" if accel == "octree" else "--s"
        label = f"{accel} r={radius:g}" + (f" {precision}" if precision != "fp32" else "")
        ax.errorbar(n, med, yerr=err, fmt=style, capsize=3, label=label)
        if accel == "octree":
            for x, y, s in zip(n, med, [p[4] for p in pts]):
                if s > 0:
                    ax.annotate(f"{s:.1f}x", (x, y), textcoords="offset points", xytext=(4, -12), fontsize=8)
    r0 = rows[0]
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("spheres")
    ax.set_ylabel("render time, ms (device, median; bars: min-max)")
    ax.set_title(args.title or f"{r0['device']}: {r0['width']}x{r0['height']}, {r0['spp']} spp, depth {r0['depth']}")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)


if __name__ == "__main__":
    main()
