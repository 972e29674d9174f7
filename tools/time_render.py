#!/usr/bin/env python3
"""Times `octrace render` the way docs/performance.md reports it: one warm-up run, then
N runs; prints the median, min and max of the device render time (timestamp
queries, from --json) and of the whole process's wall time, and with the
octree its build time and statistics.

  tools/time_render.py [--runs 5] [--octrace build/app/octrace] -- RENDER FLAGS...
"""
import argparse
import json
import statistics
import subprocess
import sys
import time

import tool_args


def main():
    ap = tool_args.Parser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=tool_args.positive_int, default=5)
    ap.add_argument("--octrace", type=tool_args.executable, default="build/app/octrace")
    ap.add_argument("flags", nargs=argparse.REMAINDER)
    args = ap.parse_args()
    flags = [f for f in args.flags if f != "--"]
    cmd = [args.octrace, "render", "--json", "--quiet", "--out", "/tmp/octrace_time_render.pfm"] + flags
    device_ms, wall_ms, build_ms = [], [], []
    summary = None
    for i in range(args.runs + 1):
        start = time.perf_counter()
        out = subprocess.run(cmd, capture_output=True, text=True)
        wall = (time.perf_counter() - start) * 1000
        if out.returncode != 0:
            sys.exit(f"time_render: {' '.join(cmd)} failed: {out.stderr.strip()}")
        summary = json.loads(out.stdout)
        if i == 0:
            continue  # warm-up
        device_ms.append(summary["times_ms"]["render"])
        build_ms.append(summary["times_ms"]["accel_build"])
        wall_ms.append(wall)

    def line(name, xs):
        return (f"{name:<22} median {statistics.median(xs):9.1f} ms  "
                f"min {min(xs):9.1f}  max {max(xs):9.1f}  (n={len(xs)})")

    d = summary["device"]
    print(f"device: {d['name']} ({d['type']}); {summary['width']}x{summary['height']}, {summary['spp']} spp, "
          f"depth {summary['depth']}, accel {summary['accel']}, scene {summary['scene']['source']}")
    print(line("render (device time)", device_ms))
    print(line("whole process (wall)", wall_ms))
    if "octree" in summary:
        o = summary["octree"]
        print(line("octree build (wall)", build_ms))
        print(f"octree: {o['nodes']} nodes, {o['leaves']} leaves, depth {o['depth_reached']}, "
              f"{o['refs_per_sphere']:.2f} refs/sphere, {o['bytes_per_sphere']:.1f} bytes/sphere, "
              f"{o['big_spheres']} big spheres")


if __name__ == "__main__":
    main()
