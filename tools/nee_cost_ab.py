#!/usr/bin/python3
"""The cost of NEE in two builds, side by side: device time of the rtiow
field with one emitter (r = 0.5) 30 above it (the scene of
tools/nee_efficiency.py's cost row), 160x90, 16 spp, NEE on and off, each
build, interleaved run by run so that a change in the machine's load hits
all four alike; prints the medians, new / old with NEE on, and on / off for
each build (an optimisation of light sampling: optimisation-log.md).

  tools/nee_cost_ab.py OLD_BINARY NEW_BINARY [--device cpu] [--repeats 7]

Bad input exits with 2; a render that fails ends the tool with octrace's
error line and its exit status.
"""
import argparse
import json
import os
import shutil
import statistics
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import tool_args  # noqa: E402
from nee_efficiency import far_light_scene  # noqa: E402


def render(binary, args, scene, nee, out):
    r = tool_args.run([binary, "render", "--json", "--quiet", "--device", args.device, "--size", "160x90",
             "--spp", "16", "--nee", nee, "--scene", scene, "--out", out])
    return json.loads(r)["times_ms"]["render"]


def main():
    ap = tool_args.Parser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("old", type=tool_args.executable)
    ap.add_argument("new", type=tool_args.executable)
    ap.add_argument("--device", default="auto")
    ap.add_argument("--repeats", type=tool_args.positive_int, default=7)
    args = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="nee_cost_ab")
    try:
        scene = far_light_scene(args.old, args.device, tmp)
        runs = {(b, nee): [] for b in ("old", "new") for nee in ("on", "off")}
        for _ in range(args.repeats):
            for (b, nee), times in runs.items():
                times.append(render(getattr(args, b), args, scene, nee, os.path.join(tmp, "out.pfm")))
    finally:
        shutil.rmtree(tmp)
    for (b, nee), times in runs.items():
        print(f"{b} nee {nee}: median {statistics.median(times):.1f} ms ({' '.join(f'{t:.0f}' for t in times)})")
    m = {k: statistics.median(v) for k, v in runs.items()}
    print(f"new / old, NEE on: {m['new', 'on'] / m['old', 'on']:.3f}")
    print(f"NEE on / off: old {m['old', 'on'] / m['old', 'off']:.2f}, new {m['new', 'on'] / m['new', 'off']:.2f}")


if __name__ == "__main__":
    main()
