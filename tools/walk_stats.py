#!/usr/bin/env python3
"""What the walks do, per query, for scenes and acceleration structures side
by side: `octrace render --walk-stats --json` for each scene and accel, as a
table of nodes expanded, leaves, box tests and primitive tests per query
(a closest-hit or shadow-ray query of the scene; every level of the walk
counts, the meshes' own trees included), and how full the subgroups were
where queries start, at node expansions and at primitive tests.

  tools/walk_stats.py --octrace BIN [--accel octree,bvh] [--render "ARGS"] \
      --scene "LABEL=SCENE FLAGS" ... [--out FILE]

--render holds the flags every render shares (size, spp, depth, device);
each --scene a label and that scene's own flags, e.g.
`--scene "488 spheres=--spheres 488 --radius 0.1"` (the label ends at the first
`=`) or
`--scene "balloon=--scene balloon/scene.gltf"`. The counts follow from the
scene, the structure, the image and the samples, hardly from the device:
the walk is the same, and only paths that the devices' float rounding sends
elsewhere differ (the H200 against lavapipe: queries within 0.1%, the
figures per query equal to two decimals; docs/results/h200/walk_stats/).
The lanes busy do depend on the device: its subgroup size (32 on NVIDIA, 8
on llvmpipe) and which lanes run a step together. Prints the table; with --out also
writes it as markdown, with the date, the device, the checkout's commit and
the command. The passes' times are not reported: counting costs time.
"""
import argparse
import datetime
import json
import os
import shlex
import subprocess
import sys
import tempfile

import tool_args


def render(binary, args, out_dir):
    cmd = [binary, "render"] + args + ["--walk-stats", "--json", "-q", "--out", os.path.join(out_dir, "walk.pfm")]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"walk_stats.py: {' '.join(shlex.quote(c) for c in cmd)} failed with exit {p.returncode}: "
                 f"{p.stderr.strip()[-500:]}")
    return json.loads(p.stdout)


def split_flags(what, text):
    """Shell-style words of a flags string; bad quoting ends the tool in one line."""
    try:
        return shlex.split(text)
    except ValueError as e:  # e.g. "No closing quotation"
        tool_args.fail("walk_stats.py", f"{what}: {e} in {text!r}")


def busy(count, slots):
    """The share of a subgroup's lanes busy at the steps counted (octrace's walk.*_slots)."""
    return f"{100.0 * count / slots:.0f}%" if slots else "-"


def main():
    ap = tool_args.Parser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--octrace", required=True, type=tool_args.executable, help="the octrace binary")
    ap.add_argument("--accel", default="octree,bvh", help="comma-separated structures (default octree,bvh)")
    ap.add_argument("--render", default="", help="flags every render shares")
    ap.add_argument("--scene", action="append", required=True, help="LABEL=FLAGS of one scene (repeatable)")
    ap.add_argument("--out", type=tool_args.output_file, help="also write the table as markdown here")
    a = ap.parse_args()

    shared = split_flags("--render", a.render)
    accels = [x for x in a.accel.split(",") if x]
    if not accels:
        tool_args.fail("walk_stats.py", f"--accel {a.accel!r}: no structure named (e.g. octree,bvh)")
    # Every --scene is read before the first render.
    scenes = []
    for spec in a.scene:
        label, sep, flags = spec.partition("=")
        if not sep or not label:
            tool_args.fail("walk_stats.py", f"--scene '{spec}' is not LABEL=FLAGS")
        scenes.append((label, split_flags(f"--scene '{label}=...'", flags)))
    header = ("| scene | accel | queries | nodes | leaves | box tests | primitive tests | primitives per leaf "
              "| mesh instances | lanes busy: queries | nodes | primitives |")
    rows = [header, "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    device = ""
    for label, flags in scenes:
        for accel in accels:
            with tempfile.TemporaryDirectory() as out_dir:
                j = render(a.octrace, shared + flags + ["--accel", accel], out_dir)
            device = j["device"]["name"]
            w = j["walk"]
            q = w["queries"] or 1
            per_leaf = w["primitives"] / w["leaves"] if w["leaves"] else float("nan")
            rows.append(f"| {label} | {accel} | {w['queries']} | {w['nodes'] / q:.2f} | {w['leaves'] / q:.2f} "
                        f"| {w['boxes'] / q:.2f} | {w['primitives'] / q:.2f} | {per_leaf:.2f} "
                        f"| {w['instances'] / q:.2f} | {busy(w['queries'], w['query_slots'])} "
                        f"| {busy(w['nodes'], w['node_slots'])} | {busy(w['primitives'], w['primitive_slots'])} |")
            print(rows[-1], flush=True)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                            cwd=os.path.dirname(os.path.abspath(__file__))).stdout.strip() or "unknown commit"
    if a.out:
        now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
        with open(a.out, "w") as f:
            f.write(f"# Walk statistics per query\n\n{now}, {device}, checkout at {commit}.\n\n")
            f.write("Command: `tools/walk_stats.py " + " ".join(shlex.quote(x) for x in sys.argv[1:]) + "`\n\n")
            f.write("Per query (closest-hit and shadow-ray queries of the scene): internal nodes expanded, "
                    "leaves (and big lists) tested, ray/box tests, ray/primitive tests, mesh instances entered; "
                    "then the share of a subgroup's lanes busy where queries start, at node expansions and at "
                    "primitive tests (a subgroup: a warp on a GPU, the 8 lanes of a vector on llvmpipe).\n\n")
            f.write("\n".join(rows) + "\n")


if __name__ == "__main__":
    main()
