#!/usr/bin/env python3
"""A/B timing of `octrace render` variants, alternating, in one run: the
measurement behind the optimisation log's before/after figures.

  tools/ab_render.py --octrace BIN [--rounds 5] --render "ARGS" \
      --variant "LABEL=[ENV=VALUE ...] [-- extra render flags]" ... [--out FILE]

Each variant is a label, optional environment settings and optional extra
render flags, e.g. `--variant "base="`, `--variant "fast=OCTRACE_X=1"`,
`--variant "bvh=-- --accel bvh"`; the setting BIN=PATH runs another binary
for that variant (a before/after of a code change: `--variant "new=BIN=b2"`). After one warm-up process per variant,
ROUNDS rounds run every variant once, in turn. The figure is `render --json`
times_ms.render: the sum of the passes' timestamp queries (device time; no
set-up, read-back or resolve); with `--metric wall`, the whole process's wall
time instead (start to exit: device and pipeline creation, the write included);
with `--metric write`, times_ms.write: encoding the image and writing its
file (the format from the render's `-o`); with `--metric readback`,
times_ms.readback: the accumulation read back from the device and resolved;
with `--metric scene`, times_ms.scene: loading the scene (its file read
and parsed, a glTF file's images decoded); with `--metric accel_build`,
times_ms.accel_build: the acceleration
structure's build on the host. Prints, per variant, the median, min and max
over rounds, rays/s, and the ratio of the median to the first variant's;
with --out, also writes that table as markdown (date and device included).
"""
import argparse
import datetime
import json
import os
import statistics
import subprocess
import sys
import time

import tool_args


def parse_variant(text):
    label, _, rest = text.partition("=")
    if not label:
        tool_args.fail("ab_render.py", f"--variant '{text}' has no label (LABEL=...)")
    env_part, _, flags = rest.partition("--")
    env = {}
    for item in env_part.split():
        k, sep, v = item.partition("=")
        if not sep:
            tool_args.fail("ab_render.py", f"--variant '{text}': '{item}' is not ENV=VALUE")
        env[k] = v
    if "BIN" in env:
        # Another binary for this variant: checked now, not when its turn comes.
        try:
            tool_args.executable(env["BIN"])
        except argparse.ArgumentTypeError as e:
            tool_args.fail("ab_render.py", f"--variant '{text}': BIN={e}")
    return label, env, flags.split()


def render(binary, args, variant):
    label, env, flags = variant
    env = dict(env)
    binary = env.pop("BIN", binary)
    cmd = [binary, "render"] + args + flags + ["--json", "-q"]
    start = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True, env={**os.environ, **env})
    wall_ms = (time.perf_counter() - start) * 1e3
    if p.returncode != 0:
        sys.exit(f"ab_render.py: variant {label}: {' '.join(cmd)} failed with exit {p.returncode}: "
                 f"{p.stderr.strip()[-500:]}")
    j = json.loads(p.stdout)
    j["wall_ms"] = wall_ms
    return j


def main():
    ap = tool_args.Parser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--octrace", required=True, type=tool_args.executable, help="octrace binary")
    ap.add_argument("--render", required=True, help="render options shared by every variant (one string)")
    ap.add_argument("--variant", action="append", required=True, help="LABEL=[ENV=VALUE ...] [-- flags]")
    ap.add_argument("--rounds", type=tool_args.positive_int, default=5)
    ap.add_argument("--out", type=tool_args.output_file, help="markdown file to write the table to")
    ap.add_argument("--metric", choices=["render", "wall", "write", "readback", "scene", "accel_build"], default="render",
                    help="render: device time of the passes; wall: the whole process; write: the image's file; "
                         "readback: the accumulation's read-back; scene: the scene's loading; accel_build: the acceleration structure's "
                         "build on the host")
    a = ap.parse_args()
    variants = [parse_variant(v) for v in a.variant]
    args = a.render.split()
    info = {}
    for v in variants:  # warm-up
        info[v[0]] = render(a.octrace, args, v)
    times = {v[0]: [] for v in variants}
    for r in range(a.rounds):
        for v in variants:
            j = render(a.octrace, args, v)
            times[v[0]].append(j["wall_ms"] if a.metric == "wall" else j["times_ms"][a.metric])
            info[v[0]] = j
        print(f"round {r + 1}/{a.rounds}: " + ", ".join(f"{k} {t[-1]:.3f} ms" for k, t in times.items()),
              file=sys.stderr)
    first = statistics.median(times[variants[0][0]])
    dev = info[variants[0][0]]["device"]
    date = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    what = {"render": "times_ms.render", "wall": "whole-process wall time", "write": "times_ms.write",
            "readback": "times_ms.readback", "scene": "times_ms.scene", "accel_build": "times_ms.accel_build"}[a.metric]
    # Variants may run on other devices or drivers (--device, VK_ICD_FILENAMES):
    # then each row names its own.
    device_of = {label: f"{info[label]['device']['name']} ({info[label]['device']['driver']})"
                 for label, _, _ in variants}
    several = len(set(device_of.values())) > 1
    where = "each variant's device in its row" if several else f"{dev['name']} ({dev['driver']})"
    lines = [f"{date}, {where}; `octrace render {a.render} --json`, {what}, "
             f"median of {a.rounds} rounds after a warm-up, variants alternating", "",
             "| variant | env | flags | " + ("device | " if several else "") +
             "median ms | min | max | rays/s | against first |",
             "| --- | --- | --- | " + ("--- | " if several else "") + "---: | ---: | ---: | ---: | ---: |"]
    for label, env, flags in variants:
        t = times[label]
        med = statistics.median(t)
        rays = info[label].get("rays", 0)
        rps = f"{rays / med * 1e3:.3g}" if rays and a.metric == "render" else ""
        envs = " ".join(f"{k}={v}" for k, v in env.items())
        device = f"{device_of[label]} | " if several else ""
        lines.append(f"| {label} | {envs} | {' '.join(flags)} | {device}{med:.3f} | {min(t):.3f} | {max(t):.3f} | "
                     f"{rps} | {med / first:.3f}x |")
    tool_args.print_table(lines, a.out)


if __name__ == "__main__":
    main()
