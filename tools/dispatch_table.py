#!/usr/bin/env python3
"""Where a render's passes spend their device time, dispatch by dispatch:
`octrace render --dispatch-times` run several times, the medians tabulated.

  tools/dispatch_table.py --octrace BIN --render "ARGS" [--rounds 5] [--out FILE.md]

After one warm-up process, ROUNDS processes render ARGS with
`--dispatch-times --json`. For each stage and tail level (the camera's
tiles, the whole paths or the head, each tail level and its subgroup stage,
the sum; each dispatch's time runs from the end of the one before, summed
over its runs) the table gives the median of its milliseconds, its share of
the median passes (`times_ms.render`; with several devices, the sum of
theirs), and the last round's runs and paths a tail level took (the
batches, which follow the wall clock, may move them from round to round),
and the rays the render traced; the last line, the passes themselves.
With --out, also writes the table as markdown, with the date, the device
and the command.
"""
import argparse
import datetime
import json
import os
import statistics
import sys
import tempfile

import tool_args


def render(octrace, args, out):
    return json.loads(tool_args.run([octrace, "render"] + args + ["--dispatch-times", "--json", "-q", "-o", out]))


def main():
    ap = tool_args.Parser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--octrace", required=True, type=tool_args.executable, help="octrace binary")
    ap.add_argument("--render", required=True, help="render options (one string)")
    ap.add_argument("--rounds", type=tool_args.positive_int, default=5)
    ap.add_argument("--out", type=tool_args.output_file, help="markdown file to write the table to")
    a = ap.parse_args()
    args = a.render.split()
    with tempfile.TemporaryDirectory() as tmp:
        image = os.path.join(tmp, "image.pfm")
        render(a.octrace, args, image)  # warm-up
        runs = []
        for r in range(a.rounds):
            runs.append(render(a.octrace, args, image))
            print(f"round {r + 1}/{a.rounds}: {runs[-1]['times_ms']['render']:.3f} ms", file=sys.stderr)
    def passes_of(j):
        devices = j.get("devices")
        return sum(d["render_ms"] for d in devices) if devices else j["times_ms"]["render"]

    def ms_of(j, stage, level):
        return sum(d["ms"] for d in j["dispatches"] if d["stage"] == stage and d["level"] == level)

    passes = statistics.median(passes_of(j) for j in runs)
    last = runs[-1]
    rows = []
    for d in last["dispatches"]:
        ms = statistics.median(ms_of(j, d["stage"], d["level"]) for j in runs)
        tail = d["stage"] in ("tail", "tail_subgroup")
        name = f"{d['stage']} {d['level']}" if tail else d["stage"]
        rows.append(f"| {name} | {ms:.3f} | {100 * ms / passes:.1f}% | {d['runs']} | {d['paths'] if tail else ''} |")
    dev = last["device"]
    date = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    lines = [f"{date}, {dev['name']} ({dev['driver']}), octrace {last.get('octrace', '')}; "
             f"`octrace render {a.render} --dispatch-times --json`, medians of {a.rounds} rounds after a warm-up; "
             f"{last['rays']} rays", "",
             "| dispatch | median ms | of the passes | runs | paths |",
             "| --- | ---: | ---: | ---: | ---: |"] + rows + [
             f"| the passes | {passes:.3f} | 100% | | |"]
    tool_args.print_table(lines, a.out)


if __name__ == "__main__":
    main()
