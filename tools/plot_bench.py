#!/usr/bin/python3
"""Plots `octrace bench --csv` output like the study's figure 4: render time
against sphere count, log axes, one line per accel and radius, the octree's
speedup over brute force written next to its points. It takes the sphere
sweep's CSV (`bench --spheres ... --csv`, the default bench), not that of
`bench --scene` or `bench --family`.

  tools/plot_bench.py bench.csv [more.csv ...] -o bench.png [--title TEXT]

Uses Debian's python3-matplotlib (installed by tools/setup.sh).
"""
import argparse
import csv
import os
import sys
from collections import defaultdict

import tool_args

# The sphere sweep's columns that the plot reads; the title's too unless --title.
COLUMNS = ["spheres", "radius", "accel", "precision", "skipped", "median_ms", "min_ms", "max_ms", "speedup"]
TITLE_COLUMNS = ["device", "width", "height", "spp", "depth"]


def main():
    ap = tool_args.Parser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv", nargs="+", type=tool_args.input_file)
    ap.add_argument("-o", "--out", required=True, type=tool_args.output_file, help="PNG to write")
    ap.add_argument("--title", default=None)
    args = ap.parse_args()
    # After the arguments, so that --help and bad input need no matplotlib.
    try:
        import matplotlib
    except ImportError:
        sys.exit("plot_bench.py: needs matplotlib (Debian's python3-matplotlib: tools/setup.sh; "
                 "or pip install matplotlib)")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.backend_bases import FigureCanvasBase
    # matplotlib picks the format from the extension (none: PNG); an unknown
    # one would fail only after the plot is drawn.
    ext = os.path.splitext(args.out)[1][1:].lower()
    formats = FigureCanvasBase.get_supported_filetypes()
    if ext and ext not in formats:
        tool_args.fail("plot_bench.py", f"-o {args.out}: unknown image format '.{ext}' "
                                        f"(one of {', '.join('.' + f for f in sorted(formats))})")

    rows = []
    needed = COLUMNS + ([] if args.title else TITLE_COLUMNS)
    for path in args.csv:
        try:
            with open(path, newline="") as f:
                reader = csv.DictReader(f)
                missing = [c for c in needed if c not in (reader.fieldnames or [])]
                if missing:
                    tool_args.fail("plot_bench.py", f"{path}: not the sphere sweep's CSV (`octrace bench --spheres "
                                                    f"... --csv`): no column {', '.join(missing)}")
                rows += [(path, reader.line_num, r) for r in reader]
        except (UnicodeDecodeError, csv.Error) as e:  # not a text CSV at all
            tool_args.fail("plot_bench.py", f"{path}: not a CSV file: {e}")
    if not rows:
        tool_args.fail("plot_bench.py", f"{', '.join(args.csv)}: no rows")

    lines = defaultdict(list)
    for path, line, r in rows:
        if r["skipped"] == "1":
            continue
        try:
            key = (r["accel"], r["precision"], float(r["radius"]))
            lines[key].append((int(r["spheres"]), float(r["median_ms"]), float(r["min_ms"]), float(r["max_ms"]),
                               float(r["speedup"] or 0)))
        except (TypeError, ValueError) as e:  # a short row gives None, a bad number ValueError
            tool_args.fail("plot_bench.py", f"{path}: line {line}: {e}")
    if not lines:
        tool_args.fail("plot_bench.py", f"{', '.join(args.csv)}: nothing to plot: every row is skipped")

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
    r0 = rows[0][2]
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
